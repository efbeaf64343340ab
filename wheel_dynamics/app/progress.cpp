#include "progress.h"

#include <cmath>

namespace wheelsim::rig {

ProgressLine::ProgressLine(double interval_s, std::FILE *out)
    : interval_s_(interval_s), out_(out), start_(Clock::now()), last_(start_) {}

void ProgressLine::update(const RigSimulation &sim, const RigOutputs &out) {
  if (interval_s_ <= 0.0)
    return;
  if (first_step_ < 0)
    first_step_ = last_step_ = out.step; // the first step this process runs (not 0 after a resume)
  ++n_;
  sum_slip_ += out.slip;
  sum_drawbar_pull_N_ += out.drawbar_pull_N;
  sum_sinkage_m_ += out.sinkage_m;
  const auto now = Clock::now();
  if (std::chrono::duration<double>(now - last_).count() >= interval_s_)
    print(sim, out);
}

void ProgressLine::print(const RigSimulation &sim, const RigOutputs &out) {
  if (first_step_ < 0)
    first_step_ = last_step_ = out.step;
  const auto now = Clock::now();
  const auto seconds = [now](Clock::time_point t) {
    return std::chrono::duration<double>(now - t).count();
  };
  const double since_last = seconds(last_), since_start = seconds(start_);
  const double rate = since_last > 0.0 ? (out.step - last_step_) / since_last : 0.0;
  const double mean_rate = since_start > 0.0 ? (out.step - first_step_) / since_start : 0.0;
  // means since the previous line; this step alone if none was added
  const bool any = n_ > 0;
  const double slip = any ? sum_slip_ / n_ : out.slip;
  const double drawbar_pull_N = any ? sum_drawbar_pull_N_ / n_ : out.drawbar_pull_N;
  const double sinkage_m = any ? sum_sinkage_m_ / n_ : out.sinkage_m;
  char eta[64] = "after the settle phase";
  if (!std::isnan(sim.test_start_s()) && mean_rate > 0.0) {
    const double left_s = sim.test_start_s() + sim.config().run.duration_s - out.time_s;
    const double wall_left = std::max(0.0, left_s / sim.config().run.dt_s / mean_rate);
    std::snprintf(eta, sizeof(eta), "%02d:%02d:%02d", static_cast<int>(wall_left / 3600),
                  static_cast<int>(std::fmod(wall_left / 60, 60)),
                  static_cast<int>(std::fmod(wall_left, 60)));
  }
  std::fprintf(out_,
               "wheel-rig: t = %.4f s (%s), %.0f steps/s, slip %.4f, drawbar pull %.4g N, "
               "sinkage %.4g m, ETA %s\n",
               out.time_s, to_string(out.phase), rate, slip, drawbar_pull_N, sinkage_m, eta);
  std::fflush(out_);
  last_ = now;
  last_step_ = out.step;
  n_ = 0;
  sum_slip_ = sum_drawbar_pull_N_ = sum_sinkage_m_ = 0.0;
}

} // namespace wheelsim::rig
