// The scm-soil executable (docs/chrono-interop.md): import and export through files give the
// library's values and the documented exit statuses; --help, --version, a misspelt and a missing
// option follow the wheelsim command-line conventions (wheelsim/cli.h).
#include "wheelsim/cli.h"
#include "wheelsim/scm/chrono_soil.h"
#include "wheelsim/scm/soil_file.h"

#include "cli_test_util.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace {

using namespace wheelsim::scm;
using Result = wheelsim::cli_test::CommandResult;

Result run(const std::string &args) {
  return wheelsim::cli_test::run_command(std::string(SCM_SOIL_EXE) + " " + args);
}

std::filesystem::path temp_dir() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("scm_soil_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

std::string lete() { return std::string(SCM_SOILS_DIR) + "/lete_sand.toml"; }

TEST(ScmSoilCli, ExportThenImportGivesTheSameSoil) {
  const auto dir = temp_dir();
  const SoilParameters original = load_soil_file(lete());
  for (const char *format : {"terrain-node", "soil-parameters"}) {
    SCOPED_TRACE(format);
    const std::string json = (dir / (std::string(format) + ".json")).string();
    const std::string toml = (dir / (std::string(format) + ".toml")).string();
    Result r = run("export " + lete() + " --format " + format + " --out " + json);
    ASSERT_EQ(r.status, 0) << r.output;
    ChronoLayout layout;
    const ChronoSoil c = load_chrono_soil(json, &layout);
    EXPECT_STREQ(chrono_layout_name(layout), format);
    EXPECT_EQ(c.Mohr_friction, 31.1); // degrees in Chrono's file
    EXPECT_EQ(c.Bekker_Kphi, 5301000.0);
    r = run("import " + json + " --out " + toml);
    ASSERT_EQ(r.status, 0) << r.output;
    const SoilParameters back = load_soil_file(toml);
    EXPECT_EQ(back.name, "LETE sand");
    EXPECT_EQ(back.Bekker_n, original.Bekker_n);
    EXPECT_EQ(back.Bekker_Kc, original.Bekker_Kc);
    EXPECT_EQ(back.Bekker_Kphi, original.Bekker_Kphi);
    EXPECT_EQ(back.Mohr_cohesion, original.Mohr_cohesion);
    EXPECT_EQ(back.Mohr_friction, original.Mohr_friction);
    EXPECT_EQ(back.Janosi_shear, original.Janosi_shear);
    EXPECT_EQ(back.elastic_K, original.elastic_K);
    EXPECT_EQ(back.damping_R, original.damping_R);
  }
  std::filesystem::remove_all(dir);
}

TEST(ScmSoilCli, ImportNamesTheSoilAndWritesToStdout) {
  const auto dir = temp_dir();
  const std::string json = (dir / "my_chrono_soil.json").string();
  std::ofstream(json) << R"({"Soil parameters": {"Bekker Kphi": 2e6, "Bekker Kc": 0,
    "Bekker n exponent": 1.1, "Mohr cohesive limit": 0, "Mohr friction limit": 30,
    "Janosi shear coefficient": 0.01, "Elastic stiffness": 4e7, "Damping": 3e4}})";
  Result r = run("import " + json);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("name = \"my_chrono_soil\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("friction_angle = 30.0"), std::string::npos) << r.output;
  r = run("import " + json + " --name 'snow-like'");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("name = \"snow-like\""), std::string::npos) << r.output;
  std::filesystem::remove_all(dir);
}

TEST(ScmSoilCli, BadInputExitsTwoNamingTheKey) {
  const auto dir = temp_dir();
  const std::string json = (dir / "bad.json").string();
  std::ofstream(json) << R"({"Soil parameters": {"Bekker Kphi": 2e6, "Bekker Kc": 0,
    "Bekker n exponent": 1.1, "Mohr cohesive limit": 0,
    "Janosi shear coefficient": 0.01, "Elastic stiffness": 4e7, "Damping": 3e4}})";
  Result r = run("import " + json);
  EXPECT_EQ(r.status, wheelsim::cli::kExitUsage) << r.output;
  EXPECT_NE(r.output.find("\"Mohr friction limit\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("in deg"), std::string::npos) << r.output;
  r = run("import " + (dir / "missing.json").string());
  EXPECT_EQ(r.status, wheelsim::cli::kExitUsage) << r.output;
  EXPECT_NE(r.output.find("cannot open"), std::string::npos) << r.output;
  r = run("export " + json); // not a soil file
  EXPECT_EQ(r.status, wheelsim::cli::kExitUsage) << r.output;
  r = run("export " + lete() + " --grid-spacing -1");
  EXPECT_EQ(r.status, wheelsim::cli::kExitUsage) << r.output;
  EXPECT_NE(r.output.find("--grid-spacing must be > 0 m"), std::string::npos) << r.output;
  r = run("export " + lete() + " --format chrono");
  EXPECT_EQ(r.status, wheelsim::cli::kExitUsage) << r.output;
  std::filesystem::remove_all(dir);
}

TEST(ScmSoilCli, FollowsTheCommandLineConventions) {
  Result r = run("--help");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("import"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("export"), std::string::npos) << r.output;
  r = run("export --help");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--format"), std::string::npos) << r.output;
  r = run("--version");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, wheelsim::cli::version_line("scm-soil") + "\n");
  r = run("export " + lete() + " --fromat soil-parameters");
  EXPECT_EQ(r.status, wheelsim::cli::kExitUsage) << r.output;
  EXPECT_NE(r.output.find("unknown option '--fromat' (did you mean '--format'?)"),
            std::string::npos)
      << r.output;
  r = run("");
  EXPECT_EQ(r.status, wheelsim::cli::kExitUsage) << r.output;
  r = run("import");
  EXPECT_EQ(r.status, wheelsim::cli::kExitUsage) << r.output;
  EXPECT_NE(r.output.find("chrono_json"), std::string::npos) << r.output;
  r = run("imprt x.json");
  EXPECT_EQ(r.status, wheelsim::cli::kExitUsage) << r.output;
  EXPECT_NE(r.output.find("did you mean 'import'"), std::string::npos) << r.output;
}

} // namespace
