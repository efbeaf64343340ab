// wheel-rig: the multibody test rig process. Reads a rig config (TOML, docs/rig-config.md), runs
// the rig on its terrain — in-process (flat; scm: the SCM soft soil, docs/scm.md) or remote (dem:
// LIGGGHTS with fix wheel/cosim 'motion coupled', over ZeroMQ, docs/coupling-protocol.md) — and
// writes the HDF5 run file (docs/hdf5-layout.md), with a progress line on the terminal.
//
//   wheel-rig --config rig.toml [--out run.h5] [--endpoint ipc:///tmp/x.sock]
//             [--surface-height Z] [--quiet]
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
#include "wheelsim/rig/config_schema.h"
#include "wheelsim/rig/rig_config.h"
#include "wheelsim/rig/rig_simulation.h"
#include "wheelsim/rig/run_health.h"
#include "wheelsim/rig/terrain_registry.h"
#include "wheelsim/run_file/run_file.h"
#include "wheelsim_version.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

namespace {

using namespace wheelsim;

std::chrono::milliseconds millis(double seconds) {
  return std::chrono::milliseconds(static_cast<long long>(seconds * 1000.0));
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
};

/// The rig. Its x and y are measured from the wheel's initial position in LIGGGHTS' box.
class RigDriver : public DemDriver {
public:
  RigDriver(rig::RigSimulation &sim, Sink &sink) : sim_(sim), sink_(sink) {}
  coupler::WheelState start(const coupler::Hello &hello) override {
    const WheelPose initial = coupler::from_message(hello);
    offset_ = Eigen::Vector3d(initial.p_WB_W.x(), initial.p_WB_W.y(), 0.0);
    sink_.step_offset = hello.start_step;
    return message();
  }
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
  Eigen::Vector3d offset_ = Eigen::Vector3d::Zero();
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
void run_dem(const rig::RigConfig &config, DemDriver &driver, runfile::RunFile &file, bool quiet) {
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
  file.set_parameter("coupling/start_step", static_cast<std::int64_t>(hello.start_step), "1");
  file.set_parameter("coupling/exchange_every", static_cast<std::int64_t>(every), "1");
  file.set_parameter("coupling/dt", hello.dt_s, "s");
  file.set_parameter("coupling/endpoint", terrain.endpoint);
  coupler::Welcome welcome;
  welcome.start_step = hello.start_step;
  welcome.dt_s = hello.dt_s;
  welcome.state = driver.start(hello);
  server.welcome(welcome);
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

/// --check: what a run builds from its config before its first step, without running it: the rig
/// (the wheel: mesh loaded and checked, mass properties, release position) and the in-process
/// terrain (SCM: soil file and grid). Throws rig::RigConfigError naming the key.
void check_run_inputs(const rig::RigConfig &config) {
  rig::RigSimulation sim(config);
  if (const rig::TerrainKind &kind = rig::terrain_kind(config.terrain.type); kind.make)
    kind.make(config, sim.wheel());
}

/// Runs the rig on the terrain of `config` (or the --kinematic twist) to its end.
void run_terrain(const rig::RigConfig &config, const std::vector<double> &kinematic, Sink &sink,
                 runfile::RunFile &file, bool quiet) {
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
    RigDriver driver(sink.sim, sink);
    run_dem(config, driver, file, quiet);
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
    if (!out_path.empty())
      config.output.file = out_path;
    if (!endpoint.empty())
      config.terrain.endpoint = endpoint;
    if (surface_height)
      config.terrain.surface_height_m = *surface_height;
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
    if (check) {
      check_run_inputs(config);
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
  try {
    rig::RigSimulation sim(config);
    runfile::FlushPolicy flush;
    flush.write_every_rows = config.output.flush_interval;
    file = std::make_unique<runfile::RunFile>(
        config.output.file, runfile::Creator{"wheel-rig", WHEELSIM_VERSION, WHEELSIM_GIT_REVISION},
        flush);
    file->set_parameter_text("rig_config", config.text);
    file->set_parameter("rig_config_file", config.source);
    std::ostringstream command;
    for (int i = 0; i < argc; ++i)
      command << (i ? " " : "") << argv[i];
    file->set_parameter("command_line", command.str());
    file->set_parameter("wheel/mass", sim.wheel().mass_kg, "kg");
    file->set_parameter("wheel/axle_inertia", sim.wheel().axle_inertia_kg_m2, "kg m^2");
    file->set_parameter("wheel/effective_radius", sim.wheel().effective_radius_m, "m");
    file->set_parameter("wheel/rim_radius", sim.wheel().rim_radius_m, "m");
    file->set_parameter("wheel/source", sim.wheel().source);
    file->set_parameter("terrain/surface_height", config.terrain.surface_height_m, "m");
    file->set_parameter("run/dt", config.run.dt_s, "s");
    file->set_parameter("run/dt_source", dt ? "--dt (scripts/wheel-cosim: the bed's time step)"
                                            : "the rig config's run.dt");
    for (const std::string &p : parameters) {
      const auto eq = p.find('='); // KEY=VALUE, checked before the run
      file->set_parameter(p.substr(0, eq), p.substr(eq + 1));
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
    if (checked)
      file->begin_health("running");
    rig::RunRecorder recorder(*file);
    rig::ProgressLine progress(quiet ? 0.0 : config.output.progress_interval_s, stdout);
    Sink sink{recorder, progress, sim, health, std::max(1LL, config.output.every), step_offset};
    try {
      run_terrain(config, kinematic, sink, *file, quiet);
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
      file->set_parameter("run/wall_time", wall.count(), "s");
      file->close();
    }
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wheel-rig: error closing the run file: %s\n", e.what());
    status = status ? status : 1;
  }
  return status;
}
