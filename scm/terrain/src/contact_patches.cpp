// Flood fill of contact nodes and b = 2A/L per patch (see contact_patches.h).
#include "contact_patches.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

namespace wheelsim::scm::detail {

namespace {
double cross(const Eigen::Vector2d &o, const Eigen::Vector2d &a, const Eigen::Vector2d &b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}
} // namespace

void convex_hull_area_perimeter(std::vector<Eigen::Vector2d> pts, double &area, double &perimeter) {
  area = 0.0;
  perimeter = 0.0;
  std::sort(pts.begin(), pts.end(), [](const Eigen::Vector2d &a, const Eigen::Vector2d &b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  const int n = static_cast<int>(pts.size());
  if (n < 2)
    return;
  // Andrew's monotone chain.
  std::vector<Eigen::Vector2d> hull(2 * n);
  int k = 0;
  for (int i = 0; i < n; ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0.0)
      --k;
    hull[k++] = pts[i];
  }
  for (int i = n - 2, lower = k + 1; i >= 0; --i) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0.0)
      --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1); // last point repeats the first
  const int m = static_cast<int>(hull.size());
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector2d &a = hull[i], &b = hull[(i + 1) % m];
    area += a.x() * b.y() - b.x() * a.y();
    perimeter += (b - a).norm();
  }
  area = 0.5 * std::abs(area);
}

void find_contact_patches(StepWindow &w, const std::vector<int> &contact_cells, double delta,
                          std::vector<ContactPatch> &patches) {
  patches.clear();
  const int nx = w.nx();
  std::vector<int> queue;
  std::vector<Eigen::Vector2d> extremes;
  for (int seed : contact_cells) {
    if (w.patch[seed] != -1)
      continue;
    const int id = static_cast<int>(patches.size());
    patches.emplace_back();
    ContactPatch &p = patches.back();
    queue.assign(1, seed);
    w.patch[seed] = id;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int c = queue[q];
      const int ci = c % nx;
      const int nbr[4] = {ci > 0 ? c - 1 : -1, ci + 1 < nx ? c + 1 : -1, c - nx, c + nx};
      for (int nb : nbr) {
        if (nb < 0 || nb >= w.size() || !(w.flags[nb] & kContact) || w.patch[nb] != -1)
          continue;
        w.patch[nb] = id;
        queue.push_back(nb);
      }
    }
    p.cells = queue;
    // The hull only needs the two extreme nodes of each grid row.
    int r_lo = std::numeric_limits<int>::max(), r_hi = -1;
    for (int c : p.cells) {
      r_lo = std::min(r_lo, c / nx);
      r_hi = std::max(r_hi, c / nx);
    }
    std::vector<int> lo(r_hi - r_lo + 1, std::numeric_limits<int>::max()), hi(lo.size(), -1);
    for (int c : p.cells) {
      const int r = c / nx - r_lo;
      lo[r] = std::min(lo[r], c % nx);
      hi[r] = std::max(hi[r], c % nx);
    }
    extremes.clear();
    for (std::size_t r = 0; r < lo.size(); ++r) {
      if (hi[r] < 0)
        continue;
      const double y = static_cast<double>(w.j0() + r_lo + static_cast<int>(r)) * delta;
      extremes.emplace_back(static_cast<double>(w.i0() + lo[r]) * delta, y);
      extremes.emplace_back(static_cast<double>(w.i0() + hi[r]) * delta, y);
    }
    convex_hull_area_perimeter(extremes, p.area_m2, p.perimeter_m);
    p.inv_b = p.area_m2 < 1e-6 ? 0.0 : p.perimeter_m / (2.0 * p.area_m2);
  }
}

} // namespace wheelsim::scm::detail
