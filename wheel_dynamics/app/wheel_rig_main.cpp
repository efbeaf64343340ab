// wheel-rig: the multibody test rig process. Reads a rig config (TOML, docs/rig-config.md), runs
// the rig on its terrain — in-process (flat) or remote (dem: LIGGGHTS with fix wheel/cosim
// 'motion coupled', over ZeroMQ, docs/coupling-protocol.md) — and writes the HDF5 run file
// (docs/hdf5-layout.md), with a progress line on the terminal.
//
//   wheel-rig --config rig.toml [--out run.h5] [--endpoint ipc:///tmp/x.sock]
//             [--surface-height Z] [--quiet]
//
// Exit status: 0 finished, 1 error (the message names the side and what failed), 2 bad command
// line or config, 130 interrupted. The run file is closed (readable) in every case.
#include "progress.h"
#include "run_recorder.h"

#include "coupler/coupling.h"
#include "coupler/transport.h"
#include "wheelsim/rig/flat_ground.h"
#include "wheelsim/rig/rig_config.h"
#include "wheelsim/rig/rig_simulation.h"
#include "wheelsim/run_file/run_file.h"
#include "wheelsim_rig_version.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <variant>

namespace {

using namespace wheelsim;

std::atomic<int> g_signal{0};
extern "C" void on_signal(int signal_number) { g_signal = signal_number; }

struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void check_interrupt() {
  if (g_signal != 0)
    throw Interrupted("interrupted by signal " + std::to_string(g_signal.load()));
}

std::chrono::milliseconds millis(double seconds) {
  return std::chrono::milliseconds(static_cast<long long>(seconds * 1000.0));
}

/// Rig state (rig frame) -> wire state (LIGGGHTS world frame = rig frame + offset).
coupler::WheelState to_wire(const rig::WheelState &s, const Eigen::Vector3d &offset) {
  coupler::WheelState w;
  const Eigen::Vector3d p = s.p_WBo_W + offset;
  for (int k = 0; k < 3; ++k) {
    w.p_WC_W[k] = p[k];
    w.v_WC_W[k] = s.v_WBo_W[k];
    w.w_WB_W[k] = s.w_WB_W[k];
  }
  const Eigen::Quaterniond q = s.R_WB.normalized();
  w.q_WB = {q.w(), q.x(), q.y(), q.z()};
  return w;
}

/// Records every output.every-th step, with `step_offset` added to the rig's step.
struct Sink {
  rig::RunRecorder &recorder;
  rig::ProgressLine &progress;
  const rig::RigSimulation &sim;
  long long every;
  std::int64_t step_offset;
  void operator()(const rig::RigOutputs &o, double contacts) {
    if (o.step % every == 0)
      recorder.record(step_offset + o.step, o, contacts);
    progress.update(sim, o);
  }
};

/// The in-process flat ground.
void run_flat(rig::RigSimulation &sim, Sink &sink) {
  rig::FlatGround ground = rig::make_flat_ground(sim.config(), sim.wheel());
  while (!sim.finished()) {
    check_interrupt();
    const rig::RigOutputs &o = sim.advance(ground.contact(sim.wheel_state(), sim.time_s()));
    sink(o, 1.0);
  }
}

/// The remote DEM terrain: LIGGGHTS' fix wheel/cosim connects to us.
void run_dem(rig::RigSimulation &sim, Sink &sink, runfile::RunFile &file, bool quiet) {
  const rig::TerrainConfig &terrain = sim.config().terrain;
  coupler::Timeouts timeouts;
  timeouts.step = millis(terrain.timeout_s);
  timeouts.handshake = std::max(timeouts.step, millis(60.0));
  coupler::CouplingServer server(coupler::ZmqTransport::bind(terrain.endpoint, "LIGGGHTS"),
                                 timeouts);
  if (!quiet)
    std::printf("wheel-rig: waiting for LIGGGHTS at %s (%.0f s)\n", terrain.endpoint.c_str(),
                timeouts.handshake.count() / 1000.0);
  const coupler::Hello hello = server.accept(sim.config().run.dt_s);
  // The rig's x and y are measured from the wheel's initial position in LIGGGHTS' box.
  const Eigen::Vector3d offset(hello.p_WC_W[0], hello.p_WC_W[1], 0.0);
  const int every = static_cast<int>(hello.exchange_every);
  sink.step_offset = hello.start_step;
  file.set_parameter("coupling/start_step", static_cast<std::int64_t>(hello.start_step), "1");
  file.set_parameter("coupling/exchange_every", static_cast<std::int64_t>(every), "1");
  file.set_parameter("coupling/dt", hello.dt_s, "s");
  file.set_parameter("coupling/endpoint", terrain.endpoint);
  file.set_parameter("coupling/x_offset", offset.x(), "m");
  file.set_parameter("coupling/y_offset", offset.y(), "m");
  coupler::Welcome welcome;
  welcome.start_step = hello.start_step;
  welcome.dt_s = hello.dt_s;
  welcome.state = to_wire(sim.wheel_state(), offset);
  server.welcome(welcome);
  if (!quiet)
    std::printf("wheel-rig: LIGGGHTS connected (start step %lld, dt %g s, exchange every %d)\n",
                static_cast<long long>(hello.start_step), hello.dt_s, every);
  for (;;) {
    check_interrupt();
    auto message = server.receive();
    if (const auto *close = std::get_if<coupler::Close>(&message)) {
      if (close->reason == coupler::CloseReason::Finished) {
        if (!quiet)
          std::printf("wheel-rig: LIGGGHTS finished its run at t = %.4f s (%s phase)\n",
                      sim.time_s(), rig::to_string(sim.phase()));
        return;
      }
      throw std::runtime_error("LIGGGHTS closed the coupling (" + to_string(close->reason) +
                               "): " + close->message());
    }
    const coupler::Wrench &w = std::get<coupler::Wrench>(message);
    rig::ContactWrench wrench;
    wrench.force_N = Eigen::Vector3d(w.f_C_W[0], w.f_C_W[1], w.f_C_W[2]);
    wrench.torque_Nm = Eigen::Vector3d(w.t_C_W[0], w.t_C_W[1], w.t_C_W[2]);
    for (int k = 0; k < every && !sim.finished(); ++k)
      sink(sim.advance(wrench), static_cast<double>(w.n_contacts));
    if (sim.finished()) {
      std::ostringstream text;
      text << "finished: the rig's test phase ended at t = " << sim.time_s() << " s";
      server.close(coupler::CloseReason::Finished, text.str());
      if (!quiet)
        std::printf("wheel-rig: %s; told LIGGGHTS to stop\n", text.str().c_str());
      return;
    }
    coupler::Pose pose;
    pose.step = w.step + every;
    pose.state = to_wire(sim.wheel_state(), offset);
    server.send_pose(pose);
  }
}

} // namespace

int main(int argc, char **argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  CLI::App app{"wheel-rig: the multibody wheel test rig (docs/rig-config.md)"};
  std::string config_path, out_path, endpoint;
  std::optional<double> surface_height;
  bool quiet = false;
  app.add_option("--config", config_path, "rig configuration (TOML)")->required();
  app.add_option("--out", out_path, "HDF5 run file (default: [output] file of the config)");
  app.add_option("--endpoint", endpoint,
                 "coupling endpoint for terrain type dem (overrides [terrain] endpoint)");
  app.add_option("--surface-height", surface_height,
                 "undisturbed soil surface height [m] (overrides [terrain] surface_height)");
  app.add_flag("--quiet", quiet, "no progress lines");
  app.set_version_flag("--version", std::string(WHEELSIM_VERSION) + " (git " +
                                        WHEELSIM_GIT_REVISION + ")");
  CLI11_PARSE(app, argc, argv);

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  rig::RigConfig config;
  try {
    config = rig::load_rig_config(config_path);
    if (!out_path.empty())
      config.output.file = out_path;
    if (!endpoint.empty())
      config.terrain.endpoint = endpoint;
    if (surface_height)
      config.terrain.surface_height_m = *surface_height;
    if (config.terrain.type == rig::TerrainType::dem && config.terrain.endpoint.empty())
      throw rig::RigConfigError(config_path +
                                ": terrain.type = \"dem\" needs terrain.endpoint (or --endpoint)");
    if (config.terrain.type == rig::TerrainType::scm)
      throw rig::RigConfigError(config_path + ": terrain.type = \"scm\" is not available in this "
                                              "build yet; use \"dem\" or \"flat\"");
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wheel-rig: %s\n", e.what());
    return 2;
  }

  std::unique_ptr<runfile::RunFile> file;
  int status = 0;
  try {
    rig::RigSimulation sim(config);
    runfile::FlushPolicy flush;
    flush.flush_every = config.output.flush_interval;
    file = std::make_unique<runfile::RunFile>(
        config.output.file,
        runfile::Creator{"wheel-rig", WHEELSIM_VERSION, WHEELSIM_GIT_REVISION}, flush);
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

    rig::RunRecorder recorder(*file);
    rig::ProgressLine progress(quiet ? 0.0 : config.output.progress_interval_s, stdout);
    Sink sink{recorder, progress, sim, std::max(1LL, config.output.every), 0};
    if (config.terrain.type == rig::TerrainType::dem)
      run_dem(sim, sink, *file, quiet);
    else
      run_flat(sim, sink);
    for (const std::string &w : sim.warnings())
      std::fprintf(stderr, "wheel-rig: warning: %s\n", w.c_str());
    if (!quiet)
      std::printf("wheel-rig: done at t = %.4f s; run file %s\n", sim.time_s(),
                  config.output.file.c_str());
  } catch (const Interrupted &e) {
    std::fprintf(stderr, "wheel-rig: %s; run file closed\n", e.what());
    status = 130;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wheel-rig: error: %s\n", e.what());
    status = 1;
  }
  try {
    if (file)
      file->close();
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wheel-rig: error closing the run file: %s\n", e.what());
    status = status ? status : 1;
  }
  return status;
}
