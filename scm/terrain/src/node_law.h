// The SCM node law (TERRAMECHANICS.md §4 steps 2, 4, 5) in Chrono's order: elastic trial,
// unilaterality, shear displacement, Bekker plastic correction, damping, Mohr–Coulomb and
// Janosi–Hanamoto. One node, one step; no grid.
#pragma once

#include "node_state.h"

#include "wheelsim/scm/soil.h"

#include <Eigen/Core>

namespace wheelsim::scm::detail {

/// Soil constants prepared once.
struct NodeLawConstants {
  double n = 1.0, kc = 0.0, kphi = 0.0; ///< Bekker [-], [N/m^(n+1)], [N/m^(n+2)]
  double cohesion = 0.0, tan_phi = 0.0; ///< Mohr–Coulomb [Pa], [-]
  double K = 0.01;                      ///< Janosi shear modulus [m]
  double Ke = 2e8;                      ///< elastic stiffness [Pa/m], max(elastic_K, kφ) as Chrono
  double R = 0.0;                       ///< damping [Pa s/m]
  static NodeLawConstants from(const SoilParameters &soil);
};

/// Elastic trial pressure Ke (z − z_plastic) [Pa] of a node met by the wheel surface at height
/// hit_z [m]: the node is in contact iff this is > 0.
inline double elastic_trial(const NodeState &node, double hit_z_m, double Ke) {
  return Ke * ((node.level_initial - hit_z_m) - node.sinkage_plastic);
}

struct NodeLawResult {
  double sigma = 0.0;                              ///< normal pressure incl. damping [Pa]
  double tau = 0.0;                                ///< shear stress [Pa]
  Eigen::Vector3d t_dir = Eigen::Vector3d::Zero(); ///< shear direction (−v_t / |v_t|, or 0)
  double plastic_flow_m = 0.0; ///< increase of the plastic sinkage this step [m]
};

/// Applies the law to a node in contact (elastic_trial > 0). hit_z: wheel surface height [m];
/// inv_b: 1/b of the node's patch [1/m] (0 for a patch without area, as Chrono); normal: unit
/// direction of the normal pressure on the wheel; v: velocity of the wheel surface point relative
/// to the (resting) soil [m/s] (its normal part damps); v_shear: the slip velocity that shears the
/// soil [m/s] (its part across the normal sets j and τ's direction; v itself unless the shear
/// surface is set apart, ScmSettings::shear_radius_m); dt [s]. Updates the node's level, plastic
/// sinkage, yield, j, σ, τ.
NodeLawResult apply_node_law(NodeState &node, const NodeLawConstants &c, double hit_z_m,
                             double inv_b, const Eigen::Vector3d &normal, const Eigen::Vector3d &v,
                             const Eigen::Vector3d &v_shear, double dt_s);

} // namespace wheelsim::scm::detail
