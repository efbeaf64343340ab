// Runs the wheel-mesh executable and checks its exit status and messages.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "wheel_mesh_cli.h"
#include "wheelsim/cli.h"

namespace fs = std::filesystem;

namespace {

/// Bad parameters are bad usage: exit status 2 and a message with every fragment.
void expect_rejected(const std::string &args, const std::vector<std::string> &fragments) {
  const CliResult r = run_cli(args);
  EXPECT_EQ(r.status, 2) << args << ": " << r.output;
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

TEST(WheelMeshCli, HelpVersionAndUsageErrorsFollowTheConventions) {
  CliResult r = run_cli("--help");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--diameter"), std::string::npos) << r.output;
  r = run_cli("--version");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, wheelsim::cli::version_line("wheel-mesh") + "\n");
  r = run_cli("--diamter 0.5 --width 0.2 --smooth");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("wheel-mesh: unknown option '--diamter' (did you mean '--diameter'?)"),
            std::string::npos)
      << r.output;
  r = run_cli("--width 0.2 --smooth");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("wheel-mesh: --diameter is required"), std::string::npos) << r.output;
  r = run_cli("--diameter 0.5 --width 0.2 --lugs 10 --type straight");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--lug-height is required"), std::string::npos) << r.output;
}

// Millimetres given for metres: rejected at once (it used to generate a 200 m wheel at 8 mm
// resolution for minutes), with the value in metres to write instead.
TEST(WheelMeshCli, ImplausibleSizesFailWithinOneSecond) {
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases{
      {"--diameter 200 --width 80 --smooth",
       "--diameter 200 m is implausible for a wheel diameter (expected 0.05–5 m); the generator "
       "takes metres: did you mean --diameter 0.2?"},
      {"--diameter 0.2 --width 80 --smooth",
       "--width 80 m is implausible for a wheel width (expected 0.01–3 m); the generator takes "
       "metres: did you mean --width 0.08?"},
      {"--diameter 1.234 --width 0.479 --lugs 15 --type straight --lug-height 60",
       "--lug-height 60 m: must be less than the outer radius D0/2 = 0.617 m (the rim radius "
       "D0/2 - lh must stay > 0); the generator takes metres: did you mean --lug-height 0.06?"},
      {"--diameter 2 --width 0.479 --lugs 15 --type straight --lug-height 0.7",
       "--lug-height 0.7 m is implausible for a lug height (expected 0.0005–0.5 m); the generator "
       "takes metres\n"},
      {"--diameter 1.234 --width 0.479 --lugs 15 --type straight --lug-height 0.06 "
       "--lug-width 40",
       "--lug-width 40 m is implausible for a lug width (expected 0.0005–0.5 m); the generator "
       "takes metres: did you mean --lug-width 0.04?"},
      {"--diameter 0.01 --width 0.2 --smooth",
       "--diameter 0.01 m is implausible for a wheel diameter (expected 0.05–5 m); the generator "
       "takes metres\n"},
      {"--diameter 1.234 --width 0.479 --smooth --max-arc 1e-5",
       "triangles (at most 1e+07); coarsen the resolution"},
  };
  for (const Case &c : cases) {
    const CliResult r = run_cli(c.args);
    EXPECT_EQ(r.status, 2) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << ": " << r.output;
    EXPECT_LT(r.seconds, 1.0) << c.args;
  }
}
