// wheelsim_run_file: writing, then reading back with the HDF5 C API (h5_read.h, not the writer's
// code): layout, dtypes, shapes, chunking, units, values over several flushes and chunk
// boundaries; parameters; terrain snapshots; errors.
#include "h5_read.h"
#include "sample_values.h"
#include "wheelsim/run_file/run_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace rf = wheelsim::runfile;
namespace fs = std::filesystem;

namespace {

std::string temp_path(const std::string &name) {
  const fs::path dir =
      fs::temp_directory_path() / ("wheelsim_run_file_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return (dir / name).string();
}

const rf::Creator kCreator{"test_run_file", "9.8.7", "deadbeef", "Test Author"};

void append_sample(rf::TimeSeries &s, std::int64_t step) {
  std::vector<double> v(s.components());
  for (int c = 0; c < s.components(); ++c)
    v[c] = sample::value(step, c);
  s.append(step, sample::time_s(step), v.data());
}

/// Checks /observables/<name> holds exactly the steps `steps` with the sample values.
void expect_series(hid_t f, const std::string &name, const std::vector<std::int64_t> &steps,
                   int components, const std::string &unit) {
  const std::string g = "/observables/" + name;
  SCOPED_TRACE(g);
  const hsize_t n = steps.size();
  std::vector<hsize_t> maxdims;
  EXPECT_EQ(h5read::dims(f, g + "/step", &maxdims), std::vector<hsize_t>{n});
  EXPECT_EQ(maxdims, std::vector<hsize_t>{H5S_UNLIMITED});
  EXPECT_EQ(h5read::dims(f, g + "/time"), std::vector<hsize_t>{n});
  const std::vector<hsize_t> value_dims =
      components == 1 ? std::vector<hsize_t>{n} : std::vector<hsize_t>{n, hsize_t(components)};
  EXPECT_EQ(h5read::dims(f, g + "/value", &maxdims), value_dims);
  EXPECT_EQ(maxdims[0], H5S_UNLIMITED);
  const std::vector<hsize_t> chunk = components == 1
                                         ? std::vector<hsize_t>{1024}
                                         : std::vector<hsize_t>{1024, hsize_t(components)};
  EXPECT_EQ(h5read::chunk(f, g + "/value"), chunk);
  EXPECT_EQ(h5read::chunk(f, g + "/step"), std::vector<hsize_t>{1024});
  EXPECT_EQ(h5read::type_of(f, g + "/step"), std::make_pair(H5T_INTEGER, std::size_t{8}));
  EXPECT_EQ(h5read::type_of(f, g + "/time"), std::make_pair(H5T_FLOAT, std::size_t{8}));
  EXPECT_EQ(h5read::type_of(f, g + "/value"), std::make_pair(H5T_FLOAT, std::size_t{8}));
  EXPECT_EQ(h5read::string_attr(f, g + "/value", "unit"), unit);
  EXPECT_EQ(h5read::string_attr(f, g + "/time", "unit"), "s");

  EXPECT_EQ(h5read::int64s(f, g + "/step"), steps);
  const auto time = h5read::doubles(f, g + "/time");
  const auto value = h5read::doubles(f, g + "/value");
  ASSERT_EQ(time.size(), n);
  ASSERT_EQ(value.size(), n * components);
  int bad = 0;
  for (hsize_t i = 0; i < n && bad < 5; ++i) {
    if (time[i] != sample::time_s(steps[i]))
      ADD_FAILURE() << "time row " << i << ": " << time[i] << ", expected "
                    << sample::time_s(steps[i]) << (++bad, "");
    for (int c = 0; c < components; ++c)
      if (value[i * components + c] != sample::value(steps[i], c))
        ADD_FAILURE() << "value row " << i << " component " << c << ": "
                      << value[i * components + c] << ", expected " << sample::value(steps[i], c)
                      << (++bad, "");
  }
}

std::vector<std::int64_t> steps_range(std::int64_t first, std::int64_t count, std::int64_t stride) {
  std::vector<std::int64_t> s;
  for (std::int64_t i = 0; i < count; ++i)
    s.push_back(first + i * stride);
  return s;
}

} // namespace

TEST(RunFile, SeriesRoundTripOverFlushesAndChunkBoundaries) {
  const std::string path = temp_path("roundtrip.h5");
  const std::int64_t rows = 2500; // > 2 chunks of 1024
  {
    rf::RunFile file(path, kCreator, rf::FlushPolicy{700, 0.0});
    auto &slip = file.observable("slip", "1", 1);
    auto &pos = file.observable("wheel/position", "m", 3);
    auto &quat = file.observable("wheel/orientation", "1", 4);
    auto &sparse = file.observable("contact/force", "N", 3);     // every 10th step only
    EXPECT_EQ(&file.observable("wheel/position", "m", 3), &pos); // same series again
    for (std::int64_t i = 0; i < rows; ++i) {
      const std::int64_t step = 2 * i + 1;
      append_sample(slip, step);
      append_sample(pos, step);
      append_sample(quat, step);
      if (i % 10 == 0)
        append_sample(sparse, step);
      if (i == 1234)
        file.flush(); // a manual flush in the middle of a chunk
    }
    // automatic writes to the working copy before rows 701, 1401 (a manual commit after 1235
    // rows), 1936, ...; no automatic commit (commit_interval 0): one commit in all.
    EXPECT_EQ(file.flush_count(), 1);
    EXPECT_GT(pos.rows_written(), 1235);
    EXPECT_EQ(pos.rows(), rows);
    EXPECT_LE(pos.buffered_rows(), 700);
    EXPECT_EQ(pos.rows_written() + pos.buffered_rows(), rows);
  } // destructor: writes the rest, closes and renames the working copy onto `path`
  EXPECT_FALSE(std::filesystem::exists(path + ".writing"));
  EXPECT_FALSE(std::filesystem::exists(path + ".publishing"));

  h5read::File f(path);
  expect_series(f.id(), "slip", steps_range(1, rows, 2), 1, "1");
  expect_series(f.id(), "wheel/position", steps_range(1, rows, 2), 3, "m");
  expect_series(f.id(), "wheel/orientation", steps_range(1, rows, 2), 4, "1");
  expect_series(f.id(), "contact/force", steps_range(1, rows / 10, 20), 3, "N");

  EXPECT_EQ(h5read::int_attr(f.id(), "/h5md", "version"), (std::vector<int>{1, 0}));
  EXPECT_EQ(h5read::string_attr(f.id(), "/h5md/creator", "name"), "test_run_file");
  EXPECT_EQ(h5read::string_attr(f.id(), "/h5md/creator", "version"), "9.8.7");
  EXPECT_EQ(h5read::string_attr(f.id(), "/h5md/creator", "git_revision"), "deadbeef");
  EXPECT_EQ(h5read::string_attr(f.id(), "/h5md/author", "name"), "Test Author");
  EXPECT_TRUE(h5read::exists(f.id(), "/parameters"));
  EXPECT_TRUE(h5read::exists(f.id(), "/terrain"));
}

TEST(RunFile, CloseIsIdempotentAndUseAfterCloseThrows) {
  const std::string path = temp_path("closed.h5");
  rf::RunFile file(path, kCreator);
  auto &s = file.observable("sinkage", "m", 1);
  s.append(1, 0.1, 0.02);
  file.close();
  EXPECT_FALSE(file.is_open());
  file.close();
  EXPECT_THROW(s.append(2, 0.2, 0.03), rf::RunFileError);
  EXPECT_THROW(file.observable("slip", "1", 1), rf::RunFileError);
  EXPECT_THROW(file.flush(), rf::RunFileError);
  h5read::File f(path);
  EXPECT_EQ(h5read::doubles(f.id(), "/observables/sinkage/value"), std::vector<double>{0.02});
}

TEST(RunFile, ParametersRoundTrip) {
  const std::string path = temp_path("parameters.h5");
  const std::string toml =
      "# rig config\n[wheel]\nmesh = \"wheel.obj\"  # µ-wheel\nradius = 0.15\n";
  {
    rf::RunFile file(path, kCreator);
    file.set_parameter_text("rig.toml", toml);
    file.set_parameter("liggghts/deck_arguments", "-in in.wheel -var seed 7");
    file.set_parameter("rig/spring_k", 2.5e4, "N/m");
    file.set_parameter("rig/seed", std::int64_t{42}, "1");
    file.set_parameter("run/steps", 100000, "1");
    EXPECT_THROW(file.set_parameter("rig/spring_k", 1.0, "N/m"), rf::RunFileError);
    EXPECT_THROW(file.set_parameter("rig/mass", 1.0, ""), rf::RunFileError);
    EXPECT_THROW(file.set_parameter_text("a//b", "x"), rf::RunFileError);
  }
  h5read::File f(path);
  EXPECT_EQ(h5read::string_dataset(f.id(), "/parameters/rig.toml"), toml);
  EXPECT_EQ(h5read::string_dataset(f.id(), "/parameters/liggghts/deck_arguments"),
            "-in in.wheel -var seed 7");
  EXPECT_EQ(h5read::doubles(f.id(), "/parameters/rig/spring_k"), std::vector<double>{2.5e4});
  EXPECT_EQ(h5read::string_attr(f.id(), "/parameters/rig/spring_k", "unit"), "N/m");
  EXPECT_EQ(h5read::int64s(f.id(), "/parameters/rig/seed"), std::vector<std::int64_t>{42});
  EXPECT_EQ(h5read::type_of(f.id(), "/parameters/rig/seed"),
            std::make_pair(H5T_INTEGER, std::size_t{8}));
  EXPECT_EQ(h5read::int64s(f.id(), "/parameters/run/steps"), std::vector<std::int64_t>{100000});
  EXPECT_EQ(h5read::dims(f.id(), "/parameters/rig/spring_k"), std::vector<hsize_t>{}); // scalar
}

TEST(RunFile, TerrainSnapshotRoundTrip) {
  const std::string path = temp_path("terrain.h5");
  std::vector<double> grid(3 * 5);
  for (std::size_t i = 0; i < grid.size(); ++i)
    grid[i] = 0.001 * static_cast<double>(i);
  {
    rf::RunFile file(path, kCreator);
    file.write_snapshot("height/000100", 100, 0.005, rf::Grid2D{grid.data(), 3, 5}, "m",
                        {{"dx", 0.01, "m"}, {"origin_x", -0.5, "m"}});
    EXPECT_THROW(
        file.write_snapshot("height/000100", 100, 0.005, rf::Grid2D{grid.data(), 3, 5}, "m"),
        rf::RunFileError);
    EXPECT_THROW(file.write_snapshot("p", 1, 0.0, rf::Grid2D{grid.data(), 0, 5}, "Pa"),
                 rf::RunFileError);
    EXPECT_THROW(file.write_snapshot("p", 1, 0.0, rf::Grid2D{grid.data(), 3, 5}, "Pa",
                                     {{"value", 1.0, "m"}}),
                 rf::RunFileError);
  }
  h5read::File f(path);
  const std::string g = "/terrain/height/000100";
  EXPECT_EQ(h5read::dims(f.id(), g + "/value"), (std::vector<hsize_t>{3, 5}));
  EXPECT_EQ(h5read::doubles(f.id(), g + "/value"), grid);
  EXPECT_EQ(h5read::string_attr(f.id(), g + "/value", "unit"), "m");
  EXPECT_EQ(h5read::int64s(f.id(), g + "/step"), std::vector<std::int64_t>{100});
  EXPECT_EQ(h5read::doubles(f.id(), g + "/time"), std::vector<double>{0.005});
  EXPECT_EQ(h5read::string_attr(f.id(), g + "/time", "unit"), "s");
  EXPECT_EQ(h5read::doubles(f.id(), g + "/dx"), std::vector<double>{0.01});
  EXPECT_EQ(h5read::string_attr(f.id(), g + "/origin_x", "unit"), "m");
  EXPECT_FALSE(h5read::exists(f.id(), "/terrain/p"));
}

TEST(RunFile, MissingDirectoryIsAClearErrorNamingThePath) {
  const std::string path = "/nonexistent_wheelsim_dir/sub/run.h5";
  try {
    rf::RunFile file(path, kCreator);
    FAIL() << "no error for " << path;
  } catch (const rf::RunFileError &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("does not exist"), std::string::npos) << what;
  }
}

TEST(RunFile, UnwritableFileIsAnErrorNamingThePath) {
  // A directory where the file should be: the message names the path and says so.
  const std::string path = temp_path("is_a_directory.h5");
  fs::create_directories(path);
  try {
    rf::RunFile file(path, kCreator);
    FAIL() << "no error for " << path;
  } catch (const rf::RunFileError &e) {
    EXPECT_NE(std::string(e.what()).find("cannot create run file '" + path + "'"),
              std::string::npos)
        << e.what();
  }
}

TEST(RunFile, BadObservableDeclarationsAndAppendsThrow) {
  rf::RunFile file(temp_path("bad.h5"), kCreator);
  auto &pos = file.observable("wheel/position", "m", 3);
  EXPECT_THROW(file.observable("wheel/position", "mm", 3), rf::RunFileError); // other unit
  EXPECT_THROW(file.observable("wheel/position", "m", 4), rf::RunFileError);  // other shape
  EXPECT_THROW(file.observable("wheel", "m", 1), rf::RunFileError);           // is the parent group
  EXPECT_THROW(file.observable("slip", "1", 0), rf::RunFileError);
  EXPECT_THROW(file.observable("slip", "", 1), rf::RunFileError);
  EXPECT_THROW(file.observable("/slip", "1", 1), rf::RunFileError);
  EXPECT_THROW(file.observable("slip/", "1", 1), rf::RunFileError);
  EXPECT_THROW(file.observable("a/../b", "1", 1), rf::RunFileError);
  const double v[3] = {1, 2, 3};
  pos.append(5, 0.1, v);
  EXPECT_THROW(pos.append(5, 0.1, v), rf::RunFileError); // step not increasing
  EXPECT_THROW(pos.append(4, 0.1, v), rf::RunFileError);
  EXPECT_THROW(pos.append(6, 0.1, 1.0), rf::RunFileError); // scalar append on a vector
  EXPECT_THROW(pos.append(6, 0.1, nullptr), rf::RunFileError);
  EXPECT_THROW(file.set_flush_policy(rf::FlushPolicy{-1, 1.0}), rf::RunFileError);
  try {
    pos.append(3, 0.1, v);
  } catch (const rf::RunFileError &e) {
    EXPECT_NE(std::string(e.what()).find("step 3 appended after step 5"), std::string::npos)
        << e.what();
  }
}

TEST(RunFile, NothingIsWrittenBeforeAFlushBufferedRowsStayInMemory) {
  rf::RunFile file(temp_path("buffer.h5"), kCreator, rf::FlushPolicy{0, 0.0});
  auto &s = file.observable("drawbar_pull", "N", 1);
  for (int i = 0; i < 5000; ++i)
    s.append(i, 0.001 * i, 1.0 * i);
  EXPECT_EQ(file.flush_count(), 0);
  EXPECT_EQ(s.rows_written(), 0);
  EXPECT_EQ(s.buffered_rows(), 5000);
  file.flush();
  EXPECT_EQ(s.rows_written(), 5000);
  EXPECT_EQ(s.buffered_rows(), 0);
}

// --- resume (docs/coupled-runs.md, "Checkpoint and resume") ------------------------------------

TEST(RunFileResume, KeepsRowsBeforeTheStepAndContinuesAfterThem) {
  const std::string path = temp_path("resume.h5");
  {
    rf::RunFile file(path, kCreator);
    file.set_parameter("rig_config", "first start");
    file.begin_health("running");
    rf::TimeSeries &pos = file.observable("wheel/position", "m", 3);
    rf::TimeSeries &slip = file.observable("slip", "1", 1);
    for (std::int64_t step = 0; step < 100; ++step) {
      append_sample(pos, step);
      append_sample(slip, step);
    }
    file.add_health_finding({10, 0.1, "early", "warning", "before the checkpoint"});
    file.add_health_finding({80, 0.8, "late", "warning", "after the checkpoint"});
    file.flush();
  } // the "stopped" run: its last commit holds steps 0..99
  {
    rf::RunFile file(path, rf::RunFile::Resume{50});
    EXPECT_TRUE(file.has_parameter("rig_config"));
    EXPECT_FALSE(file.has_parameter("resume/1/step"));
    EXPECT_TRUE(file.has_health());
    rf::TimeSeries &pos = file.observable("wheel/position", "m", 3);
    EXPECT_EQ(pos.rows(), 50);
    EXPECT_THROW(file.observable("slip", "N", 1), rf::RunFileError); // another unit
    // Steps must still increase past the kept rows.
    std::vector<double> v(3, 0.0);
    EXPECT_THROW(pos.append(49, 0.0, v.data()), rf::RunFileError);
    for (std::int64_t step = 50; step < 60; ++step)
      append_sample(pos, step);
    file.set_parameter("resume/1/step", std::int64_t{50}, "1");
    file.add_health_finding({55, 0.55, "resumed", "warning", "after the resume"});
    file.close();
  }
  h5read::File f(path);
  std::vector<std::int64_t> steps(60);
  for (std::int64_t k = 0; k < 60; ++k)
    steps[k] = k;
  expect_series(f.id(), "wheel/position", steps, 3, "m");
  EXPECT_EQ(h5read::dims(f.id(), "/observables/slip/step"), std::vector<hsize_t>{50});
  EXPECT_EQ(h5read::int64s(f.id(), "/health/step"), (std::vector<std::int64_t>{10, 55}));
  EXPECT_EQ(h5read::string_dataset(f.id(), "/parameters/rig_config"), "first start");
}

TEST(RunFileResume, AMissingFileIsNamed) {
  const std::string path = temp_path("no_such_run.h5");
  std::remove(path.c_str());
  try {
    rf::RunFile file(path, rf::RunFile::Resume{10});
    FAIL() << "no error";
  } catch (const rf::RunFileError &e) {
    EXPECT_NE(std::string(e.what()).find("cannot resume run file '" + path + "'"),
              std::string::npos)
        << e.what();
  }
}
