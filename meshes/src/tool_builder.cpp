// Construction (docs/tool-mesh.md, "How the mesh is built"):
//  1. The plane region (z = 0) is a set of convex cells, counter-clockwise seen from +z, sharing
//     their points exactly: a rectilinear grid whose lines are the region's edges (subdivided by
//     --max-edge) with the cells of the frame's hole left out, or a polar grid of rings x
//     segments (a fan around the centre of the disc).
//  2. The caps are the cells at z = +-height/2 (the bottom one reversed), split into triangles
//     from their first point.
//  3. A boundary edge is an edge of one cell only (its reverse belongs to no cell); the region
//     lies to its left, so the wall quad swept from z_k to z_k+1 along it faces outward.
#include "tool_builder.h"

#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Core>

namespace wheelsim::meshes {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using geometry::TriangleMesh;

/// Convex cells in the plane z = 0, counter-clockwise seen from +z, on shared points.
struct PlaneRegion {
  std::vector<Vector2d> points_m;
  std::vector<std::vector<int>> cells;
};

/// edge_parts as an int: the spec passed validate(), its counts are bounded.
int parts(double length_m, double max_edge_m) {
  return static_cast<int>(edge_parts(length_m, max_edge_m));
}

/// The breakpoints `edges` (increasing) with every interval split into equal parts no longer
/// than max_edge_m.
std::vector<double> subdivide(const std::vector<double> &edges, double max_edge_m) {
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const int n = parts(edges[i + 1] - edges[i], max_edge_m);
    for (int k = 0; k < n; ++k)
      out.push_back(edges[i] + (edges[i + 1] - edges[i]) * k / n);
  }
  out.push_back(edges.back());
  return out;
}

/// Rectangle [-hx, hx] x [-hy, hy], without the hole [-gx, gx] x [-gy, gy] when gx, gy > 0.
PlaneRegion rectilinear_region(double hx, double hy, double gx, double gy, double max_edge_m) {
  const bool hole = gx > 0.0 && gy > 0.0;
  const std::vector<double> xs = subdivide(
      hole ? std::vector<double>{-hx, -gx, gx, hx} : std::vector<double>{-hx, hx}, max_edge_m);
  const std::vector<double> ys = subdivide(
      hole ? std::vector<double>{-hy, -gy, gy, hy} : std::vector<double>{-hy, hy}, max_edge_m);
  PlaneRegion r;
  const int nx = static_cast<int>(xs.size()), ny = static_cast<int>(ys.size());
  std::vector<int> id(static_cast<std::size_t>(nx) * ny, -1);
  auto point = [&](int i, int j) {
    int &v = id[static_cast<std::size_t>(j) * nx + i];
    if (v < 0) {
      v = static_cast<int>(r.points_m.size());
      r.points_m.emplace_back(xs[i], ys[j]);
    }
    return v;
  };
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const double xc = 0.5 * (xs[i] + xs[i + 1]), yc = 0.5 * (ys[j] + ys[j + 1]);
      if (hole && std::abs(xc) < gx && std::abs(yc) < gy)
        continue;
      r.cells.push_back({point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)});
    }
  }
  return r;
}

/// Annulus r_in..r_out (a disc when r_in = 0) with `segments` around; rings no wider than
/// max_edge_m. Point (ring l, segment m) is at angle 2 pi m / segments from +x towards +y.
PlaneRegion polar_region(double r_in, double r_out, int segments, double max_edge_m) {
  const int rings = parts(r_out - r_in, max_edge_m);
  PlaneRegion r;
  const int first = r_in > 0.0 ? 0 : 1; // the disc's ring 0 is its centre point
  for (int l = first; l <= rings; ++l) {
    const double radius = r_in + (r_out - r_in) * l / rings;
    for (int m = 0; m < segments; ++m) {
      const double theta = 2.0 * M_PI * m / segments;
      r.points_m.emplace_back(radius * std::cos(theta), radius * std::sin(theta));
    }
  }
  auto point = [&](int l, int m) { return (l - first) * segments + m % segments; };
  int centre = -1;
  if (first == 1) {
    centre = static_cast<int>(r.points_m.size());
    r.points_m.emplace_back(0.0, 0.0);
  }
  for (int l = 0; l < rings; ++l) {
    for (int m = 0; m < segments; ++m) {
      if (l == 0 && centre >= 0)
        r.cells.push_back({centre, point(1, m), point(1, m + 1)});
      else
        r.cells.push_back({point(l, m), point(l + 1, m), point(l + 1, m + 1), point(l, m + 1)});
    }
  }
  return r;
}

PlaneRegion plane_region(const ToolSpec &s) {
  switch (s.kind) {
  case ToolKind::plate_rect:
    return rectilinear_region(0.5 * s.lx_m, 0.5 * s.ly_m, 0.0, 0.0, s.max_edge_m);
  case ToolKind::frame:
    return rectilinear_region(s.half_x_m(), s.half_y_m(), 0.5 * s.lx_m, 0.5 * s.ly_m, s.max_edge_m);
  case ToolKind::plate_disc:
    return polar_region(0.0, s.radius_m, segment_count(s), s.max_edge_m);
  case ToolKind::ring:
    return polar_region(s.inner_radius_m, s.radius_m, segment_count(s), s.max_edge_m);
  }
  return {};
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

/// Extrudes `region` from z = -height/2 to +height/2 in `levels` equal steps.
TriangleMesh extrude(const PlaneRegion &region, double height_m, int levels) {
  TriangleMesh mesh;
  std::unordered_map<std::uint64_t, int> ids; // (point, level) -> vertex
  auto vertex = [&](int p, int k) {
    const auto [it, added] = ids.emplace(edge_key(p, k), static_cast<int>(mesh.vertices_m.size()));
    if (added) {
      const double z = height_m * (static_cast<double>(k) / levels - 0.5);
      mesh.vertices_m.emplace_back(region.points_m[p].x(), region.points_m[p].y(), z);
    }
    return it->second;
  };
  // Caps: +z on top (counter-clockwise seen from +z), reversed at the bottom.
  for (const auto &c : region.cells) {
    for (std::size_t i = 1; i + 1 < c.size(); ++i) {
      mesh.triangles.push_back(
          {vertex(c[0], levels), vertex(c[i], levels), vertex(c[i + 1], levels)});
      mesh.triangles.push_back({vertex(c[0], 0), vertex(c[i + 1], 0), vertex(c[i], 0)});
    }
  }
  // Walls along the boundary edges a -> b (region on the left, outward to the right).
  std::unordered_set<std::uint64_t> directed;
  for (const auto &c : region.cells)
    for (std::size_t i = 0; i < c.size(); ++i)
      directed.insert(edge_key(c[i], c[(i + 1) % c.size()]));
  for (const auto &c : region.cells) {
    for (std::size_t i = 0; i < c.size(); ++i) {
      const int a = c[i], b = c[(i + 1) % c.size()];
      if (directed.count(edge_key(b, a)) > 0)
        continue; // an inner edge
      for (int k = 0; k < levels; ++k) {
        mesh.triangles.push_back({vertex(a, k), vertex(b, k), vertex(b, k + 1)});
        mesh.triangles.push_back({vertex(a, k), vertex(b, k + 1), vertex(a, k + 1)});
      }
    }
  }
  return mesh;
}

} // namespace

TriangleMesh build_tool_mesh(const ToolSpec &spec) {
  validate(spec);
  return extrude(plane_region(spec), spec.height_m, parts(spec.height_m, spec.max_edge_m));
}

} // namespace wheelsim::meshes
