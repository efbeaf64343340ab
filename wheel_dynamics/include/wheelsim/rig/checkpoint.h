// The rig's checkpoint file (docs/coupled-runs.md, "Checkpoint and resume"): everything a rig run
// needs to continue as the same run — time, step, phase, the rig's coordinates, velocities, drives
// and reactions, the phase logic's timers (release, settle detection, ramp, test start), the
// health checks' accumulators and findings, and the coupling's step offset — as named values.
//
//   CheckpointData data;
//   sim.save_checkpoint(data); health.save_checkpoint(data); data.set_integer("liggghts_step", s);
//   data.write("run/checkpoints/rig-1200.ckpt");          // temp file + rename: atomic
//   const CheckpointData back = CheckpointData::read(path);  // CheckpointError names what is wrong
//
// Format (version 1), text: the first line `wheelsim-rig-checkpoint 1`, then one entry a line:
//   n KEY COUNT V1 ... VCOUNT    numbers, 17 significant digits (doubles read back bit for bit)
//   i KEY VALUE                  a 64-bit integer
//   t KEY TEXT                   text, with \\, \n escaped
// and a last line `end` (a file without it is incomplete and refused).
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace wheelsim::rig {

class CheckpointError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Format version of the rig checkpoint file; a file of another version is refused.
constexpr int kCheckpointVersion = 1;

class CheckpointData {
public:
  void set_number(const std::string &key, double value) { numbers_[key] = {value}; }
  void set_numbers(const std::string &key, std::vector<double> values) {
    numbers_[key] = std::move(values);
  }
  void set_integer(const std::string &key, std::int64_t value) { integers_[key] = value; }
  void set_text(const std::string &key, const std::string &text) { texts_[key] = text; }

  /// Each throws CheckpointError naming the file and the key if it is missing (or, for number(),
  /// holds other than one value).
  double number(const std::string &key) const;
  const std::vector<double> &numbers(const std::string &key) const;
  std::int64_t integer(const std::string &key) const;
  const std::string &text(const std::string &key) const;
  bool has(const std::string &key) const;

  /// Writes `path` + ".writing", then renames it onto `path` (a kill leaves the old file or the
  /// new one, never a torn one). Throws CheckpointError naming the path.
  void write(const std::string &path) const;
  /// Reads a file written by write(). Throws CheckpointError naming the path and the problem
  /// (missing, another format version, incomplete, a malformed line).
  static CheckpointData read(const std::string &path);

  const std::string &source() const { return source_; }

private:
  [[noreturn]] void missing(const std::string &key, const char *kind) const;
  std::map<std::string, std::vector<double>> numbers_;
  std::map<std::string, std::int64_t> integers_;
  std::map<std::string, std::string> texts_;
  std::string source_ = "checkpoint data";
};

} // namespace wheelsim::rig
