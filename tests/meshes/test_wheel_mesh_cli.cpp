// Runs the wheel-mesh executable and checks its exit status and messages.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

struct CliResult {
  int status;
  std::string output; // stdout and stderr
};

CliResult run_cli(const std::string &args) {
  // One log per process: ctest -j runs these tests as parallel processes.
  const fs::path log =
      fs::temp_directory_path() / ("wheelsim_test_cli_" + std::to_string(::getpid()) + ".log");
  const std::string cmd = std::string(WHEEL_MESH_EXE) + " " + args + " > " + log.string() + " 2>&1";
  const int raw = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  fs::remove(log);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, ss.str()};
}

void expect_rejected(const std::string &args, const std::vector<std::string> &fragments) {
  const CliResult r = run_cli(args);
  EXPECT_NE(r.status, 0) << args;
  for (const auto &f : fragments) {
    EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in: " << r.output;
  }
}

const std::string kWheel1 = "--diameter 1.234 --width 0.479 --lug-angle 25 ";

} // namespace

TEST(WheelMeshCli, LugHeightAtLeastRadius) {
  expect_rejected(kWheel1 + "--lugs 15 --type straight --lug-height 0.7",
                  {"--lug-height 0.7 m", "outer radius D0/2 = 0.617 m"});
}

TEST(WheelMeshCli, ZeroLugsWithStraightType) {
  expect_rejected(kWheel1 + "--lugs 0 --type straight --lug-height 0.06",
                  {"--lugs 0 with --type straight", "--smooth"});
}

TEST(WheelMeshCli, OverlappingLugs) {
  expect_rejected(kWheel1 + "--lugs 40 --type straight --lug-height 0.06 --lug-width 0.1",
                  {"lugs touch or overlap", "--lugs 40", "--lug-width 0.1 m"});
}

TEST(WheelMeshCli, UnknownType) {
  expect_rejected(kWheel1 + "--lugs 15 --type zigzag --lug-height 0.06", {"--type 'zigzag'"});
}

TEST(WheelMeshCli, MissingCentreLength) {
  expect_rejected(kWheel1 + "--lugs 15 --type combined --lug-height 0.06", {"--centre-length"});
}

TEST(WheelMeshCli, CentreLengthWiderThanWheel) {
  expect_rejected(kWheel1 + "--lugs 15 --type combined --lug-height 0.06 --centre-length 0.5",
                  {"--centre-length 0.5 m"});
}

TEST(WheelMeshCli, WritesMeshesAndProperties) {
  const fs::path dir = fs::temp_directory_path() / "wheelsim_test_cli_out";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const CliResult r = run_cli(
      "--diameter 0.2 --width 0.08 --lugs 8 --lug-height 0.01 --lug-width 0.008 "
      "--lug-angle 25 --centre-length 0.02 --type combined --max-arc 0.01 "
      "--out " +
      (dir / "small").string() + " --formats obj,stl,ply --props " + (dir / "small.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char *f : {"small.obj", "small.stl", "small.ply", "small.json"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  EXPECT_NE(r.output.find("inertia about centroid"), std::string::npos);
  std::ifstream in(dir / "small.json");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("\"mass_kg\""), std::string::npos);
}

TEST(WheelMeshCli, ZeroLugsWithoutTypeIsSmooth) {
  const CliResult r = run_cli("--diameter 0.5 --width 0.2 --lugs 0");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("smooth"), std::string::npos);
}
