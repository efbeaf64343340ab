// Reference test (TERRAMECHANICS.md §2): a smooth rigid cylinder lowered quasi-statically
// (displacement-controlled, ω = 0, v_x = 0) onto SCM settles, when the vertical soil force equals
// the load W, at the sinkage of the full-chord Bekker integral
//   W = b ∫_{−a}^{a} (kc/b' + kφ) z(x)^n dx,  z(x) = z0 − (R − sqrt(R² − x²)),  a = sqrt(2 R z0 −
//   z0²),
// solved numerically here. b is the wheel width; b' in kc/b' is SCM's patch width 2A/L of the
// contact rectangle 2a × b (the §2 formula's b' = b is printed for comparison). Tolerance 3 %.
#include "scm_test_util.h"

#include "wheelsim/scm/scm_terrain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <ostream>
#include <string>

namespace wheelsim::scm {
namespace {

constexpr double kR = 0.617, kWidth = 0.479; // smooth_1234 (TERRAMECHANICS.md §7)

// W(z0) of the full chord; patch_b(a) gives b' for the Bekker kc term.
double chord_load(const SoilParameters &s, double z0,
                  const std::function<double(double)> &patch_b) {
  const double a = std::sqrt(2.0 * kR * z0 - z0 * z0);
  const double k = s.Bekker_Kc / patch_b(a) + s.Bekker_Kphi;
  const int n = 20000; // midpoint rule; the integrand vanishes like (a − |x|)^n at the ends
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = -a + (i + 0.5) * 2.0 * a / n;
    const double z = z0 - (kR - std::sqrt(kR * kR - x * x));
    if (z > 0.0)
      sum += std::pow(z, s.Bekker_n);
  }
  return kWidth * k * sum * 2.0 * a / n;
}

double solve_chord_sinkage(const SoilParameters &s, double W,
                           const std::function<double(double)> &patch_b) {
  double lo = 1e-6, hi = 0.5 * kR;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (chord_load(s, mid, patch_b) < W ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Lowers the wheel at 20 mm/s with dt = 1 ms (20 µm per step) until F_z reaches W; returns the
// sinkage of the lowest rim point, interpolated to F_z = W.
double scm_standing_sinkage(const SoilParameters &soil, double W, NormalDirection normal) {
  ScmSettings s;
  s.grid_spacing_m = kWidth / 48.0; // 48 node rows exactly span the width
  s.normal = normal;
  s.bulldozing.enabled = false; // the analytic anchor has no bulldozing
  ScmTerrain t(soil, s, test::make_cylinder(kR, kWidth, 720, 1));
  const double dt = 1e-3, vz = -0.02;
  WheelPose b;
  b.p_WB_W = Eigen::Vector3d(s.grid_spacing_m / 3.0, s.grid_spacing_m / 2.0, kR + 1e-3);
  b.v_WB_W = Eigen::Vector3d(0, 0, vz);
  double f_prev = 0.0, sink_prev = -1e-3;
  for (int step = 0; step < 100000; ++step) {
    const double sink = kR - b.p_WB_W.z();
    const double f = t.advance(b, dt).wrench.f_B_W.z();
    if (f >= W)
      return sink_prev + (W - f_prev) / (f - f_prev) * (sink - sink_prev);
    f_prev = f;
    sink_prev = sink;
    b.p_WB_W.z() += vz * dt;
  }
  ADD_FAILURE() << "load never reached";
  return 0.0;
}

struct Case {
  const char *soil;
  double W;
};

void PrintTo(const Case &c, std::ostream *os) { *os << c.soil << ", W = " << c.W << " N"; }

class StandingSinkage : public ::testing::TestWithParam<Case> {};

TEST_P(StandingSinkage, MatchesFullChordBekkerIntegral) {
  const Case c = GetParam();
  SoilParameters soil = std::string(c.soil) == "lete" ? test::lete_sand() : test::dry_sand();
  soil.damping_R = 0.0; // quasi-static: no rate term
  const double z_scm = scm_standing_sinkage(soil, c.W, NormalDirection::vertical);
  const double z_ref = solve_chord_sinkage(
      soil, c.W, [](double a) { return 2.0 * (2 * a * kWidth) / (2.0 * (2 * a + kWidth)); });
  const double z_ref_b = solve_chord_sinkage(soil, c.W, [](double) { return kWidth; });
  std::printf("  %s, W = %.0f N: SCM %.5f m, chord integral (b' = 2A/L) %.5f m (%+.2f %%), "
              "(b' = b) %.5f m\n",
              soil.name.c_str(), c.W, z_scm, z_ref, 100.0 * (z_scm / z_ref - 1.0), z_ref_b);
  EXPECT_NEAR(z_scm, z_ref, 0.03 * z_ref);
  RecordProperty("sinkage_scm_m", std::to_string(z_scm));
  RecordProperty("sinkage_reference_m", std::to_string(z_ref));
}

INSTANTIATE_TEST_SUITE_P(Soils, StandingSinkage,
                         ::testing::Values(Case{"lete", 13200.0}, Case{"lete", 6600.0},
                                           Case{"dry", 13200.0}, Case{"dry", 6600.0}),
                         [](const auto &info) {
                           return std::string(info.param.soil) + "_" +
                                  std::to_string(static_cast<int>(info.param.W)) + "N";
                         });

TEST(StandingSinkage, SurfaceNormalCloseToVertical) {
  // With the wheel-normal direction only the vertical component of σ n carries W; at these
  // small contact angles it is within 3 % of the full-chord value as well.
  SoilParameters soil = test::lete_sand();
  soil.damping_R = 0.0;
  const double z_scm = scm_standing_sinkage(soil, 13200.0, NormalDirection::surface);
  const double z_ref = solve_chord_sinkage(
      soil, 13200.0, [](double a) { return 2.0 * (2 * a * kWidth) / (2.0 * (2 * a + kWidth)); });
  std::printf("  surface normal: SCM %.5f m, reference %.5f m (%+.2f %%)\n", z_scm, z_ref,
              100.0 * (z_scm / z_ref - 1.0));
  EXPECT_NEAR(z_scm, z_ref, 0.03 * z_ref);
}

} // namespace
} // namespace wheelsim::scm
