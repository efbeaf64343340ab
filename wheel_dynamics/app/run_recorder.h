// Writes the rig's per-step outputs (RigOutputs) into the HDF5 run file: one H5MD-like time
// series per quantity (docs/hdf5-layout.md lists them with units).
#pragma once

#include "wheelsim/rig/rig_simulation.h"
#include "wheelsim/run_file/run_file.h"

#include <cstdint>
#include <memory>

namespace wheelsim::rig {

class RunRecorder {
public:
  /// Declares every series in `file` (kept by reference: it must outlive the recorder).
  explicit RunRecorder(runfile::RunFile &file);
  ~RunRecorder();
  /// Appends the outputs of one step; `step` is the step number written to the file (the
  /// LIGGGHTS step for a coupled run, the rig's own step otherwise).
  void record(std::int64_t step, const RigOutputs &out, double contacts);

private:
  runfile::RunFile &file_;
  struct Series; // pointers to the series, which the RunFile owns
  std::unique_ptr<Series> s_;
};

} // namespace wheelsim::rig
