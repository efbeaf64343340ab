// Sphere–surface contact detection against a rigid triangle mesh, in the mesh's own frame.
//
// The wheel is rigid, so its mesh is indexed once, in the wheel frame, and candidate spheres are
// transformed into that frame (never the mesh into the world). The rules below make the contact
// set right on tessellated surfaces:
//  - a face contact (closest point inside a triangle) is always kept;
//  - an edge contact is kept only if the sphere centre lies in the edge's normal cone (the wedge
//    between the two face normals: convex edges only; concave edges never) and neither triangle
//    of the edge has a face contact;
//  - a vertex contact is kept only if the centre lies in the vertex's normal cone (the direction
//    to the centre makes an obtuse or right angle with every edge leaving the vertex) and no face
//    or edge incident to the vertex has a kept contact;
//  - edge and vertex contacts reached from several triangles are reported once, and so is a
//    contact found twice through round-off (same point to 1e-6 of the radius, same normal).
// Consequences (tested in tests/geometry/test_sphere_contact_index.cpp): a sphere on a flat face
// split into many triangles has exactly one contact, also exactly over a shared edge or vertex;
// a sphere in the concave corner between a lug face and the rim has two; sliding across a convex
// edge or vertex gives one contact whose normal turns continuously, never zero or two.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "wheelsim/geometry/triangle_mesh.h"

namespace wheelsim::geometry {

/// Which part of the surface a contact point lies on.
enum class SurfaceFeature : std::uint8_t { Face, Edge, Vertex };

/// One sphere–surface contact, in the mesh frame.
struct SurfaceContact {
  /// Closest point of the surface to the sphere centre [m].
  Eigen::Vector3d point_m;
  /// Unit contact normal, from the surface towards the sphere centre.
  Eigen::Vector3d normal;
  /// Penetration depth: radius − distance(centre, point) [m], > 0.
  double overlap_m = 0.0;
  SurfaceFeature feature = SurfaceFeature::Face;
  /// Identifies the face, edge or vertex uniquely within the mesh (stable across queries): use it
  /// to key contact history.
  std::int64_t feature_key = -1;
  /// A triangle that carries the contact point (the face itself, or one triangle of the edge or
  /// vertex): for per-triangle output such as contact pressure.
  int triangle = -1;
};

/// Uniform-grid index of a closed triangle mesh for sphere contact queries. Built once; queries
/// are read-only for the mesh but use internal scratch space: one index per thread.
class SphereContactIndex {
public:
  /// Indexes `mesh` (copied). `cell_size_m` ≤ 0 picks one from the triangle sizes. Throws
  /// MeshError for an empty mesh or an edge shared by more than two triangles.
  explicit SphereContactIndex(TriangleMesh mesh, double cell_size_m = 0.0);

  /// Appends to `contacts` every contact of the sphere (centre [m] in the mesh frame, radius
  /// [m]) with the surface, by the rules above; returns how many were appended. A sphere whose
  /// centre is inside the solid (behind every face it overlaps) gets none.
  int find_contacts(const Eigen::Vector3d &centre_m, double radius_m,
                    std::vector<SurfaceContact> &contacts) const;

  /// Whether some point of the surface lies closer than `distance_m` [m] to `centre_m` (mesh
  /// frame [m]), on either side of it (no contact rules: inside the solid counts too). For
  /// bounding which spheres can reach the surface soon (the fix's candidate list).
  bool surface_within(const Eigen::Vector3d &centre_m, double distance_m) const;

  /// Largest distance of a vertex from the mesh-frame origin [m] (for a cheap reject test).
  double bounding_radius_m() const { return bounding_radius_m_; }
  double cell_size_m() const { return cell_size_m_; }
  const TriangleMesh &mesh() const { return mesh_; }
  /// Unit outward normal of triangle `t`.
  const Eigen::Vector3d &triangle_normal(int t) const { return normals_[t]; }

private:
  struct Edge {
    int v0, v1; // vertex indices, v0 < v1
    int tri[2]; // the two triangles sharing it
  };
  void build_adjacency();
  void build_grid(double cell_size_m);
  bool cell_range(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi, int lo_idx[3],
                  int hi_idx[3]) const;
  bool edge_cone_contains(int edge, const Eigen::Vector3d &direction) const;
  bool vertex_cone_contains(int vertex, const Eigen::Vector3d &direction) const;

  TriangleMesh mesh_;
  std::vector<Eigen::Vector3d> normals_;
  std::vector<Edge> edges_;
  std::vector<std::array<int, 3>> triangle_edges_;      // edge index of (a,b), (b,c), (c,a)
  std::vector<int> vertex_edge_offsets_, vertex_edges_; // CSR: edges incident to each vertex
  std::vector<int> vertex_tri_offsets_, vertex_tris_;   // CSR: triangles incident to each vertex
  double bounding_radius_m_ = 0.0;

  Eigen::Vector3d grid_origin_m_;
  double cell_size_m_ = 0.0;
  int dims_[3] = {0, 0, 0};
  std::vector<int> cell_offsets_, cell_triangles_; // CSR: triangles near each cell

  // Query scratch (hence one index per thread).
  mutable std::vector<int> candidates_;
  struct RawHit {
    int triangle;
    int region; // 0 face, 1..3 edge (ab, bc, ca), 4..6 vertex (a, b, c)
    Eigen::Vector3d point;
    double distance;
  };
  mutable std::vector<RawHit> hits_;
};

} // namespace wheelsim::geometry
