// Exact rasterisation of the wheel mesh onto the SCM grid (see wheel_raster.h).
#include "wheel_raster.h"

#include "wheelsim/geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace wheelsim::scm::detail {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

std::int64_t floor_i(double x) {
  const auto i = static_cast<std::int64_t>(x);
  return i - (x < static_cast<double>(i));
}
std::int64_t ceil_i(double x) {
  const auto i = static_cast<std::int64_t>(x);
  return i + (x > static_cast<double>(i));
}
} // namespace

double WheelRasteriser::Box::lowest(const Eigen::Vector3d &up) const {
  double h = 0.0;
  for (int k = 0; k < 3; ++k)
    h += up[k] >= 0.0 ? up[k] * lo[k] : up[k] * hi[k];
  return h;
}

void WheelRasteriser::Box::grow(const Eigen::Vector3d &v) {
  lo = lo.cwiseMin(v);
  hi = hi.cwiseMax(v);
}

WheelRasteriser::WheelRasteriser(const geometry::TriangleMesh &mesh, int sectors, int bands)
    : vertices_B_(mesh.vertices_m) {
  double r_max = 0.0;
  for (const auto &v : vertices_B_)
    r_max = std::max(r_max, std::hypot(v.x(), v.z()));
  struct Keyed {
    int key;
    Triangle t;
  };
  std::vector<Keyed> keyed;
  keyed.reserve(mesh.triangles.size());
  const double two_pi = 2.0 * M_PI;
  for (const auto &t : mesh.triangles) {
    const Eigen::Vector3d &a = vertices_B_[t[0]], &b = vertices_B_[t[1]], &c = vertices_B_[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    if (!(len > 0.0))
      continue; // degenerate: covers no area
    const Eigen::Vector3d m = (a + b + c) / 3.0;
    double angle = std::atan2(m.z(), m.x());
    if (angle < 0.0)
      angle += two_pi;
    const int s = std::min(sectors - 1, static_cast<int>(angle / two_pi * sectors));
    const double r =
        std::max({std::hypot(a.x(), a.z()), std::hypot(b.x(), b.z()), std::hypot(c.x(), c.z())});
    const int band = r_max > 0.0 ? std::min(bands - 1, static_cast<int>(r / r_max * bands)) : 0;
    keyed.push_back({s * bands + band, Triangle{{t[0], t[1], t[2]}, n / len}});
  }
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const Keyed &x, const Keyed &y) { return x.key < y.key; });
  const Box empty{Eigen::Vector3d::Constant(kInf), Eigen::Vector3d::Constant(-kInf)};
  sectors_.assign(sectors, Sector{empty, std::vector<Bin>(bands, Bin{empty, 0, 0})});
  tri_.reserve(keyed.size());
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    Sector &sec = sectors_[keyed[k].key / bands];
    Bin &bin = sec.bands[keyed[k].key % bands];
    const int index = static_cast<int>(tri_.size());
    if (bin.begin == bin.end)
      bin.begin = bin.end = index;
    tri_.push_back(keyed[k].t);
    bin.end = index + 1;
    for (int v : keyed[k].t.v) {
      bin.box.grow(vertices_B_[v]);
      sec.box.grow(vertices_B_[v]);
    }
  }
  vertices_W_.resize(vertices_B_.size());
  stamp_.assign(vertices_B_.size(), 0);
}

void WheelRasteriser::rasterise(const Eigen::Matrix3d &R, const Eigen::Vector3d &p, double z_cut,
                                double delta, int margin, const TileGrid &grid,
                                StepWindow &window) {
  step_normal_W_.clear();
  if (++step_ == 0) { // wrapped: invalidate every stamp
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    step_ = 1;
  }
  // World up seen in B: the height of a body point v_B is p.z + up_B · v_B.
  const Eigen::Vector3d up_B = R.row(2).transpose();
  const double h_cut = z_cut - p.z();

  // Pass 1: bins that reach below the cut, and the xy footprint of their boxes (the window).
  thread_local std::vector<const Bin *> live;
  live.clear();
  double x_lo = kInf, x_hi = -kInf, y_lo = kInf, y_hi = -kInf;
  for (const Sector &sec : sectors_) {
    if (!(sec.box.lowest(up_B) < h_cut))
      continue;
    for (const Bin &bin : sec.bands) {
      if (bin.begin == bin.end || !(bin.box.lowest(up_B) < h_cut))
        continue;
      live.push_back(&bin);
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector3d corner((k & 1 ? bin.box.hi : bin.box.lo).x(),
                                     (k & 2 ? bin.box.hi : bin.box.lo).y(),
                                     (k & 4 ? bin.box.hi : bin.box.lo).z());
        const Eigen::Vector3d w = R * corner + p;
        x_lo = std::min(x_lo, w.x());
        x_hi = std::max(x_hi, w.x());
        y_lo = std::min(y_lo, w.y());
        y_hi = std::max(y_hi, w.y());
      }
    }
  }
  if (live.empty()) {
    window.clear();
    return;
  }
  const std::int64_t i0 = floor_i(x_lo / delta) - margin, i1 = ceil_i(x_hi / delta) + margin;
  const std::int64_t j0 = floor_i(y_lo / delta) - margin, j1 = ceil_i(y_hi / delta) + margin;
  window.reset(i0, j0, static_cast<int>(i1 - i0 + 1), static_cast<int>(j1 - j0 + 1), grid);

  // Pass 2: downward-facing triangles that reach below the cut, rasterised onto the nodes they
  // cover. Barycentric coordinates of node (x, y) in the projected triangle; inclusive edges with
  // a relative tolerance, so a node on a shared edge is never missed (both sides agree on z).
  constexpr double kEdgeTolerance = 1e-12;
  const double inv_delta = 1.0 / delta;
  auto vertex_W = [&](int v) -> const Eigen::Vector3d & {
    if (stamp_[v] != step_) {
      vertices_W_[v] = R * vertices_B_[v] + p;
      stamp_[v] = step_;
    }
    return vertices_W_[v];
  };
  for (const Bin *bin : live) {
    for (int t = bin->begin; t < bin->end; ++t) {
      const Triangle &tr = tri_[t];
      if (up_B.dot(tr.n_B) >= 0.0)
        continue; // not facing down: the lowest surface point over a node is on a downward face
      const Eigen::Vector3d &A = vertex_W(tr.v[0]), &B = vertex_W(tr.v[1]), &C = vertex_W(tr.v[2]);
      if (std::min({A.z(), B.z(), C.z()}) >= z_cut)
        continue;
      const double ax = A.x(), ay = A.y();
      const double bx = B.x() - ax, by = B.y() - ay;
      const double cx = C.x() - ax, cy = C.y() - ay;
      const double det = bx * cy - by * cx;
      if (std::abs(det) <= 1e-14 * (bx * bx + by * by + cx * cx + cy * cy))
        continue; // seen edge-on from above: covers no node area
      const std::int64_t ia = ceil_i(std::min({A.x(), B.x(), C.x()}) * inv_delta - 1e-9);
      const std::int64_t ib = floor_i(std::max({A.x(), B.x(), C.x()}) * inv_delta + 1e-9);
      if (ib < ia)
        continue;
      const std::int64_t ja = ceil_i(std::min({A.y(), B.y(), C.y()}) * inv_delta - 1e-9);
      const std::int64_t jb = floor_i(std::max({A.y(), B.y(), C.y()}) * inv_delta + 1e-9);
      if (jb < ja)
        continue;
      const int tri_index = static_cast<int>(step_normal_W_.size());
      bool hit = false;
      const double inv = 1.0 / det;
      const double zb = B.z() - A.z(), zc = C.z() - A.z();
      for (std::int64_t j = ja; j <= jb; ++j) {
        const double qy = j * delta - ay;
        for (std::int64_t i = ia; i <= ib; ++i) {
          const double qx = i * delta - ax;
          const double lb = (qx * cy - qy * cx) * inv;
          const double lc = (bx * qy - by * qx) * inv;
          if (lb < -kEdgeTolerance || lc < -kEdgeTolerance || lb + lc > 1.0 + kEdgeTolerance)
            continue;
          const double z = A.z() + lb * zb + lc * zc;
          const int c = window.cell(i, j);
          if (z < window.hit_z[c]) {
            window.hit_z[c] = z;
            window.hit_tri[c] = tri_index;
            hit = true;
          }
        }
      }
      if (hit)
        step_normal_W_.push_back(R * tr.n_B);
    }
  }
}

} // namespace wheelsim::scm::detail
