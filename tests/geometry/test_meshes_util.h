// Small meshes and helpers shared by the geometry tests.
#pragma once

#include <filesystem>
#include <string>

#include <Eigen/Geometry>

#include "wheelsim/geometry/triangle_mesh.h"

namespace wheelsim::geometry::test_meshes {

/// Axis-aligned box [0, a] x [0, b] x [0, c] [m], outward winding, 12 triangles.
inline TriangleMesh box(double a, double b, double c) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices_m.emplace_back((i & 1) ? a : 0.0, (i & 2) ? b : 0.0, (i & 4) ? c : 0.0);
  }
  // Faces as quads (outward, counter-clockwise seen from outside).
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto &q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

/// Applies p -> R p + t to every vertex.
inline TriangleMesh transformed(TriangleMesh m, const Eigen::Matrix3d &R,
                                const Eigen::Vector3d &t) {
  for (auto &v : m.vertices_m)
    v = R * v + t;
  return m;
}

/// A fresh empty directory under the system temp dir.
inline std::filesystem::path temp_dir(const std::string &name) {
  const auto dir = std::filesystem::temp_directory_path() / ("wheelsim_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

} // namespace wheelsim::geometry::test_meshes
