// RunHealth (docs/run-health.md): each check fires on a run that goes wrong in its way and stays
// silent on a healthy one; the batch-means standard error against the analytic AR(1) answer.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "wheelsim/rig/run_health.h"

namespace wheelsim::rig {
namespace {

/// The small test wheel on the flat ground (R_eff 0.1 m, 15 N, 20 % slip), 1 s test phase.
std::string config(const std::string &carriage = "mode = \"imposed_slip\"\nslip = 0.2",
                   const std::string &run = "dt = 2.0e-4\nduration = 1.0") {
  return R"(
[wheel]
mass = 1.0
inertia = 0.005
effective_radius = 0.1
[rig]
spindle_mass = 0.5
vertical_load = 15.0
spring_k = 3000.0
spring_c = 30.0
[motor]
omega = 2.0
ramp_time = 0.2
[carriage]
)" + carriage +
         "\n[run]\n" + run + R"(
release_speed = 0.02
[terrain]
type = "flat"
stiffness = 2.0e4
damping = 150.0
friction = 0.6
friction_model = "regularized"
slip_velocity_scale = 0.01
)";
}

/// Runs `sim` to its end on `terrain` (a callable: state, time -> wrench) with the checks; returns
/// the findings. A RunHealthError ends the run early (its finding is in the list).
template <class Terrain>
std::vector<HealthFinding> run_checked(RigSimulation &sim, Terrain terrain,
                                       double stiffness_N_m = 2.0e4, double damping_N_s_m = 0.0) {
  RunHealth health(sim, nullptr);
  health.set_contact_stiffness(stiffness_N_m, damping_N_s_m);
  try {
    while (!sim.finished()) {
      const WheelWrench w = terrain(sim.wheel_state(), sim.time_s());
      health.before_step(w);
      health.after_step(sim.advance(w), 1.0);
    }
    health.finish();
  } catch (const RunHealthError &) {
  }
  return health.findings();
}

std::vector<std::string> codes(const std::vector<HealthFinding> &findings) {
  std::vector<std::string> out;
  for (const auto &f : findings)
    out.push_back(f.code + "/" + to_string(f.severity));
  return out;
}

TEST(RunHealth, BatchMeansStandardErrorOfAnAr1SignalWithin10Percent) {
  // x_t = a x_{t-1} + e_t, e ~ N(0, 1): Var(mean of N) -> 1/((1-a)^2 N) for N >> 1/(1-a). One
  // estimate from 20 batches scatters by ~1/sqrt(2*19) = 16 %; the RMS over 16 independent
  // series (seeds 1..16) is the estimator's accuracy, ~4 % of scatter left.
  for (const double a : {0.0, 0.9, 0.99}) {
    const int N = 400000, series = 16;
    const double expected = 1.0 / ((1.0 - a) * std::sqrt(double(N)));
    double sum_var = 0.0;
    std::vector<double> x(N);
    for (int seed = 1; seed <= series; ++seed) {
      std::mt19937_64 rng(seed);
      std::normal_distribution<double> e(0.0, 1.0);
      double prev = 0.0;
      for (int i = 0; i < 2000; ++i) // burn-in: start from the stationary distribution
        prev = a * prev + e(rng);
      for (int i = 0; i < N; ++i)
        x[i] = prev = a * prev + e(rng);
      const double sem = batch_means_sem(x, 20);
      sum_var += sem * sem;
    }
    const double rms = std::sqrt(sum_var / series);
    EXPECT_NEAR(rms / expected, 1.0, 0.10) << "a = " << a << ": SEM " << rms << " vs " << expected;
    std::printf("[ info     ] AR(1) a = %g: batch-means SEM %.4g, analytic %.4g (%+.1f %%)\n", a,
                rms, expected, 100.0 * (rms / expected - 1.0));
  }
  EXPECT_TRUE(std::isnan(batch_means_sem({1.0, 2.0, 3.0}, 10)));
}

TEST(RunHealth, AHealthyFlatGroundRunHasNoFinding) {
  RigSimulation sim(parse_rig_config(config(), "t.toml"));
  FlatGround ground = make_flat_ground(sim.config(), sim.wheel());
  const auto findings =
      run_checked(sim, [&](const WheelPose &s, double t) { return ground.contact(s, t); });
  EXPECT_TRUE(findings.empty()) << findings.front().code << ": " << findings.front().message;
}

TEST(RunHealth, NonFiniteContactForceStopsNamingTheQuantityAndStep) {
  RigSimulation sim(parse_rig_config(config(), "t.toml"));
  FlatGround ground = make_flat_ground(sim.config(), sim.wheel());
  const auto findings = run_checked(sim, [&](const WheelPose &s, double t) {
    WheelWrench w = ground.contact(s, t);
    if (sim.step() == 1234)
      w.f_B_W.z() = std::nan("");
    return w;
  });
  ASSERT_EQ(codes(findings), std::vector<std::string>{"nonfinite_state/error"});
  EXPECT_EQ(findings[0].step, 1234);
  EXPECT_NE(findings[0].message.find("contact force z is nan at step 1234"), std::string::npos)
      << findings[0].message;
  EXPECT_FALSE(sim.finished());
}

TEST(RunHealth, AWheelThatFallsThroughTheGroundStopsAtOneRadiusOfSinkage) {
  // The ground vanishes 0.1 s into the test phase: the wheel falls; stopped when sinkage > R.
  RigSimulation sim(parse_rig_config(config(), "t.toml"));
  FlatGround ground = make_flat_ground(sim.config(), sim.wheel());
  const auto findings = run_checked(sim, [&](const WheelPose &s, double t) {
    return sim.phase() == Phase::test && t > sim.test_start_s() + 0.1 ? WheelWrench{}
                                                                      : ground.contact(s, t);
  });
  ASSERT_FALSE(findings.empty());
  EXPECT_EQ(findings.back().code, "sinkage_beyond_radius");
  EXPECT_EQ(findings.back().severity, Severity::error);
  EXPECT_FALSE(sim.finished());
}

TEST(RunHealth, AWheelSinkingWhileCarriedWarnsAtOneRadiusAndStopsAtTwo) {
  // In the test phase the terrain carries 90 % of the load (a wheel digging into a soft soil):
  // it sinks on; past one radius a warning (once), past two radii the run stops.
  RigSimulation sim(parse_rig_config(config(), "t.toml"));
  FlatGround ground = make_flat_ground(sim.config(), sim.wheel());
  const double W = sim.rig().vertical_load_N();
  const auto findings = run_checked(sim, [&](const WheelPose &s, double t) {
    if (sim.phase() != Phase::test)
      return ground.contact(s, t);
    WheelWrench w;
    w.f_B_W.z() = 0.9 * W;
    return w;
  });
  std::vector<const HealthFinding *> buried;
  for (const auto &f : findings)
    if (f.code == "sinkage_beyond_radius")
      buried.push_back(&f);
  ASSERT_EQ(buried.size(), 2u);
  EXPECT_EQ(buried[0]->severity, Severity::warning);
  EXPECT_NE(buried[0]->message.find("while the terrain still carries it"), std::string::npos)
      << buried[0]->message;
  EXPECT_EQ(buried[1]->severity, Severity::error);
  EXPECT_NE(buried[1]->message.find("more than 2 radii"), std::string::npos) << buried[1]->message;
  EXPECT_FALSE(sim.finished());
}

TEST(RunHealth, GridCoarserThanHalfTheRimRadiusIsAnErrorBeforeTheRun) {
  RigSimulation sim(parse_rig_config(config(), "t.toml"));
  RunHealth health(sim, nullptr);
  try {
    health.set_grid(5.0, 2e8); // metres where millimetres were meant
    FAIL() << "no error for grid spacing 5 m";
  } catch (const RunHealthError &e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 0.005?"), std::string::npos) << e.what();
  }
  EXPECT_EQ(health.status(), "unhealthy");
  RunHealth fine(sim, nullptr);
  fine.set_grid(0.005, 2e8);
  EXPECT_TRUE(fine.findings().empty());
}

TEST(RunHealth, GridWiderThanTheLugsIsAWarning) {
  // test_small (wheel-mesh catalogue): 8 lugs 8 mm thick, from test_small.props.toml beside the
  // mesh. 10 mm spacing lets a lug pass between node rows; 5 mm (the shipped config) does not.
  std::string cfg = config();
  cfg.replace(cfg.find("mass = 1.0\ninertia = 0.005\n"), 27,
              "mesh = \"" WHEELSIM_MESH_DIR "/test_small.stl\"\ndensity = 7850.0\n");
  cfg.replace(cfg.find("vertical_load = 15.0"), 20, "vertical_load = 300.0"); // 16.4 kg of steel
  RigSimulation sim(parse_rig_config(cfg, "t.toml"));
  EXPECT_EQ(sim.wheel().lug_count, 8);
  EXPECT_DOUBLE_EQ(sim.wheel().lug_width_m, 0.008);
  EXPECT_DOUBLE_EQ(sim.wheel().lug_height_m, 0.01);
  RunHealth coarse(sim, nullptr);
  coarse.set_grid(0.01, 2e8);
  ASSERT_EQ(codes(coarse.findings()), std::vector<std::string>{"grid_coarse/warning"});
  EXPECT_NE(coarse.findings()[0].message.find("use at most 0.004 m"), std::string::npos)
      << coarse.findings()[0].message;
  RunHealth fine(sim, nullptr);
  fine.set_grid(0.005, 2e8);
  EXPECT_TRUE(fine.findings().empty());
}

// Fewer than 3 grid nodes across the wheel's width stops the run before its first step (and
// wheel-rig --check): test_small is 0.08 m wide, so 0.03 m (2.7 nodes) stops while 0.02 m (4)
// passes; both are below half its rim radius (0.05 m), the other setup limit.
TEST(RunHealth, GridWithFewerThanThreeNodesAcrossTheWheelIsAnErrorBeforeTheRun) {
  std::string cfg = config();
  cfg.replace(cfg.find("mass = 1.0\n"), 11,
              "mass = 1.0\nmesh = \"" WHEELSIM_MESH_DIR "/test_small.stl\"\n");
  RigSimulation sim(parse_rig_config(cfg, "t.toml"));
  ASSERT_NEAR(sim.wheel().width_m, 0.08, 1e-6);
  RunHealth coarse(sim, nullptr);
  try {
    coarse.set_grid(0.03, 2e8);
    FAIL() << "no error for 0.03 m across a 0.08 m wide wheel";
  } catch (const RunHealthError &e) {
    EXPECT_NE(std::string(e.what()).find("grid_coarse: terrain.grid_spacing = 0.03 m leaves fewer "
                                         "than 3 grid nodes across the wheel's width (0.08 m"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("use at most 0.0266667 m (width/3)"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(coarse.status(), "unhealthy");
  RunHealth fine(sim, nullptr);
  fine.set_grid(0.02, 2e8);
  EXPECT_FALSE(fine.has_error()); // the lugs' warning (8 mm thick) only
}

TEST(RunHealth, ContactStiffTooForTheTimeStepIsFlagged) {
  // omega_c dt = sqrt(k / 1.5 kg) * 2e-4 s: 2e4 N/m -> 0.023 (fine); 1e8 -> 1.6 (warning: over
  // half the limit 2); 1e9 -> 5.2 (error; the flat ground itself is still 2e4 N/m, so the run
  // stays finite).
  for (const auto &[k, expected] : std::vector<std::pair<double, std::string>>{
           {1e8, "dt_unstable/warning"}, {1e9, "dt_unstable/error"}}) {
    RigSimulation sim(parse_rig_config(config(), "t.toml"));
    FlatGround ground = make_flat_ground(sim.config(), sim.wheel());
    const auto findings = run_checked(
        sim, [&](const WheelPose &s, double t) { return ground.contact(s, t); }, k);
    EXPECT_EQ(codes(findings), std::vector<std::string>{expected}) << "k = " << k;
  }
}

TEST(RunHealth, ContactDampingLowersTheStableTimeStep) {
  // The bound wheel-rig --check uses (time_step.h): dt < 4 / (c/m + sqrt((c/m)^2 + 4 k/m)). On
  // 1.5 kg with k = 1e8 N/m: 2.45e-4 s undamped (dt = 2e-4 s is 0.82 of it: a warning), 1.65e-4 s
  // with c = 1e4 N s/m (1.22 of it: an error, although omega dt = 1.63 < 2).
  RigSimulation sim(parse_rig_config(config(), "t.toml"));
  ASSERT_DOUBLE_EQ(sim.rig().spindle_dof_mass_kg(), 1.5);
  FlatGround ground = make_flat_ground(sim.config(), sim.wheel());
  const auto findings = run_checked(
      sim, [&](const WheelPose &s, double t) { return ground.contact(s, t); }, 1e8, 1e4);
  ASSERT_EQ(codes(findings), std::vector<std::string>{"dt_unstable/error"});
  EXPECT_NE(findings[0].message.find("damping 10000 N s/m"), std::string::npos)
      << findings[0].message;
  EXPECT_NE(findings[0].message.find("stable up to dt = 0.000164575"), std::string::npos)
      << findings[0].message;
}

TEST(RunHealth, EfficiencyAboveOneMinusSlipIsFlagged) {
  // The ground acts at 0.9 R_eff: T = F 0.9 R_eff with F = DP, so T/R_eff < DP and
  // eta = (1 - s)/0.9 = 0.89 > 1 - s = 0.8.
  RigSimulation sim(parse_rig_config(config(), "t.toml"));
  FlatGroundParameters p = sim.config().terrain.flat;
  p.radius_m = 0.9 * sim.wheel().effective_radius_m;
  p.surface_height_m = sim.config().terrain.surface_height_m + 0.1 * sim.wheel().effective_radius_m;
  FlatGround ground(p);
  const auto findings =
      run_checked(sim, [&](const WheelPose &s, double t) { return ground.contact(s, t); });
  ASSERT_EQ(codes(findings), std::vector<std::string>{"efficiency_bound/warning"});
  EXPECT_NE(findings[0].message.find("above the bound 1 - s = 0.8"), std::string::npos)
      << findings[0].message;
}

TEST(RunHealth, WheelOutOfContactInTheTestPhaseIsFlagged) {
  // Every 4th step of the test phase the ground gives nothing (25 % out of contact: warning).
  RigSimulation sim(parse_rig_config(config(), "t.toml"));
  FlatGround ground = make_flat_ground(sim.config(), sim.wheel());
  const auto findings = run_checked(sim, [&](const WheelPose &s, double t) {
    const WheelWrench w = ground.contact(s, t);
    return sim.phase() == Phase::test && sim.step() % 4 == 0 ? WheelWrench{} : w;
  });
  const auto c = codes(findings);
  EXPECT_NE(std::find(c.begin(), c.end(), "lost_contact/warning"), c.end()) << c.size();
}

/// Synthetic test-phase outputs fed to after_step: `f(i)` fills step i's outputs.
template <class F> std::vector<HealthFinding> feed(const std::string &carriage, int n, F f) {
  RigSimulation sim(parse_rig_config(config(carriage), "t.toml"));
  RunHealth health(sim, nullptr);
  for (int i = 0; i < n; ++i) {
    RigOutputs o;
    o.step = i;
    o.time_s = i * 2e-4;
    o.phase = Phase::test;
    o.vertical_load_N = 15.0;
    o.contact.f_B_W.z() = 15.0;
    o.slip = 0.2;
    f(i, o);
    health.after_step(o, 1.0);
  }
  health.finish();
  return health.findings();
}

TEST(RunHealth, SlipNotHeldIsAnError) {
  const auto findings =
      feed("mode = \"imposed_slip\"\nslip = 0.2", 1000, [](int, RigOutputs &o) { o.slip = 0.25; });
  EXPECT_EQ(codes(findings), std::vector<std::string>{"slip_not_held/error"});
  EXPECT_TRUE(feed("mode = \"imposed_slip\"\nslip = 0.2", 1000, [](int, RigOutputs &) {}).empty());
}

TEST(RunHealth, ADriftingDrawbarPullIsNotSteady) {
  // DP rising by 2 N over the window (13 % of W) with noise of 0.1 N: flagged; the same noise
  // around a constant: not flagged.
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 0.1);
  const auto drift = feed("mode = \"imposed_slip\"\nslip = 0.2", 5000, [&](int i, RigOutputs &o) {
    o.drawbar_pull_N = 3.0 + 2.0 * i / 5000.0 + noise(rng);
  });
  EXPECT_EQ(codes(drift), std::vector<std::string>{"steady_state_trend/warning"});
  const auto steady = feed("mode = \"imposed_slip\"\nslip = 0.2", 5000,
                           [&](int, RigOutputs &o) { o.drawbar_pull_N = 3.0 + noise(rng); });
  EXPECT_TRUE(steady.empty()) << steady.front().message;
}

TEST(RunHealth, EachSlipModeChecksWhatItsTableEntryHolds) {
  // The slip modes' held_slip and steady (slip_modes.cpp) drive the checks: an imposed speed
  // with the speed motor holds 1 - v/(omega R_eff) = 1 - 0.16/(2 * 0.1) = 0.2; a constant load
  // lets slip emerge but expects it steady (not the drawbar pull); a ramped load expects nothing
  // steady. Drifts as in ADriftingDrawbarPullIsNotSteady (noise 0.1 N, 0.005, 0.1 mm).
  const std::string speed = "mode = \"imposed_speed\"\nspeed = 0.16";
  const std::string constant = "mode = \"constant_load\"\nload = 3.0";
  const std::string ramped =
      "mode = \"ramped_load\"\nload_start = 0.0\nload_end = 5.0\nramp_time = 1.0";
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto drifting = [&](int i, RigOutputs &o) {
    o.drawbar_pull_N = 3.0 + 2.0 * i / 5000.0 + 0.1 * noise(rng);
    o.slip = 0.2 + 0.1 * i / 5000.0 + 0.005 * noise(rng);
    o.sinkage_m = 0.01 + 0.01 * i / 5000.0 + 1e-4 * noise(rng);
  };
  EXPECT_TRUE(feed(speed, 1000, [](int, RigOutputs &) {}).empty());
  EXPECT_EQ(codes(feed(speed, 1000, [](int, RigOutputs &o) { o.slip = 0.25; })),
            std::vector<std::string>{"slip_not_held/error"});
  EXPECT_TRUE(feed(constant, 1000, [](int, RigOutputs &o) { o.slip = 0.25; }).empty());
  const auto f_speed = feed(speed, 5000, drifting);
  const auto f_constant = feed(constant, 5000, drifting);
  const auto f_ramped = feed(ramped, 5000, drifting);
  const auto trend_of = [](const std::vector<HealthFinding> &f) {
    std::vector<std::string> out;
    for (const auto &x : f)
      if (x.code == "steady_state_trend")
        out.push_back(x.message.substr(0, x.message.find(" changed")));
    return out;
  };
  EXPECT_EQ(trend_of(f_speed), (std::vector<std::string>{"the drawbar pull", "the sinkage"}));
  EXPECT_EQ(trend_of(f_constant), (std::vector<std::string>{"the slip", "the sinkage"}));
  EXPECT_TRUE(f_ramped.empty()) << f_ramped.front().message;
}

} // namespace
} // namespace wheelsim::rig
