// See sphere_contact_index.h for the contact rules. Closest point on a triangle by Voronoi-region
// classification (Ericson, Real-Time Collision Detection, §5.1.5); the grid registers a triangle
// in every cell whose circumscribed sphere it touches, so a triangle within a query sphere is
// always found in a cell overlapping that sphere's bounding box.
#include "wheelsim/geometry/sphere_contact_index.h"

#include "wheelsim/geometry/mesh_error.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace wheelsim::geometry {
namespace {

/// Relative tolerance of the normal-cone tests (cosine units). Large against round-off of the
/// closest-point computation (~1e-13 relative), small against any real geometry; a contact that
/// passes by tolerance next to a face contact is removed by the adjacency rules.
constexpr double kConeTolerance = 1e-9;
/// Two kept contacts of one sphere whose points are closer than this fraction of the radius and
/// whose normals agree to within kSameNormalCosine are one contact found twice through round-off
/// (e.g. over a vertex shared by coplanar triangles, reached as the end of two different edges).
constexpr double kSamePointFraction = 1e-6;
constexpr double kSameNormalCosine = 1.0 - 1e-6;
/// Upper bound on grid cells (memory: 4 bytes per cell plus the registrations).
constexpr long kMaxCells = 8'000'000;

enum Region {
  kFace = 0,
  kEdgeAB = 1,
  kEdgeBC = 2,
  kEdgeCA = 3,
  kVertA = 4,
  kVertB = 5,
  kVertC = 6
};

/// Closest point of triangle (a, b, c) to p and the Voronoi region it lies in. Points on a
/// triangle's boundary are classified as edge or vertex, never as face.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d &p, const Eigen::Vector3d &a,
                                          const Eigen::Vector3d &b, const Eigen::Vector3d &c,
                                          int &region) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    region = kVertA;
    return a;
  }
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    region = kVertB;
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    region = kEdgeAB;
    return a + (d1 / (d1 - d3)) * ab;
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    region = kVertC;
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    region = kEdgeCA;
    return a + (d2 / (d2 - d6)) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    region = kEdgeBC;
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  region = kFace;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

} // namespace

SphereContactIndex::SphereContactIndex(TriangleMesh mesh, double cell_size_m)
    : mesh_(std::move(mesh)) {
  if (mesh_.triangles.empty())
    throw MeshError("contact index: the mesh has no triangles");
  normals_.reserve(mesh_.triangles.size());
  for (const auto &t : mesh_.triangles) {
    const Eigen::Vector3d &a = mesh_.vertices_m[t[0]], &b = mesh_.vertices_m[t[1]],
                          &c = mesh_.vertices_m[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    normals_.push_back(len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero());
  }
  for (const auto &v : mesh_.vertices_m)
    bounding_radius_m_ = std::max(bounding_radius_m_, v.norm());
  build_adjacency();
  build_grid(cell_size_m);
}

void SphereContactIndex::build_adjacency() {
  const int nv = static_cast<int>(mesh_.vertices_m.size());
  const int nt = static_cast<int>(mesh_.triangles.size());
  std::map<std::pair<int, int>, int> edge_of;
  triangle_edges_.assign(nt, {-1, -1, -1});
  for (int t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int u = mesh_.triangles[t][k], w = mesh_.triangles[t][(k + 1) % 3];
      const std::pair<int, int> key(std::min(u, w), std::max(u, w));
      auto it = edge_of.find(key);
      if (it == edge_of.end()) {
        edge_of.emplace(key, static_cast<int>(edges_.size()));
        triangle_edges_[t][k] = static_cast<int>(edges_.size());
        edges_.push_back({key.first, key.second, {t, -1}});
      } else {
        Edge &e = edges_[it->second];
        if (e.tri[1] >= 0)
          throw MeshError("contact index: edge between vertices " + std::to_string(key.first) +
                          " and " + std::to_string(key.second) +
                          " is shared by more than two triangles");
        e.tri[1] = t;
        triangle_edges_[t][k] = it->second;
      }
    }
  }
  // CSR lists of the edges and triangles around each vertex.
  auto build_csr = [nv](const std::vector<std::pair<int, int>> &pairs, std::vector<int> &offsets,
                        std::vector<int> &items) {
    offsets.assign(nv + 1, 0);
    for (const auto &p : pairs)
      ++offsets[p.first + 1];
    for (int i = 0; i < nv; ++i)
      offsets[i + 1] += offsets[i];
    items.assign(pairs.size(), -1);
    std::vector<int> fill(offsets.begin(), offsets.end() - 1);
    for (const auto &p : pairs)
      items[fill[p.first]++] = p.second;
  };
  std::vector<std::pair<int, int>> vertex_edge, vertex_tri;
  for (int e = 0; e < static_cast<int>(edges_.size()); ++e) {
    vertex_edge.emplace_back(edges_[e].v0, e);
    vertex_edge.emplace_back(edges_[e].v1, e);
  }
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      vertex_tri.emplace_back(mesh_.triangles[t][k], t);
  build_csr(vertex_edge, vertex_edge_offsets_, vertex_edges_);
  build_csr(vertex_tri, vertex_tri_offsets_, vertex_tris_);
}

void SphereContactIndex::build_grid(double cell_size_m) {
  Eigen::Vector3d lo = mesh_.vertices_m.front(), hi = lo;
  for (const auto &v : mesh_.vertices_m) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  if (cell_size_m <= 0.0) {
    double total = 0.0;
    for (const auto &e : edges_)
      total += (mesh_.vertices_m[e.v1] - mesh_.vertices_m[e.v0]).norm();
    cell_size_m = total / static_cast<double>(edges_.size());
  }
  const Eigen::Vector3d extent = hi - lo;
  cell_size_m = std::max(cell_size_m, 1e-6 * extent.norm());
  auto cells_for = [&](double h) {
    long n = 1;
    for (int k = 0; k < 3; ++k)
      n *= static_cast<long>(std::floor(extent[k] / h)) + 1;
    return n;
  };
  while (cells_for(cell_size_m) > kMaxCells)
    cell_size_m *= 1.25;
  cell_size_m_ = cell_size_m;
  grid_origin_m_ = lo;
  for (int k = 0; k < 3; ++k)
    dims_[k] = static_cast<int>(std::floor(extent[k] / cell_size_m)) + 1;

  const double half_diagonal = 0.5 * std::sqrt(3.0) * cell_size_m * (1.0 + 1e-9);
  std::vector<std::pair<long, int>> registrations;
  for (int t = 0; t < static_cast<int>(mesh_.triangles.size()); ++t) {
    const auto &tri = mesh_.triangles[t];
    const Eigen::Vector3d &a = mesh_.vertices_m[tri[0]], &b = mesh_.vertices_m[tri[1]],
                          &c = mesh_.vertices_m[tri[2]];
    int lo_idx[3], hi_idx[3];
    cell_range(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), lo_idx, hi_idx);
    for (int i = lo_idx[0]; i <= hi_idx[0]; ++i)
      for (int j = lo_idx[1]; j <= hi_idx[1]; ++j)
        for (int k = lo_idx[2]; k <= hi_idx[2]; ++k) {
          const Eigen::Vector3d centre =
              grid_origin_m_ + cell_size_m * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
          int region;
          if ((closest_point_on_triangle(centre, a, b, c, region) - centre).norm() <= half_diagonal)
            registrations.emplace_back((static_cast<long>(k) * dims_[1] + j) * dims_[0] + i, t);
        }
  }
  std::sort(registrations.begin(), registrations.end());
  const long ncells = static_cast<long>(dims_[0]) * dims_[1] * dims_[2];
  cell_offsets_.assign(ncells + 1, 0);
  cell_triangles_.resize(registrations.size());
  for (std::size_t r = 0; r < registrations.size(); ++r) {
    ++cell_offsets_[registrations[r].first + 1];
    cell_triangles_[r] = registrations[r].second;
  }
  for (long c = 0; c < ncells; ++c)
    cell_offsets_[c + 1] += cell_offsets_[c];
}

bool SphereContactIndex::cell_range(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi,
                                    int lo_idx[3], int hi_idx[3]) const {
  for (int k = 0; k < 3; ++k) {
    const double l = std::floor((lo[k] - grid_origin_m_[k]) / cell_size_m_);
    const double h = std::floor((hi[k] - grid_origin_m_[k]) / cell_size_m_);
    if (h < 0.0 || l >= dims_[k])
      return false;
    lo_idx[k] = static_cast<int>(std::max(l, 0.0));
    hi_idx[k] = static_cast<int>(std::min(h, static_cast<double>(dims_[k] - 1)));
  }
  return true;
}

bool SphereContactIndex::edge_cone_contains(int edge, const Eigen::Vector3d &direction) const {
  const Edge &e = edges_[edge];
  if (e.tri[1] < 0)
    return false; // open edge: not a solid's surface
  const Eigen::Vector3d &v0 = mesh_.vertices_m[e.v0], &v1 = mesh_.vertices_m[e.v1];
  const Eigen::Vector3d u = (v1 - v0).normalized();
  const double tolerance = kConeTolerance * direction.norm();
  for (int side = 0; side < 2; ++side) {
    const auto &tri = mesh_.triangles[e.tri[side]];
    int third = tri[0];
    for (int k = 0; k < 3; ++k)
      if (tri[k] != e.v0 && tri[k] != e.v1)
        third = tri[k];
    Eigen::Vector3d inward = mesh_.vertices_m[third] - v0;
    inward -= inward.dot(u) * u; // in the triangle's plane, perpendicular to the edge
    if (direction.dot(inward.normalized()) > tolerance)
      return false;
  }
  return true;
}

bool SphereContactIndex::vertex_cone_contains(int vertex, const Eigen::Vector3d &direction) const {
  const Eigen::Vector3d &v = mesh_.vertices_m[vertex];
  const double tolerance = kConeTolerance * direction.norm();
  for (int i = vertex_edge_offsets_[vertex]; i < vertex_edge_offsets_[vertex + 1]; ++i) {
    const Edge &e = edges_[vertex_edges_[i]];
    const int other = e.v0 == vertex ? e.v1 : e.v0;
    if (direction.dot((mesh_.vertices_m[other] - v).normalized()) > tolerance)
      return false;
  }
  return true;
}

bool SphereContactIndex::surface_within(const Eigen::Vector3d &centre_m, double distance_m) const {
  // A triangle closer than distance_m has its closest point q inside the query box and inside
  // the grid, and is registered in q's cell (build_grid): visiting the box's cells finds it.
  const Eigen::Vector3d reach = Eigen::Vector3d::Constant(distance_m);
  int lo_idx[3], hi_idx[3];
  if (!cell_range(centre_m - reach, centre_m + reach, lo_idx, hi_idx))
    return false;
  for (int k = lo_idx[2]; k <= hi_idx[2]; ++k)
    for (int j = lo_idx[1]; j <= hi_idx[1]; ++j)
      for (int i = lo_idx[0]; i <= hi_idx[0]; ++i) {
        const long cell = (static_cast<long>(k) * dims_[1] + j) * dims_[0] + i;
        for (int c = cell_offsets_[cell]; c < cell_offsets_[cell + 1]; ++c) {
          const auto &tri = mesh_.triangles[cell_triangles_[c]];
          int region;
          const Eigen::Vector3d q =
              closest_point_on_triangle(centre_m, mesh_.vertices_m[tri[0]],
                                        mesh_.vertices_m[tri[1]], mesh_.vertices_m[tri[2]], region);
          if ((centre_m - q).squaredNorm() < distance_m * distance_m)
            return true;
        }
      }
  return false;
}

int SphereContactIndex::find_contacts(const Eigen::Vector3d &centre_m, double radius_m,
                                      std::vector<SurfaceContact> &contacts) const {
  const Eigen::Vector3d reach = Eigen::Vector3d::Constant(radius_m);
  int lo_idx[3], hi_idx[3];
  if (!cell_range(centre_m - reach, centre_m + reach, lo_idx, hi_idx))
    return 0;
  candidates_.clear();
  for (int k = lo_idx[2]; k <= hi_idx[2]; ++k)
    for (int j = lo_idx[1]; j <= hi_idx[1]; ++j)
      for (int i = lo_idx[0]; i <= hi_idx[0]; ++i) {
        const long cell = (static_cast<long>(k) * dims_[1] + j) * dims_[0] + i;
        candidates_.insert(candidates_.end(), cell_triangles_.begin() + cell_offsets_[cell],
                           cell_triangles_.begin() + cell_offsets_[cell + 1]);
      }
  if (candidates_.empty())
    return 0;
  std::sort(candidates_.begin(), candidates_.end());
  candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());

  hits_.clear();
  for (int t : candidates_) {
    const auto &tri = mesh_.triangles[t];
    int region;
    const Eigen::Vector3d q =
        closest_point_on_triangle(centre_m, mesh_.vertices_m[tri[0]], mesh_.vertices_m[tri[1]],
                                  mesh_.vertices_m[tri[2]], region);
    const double distance = (centre_m - q).norm();
    if (distance < radius_m)
      hits_.push_back({t, region, q, distance});
  }
  if (hits_.empty())
    return 0;

  const std::int64_t nt = static_cast<std::int64_t>(mesh_.triangles.size());
  const std::int64_t ne = static_cast<std::int64_t>(edges_.size());
  const std::size_t first = contacts.size();
  auto has_face_contact = [&](int t) {
    for (const RawHit &h : hits_)
      if (h.triangle == t && h.region == kFace)
        return true;
    return false;
  };
  auto already_reported = [&](std::int64_t key) {
    for (std::size_t c = first; c < contacts.size(); ++c)
      if (contacts[c].feature_key == key)
        return true;
    return false;
  };
  const double same_point_m = kSamePointFraction * radius_m;
  auto duplicates_kept = [&](const Eigen::Vector3d &point, const Eigen::Vector3d &normal) {
    for (std::size_t c = first; c < contacts.size(); ++c)
      if ((contacts[c].point_m - point).norm() < same_point_m &&
          contacts[c].normal.dot(normal) > kSameNormalCosine)
        return true;
    return false;
  };

  // 1. Faces: always kept, if the centre is in front of the face.
  for (const RawHit &h : hits_) {
    if (h.region != kFace)
      continue;
    const Eigen::Vector3d &n = normals_[h.triangle];
    if ((centre_m - h.point).dot(n) < 0.0 || duplicates_kept(h.point, n))
      continue; // centre behind the face (inside the solid), or found twice
    contacts.push_back(
        {h.point, n, radius_m - h.distance, SurfaceFeature::Face, h.triangle, h.triangle});
  }
  // 2. Edges: convex-edge normal cone, no face contact on either triangle, reported once.
  for (const RawHit &h : hits_) {
    if (h.region < kEdgeAB || h.region > kEdgeCA || h.distance <= 0.0)
      continue;
    const int edge = triangle_edges_[h.triangle][h.region - kEdgeAB];
    const std::int64_t key = nt + edge;
    const Edge &e = edges_[edge];
    const Eigen::Vector3d direction = centre_m - h.point;
    if (already_reported(key) || has_face_contact(e.tri[0]) ||
        (e.tri[1] >= 0 && has_face_contact(e.tri[1])) || !edge_cone_contains(edge, direction) ||
        duplicates_kept(h.point, direction / h.distance))
      continue;
    contacts.push_back({h.point, direction / h.distance, radius_m - h.distance,
                        SurfaceFeature::Edge, key, h.triangle});
  }
  // 3. Vertices: normal cone, nothing kept on an incident face or edge, reported once.
  for (const RawHit &h : hits_) {
    if (h.region < kVertA || h.distance <= 0.0)
      continue;
    const int vertex = mesh_.triangles[h.triangle][h.region - kVertA];
    const std::int64_t key = nt + ne + vertex;
    if (already_reported(key))
      continue;
    bool blocked = false;
    for (int i = vertex_tri_offsets_[vertex]; i < vertex_tri_offsets_[vertex + 1] && !blocked; ++i)
      blocked = has_face_contact(vertex_tris_[i]);
    for (int i = vertex_edge_offsets_[vertex]; i < vertex_edge_offsets_[vertex + 1] && !blocked;
         ++i)
      blocked = already_reported(nt + vertex_edges_[i]);
    const Eigen::Vector3d direction = centre_m - h.point;
    if (blocked || !vertex_cone_contains(vertex, direction) ||
        duplicates_kept(h.point, direction / h.distance))
      continue;
    contacts.push_back({h.point, direction / h.distance, radius_m - h.distance,
                        SurfaceFeature::Vertex, key, h.triangle});
  }
  return static_cast<int>(contacts.size() - first);
}

} // namespace wheelsim::geometry
