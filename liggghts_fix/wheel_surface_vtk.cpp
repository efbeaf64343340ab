#include "wheel_surface_vtk.h"

#include <cstdio>

namespace wheelsim {

bool write_wheel_surface_vtk(const std::string &path, const geometry::TriangleMesh &mesh,
                             const WheelState &state, const std::vector<double> &pressure_Pa,
                             const std::vector<double> &contact_count, long step, double time_s) {
  FILE *out = std::fopen(path.c_str(), "w");
  if (out == nullptr)
    return false;
  const Eigen::Matrix3d R = state.orientation.toRotationMatrix();
  std::fprintf(out, "# vtk DataFile Version 3.0\n");
  std::fprintf(out, "wheelsim wheel surface, step %ld, time %.9g s\n", step, time_s);
  std::fprintf(out, "ASCII\nDATASET POLYDATA\nPOINTS %zu double\n", mesh.vertices_m.size());
  for (const Eigen::Vector3d &v : mesh.vertices_m) {
    const Eigen::Vector3d w = state.position_m + R * v;
    std::fprintf(out, "%.9g %.9g %.9g\n", w.x(), w.y(), w.z());
  }
  const std::size_t nt = mesh.triangles.size();
  std::fprintf(out, "POLYGONS %zu %zu\n", nt, 4 * nt);
  for (const auto &t : mesh.triangles)
    std::fprintf(out, "3 %d %d %d\n", t[0], t[1], t[2]);
  std::fprintf(out, "CELL_DATA %zu\nSCALARS contact_pressure double 1\nLOOKUP_TABLE default\n", nt);
  for (std::size_t i = 0; i < nt; ++i)
    std::fprintf(out, "%.6g\n", i < pressure_Pa.size() ? pressure_Pa[i] : 0.0);
  std::fprintf(out, "SCALARS contact_count double 1\nLOOKUP_TABLE default\n");
  for (std::size_t i = 0; i < nt; ++i)
    std::fprintf(out, "%.6g\n", i < contact_count.size() ? contact_count[i] : 0.0);
  const bool ok = std::ferror(out) == 0;
  return std::fclose(out) == 0 && ok;
}

} // namespace wheelsim
