// wheelsim::runfile — the rig's HDF5 run file (DESIGN.md §4.3, docs/hdf5-layout.md).
//
// One writer per run. The layout is H5MD-like:
//   /h5md                      version [1 0], creator {name, version, git_revision}, author {name}
//   /parameters/<name>         every input, as scalar datasets (text, float, integer)
//   /observables/<name>/{step,time,value}   time series, value with a `unit` attribute
//   /terrain/<name>/{step,time,value,...}   2-D snapshots (SCM maps)
//
// Crash safety: the HDF5 library is only called inside the public methods, and every method that
// changes the file ends with H5Fflush. Between calls the file on disk is therefore complete and
// consistent; rows appended since the last flush live only in memory. A process killed with
// SIGKILL between flushes leaves a file that reads back with every row up to the last flush()
// (manual or automatic) and nothing after it. A kill *during* a flush leaves a file that opens,
// with every row of the previous flush intact and part of the interrupted flush's rows; rows
// whose extent but not data reached the disk read as step kUnwrittenStep (-1), time and value
// NaN. tests/run_file proves both; docs/hdf5-layout.md has the measurements.
//
// No HDF5 header is included here: the handles live in the .cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace wheelsim::runfile {

/// Every failure (HDF5 error, bad name, bad argument, use after close) throws this; the message
/// names the file and the object concerned and, for HDF5 errors, the library's own description.
class RunFileError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Who wrote the file: /h5md/creator and /h5md/author.
struct Creator {
  std::string name;         ///< program name, e.g. "wheel-rig"
  std::string version;      ///< program version, e.g. "0.1.0"
  std::string git_revision; ///< e.g. the output of `git describe --always --dirty`
  std::string author = {};  ///< /h5md/author name; empty: $USER, or "unknown"
};

/// When RunFile flushes by itself (checked at every append). 0 disables a criterion.
struct FlushPolicy {
  std::int64_t flush_every = 1000; ///< rows buffered in any one series (memory bound per series)
  double flush_interval_s = 10.0;  ///< wall-clock seconds since the last flush [s]
};

class RunFile;

/// The `step` fill value: a row with this step was never written (a kill inside a flush left the
/// dataset's extent on disk but not the row's data); its time and value read as NaN.
constexpr std::int64_t kUnwrittenStep = -1;

/// One time series /observables/<name>/{step,time,value}. Obtained from RunFile::observable();
/// owned by the RunFile (the reference stays valid until the RunFile is destroyed).
class TimeSeries {
public:
  ~TimeSeries();
  TimeSeries(const TimeSeries &) = delete;
  TimeSeries &operator=(const TimeSeries &) = delete;

  /// Buffers one row: `values` points to components() doubles in the series' unit. `step` must
  /// be >= 0 and greater than the previous step of this series. If an automatic flush of the whole file
  /// is due (FlushPolicy: this series holds flush_every rows, or flush_interval has passed), it
  /// is done first, before the row is buffered — so when every observable of step n is appended
  /// before any of step n+1, flushes end at step boundaries. Throws RunFileError if that flush
  /// fails or the file is closed.
  void append(std::int64_t step, double time_s, const double *values);
  /// Convenience for scalar series (components() == 1).
  void append(std::int64_t step, double time_s, double value);

  const std::string &name() const { return name_; }
  const std::string &unit() const { return unit_; }
  int components() const { return components_; }
  /// Rows appended so far (written or buffered).
  std::int64_t rows() const { return rows_written_ + buffered_rows(); }
  /// Rows in the file as of the last flush.
  std::int64_t rows_written() const { return rows_written_; }
  std::int64_t buffered_rows() const { return static_cast<std::int64_t>(steps_.size()); }

private:
  friend class RunFile;
  struct Datasets; // HDF5 handles, defined in the .cpp
  TimeSeries(RunFile &owner, std::string name, std::string unit, int components,
             std::unique_ptr<Datasets> datasets);
  void write_buffered(); // called by RunFile::flush()
  void close_datasets();

  RunFile *owner_;
  std::string name_, unit_;
  int components_;
  std::unique_ptr<Datasets> datasets_;
  std::vector<std::int64_t> steps_;
  std::vector<double> times_, values_;
  std::int64_t rows_written_ = 0;
  std::int64_t last_step_ = 0;
  bool has_last_step_ = false;
};

/// A named number stored beside a terrain snapshot (e.g. grid spacing), with its unit.
struct SnapshotScalar {
  std::string name;
  double value;
  std::string unit; ///< "1" for dimensionless
};

/// A row-major 2-D array of doubles: values[i * cols + j], i < rows, j < cols.
struct Grid2D {
  const double *values;
  std::size_t rows;
  std::size_t cols;
};

class RunFile {
public:
  /// Creates (truncates) `path` and writes /h5md and the empty /parameters, /observables,
  /// /terrain groups. Throws RunFileError naming the path if it cannot be created (e.g. its
  /// directory does not exist).
  RunFile(const std::string &path, const Creator &creator, const FlushPolicy &policy = {});
  /// Closes the file (close()); an error there is printed to stderr, not thrown.
  ~RunFile();
  RunFile(const RunFile &) = delete;
  RunFile &operator=(const RunFile &) = delete;

  // --- /parameters: scalar datasets; `name` may contain '/' (subgroups). Each name once. ---
  /// Text verbatim (e.g. the rig config TOML, the LIGGGHTS deck arguments): variable-length
  /// UTF-8 string dataset.
  void set_parameter_text(const std::string &name, const std::string &text);
  void set_parameter(const std::string &name, const std::string &value);
  void set_parameter(const std::string &name, const char *value);
  /// Numbers carry their unit as the dataset's `unit` attribute ("1" for dimensionless).
  void set_parameter(const std::string &name, double value, const std::string &unit);
  void set_parameter(const std::string &name, std::int64_t value, const std::string &unit);
  void set_parameter(const std::string &name, int value, const std::string &unit);

  // --- /observables ---
  /// The series /observables/<name>; created (and flushed to the file, empty) on first use.
  /// `name` may contain '/' ("wheel/position"). `unit` is stored on `value` ("1" for
  /// dimensionless); `components` is 1 (value is [n]) or more (value is [n x components], e.g. 3
  /// for a vector, 4 for a quaternion w x y z). Asking again for an existing name returns the
  /// same series; a different unit or component count is an error.
  TimeSeries &observable(const std::string &name, const std::string &unit, int components);

  // --- /terrain ---
  /// Writes /terrain/<group_name>/{step, time [s], value [rows x cols] with `unit`} and one
  /// scalar dataset (with its `unit`) per entry of `scalars`. `group_name` may contain '/';
  /// each snapshot name once.
  void write_snapshot(const std::string &group_name, std::int64_t step, double time_s,
                      const Grid2D &grid, const std::string &unit,
                      const std::vector<SnapshotScalar> &scalars = {});

  /// Writes every buffered row and calls H5Fflush: after it returns, the file on disk holds
  /// everything appended so far.
  void flush();
  /// flush(), then closes every HDF5 handle and the file. Idempotent. Any use afterwards throws.
  void close();
  bool is_open() const;

  const std::string &path() const { return path_; }
  const FlushPolicy &flush_policy() const { return policy_; }
  void set_flush_policy(const FlushPolicy &policy);
  /// Number of flushes done (manual and automatic), for tests and progress reports.
  std::int64_t flush_count() const { return flush_count_; }

private:
  friend class TimeSeries;
  struct Impl; // HDF5 handles, defined in the .cpp
  void before_append(const TimeSeries &series);
  void require_open(const char *what) const;

  std::string path_;
  FlushPolicy policy_;
  std::unique_ptr<Impl> impl_;
  std::map<std::string, std::unique_ptr<TimeSeries>> series_;
  std::int64_t flush_count_ = 0;
  double last_flush_s_ = 0.0; // steady clock [s]
};

} // namespace wheelsim::runfile
