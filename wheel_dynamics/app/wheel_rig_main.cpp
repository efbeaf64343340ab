// wheel-rig: the multibody test rig process. Reads a rig config (TOML, docs/rig-config.md), runs
// the rig on its terrain — in-process (flat; scm: the SCM soft soil, docs/scm.md) or remote (dem:
// LIGGGHTS with fix wheel/cosim 'motion coupled', over ZeroMQ, docs/coupling-protocol.md) — and
// writes the HDF5 run file (docs/hdf5-layout.md), with a progress line on the terminal.
//
//   wheel-rig --config rig.toml [--out run.h5] [--endpoint ipc:///tmp/x.sock]
//             [--surface-height Z] [--quiet] [--checkpoint-dir DIR [--checkpoint-every-steps N]
//             [--checkpoint-every-seconds S] [--inputs-hash H]] [--resume DIR/rig-STEP.ckpt]
//   wheel-rig --config rig.toml --check      (validate as a run would; no run, no run file)
//   wheel-rig --list-keys                    (the config schema as JSON, config_schema.h)
//
// Exit status (wheelsim/cli.h): 0 finished (or --check: valid; --help, --version), 1 error while
// running (the message names the side and what failed), 2 bad command line or config (the
// message names the option or the key). The run file is closed on every error; a signal ends the
// process at once and the file keeps what was flushed (every [output] flush_interval recorded
// steps).
#include "progress.h"
#include "run_recorder.h"
#include "terrain_snapshots.h"

#include "coupler/coupling.h"
#include "coupler/pose_messages.h"
#include "coupler/transport.h"
#include "wheelsim/cli.h"
#include "wheelsim/rig/checkpoint.h"
#include "wheelsim/rig/config_schema.h"
#include "wheelsim/rig/rig_config.h"
#include "wheelsim/rig/rig_simulation.h"
#include "wheelsim/rig/run_health.h"
#include "wheelsim/rig/terrain_registry.h"
#include "wheelsim/rig/time_step.h"
#include "wheelsim/run_file/run_file.h"
#include "wheelsim_version.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

namespace {

using namespace wheelsim;

// Rounded up: a timeout under a millisecond must not become 0 ms (a receive that fails at once).
std::chrono::milliseconds millis(double seconds) {
  return std::chrono::ceil<std::chrono::milliseconds>(std::chrono::duration<double>(seconds));
}

/// Advances the rig one step at a time with the run's health checks (docs/run-health.md) and
/// records every output.every-th step, with `step_offset` added to the rig's step.
struct Sink {
  rig::RunRecorder &recorder;
  rig::ProgressLine &progress;
  rig::RigSimulation &sim;
  rig::RunHealth &health;
  long long every;
  std::int64_t &step_offset; ///< LIGGGHTS' start step in a DEM run, else 0
  /// One step with the terrain's wrench at the current state and its contact count.
  const rig::RigOutputs &advance(const WheelWrench &wrench, double contacts) {
    health.before_step(wrench);
    const rig::RigOutputs &o = sim.advance(wrench);
    health.after_step(o, contacts);
    if (o.step % every == 0)
      recorder.record(step_offset + o.step, o, contacts);
    progress.update(sim, o);
    return o;
  }
};

/// /parameters of the run file, for the terrain registry's entries.
class RunFileParameters : public rig::ParameterSink {
public:
  explicit RunFileParameters(runfile::RunFile &file) : file_(file) {}
  void number(const std::string &name, double value, const std::string &unit) override {
    file_.set_parameter(name, value, unit);
  }
  void text(const std::string &name, const std::string &value) override {
    file_.set_parameter(name, value);
  }
  void long_text(const std::string &name, const std::string &text) override {
    file_.set_parameter_text(name, text);
  }

private:
  runfile::RunFile &file_;
};

/// An in-process terrain of the registry (flat, scm): built by its factory, its /parameters
/// written, stepped once per rig step; terrains with a height grid get /terrain snapshots.
void run_in_process(const rig::TerrainKind &kind, Sink &sink, runfile::RunFile &file) {
  rig::RigSimulation &sim = sink.sim;
  const rig::RigConfig &config = sim.config();
  const std::unique_ptr<rig::Terrain> ground = kind.make(config, sim.wheel());
  RunFileParameters parameters(file);
  if (kind.start)
    kind.start(config, *ground, parameters, sink.health);
  std::optional<rig::TerrainSnapshots> snapshots;
  if (ground->height_grid())
    snapshots.emplace(config.terrain.scm, file);
  while (!sim.finished()) {
    const WheelWrench wrench = ground->contact(sim.wheel_state(), sim.time_s());
    const rig::RigOutputs &o = sink.advance(wrench, ground->contact_count());
    if (snapshots)
      snapshots->after_step(*ground->height_grid(), o.step, o.time_s);
  }
  if (snapshots)
    snapshots->at_end(*ground->height_grid(), sim.step(), sim.time_s());
}

/// What moves the wheel in a DEM run: the rig (normal use) or a fixed twist (--kinematic).
class DemDriver {
public:
  virtual ~DemDriver() = default;
  /// Called once with LIGGGHTS' Hello; returns the wheel state (world frame) for its start step.
  virtual coupler::WheelState start(const coupler::Hello &hello) = 0;
  /// Advances one step with the wrench of the current step; returns the new state.
  virtual coupler::WheelState advance(const WheelWrench &wrench, double contacts) = 0;
  virtual bool finished() const = 0;
  virtual std::string where() const = 0; ///< "t = ... s (phase)" for messages
  /// Where the origin of the recorded positions lies in LIGGGHTS' box [m]: box = recorded +
  /// origin (valid once start() has run). Zero where the driver records in the box frame.
  virtual Eigen::Vector3d origin_in_box() const { return Eigen::Vector3d::Zero(); }
};

/// The rig. Its x and y are measured from the wheel's initial position in LIGGGHTS' box.
class RigDriver : public DemDriver {
public:
  /// `resumed`: the checkpoint the rig was restored from (its state is in `sim` already), or null.
  RigDriver(rig::RigSimulation &sim, Sink &sink, const rig::CheckpointData *resumed)
      : sim_(sim), sink_(sink), resumed_(resumed) {}
  coupler::WheelState start(const coupler::Hello &hello) override {
    if (resumed_) { // LIGGGHTS must start from the restart file of the same step
      const std::int64_t step = resumed_->integer("coupling/liggghts_step");
      if (hello.start_step != step)
        throw coupler::ProtocolError("checkpoint mismatch: LIGGGHTS starts at step " +
                                     std::to_string(hello.start_step) + ", the rig's checkpoint " +
                                     resumed_->source() + " is at step " + std::to_string(step) +
                                     "; resume both halves of one checkpoint (liggghts-" +
                                     std::to_string(step) + ".restart)");
      const std::int64_t every = resumed_->integer("coupling/exchange_every");
      if (hello.exchange_every != every)
        throw coupler::ProtocolError("checkpoint mismatch: LIGGGHTS exchanges every " +
                                     std::to_string(hello.exchange_every) +
                                     " steps, the checkpoint's run every " + std::to_string(every));
      const std::vector<double> &o = resumed_->numbers("coupling/offset");
      offset_ = Eigen::Vector3d(o.at(0), o.at(1), o.at(2));
      sink_.step_offset = resumed_->integer("coupling/step_offset");
      return message();
    }
    const WheelPose initial = coupler::from_message(hello);
    offset_ = Eigen::Vector3d(initial.p_WB_W.x(), initial.p_WB_W.y(), 0.0);
    sink_.step_offset = hello.start_step;
    return message();
  }
  /// The rig frame's origin in LIGGGHTS' box (x, y of the wheel's initial position).
  const Eigen::Vector3d &offset() const { return offset_; }
  Eigen::Vector3d origin_in_box() const override { return offset_; }
  coupler::WheelState advance(const WheelWrench &wrench, double contacts) override {
    sink_.advance(wrench, contacts);
    return message();
  }
  bool finished() const override { return sim_.finished(); }
  std::string where() const override {
    std::ostringstream out;
    out << "t = " << sim_.time_s() << " s (" << rig::to_string(sim_.phase()) << " phase)";
    return out.str();
  }

private:
  /// The rig's state in LIGGGHTS' world frame (rig frame + offset), as a wire message.
  coupler::WheelState message() const {
    WheelPose pose = sim_.wheel_state();
    pose.p_WB_W += offset_;
    pose.q_WB.normalize();
    return coupler::to_message(pose);
  }

  rig::RigSimulation &sim_;
  Sink &sink_;
  const rig::CheckpointData *resumed_;
  Eigen::Vector3d offset_ = Eigen::Vector3d::Zero();
};

/// When to checkpoint and where (docs/coupled-runs.md, "Checkpoint and resume").
struct CheckpointSettings {
  std::string dir;           ///< empty: no checkpoints
  long long every_steps = 0; ///< LIGGGHTS steps between checkpoints (0: by wall time only)
  double every_s = 600.0;    ///< wall time between checkpoints [s] (0: by steps only)
  std::string inputs_hash = "none";
  /// The run's wall time before this session (a resumed run: the checkpoint's) [s], and this
  /// session's start: each checkpoint records their sum as the run's wall time so far.
  double wall_before_s = 0.0;
  std::chrono::steady_clock::time_point wall_start = std::chrono::steady_clock::now();
};

/// Decides when both sides checkpoint (the rig sets kPoseCheckpointNext on a Pose: both save the
/// next exchange step) and writes the rig's half: DIR/rig-<step>.ckpt with the rig's and the
/// health checks' state, the coupling's offsets, and the run file committed up to that step.
class Checkpointer {
public:
  Checkpointer(const CheckpointSettings &settings, Sink &sink, runfile::RunFile &file,
               const RigDriver &driver)
      : settings_(settings), sink_(sink), file_(file), driver_(driver),
        last_wall_(std::chrono::steady_clock::now()) {}
  /// Called once the coupling starts at LIGGGHTS step `start_step`.
  void start(std::int64_t start_step) { last_step_ = start_step; }
  /// Before sending the Pose of `pose_step`: true if it should carry kPoseCheckpointNext (then
  /// the checkpoint is at pose_step + every).
  bool due(std::int64_t pose_step, int every) {
    if (pending_ >= 0)
      return false;
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - last_wall_).count();
    const bool by_steps =
        settings_.every_steps > 0 && pose_step + every - last_step_ >= settings_.every_steps;
    const bool by_wall = settings_.every_s > 0.0 && wall >= settings_.every_s;
    if (!by_steps && !by_wall)
      return false;
    pending_ = pose_step + every;
    return true;
  }
  std::int64_t pending() const { return pending_; }
  /// The rig's half of the checkpoint at LIGGGHTS step `step` (the rig's state is that step's).
  void write(std::int64_t step, int every, bool quiet) {
    file_.flush(); // rows before `step` committed: a resume keeps exactly those
    rig::CheckpointData data;
    data.set_text("program",
                  std::string("wheel-rig ") + WHEELSIM_VERSION + " " + WHEELSIM_GIT_REVISION);
    data.set_integer("coupling/liggghts_step", step);
    data.set_integer("coupling/step_offset", sink_.step_offset);
    data.set_integer("coupling/exchange_every", every);
    const Eigen::Vector3d &o = driver_.offset();
    data.set_numbers("coupling/offset", {o.x(), o.y(), o.z()});
    data.set_text("inputs_hash", settings_.inputs_hash);
    data.set_text("rig_config", sink_.sim.config().text);
    data.set_number("run/dt", sink_.sim.config().run.dt_s);
    data.set_text("run_file/path", file_.path());
    data.set_integer("run_file/before_step", step);
    data.set_number(
        "run/wall_time",
        settings_.wall_before_s +
            std::chrono::duration<double>(std::chrono::steady_clock::now() - settings_.wall_start)
                .count());
    sink_.sim.save_checkpoint(data);
    sink_.health.save_checkpoint(data);
    const std::string path = settings_.dir + "/rig-" + std::to_string(step) + ".ckpt";
    data.write(path);
    // Keep the newest two (LIGGGHTS keeps its two as well): a kill while one side writes the
    // next one leaves the previous pair complete.
    written_.push_back(path);
    while (written_.size() > 2) {
      std::remove(written_.front().c_str());
      written_.erase(written_.begin());
    }
    pending_ = -1;
    last_step_ = step;
    last_wall_ = std::chrono::steady_clock::now();
    if (!quiet)
      std::printf("wheel-rig: checkpoint %s at step %lld (t = %.6g s, %s phase)\n", path.c_str(),
                  static_cast<long long>(step), sink_.sim.time_s(),
                  rig::to_string(sink_.sim.phase()));
  }

private:
  CheckpointSettings settings_;
  Sink &sink_;
  runfile::RunFile &file_;
  const RigDriver &driver_;
  std::chrono::steady_clock::time_point last_wall_;
  std::int64_t last_step_ = 0;
  std::int64_t pending_ = -1;
  std::vector<std::string> written_;
};

/// --kinematic: the wheel follows a fixed twist from LIGGGHTS' initial pose, integrated by
/// integrate_pose as fix wheel/cosim's `motion prescribed` is (p += v dt; q <- exp(w dt) q), so a
/// coupled run can be compared with a prescribed one. Records the pose and the contact wrench only.
class KinematicDriver : public DemDriver {
public:
  KinematicDriver(const Eigen::Vector3d &v, const Eigen::Vector3d &w, double dt,
                  runfile::RunFile &file)
      : dt_(dt), position_(&file.observable("wheel/position", "m", 3)),
        orientation_(&file.observable("wheel/orientation", "1", 4)),
        force_(&file.observable("contact/force", "N", 3)),
        torque_(&file.observable("contact/torque", "N m", 3)),
        count_(&file.observable("contact/count", "1", 1)) {
    pose_.v_WB_W = v;
    pose_.w_WB_W = w;
  }
  coupler::WheelState start(const coupler::Hello &hello) override {
    const WheelPose initial = coupler::from_message(hello);
    pose_.p_WB_W = initial.p_WB_W;
    pose_.q_WB = initial.q_WB;
    step_ = hello.start_step;
    return coupler::to_message(pose_);
  }
  coupler::WheelState advance(const WheelWrench &wrench, double contacts) override {
    const double t = step_ * dt_;
    const Eigen::Vector3d &p_WB_W = pose_.p_WB_W;
    const Eigen::Quaterniond &q_WB = pose_.q_WB;
    const double p[3] = {p_WB_W.x(), p_WB_W.y(), p_WB_W.z()},
                 q[4] = {q_WB.w(), q_WB.x(), q_WB.y(), q_WB.z()};
    const double f[3] = {wrench.f_B_W.x(), wrench.f_B_W.y(), wrench.f_B_W.z()};
    const double tq[3] = {wrench.t_B_W.x(), wrench.t_B_W.y(), wrench.t_B_W.z()};
    position_->append(step_, t, p);
    orientation_->append(step_, t, q);
    force_->append(step_, t, f);
    torque_->append(step_, t, tq);
    count_->append(step_, t, contacts);
    pose_ = integrate_pose(pose_, dt_);
    ++step_;
    return coupler::to_message(pose_);
  }
  bool finished() const override { return false; } // until LIGGGHTS closes
  std::string where() const override { return "step " + std::to_string(step_); }

private:
  double dt_;
  runfile::TimeSeries *position_, *orientation_, *force_, *torque_, *count_;
  WheelPose pose_; ///< LIGGGHTS' world frame; the twist is the fixed one
  std::int64_t step_ = 0;
};

/// The remote DEM terrain: LIGGGHTS' fix wheel/cosim connects to us.
void run_dem(const rig::RigConfig &config, DemDriver &driver, runfile::RunFile &file, bool quiet,
             Checkpointer *checkpointer = nullptr) {
  const rig::TerrainConfig &terrain = config.terrain;
  coupler::Timeouts timeouts;
  timeouts.step = millis(terrain.timeout_s);
  timeouts.handshake = std::max(timeouts.step, millis(60.0));
  coupler::CouplingServer server(coupler::ZmqTransport::bind(terrain.endpoint, "LIGGGHTS"),
                                 timeouts);
  if (!quiet)
    std::printf("wheel-rig: waiting for LIGGGHTS at %s (%.0f s)\n", terrain.endpoint.c_str(),
                timeouts.handshake.count() / 1000.0);
  const coupler::Hello hello = server.accept(config.run.dt_s);
  const int every = static_cast<int>(hello.exchange_every);
  if (!file.has_parameter("coupling/start_step")) { // a resumed file has the first start's
    file.set_parameter("coupling/start_step", static_cast<std::int64_t>(hello.start_step), "1");
    file.set_parameter("coupling/exchange_every", static_cast<std::int64_t>(every), "1");
    file.set_parameter("coupling/dt", hello.dt_s, "s");
    file.set_parameter("coupling/endpoint", terrain.endpoint);
  }
  coupler::Welcome welcome;
  welcome.start_step = hello.start_step;
  welcome.dt_s = hello.dt_s;
  try {
    welcome.state = driver.start(hello);
  } catch (const coupler::ProtocolError &e) { // LIGGGHTS stops with the same text
    server.close(coupler::CloseReason::ProtocolError, e.what());
    throw;
  }
  server.welcome(welcome);
  // The positions' frame (docs/hdf5-layout.md): the rig records x and y from the wheel's start
  // in the box, so a reader needs the start to place the wheel in the bin (a resumed file has it).
  if (!file.has_parameter("coupling/origin_x")) {
    const Eigen::Vector3d origin = driver.origin_in_box();
    file.set_parameter("coupling/origin_x", origin.x(), "m");
    file.set_parameter("coupling/origin_y", origin.y(), "m");
  }
  if (checkpointer)
    checkpointer->start(hello.start_step);
  if (!quiet)
    std::printf("wheel-rig: LIGGGHTS connected (start step %lld, dt %g s, exchange every %d)\n",
                static_cast<long long>(hello.start_step), hello.dt_s, every);
  for (;;) {
    auto message = server.receive();
    if (const auto *close = std::get_if<coupler::Close>(&message)) {
      if (close->reason == coupler::CloseReason::Finished) {
        if (!quiet)
          std::printf("wheel-rig: LIGGGHTS finished its run at %s\n", driver.where().c_str());
        return;
      }
      throw std::runtime_error("LIGGGHTS closed the coupling (" + to_string(close->reason) +
                               "): " + close->message());
    }
    const coupler::Wrench &w = std::get<coupler::Wrench>(message);
    const WheelWrench wrench = coupler::from_message(w);
    coupler::Pose pose;
    pose.step = w.step + every;
    for (int k = 0; k < every && !driver.finished(); ++k)
      pose.state = driver.advance(wrench, static_cast<double>(w.n_contacts));
    if (driver.finished()) {
      const std::string text = "finished: the rig's test phase ended at " + driver.where();
      server.close(coupler::CloseReason::Finished, text);
      if (!quiet)
        std::printf("wheel-rig: %s; told LIGGGHTS to stop\n", text.c_str());
      return;
    }
    if (checkpointer && checkpointer->pending() == pose.step)
      checkpointer->write(pose.step, every, quiet);
    if (checkpointer && checkpointer->due(pose.step, every))
      pose.flags |= coupler::kPoseCheckpointNext;
    try {
      server.send_pose(pose);
    } catch (const coupler::PeerClosedError &e) {
      if (e.reason() != coupler::CloseReason::Finished)
        throw;
      if (!quiet) // LIGGGHTS ended its run after its last Wrench without waiting for this Pose
        std::printf("wheel-rig: LIGGGHTS finished its run at %s\n", driver.where().c_str());
      return;
    }
  }
}

/// /parameters nowhere: --check starts the terrain as a run does, without a run file.
class NoParameters : public rig::ParameterSink {
public:
  void number(const std::string &, double, const std::string &) override {}
  void text(const std::string &, const std::string &) override {}
  void long_text(const std::string &, const std::string &) override {}
};

/// --check: what a run builds from its config before its first step, without running it: the rig
/// (the wheel: mesh loaded and checked, mass properties, release position), the in-process
/// terrain (SCM: soil file, grid and domain) and its start with the run health's setup checks
/// (SCM: grid_coarse); and the time step against the rig's stability bound (time_step.h), which a
/// run leaves to its health checks. Throws rig::RigConfigError naming the key; `dt_name` is how the
/// time step was given ("run.dt" or "--dt").
void check_run_inputs(const rig::RigConfig &config, const std::string &dt_name) {
  rig::RigSimulation sim(config);
  if (const rig::TerrainKind &kind = rig::terrain_kind(config.terrain.type); kind.make) {
    const std::unique_ptr<rig::Terrain> terrain = kind.make(config, sim.wheel());
    NoParameters parameters;
    rig::RunHealth health(sim, nullptr);
    try {
      if (kind.start)
        kind.start(config, *terrain, parameters, health);
    } catch (const rig::RunHealthError &e) { // a run would stop here, before its first step
      throw rig::RigConfigError(config.source + ": " + e.what());
    }
  }
  rig::check_time_step(config, sim.rig(), dt_name);
}

/// Runs the rig on the terrain of `config` (or the --kinematic twist) to its end.
void run_terrain(const rig::RigConfig &config, const std::vector<double> &kinematic, Sink &sink,
                 runfile::RunFile &file, bool quiet, const CheckpointSettings &checkpoints,
                 const rig::CheckpointData *resumed) {
  if (!kinematic.empty()) {
    KinematicDriver driver(Eigen::Vector3d(kinematic[0], kinematic[1], kinematic[2]),
                           Eigen::Vector3d(kinematic[3], kinematic[4], kinematic[5]),
                           config.run.dt_s, file);
    std::ostringstream twist;
    for (double value : kinematic)
      twist << (twist.tellp() > 0 ? " " : "") << value;
    file.set_parameter("kinematic_twist", twist.str() + " (vx vy vz [m/s] wx wy wz [rad/s])");
    run_dem(config, driver, file, quiet);
  } else if (const rig::TerrainKind &kind = rig::terrain_kind(config.terrain.type); kind.make) {
    run_in_process(kind, sink, file);
  } else { // the remote terrain: LIGGGHTS over the coupler
    RigDriver driver(sink.sim, sink, resumed);
    std::optional<Checkpointer> checkpointer;
    if (!checkpoints.dir.empty())
      checkpointer.emplace(checkpoints, sink, file, driver);
    run_dem(config, driver, file, quiet, checkpointer ? &*checkpointer : nullptr);
  }
}

} // namespace

int main(int argc, char **argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  CLI::App app{"wheel-rig: the multibody wheel test rig (docs/rig-config.md)"};
  std::string config_path, out_path, endpoint;
  std::optional<double> surface_height;
  bool quiet = false;
  std::vector<double> kinematic;
  std::vector<std::string> parameters;
  bool check = false;
  std::optional<double> dt;
  bool list_keys = false;
  CheckpointSettings checkpoints;
  std::string resume_path;
  app.add_option("--config", config_path, "rig configuration (TOML); required unless --list-keys");
  app.add_option("--out", out_path, "HDF5 run file (default: [output] file of the config)");
  app.add_option("--endpoint", endpoint,
                 "coupling endpoint for terrain type dem (overrides [terrain] endpoint)");
  app.add_option("--surface-height", surface_height,
                 "undisturbed soil surface height [m] (overrides [terrain] surface_height)");
  app.add_option("--dt", dt,
                 "time step [s] (overrides [run] dt; scripts/wheel-cosim passes the bed's LIGGGHTS "
                 "time step when the rig config leaves run.dt out)");
  app.add_flag("--quiet", quiet, "no progress lines");
  app.add_option("--kinematic", kinematic,
                 "DEM test mode: the wheel follows the fixed twist vx vy vz [m/s] wx wy wz "
                 "[rad/s] (world frame) from LIGGGHTS' initial pose; the rig model is not used")
      ->expected(6);
  app.add_option("--parameter", parameters,
                 "KEY=VALUE stored as /parameters/KEY of the run file (repeatable; the launcher "
                 "records the LIGGGHTS side: deck, command line, bed, soil, mesh and its hash)");
  app.add_flag("--check", check,
               "only check: load and validate the config with the other options exactly as a run "
               "would (keys, wheel mesh, SCM soil file, DEM endpoint), print 'CONFIG: ok' (nothing "
               "with --quiet); exit 0 if valid, 2 naming the key if not; runs nothing, writes no "
               "run file");
  app.add_flag("--list-keys", list_keys,
               "print the rig config's schema as JSON (every table.key with its type, unit, "
               "default, range and the terrain type or carriage mode it applies to) and exit 0");
  app.add_option("--checkpoint-dir", checkpoints.dir,
                 "DEM runs: write checkpoints (rig-<step>.ckpt; LIGGGHTS writes liggghts-<step>."
                 "restart beside them with fix wheel/cosim's 'checkpoint DIR') into this existing "
                 "directory; docs/coupled-runs.md \"Checkpoint and resume\"");
  app.add_option("--checkpoint-every-steps", checkpoints.every_steps,
                 "LIGGGHTS steps between checkpoints (default 0: by wall time only)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--checkpoint-every-seconds", checkpoints.every_s,
                 "wall time between checkpoints [s] (default 600; 0: by steps only)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--inputs-hash", checkpoints.inputs_hash,
                 "a word identifying the run's inputs, stored in each checkpoint and compared on "
                 "--resume (scripts/wheel-cosim passes a sha256 of them)");
  app.add_option("--resume", resume_path,
                 "continue the run from this checkpoint (DIR/rig-<step>.ckpt) with LIGGGHTS "
                 "restarted from DIR/liggghts-<step>.restart: the run file (--out) keeps its rows "
                 "before that step and goes on");
  cli::setup(app, "wheel-rig");
  if (const auto status = cli::parse(app, argc, argv))
    return *status;
  if (list_keys) {
    std::fputs(rig::rig_config_schema_json().c_str(), stdout);
    return cli::kExitSuccess;
  }
  if (config_path.empty())
    return cli::report_usage_error("wheel-rig", "--config is required");

  rig::RigConfig config;
  try {
    config = rig::load_rig_config(config_path);
    // The options get the checks their config keys get (a bad value is named, also by --check).
    if (app.count("--out") && out_path.empty())
      throw cli::UsageError("--out expects a run file path, got ''");
    if (!out_path.empty())
      config.output.file = out_path;
    if (app.count("--endpoint") && endpoint.rfind("ipc://", 0) != 0 &&
        endpoint.rfind("tcp://", 0) != 0)
      throw cli::UsageError("--endpoint must start with ipc:// or tcp://, got '" + endpoint + "'");
    if (!endpoint.empty())
      config.terrain.endpoint = endpoint;
    if (surface_height && !std::isfinite(*surface_height))
      throw cli::UsageError("--surface-height must be a finite height [m], got " +
                            std::to_string(*surface_height));
    if (surface_height)
      config.terrain.surface_height_m = *surface_height;
    for (double v : kinematic)
      if (!std::isfinite(v))
        throw cli::UsageError("--kinematic expects six finite numbers (vx vy vz [m/s] wx wy wz "
                              "[rad/s]), got a non-finite one");
    if (!resume_path.empty() && !std::filesystem::is_regular_file(resume_path))
      throw cli::UsageError("--resume: checkpoint '" + resume_path + "' not found");
    if (dt && !(*dt > 0.0 && std::isfinite(*dt)))
      throw cli::UsageError("--dt must be a time step > 0 s, got " + std::to_string(*dt));
    if (dt)
      config.run.dt_s = *dt;
    else if (config.run.dt_s == 0.0 && !check)
      throw rig::RigConfigError(config_path + ": run.dt is not set: a DEM run takes the bed's "
                                              "time step from --dt (scripts/wheel-cosim passes it "
                                              "from the bed's .vars), or set [run] dt");
    if (config.terrain.type == rig::TerrainType::dem && config.terrain.endpoint.empty())
      throw rig::RigConfigError(config_path +
                                ": terrain.type = \"dem\" needs terrain.endpoint (or --endpoint)");
    if (!kinematic.empty() && config.terrain.type != rig::TerrainType::dem)
      throw cli::UsageError("--kinematic needs terrain.type = \"dem\" (" + config_path + ")");
    for (const std::string &p : parameters)
      if (p.find('=') == std::string::npos || p.find('=') == 0)
        throw cli::UsageError("--parameter expects KEY=VALUE, got '" + p + "'");
    if ((!checkpoints.dir.empty() || !resume_path.empty()) &&
        (config.terrain.type != rig::TerrainType::dem || !kinematic.empty()))
      throw cli::UsageError("--checkpoint-dir and --resume need terrain.type = \"dem\" and the "
                            "rig model (not --kinematic)");
    if (!checkpoints.dir.empty() && !std::filesystem::is_directory(checkpoints.dir))
      throw cli::UsageError("--checkpoint-dir: '" + checkpoints.dir +
                            "' is not a directory (create it first)");
    if (!checkpoints.dir.empty() && checkpoints.every_steps == 0 && checkpoints.every_s == 0.0)
      throw cli::UsageError("--checkpoint-every-steps and --checkpoint-every-seconds are both 0: "
                            "give one > 0, or leave --checkpoint-dir out");
    if (check) {
      check_run_inputs(config, dt ? "--dt" : "run.dt");
      if (!quiet)
        std::printf("%s: ok\n", config_path.c_str());
      return cli::kExitSuccess;
    }
  } catch (const cli::UsageError &e) {
    return cli::report_usage_error("wheel-rig", e.what());
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wheel-rig: %s\n", e.what());
    return cli::kExitUsage;
  }

  std::unique_ptr<runfile::RunFile> file;
  int status = 0;
  const auto wall_start = std::chrono::steady_clock::now(); // the run's cost: run/wall_time
  checkpoints.wall_start = wall_start;
  std::string resume_key; // "resume/<k>/" of this session when resumed
  try {
    rig::RigSimulation sim(config);
    runfile::FlushPolicy flush;
    flush.write_every_rows = config.output.flush_interval;
    // --resume: the checkpoint must be of this run (same rig config, same inputs, same dt).
    std::optional<rig::CheckpointData> resumed;
    if (!resume_path.empty()) {
      resumed = rig::CheckpointData::read(resume_path);
      if (resumed->text("rig_config") != config.text)
        throw rig::RigConfigError("--resume: the rig config " + config_path +
                                  " differs from the one the checkpoint " + resume_path +
                                  " was written with (resume with the same config)");
      if (resumed->text("inputs_hash") != checkpoints.inputs_hash)
        throw rig::RigConfigError("--resume: the checkpoint " + resume_path +
                                  " was written with inputs hash " + resumed->text("inputs_hash") +
                                  ", this run has " + checkpoints.inputs_hash +
                                  " (an input changed since)");
      if (resumed->number("run/dt") != config.run.dt_s)
        throw rig::RigConfigError("--resume: the checkpoint's time step " +
                                  std::to_string(resumed->number("run/dt")) + " s differs from " +
                                  std::to_string(config.run.dt_s) + " s");
      sim.restore_checkpoint(*resumed);
      file = std::make_unique<runfile::RunFile>(
          config.output.file, runfile::RunFile::Resume{resumed->integer("run_file/before_step")},
          flush);
    } else {
      file = std::make_unique<runfile::RunFile>(
          config.output.file,
          runfile::Creator{"wheel-rig", WHEELSIM_VERSION, WHEELSIM_GIT_REVISION}, flush);
    }
    std::ostringstream command;
    for (int i = 0; i < argc; ++i)
      command << (i ? " " : "") << argv[i];
    if (resumed) { // provenance: resume/<k>/..., k = 1, 2, ... in the order of the resumes
      int k = 1;
      while (file->has_parameter("resume/" + std::to_string(k) + "/step"))
        ++k;
      const std::string key = "resume/" + std::to_string(k) + "/";
      resume_key = key;
      if (resumed->has("run/wall_time"))
        checkpoints.wall_before_s = resumed->number("run/wall_time");
      file->set_parameter(key + "step", resumed->integer("coupling/liggghts_step"), "1");
      file->set_parameter(key + "time", sim.time_s(), "s");
      file->set_parameter(key + "phase", rig::to_string(sim.phase()));
      file->set_parameter(key + "checkpoint", resume_path);
      file->set_parameter(key + "command_line", command.str());
      file->set_parameter(key + "git_revision", WHEELSIM_GIT_REVISION);
      for (const std::string &p : parameters) { // the launcher's values of this start
        const auto eq = p.find('=');
        if (!file->has_parameter(p.substr(0, eq)))
          file->set_parameter(p.substr(0, eq), p.substr(eq + 1));
      }
    } else {
      file->set_parameter_text("rig_config", config.text);
      file->set_parameter("rig_config_file", config.source);
      file->set_parameter("command_line", command.str());
      file->set_parameter("wheel/mass", sim.wheel().mass_kg, "kg");
      file->set_parameter("wheel/axle_inertia", sim.wheel().axle_inertia_kg_m2, "kg m^2");
      file->set_parameter("wheel/effective_radius", sim.wheel().effective_radius_m, "m");
      file->set_parameter("wheel/rim_radius", sim.wheel().rim_radius_m, "m");
      if (sim.wheel().width_m > 0.0)
        file->set_parameter("wheel/width", sim.wheel().width_m, "m");
      file->set_parameter("wheel/source", sim.wheel().source);
      if (sim.wheel().lug_count > 0) { // from the mesh's props file (post-processing's window)
        file->set_parameter("wheel/lug_count", std::int64_t{sim.wheel().lug_count}, "1");
        file->set_parameter("wheel/lug_width", sim.wheel().lug_width_m, "m");
        file->set_parameter("wheel/lug_height", sim.wheel().lug_height_m, "m");
      }
      file->set_parameter("terrain/surface_height", config.terrain.surface_height_m, "m");
      file->set_parameter("run/dt", config.run.dt_s, "s");
      file->set_parameter("run/dt_source", dt ? "--dt (scripts/wheel-cosim: the bed's time step)"
                                              : "the rig config's run.dt");
      for (const std::string &p : parameters) {
        const auto eq = p.find('='); // KEY=VALUE, checked before the run
        file->set_parameter(p.substr(0, eq), p.substr(eq + 1));
      }
      if (!checkpoints.dir.empty()) {
        file->set_parameter("checkpoint/dir", checkpoints.dir);
        file->set_parameter("checkpoint/every_steps",
                            static_cast<std::int64_t>(checkpoints.every_steps), "1");
        file->set_parameter("checkpoint/every_seconds", checkpoints.every_s, "s");
        file->set_parameter("checkpoint/inputs_hash", checkpoints.inputs_hash);
      }
    }

    // Run health (docs/run-health.md): findings go to the terminal and to /health as they come.
    const bool checked = kinematic.empty(); // --kinematic has no rig to check
    std::int64_t step_offset = 0;
    rig::RunHealth health(sim, [&](const rig::HealthFinding &f) {
      std::fprintf(stderr, "wheel-rig: health %s [%s]: %s\n", rig::to_string(f.severity),
                   f.code.c_str(), f.message.c_str());
      file->add_health_finding(
          {step_offset + f.step, f.time_s, f.code, rig::to_string(f.severity), f.message});
    });
    if (checked && file->has_health()) // resumed: its findings before the checkpoint stay
      file->set_health_status("running");
    else if (checked)
      file->begin_health("running");
    if (resumed)
      health.restore_checkpoint(*resumed);
    rig::RunRecorder recorder(*file);
    rig::ProgressLine progress(quiet ? 0.0 : config.output.progress_interval_s, stdout);
    Sink sink{recorder, progress, sim, health, std::max(1LL, config.output.every), step_offset};
    try {
      run_terrain(config, kinematic, sink, *file, quiet, checkpoints,
                  resumed ? &*resumed : nullptr);
      if (checked)
        health.finish();
    } catch (const rig::RunHealthError &) {
      file->set_health_status(health.status());
      throw;
    } catch (const std::exception &e) {
      if (checked) {
        health.run_failed(e.what());
        file->set_health_status(health.status());
      }
      throw;
    }
    if (checked) {
      file->set_health_status(health.status());
      if (health.has_error()) {
        std::fprintf(stderr,
                     "wheel-rig: error: the run is unhealthy (see the health lines above "
                     "and /health in %s)\n",
                     config.output.file.c_str());
        status = cli::kExitFailure;
      }
    }
    if (!quiet && kinematic.empty())
      std::printf("wheel-rig: done at t = %.4f s; run file %s\n", sim.time_s(),
                  config.output.file.c_str());
    else if (!quiet)
      std::printf("wheel-rig: done (kinematic); run file %s\n", config.output.file.c_str());
  } catch (const rig::RunHealthError &) { // its health line has been printed
    std::fprintf(stderr,
                 "wheel-rig: error: the run was stopped by its health check (/health in "
                 "%s)\n",
                 config.output.file.c_str());
    status = cli::kExitFailure;
  } catch (const rig::RigConfigError &e) { // the wheel or the terrain the config names
    std::fprintf(stderr, "wheel-rig: error: %s\n", e.what());
    status = cli::kExitUsage;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wheel-rig: error: %s\n", e.what());
    status = cli::kExitFailure;
  }
  try {
    if (file) {
      // Also for a failed run: what it cost until it stopped (docs/hdf5-layout.md).
      const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - wall_start;
      if (!resume_key.empty()) // this session's; the run's: the checkpoint's + this session's
        file->set_parameter(resume_key + "wall_time", wall.count(), "s");
      if (!file->has_parameter("run/wall_time")) // a stopped session that closed wrote it
        file->set_parameter("run/wall_time", checkpoints.wall_before_s + wall.count(), "s");
      file->close();
    }
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wheel-rig: error closing the run file: %s\n", e.what());
    status = status ? status : 1;
  }
  return status;
}
