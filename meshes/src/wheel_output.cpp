#include "wheel_output.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "tool_builder.h"
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

/// Validates `mesh` with check_mesh and computes its mass properties; throws Error naming
/// `what` if the mesh is invalid (a generator bug) or the density is not > 0.
template <class Error>
GeneratedSolid validated(geometry::TriangleMesh mesh, double density_kg_m3,
                         const std::string &what) {
  GeneratedSolid g;
  g.mesh = std::move(mesh);
  const geometry::MeshReport report = geometry::check_mesh(g.mesh);
  if (!report.ok()) {
    std::string message = "generated mesh is invalid (" + what + "): ";
    for (const auto &e : report.errors)
      message += e + "; ";
    throw Error(message);
  }
  g.warnings = report.warnings;
  try {
    g.props = geometry::mass_properties(g.mesh, density_kg_m3);
  } catch (const geometry::MeshError &e) {
    throw Error(std::string("--density: ") + e.what());
  }
  return g;
}

toml::table mesh_table(const GeneratedSolid &g, const std::vector<std::string> &mesh_files) {
  toml::array files;
  for (const auto &f : mesh_files)
    files.push_back(std::filesystem::path(f).filename().string());
  return toml::table{{"files", files},
                     {"vertex_count", static_cast<int64_t>(g.mesh.vertices_m.size())},
                     {"triangle_count", static_cast<int64_t>(g.mesh.triangles.size())}};
}

/// The mass properties, with the inertia also about the frame origin under `origin_key`.
toml::table mass_table(const geometry::MassProperties &p, const char *origin_key) {
  return toml::table{
      {"density_kg_m3", p.density_kg_m3},
      {"volume_m3", p.volume_m3},
      {"mass_kg", p.mass_kg},
      {"centroid_m", vector_array(p.centroid_m)},
      {"inertia_about_centroid_kg_m2", matrix_array(p.inertia_about_centroid_kg_m2)},
      {origin_key, matrix_array(geometry::inertia_about_point(p, Eigen::Vector3d::Zero()))}};
}

void write_toml_or_json(const std::string &path, const toml::table &root) {
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

/// Counts, volume, mass, centroid, inertia and warnings, one indented line each.
std::string format_solid(const GeneratedSolid &g) {
  const auto &p = g.props;
  const Eigen::Matrix3d &I = p.inertia_about_centroid_kg_m2;
  std::ostringstream os;
  os.precision(6);
  os << "  triangles " << g.mesh.triangles.size() << ", vertices " << g.mesh.vertices_m.size()
     << "\n"
     << "  volume " << p.volume_m3 << " m^3, density " << p.density_kg_m3 << " kg/m^3, mass "
     << p.mass_kg << " kg\n"
     << "  centroid (" << p.centroid_m.x() << ", " << p.centroid_m.y() << ", " << p.centroid_m.z()
     << ") m\n"
     << "  inertia about centroid [kg m^2]: [[" << I(0, 0) << ", " << I(0, 1) << ", " << I(0, 2)
     << "], [" << I(1, 0) << ", " << I(1, 1) << ", " << I(1, 2) << "], [" << I(2, 0) << ", "
     << I(2, 1) << ", " << I(2, 2) << "]]\n";
  for (const auto &warning : g.warnings)
    os << "  warning: " << warning << "\n";
  return os.str();
}

} // namespace

GeneratedSolid generate_wheel(const WheelSpec &spec, double density_kg_m3) {
  return validated<WheelSpecError>(build_wheel_mesh(spec), density_kg_m3, describe(spec));
}

GeneratedSolid generate_tool(const ToolSpec &spec, double density_kg_m3) {
  return validated<ToolSpecError>(build_tool_mesh(spec), density_kg_m3, describe(spec));
}

std::vector<std::string> write_mesh_files(const geometry::TriangleMesh &mesh,
                                          const std::string &prefix,
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
                      const GeneratedSolid &w, const std::vector<std::string> &mesh_files) {
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
  const toml::table root{
      {"wheel", wheel},
      {"mesh", mesh_table(w, mesh_files)},
      {"mass_properties", mass_table(w.props, "inertia_about_wheel_centre_kg_m2")}};
  write_toml_or_json(path, root);
}

void write_properties(const std::string &path, const std::string &name, const ToolSpec &spec,
                      const GeneratedSolid &g, const std::vector<std::string> &mesh_files) {
  toml::table tool{{"name", name},
                   {"tool", to_string(spec.kind)},
                   {"description", describe(spec)},
                   {"frame", "centred at the origin (bounding-box centre and centroid), z up"},
                   {"size_x_m", 2.0 * spec.half_x_m()},
                   {"size_y_m", 2.0 * spec.half_y_m()},
                   {"size_z_m", spec.height_m}};
  switch (spec.kind) {
  case ToolKind::plate_rect:
    tool.insert("lx_m", spec.lx_m);
    tool.insert("ly_m", spec.ly_m);
    tool.insert("thickness_m", spec.height_m);
    break;
  case ToolKind::plate_disc:
    tool.insert("radius_m", spec.radius_m);
    tool.insert("thickness_m", spec.height_m);
    break;
  case ToolKind::frame:
    tool.insert("hole_lx_m", spec.lx_m);
    tool.insert("hole_ly_m", spec.ly_m);
    tool.insert("wall_m", spec.wall_m);
    tool.insert("height_m", spec.height_m);
    break;
  case ToolKind::ring:
    tool.insert("inner_radius_m", spec.inner_radius_m);
    tool.insert("outer_radius_m", spec.radius_m);
    tool.insert("height_m", spec.height_m);
    break;
  }
  if (spec.round()) {
    const int n = segment_count(spec);
    tool.insert("segments", n);
    tool.insert("chord_error_fraction", 1.0 - std::cos(std::acos(-1.0) / n));
  }
  tool.insert("max_edge_m", spec.max_edge_m);
  tool.insert("ideal_volume_m3", ideal_volume_m3(spec));
  const toml::table root{{"tool", tool},
                         {"mesh", mesh_table(g, mesh_files)},
                         {"mass_properties", mass_table(g.props, "inertia_about_origin_kg_m2")}};
  write_toml_or_json(path, root);
}

std::string format_properties(const std::string &name, const WheelSpec &spec,
                              const GeneratedSolid &w) {
  return name + ": " + describe(spec) + "\n" + format_solid(w);
}

std::string format_properties(const std::string &name, const ToolSpec &spec,
                              const GeneratedSolid &g) {
  std::ostringstream os;
  os.precision(6);
  const double ideal = ideal_volume_m3(spec);
  os << name << ": " << describe(spec) << "\n"
     << "  bounding box " << 2.0 * spec.half_x_m() << " x " << 2.0 * spec.half_y_m() << " x "
     << spec.height_m << " m, centred at the origin, z up\n"
     << format_solid(g) << "  ideal volume " << ideal << " m^3 (mesh " << std::setprecision(3)
     << 100.0 * (g.props.volume_m3 / ideal - 1.0) << " %)\n";
  return os.str();
}

} // namespace wheelsim::meshes
