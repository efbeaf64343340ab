// Unit tests of the SCM node law (TERRAMECHANICS.md §1, §4): Bekker loading curve, elastic
// unloading and reloading, Janosi–Hanamoto shear, the Mohr–Coulomb limit, damping.
#include "node_law.h"
#include "scm_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace wheelsim::scm {
namespace {

using detail::apply_node_law;
using detail::elastic_trial;
using detail::NodeLawConstants;
using detail::NodeState;

constexpr double kRel = 1e-12; // the law is closed-form: only round-off may differ

NodeLawConstants lete(double R = 0.0) {
  SoilParameters s = test::lete_sand();
  s.damping_R = R;
  return NodeLawConstants::from(s);
}

double bekker(const NodeLawConstants &c, double z, double inv_b) {
  return (c.kc * inv_b + c.kphi) * std::pow(z, c.n);
}

const Eigen::Vector3d kUp(0, 0, 1);
const Eigen::Vector3d kRest(0, 0, 0);

TEST(NodeLaw, LoadingFollowsBekkerCurve) {
  const NodeLawConstants c = lete();
  const double inv_b = 1.0 / 0.3;
  NodeState n = NodeState::undisturbed(0.0);
  for (int k = 1; k <= 100; ++k) {
    const double z = 1e-3 * k;
    ASSERT_GT(elastic_trial(n, -z, c.Ke), 0.0);
    const auto r = apply_node_law(n, c, -z, inv_b, kUp, kRest, kRest, 1e-3);
    ASSERT_NEAR(r.sigma, bekker(c, z, inv_b), kRel * bekker(c, z, inv_b)) << "z = " << z;
    EXPECT_NEAR(n.sinkage_plastic, z - r.sigma / c.Ke, 1e-15);
    EXPECT_DOUBLE_EQ(n.level, -z);
  }
}

TEST(NodeLaw, ElasticUnloadingAndReloadingKeepPlasticSinkage) {
  const NodeLawConstants c = lete();
  const double inv_b = 2.0;
  NodeState n = NodeState::undisturbed(0.0);
  for (double z = 0.005; z <= 0.05 + 1e-12; z += 0.005)
    apply_node_law(n, c, -z, inv_b, kUp, kRest, kRest, 1e-3);
  const double yield = bekker(c, 0.05, inv_b);
  const double zp = 0.05 - yield / c.Ke;
  ASSERT_NEAR(n.sigma_yield, yield, kRel * yield);
  // Unload by 0.1 mm, then reload to just below the old sinkage: elastic, slope Ke.
  for (double z : {0.0499, 0.04995, 0.04999}) {
    const auto r = apply_node_law(n, c, -z, inv_b, kUp, kRest, kRest, 1e-3);
    EXPECT_NEAR(r.sigma, c.Ke * (z - zp), 1e-9 * yield) << "z = " << z;
    EXPECT_NEAR(n.sinkage_plastic, zp, 1e-15) << "no new plastic sinkage below yield";
    EXPECT_NEAR(n.sigma_yield, yield, kRel * yield);
    EXPECT_EQ(r.plastic_flow_m, 0.0);
  }
  // Unloaded past the plastic sinkage: out of contact.
  EXPECT_LE(elastic_trial(n, -(zp - 1e-6), c.Ke), 0.0);
  // Reloading past the old sinkage rejoins the Bekker curve.
  const auto r = apply_node_law(n, c, -0.06, inv_b, kUp, kRest, kRest, 1e-3);
  EXPECT_NEAR(r.sigma, bekker(c, 0.06, inv_b), kRel * r.sigma);
  EXPECT_GT(r.plastic_flow_m, 0.0);
}

TEST(NodeLaw, JanosiHanamotoShearOnAccumulatedDisplacement) {
  const NodeLawConstants c = lete();
  NodeState n = NodeState::undisturbed(0.0);
  const Eigen::Vector3d v(0.3, -0.4, 0.0); // |v_t| = 0.5 m/s
  const double dt = 1e-3, z = 0.03;
  detail::NodeLawResult r;
  for (int k = 1; k <= 40; ++k) {
    r = apply_node_law(n, c, -z, 0.0, kUp, v, v, dt);
    const double j = 0.5 * dt * k;
    EXPECT_NEAR(n.shear_j, j, 1e-15);
    const double sigma = bekker(c, z, 0.0);
    const double tau = (c.cohesion + sigma * c.tan_phi) * (1.0 - std::exp(-j / c.K));
    ASSERT_NEAR(r.tau, tau, kRel * (c.cohesion + sigma * c.tan_phi)) << "j = " << j;
  }
  EXPECT_NEAR((r.t_dir - Eigen::Vector3d(-0.6, 0.8, 0.0)).norm(), 0.0, 1e-15)
      << "shear opposes the slip velocity";
}

TEST(NodeLaw, ShearSaturatesAtMohrCoulombLimit) {
  const NodeLawConstants c = lete();
  NodeState n = NodeState::undisturbed(0.0);
  const Eigen::Vector3d v(1.0, 0.0, 0.0);
  detail::NodeLawResult r;
  for (int k = 0; k < 100; ++k) // j = 100 × 0.02 m = 167 K: 1 − exp(−167) = 1 in double
    r = apply_node_law(n, c, -0.02, 0.0, kUp, v, v, 0.02);
  const double tau_max = c.cohesion + r.sigma * c.tan_phi;
  EXPECT_NEAR(r.tau, tau_max, kRel * tau_max);
  EXPECT_LE(r.tau, tau_max);
}

TEST(NodeLaw, DampingAddsMinusRTimesNormalVelocity) {
  const double R = 3e4;
  const NodeLawConstants c = lete(R);
  NodeState n = NodeState::undisturbed(0.0);
  const Eigen::Vector3d v(0.0, 0.0, -0.2); // wheel surface moving into the soil
  const auto r = apply_node_law(n, c, -0.02, 0.0, kUp, v, v, 1e-3);
  EXPECT_NEAR(r.sigma, bekker(c, 0.02, 0.0) + 0.2 * R, kRel * r.sigma);
  EXPECT_NEAR(n.sigma_yield, bekker(c, 0.02, 0.0), kRel * r.sigma) << "yield without damping";
}

TEST(NodeLaw, ElasticStiffnessAtLeastKphiAsChrono) {
  SoilParameters s = test::lete_sand();
  s.elastic_K = 1e5;
  EXPECT_EQ(NodeLawConstants::from(s).Ke, s.Bekker_Kphi);
}

TEST(NodeLaw, ShearFromTheShearVelocityDampingFromTheSurfacePoint) {
  // A surface point moving forward and down while the shear surface (e.g. the lug tips) moves
  // backward: the damping takes v's normal part, the shear direction and j v_shear's tangential
  // part (its normal part is ignored).
  const double R = 3e4, dt = 1e-3;
  const NodeLawConstants c = lete(R);
  NodeState n = NodeState::undisturbed(0.0);
  const Eigen::Vector3d v(0.3, 0.0, -0.2), v_shear(-0.1, 0.0, 0.5);
  const auto r = apply_node_law(n, c, -0.02, 0.0, kUp, v, v_shear, dt);
  EXPECT_NEAR(r.sigma, bekker(c, 0.02, 0.0) + 0.2 * R, kRel * r.sigma);
  EXPECT_TRUE(r.t_dir.isApprox(Eigen::Vector3d(1.0, 0.0, 0.0), 1e-15)) << r.t_dir.transpose();
  EXPECT_NEAR(n.shear_j, 0.1 * dt, 1e-15);
}

} // namespace
} // namespace wheelsim::scm
