#include "terrain_snapshots.h"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace wheelsim::rig {
namespace {

scm::Field field_named(const std::string &name) {
  for (scm::Field f :
       {scm::Field::height, scm::Field::sinkage, scm::Field::plastic_sinkage, scm::Field::pressure,
        scm::Field::shear_stress, scm::Field::shear_displacement})
    if (name == scm::to_string(f))
      return f;
  throw std::invalid_argument("terrain.snapshot_fields: unknown field '" + name + "'");
}

} // namespace

TerrainSnapshots::TerrainSnapshots(const ScmTerrainConfig &config, runfile::RunFile &file)
    : file_(file), times_s_(config.snapshot_times_s), interval_s_(config.snapshot_interval_s),
      next_interval_s_(config.snapshot_interval_s) {
  for (const std::string &name : config.snapshot_fields)
    fields_.push_back(field_named(name));
}

void TerrainSnapshots::after_step(const scm::ScmTerrain &terrain, std::int64_t step,
                                  double time_s) {
  bool due = false;
  while (next_time_ < times_s_.size() && times_s_[next_time_] <= time_s) {
    due = true;
    ++next_time_;
  }
  if (interval_s_ > 0.0 && time_s >= next_interval_s_) {
    due = true;
    while (next_interval_s_ <= time_s)
      next_interval_s_ += interval_s_;
  }
  if (due)
    write(terrain, step, time_s);
}

void TerrainSnapshots::at_end(const scm::ScmTerrain &terrain, std::int64_t step, double time_s) {
  if (step != last_step_)
    write(terrain, step, time_s);
}

void TerrainSnapshots::write(const scm::ScmTerrain &terrain, std::int64_t step, double time_s) {
  char step_name[32];
  std::snprintf(step_name, sizeof step_name, "%09lld", static_cast<long long>(step));
  for (scm::Field field : fields_) {
    const scm::FieldMap map = terrain.sample(field);
    if (map.values.empty())
      continue; // nothing touched yet
    const runfile::Grid2D grid{map.values.data(), map.rows, map.cols};
    file_.write_snapshot(
        std::string(scm::to_string(field)) + "/" + step_name, step, time_s, grid,
        scm::unit_of(field),
        {{"x0", map.x0_m, "m"}, {"y0", map.y0_m, "m"}, {"spacing", map.spacing_m, "m"}});
  }
  last_step_ = step;
  ++written_;
}

} // namespace wheelsim::rig
