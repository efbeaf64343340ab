#include "wheel_output.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "wheel_builder.h"
#include "wheelsim/geometry/mesh_check.h"
#include "wheelsim/geometry/mesh_error.h"
#include "wheelsim/geometry/mesh_io.h"

namespace wheelsim::meshes {
namespace {

toml::array vector_array(const Eigen::Vector3d &v) { return toml::array{v.x(), v.y(), v.z()}; }

toml::array matrix_array(const Eigen::Matrix3d &m) {
  toml::array rows;
  for (int i = 0; i < 3; ++i)
    rows.push_back(toml::array{m(i, 0), m(i, 1), m(i, 2)});
  return rows;
}

bool ends_with(const std::string &s, const std::string &suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace

GeneratedWheel generate_wheel(const WheelSpec &spec, double density_kg_m3) {
  GeneratedWheel w;
  w.mesh = build_wheel_mesh(spec);
  const geometry::MeshReport report = geometry::check_mesh(w.mesh);
  if (!report.ok()) {
    std::string message = "generated mesh is invalid (" + describe(spec) + "): ";
    for (const auto &e : report.errors)
      message += e + "; ";
    throw WheelSpecError(message);
  }
  w.warnings = report.warnings;
  try {
    w.props = geometry::mass_properties(w.mesh, density_kg_m3);
  } catch (const geometry::MeshError &e) {
    throw WheelSpecError(std::string("--density: ") + e.what());
  }
  return w;
}

std::vector<std::string> write_wheel(const geometry::TriangleMesh &mesh, const std::string &prefix,
                                     const std::vector<std::string> &formats) {
  std::vector<std::string> paths;
  for (const std::string &f : formats) {
    if (f != "obj" && f != "stl" && f != "ply") {
      throw WheelSpecError("--formats '" + f + "': expected obj, stl or ply");
    }
    paths.push_back(prefix + "." + f);
    geometry::write_mesh(mesh, paths.back());
  }
  return paths;
}

void write_properties(const std::string &path, const std::string &name, const WheelSpec &spec,
                      const GeneratedWheel &w, const std::vector<std::string> &mesh_files) {
  toml::table wheel{{"name", name},
                    {"description", describe(spec)},
                    {"frame", "wheel centre at the origin, axle +y, x forward, z up"},
                    {"outer_radius_m", spec.outer_radius_m()},
                    {"rim_radius_m", spec.rim_radius_m()},
                    {"width_m", spec.width_m},
                    {"smooth", spec.smooth},
                    {"lug_count", spec.smooth ? 0 : spec.lug_count}};
  if (!spec.smooth) {
    wheel.insert("lug_type", to_string(spec.type));
    wheel.insert("lug_height_m", spec.lug_height_m);
    wheel.insert("lug_width_m", spec.lug_width_m);
    wheel.insert("lug_angle_deg", spec.lug_angle_deg);
    if (spec.type != LugType::straight)
      wheel.insert("centre_length_m", spec.centre_length_m);
  }
  toml::array files;
  for (const auto &f : mesh_files)
    files.push_back(std::filesystem::path(f).filename().string());
  toml::table mesh{{"files", files},
                   {"vertex_count", static_cast<int64_t>(w.mesh.vertices_m.size())},
                   {"triangle_count", static_cast<int64_t>(w.mesh.triangles.size())}};
  const auto &p = w.props;
  toml::table mass{{"density_kg_m3", p.density_kg_m3},
                   {"volume_m3", p.volume_m3},
                   {"mass_kg", p.mass_kg},
                   {"centroid_m", vector_array(p.centroid_m)},
                   {"inertia_about_centroid_kg_m2", matrix_array(p.inertia_about_centroid_kg_m2)},
                   {"inertia_about_wheel_centre_kg_m2",
                    matrix_array(geometry::inertia_about_point(p, Eigen::Vector3d::Zero()))}};
  toml::table root{{"wheel", wheel}, {"mesh", mesh}, {"mass_properties", mass}};
  std::ofstream out(path);
  if (!out)
    throw std::runtime_error(path + ": cannot open for writing");
  if (ends_with(path, ".json")) {
    out << toml::json_formatter{root} << "\n";
  } else {
    out << "# written by wheel-mesh; units in the key names\n" << root << "\n";
  }
  if (!out)
    throw std::runtime_error(path + ": write failed");
}

std::string format_properties(const std::string &name, const WheelSpec &spec,
                              const GeneratedWheel &w) {
  const auto &p = w.props;
  const Eigen::Matrix3d &I = p.inertia_about_centroid_kg_m2;
  std::ostringstream os;
  os.precision(6);
  os << name << ": " << describe(spec) << "\n"
     << "  triangles " << w.mesh.triangles.size() << ", vertices " << w.mesh.vertices_m.size()
     << "\n"
     << "  volume " << p.volume_m3 << " m^3, density " << p.density_kg_m3 << " kg/m^3, mass "
     << p.mass_kg << " kg\n"
     << "  centroid (" << p.centroid_m.x() << ", " << p.centroid_m.y() << ", " << p.centroid_m.z()
     << ") m\n"
     << "  inertia about centroid [kg m^2]: [[" << I(0, 0) << ", " << I(0, 1) << ", " << I(0, 2)
     << "], [" << I(1, 0) << ", " << I(1, 1) << ", " << I(1, 2) << "], [" << I(2, 0) << ", "
     << I(2, 1) << ", " << I(2, 2) << "]]\n";
  for (const auto &warning : w.warnings)
    os << "  warning: " << warning << "\n";
  return os.str();
}

} // namespace wheelsim::meshes
