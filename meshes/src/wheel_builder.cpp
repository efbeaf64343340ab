// Construction (see docs/wheel-mesh.md, "How the mesh is built"):
//  1. Unroll the tread to (theta, y). Cut the width into bands at every lug end and kink and at
//     uniform subdivisions; within a band every lug boundary is a straight line.
//  2. Each level y_j gets one sorted set of angles: all lug boundaries there, theta = 0, and
//     uniform subdivision. Every surface touching the level uses exactly these points, so there
//     are no T-junctions; vertices are keyed by (level, point, radius) and shared exactly.
//  3. In each band the lug boundaries split the circle into trapezoids (lug top at R_out, gap at
//     R_rim); each is zipper-triangulated between its points on the two levels. Radial walls
//     join R_rim and R_out along the lug boundaries; at levels where the radius changes (lug
//     ends, and the side planes) planar end walls close the step.
//  4. The side discs inside R_rim are concentric rings zipped together (no long slivers).
// Triangles are oriented by an outward hint per surface (radial, +-y, or the wall normal).
#include "wheel_builder.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <tuple>

#include <Eigen/Geometry>

#include "lug_layout.h"

namespace wheelsim::meshes {
namespace {

using Eigen::Vector3d;
using geometry::TriangleMesh;

constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kAngleTol = 1e-10; // [rad] angles closer than this are the same point
constexpr double kYTol = 1e-9;      // [m] levels closer than this are the same level

enum class Region { none, gap, lug };

double wrap_angle(double theta) {
  double t = std::fmod(theta, kTwoPi);
  if (t < 0.0)
    t += kTwoPi;
  if (t >= kTwoPi - kAngleTol)
    t = 0.0;
  return t;
}

// Wraps to (-pi, pi].
double wrap_difference(double d) {
  d = std::fmod(d, kTwoPi);
  if (d > 0.5 * kTwoPi)
    d -= kTwoPi;
  if (d <= -0.5 * kTwoPi)
    d += kTwoPi;
  return d;
}

struct Boundary {
  double theta_lo;       // at the lower level, wrapped to [0, 2 pi)
  double theta_hi;       // at the upper level, unwrapped near theta_lo
  bool leading;          // true: the lug is at larger theta (a lug starts here)
  double s_lo_m, s_hi_m; // unwrapped arc positions on the lug top, for the wall normal
};

class Builder {
public:
  explicit Builder(const WheelSpec &spec)
      : spec_(spec), lugs_(lug_layout(spec)), r_out_(spec.outer_radius_m()),
        r_rim_(spec.rim_radius_m()) {}

  TriangleMesh build() {
    make_levels();
    check_clearance();
    make_level_points();
    std::vector<std::vector<Region>> below(levels_.size()), above(levels_.size());
    for (std::size_t j = 0; j < levels_.size(); ++j) {
      below[j].assign(points_[j].size(), Region::none);
      above[j].assign(points_[j].size(), Region::none);
    }
    for (std::size_t j = 0; j + 1 < levels_.size(); ++j) {
      band(j, above[j], below[j + 1]);
    }
    for (std::size_t j = 0; j < levels_.size(); ++j) {
      end_walls(j, below[j], above[j]);
    }
    side_disc(0, -1.0);
    side_disc(levels_.size() - 1, +1.0);
    return std::move(mesh_);
  }

private:
  const WheelSpec &spec_;
  std::vector<LugFootprint> lugs_;
  double r_out_, r_rim_;
  std::vector<double> levels_;              // y [m], increasing
  std::vector<std::vector<double>> points_; // per level: sorted angles [rad] in [0, 2 pi)
  std::map<std::tuple<int, int, int>, int> vertex_ids_;
  TriangleMesh mesh_;

  double theta_of(double s_m) const { return s_m / r_out_; }

  bool lug_at_level(const LugFootprint &l, double y) const {
    return y >= l.y0_m - kYTol && y <= l.y1_m + kYTol;
  }
  bool lug_in_band(const LugFootprint &l, double ya, double yb) const {
    return l.y0_m <= ya + kYTol && l.y1_m >= yb - kYTol;
  }

  void make_levels() {
    const double half_w = 0.5 * spec_.width_m;
    std::vector<double> critical{-half_w, half_w};
    for (const auto &l : lugs_) {
      critical.push_back(l.y0_m);
      critical.push_back(l.y1_m);
      for (double y : l.kinks())
        critical.push_back(y);
    }
    std::sort(critical.begin(), critical.end());
    std::vector<double> unique;
    for (double y : critical) {
      if (y < -half_w - kYTol || y > half_w + kYTol)
        continue;
      if (unique.empty() || y - unique.back() > kYTol)
        unique.push_back(y);
    }
    unique.front() = -half_w;
    unique.back() = half_w;
    for (std::size_t i = 0; i + 1 < unique.size(); ++i) {
      const double dy = unique[i + 1] - unique[i];
      const int n =
          std::max(1, static_cast<int>(std::ceil(dy / spec_.resolution.max_width_edge_m - 1e-9)));
      for (int k = 0; k < n; ++k)
        levels_.push_back(unique[i] + dy * k / n);
    }
    levels_.push_back(half_w);
  }

  // Lugs present at a level must be separated by at least kMinLugClearance_m on the lug top.
  // Boundaries are linear between levels, so checking every level checks everywhere.
  void check_clearance() const {
    if (lugs_.empty())
      return;
    const double circumference = kTwoPi * r_out_;
    for (double y : levels_) {
      std::vector<std::pair<double, double>> spans; // (leading, trailing) [m], leading wrapped
      for (const auto &l : lugs_) {
        if (!lug_at_level(l, y))
          continue;
        const double lead = l.leading(y), trail = l.trailing(y);
        const double lead_w =
            std::fmod(std::fmod(lead, circumference) + circumference, circumference);
        spans.push_back({lead_w, lead_w + (trail - lead)});
      }
      if (spans.empty())
        continue;
      std::sort(spans.begin(), spans.end());
      double total = 0.0;
      for (std::size_t i = 0; i < spans.size(); ++i) {
        total += spans[i].second - spans[i].first;
        const double next_lead =
            i + 1 < spans.size() ? spans[i + 1].first : spans.front().first + circumference;
        const double gap = next_lead - spans[i].second;
        if (gap < kMinLugClearance_m || total > circumference) {
          std::ostringstream os;
          os << "lugs touch or overlap: at y = " << y << " m the clearance between neighbouring "
             << to_string(spec_.type) << " lugs on the lug top is " << gap << " m (< "
             << kMinLugClearance_m << " m) with --lugs " << spec_.lug_count << ", --lug-width "
             << spec_.lug_width_m << " m, --lug-angle " << spec_.lug_angle_deg << " deg";
          if (spec_.type != LugType::straight) {
            os << ", --centre-length " << spec_.centre_length_m << " m";
          }
          os << ", --diameter " << spec_.diameter_m << " m; use fewer or thinner lugs";
          if (spec_.type == LugType::nondirectional) {
            os << " or a shorter --centre-length (the half-lugs are half a pitch apart)";
          }
          throw WheelSpecError(os.str());
        }
      }
    }
  }

  std::vector<double> boundary_angles(double y) const {
    std::vector<double> angles;
    for (const auto &l : lugs_) {
      if (!lug_at_level(l, y))
        continue;
      angles.push_back(wrap_angle(theta_of(l.leading(y))));
      angles.push_back(wrap_angle(theta_of(l.trailing(y))));
    }
    return angles;
  }

  void make_level_points() {
    const double max_step = std::min(spec_.resolution.max_arc_m / r_out_,
                                     spec_.resolution.max_angle_deg * kTwoPi / 360.0);
    for (double y : levels_) {
      std::vector<double> fixed = boundary_angles(y);
      fixed.push_back(0.0);
      std::sort(fixed.begin(), fixed.end());
      std::vector<double> unique;
      for (double t : fixed) {
        if (unique.empty() || t - unique.back() > kAngleTol)
          unique.push_back(t);
      }
      std::vector<double> pts;
      for (std::size_t i = 0; i < unique.size(); ++i) {
        const double a = unique[i];
        const double b = i + 1 < unique.size() ? unique[i + 1] : unique.front() + kTwoPi;
        const int n = std::max(1, static_cast<int>(std::ceil((b - a) / max_step - 1e-9)));
        for (int k = 0; k < n; ++k)
          pts.push_back(a + (b - a) * k / n);
      }
      points_.push_back(std::move(pts));
    }
  }

  // Index of the point of level j at angle theta (which must be one of its points).
  int point_index(std::size_t j, double theta) const {
    const auto &p = points_[j];
    const double t = wrap_angle(theta);
    auto it = std::lower_bound(p.begin(), p.end(), t);
    int best = -1;
    double best_d = HUGE_VAL;
    for (int cand : {static_cast<int>(it - p.begin()) - 1, static_cast<int>(it - p.begin()), 0,
                     static_cast<int>(p.size()) - 1}) {
      if (cand < 0 || cand >= static_cast<int>(p.size()))
        continue;
      const double d = std::abs(wrap_difference(p[cand] - t));
      if (d < best_d)
        best_d = d, best = cand;
    }
    if (best_d > 1e-9)
      throw std::logic_error("wheel_builder: boundary angle not among level points");
    return best;
  }

  int vertex(std::size_t j, int i, bool outer) {
    const auto key = std::make_tuple(static_cast<int>(j), i, outer ? 1 : 0);
    auto it = vertex_ids_.find(key);
    if (it != vertex_ids_.end())
      return it->second;
    const double r = outer ? r_out_ : r_rim_;
    const double th = points_[j][i];
    mesh_.vertices_m.emplace_back(r * std::sin(th), levels_[j], r * std::cos(th));
    const int id = static_cast<int>(mesh_.vertices_m.size()) - 1;
    vertex_ids_.emplace(key, id);
    return id;
  }

  int new_vertex(const Vector3d &p) {
    mesh_.vertices_m.push_back(p);
    return static_cast<int>(mesh_.vertices_m.size()) - 1;
  }

  void triangle(int a, int b, int c, const Vector3d &outward) {
    const auto &v = mesh_.vertices_m;
    const Vector3d n = (v[b] - v[a]).cross(v[c] - v[a]);
    if (n.dot(outward) < 0.0)
      std::swap(b, c);
    mesh_.triangles.push_back({a, b, c});
  }

  void quad(int a, int b, int c, int d, const Vector3d &outward) {
    triangle(a, b, c, outward);
    triangle(a, c, d, outward);
  }

  Vector3d radial_hint(int a, int b, int c) const {
    const auto &v = mesh_.vertices_m;
    Vector3d m = v[a] + v[b] + v[c];
    m.y() = 0.0;
    return m;
  }

  // Triangulates the strip between chains lo and hi (vertex ids with parameters in [0, 1],
  // increasing, both running from the same start side to the same end side).
  void zipper(const std::vector<int> &lo, const std::vector<double> &t_lo,
              const std::vector<int> &hi, const std::vector<double> &t_hi,
              const std::function<Vector3d(int, int, int)> &hint) {
    std::size_t i = 0, k = 0;
    const std::size_t p = lo.size() - 1, q = hi.size() - 1;
    while (i < p || k < q) {
      if (k == q || (i < p && t_lo[i + 1] <= t_hi[k + 1])) {
        triangle(lo[i], lo[i + 1], hi[k], hint(lo[i], lo[i + 1], hi[k]));
        ++i;
      } else {
        triangle(lo[i], hi[k + 1], hi[k], hint(lo[i], hi[k + 1], hi[k]));
        ++k;
      }
    }
  }

  // Points of level j from angle start (wrapped) forward over `span` [rad]: point indices and
  // unwrapped angle offsets from start.
  void chain(std::size_t j, double start, double span, std::vector<int> &idx,
             std::vector<double> &offset) const {
    idx.clear();
    offset.clear();
    const auto &p = points_[j];
    const int n = static_cast<int>(p.size());
    const int s = point_index(j, start);
    for (int step = 0; step <= n; ++step) {
      const int i = (s + step) % n;
      double off = p[i] - p[s] + (s + step >= n ? kTwoPi : 0.0);
      if (step == n)
        off = kTwoPi;
      if (off > span + 1e-9)
        break;
      idx.push_back(i);
      offset.push_back(off);
    }
  }

  void band(std::size_t j, std::vector<Region> &state_lo, std::vector<Region> &state_hi) {
    const double ya = levels_[j], yb = levels_[j + 1];
    std::vector<Boundary> bounds;
    for (const auto &l : lugs_) {
      if (!lug_in_band(l, ya, yb))
        continue;
      for (bool leading : {true, false}) {
        const double sa = leading ? l.leading(ya) : l.trailing(ya);
        const double sb = leading ? l.leading(yb) : l.trailing(yb);
        const double ta = wrap_angle(theta_of(sa));
        const double tb = ta + wrap_difference(wrap_angle(theta_of(sb)) - ta);
        bounds.push_back({ta, tb, leading, sa, sb});
      }
    }
    if (bounds.empty()) {
      bounds.push_back({0.0, 0.0, false, 0.0, 0.0}); // a seam line in an all-gap band
    }
    std::sort(bounds.begin(), bounds.end(),
              [](const Boundary &x, const Boundary &y) { return x.theta_lo < y.theta_lo; });

    const std::size_t nb = bounds.size();
    std::vector<int> ilo, ihi, vlo, vhi;
    std::vector<double> olo, ohi, tlo, thi;
    double sum_hi = 0.0;
    for (std::size_t m = 0; m < nb; ++m) {
      const Boundary &b0 = bounds[m];
      const Boundary &b1 = bounds[(m + 1) % nb];
      const double wrap = (m + 1 == nb) ? kTwoPi : 0.0;
      const double span_lo = b1.theta_lo + wrap - b0.theta_lo;
      const double span_hi = b1.theta_hi + wrap - b0.theta_hi;
      sum_hi += span_hi;
      if (span_hi < -1e-9) {
        std::ostringstream os;
        os << "--max-width-edge " << spec_.resolution.max_width_edge_m
           << " m: lug boundaries cross within a band at y = " << ya
           << " m; use a smaller --max-width-edge";
        throw WheelSpecError(os.str());
      }
      const Region region = b0.leading ? Region::lug : Region::gap;
      const bool outer = region == Region::lug;
      chain(j, b0.theta_lo, span_lo, ilo, olo);
      chain(j + 1, b0.theta_hi, span_hi, ihi, ohi);
      vlo.clear();
      vhi.clear();
      tlo.clear();
      thi.clear();
      for (std::size_t k = 0; k < ilo.size(); ++k) {
        vlo.push_back(vertex(j, ilo[k], outer));
        tlo.push_back(span_lo > 0 ? olo[k] / span_lo : 0.0);
        if (k + 1 < ilo.size())
          state_lo[ilo[k]] = region;
      }
      for (std::size_t k = 0; k < ihi.size(); ++k) {
        vhi.push_back(vertex(j + 1, ihi[k], outer));
        thi.push_back(span_hi > 0 ? ohi[k] / span_hi : 0.0);
        if (k + 1 < ihi.size())
          state_hi[ihi[k]] = region;
      }
      zipper(vlo, tlo, vhi, thi, [this](int a, int b, int c) { return radial_hint(a, b, c); });
    }
    if (std::abs(sum_hi - kTwoPi) > 1e-6) {
      throw std::logic_error("wheel_builder: band regions do not cover the circumference");
    }

    // Radial walls along the lug boundaries.
    for (const Boundary &b : bounds) {
      if (lugs_.empty())
        break;
      const int ia = point_index(j, b.theta_lo), ib = point_index(j + 1, b.theta_hi);
      // Outward in the unrolled (s, y) plane: towards -s on a leading boundary, +s on a trailing.
      const double ds = b.s_hi_m - b.s_lo_m, dy = yb - ya;
      const double ns = b.leading ? -dy : dy, ny = b.leading ? ds : -ds;
      const double th = 0.5 * (b.theta_lo + b.theta_hi);
      const Vector3d e_theta(std::cos(th), 0.0, -std::sin(th));
      const Vector3d hint = ns * e_theta + ny * Vector3d::UnitY();
      quad(vertex(j, ia, false), vertex(j + 1, ib, false), vertex(j + 1, ib, true),
           vertex(j, ia, true), hint);
    }
  }

  // Planar walls in the plane y = levels_[j] where the radius profile steps between R_rim and
  // R_out (lug ends; the lug part of the side planes).
  void end_walls(std::size_t j, const std::vector<Region> &below,
                 const std::vector<Region> &above) {
    const int n = static_cast<int>(points_[j].size());
    for (int i = 0; i < n; ++i) {
      const bool lug_below = below[i] == Region::lug, lug_above = above[i] == Region::lug;
      if (lug_below == lug_above)
        continue;
      const int i1 = (i + 1) % n;
      const Vector3d hint = lug_above ? Vector3d(-Vector3d::UnitY()) : Vector3d(Vector3d::UnitY());
      quad(vertex(j, i, false), vertex(j, i1, false), vertex(j, i1, true), vertex(j, i, true),
           hint);
    }
  }

  // The disc of radius R_rim in the side plane of level j: concentric rings, zipped pairwise.
  void side_disc(std::size_t j, double side) {
    const Vector3d hint = side * Vector3d::UnitY();
    auto flat_hint = [&hint](int, int, int) { return hint; };
    const double y = levels_[j];
    std::vector<int> outer;
    std::vector<double> t_outer;
    for (std::size_t i = 0; i < points_[j].size(); ++i) {
      outer.push_back(vertex(j, static_cast<int>(i), false));
      t_outer.push_back(points_[j][i] / kTwoPi);
    }
    outer.push_back(outer.front());
    t_outer.push_back(1.0);
    const double dr = spec_.resolution.max_width_edge_m;
    const int rings = std::max(1, static_cast<int>(std::ceil(r_rim_ / dr - 1e-9)));
    for (int k = 1; k < rings; ++k) {
      const double r = r_rim_ * (rings - k) / rings;
      const double step = std::min(dr / r, spec_.resolution.max_angle_deg * kTwoPi / 360.0 * 4);
      const int n = std::max(8, static_cast<int>(std::ceil(kTwoPi / step)));
      std::vector<int> inner;
      std::vector<double> t_inner;
      for (int i = 0; i < n; ++i) {
        const double th = kTwoPi * i / n;
        inner.push_back(new_vertex(Vector3d(r * std::sin(th), y, r * std::cos(th))));
        t_inner.push_back(static_cast<double>(i) / n);
      }
      inner.push_back(inner.front());
      t_inner.push_back(1.0);
      zipper(outer, t_outer, inner, t_inner, flat_hint);
      outer = std::move(inner);
      t_outer = std::move(t_inner);
    }
    const int centre = new_vertex(Vector3d(0.0, y, 0.0));
    for (std::size_t i = 0; i + 1 < outer.size(); ++i) {
      triangle(outer[i], outer[i + 1], centre, hint);
    }
  }
};

} // namespace

TriangleMesh build_wheel_mesh(const WheelSpec &spec) {
  validate(spec);
  return Builder(spec).build();
}

} // namespace wheelsim::meshes
