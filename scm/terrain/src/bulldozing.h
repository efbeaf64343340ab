// Bulldozing with erosion (TERRAMECHANICS.md §4 step 6), Chrono's heuristic: the plastic flow of
// each contact patch (sum of its nodes' plastic sinkage increments) × flow_factor is spread evenly
// over the patch boundary (non-contact 4-neighbours of its nodes), then the erosion domain (the
// boundary dilated by erosion_rings − 1 rings of non-contact nodes) is swept erosion_iterations
// times: soil that could not be placed ("remainder": the wheel is in the way) flows on, and any
// step between neighbours steeper than the angle of repose is halved towards it. Every transfer
// removes from one node exactly what it adds to another, so soil volume is conserved.
#pragma once

#include "contact_patches.h"

#include <Eigen/Core>
#include <vector>

namespace wheelsim::scm::detail {

struct BulldozingConstants {
  double flow_factor = 1.0;
  double max_step_m = 0.0; ///< Δ tan(angle of repose): largest level step between neighbours
  int iterations = 3;
  int rings = 5;
};

/// plastic_flow[c]: plastic sinkage increment of contact cell c this step [m]. domain_m: soil
/// bounds (x_min, x_max, y_min, y_max) [m] or nullptr; delta_m: grid spacing. max_level: running
/// upper bound of node levels, raised as soil piles up. Returns the erosion domain's node count.
int bulldoze(StepWindow &window, TileGrid &grid, const std::vector<ContactPatch> &patches,
             const std::vector<double> &plastic_flow, const BulldozingConstants &c,
             const Eigen::Vector4d *domain_m, double delta_m, double &max_level);

} // namespace wheelsim::scm::detail
