// Bulldozing and erosion (see bulldozing.h).
#include "bulldozing.h"

#include <algorithm>
#include <cmath>

namespace wheelsim::scm::detail {

namespace {

// Raises the node by `amount`, but not into the wheel (hit_z): the rest waits as remainder.
// Like Chrono, the reference level of the sinkage moves with the soil.
void add_soil(NodeState &n, double amount, double hit_z, double &max_level) {
  const double room = std::max(0.0, hit_z - n.level);
  const double placed = std::min(amount, room);
  n.remainder += amount - placed;
  n.level += placed;
  n.level_initial += placed;
  max_level = std::max(max_level, n.level_initial - n.sinkage_plastic);
}

// Takes `amount` from the node: from its remainder first, then from its level.
void remove_soil(NodeState &n, double amount) {
  const double from_remainder = std::min(n.remainder, amount);
  n.remainder -= from_remainder;
  const double rest = amount - from_remainder;
  n.level -= rest;
  n.level_initial -= rest;
}

} // namespace

int bulldoze(StepWindow &w, TileGrid &grid, const std::vector<ContactPatch> &patches,
             const std::vector<double> &plastic_flow, const BulldozingConstants &c,
             const Eigen::Vector4d *domain_m, double delta, double &max_level) {
  const int nx = w.nx(), size = w.size();
  auto neighbours = [&](int cell, int out[4]) {
    const int ci = cell % nx;
    out[0] = ci > 0 ? cell - 1 : -1;
    out[1] = ci + 1 < nx ? cell + 1 : -1;
    out[2] = cell - nx >= 0 ? cell - nx : -1;
    out[3] = cell + nx < size ? cell + nx : -1;
  };
  auto is_soil = [&](int cell) {
    if (!domain_m)
      return true;
    const double x = w.i_of(cell) * delta, y = w.j_of(cell) * delta;
    const Eigen::Vector4d &d = *domain_m;
    return x >= d[0] && x <= d[1] && y >= d[2] && y <= d[3];
  };

  // (1) Spread each patch's plastic flow over its boundary.
  std::vector<int> domain; // boundary first, then the rings, in discovery order
  std::vector<int> stamp(size, -1);
  std::vector<int> boundary;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    boundary.clear();
    double flow = 0.0;
    for (int cell : patches[p].cells) {
      flow += plastic_flow[cell];
      int nb[4];
      neighbours(cell, nb);
      for (int b : nb) {
        if (b < 0 || (w.flags[b] & kContact) || stamp[b] == static_cast<int>(p) || !is_soil(b))
          continue;
        stamp[b] = static_cast<int>(p);
        boundary.push_back(b);
      }
    }
    if (boundary.empty())
      continue;
    const double raise = c.flow_factor * flow / static_cast<double>(boundary.size());
    for (int b : boundary) {
      add_soil(w.node(b, grid), raise, w.hit_z[b], max_level);
      if (!(w.flags[b] & kBoundary)) {
        w.flags[b] |= kBoundary | kErosion;
        domain.push_back(b);
      }
    }
  }

  // (2) Erosion domain: dilate the boundary by rings − 1 rings of non-contact nodes.
  std::size_t front_begin = 0;
  for (int ring = 1; ring < c.rings; ++ring) {
    const std::size_t front_end = domain.size();
    for (std::size_t k = front_begin; k < front_end; ++k) {
      int nb[4];
      neighbours(domain[k], nb);
      for (int b : nb) {
        if (b < 0 || (w.flags[b] & (kContact | kErosion)) || !is_soil(b))
          continue;
        w.flags[b] |= kErosion;
        domain.push_back(b);
      }
    }
    front_begin = front_end;
  }

  // (3) Erosion sweeps.
  for (int it = 0; it < c.iterations; ++it) {
    for (int cell : domain) {
      NodeState &a = w.node(cell, grid);
      int nb[4];
      neighbours(cell, nb);
      for (int b : nb) {
        if (b < 0 || !is_soil(b))
          continue;
        NodeState &o = w.node(b, grid);
        // Remainder flows down its own gradient.
        double diff = 0.5 * (a.remainder - o.remainder) / 4.0;
        if (diff > 0.0) {
          remove_soil(a, diff);
          add_soil(o, diff, w.hit_z[b], max_level);
        }
        // Slopes steeper than the angle of repose are relaxed (not against the wheel).
        if (w.flags[b] & kContact)
          continue;
        const double dy = (a.level + a.remainder) - (o.level + o.remainder);
        diff = 0.5 * (std::abs(dy) - c.max_step_m) / 4.0;
        if (diff > 0.0) {
          if (dy > 0.0) {
            remove_soil(a, diff);
            add_soil(o, diff, w.hit_z[b], max_level);
          } else {
            remove_soil(o, diff);
            add_soil(a, diff, w.hit_z[cell], max_level);
          }
        }
      }
    }
  }
  return static_cast<int>(domain.size());
}

} // namespace wheelsim::scm::detail
