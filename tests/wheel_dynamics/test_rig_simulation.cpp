// RigSimulation on the rigid flat ground: phases, imposed slip (sign, magnitude, held slip),
// constant and ramped drawbar load, the definitions of the outputs.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "wheelsim/rig/rig_simulation.h"

namespace wheelsim::rig {
namespace {

constexpr double kMu = 0.6;
constexpr double kLoad = 13200.0; // N
constexpr double kOmega = 1.05;   // rad/s
constexpr double kR = 0.617;      // m

std::string config(const std::string &carriage, const std::string &friction,
                   double duration = 3.0) {
  return R"(
[wheel]
mass = 205.0
inertia = 72.0
effective_radius = 0.617
[rig]
spindle_mass = 100.0
vertical_load = 13200.0
spring_k = 12000.0
spring_c = 800.0
[motor]
omega = 1.05
ramp_time = 1.0
[carriage]
)" + carriage +
         R"(
[run]
dt = 1.0e-4
duration = )" +
         std::to_string(duration) +
         R"(
[terrain]
type = "flat"
stiffness = 1.0e7
damping = 1.1e5
friction = 0.6
)" + friction +
         "\n";
}

const std::string kCoulomb = "friction_model = \"coulomb\"\ntangential_damping = 2.0e4";
const std::string kRegularized = "friction_model = \"regularized\"\nslip_velocity_scale = 0.1";

struct SimRun {
  std::vector<RigOutputs> out;
  RigSimulation sim;
  explicit SimRun(const std::string &text) : sim(parse_rig_config(text, "test.toml")) {
    FlatGround ground = make_flat_ground(sim.config(), sim.wheel());
    sim.run(ground, [&](const RigOutputs &o) { out.push_back(o); });
  }
  /// Mean and max |deviation| of a member over the last `seconds` of the run.
  template <class F> std::pair<double, double> tail(double seconds, F f) const {
    double sum = 0, n = 0;
    const double t_end = out.back().time_s;
    for (const auto &o : out)
      if (o.time_s > t_end - seconds)
        sum += f(o), ++n;
    const double mean = sum / n;
    double dev = 0;
    for (const auto &o : out)
      if (o.time_s > t_end - seconds)
        dev = std::max(dev, std::abs(f(o) - mean));
    return {mean, dev};
  }
};

TEST(RigSimulation, PhasesReleaseWithoutImpactAndSettle) {
  const SimRun r(config("mode = \"imposed_slip\"\nslip = 0.2", kCoulomb));
  EXPECT_TRUE(r.sim.warnings().empty()) << r.sim.warnings().front();
  // Phases in order, each present.
  std::vector<Phase> seen;
  for (const auto &o : r.out)
    if (seen.empty() || seen.back() != o.phase)
      seen.push_back(o.phase);
  ASSERT_EQ(seen, (std::vector<Phase>{Phase::release, Phase::settle, Phase::ramp, Phase::test}));
  // Gentle release: the contact force never exceeds the load by more than 2 % before the ramp.
  double peak = 0;
  for (const auto &o : r.out)
    if (o.phase == Phase::release || o.phase == Phase::settle)
      peak = std::max(peak, o.contact.f_B_W.z());
  EXPECT_LT(peak, 1.02 * kLoad);
  EXPECT_GT(peak, 0.98 * kLoad);
  // Static sinkage on the penalty ground: W / k_n.
  EXPECT_NEAR(r.sim.static_sinkage_m(), kLoad / 1e7, 0.01 * kLoad / 1e7);
  EXPECT_NEAR(r.sim.test_start_s(), r.out.back().time_s + 1e-4 - 3.0, 1e-9);
  EXPECT_TRUE(r.sim.finished());
}

TEST(RigSimulation, ImposedSlipDrawbarPullIsMuWAndSlipHeld) {
  const SimRun r(config("mode = \"imposed_slip\"\nslip = 0.2", kCoulomb));
  const auto dp = r.tail(1.0, [](const RigOutputs &o) { return o.drawbar_pull_N; });
  const auto s = r.tail(1.0, [](const RigOutputs &o) { return o.slip; });
  const auto T = r.tail(1.0, [](const RigOutputs &o) { return o.driving_torque_Nm; });
  const auto eta = r.tail(1.0, [](const RigOutputs &o) { return o.tractive_efficiency; });
  const auto ft = r.tail(1.0, [](const RigOutputs &o) { return o.traction_force_N; });
  const auto sink = r.tail(1.0, [](const RigOutputs &o) { return o.sinkage_m; });
  RecordProperty("drawbar_pull_N", std::to_string(dp.first));
  EXPECT_GT(dp.first, 0.0);
  EXPECT_NEAR(dp.first, kMu * kLoad, 0.005 * kMu * kLoad);
  EXPECT_NEAR(s.first, 0.2, 0.005 * 0.2); // held within 0.5 %, every step:
  EXPECT_LE(s.second, 0.005 * 0.2);
  // Fully sliding: T = μ W R, F_T = T / R = μ W, η = DP v / (T ω) = 1 - s.
  EXPECT_NEAR(T.first, kMu * kLoad * kR, 0.005 * kMu * kLoad * kR);
  EXPECT_NEAR(ft.first, T.first / kR, 1e-9);
  EXPECT_NEAR(eta.first, 0.8, 0.005);
  EXPECT_NEAR(sink.first, kLoad / 1e7, 0.01 * kLoad / 1e7);
  const RigOutputs &last = r.out.back();
  EXPECT_NEAR(last.omega_rad_s, kOmega, 1e-12);
  EXPECT_NEAR(last.forward_velocity_m_s, 0.8 * kOmega * kR, 1e-12);
  EXPECT_NEAR(last.slip_velocity_m_s, 0.2 * kOmega * kR, 1e-12);
  EXPECT_DOUBLE_EQ(last.lateral_force_N, 0.0);
}

TEST(RigSimulation, ImposedNegativeSlipBrakesAndZeroSlipSticks) {
  const SimRun braked(config("mode = \"imposed_slip\"\nslip = -0.2", kCoulomb));
  const auto dp = braked.tail(1.0, [](const RigOutputs &o) { return o.drawbar_pull_N; });
  EXPECT_NEAR(dp.first, -kMu * kLoad, 0.005 * kMu * kLoad);
  const SimRun rolling(config("mode = \"imposed_slip\"\nslip = 0.0", kCoulomb));
  const auto dp0 = rolling.tail(1.0, [](const RigOutputs &o) { return o.drawbar_pull_N; });
  EXPECT_NEAR(dp0.first, 0.0, 1e-3 * kMu * kLoad); // rigid ground: no motion resistance
}

// Carriage speed and wheel speed imposed independently (carriage.mode = "imposed_speed" with
// motor.omega). On the flat ground the contact point slides backwards over the ground at
// v_j = v − ω R_eff < 0 whenever v > ω R_eff, so the Coulomb friction force on the wheel is
// −μN along x: the carriage must push, DP = −μW; its torque about the centre is (−R)(−μN) =
// +μNR about +y, which the motor holds: T = −μ W R_eff (a braking torque, the opposite sign of
// the driving case's +μ W R_eff). That holds for a locked wheel (ω = 0) and for any skid
// point (v > ω R_eff > 0). With the regularized law the force is μN tanh(|v_j| / v_c).
std::string with_omega(std::string text, const std::string &omega) {
  return text.replace(text.find("omega = 1.05"), 12, "omega = " + omega);
}

TEST(RigSimulation, LockedWheelPulledAtConstantSpeedGivesMinusMuW) {
  const double v = 0.2; // m/s
  const SimRun r(with_omega(
      config("mode = \"imposed_speed\"\nspeed = " + std::to_string(v), kCoulomb), "0.0"));
  EXPECT_TRUE(r.sim.finished());
  const auto dp = r.tail(1.0, [](const RigOutputs &o) { return o.drawbar_pull_N; });
  const auto T = r.tail(1.0, [](const RigOutputs &o) { return o.driving_torque_Nm; });
  const auto vx = r.tail(1.0, [](const RigOutputs &o) { return o.forward_velocity_m_s; });
  RecordProperty("drawbar_pull_N", std::to_string(dp.first));
  RecordProperty("driving_torque_Nm", std::to_string(T.first));
  // DP = -μW and T = -μ W R_eff within 0.5 %, at every step of the last second within 1 %.
  EXPECT_NEAR(dp.first, -kMu * kLoad, 0.005 * kMu * kLoad);
  EXPECT_LT(dp.second, 0.01 * kMu * kLoad);
  EXPECT_NEAR(T.first, -kMu * kLoad * kR, 0.005 * kMu * kLoad * kR);
  EXPECT_NEAR(vx.first, v, 1e-12);
  const RigOutputs &last = r.out.back();
  EXPECT_DOUBLE_EQ(last.omega_rad_s, 0.0); // the wheel never turns
  EXPECT_DOUBLE_EQ(last.theta_rad, 0.0);
  EXPECT_TRUE(std::isnan(last.slip)); // driving slip undefined at ω = 0 (skid convention: -1)
  EXPECT_NEAR(last.slip_velocity_m_s, -v, 1e-12);
  // Regularized friction: DP = -μ W tanh(v / v_c), v_c = 0.1 m/s.
  const SimRun reg(with_omega(
      config("mode = \"imposed_speed\"\nspeed = " + std::to_string(v), kRegularized), "0"));
  const auto dp_reg = reg.tail(1.0, [](const RigOutputs &o) { return o.drawbar_pull_N; });
  const double expected = -kMu * kLoad * std::tanh(v / 0.1);
  EXPECT_NEAR(dp_reg.first, expected, 0.005 * std::abs(expected));
}

TEST(RigSimulation, SkidAtImposedSpeedsGivesMinusMuWAndBrakingTorque) {
  // v = 2 ω R_eff: driving slip 1 - v/(ω R) = -1, skid slip (ω R - v)/v = -0.5.
  const double v = 2.0 * kOmega * kR;
  const SimRun r(config("mode = \"imposed_speed\"\nspeed = " + std::to_string(v), kCoulomb));
  const auto dp = r.tail(1.0, [](const RigOutputs &o) { return o.drawbar_pull_N; });
  const auto T = r.tail(1.0, [](const RigOutputs &o) { return o.driving_torque_Nm; });
  const auto s = r.tail(1.0, [](const RigOutputs &o) { return o.slip; });
  const auto eta = r.tail(1.0, [](const RigOutputs &o) { return o.tractive_efficiency; });
  RecordProperty("drawbar_pull_N", std::to_string(dp.first));
  RecordProperty("driving_torque_Nm", std::to_string(T.first));
  EXPECT_NEAR(dp.first, -kMu * kLoad, 0.005 * kMu * kLoad);
  EXPECT_NEAR(T.first, -kMu * kLoad * kR, 0.005 * kMu * kLoad * kR);
  const double v_set = std::stod(std::to_string(v)); // the value written into the config
  EXPECT_NEAR(s.first, 1.0 - v_set / (kOmega * kR), 1e-9);
  EXPECT_NEAR(s.first, -1.0, 1e-5);
  // η = DP v / (T ω) = v / (ω R_eff) (both powers negative: the wheel brakes the carriage).
  EXPECT_NEAR(eta.first, v_set / (kOmega * kR), 0.01 * v_set / (kOmega * kR));
  EXPECT_NEAR(r.out.back().omega_rad_s, kOmega, 1e-12);
}

// Free carriage, constant drawbar load L = μ W / 2 on the regularized law
// F = μ N tanh(v_j / v_c): steady slip s = v_c atanh(L / μ W) / (ω R).
TEST(RigSimulation, ConstantLoadSettlesToTheFrictionLawSlip) {
  const double L = 0.5 * kMu * kLoad;
  const SimRun r(config("mode = \"constant_load\"\nload = " + std::to_string(L), kRegularized));
  const double expected = 0.1 * std::atanh(0.5) / (kOmega * kR);
  const auto s = r.tail(1.0, [](const RigOutputs &o) { return o.slip; });
  const auto dp = r.tail(1.0, [](const RigOutputs &o) { return o.drawbar_pull_N; });
  RecordProperty("slip", std::to_string(s.first));
  EXPECT_NEAR(s.first, expected, 0.005 * expected);
  EXPECT_LT(s.second, 0.005 * expected); // settled
  EXPECT_NEAR(dp.first, L, 1e-9);
  EXPECT_NEAR(r.out.back().drawbar_load_command_N, L, 1e-9);
  // Coulomb with stiction: the wheel grips, no steady slip below the cap.
  const SimRun c(config("mode = \"constant_load\"\nload = " + std::to_string(L), kCoulomb));
  const auto sc = c.tail(1.0, [](const RigOutputs &o) { return o.slip; });
  EXPECT_NEAR(sc.first, 0.0, 1e-3);
}

// Ramped load: the drawbar load rises monotonically from load_start to load_end; slip follows the
// friction law quasi-statically.
TEST(RigSimulation, RampedLoadGivesMonotoneDrawbarRampAndSlipCurve) {
  const double L1 = 0.8 * kMu * kLoad;
  const SimRun r(config("mode = \"ramped_load\"\nload_start = 0.0\nload_end = " +
                            std::to_string(L1) + "\nramp_time = 4.0",
                        kRegularized, 4.0));
  double prev = -1, first = NAN;
  int n = 0;
  for (const auto &o : r.out) {
    if (o.phase != Phase::test)
      continue;
    if (std::isnan(first))
      first = o.drawbar_pull_N;
    EXPECT_GT(o.drawbar_pull_N, prev) << "at t = " << o.time_s;
    prev = o.drawbar_pull_N;
    ++n;
  }
  EXPECT_NEAR(first, 0.0, 1e-9);
  EXPECT_NEAR(prev, L1, L1 * 1e-3);
  EXPECT_EQ(n, 40000);
  // The slip at a few points of the ramp against the law at the contact's own force and normal
  // load (the drawbar load differs from the contact force by the carriage's inertia, M_x dv/dt).
  int checked = 0;
  for (const auto &o : r.out)
    if (o.phase == Phase::test && o.drawbar_pull_N > 0.1 * kMu * kLoad && o.step % 5000 == 0) {
      const double Fx = o.contact.f_B_W.x(), N = o.contact.f_B_W.z();
      const double s_law = 0.1 * std::atanh(Fx / (kMu * N)) / (kOmega * kR);
      EXPECT_NEAR(o.slip, s_law, 0.005 * s_law) << "load " << o.drawbar_pull_N;
      EXPECT_NEAR(Fx, o.drawbar_pull_N, 0.05 * o.drawbar_pull_N);
      ++checked;
    }
  EXPECT_GE(checked, 6);
}

TEST(RigSimulation, TorqueMotorAndAdvanceAfterEndThrow) {
  std::string text = config("mode = \"imposed_slip\"\nslip = 0.1", kCoulomb, 0.5);
  text.replace(text.find("omega = 1.05"), 12, "torque = 6000.0");
  RigSimulation sim(parse_rig_config(text, "t.toml"));
  FlatGround g = make_flat_ground(sim.config(), sim.wheel());
  RigOutputs last;
  sim.run(g, [&](const RigOutputs &o) { last = o; });
  EXPECT_NEAR(last.driving_torque_Nm, 6000.0, 1e-9);
  EXPECT_NEAR(last.slip, 0.1, 1e-9); // the carriage follows the emerging ω
  EXPECT_THROW(sim.advance(WheelWrench{}), std::logic_error);
}

TEST(RigSimulation, ReleaseTimeoutIsAnError) {
  std::string text = config("mode = \"imposed_slip\"\nslip = 0.1", kCoulomb);
  text.replace(text.find("[run]\n"), 6, "[run]\nrelease_timeout = 0.2\n");
  RigSimulation sim(parse_rig_config(text, "t.toml"));
  try {
    while (!sim.finished())
      sim.advance(WheelWrench{}); // no terrain: never carried
    FAIL() << "no error";
  } catch (const std::runtime_error &e) {
    EXPECT_NE(std::string(e.what()).find("run.release_timeout"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace wheelsim::rig
