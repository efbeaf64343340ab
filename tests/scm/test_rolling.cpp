// Reference tests with a wheel rolled at prescribed kinematics (fixed centre height, 20 % slip):
// soil volume conservation of bulldozing with flow factor 1, and sparse storage.
#include "scm_test_util.h"

#include "wheelsim/scm/scm_terrain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace wheelsim::scm {
namespace {

constexpr double kRollingR = 0.5, kRollingWidth = 0.3;

// Rolls the wheel (centre height R − sinkage) from x0 over `length` at v = 0.5 m/s, 20 % slip.
void roll(ScmTerrain &t, double x0, double length, double sinkage, double dt = 1e-3) {
  const double v = 0.5, omega = v / (kRollingR * (1.0 - 0.2));
  WheelPose b;
  b.v_WB_W = Eigen::Vector3d(v, 0, 0);
  b.w_WB_W = Eigen::Vector3d(0, omega, 0); // +y axle: rolling forward
  const int steps = static_cast<int>(std::lround(length / (v * dt)));
  for (int k = 0; k <= steps; ++k) {
    b.p_WB_W = Eigen::Vector3d(x0 + v * dt * k, 0.0123, kRollingR - sinkage);
    b.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(omega * dt * k, Eigen::Vector3d::UnitY()));
    t.advance(b, dt);
  }
  // Lift out slowly (0.1 mm per step, no motion otherwise) so the soil under the wheel recovers
  // its elastic sinkage (up to 0.1 mm per node) before contact ends, then clear the wheel.
  b.v_WB_W.setZero();
  b.w_WB_W.setZero();
  for (int k = 0; k < 60; ++k) {
    b.p_WB_W.z() += 1e-4;
    t.advance(b, dt);
  }
  b.p_WB_W.z() += 1.0;
  t.advance(b, dt);
}

TEST(Bulldozing, VolumeConservedWithFlowFactorOne) {
  ScmSettings s;
  s.grid_spacing_m = 0.02;
  s.bulldozing.flow_factor = 1.0;
  s.bulldozing.erosion_angle_deg = 40.0;
  s.bulldozing.erosion_iterations = 3;
  s.bulldozing.erosion_rings = 5;
  ScmTerrain t(test::lete_sand(), s, test::make_cylinder(kRollingR, kRollingWidth, 180, 2));
  roll(t, 0.0, 1.5, 0.04);
  const FieldMap sink = t.sample(Field::sinkage);
  double rut = 0.0, pile = 0.0;
  for (double z : sink.values)
    (z > 0.0 ? rut : pile) += std::abs(z) * s.grid_spacing_m * s.grid_spacing_m;
  const double change = t.volume_change_m3();
  std::printf("  rut %.6f m^3, piles %.6f m^3, net change %.3e m^3 (%.3f %% of the rut)\n", rut,
              pile, change, 100.0 * change / rut);
  ASSERT_GT(rut, 0.5 * 1.5 * kRollingWidth * 0.02) << "the wheel made a rut";
  EXPECT_GT(pile, 0.5 * rut) << "bulldozed soil is in the piles";
  EXPECT_LT(std::abs(change), 0.01 * rut) << "volume conserved within 1 % of the rut volume";
}

TEST(Bulldozing, FlowFactorZeroLosesTheRutVolume) {
  // Control for the test above: without flow the rut volume is simply missing.
  ScmSettings s;
  s.bulldozing.flow_factor = 0.0;
  ScmTerrain t(test::lete_sand(), s, test::make_cylinder(kRollingR, kRollingWidth, 180, 2));
  roll(t, 0.0, 0.5, 0.04);
  double rut = 0.0;
  for (double z : t.sample(Field::sinkage).values)
    rut += std::max(z, 0.0) * s.grid_spacing_m * s.grid_spacing_m;
  EXPECT_NEAR(t.volume_change_m3(), -rut, 0.01 * rut);
}

TEST(SparseStorage, StoredNodesGrowWithTouchedLengthOnly) {
  ScmSettings s;
  s.grid_spacing_m = 0.02;
  const auto mesh = test::make_cylinder(kRollingR, kRollingWidth, 120, 1);
  const double tile = 32 * s.grid_spacing_m;
  const double reach = (s.bulldozing.erosion_rings + 2) * s.grid_spacing_m;
  // Upper bound: the tiles of the track's footprint (wheel chord + erosion reach), one extra tile
  // row/column each way for tile alignment.
  auto bound = [&](double length) {
    const double nx = std::ceil((length + 2 * kRollingR + 2 * reach) / tile) + 1;
    const double ny = std::ceil((kRollingWidth + 2 * reach) / tile) + 1;
    return static_cast<std::size_t>(nx * ny * 32 * 32);
  };
  std::size_t stored[2];
  const double lengths[2] = {2.0, 8.0};
  for (int k = 0; k < 2; ++k) {
    ScmTerrain t(test::lete_sand(), s, mesh);
    roll(t, 0.0, lengths[k], 0.03, 4e-3);
    stored[k] = t.stored_nodes();
    EXPECT_LE(stored[k], bound(lengths[k])) << "track " << lengths[k] << " m";
    std::printf("  track %.0f m: %zu stored nodes (bound %zu)\n", lengths[k], stored[k],
                bound(lengths[k]));
  }
  // Per metre of track, growth is the footprint width only.
  const double per_m = double(stored[1] - stored[0]) / (lengths[1] - lengths[0]);
  EXPECT_LE(per_m, (std::ceil((kRollingWidth + 2 * reach) / tile) + 1) * 32 * 32 / tile);
  // Far from the origin costs the same.
  ScmTerrain far(test::lete_sand(), s, mesh);
  roll(far, 1000.0, lengths[0], 0.03, 4e-3);
  EXPECT_LE(far.stored_nodes(), stored[0] + 2 * 32 * 32 * 2);
  EXPECT_GE(far.stored_nodes() + 2 * 32 * 32 * 2, stored[0]);
}

} // namespace
} // namespace wheelsim::scm
