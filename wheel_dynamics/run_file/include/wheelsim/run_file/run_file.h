// wheelsim::runfile — the rig's HDF5 run file (DESIGN.md §4.3, docs/hdf5-layout.md).
//
// One writer per run. The layout is H5MD-like:
//   /h5md                      version [1 0], creator {name, version, git_revision}, author {name}
//   /parameters/<name>         every input, as scalar datasets (text, float, integer)
//   /observables/<name>/{step,time,value}   time series, value with a `unit` attribute
//   /terrain/<name>/{step,time,value,...}   2-D snapshots (SCM maps)
//   /health                    the run's own checks: attribute status, {step,time,code,severity,
//                              message} one row per finding (docs/run-health.md)
//
// Crash safety (docs/hdf5-layout.md, "Crash guarantees"): the HDF5 library writes to a working
// copy, `<path>.writing`, never to `path` itself. A commit (flush(), the automatic commit of the
// FlushPolicy, and every method that adds an object: a parameter, an observable, a snapshot)
// writes the buffered rows to the working copy, calls H5Fflush, copies the working copy to
// `<path>.publishing` and renames that onto `path` (rename(2) replaces `path` atomically). So at
// any moment, `path` is a complete file holding exactly what the last commit held: a process
// killed with SIGKILL at any instant — also inside a commit — loses no committed row and leaves no
// torn series. close() commits and renames the closed working copy onto `path`. A crash leaves the
// working copy (and perhaps the staging copy) beside `path`; the next RunFile at `path` removes
// them. Between commits, rows go to the working copy when a series buffers `write_every_rows`
// rows (a memory bound, not a commit). tests/run_file kills writers >= 1000 times inside commits.
// What this does not cover: a power loss or kernel crash (no fsync: the guarantee is for process
// death, where the page cache survives).
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

/// When RunFile writes and commits by itself (checked at every append). 0 disables a criterion.
struct FlushPolicy {
  /// Rows buffered in memory in any one series before every series' buffered rows are written to
  /// the working copy (a memory bound; readers of `path` see them at the next commit).
  std::int64_t write_every_rows = 1000;
  /// Wall-clock time between automatic commits [s].
  double commit_interval_s = 10.0;
  /// Automatic commits are at least this many times the last commit's duration apart, so that
  /// copying a large file costs at most ~1/commit_cost_factor of the run's wall time; 0: no
  /// stretch (commit_interval_s alone).
  double commit_cost_factor = 50.0;
};

class RunFile;

/// The `step` fill value of every series (time and value: NaN). A committed file never holds such
/// a row; it marks rows of a working copy whose extent but not data reached the disk.
constexpr std::int64_t kUnwrittenStep = -1;

/// One time series /observables/<name>/{step,time,value}. Obtained from RunFile::observable();
/// owned by the RunFile (the reference stays valid until the RunFile is destroyed).
class TimeSeries {
public:
  ~TimeSeries();
  TimeSeries(const TimeSeries &) = delete;
  TimeSeries &operator=(const TimeSeries &) = delete;

  /// Buffers one row: `values` points to components() doubles in the series' unit. `step` must
  /// be >= 0 and greater than the previous step of this series. If an automatic write or commit
  /// is due (FlushPolicy: this series holds write_every_rows rows, or commit_interval has
  /// passed), it is done first, before the row is buffered — so when every observable of step n
  /// is appended before any of step n+1, commits end at step boundaries. Throws RunFileError if
  /// that write or commit fails or the file is closed.
  void append(std::int64_t step, double time_s, const double *values);
  /// Convenience for scalar series (components() == 1).
  void append(std::int64_t step, double time_s, double value);

  const std::string &name() const { return name_; }
  const std::string &unit() const { return unit_; }
  int components() const { return components_; }
  /// Rows appended so far (written or buffered).
  std::int64_t rows() const { return rows_written_ + buffered_rows(); }
  /// Rows in the working copy (committed or not).
  std::int64_t rows_written() const { return rows_written_; }
  std::int64_t buffered_rows() const { return static_cast<std::int64_t>(steps_.size()); }

private:
  friend class RunFile;
  struct Datasets; // HDF5 handles, defined in the .cpp
  TimeSeries(RunFile &owner, std::string name, std::string unit, int components,
             std::unique_ptr<Datasets> datasets);
  void write_buffered(); // called by RunFile::write_buffered_rows()
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

/// One finding of a run's health checks (docs/run-health.md), a row of /health.
struct HealthRecord {
  std::int64_t step = 0;
  double time_s = 0.0;
  std::string code;     ///< e.g. "nonfinite_state"
  std::string severity; ///< "warning" or "error"
  std::string message;  ///< what was seen, with numbers and units, and what to do
};

class RunFile {
public:
  /// Creates (replaces) `path` and writes /h5md and the empty /parameters, /observables,
  /// /terrain groups (committed). Throws RunFileError naming the path if it cannot be created
  /// (e.g. its directory does not exist).
  RunFile(const std::string &path, const Creator &creator, const FlushPolicy &policy = {});
  /// Resumes the run file `path` of a run that stopped (docs/coupled-runs.md, "Checkpoint and
  /// resume"): its last commit is reopened for writing, every /observables series and /health
  /// keep only their rows with step < `before_step` (the rows the checkpoint's run had committed;
  /// later ones are written again by the resumed run), and appending goes on after them. The
  /// file's /h5md and /parameters stay as they are (has_parameter() tells which are set; each is
  /// still written once). Throws RunFileError naming the path if it is missing or not a run file.
  struct Resume {
    std::int64_t before_step;
  };
  RunFile(const std::string &path, const Resume &resume, const FlushPolicy &policy = {});
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
  /// True if /parameters/<name> exists (a resumed file has its first run's parameters).
  bool has_parameter(const std::string &name) const;

  // --- /observables ---
  /// The series /observables/<name>; created (and committed, empty) on first use.
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

  // --- /health ---
  /// Creates /health with status `status` (e.g. "running") and no rows; committed. Once.
  void begin_health(const std::string &status);
  /// True once /health exists (begin_health, or a resumed file that has it).
  bool has_health() const;
  /// Appends one finding to /health (begin_health first); committed at once, so a run that dies
  /// afterwards keeps it.
  void add_health_finding(const HealthRecord &record);
  /// Replaces /health's status attribute (e.g. "healthy", "warnings", "unhealthy"); committed.
  void set_health_status(const std::string &status);

  /// Commits: writes every buffered row to the working copy, H5Fflush, and publishes it as `path`
  /// (copy, then atomic rename). After it returns, `path` holds everything appended so far.
  void flush();
  /// Writes the buffered rows, closes every HDF5 handle and the working copy, and renames it onto
  /// `path`. Idempotent. Any use afterwards throws.
  void close();
  bool is_open() const;

  const std::string &path() const { return path_; }
  const FlushPolicy &flush_policy() const { return policy_; }
  void set_flush_policy(const FlushPolicy &policy);
  /// Number of flush() commits done (manual and automatic), for tests and progress reports.
  std::int64_t flush_count() const { return flush_count_; }
  /// The working copy HDF5 writes to (`path` + ".writing"); gone after close().
  std::string working_path() const { return path_ + ".writing"; }

private:
  friend class TimeSeries;
  struct Impl; // HDF5 handles, defined in the .cpp
  void before_append(const TimeSeries &series);
  void write_buffered_rows(); // every series' buffered rows to the working copy (no commit)
  void commit();              // H5Fflush, then publish the working copy as path_
  void require_open(const char *what) const;
  void open_file_objects(bool create); // property lists, types, the top-level groups
  void truncate_resumed(std::int64_t before_step);
  // Series of a resumed file not yet asked for: rows kept and the last kept step.
  std::map<std::string, std::pair<std::int64_t, std::int64_t>> resumed_rows_;

  std::string path_;
  FlushPolicy policy_;
  std::unique_ptr<Impl> impl_;
  std::map<std::string, std::unique_ptr<TimeSeries>> series_;
  std::int64_t flush_count_ = 0;
  double last_commit_s_ = 0.0;          // steady clock at the end of the last commit [s]
  double last_commit_duration_s_ = 0.0; // wall time the last commit took [s]
};

} // namespace wheelsim::runfile
