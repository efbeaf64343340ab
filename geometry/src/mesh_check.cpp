#include "wheelsim/geometry/mesh_check.h"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_map>

#include <Eigen/Geometry>

namespace wheelsim::geometry {
namespace {

struct EdgeUse {
  int forward = 0;  // traversed from the smaller to the larger vertex index
  int backward = 0; // traversed from the larger to the smaller vertex index
};

bool has_repeated_index(const std::array<int, 3> &t) {
  return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
}

std::string plural(int n, const char *word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

// A power of ten that brings the diagonal near 1 m, with the unit it corresponds to.
std::string scale_hint(double diagonal_m) {
  struct Unit {
    double scale;
    const char *name;
  };
  static const Unit units[] = {
      {1e-3, "millimetres"}, {1e-2, "centimetres"}, {1e-6, "micrometres"}, {1e3, "kilometres"}};
  for (const Unit &u : units) {
    const double d = diagonal_m * u.scale;
    if (d >= 0.05 && d <= kMaxPlausibleDiagonal_m) {
      std::ostringstream os;
      os << "looks like " << u.name << ": use scale " << u.scale;
      return os.str();
    }
  }
  const double s = std::pow(10.0, -std::round(std::log10(diagonal_m)));
  std::ostringstream os;
  os << "use a scale near " << s;
  return os.str();
}

} // namespace

std::string format_point(const Eigen::Vector3d &p) {
  std::ostringstream os;
  os.precision(6);
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

double signed_volume(const TriangleMesh &mesh) {
  if (mesh.vertices_m.empty()) {
    return 0.0;
  }
  // Tetrahedra from a reference point near the mesh keep round-off small far from the origin.
  const Eigen::Vector3d o = mesh.vertices_m.front();
  double six_v = 0.0;
  for (const auto &t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices_m[t[0]] - o;
    const Eigen::Vector3d b = mesh.vertices_m[t[1]] - o;
    const Eigen::Vector3d c = mesh.vertices_m[t[2]] - o;
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6.0;
}

MeshReport check_mesh(const TriangleMesh &mesh) {
  MeshReport r;
  r.vertex_count = static_cast<int>(mesh.vertices_m.size());
  r.triangle_count = static_cast<int>(mesh.triangles.size());
  if (mesh.triangles.empty()) {
    r.errors.push_back("mesh has no triangles");
    return r;
  }
  for (const auto &t : mesh.triangles) {
    for (int i : t) {
      if (i < 0 || i >= r.vertex_count) {
        r.errors.push_back("triangle refers to vertex " + std::to_string(i) + " but there are " +
                           std::to_string(r.vertex_count) + " vertices");
        return r;
      }
    }
  }

  // Every later check is meaningless with a NaN or infinite coordinate.
  for (int i = 0; i < r.vertex_count; ++i) {
    if (!mesh.vertices_m[i].allFinite()) {
      r.errors.push_back("vertex " + std::to_string(i) +
                         " has a coordinate that is not a finite number: " +
                         format_point(mesh.vertices_m[i]) + " m");
      return r;
    }
  }

  // Bounding box and size plausibility.
  r.bbox_min_m = r.bbox_max_m = mesh.vertices_m.front();
  for (const auto &v : mesh.vertices_m) {
    r.bbox_min_m = r.bbox_min_m.cwiseMin(v);
    r.bbox_max_m = r.bbox_max_m.cwiseMax(v);
  }
  r.bbox_diagonal_m = (r.bbox_max_m - r.bbox_min_m).norm();

  // Degenerate triangles. Zero area relative to the mesh size (1e-12 of diagonal^2 is far below
  // any real facet and far above round-off of a collinear triple).
  const double area_eps = 1e-12 * r.bbox_diagonal_m * r.bbox_diagonal_m;
  for (int i = 0; i < r.triangle_count; ++i) {
    const auto &t = mesh.triangles[i];
    if (has_repeated_index(t)) {
      r.degenerate_triangles.push_back(i);
      continue;
    }
    const Eigen::Vector3d &a = mesh.vertices_m[t[0]];
    const double twice_area = (mesh.vertices_m[t[1]] - a).cross(mesh.vertices_m[t[2]] - a).norm();
    if (twice_area <= 2.0 * area_eps) {
      r.degenerate_triangles.push_back(i);
    }
  }

  // Edge topology.
  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(mesh.triangles.size() * 2);
  for (const auto &t : mesh.triangles) {
    if (has_repeated_index(t)) {
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      const std::uint64_t lo = static_cast<std::uint32_t>(std::min(a, b));
      const std::uint64_t hi = static_cast<std::uint32_t>(std::max(a, b));
      EdgeUse &use = edges[(lo << 32) | hi];
      (a < b ? use.forward : use.backward)++;
    }
  }
  int first_boundary = -1, first_nonmanifold = -1, first_inconsistent = -1;
  for (const auto &[key, use] : edges) {
    const int v = static_cast<int>(key >> 32);
    const int n = use.forward + use.backward;
    if (n == 1) {
      r.boundary_edges++;
      if (first_boundary < 0 || v < first_boundary)
        first_boundary = v;
    } else if (n > 2) {
      r.nonmanifold_edges++;
      if (first_nonmanifold < 0 || v < first_nonmanifold)
        first_nonmanifold = v;
    } else if (use.forward != 1) {
      r.inconsistent_edges++;
      if (first_inconsistent < 0 || v < first_inconsistent)
        first_inconsistent = v;
    }
  }
  auto at_vertex = [&](int v) {
    return "(first at vertex " + format_point(mesh.vertices_m[v]) + " m)";
  };
  if (r.boundary_edges > 0) {
    r.errors.push_back("mesh is not closed: " + plural(r.boundary_edges, "boundary edge") + " " +
                       at_vertex(first_boundary));
  }
  if (r.nonmanifold_edges > 0) {
    r.errors.push_back("mesh is not manifold: " + plural(r.nonmanifold_edges, "edge") +
                       " shared by more than two triangles " + at_vertex(first_nonmanifold));
  }
  if (r.inconsistent_edges > 0) {
    r.errors.push_back("mesh is inconsistently oriented: " + plural(r.inconsistent_edges, "edge") +
                       " traversed in the same direction by both its triangles (a flipped "
                       "triangle) " +
                       at_vertex(first_inconsistent));
  }

  r.signed_volume_m3 = signed_volume(mesh);
  if (r.closed() && r.consistently_oriented() && !(r.signed_volume_m3 > 0.0)) {
    std::ostringstream os;
    os << "mesh is inside out: signed volume " << r.signed_volume_m3
       << " m^3 <= 0 (normals point inward; reverse the triangle winding)";
    r.errors.push_back(os.str());
  }
  if (r.bbox_diagonal_m < kMinPlausibleDiagonal_m || r.bbox_diagonal_m > kMaxPlausibleDiagonal_m) {
    std::ostringstream os;
    os << "implausible size for metres: bounding-box diagonal " << r.bbox_diagonal_m
       << " m is outside [" << kMinPlausibleDiagonal_m << ", " << kMaxPlausibleDiagonal_m << "] m; "
       << scale_hint(r.bbox_diagonal_m);
    r.errors.push_back(os.str());
  }
  if (!r.degenerate_triangles.empty()) {
    const auto &t = mesh.triangles[r.degenerate_triangles.front()];
    r.warnings.push_back(
        plural(static_cast<int>(r.degenerate_triangles.size()), "degenerate triangle") +
        " (zero area or repeated vertex; first at vertex " + format_point(mesh.vertices_m[t[0]]) +
        " m)");
  }
  return r;
}

} // namespace wheelsim::geometry
