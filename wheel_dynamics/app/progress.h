// The rig's progress line on the terminal: simulated time and phase, steps per second, slip,
// drawbar pull, and the time left (known once the test phase has started).
#pragma once

#include "wheelsim/rig/rig_simulation.h"

#include <chrono>
#include <cstdio>

namespace wheelsim::rig {

class ProgressLine {
public:
  /// `interval_s` wall seconds between lines (0: never); lines go to `out`.
  ProgressLine(double interval_s, std::FILE *out);
  /// Prints a line if the interval has passed (call every step: cheap otherwise).
  void update(const RigSimulation &sim, const RigOutputs &out);

private:
  void print(const RigSimulation &sim, const RigOutputs &out);
  using Clock = std::chrono::steady_clock;
  double interval_s_;
  std::FILE *out_;
  Clock::time_point last_;
  long long last_step_ = -1; // the step of the last line; -1: none yet (taken from the first
                             // update, so a resumed run's first rate counts only its own steps)
};

} // namespace wheelsim::rig
