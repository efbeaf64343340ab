// The wheel-rig executable's command line: --help, --version, usage errors (wheelsim/cli.h), and
// --check, which validates a config as a run would (the keys, the wheel mesh, the SCM soil file,
// the DEM endpoint) without running or writing the run file. The sweep driver's --dry-run uses it.
#include "wheelsim/cli.h"

#include "cli_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using wheelsim::cli_test::CommandResult;

CommandResult rig(const std::string &args) {
  return wheelsim::cli_test::run_command(std::string(WHEEL_RIG_EXE) + " " + args);
}

std::string read(const std::string &path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// `text` with the first `from` replaced by `to` (the test fails if `from` is missing).
std::string replaced(std::string text, const std::string &from, const std::string &to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the example config";
  if (at != std::string::npos)
    text.replace(at, from.size(), to);
  return text;
}

class WheelRigCli : public testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("wheel_rig_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  /// Writes `text` as <tmp>/<name> and returns its path.
  std::string write(const std::string &name, const std::string &text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  /// The SCM example with absolute paths to the built wheel mesh and the shipped soil.
  std::string scm_config() {
    std::string text = read(RIG_EXAMPLES_DIR "/rig_scm.toml");
    text = replaced(text, "../../build/meshes/wheel2.obj", WHEELSIM_MESH_DIR "/wheel2.obj");
    return replaced(text, "../../inputs/scm_soils/", WHEELSIM_SOURCE_DIR "/inputs/scm_soils/");
  }
  std::string run_file() const { return (dir_ / "run.h5").string(); }
  /// `text` written as <tmp>/<name> fails `wheel-rig --check` (with `args`) with exit 2, one line
  /// on stderr containing `message`, and no run file.
  void expect_check_error(const std::string &name, const std::string &text, const std::string &args,
                          const std::string &message) {
    const std::string path = write(name, text);
    const CommandResult r = rig("--config " + path + " --check --out " + run_file() + " " + args);
    EXPECT_EQ(r.status, 2) << name << ": " << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << name << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << name << ": " << r.output;
    EXPECT_FALSE(fs::exists(run_file())) << name;
  }
  fs::path dir_;
};

TEST_F(WheelRigCli, HelpVersionAndUsageErrorsFollowTheConventions) {
  CommandResult r = rig("--help");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--check"), std::string::npos) << r.output;
  r = rig("--version");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, wheelsim::cli::version_line("wheel-rig") + "\n");
  r = rig("--confg " RIG_EXAMPLES_DIR "/rig_flat.toml");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("wheel-rig: unknown option '--confg' (did you mean '--config'?)"),
            std::string::npos)
      << r.output;
  r = rig("--out run.h5");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("wheel-rig: --config is required"), std::string::npos) << r.output;
  r = rig("--config " RIG_EXAMPLES_DIR "/rig_flat.toml --check --parameter novalue");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--parameter expects KEY=VALUE, got 'novalue'"), std::string::npos)
      << r.output;
  r = rig("--config " RIG_EXAMPLES_DIR "/rig_flat.toml --check --kinematic 1 0 0 0 1 0");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--kinematic needs terrain.type = \"dem\""), std::string::npos)
      << r.output;
}

TEST_F(WheelRigCli, CheckAcceptsTheExamplesAndWritesNothing) {
  const std::string flat = RIG_EXAMPLES_DIR "/rig_flat.toml";
  const std::string scm = write("scm.toml", scm_config());
  for (const std::string &config : {flat, scm}) {
    CommandResult r = rig("--config " + config + " --check --out " + run_file());
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output, config + ": ok\n");
    EXPECT_FALSE(fs::exists(run_file())) << "--check must not create the run file";
    r = rig("--config " + config + " --check --quiet");
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output, "");
  }
}

TEST_F(WheelRigCli, CheckRejectsWhatARunWouldRejectNamingTheKey) {
  const std::string flat = read(RIG_EXAMPLES_DIR "/rig_flat.toml");
  // The flat example's [terrain] as a DEM terrain (without its flat-ground keys).
  const auto terrain = flat.find("[terrain]"), output = flat.find("[output]");
  ASSERT_NE(terrain, std::string::npos);
  ASSERT_NE(output, std::string::npos);
  const std::string dem_text = flat.substr(0, terrain) +
                               "[terrain]\ntype = \"dem\"\nsurface_height = 0.0\n\n" +
                               flat.substr(output);
  struct Case {
    std::string name, text, extra_args, message;
  };
  const std::vector<Case> cases{
      {"negative_dt.toml", replaced(flat, "dt = 1.0e-4", "dt = -1"), "",
       "negative_dt.toml:25: run.dt must be > 0 s, got -1"},
      {"misspelt_key.toml", replaced(flat, "duration = 3.0", "duraton = 3.0"), "",
       "unknown key 'run.duraton'; did you mean 'run.duration'?"},
      {"dem.toml", dem_text, "", "missing key 'terrain.endpoint'"},
      // What the rig and the terrain load before a run: the wheel mesh, the SCM soil file.
      {"no_mesh.toml",
       replaced(scm_config(), WHEELSIM_MESH_DIR "/wheel2.obj", WHEELSIM_MESH_DIR "/absent.obj"), "",
       "wheel.mesh"},
      {"no_soil.toml", replaced(scm_config(), "lete_sand.toml", "absent_sand.toml"), "",
       "terrain.soil"},
  };
  for (const Case &c : cases) {
    const std::string path = write(c.name, c.text);
    const CommandResult r = rig("--config " + path + " --check --out " + run_file());
    EXPECT_EQ(r.status, 2) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.name << ": " << r.output;
    EXPECT_EQ(r.output.find(": ok"), std::string::npos) << c.name << ": " << r.output;
    EXPECT_FALSE(fs::exists(run_file())) << c.name;
  }
  // A DEM config with its endpoint is valid (--check connects to nothing).
  const std::string dem =
      write("dem_endpoint.toml", replaced(dem_text, "type = \"dem\"",
                                          "type = \"dem\"\nendpoint = \"ipc:///tmp/unused.sock\""));
  const CommandResult r = rig("--config " + dem + " --check --out " + run_file());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(run_file()));
  // The options get the checks their keys get: each bad value named, by --check too.
  const std::vector<std::pair<std::string, std::string>> options{
      {"--endpoint foo://bar", "--endpoint must start with ipc:// or tcp://, got 'foo://bar'"},
      {"--out ''", "--out expects a run file path, got ''"},
      {"--surface-height nan", "--surface-height must be a finite height [m]"},
      {"--kinematic nan 0 0 0 0 0", "--kinematic expects six finite numbers"},
      {"--resume " + (dir_ / "none.ckpt").string(), "--resume: checkpoint '"},
  };
  for (const auto &[args, message] : options) {
    const CommandResult o = rig("--config " + dem + " --check " + args);
    EXPECT_EQ(o.status, 2) << args << ": " << o.output;
    EXPECT_NE(o.output.find(message), std::string::npos) << args << ": " << o.output;
  }
}

} // namespace

namespace {

// The time step against the rig's stability bound (docs/rig-config.md "Time step"), on every
// terrain: the flat example's contact (limit 4.59 ms) with --dt 1 or run.dt = 0.01; the SCM
// example's suspension (limit 0.2215 s: the SCM contact is checked per step by the run health).
TEST_F(WheelRigCli, CheckRejectsATimeStepAboveTheRigsStabilityLimit) {
  const std::string flat = read(RIG_EXAMPLES_DIR "/rig_flat.toml");
  expect_check_error("flat_dt1.toml", flat, "--dt 1.0",
                     "--dt = 1 s is at or above the stability limit 0.00458846 s of the flat "
                     "ground's contact (terrain.stiffness = 1e+07 N/m");
  expect_check_error("flat_dt.toml", replaced(flat, "dt = 1.0e-4", "dt = 0.01"), "",
                     "run.dt = 0.01 s is at or above the stability limit 0.00458846 s");
  expect_check_error("scm_dt1.toml", scm_config(), "--dt 1",
                     "--dt = 1 s is at or above the stability limit 0.221546 s of the suspension "
                     "(rig.spring_k = 12000 N/m");
  const CommandResult ok = rig("--config " + write("scm.toml", scm_config()) + " --check --dt 0.2");
  EXPECT_EQ(ok.status, 0) << ok.output;
}

// A grid spacing that leaves fewer than 3 nodes across the wheel (wheel 2: 0.479 m wide) is refused
// by --check as a run stops on it (run health grid_coarse, before the first step).
TEST_F(WheelRigCli, CheckRejectsAGridCoarserThanAThirdOfTheWheelsWidth) {
  expect_check_error("grid_0.2.toml",
                     replaced(scm_config(), "grid_spacing = 0.02 ", "grid_spacing = 0.2 "), "",
                     "grid_coarse: terrain.grid_spacing = 0.2 m leaves fewer than 3 grid nodes "
                     "across the wheel's width (0.479 m, wheel.mesh)");
  const CommandResult ok =
      rig("--config " +
          write("grid_0.15.toml",
                replaced(scm_config(), "grid_spacing = 0.02 ", "grid_spacing = 0.15 ")) +
          " --check");
  EXPECT_EQ(ok.status, 0) << ok.output;
}

// A bounded soil needs grid_length and grid_width together, at least as wide as the wheel and as
// long as two rim radii plus the carriage's travel: wheel 2 (rim radius 0.617 m) at 0.518 m/s
// ((1 - 0.2) 1.05 rad/s 0.617 m) over 0.5 s of ramp + 4 s of test phase travels 2.33 m: 3.566 m.
TEST_F(WheelRigCli, CheckRejectsASoilBinTooSmallForTheWheelOrAHalfGivenOne) {
  const auto bin = [&](const std::string &keys) {
    return replaced(scm_config(), "grid_spacing = 0.02 ", "grid_spacing = 0.02\n" + keys + "\n");
  };
  expect_check_error("length_alone.toml", bin("grid_length = 6.0"), "",
                     "terrain.grid_length is given without terrain.grid_width: a bounded soil bin "
                     "needs both");
  expect_check_error("short.toml", bin("grid_length = 3.5\ngrid_width = 1.0"), "",
                     "terrain.grid_length = 3.5 m is too short for the wheel: the soil starts one "
                     "rim radius (0.617 m) behind the wheel's start and must reach one rim radius "
                     "beyond its end, 2.33226 m ahead");
  expect_check_error("narrow.toml", bin("grid_length = 6.0\ngrid_width = 0.4"), "",
                     "terrain.grid_width = 0.4 m is narrower than the wheel (0.479 m wide");
  const CommandResult ok =
      rig("--config " + write("bin.toml", bin("grid_length = 3.6\ngrid_width = 0.5")) + " --check");
  EXPECT_EQ(ok.status, 0) << ok.output;
}

// A NaN vertex in the wheel mesh is named with the file and the vertex (number and line), not
// reported as an inside-out mesh.
TEST_F(WheelRigCli, CheckNamesANonFiniteMeshVertex) {
  std::istringstream mesh(read(WHEELSIM_MESH_DIR "/test_small.obj"));
  std::string text;
  int vertices = 0;
  for (std::string line; std::getline(mesh, line);)
    text += (line.rfind("v ", 0) == 0 && ++vertices == 100 ? "v nan 0.01 0.05" : line) + "\n";
  const std::string path = write("nan.obj", text);
  const std::string config = replaced(scm_config(), WHEELSIM_MESH_DIR "/wheel2.obj", path);
  expect_check_error("nan_mesh.toml", config, "",
                     "wheel.mesh: " + path +
                         ": vertex 100 (line 101) has a coordinate that is not a finite number: "
                         "(nan, 0.01, 0.05)");
}

} // namespace
