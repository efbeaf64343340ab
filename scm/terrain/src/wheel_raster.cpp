// Exact rasterisation of the wheel mesh onto the SCM grid (see wheel_raster.h).
#include "wheel_raster.h"

#include "wheelsim/geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wheelsim::scm::detail {

WheelRasteriser::WheelRasteriser(const geometry::TriangleMesh &mesh, int bins) {
  bins_.resize(bins);
  for (auto &b : bins_) {
    b.lo.setConstant(std::numeric_limits<double>::infinity());
    b.hi.setConstant(-std::numeric_limits<double>::infinity());
  }
  tri_.reserve(mesh.triangles.size());
  const double two_pi = 2.0 * M_PI;
  for (const auto &t : mesh.triangles) {
    Triangle tr;
    for (int k = 0; k < 3; ++k)
      tr.v_B[k] = mesh.vertices_m[t[k]];
    const Eigen::Vector3d n = (tr.v_B[1] - tr.v_B[0]).cross(tr.v_B[2] - tr.v_B[0]);
    const double len = n.norm();
    if (!(len > 0.0))
      continue; // degenerate: covers no area
    tr.n_B = n / len;
    const Eigen::Vector3d c = (tr.v_B[0] + tr.v_B[1] + tr.v_B[2]) / 3.0;
    double angle = std::atan2(c.z(), c.x());
    if (angle < 0.0)
      angle += two_pi;
    const int k = std::min(bins - 1, static_cast<int>(angle / two_pi * bins));
    const int index = static_cast<int>(tri_.size());
    tri_.push_back(tr);
    Bin &b = bins_[k];
    b.triangles.push_back(index);
    for (const auto &v : tr.v_B) {
      b.lo = b.lo.cwiseMin(v);
      b.hi = b.hi.cwiseMax(v);
    }
  }
}

void WheelRasteriser::rasterise(const Eigen::Matrix3d &R, const Eigen::Vector3d &p,
                                double z_cut, double delta, int margin, const TileGrid &grid,
                                StepWindow &window) {
  step_v_W_.clear();
  step_normal_W_.clear();
  // World up seen in B: the height of a body point v_B is p.z + up_B · v_B.
  const Eigen::Vector3d up_B = R.row(2).transpose();
  const double h_cut = z_cut - p.z();
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const Bin &b : bins_) {
    if (b.triangles.empty())
      continue;
    double reach = 0.0; // lowest up_B · v over the bin's box
    for (int k = 0; k < 3; ++k)
      reach += up_B[k] >= 0.0 ? up_B[k] * b.lo[k] : up_B[k] * b.hi[k];
    if (reach >= h_cut)
      continue;
    for (int t : b.triangles) {
      const Triangle &tr = tri_[t];
      if (up_B.dot(tr.n_B) >= 0.0)
        continue; // not facing down: the lowest surface point over a node is on a downward face
      const double h0 = up_B.dot(tr.v_B[0]), h1 = up_B.dot(tr.v_B[1]), h2 = up_B.dot(tr.v_B[2]);
      if (std::min({h0, h1, h2}) >= h_cut)
        continue;
      std::array<Eigen::Vector3d, 3> v;
      for (int k = 0; k < 3; ++k) {
        v[k] = R * tr.v_B[k] + p;
        x_lo = std::min(x_lo, v[k].x());
        x_hi = std::max(x_hi, v[k].x());
        y_lo = std::min(y_lo, v[k].y());
        y_hi = std::max(y_hi, v[k].y());
      }
      step_v_W_.push_back(v);
      step_normal_W_.push_back(R * tr.n_B);
    }
  }
  if (step_v_W_.empty()) {
    window.clear();
    return;
  }
  const std::int64_t i0 = static_cast<std::int64_t>(std::floor(x_lo / delta)) - margin;
  const std::int64_t i1 = static_cast<std::int64_t>(std::ceil(x_hi / delta)) + margin;
  const std::int64_t j0 = static_cast<std::int64_t>(std::floor(y_lo / delta)) - margin;
  const std::int64_t j1 = static_cast<std::int64_t>(std::ceil(y_hi / delta)) + margin;
  window.reset(i0, j0, static_cast<int>(i1 - i0 + 1), static_cast<int>(j1 - j0 + 1), grid);

  // Barycentric coordinates of the node (x, y) in the projected triangle; inclusive edges with a
  // relative tolerance, so a node on a shared edge is never missed (both sides agree on z there).
  constexpr double kEdgeTolerance = 1e-12;
  const int nt = static_cast<int>(step_v_W_.size());
  for (int t = 0; t < nt; ++t) {
    const auto &v = step_v_W_[t];
    const double ax = v[0].x(), ay = v[0].y();
    const double bx = v[1].x() - ax, by = v[1].y() - ay;
    const double cx = v[2].x() - ax, cy = v[2].y() - ay;
    const double det = bx * cy - by * cx;
    if (std::abs(det) <= 1e-14 * (bx * bx + by * by + cx * cx + cy * cy))
      continue; // seen edge-on from above: covers no node area
    const double inv = 1.0 / det;
    const double zb = v[1].z() - v[0].z(), zc = v[2].z() - v[0].z();
    const double tx_lo = std::min({v[0].x(), v[1].x(), v[2].x()});
    const double tx_hi = std::max({v[0].x(), v[1].x(), v[2].x()});
    const double ty_lo = std::min({v[0].y(), v[1].y(), v[2].y()});
    const double ty_hi = std::max({v[0].y(), v[1].y(), v[2].y()});
    const std::int64_t ia = static_cast<std::int64_t>(std::ceil(tx_lo / delta - 1e-9));
    const std::int64_t ib = static_cast<std::int64_t>(std::floor(tx_hi / delta + 1e-9));
    const std::int64_t ja = static_cast<std::int64_t>(std::ceil(ty_lo / delta - 1e-9));
    const std::int64_t jb = static_cast<std::int64_t>(std::floor(ty_hi / delta + 1e-9));
    for (std::int64_t j = ja; j <= jb; ++j) {
      const double qy = j * delta - ay;
      for (std::int64_t i = ia; i <= ib; ++i) {
        const double qx = i * delta - ax;
        const double lb = (qx * cy - qy * cx) * inv;
        const double lc = (bx * qy - by * qx) * inv;
        if (lb < -kEdgeTolerance || lc < -kEdgeTolerance || lb + lc > 1.0 + kEdgeTolerance)
          continue;
        const double z = v[0].z() + lb * zb + lc * zc;
        const int c = window.cell(i, j);
        if (z < window.hit_z[c]) {
          window.hit_z[c] = z;
          window.hit_tri[c] = t;
        }
      }
    }
  }
}

} // namespace wheelsim::scm::detail
