// SCM terrain snapshots in the run file: at the simulated times of terrain.snapshot_times, every
// terrain.snapshot_interval and at the end of the run, each field of terrain.snapshot_fields is
// sampled over the touched part of the grid and written as /terrain/<field>/<step, 9 digits>
// (docs/hdf5-layout.md "Terrain snapshots"; PNG maps: wheelsim-post maps, docs/postprocess.md).
#pragma once

#include "wheelsim/rig/rig_config.h"
#include "wheelsim/run_file/run_file.h"
#include "wheelsim/scm/scm_terrain.h"

#include <cstdint>
#include <vector>

namespace wheelsim::rig {

class TerrainSnapshots {
public:
  TerrainSnapshots(const ScmTerrainConfig &config, runfile::RunFile &file);
  /// Writes the snapshots due at `time_s` (call after each step).
  void after_step(const scm::ScmTerrain &terrain, std::int64_t step, double time_s);
  /// Writes the final snapshot (unless one was written at this step).
  void at_end(const scm::ScmTerrain &terrain, std::int64_t step, double time_s);
  int written() const { return written_; }

private:
  void write(const scm::ScmTerrain &terrain, std::int64_t step, double time_s);
  runfile::RunFile &file_;
  std::vector<scm::Field> fields_;
  std::vector<double> times_s_;
  std::size_t next_time_ = 0;
  double interval_s_;
  double next_interval_s_;
  std::int64_t last_step_ = -1;
  int written_ = 0;
};

} // namespace wheelsim::rig
