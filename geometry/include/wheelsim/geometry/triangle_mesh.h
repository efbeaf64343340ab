// Indexed triangle mesh in metres: the one mesh type shared by the generator, the fix, the rig and
// SCM.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

namespace wheelsim::geometry {

/// An indexed triangle mesh with shared vertices.
///
/// Units and conventions:
/// - `vertices_m`: vertex positions [m] in the mesh's own (body) frame. For wheels made by
///   wheel-mesh this is the wheel frame: centre at the origin, axle along +y, x forward, z up.
/// - `triangles`: zero-based indices into `vertices_m`. A triangle (a, b, c) is counter-clockwise
///   seen from outside the solid, so its right-hand normal (b - a) x (c - a) points outward.
/// A valid solid (see check_mesh) is closed, consistently oriented and has positive volume.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices_m;
  std::vector<std::array<int, 3>> triangles;
};

} // namespace wheelsim::geometry
