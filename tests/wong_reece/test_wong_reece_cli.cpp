// The wong-reece executable: its CSV has the documented columns and the library's numbers; bad
// options exit with status 2 and name the option and its range; --help, --version, a misspelt
// and a missing option follow the wheelsim command-line conventions (wheelsim/cli.h).
#include "wheelsim/cli.h"
#include "wheelsim/scm/wong_reece.h"

#include "cli_test_util.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace {

using namespace wheelsim::scm;
using namespace wr_test;

using CliRun = wheelsim::cli_test::CommandResult;

CliRun run(const std::string &args) {
  return wheelsim::cli_test::run_command(std::string(WONG_REECE_EXE) + " " + args);
}

std::vector<std::string> split(const std::string &line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ','))
    out.push_back(cell);
  return out;
}

std::string lete() { return std::string(SCM_SOILS_DIR) + "/lete_sand.toml"; }

TEST(WongReeceCli, CsvHasTheDocumentedColumnsAndTheLibrarysNumbers) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("wong_reece_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string csv = (dir / "out.csv").string();
  const CliRun r = run("--soil " + lete() +
                       " --radius 0.617 --width 0.479 --load 13200 "
                       "--slips 0.1,0.3,0.5 --csv " +
                       csv);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("drawbar pull [N]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sinkage [mm]"), std::string::npos);

  std::ifstream in(csv);
  std::string header;
  ASSERT_TRUE(std::getline(in, header));
  EXPECT_EQ(header, "slip,sinkage_m,entry_angle_rad,exit_angle_rad,max_stress_angle_rad,"
                    "drawbar_pull_N,torque_Nm,traction_force_N,tractive_efficiency");
  const SoilParameters s = soil("lete_sand");
  std::string line;
  int rows = 0;
  for (double slip : {0.1, 0.3, 0.5}) {
    ASSERT_TRUE(std::getline(in, line));
    const auto cells = split(line);
    ASSERT_EQ(cells.size(), 9u) << line;
    const WongReeceResult ref = solve_wong_reece(s, {kRadius, kWidth}, kLoad, slip);
    EXPECT_NEAR(std::stod(cells[0]), slip, 1e-12);
    EXPECT_NEAR(std::stod(cells[1]) / ref.sinkage_m, 1.0, 1e-8);
    EXPECT_NEAR(std::stod(cells[5]) / ref.drawbar_pull_N, 1.0, 1e-8);
    EXPECT_NEAR(std::stod(cells[6]) / ref.torque_Nm, 1.0, 1e-8);
    EXPECT_NEAR(std::stod(cells[7]) / ref.traction_force_N, 1.0, 1e-8);
    EXPECT_NEAR(std::stod(cells[8]) / ref.tractive_efficiency, 1.0, 1e-8);
    ++rows;
  }
  EXPECT_FALSE(std::getline(in, line) && !line.empty());
  EXPECT_EQ(rows, 3);
  std::filesystem::remove_all(dir);
}

TEST(WongReeceCli, DistributionIsPrinted) {
  const CliRun r = run("--soil " + lete() +
                       " --radius 0.617 --width 0.479 --load 13200 --slips 0.2 "
                       "--distribution 0.2 --distribution-points 5");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("# stress distribution at slip 0.2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sigma [kPa]"), std::string::npos);
}

TEST(WongReeceCli, BadOptionsNameTheOptionAndRange) {
  const std::string base = "--soil " + lete() + " --width 0.479 --load 13200 ";
  CliRun r = run(base + "--radius -1");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "wong-reece: --radius must be > 0 m, got -1\n");
  r = run(base + "--radius 0.617 --slips 0.1,1.5");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "wong-reece: --slips: each slip must be in [0, 1] (driven wheel), got 1.5\n");
  r = run(base + "--radius 0.617 --c1 1.2");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "wong-reece: --c1 must be in [0, 1), got 1.2\n");
  r = run("--soil /nonexistent.toml --radius 0.617 --width 0.479 --load 13200");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("/nonexistent.toml: cannot open the soil file"), std::string::npos);
  // A load the soil cannot carry: a model failure, status 1.
  r = run("--soil " + std::string(SCM_SOILS_DIR) +
          "/dry_sand.toml --radius 0.617 --width 0.479 --load 1e8 --slips 0.2");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("cannot carry"), std::string::npos) << r.output;
}

TEST(WongReeceCli, HelpVersionAndUsageErrorsFollowTheConventions) {
  CliRun r = run("--help");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--radius"), std::string::npos) << r.output;
  r = run("--version");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, wheelsim::cli::version_line("wong-reece") + "\n");
  // The misspelt option is named, not the required one it was meant to give.
  r = run("--soil " + lete() + " --raduis 0.3 --width 0.479 --load 13200");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("wong-reece: unknown option '--raduis' (did you mean '--radius'?)"),
            std::string::npos)
      << r.output;
  r = run("--soil " + lete() + " --width 0.479 --load 13200");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("wong-reece: --radius is required"), std::string::npos) << r.output;
}

} // namespace
