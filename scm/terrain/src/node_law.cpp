// The SCM node law (see node_law.h and the list of choices in scm_terrain.cpp).
#include "node_law.h"

#include <algorithm>
#include <cmath>

namespace wheelsim::scm::detail {

NodeLawConstants NodeLawConstants::from(const SoilParameters &soil) {
  NodeLawConstants c;
  c.n = soil.Bekker_n;
  c.kc = soil.Bekker_Kc;
  c.kphi = soil.Bekker_Kphi;
  c.cohesion = soil.Mohr_cohesion;
  c.tan_phi = std::tan(soil.Mohr_friction);
  c.K = soil.Janosi_shear;
  c.Ke = std::max(soil.elastic_K, soil.Bekker_Kphi);
  c.R = soil.damping_R;
  return c;
}

NodeLawResult apply_node_law(NodeState &node, const NodeLawConstants &c, double hit_z, double inv_b,
                             const Eigen::Vector3d &normal, const Eigen::Vector3d &v,
                             const Eigen::Vector3d &v_shear, double dt) {
  NodeLawResult r;
  const double z = node.level_initial - hit_z; // total sinkage
  double sigma = c.Ke * (z - node.sinkage_plastic);
  if (!(sigma > 0.0))
    return r; // unilateral: callers only pass nodes in contact

  // Normal velocity of the surface point (damping); slip velocity across the normal (shear).
  const double vn = v.dot(normal);
  const Eigen::Vector3d vt = v_shear - v_shear.dot(normal) * normal;
  const double vt_norm = vt.norm();
  if (vt_norm > 0.0)
    r.t_dir = -vt / vt_norm;

  node.level = hit_z;
  node.shear_j += vt_norm * dt;

  if (sigma > node.sigma_yield) { // plastic: back onto the Bekker curve
    sigma = (c.kc * inv_b + c.kphi) * std::pow(z, c.n);
    node.sigma_yield = sigma;
    const double old = node.sinkage_plastic;
    node.sinkage_plastic = z - sigma / c.Ke;
    r.plastic_flow_m = node.sinkage_plastic - old;
  }
  sigma += -vn * c.R; // damping, not clamped (as Chrono)

  const double tau_max = c.cohesion + sigma * c.tan_phi;
  const double tau = tau_max * (1.0 - std::exp(-node.shear_j / c.K));
  node.sigma = sigma;
  node.tau = tau;
  r.sigma = sigma;
  r.tau = tau;
  return r;
}

} // namespace wheelsim::scm::detail
