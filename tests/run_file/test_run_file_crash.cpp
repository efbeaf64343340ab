// Crash safety: a child process writes a run file and is killed with SIGKILL; the parent reads
// the file back with the HDF5 C API. Between flushes the writer makes no HDF5 call, so the file
// must hold exactly the rows of the last flush (manual, row-count or wall-clock), nothing more.
// The last test kills the writer at random moments (also inside flushes): the file must open and
// hold no wrong value; how many series a kill inside a flush damaged is printed, not asserted.
#include "h5_read.h"
#include "sample_values.h"
#include "wheelsim/run_file/run_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace rf = wheelsim::runfile;
namespace fs = std::filesystem;

namespace {

std::string temp_path(const std::string &name) {
  const fs::path dir =
      fs::temp_directory_path() / ("wheelsim_run_file_crash_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return (dir / name).string();
}

const rf::Creator kCreator{"test_run_file_crash", "1.0", "cafe"};

struct Series {
  const char *name;
  const char *unit;
  int components;
};
const Series kSeries[] = {{"slip", "1", 1}, {"wheel/position", "m", 3},
                          {"wheel/orientation", "1", 4}};

/// Appends step `step` (sample values) to all three series.
void append_row(std::vector<rf::TimeSeries *> &series, std::int64_t step) {
  for (auto *s : series) {
    double v[4];
    for (int c = 0; c < s->components(); ++c)
      v[c] = sample::value(step, c);
    s->append(step, sample::time_s(step), v);
  }
}

std::vector<rf::TimeSeries *> declare(rf::RunFile &file) {
  std::vector<rf::TimeSeries *> out;
  for (const auto &s : kSeries)
    out.push_back(&file.observable(s.name, s.unit, s.components));
  return out;
}

/// Runs `body` in a forked child that must end by SIGKILL; returns after the child is dead.
/// Fails the test if the child exited otherwise (e.g. an exception: exit code 3).
void run_child_until_killed(const std::function<void()> &body,
                            const std::function<void(pid_t)> &parent_action = nullptr) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  ASSERT_GE(pid, 0) << "fork failed";
  if (pid == 0) {
    try {
      body();
    } catch (const std::exception &e) {
      std::fprintf(stderr, "child: %s\n", e.what());
      _exit(3);
    }
    _exit(4); // body returned without being killed
  }
  if (parent_action)
    parent_action(pid);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exited with code " << WEXITSTATUS(status);
  ASSERT_EQ(WTERMSIG(status), SIGKILL);
}

/// Rows of each series in the file; checks that step, time and value agree in length and that
/// the rows are exactly steps 1..n with the sample values.
std::int64_t check_consistent_prefix(const std::string &path) {
  h5read::File f(path);
  std::int64_t rows = -1;
  for (const auto &s : kSeries) {
    const std::string g = std::string("/observables/") + s.name;
    SCOPED_TRACE(g);
    const auto step = h5read::int64s(f.id(), g + "/step");
    const auto time = h5read::doubles(f.id(), g + "/time");
    const auto value = h5read::doubles(f.id(), g + "/value");
    const std::int64_t n = static_cast<std::int64_t>(step.size());
    EXPECT_EQ(time.size(), step.size());
    EXPECT_EQ(value.size(), step.size() * s.components);
    if (rows < 0)
      rows = n;
    EXPECT_EQ(n, rows) << "series of different lengths";
    for (std::int64_t i = 0; i < n && i < static_cast<std::int64_t>(time.size()); ++i) {
      const std::int64_t st = i + 1;
      if (step[i] != st || time[i] != sample::time_s(st)) {
        ADD_FAILURE() << "row " << i << ": step " << step[i] << " time " << time[i];
        break;
      }
      for (int c = 0; c < s.components; ++c)
        if (i * s.components + c < static_cast<std::int64_t>(value.size()) &&
            value[i * s.components + c] != sample::value(st, c)) {
          ADD_FAILURE() << "row " << i << " component " << c << ": " << value[i * s.components + c];
          i = n;
          break;
        }
    }
  }
  return rows;
}

} // namespace

TEST(RunFileCrash, SigkillAfterManualFlushKeepsExactlyTheFlushedRows) {
  const std::string path = temp_path("manual.h5");
  const std::int64_t flushed = 1500, unflushed = 700;
  run_child_until_killed([&] {
    rf::RunFile file(path, kCreator, rf::FlushPolicy{0, 0.0}); // no automatic flush
    file.set_parameter_text("rig.toml", "[run]\ndt = 1e-5\n");
    auto series = declare(file);
    for (std::int64_t step = 1; step <= flushed; ++step)
      append_row(series, step);
    file.flush();
    for (std::int64_t step = flushed + 1; step <= flushed + unflushed; ++step)
      append_row(series, step);
    raise(SIGKILL);
  });
  EXPECT_EQ(check_consistent_prefix(path), flushed);
  h5read::File f(path);
  EXPECT_EQ(h5read::string_dataset(f.id(), "/parameters/rig.toml"), "[run]\ndt = 1e-5\n");
  EXPECT_EQ(h5read::string_attr(f.id(), "/h5md/creator", "name"), "test_run_file_crash");
}

TEST(RunFileCrash, SigkillKeepsTheRowsOfTheLastAutomaticFlush) {
  const std::string path = temp_path("auto_rows.h5");
  run_child_until_killed([&] {
    rf::RunFile file(path, kCreator, rf::FlushPolicy{500, 0.0});
    auto series = declare(file);
    for (std::int64_t step = 1; step <= 1234; ++step)
      append_row(series, step);
    raise(SIGKILL);
  });
  EXPECT_EQ(check_consistent_prefix(path), 1000); // flushed before steps 501 and 1001
}

TEST(RunFileCrash, SigkillKeepsTheRowsOfTheLastWallClockFlush) {
  const std::string path = temp_path("auto_interval.h5");
  run_child_until_killed([&] {
    rf::RunFile file(path, kCreator, rf::FlushPolicy{0, 0.05});
    auto series = declare(file);
    for (std::int64_t step = 1; step <= 10; ++step)
      append_row(series, step);
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    append_row(series, 11); // first series' append sees 0.15 s > 0.05 s: flushes all 3 series
    raise(SIGKILL);
  });
  // The due flush ran at the start of the first append of step 11: steps 1..10 of all series.
  EXPECT_EQ(check_consistent_prefix(path), 10);
}

/// What a kill at a random moment left of one series.
enum class Left { Exact, Torn, Unreadable };

/// Classifies one series of a file killed at any moment. Exact: step, time and value have the
/// same length and every row is the written step 1..n with its values. Torn (a kill inside a
/// flush): the datasets may differ in length, and after the leading correct rows only unwritten
/// fill rows follow (step -1, NaN) — a wrong value anywhere fails the test. Unreadable: a read
/// failed (HDF5 metadata of the interrupted flush half on disk).
Left classify(hid_t f, const Series &s) {
  const std::string g = std::string("/observables/") + s.name;
  SCOPED_TRACE(g);
  std::vector<std::int64_t> step;
  std::vector<double> time, value;
  try {
    step = h5read::int64s(f, g + "/step");
    time = h5read::doubles(f, g + "/time");
    value = h5read::doubles(f, g + "/value");
  } catch (const std::exception &) {
    H5Eclear2(H5E_DEFAULT);
    return Left::Unreadable;
  }
  const std::size_t n = std::min({step.size(), time.size(), value.size() / s.components});
  bool fill_started = false;
  for (std::size_t i = 0; i < n; ++i) {
    const bool fill = step[i] == rf::kUnwrittenStep && std::isnan(time[i]);
    if (fill) {
      fill_started = true;
      continue;
    }
    bool ok = !fill_started && step[i] == static_cast<std::int64_t>(i + 1) &&
              time[i] == sample::time_s(i + 1);
    for (int c = 0; c < s.components; ++c)
      ok = ok && value[i * s.components + c] == sample::value(i + 1, c);
    if (!ok) {
      ADD_FAILURE() << "row " << i << ": step " << step[i] << " time " << time[i]
                    << " is neither the written row nor a fill row";
      return Left::Torn;
    }
  }
  const bool exact = !fill_started && step.size() == time.size() &&
                     value.size() == step.size() * s.components;
  return exact ? Left::Exact : Left::Torn;
}

TEST(RunFileCrash, SigkillAtRandomMomentsLeavesAFileThatOpens) {
  // The writer flushes every 50 rows, as fast as it can, so that many kills land inside a flush
  // (the window that "no HDF5 call between flushes" does not cover). Asserted: every file opens
  // and /h5md and /parameters read back; no series holds a wrong value (only correct rows, then
  // fill rows). Measured and printed, not asserted: how many series a kill inside a flush left
  // torn (datasets of unequal length, fill rows) or unreadable — HDF5 1.10 without SWMR does not
  // order its metadata writes, so the series being flushed can be damaged (docs/hdf5-layout.md).
  // The child reports through a pipe once its series are declared; the kill comes 1-40 ms later.
  const int kills = 40;
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> delay_us(1000, 40000);
  int exact = 0, torn = 0, unreadable = 0;
  for (int k = 0; k < kills; ++k) {
    SCOPED_TRACE("kill " + std::to_string(k));
    const std::string path = temp_path("random_" + std::to_string(k) + ".h5");
    const int delay = delay_us(rng);
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    run_child_until_killed(
        [&] {
          close(ready[0]);
          rf::RunFile file(path, kCreator, rf::FlushPolicy{50, 0.0});
          file.set_parameter("rig/seed", std::int64_t{7}, "1");
          auto series = declare(file);
          const char byte = 1;
          if (write(ready[1], &byte, 1) != 1)
            _exit(5);
          for (std::int64_t step = 1;; ++step)
            append_row(series, step);
        },
        [&](pid_t pid) {
          close(ready[1]);
          char byte = 0;
          const bool declared = read(ready[0], &byte, 1) == 1;
          close(ready[0]);
          std::this_thread::sleep_for(std::chrono::microseconds(delay));
          kill(pid, SIGKILL);
          ASSERT_TRUE(declared) << "the child died before declaring its series";
        });
    try {
      h5read::File f(path);
      EXPECT_EQ(h5read::string_attr(f.id(), "/h5md/creator", "name"), "test_run_file_crash");
      EXPECT_EQ(h5read::int64s(f.id(), "/parameters/rig/seed"), std::vector<std::int64_t>{7});
      for (const auto &s : kSeries) {
        switch (classify(f.id(), s)) {
        case Left::Exact: ++exact; break;
        case Left::Torn: ++torn; break;
        case Left::Unreadable: ++unreadable; break;
        }
      }
    } catch (const std::exception &e) {
      ADD_FAILURE() << "the file does not open after a kill " << delay << " us into writing: "
                    << e.what();
    }
  }
  std::printf("[ info     ] %d kills x 3 series: %d exact, %d torn, %d unreadable\n", kills, exact,
              torn, unreadable);
  EXPECT_GT(exact, 0);
}
