// Unit tests of the particle–wheel contact law against analytic values and LIGGGHTS' formulas.
// Golden numbers come from tests/contact/golden_values.py (an independent transcription of the
// LIGGGHTS 3.8 formulas; run it to regenerate them).
#include "contact_law.h"
#include "contact_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace wc = wheelsim::contact;
using Eigen::Vector3d;

namespace {

const wc::Material kParticle{5.0e7, 0.3};
const wc::Material kWheel{2.0e11, 0.3};
constexpr double kR = 2.0e-3; // particle radius [m]
constexpr double kM = 8.0e-5; // particle mass [kg]

wc::PairConstants constants(const wc::PairMaterial &pair, const wc::ContactSettings &settings) {
  return wc::makePairConstants(kParticle, kWheel, pair, settings);
}

wc::PairConstants hertz(double e = 0.5, double mu = 0.5, bool tangentialDamping = true) {
  wc::PairMaterial pair;
  pair.coefficientRestitution = e;
  pair.coefficientFriction = mu;
  wc::ContactSettings settings;
  settings.tangentialDamping = tangentialDamping;
  return constants(pair, settings);
}

wc::ContactState state(double overlap, const Vector3d &vRel = Vector3d::Zero(),
                       const Vector3d &normal = Vector3d::UnitZ()) {
  wc::ContactState s;
  s.radius = kR;
  s.mass = kM;
  s.overlap = overlap;
  s.normal = normal;
  s.vRel = vRel;
  return s;
}

double relErr(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

// ---------------------------------------------------------------------------------------------
TEST(PairConstants, EffectiveModuliAndBetaFollowLiggghts) {
  const auto pc = hertz(0.5);
  const double yeff = 1.0 / ((1 - 0.09) / 5.0e7 + (1 - 0.09) / 2.0e11);
  const double geff = 1.0 / (2 * 1.7 * 1.3 / 5.0e7 + 2 * 1.7 * 1.3 / 2.0e11);
  EXPECT_NEAR(relErr(pc.Yeff, yeff), 0.0, 1e-14);
  EXPECT_NEAR(relErr(pc.Geff, geff), 0.0, 1e-14);
  EXPECT_NEAR(
      relErr(pc.betaeff, std::log(0.5) / std::sqrt(std::log(0.5) * std::log(0.5) + M_PI * M_PI)),
      0.0, 1e-14);
  EXPECT_FALSE(pc.limitForce); // hertz default
  wc::ContactSettings eepa;
  eepa.normal = wc::NormalModel::Eepa;
  wc::PairMaterial pair;
  pair.UnloadingStiffness = 5.0;
  EXPECT_TRUE(constants(pair, eepa).limitForce); // edinburgh default
}

TEST(PairConstants, RejectsOutOfRangeValuesNamingThem) {
  wc::PairMaterial pair;
  pair.coefficientRestitution = 0.01;
  try {
    constants(pair, {});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument &err) {
    EXPECT_NE(std::string(err.what()).find("coefficientRestitution"), std::string::npos);
  }
  EXPECT_THROW(wc::makePairConstants({-1.0, 0.3}, kWheel, {}, {}), std::invalid_argument);
  EXPECT_THROW(wc::makePairConstants(kParticle, {2e11, 0.7}, {}, {}), std::invalid_argument);
  wc::ContactSettings eepa;
  eepa.normal = wc::NormalModel::Eepa;
  wc::PairMaterial bad;
  bad.UnloadingStiffness = 0.5; // k2 < k1
  EXPECT_THROW(constants(bad, eepa), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
TEST(Hertz, StaticForceIsFourThirdsYeffSqrtRDeltaToTheThreeHalves) {
  const auto pc = hertz();
  for (double delta : {1e-7, 1e-6, 1e-5, 1e-4}) {
    wc::ContactHistory h{};
    const auto r = wc::evaluate(pc, state(delta), 1e-6, true, h);
    const double expected = 4.0 / 3.0 * pc.Yeff * std::sqrt(kR) * std::pow(delta, 1.5);
    EXPECT_NEAR(r.force.z(), expected, 1e-12 * expected) << "delta = " << delta;
    EXPECT_EQ(r.force.x(), 0.0);
    EXPECT_EQ(r.force.y(), 0.0);
  }
}

/// One particle dropped on a flat face, integrated like LIGGGHTS' fix nve/sphere (velocity
/// Verlet: half kick, drift, force, half kick); returns -v_out/v_in.
double measuredRestitution(const wc::PairConstants &pc, double vIn) {
  const double dt = 2.0e-8;
  double z = kR; // centre height above the face: touching
  double v = -vIn;
  double f = 0.0;
  wc::ContactHistory h{};
  bool touched = false;
  for (int step = 0; step < 10000000; ++step) {
    v += 0.5 * dt * f / kM;
    z += dt * v;
    const double delta = kR - z;
    if (delta > 0.0) {
      touched = true;
      f = wc::evaluate(pc, state(delta, Vector3d(0, 0, v)), dt, true, h).force.z();
    } else {
      f = 0.0;
      h.reset();
    }
    v += 0.5 * dt * f / kM;
    if (touched && delta <= 0.0)
      return v / vIn;
  }
  ADD_FAILURE() << "the particle never left the face";
  return 0.0;
}

TEST(Hertz, MeasuredRestitutionMatchesTheSetValue) {
  for (double e : {0.3, 0.5, 0.9}) {
    const double eMeasured = measuredRestitution(hertz(e), 1.0);
    EXPECT_NEAR(eMeasured, e, 0.02 * e) << "set e = " << e;
  }
}

TEST(Hertz, LimitForceClampsTheAttractiveDampingForce) {
  wc::PairMaterial pair;
  wc::ContactSettings settings;
  wc::ContactHistory h{};
  // Separating fast at a small overlap: damping exceeds the spring, Fn < 0.
  const auto s = state(1e-8, Vector3d(0, 0, 1.0));
  EXPECT_LT(wc::evaluate(constants(pair, settings), s, 1e-6, true, h).force.z(), 0.0);
  settings.limitForce = wc::Switch::On;
  h.reset();
  EXPECT_EQ(wc::evaluate(constants(pair, settings), s, 1e-6, true, h).force.z(), 0.0);
}

// ---------------------------------------------------------------------------------------------
TEST(Tangential, BelowTheCapTheSpringForceIsKtTimesDisplacement) {
  const auto pc = hertz(0.5, 0.5, /*tangentialDamping=*/true);
  const double delta = 1e-5, dt = 1e-6;
  wc::ContactHistory h{};
  wc::evaluate(pc, state(delta, Vector3d(0.01, -0.02, 0)), dt, true, h); // builds displacement
  EXPECT_NEAR(h.shear[0], 0.01 * dt, 1e-20);
  EXPECT_NEAR(h.shear[1], -0.02 * dt, 1e-20);
  // Hold still: no damping, pure spring.
  const auto r = wc::evaluate(pc, state(delta), dt, true, h);
  const double kt = 8.0 * pc.Geff * std::sqrt(kR * delta);
  EXPECT_FALSE(r.sliding);
  EXPECT_NEAR(r.force.x(), -kt * 0.01 * dt, 1e-12 * kt * 0.01 * dt);
  EXPECT_NEAR(r.force.y(), kt * 0.02 * dt, 1e-12 * kt * 0.02 * dt);
}

TEST(Tangential, SlidingSitsOnTheCoulombCap) {
  const double mu = 0.4, delta = 1e-5, dt = 1e-6;
  const auto pc = hertz(0.5, mu, /*tangentialDamping=*/false);
  wc::ContactHistory h{};
  const Vector3d v(0.05, 0.02, 0.0);
  bool slid = false;
  for (int i = 0; i < 2000; ++i) {
    const auto r = wc::evaluate(pc, state(delta, v), dt, true, h);
    const double ft = std::hypot(r.force.x(), r.force.y());
    const double cap = mu * std::fabs(r.normalForce);
    EXPECT_LE(ft, cap * (1 + 1e-12)) << "step " << i;
    if (r.sliding) {
      slid = true;
      EXPECT_NEAR(ft, cap, 1e-12 * cap);
      // opposes the slip direction
      EXPECT_NEAR(r.force.x() * v.y() - r.force.y() * v.x(), 0.0, 1e-12 * cap * v.norm());
      EXPECT_LT(r.force.x() * v.x() + r.force.y() * v.y(), 0.0);
      // the spring was rescaled to the cap: |kt s| = μ|Fn|
      const double kt = 8.0 * pc.Geff * std::sqrt(kR * delta);
      EXPECT_NEAR(kt * std::hypot(h.shear[0], h.shear[1]), cap, 1e-12 * cap);
    }
  }
  EXPECT_TRUE(slid);
}

TEST(Tangential, DampingIsAddedOnlyWhileStickingAsInLiggghts) {
  const double mu = 0.4, delta = 1e-5, dt = 1e-6;
  const auto pc = hertz(0.5, mu, /*tangentialDamping=*/true);
  wc::ContactHistory h{};
  const Vector3d v(0.05, 0.0, 0.0);
  const auto r = wc::evaluate(pc, state(delta, v), dt, true, h); // sticking
  const double kt = 8.0 * pc.Geff * std::sqrt(kR * delta);
  const double gammat = -2.0 * std::sqrt(5.0 / 6.0) * pc.betaeff * std::sqrt(kt * kM);
  EXPECT_NEAR(r.force.x(), -kt * v.x() * dt - gammat * v.x(), 1e-12 * gammat * v.x());
}

TEST(Tangential, HistoryIsProjectedIntoTheTangentPlaneWhenTheNormalRotates) {
  const auto pc = hertz(0.5, 10.0); // high μ: stays below the cap
  const double delta = 1e-5, dt = 1e-6;
  wc::ContactHistory h{};
  for (int i = 0; i < 10; ++i)
    wc::evaluate(pc, state(delta, Vector3d(0.02, 0.01, 0)), dt, true, h);
  const Vector3d before(h.shear[0], h.shear[1], h.shear[2]);
  const double angle = 0.2;
  const Vector3d n(std::sin(angle), 0.0, std::cos(angle));
  const auto r = wc::evaluate(pc, state(delta, Vector3d::Zero(), n), dt, true, h);
  const Vector3d after(h.shear[0], h.shear[1], h.shear[2]);
  EXPECT_NEAR(after.dot(n), 0.0, 1e-15 * before.norm());
  // LIGGGHTS projects without rescaling the magnitude
  EXPECT_NEAR((after - (before - before.dot(n) * n)).norm(), 0.0, 1e-15 * before.norm());
  EXPECT_NEAR(r.force.dot(n) - r.normalForce, 0.0, 1e-12 * r.normalForce);
}

TEST(Tangential, TorqueIsTheTangentialForceOnTheLeverRMinusHalfDelta) {
  const auto pc = hertz();
  const double delta = 1e-5;
  wc::ContactHistory h{};
  const auto r = wc::evaluate(pc, state(delta, Vector3d(0.01, 0, 0)), 1e-6, true, h);
  const Vector3d ft(r.force.x(), r.force.y(), 0.0);
  const Vector3d expected = (-(kR - 0.5 * delta) * Vector3d::UnitZ()).cross(ft);
  EXPECT_NEAR((r.torque - expected).norm(), 0.0, 1e-15 * expected.norm());
}

TEST(Tangential, SetupEvaluationDoesNotAdvanceTheHistory) {
  const auto pc = hertz();
  wc::ContactHistory h{};
  wc::evaluate(pc, state(1e-5, Vector3d(0.01, 0, 0)), 1e-6, /*updateHistory=*/false, h);
  EXPECT_EQ(h.shear[0], 0.0);
}

TEST(RelativeVelocity, SpinActsOnTheLeverRMinusHalfDelta) {
  const Vector3d v = wc::relativeContactVelocity(Vector3d(1, 0, 0), Vector3d(0, 10, 0),
                                                 Vector3d(0.5, 0, 0), Vector3d::UnitZ(), kR, 1e-5);
  // contact point of the particle at -c_r n: v + ω × (-c_r n) = v - c_r ω × n
  const double cr = kR - 0.5e-5;
  EXPECT_NEAR(v.x(), 1.0 - 0.5 - cr * 10.0, 1e-15);
  EXPECT_NEAR(v.y(), 0.0, 1e-15);
  EXPECT_NEAR(v.z(), 0.0, 1e-15);
}

// ---------------------------------------------------------------------------------------------
TEST(Sjkr, WallCohesionIsEnergyDensityTimesContactArea) {
  wc::PairMaterial pair;
  pair.cohesionEnergyDensity = 3.0e4;
  wc::ContactSettings settings;
  settings.cohesion = wc::CohesionModel::Sjkr;
  const auto pc = constants(pair, settings);
  const auto pcNoCoh = hertz();
  for (double delta : {1e-7, 1e-5, 2e-4}) {
    wc::ContactHistory h1{}, h2{};
    const auto with = wc::evaluate(pc, state(delta), 1e-6, true, h1);
    const auto without = wc::evaluate(pcNoCoh, state(delta), 1e-6, true, h2);
    const double r = kR - delta;
    const double expected = -3.0e4 * M_PI * (kR * kR - r * r);
    EXPECT_NEAR(with.cohesionForce, expected, 1e-12 * std::fabs(expected));
    EXPECT_NEAR(with.force.z() - without.force.z(), expected, 1e-9 * std::fabs(expected));
    EXPECT_EQ(with.normalForce, without.normalForce); // tangential_reduce off by default
  }
}

TEST(TangentialHistoryAdhesive, SlidesOnThorntonsCapWithAndWithoutTangentialReduce) {
  // Held at overlap δ and sliding (no normal velocity, no damping): |Ft| = μ max(0, F_H − k_coh A
  // + 2 F_po), F_po = (2/3) π³ k_coh³ R² / Y*² (the wheel is a wall: R* = R), whether SJKR's
  // tangential_reduce has taken the pull off Fn or not; LIGGGHTS' history caps at μ F_H.
  const double mu = 0.5, kcoh = 2.0e5, dt = 1e-6;
  for (bool reduce : {false, true}) {
    wc::PairMaterial pair;
    pair.coefficientRestitution = 0.5;
    pair.coefficientFriction = mu;
    pair.cohesionEnergyDensity = kcoh;
    wc::ContactSettings settings;
    settings.cohesion = wc::CohesionModel::Sjkr;
    settings.tangential = wc::TangentialModel::HistoryAdhesive;
    settings.tangentialDamping = false;
    settings.tangentialReduce = reduce;
    const auto pc = constants(pair, settings);
    const double fPo =
        2.0 / 3.0 * std::pow(M_PI, 3) * std::pow(kcoh, 3) * kR * kR / (pc.Yeff * pc.Yeff);
    const double kHertz = 4.0 / 3.0 * pc.Yeff * std::sqrt(kR);
    const double zeroLoad = std::pow(2.0 * M_PI * kR * kcoh / kHertz, 2); // K δ^1.5 = C δ
    for (double delta : {zeroLoad, 4.0 * zeroLoad}) {
      const double fH = kHertz * std::pow(delta, 1.5);
      const double r = kR - delta;
      const double cap = mu * (fH - kcoh * M_PI * (kR * kR - r * r) + 2.0 * fPo);
      wc::ContactHistory h{};
      wc::ContactResult res;
      for (int i = 0; i < 20000 && !res.sliding; ++i)
        res = wc::evaluate(pc, state(delta, Vector3d(0.1, 0.0, 0.0)), dt, true, h);
      ASSERT_TRUE(res.sliding) << "reduce " << reduce << " delta " << delta;
      EXPECT_NEAR(std::hypot(res.force.x(), res.force.y()), cap, 1e-12 * cap)
          << "reduce " << reduce << " delta " << delta;
      EXPECT_LT(cap, mu * fH); // below history's cap: the test tells the two models apart
    }
  }
}

TEST(TangentialHistoryAdhesive, NeedsSjkrCohesion) {
  wc::PairMaterial pair;
  pair.coefficientFriction = 0.5;
  wc::ContactSettings settings;
  settings.tangential = wc::TangentialModel::HistoryAdhesive;
  try {
    constants(pair, settings);
    FAIL() << "no error without cohesion sjkr";
  } catch (const std::invalid_argument &e) {
    EXPECT_NE(std::string(e.what()).find("history_adhesive needs cohesion sjkr"), std::string::npos)
        << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
TEST(RollingEpsd2, TorqueIsCappedAndOpposesTheRotation) {
  wc::PairMaterial pair;
  pair.coefficientRollingFriction = 0.1;
  wc::ContactSettings settings;
  settings.rolling = wc::RollingModel::Epsd2;
  const auto pc = constants(pair, settings);
  const double delta = 1e-5, dt = 1e-6;
  wc::ContactHistory h{};
  auto s = state(delta);
  s.omega = Vector3d(3.0, -4.0, 7.0); // the twist part (z) is ignored by default
  bool capped = false;
  for (int i = 0; i < 5000; ++i) {
    const auto r = wc::evaluate(pc, s, dt, true, h); // vRel = 0: the torque is all rolling
    const double cap = 0.1 * kR * std::fabs(r.normalForce);
    EXPECT_LE(r.torque.norm(), cap * (1 + 1e-12));
    EXPECT_LT(r.torque.dot(s.omega), 0.0);
    EXPECT_NEAR(r.torque.z(), 0.0, 1e-15 * cap);
    // parallel to the tangential spin
    EXPECT_NEAR(r.torque.x() * 4.0 + r.torque.y() * 3.0, 0.0, 1e-12 * cap);
    if (i == 0) {
      const double kt = 8.0 * pc.Geff * std::sqrt(kR * delta);
      const double scale = kt * kR * kR * dt * (kR - 0.5 * delta) / (kR - delta);
      EXPECT_NEAR(r.torque.x(), -scale * 3.0, 1e-12 * scale * 3.0);
    }
    if (std::fabs(r.torque.norm() - cap) <= 1e-12 * cap)
      capped = true;
  }
  EXPECT_TRUE(capped);
}

TEST(RollingCdt, ConstantTorqueMuRollElasticForceLeverAgainstTheSpin) {
  // rolling_model_cdt.h, wall branch: |M| = μr (kn δ) (R − δ/2), kn δ = 4/3 Yeff sqrt(R δ) δ for
  // hertz, direction −ω with the normal (twist) part removed; independent of the history.
  wc::PairMaterial pair;
  pair.coefficientRollingFriction = 0.1;
  wc::ContactSettings settings;
  settings.rolling = wc::RollingModel::Cdt;
  const auto pc = constants(pair, settings);
  const double delta = 1e-5;
  wc::ContactHistory h{};
  auto s = state(delta);
  s.omega = Vector3d(3.0, -4.0, 7.0);
  const auto r = wc::evaluate(pc, s, 1e-6, true, h); // vRel = 0: the torque is all rolling
  const double knDelta = 4.0 / 3.0 * pc.Yeff * std::sqrt(kR * delta) * delta;
  const double cr = kR - 0.5 * delta;
  // the magnitude before the normal part is removed is μr kn δ c_r; the tangential spin is 5/√74
  // of the spin, so the torque keeps that fraction
  const double expected = 0.1 * knDelta * cr * 5.0 / std::sqrt(74.0);
  EXPECT_NEAR(r.torque.norm(), expected, 1e-12 * expected);
  EXPECT_LT(r.torque.dot(s.omega), 0.0);
  EXPECT_NEAR(r.torque.z(), 0.0, 1e-15 * expected);
  s.omega *= 10.0; // constant: the spin rate does not matter
  const auto r10 = wc::evaluate(pc, s, 1e-6, true, h);
  EXPECT_NEAR(r10.torque.norm(), expected, 1e-12 * expected);
}

/// Pair constants with rolling_friction krot of stiffness kr [N·m/rad].
wc::PairConstants krot(double kr) {
  wc::PairMaterial pair;
  pair.rollingSpringStiffness = kr;
  wc::ContactSettings settings;
  settings.rolling = wc::RollingModel::Krot;
  return constants(pair, settings);
}

TEST(RollingKrot, LinearSpringOnTheRotationRelativeToTheWheelWithoutCap) {
  // M = k_r θ_rel,t (θ_rel = (ω − ω_w) t, twist part removed), against the relative rotation,
  // elastic however far it winds up: after N steps |M| = k_r |ω_rel,t| N dt exactly.
  const auto pc = krot(5e-5);
  const double delta = 1e-5, dt = 1e-4;
  wc::ContactHistory h{};
  auto s = state(delta); // normal +z
  s.omega = Vector3d(3.0, -4.0, 7.0);
  s.omegaSurface = Vector3d(1.0, 0.0, -2.0); // the wheel's spin: ω_rel,t = (2, -4, 0)
  const Vector3d wRelT(2.0, -4.0, 0.0);
  const int n = 20000; // θ = 8.9 rad: far beyond any rolling-friction cap
  wc::ContactResult r;
  for (int i = 1; i <= n; ++i) {
    r = wc::evaluate(pc, s, dt, true, h); // vRel = 0: the torque is all rolling
    if (i == 1) {
      const Vector3d expected = -5e-5 * dt * wRelT;
      EXPECT_NEAR((r.torque - expected).norm(), 0.0, 1e-12 * expected.norm());
    }
  }
  const Vector3d expected = -5e-5 * dt * n * wRelT;
  EXPECT_NEAR((r.torque - expected).norm(), 0.0, 1e-9 * expected.norm());
  // without history update the torque is the next step's and the spring keeps its state
  const auto probe = wc::evaluate(pc, s, dt, false, h);
  EXPECT_NEAR((probe.torque - (-5e-5 * dt * (n + 1) * wRelT)).norm(), 0.0, 1e-9 * expected.norm());
  EXPECT_NEAR((Eigen::Map<const Vector3d>(h.rollTorque) + expected).norm(), 0.0,
              1e-9 * expected.norm());
  // spinning back unwinds it: elastic, no cap, no loss
  s.omega = s.omegaSurface - Vector3d(2.0, -4.0, 5.0);
  for (int i = 0; i < n; ++i)
    r = wc::evaluate(pc, s, dt, true, h);
  EXPECT_LT(r.torque.norm(), 1e-9 * expected.norm());
  // the particle turning with the wheel winds nothing
  wc::ContactHistory h2{};
  s.omega = s.omegaSurface;
  EXPECT_EQ(wc::evaluate(pc, s, dt, true, h2).torque.norm(), 0.0);
}

TEST(RollingKrot, StoredMomentFollowsTheContactPlane) {
  // a wound spring whose contact normal turns by 90° keeps its magnitude, in the new plane
  const auto pc = krot(1e-4);
  wc::ContactHistory h{};
  h.rollTorque[0] = 2e-6; // in the plane of normal +z, and 1e-6 along y
  h.rollTorque[1] = 1e-6;
  auto s = state(1e-5);
  s.normal = Vector3d(1.0, 0.0, 0.0); // x is now the normal: the y part remains, scaled up
  const auto r = wc::evaluate(pc, s, 1e-4, true, h);
  EXPECT_NEAR(r.torque.x(), 0.0, 1e-18);
  EXPECT_NEAR(r.torque.y(), -std::sqrt(5.0) * 1e-6, 1e-15);
}

TEST(RollingKrot, TimestepRuleFromTheRotationalInertia) {
  const auto pc = krot(5e-5);
  const auto *entry = wc::find_model(wc::ModelKind::Rolling, "krot");
  ASSERT_NE(entry, nullptr);
  ASSERT_NE(entry->spec->timestep, nullptr);
  const double m = 1e-4, R = 2.5e-3; // 0.5 sqrt(0.4 m R² / k_r) = 2.236e-3 s
  EXPECT_NEAR(entry->spec->timestep(pc, R, m), 0.5 * std::sqrt(0.4 * m * R * R / 5e-5), 1e-15);
  EXPECT_TRUE(std::isinf(entry->spec->timestep(krot(0.0), R, m)));
}

/// Pair constants with rolling friction μr under `model` (Cdt or Epsdt).
wc::PairConstants rolling(wc::RollingModel model, double mur) {
  wc::PairMaterial pair;
  pair.coefficientRollingFriction = mur;
  wc::ContactSettings settings;
  settings.rolling = model;
  return constants(pair, settings);
}

TEST(RollingEpsdt, CappedSpringOnTheRotationRelativeToTheWheel) {
  // M = k_t R² θ_rel,t (k_t = 8 G* sqrt(R δ), epsd2's spring; θ_rel from ω − ω_w, twist part
  // removed) until |M| reaches μr R |Fn|, then it stays on the cap.
  const auto pc = rolling(wc::RollingModel::Epsdt, 0.1);
  const double delta = 1e-5, dt = 1e-6;
  wc::ContactHistory h{};
  auto s = state(delta); // normal +z
  s.omega = Vector3d(3.0, -4.0, 7.0);
  s.omegaSurface = Vector3d(1.0, 0.0, -2.0); // ω_rel,t = (2, -4, 0)
  const Vector3d wRelT(2.0, -4.0, 0.0);
  const double kr = 8.0 * pc.Geff * std::sqrt(kR * delta) * kR * kR;
  auto r = wc::evaluate(pc, s, dt, true, h); // vRel = 0: the torque is all rolling
  EXPECT_NEAR((r.torque + kr * dt * wRelT).norm(), 0.0, 1e-12 * kr * dt * wRelT.norm());
  const double cap = 0.1 * kR * std::fabs(r.normalForce);
  const int toCap = static_cast<int>(cap / (kr * dt * wRelT.norm()));
  ASSERT_GT(toCap, 10);
  for (int i = 2; i <= toCap; ++i)
    r = wc::evaluate(pc, s, dt, true, h);
  EXPECT_NEAR((r.torque + kr * dt * toCap * wRelT).norm(), 0.0, 1e-9 * cap); // still elastic
  for (int i = 0; i < 3 * toCap; ++i)
    r = wc::evaluate(pc, s, dt, true, h);
  EXPECT_NEAR(r.torque.norm(), cap, 1e-12 * cap); // plastic: on the cap, against the rotation
  EXPECT_NEAR((r.torque / cap + wRelT.normalized()).norm(), 0.0, 1e-12);
  // spinning back unloads it elastically at once (no waiting for a sign switch)
  s.omega = s.omegaSurface - Vector3d(2.0, -4.0, 0.0);
  r = wc::evaluate(pc, s, dt, true, h);
  EXPECT_NEAR(r.torque.norm(), cap - kr * dt * wRelT.norm(), 1e-9 * cap);
  // the particle turning with the wheel winds nothing
  wc::ContactHistory h2{};
  s.omega = s.omegaSurface;
  EXPECT_EQ(wc::evaluate(pc, s, dt, true, h2).torque.norm(), 0.0);
}

TEST(RollingEpsdt, StoredMomentFollowsTheContactPlane) {
  // as krot: a stored moment whose contact normal turns by 90° keeps its magnitude (below the
  // cap), in the new plane; epsd2 would keep a normal (twisting) part
  const auto pc = rolling(wc::RollingModel::Epsdt, 10.0); // a cap far above the moment
  wc::ContactHistory h{};
  h.rollTorque[0] = 2e-9;
  h.rollTorque[1] = 1e-9;
  auto s = state(1e-5);
  s.normal = Vector3d(1.0, 0.0, 0.0);
  const auto r = wc::evaluate(pc, s, 1e-6, true, h);
  EXPECT_NEAR(r.torque.x(), 0.0, 1e-21);
  EXPECT_NEAR(r.torque.y(), -std::sqrt(5.0) * 1e-9, 1e-18);
}

/// A sphere on a still contact under a steady external torque `torque` [N·m] about x, below the
/// rolling cap: its rotation angle [rad] after `steps` steps of dt (symplectic Euler, as LIGGGHTS'
/// nve/sphere), and the largest |angle| on the way. The contact holds the sphere's centre.
std::pair<double, double> heldSphereRotation(const wc::PairConstants &pc, double torque, double dt,
                                             int steps) {
  const double inertia = 0.4 * kM * kR * kR;
  wc::ContactHistory h{};
  auto s = state(1e-5);
  double angle = 0.0, largest = 0.0;
  for (int i = 0; i < steps; ++i) {
    const auto r = wc::evaluate(pc, s, dt, true, h);
    s.omega.x() += (torque + r.torque.x()) / inertia * dt;
    angle += s.omega.x() * dt;
    largest = std::max(largest, std::fabs(angle));
  }
  return {angle, largest};
}

TEST(RollingEpsdt, HoldsASteadyMomentBelowTheCapWhereCdtCreepsAtARateProportionalToDt) {
  // cdt's torque has no spring: at rest it switches sign every step, and under a steady moment
  // below its cap the sphere keeps turning, at a steady mean rate that halves with dt (a numerical
  // creep). epsdt winds its spring to the moment and holds: the angle stays within twice the
  // static wind-up T / k_r (an undamped spring released from rest overshoots to twice it).
  // dt 1e-6 s over 0.01 s: 10 000 steps a run (250 000 took > 60 s, its timeout, under ASan), the
  // same ratios to 1e-4 as at 2e-7 s over 0.05 s, and epsdt's swing still exactly twice its
  // wind-up.
  const double mur = 0.1, dt = 1e-6, t = 0.01;
  const int steps = static_cast<int>(t / dt);
  const auto cdt = rolling(wc::RollingModel::Cdt, mur);
  const auto epsdt = rolling(wc::RollingModel::Epsdt, mur);
  wc::ContactHistory probe{};
  const double Fn = wc::evaluate(cdt, state(1e-5), dt, false, probe).normalForce;
  const double torque = 0.5 * mur * kR * Fn; // half of either cap
  const double cdtT = heldSphereRotation(cdt, torque, dt, steps).first;
  const double cdt2T = heldSphereRotation(cdt, torque, dt, 2 * steps).first;
  const double cdtHalfDt = heldSphereRotation(cdt, torque, dt / 2, 2 * steps).first;
  EXPECT_GT(cdtT, 0.0);
  EXPECT_NEAR(cdt2T / cdtT, 2.0, 0.05) << "cdt creeps steadily: " << cdtT << ", " << cdt2T;
  EXPECT_NEAR(cdtHalfDt / cdtT, 0.5, 0.05) << "cdt's creep goes as dt: " << cdtHalfDt;
  const double kr = 8.0 * epsdt.Geff * std::sqrt(kR * 1e-5) * kR * kR;
  const double wound = torque / kr;
  const auto [epsdtAngle, epsdtLargest] = heldSphereRotation(epsdt, torque, dt, 2 * steps);
  EXPECT_LE(epsdtLargest, 2.0 * wound * 1.01);
  EXPECT_LE(std::fabs(epsdtAngle), 2.0 * wound * 1.01);
  EXPECT_GT(cdt2T, 2.0 * epsdtLargest) << "over 2t cdt has crept past epsdt's largest swing";
}

// ---------------------------------------------------------------------------------------------
// EEPA (model edinburgh), linear (n = X = 1) so that the branches are straight lines in δ.
struct EepaLinear : ::testing::Test {
  static constexpr double kRatio = 5.0;  // k2/k1
  static constexpr double kcRatio = 0.5; // kc/k1
  static constexpr double kF0 = -2.0e-3; // pull-off force [N]
  wc::PairConstants pc;
  double k1 = 0, k2 = 0, kc = 0;
  void SetUp() override {
    wc::PairMaterial pair;
    pair.UnloadingStiffness = kRatio;
    pair.coefficientAdhesionStiffness = kcRatio;
    pair.pullOffForce = kF0;
    pair.overlapExponent = 1.0;
    pair.adhesionExponent = 1.0;
    wc::ContactSettings settings;
    settings.normal = wc::NormalModel::Eepa;
    settings.fixKc = true;
    pc = constants(pair, settings);
    k1 = 2.0 * pc.Yeff * kR; // linear EEPA loading stiffness
    k2 = kRatio * k1;
    kc = kcRatio * k1;
  }
  double force(double delta, wc::ContactHistory &h) {
    return wc::evaluate(pc, state(delta), 1e-6, true, h).force.z();
  }
};

TEST_F(EepaLinear, LoadUnloadReloadLoop) {
  wc::ContactHistory h{};
  const double dMax = 1e-5;
  const int n = 100;
  // loading: F = k1 δ + f0
  for (int i = 1; i <= n; ++i) {
    const double d = dMax * i / n;
    EXPECT_NEAR(force(d, h), k1 * d + kF0, 1e-9 * k1 * dMax) << "loading at " << d;
  }
  EXPECT_DOUBLE_EQ(h.deltaMax, dMax);
  // unloading: slope k2 through (δmax, k1 δmax); zero contact force at the plastic overlap
  const double dPlastic = dMax * (1.0 - 1.0 / kRatio);
  // where the unloading line meets the adhesive branch -kc δ
  const double dMeet = (k2 - k1) * dMax / (k2 + kc);
  double d = dMax;
  for (int i = 1; i <= n; ++i) {
    d = dMax - (dMax - 0.5 * dMeet) * i / n;
    const double expected = d > dMeet ? k2 * (d - dMax) + k1 * dMax : -kc * d;
    EXPECT_NEAR(force(d, h), expected + kF0, 1e-9 * k1 * dMax) << "unloading at " << d;
  }
  EXPECT_NEAR(k2 * (dPlastic - dMax) + k1 * dMax, 0.0, 1e-12 * k1 * dMax);
  // on the adhesive branch the memory moved so that reloading starts on a k2 line through the
  // current point (continuous for n = 1)
  const double dA = d;
  EXPECT_NEAR(h.deltaMax, (k2 + kc) / (k2 - k1) * dA, 1e-20);
  const double dNewMax = h.deltaMax;
  for (int i = 1; i <= n; ++i) {
    const double dr = dA + (1.2 * dMax - dA) * i / n;
    const double line = k2 * (dr - dNewMax) + k1 * dNewMax;
    const double expected = line >= k1 * dr ? k1 * dr : line;
    EXPECT_NEAR(force(dr, h), expected + kF0, 1e-9 * k1 * dMax) << "reloading at " << dr;
  }
}

TEST_F(EepaLinear, SeparationUnderTensionEndsAtZeroOverlapWithThePullOffForce) {
  wc::ContactHistory h{};
  force(1e-5, h);
  double last = 0, dLast = 0;
  for (double d = 1e-5; d > 1e-12; d *= 0.9) {
    last = force(d, h);
    dLast = d;
  }
  // on the adhesive branch F = -kc δ + f0, which tends to f0 as δ -> 0: the contact releases at
  // δ = 0 carrying the pull-off force
  EXPECT_NEAR(last, -kc * dLast + kF0, 1e-12 * std::fabs(kF0));
  EXPECT_NEAR(last, kF0, 1e-3 * std::fabs(kF0));
}

TEST(Eepa, DefaultWallContactReleasesAtThePlasticOverlap) {
  // LIGGGHTS defaults (fixKc off, limitForce on, f0 = 0): no adhesion on a wall; the force
  // reaches zero at δp = (1 - k1/k2)^(1/n) δmax and stays zero below it.
  wc::PairMaterial pair;
  pair.UnloadingStiffness = 4.0;
  pair.surfaceEnergy = 0.5; // no effect on a wall
  wc::ContactSettings settings;
  settings.normal = wc::NormalModel::Eepa;
  const auto pc = constants(pair, settings);
  const double k1 = 4.0 / 3.0 * pc.Yeff * std::sqrt(kR), k2 = 4.0 * k1;
  wc::ContactHistory h{};
  const double dMax = 2e-5;
  for (int i = 1; i <= 50; ++i) {
    const double d = dMax * i / 50;
    EXPECT_NEAR(wc::evaluate(pc, state(d), 1e-6, true, h).force.z(), k1 * std::pow(d, 1.5),
                1e-12 * k1 * std::pow(dMax, 1.5));
  }
  const double dRelease = std::pow(1.0 - k1 / k2, 1.0 / 1.5) * dMax;
  EXPECT_NEAR(h.deltaMax, dRelease, 1e-18);
  for (int i = 1; i <= 50; ++i) {
    const double d = dMax * (1.0 - i / 50.0 * 0.99);
    const double f = wc::evaluate(pc, state(d), 1e-6, true, h).force.z();
    const double expected = d > dRelease ? k2 * (std::pow(d, 1.5) - std::pow(dRelease, 1.5)) : 0.0;
    EXPECT_NEAR(f, expected, 1e-9 * k1 * std::pow(dMax, 1.5)) << "at " << d;
    EXPECT_GE(f, 0.0);
  }
  EXPECT_EQ(h.kc, 0.0); // surfaceEnergy gives no adhesive stiffness against a wall
}

// ---------------------------------------------------------------------------------------------
// Golden values: tests/contact/golden_values.py (LIGGGHTS formulas transcribed independently).
TEST(Golden, HertzWithSjkrAndEpsd2OneStep) {
  wc::PairMaterial pair;
  pair.coefficientRestitution = 0.5;
  pair.coefficientFriction = 0.5;
  pair.cohesionEnergyDensity = 1.0e5;
  pair.coefficientRollingFriction = 0.1;
  wc::ContactSettings settings;
  settings.cohesion = wc::CohesionModel::Sjkr;
  settings.rolling = wc::RollingModel::Epsd2;
  const auto pc = constants(pair, settings);
  auto s = state(1.0e-5, Vector3d(0.01, 0.0, -0.1));
  s.omega = Vector3d(0.0, 5.0, 0.0);
  wc::ContactHistory h{};
  const auto r = wc::evaluate(pc, s, 1.0e-6, true, h);
  const double tol = 1e-12;
  EXPECT_NEAR(relErr(r.force.x(), -0.0041077445411246138), 0.0, tol);
  EXPECT_EQ(r.force.y(), 0.0);
  EXPECT_NEAR(relErr(r.force.z(), 0.13489972694990762), 0.0, tol);
  EXPECT_NEAR(relErr(r.torque.y(), 7.9384051089275599e-06), 0.0, tol);
  EXPECT_NEAR(relErr(r.normalForce, 0.14743468163773071), 0.0, tol);
  EXPECT_NEAR(relErr(h.shear[0], 1e-08), 0.0, tol);
  EXPECT_NEAR(relErr(h.rollTorque[1], 2.5654525061604604e-07), 0.0, tol);
}

TEST(Golden, EepaDefaultUnloadingStep) {
  wc::PairMaterial pair;
  pair.coefficientRestitution = 0.5;
  pair.UnloadingStiffness = 5.0;
  pair.surfaceEnergy = 0.1;
  wc::ContactSettings settings;
  settings.normal = wc::NormalModel::Eepa;
  const auto pc = constants(pair, settings);
  wc::ContactHistory h{};
  h.deltaMax = 1.2e-5;
  h.oldDelta = 1.6e-5;
  const auto r = wc::evaluate(pc, state(1.5e-5, Vector3d(0, 0, 0.002)), 1e-6, true, h);
  EXPECT_NEAR(relErr(r.force.z(), 0.17633698294444883), 0.0, 1e-12);
  EXPECT_NEAR(relErr(h.deltaMax, 1.2926608140191304e-05), 0.0, 1e-12);
  EXPECT_EQ(h.oldDelta, 1.5e-5);
}

TEST(Golden, EepaFixKcAdhesiveStep) {
  wc::PairMaterial pair;
  pair.UnloadingStiffness = 5.0;
  pair.coefficientAdhesionStiffness = 0.5;
  pair.pullOffForce = -1.0e-3;
  wc::ContactSettings settings;
  settings.normal = wc::NormalModel::Eepa;
  settings.fixKc = true;
  settings.limitForce = wc::Switch::Off;
  const auto pc = constants(pair, settings);
  wc::ContactHistory h{};
  h.deltaMax = 2.0e-5;
  const auto r = wc::evaluate(pc, state(1.58e-5), 1e-6, true, h);
  EXPECT_NEAR(relErr(r.force.z(), -0.10385595033006312), 0.0, 1e-12);
  EXPECT_NEAR(relErr(h.deltaMax, 2.1725000000000003e-05), 0.0, 1e-12);
}

TEST(Golden, KrotTurnedMomentAndRelativeSpinOneStep) {
  // golden_values.py krot_case: a stored moment partly along the new normal, the spin relative
  // to the wheel's, vRel = 0 (the torque is the rolling moment alone)
  const auto pc = krot(5e-5);
  auto s = state(1.0e-5, Vector3d::Zero(), Vector3d(0.6, 0.0, 0.8));
  s.omega = Vector3d(3.0, -4.0, 7.0);
  s.omegaSurface = Vector3d(0.0, 1.5, 0.0);
  wc::ContactHistory h{};
  h.rollTorque[0] = 2.0e-7;
  h.rollTorque[1] = -1.0e-7;
  h.rollTorque[2] = 3.0e-8;
  const auto r = wc::evaluate(pc, s, 1.0e-6, true, h);
  const Vector3d expected(-1.4749619204537486e-07, 1.3017657750473138e-07, 1.1062214403403115e-07);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(relErr(r.torque[k], expected[k]), 0.0, 1e-12);
    EXPECT_NEAR(relErr(h.rollTorque[k], -expected[k]), 0.0, 1e-12);
  }
}

} // namespace
