// Bekker rigid-wheel closed forms (TERRAMECHANICS.md §2) against their definitions and an
// independent trapezoid quadrature in x.
#include "wheelsim/scm/bekker_closed_forms.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

namespace {

using namespace wheelsim::scm;
using namespace wr_test;

const char *kSoils[] = {"dry_sand",       "sandy_loam",           "sand_loam",
                        "lete_sand",      "upland_sandy_loam",    "north_gower_clayey_loam",
                        "grenville_loam", "clayey_soil_thailand", "lean_clay_wes",
                        "lunar_soil"};

/// b ∫_{x0}^{a} (kc/b + kφ) z(x)^n dx by the trapezoid rule on `steps` equal steps (x0 = −a for
/// the full chord, 0 for the front half). Independent of the library's angle substitution.
double trapezoid_load(const SoilParameters &s, double R, double b, double z0, bool full_chord,
                      int steps) {
  const double a = std::sqrt(2 * R * z0 - z0 * z0);
  const double x0 = full_chord ? -a : 0.0;
  const double h = (a - x0) / steps;
  auto p = [&](double x) {
    const double z = z0 - (R - std::sqrt(R * R - x * x));
    return z > 0 ? (s.Bekker_Kc / b + s.Bekker_Kphi) * std::pow(z, s.Bekker_n) : 0.0;
  };
  double sum = 0.5 * (p(x0) + p(a));
  for (int i = 1; i < steps; ++i)
    sum += p(x0 + i * h);
  return b * sum * h;
}

TEST(BekkerClosedForms, RollingClosedFormReproducesItsDefinition) {
  for (const char *name : kSoils) {
    SCOPED_TRACE(name);
    const SoilParameters s = soil(name);
    for (double W : {1000.0, 5000.0, 13200.0, 25300.0}) {
      const double z0 = rolling_sinkage_closed_form_m(s, kRadius, kWidth, W);
      // W = (3 − n)(kc + b kφ) sqrt(D) z0^((2n+1)/2) / 3, written out here again.
      const double n = s.Bekker_n;
      const double W_back = (3 - n) * (s.Bekker_Kc + kWidth * s.Bekker_Kphi) *
                            std::sqrt(2 * kRadius) * std::pow(z0, (2 * n + 1) / 2) / 3;
      EXPECT_NEAR(W_back / W, 1.0, 1e-12);
      EXPECT_NEAR(rolling_closed_form_load_N(s, kRadius, kWidth, z0) / W, 1.0, 1e-12);
    }
  }
}

TEST(BekkerClosedForms, LoadIntegralsMatchAnIndependentTrapezoid) {
  // 2e6 trapezoid steps in x: the end singularity (a − x)^n limits the rule to O(h^(1+n)); the
  // smallest n here is 0.2 (lean clay), so the tolerance is 2e-6 relative.
  for (const char *name : kSoils) {
    SCOPED_TRACE(name);
    const SoilParameters s = soil(name);
    for (double z0 : {0.005, 0.03, 0.12}) {
      const double front = trapezoid_load(s, kRadius, kWidth, z0, false, 2000000);
      EXPECT_NEAR(rolling_load_N(s, kRadius, kWidth, z0) / front, 1.0, 2e-6) << z0;
      EXPECT_NEAR(standing_load_N(s, kRadius, kWidth, z0) /
                      trapezoid_load(s, kRadius, kWidth, z0, true, 2000000),
                  1.0, 2e-6)
          << z0;
    }
  }
}

TEST(BekkerClosedForms, StandingSinkageMatchesBisectionOnTheTrapezoid) {
  for (const char *name : {"lete_sand", "dry_sand", "clayey_soil_thailand"}) {
    SCOPED_TRACE(name);
    const SoilParameters s = soil(name);
    double lo = 0, hi = kRadius;
    for (int i = 0; i < 50; ++i) {
      const double mid = 0.5 * (lo + hi);
      (trapezoid_load(s, kRadius, kWidth, mid, true, 200000) < kLoad ? lo : hi) = mid;
    }
    const double z_ref = 0.5 * (lo + hi);
    const double z = standing_sinkage_m(s, kRadius, kWidth, kLoad);
    EXPECT_NEAR(z / z_ref, 1.0, 1e-6);
    // The root itself is converged to 1e-12 relative on the library's own integral.
    EXPECT_NEAR(standing_load_N(s, kRadius, kWidth, z) / kLoad, 1.0, 1e-11);
    const double zr = rolling_sinkage_integral_m(s, kRadius, kWidth, kLoad);
    EXPECT_NEAR(rolling_load_N(s, kRadius, kWidth, zr) / kLoad, 1.0, 1e-11);
  }
}

TEST(BekkerClosedForms, StandingSinksAbout40PercentLessThanRollingOnLeteSand) {
  const SoilParameters s = soil("lete_sand");
  const double standing = standing_sinkage_m(s, kRadius, kWidth, kLoad);
  const double rolling = rolling_sinkage_integral_m(s, kRadius, kWidth, kLoad);
  const double closed = rolling_sinkage_closed_form_m(s, kRadius, kWidth, kLoad);
  const double less = 1.0 - standing / rolling;
  std::printf("LETE sand, 13.2 kN, R 0.617 m, b 0.479 m: standing %.3f mm, rolling (front-half "
              "integral) %.3f mm, rolling closed form %.3f mm; standing %.1f %% less than "
              "rolling\n",
              standing * 1e3, rolling * 1e3, closed * 1e3, 100 * less);
  EXPECT_GT(less, 0.35);
  EXPECT_LT(less, 0.45);
  // The closed form is a series approximation of the front-half integral, a few % low.
  EXPECT_LT(closed, rolling);
  EXPECT_GT(closed, 0.95 * rolling);
}

TEST(BekkerClosedForms, StandingSinksLessThanRollingOnEverySoil) {
  for (const char *name : kSoils) {
    const SoilParameters s = soil(name);
    EXPECT_LT(standing_sinkage_m(s, kRadius, kWidth, kLoad),
              rolling_sinkage_integral_m(s, kRadius, kWidth, kLoad))
        << name;
  }
}

TEST(BekkerClosedForms, CompactionResistanceIsTheWorkOfMakingTheRut) {
  // Rc = ∫_0^z0 b (kc/b + kφ) z^n dz (Bekker), checked by the trapezoid rule.
  const SoilParameters s = soil("lete_sand");
  const double z0 = 0.03;
  const int steps = 1000000;
  double sum = 0;
  for (int i = 1; i <= steps; ++i) {
    const double z = z0 * i / steps;
    sum += (i == steps ? 0.5 : 1.0) * kWidth * s.bekker_pressure(z, kWidth);
  }
  EXPECT_NEAR(compaction_resistance_N(s, kWidth, z0) / (sum * z0 / steps), 1.0, 1e-6);
}

TEST(BekkerClosedForms, LoadsTheSoilCannotCarryAndBadArgumentsThrow) {
  const SoilParameters s = soil("dry_sand");
  EXPECT_THROW(standing_sinkage_m(s, kRadius, kWidth, 1e8), TerramechanicsError);
  try {
    rolling_sinkage_integral_m(s, kRadius, kWidth, 1e8);
    FAIL();
  } catch (const TerramechanicsError &e) {
    EXPECT_NE(std::string(e.what()).find("cannot carry 100000000 N"), std::string::npos)
        << e.what();
  }
  try {
    standing_sinkage_m(s, -1, kWidth, kLoad);
    FAIL();
  } catch (const std::invalid_argument &e) {
    EXPECT_EQ(std::string(e.what()), "standing_sinkage_m: radius must be > 0 m, got -1");
  }
  EXPECT_THROW(rolling_sinkage_closed_form_m(s, kRadius, kWidth, 0), std::invalid_argument);
  EXPECT_THROW(rolling_load_N(s, kRadius, kWidth, 2 * kRadius), std::invalid_argument);
}

} // namespace
