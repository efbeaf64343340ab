// The state one SCM grid node keeps between steps (TERRAMECHANICS.md §4, "state per grid node").
#pragma once

namespace wheelsim::scm::detail {

/// One grid node. Levels are world z [m]. A node that was never touched is implicit and equals
/// NodeState::undisturbed(surface).
struct NodeState {
  double level = 0.0;           ///< current surface level [m]
  double level_initial = 0.0;   ///< reference level of the sinkage [m] (moves with bulldozed soil)
  double sinkage_plastic = 0.0; ///< permanent sinkage below level_initial [m]
  double sigma_yield = 0.0;     ///< highest Bekker pressure reached [Pa]
  double shear_j = 0.0;         ///< accumulated shear displacement j [m] (never reset, as Chrono)
  double sigma = 0.0;           ///< normal pressure of the last step [Pa] (0 off contact)
  double tau = 0.0;             ///< shear stress of the last step [Pa] (0 off contact)
  double remainder = 0.0;       ///< bulldozed soil waiting to flow on [m of height]

  static NodeState undisturbed(double surface_m) {
    NodeState n;
    n.level = surface_m;
    n.level_initial = surface_m;
    return n;
  }
};

} // namespace wheelsim::scm::detail
