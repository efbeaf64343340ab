#include "progress.h"

#include <cmath>

namespace wheelsim::rig {

ProgressLine::ProgressLine(double interval_s, std::FILE *out)
    : interval_s_(interval_s), out_(out), last_(Clock::now()) {}

void ProgressLine::update(const RigSimulation &sim, const RigOutputs &out) {
  if (interval_s_ <= 0.0)
    return;
  if (last_step_ < 0)
    last_step_ = out.step; // the first step this process runs (not 0 after a resume)
  const auto now = Clock::now();
  if (std::chrono::duration<double>(now - last_).count() >= interval_s_)
    print(sim, out);
}

void ProgressLine::print(const RigSimulation &sim, const RigOutputs &out) {
  const auto now = Clock::now();
  const double since_last = std::chrono::duration<double>(now - last_).count();
  const double rate = since_last > 0.0 ? (out.step - last_step_) / since_last : 0.0;
  char eta[64] = "after the settle phase";
  if (!std::isnan(sim.test_start_s()) && rate > 0.0) {
    const double left_s = sim.test_start_s() + sim.config().run.duration_s - out.time_s;
    const double wall_left = std::max(0.0, left_s / sim.config().run.dt_s / rate);
    std::snprintf(eta, sizeof(eta), "%02d:%02d:%02d", static_cast<int>(wall_left / 3600),
                  static_cast<int>(std::fmod(wall_left / 60, 60)),
                  static_cast<int>(std::fmod(wall_left, 60)));
  }
  std::fprintf(out_,
               "wheel-rig: t = %.4f s (%s), %.0f steps/s, slip %.4f, drawbar pull %.4g N, "
               "sinkage %.4g m, ETA %s\n",
               out.time_s, to_string(out.phase), rate, out.slip, out.drawbar_pull_N, out.sinkage_m,
               eta);
  std::fflush(out_);
  last_ = now;
  last_step_ = out.step;
}

} // namespace wheelsim::rig
