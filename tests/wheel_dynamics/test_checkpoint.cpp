// Rig checkpoints (wheelsim/rig/checkpoint.h; docs/coupled-runs.md "Checkpoint and resume"): a rig
// restored from a checkpoint file written in any phase continues bit for bit like the run that
// did not stop, health checks included; damaged or foreign files are refused naming the problem.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "wheelsim/rig/checkpoint.h"
#include "wheelsim/rig/run_health.h"

namespace wheelsim::rig {
namespace {

/// The small test wheel on the flat ground at 20 % slip: release, settle, ramp, 0.2 s test.
const char *kConfig = R"(
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
ramp_time = 0.1
[carriage]
mode = "imposed_slip"
slip = 0.2
[run]
dt = 2.0e-4
duration = 0.2
release_speed = 0.02
settle_min_time = 0.02
settle_window = 0.02
[terrain]
type = "flat"
stiffness = 2.0e4
damping = 150.0
friction = 0.6
friction_model = "regularized"
slip_velocity_scale = 0.01
)";

std::string temp_path(const std::string &name) {
  return (std::filesystem::temp_directory_path() / ("wheelsim_ckpt_" + name)).string();
}

struct RunResult {
  std::vector<RigOutputs> outputs;
  std::vector<Phase> phases;
  std::vector<std::string> findings;
  std::string status;
};

/// Runs to the end; with `stop_at` >= 0 the run is checkpointed after that many steps to a file,
/// and continued by a new simulation restored from it.
RunResult run(long long stop_at) {
  const RigConfig config = parse_rig_config(kConfig, "t.toml");
  auto sim = std::make_unique<RigSimulation>(config);
  auto health = std::make_unique<RunHealth>(*sim, nullptr);
  FlatGround ground = make_flat_ground(config, sim->wheel());
  RunResult r;
  while (!sim->finished()) {
    if (sim->step() == stop_at) {
      CheckpointData data;
      sim->save_checkpoint(data);
      health->save_checkpoint(data);
      const std::string path = temp_path("rig.ckpt");
      data.write(path);
      health.reset();
      sim = std::make_unique<RigSimulation>(config);
      health = std::make_unique<RunHealth>(*sim, nullptr);
      const CheckpointData back = CheckpointData::read(path);
      sim->restore_checkpoint(back);
      health->restore_checkpoint(back);
    }
    const WheelWrench w = ground.contact(sim->wheel_state(), sim->time_s());
    health->before_step(w);
    const RigOutputs &o = sim->advance(w);
    health->after_step(o, 1.0);
    r.outputs.push_back(o);
    r.phases.push_back(o.phase);
  }
  health->finish();
  for (const HealthFinding &f : health->findings())
    r.findings.push_back(f.code + ": " + f.message);
  r.status = health->status();
  return r;
}

void expect_same(const RigOutputs &a, const RigOutputs &b) {
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.time_s, b.time_s);
  EXPECT_EQ(a.phase, b.phase);
  EXPECT_EQ(a.wheel.p_WB_W, b.wheel.p_WB_W);
  EXPECT_EQ(a.wheel.q_WB.coeffs(), b.wheel.q_WB.coeffs());
  EXPECT_EQ(a.wheel.v_WB_W, b.wheel.v_WB_W);
  EXPECT_EQ(a.wheel.w_WB_W, b.wheel.w_WB_W);
  EXPECT_EQ(a.suspended_mass_z_m, b.suspended_mass_z_m);
  EXPECT_EQ(a.drawbar_pull_N, b.drawbar_pull_N);
  EXPECT_EQ(a.driving_torque_Nm, b.driving_torque_Nm);
  EXPECT_EQ(a.spindle_support_force_N, b.spindle_support_force_N);
  EXPECT_EQ(a.drawbar_load_command_N, b.drawbar_load_command_N);
}

TEST(RigCheckpoint, ARunRestoredInAnyPhaseContinuesBitForBit) {
  const RunResult reference = run(-1);
  ASSERT_EQ(reference.phases.back(), Phase::test);
  // One stop in each phase: the first step of each phase, and one in its middle.
  std::vector<long long> stops;
  for (std::size_t k = 1; k < reference.phases.size(); ++k)
    if (reference.phases[k] != reference.phases[k - 1])
      stops.push_back(static_cast<long long>(k));
  ASSERT_EQ(stops.size(), 3u) << "release -> settle -> ramp -> test";
  for (long long s : std::vector<long long>(stops))
    stops.push_back(s - 7);
  stops.push_back(static_cast<long long>(reference.outputs.size()) - 5);
  for (long long stop : stops) {
    SCOPED_TRACE("checkpoint after step " + std::to_string(stop));
    const RunResult resumed = run(stop);
    ASSERT_EQ(resumed.outputs.size(), reference.outputs.size());
    for (std::size_t k = static_cast<std::size_t>(stop); k < resumed.outputs.size(); ++k)
      expect_same(resumed.outputs[k], reference.outputs[k]);
    EXPECT_EQ(resumed.findings, reference.findings);
    EXPECT_EQ(resumed.status, reference.status);
  }
}

TEST(RigCheckpoint, DamagedOrForeignFilesAreRefusedNamingTheProblem) {
  auto message = [](const std::string &text) {
    const std::string path = temp_path("bad.ckpt");
    std::ofstream(path) << text;
    try {
      CheckpointData::read(path);
    } catch (const CheckpointError &e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("hello\n").find("not a rig checkpoint"), std::string::npos);
  EXPECT_NE(message("wheelsim-rig-checkpoint 7\nend\n").find("format version 7"),
            std::string::npos);
  EXPECT_NE(message("wheelsim-rig-checkpoint 1\ni sim/steps 3\n").find("incomplete"),
            std::string::npos);
  EXPECT_NE(message("wheelsim-rig-checkpoint 1\nn sim/q 4 1 2\nend\n").find("line 2"),
            std::string::npos);
  const std::string path = temp_path("short.ckpt");
  std::ofstream(path) << "wheelsim-rig-checkpoint 1\ni sim/steps 3\nend\n";
  const RigConfig config = parse_rig_config(kConfig, "t.toml");
  RigSimulation sim(config);
  try {
    sim.restore_checkpoint(CheckpointData::read(path));
    FAIL() << "no error";
  } catch (const CheckpointError &e) {
    EXPECT_NE(std::string(e.what()).find("no number 'sim/q'"), std::string::npos) << e.what();
  }
  try {
    CheckpointData::read(temp_path("missing.ckpt"));
    FAIL() << "no error";
  } catch (const CheckpointError &e) {
    EXPECT_NE(std::string(e.what()).find("cannot read the rig checkpoint"), std::string::npos);
  }
}

TEST(RigCheckpoint, NumbersAndTextsRoundTripExactly) {
  CheckpointData data;
  data.set_numbers("x", {0.1, -1.0 / 3.0, 1e-300, 6.02214076e23, 0.0});
  data.set_text("t", "two\nlines \\ and a backslash");
  data.set_integer("i", -1234567890123LL);
  const std::string path = temp_path("round.ckpt");
  data.write(path);
  const CheckpointData back = CheckpointData::read(path);
  EXPECT_EQ(back.numbers("x"), data.numbers("x"));
  EXPECT_EQ(back.text("t"), data.text("t"));
  EXPECT_EQ(back.integer("i"), data.integer("i"));
  EXPECT_FALSE(std::filesystem::exists(path + ".writing"));
}

} // namespace
} // namespace wheelsim::rig
