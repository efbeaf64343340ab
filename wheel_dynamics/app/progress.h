// The rig's progress line on the terminal: simulated time and phase, steps per second, slip,
// drawbar pull and sinkage, and the time left (known once the test phase has started). Slip, pull
// and sinkage are means over the steps since the previous line (one step's drawbar pull on a DEM
// soil swings by its own size from step to step); the time left is at the mean rate of every step
// this process has run (one interval's rate swings with what else shares the cores).
#pragma once

#include "wheelsim/rig/rig_simulation.h"

#include <chrono>
#include <cstdio>

namespace wheelsim::rig {

class ProgressLine {
public:
  /// `interval_s` wall seconds between lines (0: never); lines go to `out`.
  ProgressLine(double interval_s, std::FILE *out);
  /// Adds this step to the means and prints a line if the interval has passed (call every step).
  void update(const RigSimulation &sim, const RigOutputs &out);
  /// Prints a line now (means over the steps added since the previous line).
  void print(const RigSimulation &sim, const RigOutputs &out);

private:
  using Clock = std::chrono::steady_clock;
  double interval_s_;
  std::FILE *out_;
  Clock::time_point start_;   // this process's first update
  Clock::time_point last_;    // the previous line
  long long first_step_ = -1; // the first step this process ran; -1: none yet (a resumed run's
                              // rates count only its own steps, not the checkpoint's step)
  long long last_step_ = -1;  // the step of the previous line
  // sums over the steps since the previous line
  long long n_ = 0;
  double sum_slip_ = 0.0, sum_drawbar_pull_N_ = 0.0, sum_sinkage_m_ = 0.0;
};

} // namespace wheelsim::rig
