// Validation of a triangle mesh as the closed, outward-oriented surface of a solid in metres.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "wheelsim/geometry/triangle_mesh.h"

namespace wheelsim::geometry {

/// Plausible size of a mesh in metres: the bounding-box diagonal [m] must lie in this range.
/// Outside it the file is probably in other units and check_mesh suggests a `scale`.
inline constexpr double kMinPlausibleDiagonal_m = 1e-3;
inline constexpr double kMaxPlausibleDiagonal_m = 100.0;

/// What check_mesh found. Errors make the mesh unusable as a solid; warnings do not.
struct MeshReport {
  int vertex_count = 0;
  int triangle_count = 0;
  /// Edges used by one triangle only (holes, open surface).
  int boundary_edges = 0;
  /// Edges used by more than two triangles.
  int nonmanifold_edges = 0;
  /// Edges shared by two triangles that traverse it in the same direction (flipped triangle).
  int inconsistent_edges = 0;
  /// Indices of triangles with zero area or repeated vertex indices.
  std::vector<int> degenerate_triangles;
  /// Signed volume [m^3] by the divergence theorem; > 0 for outward normals.
  double signed_volume_m3 = 0.0;
  /// Axis-aligned bounding box [m] and its diagonal [m].
  Eigen::Vector3d bbox_min_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d bbox_max_m = Eigen::Vector3d::Zero();
  double bbox_diagonal_m = 0.0;
  /// One sentence per problem, e.g. "mesh is not closed: 12 boundary edges (first at vertex
  /// (0.1, 0, 0.3) m)". No file name: load_mesh prefixes it.
  std::vector<std::string> errors;
  std::vector<std::string> warnings;

  bool closed() const { return boundary_edges == 0 && nonmanifold_edges == 0; }
  bool consistently_oriented() const { return inconsistent_edges == 0; }
  bool ok() const { return errors.empty(); }
};

/// Checks `mesh` as a solid in metres:
/// - empty (no triangles) — error;
/// - a vertex with a NaN or infinite coordinate — error (0-based index; no further checks);
/// - closed: every edge shared by exactly two triangles — error otherwise;
/// - consistently oriented: the two triangles of an edge traverse it in opposite directions —
///   error otherwise;
/// - outward: signed volume > 0 — error otherwise ("inside out");
/// - plausible size: bounding-box diagonal in [1 mm, 100 m] — error otherwise, suggesting a scale
///   ("looks like millimetres: use scale 0.001");
/// - degenerate triangles (zero area, repeated indices) — warning; their indices are reported.
/// Triangles with repeated indices take no part in the edge checks.
MeshReport check_mesh(const TriangleMesh &mesh);

/// Signed volume [m^3] enclosed by `mesh` (divergence theorem; exact for closed meshes).
double signed_volume(const TriangleMesh &mesh);

/// Formats a point as "(x, y, z)" with 6 significant digits, for messages.
std::string format_point(const Eigen::Vector3d &p);

} // namespace wheelsim::geometry
