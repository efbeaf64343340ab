// Runs `wheel-mesh tool ...` and checks the files it writes, its exit status and its messages.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "wheel_mesh_cli.h"
#include "wheelsim/geometry/mass_properties.h"
#include "wheelsim/geometry/mesh_io.h"

namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path &path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

} // namespace

TEST(ToolMeshCli, WritesEveryToolAsValidMeshes) {
  const fs::path dir = fs::temp_directory_path() / "wheelsim_test_tool_cli_out";
  fs::remove_all(dir);
  fs::create_directories(dir);
  struct Case {
    std::string name, args;
    double volume_m3; // of the faceted tool
  };
  const double pi = std::acos(-1.0), f72 = 36.0 * std::sin(2.0 * pi / 72.0);
  const std::vector<Case> cases{
      {"plate", "plate-rect 0.3 0.2 0.01", 0.3 * 0.2 * 0.01},
      {"disc", "plate-disc 0.1 0.01", f72 * 0.1 * 0.1 * 0.01},
      {"frame", "frame 0.1 0.1 0.01 0.05", (0.12 * 0.12 - 0.1 * 0.1) * 0.05},
      {"ring", "ring 0.05 0.055 0.1 --max-edge 0.01", f72 * (0.055 * 0.055 - 0.05 * 0.05) * 0.1},
  };
  for (const auto &c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path prefix = dir / c.name;
    const CliResult r = run_cli("tool " + c.args + " --out " + prefix.string() +
                                " --formats obj,stl --props " + prefix.string() + ".json");
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char *ext : {".obj", ".stl", ".json"})
      EXPECT_TRUE(fs::exists(prefix.string() + ext)) << ext;
    EXPECT_NE(r.output.find("centred at the origin, z up"), std::string::npos) << r.output;
    // What the fix reads: load_mesh validates (closed, manifold, outward, size in metres).
    for (const char *ext : {".obj", ".stl"}) {
      const auto mesh = wheelsim::geometry::load_mesh(prefix.string() + ext);
      const auto p = wheelsim::geometry::mass_properties(mesh, 1.0);
      // assimp reads single precision: about 1e-7 relative.
      EXPECT_NEAR(p.volume_m3 / c.volume_m3, 1.0, 1e-6) << ext;
      EXPECT_LT(p.centroid_m.norm(), 1e-7) << ext;
    }
    const std::string json = read_text(prefix.string() + ".json");
    EXPECT_NE(json.find("\"ideal_volume_m3\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"inertia_about_origin_kg_m2\""), std::string::npos) << json;
  }
}

TEST(ToolMeshCli, BadSizesExitTwoWithAMessage) {
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases{
      {"plate-rect 50 0.2 0.01",
       "wheel-mesh tool plate-rect: error: LX 50 m is implausible for a plate length (expected "
       "0.005–5 m); the generator takes metres: did you mean LX 0.05?"},
      {"plate-disc 1e-6 0.01",
       "wheel-mesh tool plate-disc: error: R 1e-06 m is implausible for a plate radius (expected "
       "0.005–5 m); the generator takes metres\n"},
      {"frame 0.1 0.1 -0.01 0.05", "WALL -0.01 m: the wall thickness must be > 0 m"},
      {"ring 0.06 0.05 0.1",
       "wheel-mesh tool ring: error: RI 0.06 m >= RO 0.05 m: the hole (inner radius RI) must be "
       "smaller than the body (outer radius RO)"},
      {"ring 0.05 0.06 0.1 4", "SEGMENTS 4: expected 8–100000 segments"},
      {"plate-disc 0.1 0.01 --chord-error 0.5", "--chord-error 0.5: expected a fraction"},
      {"plate-rect 0.3 0.2", "wheel-mesh tool plate-rect: T is required"},
      {"plate-rect 0.3 0.2 0.01 --ot x",
       "wheel-mesh tool plate-rect: unknown option '--ot' (did you mean '--out'?)"},
      {"plate 0.3 0.2 0.01",
       "wheel-mesh tool: unknown tool 'plate' (did you mean 'plate-rect'?); expected "
       "plate-rect, plate-disc, frame or ring"},
      {"", "wheel-mesh tool: expected a tool: plate-rect, plate-disc, frame or ring"},
  };
  for (const auto &c : cases) {
    const CliResult r = run_cli("tool " + c.args);
    EXPECT_EQ(r.status, 2) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << ": " << r.output;
    EXPECT_LT(r.seconds, 1.0) << c.args;
  }
}

TEST(ToolMeshCli, HelpListsTheTools) {
  for (const std::string args : {"--help", "tool --help"}) {
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.status, 0) << args << ": " << r.output;
    for (const char *syntax :
         {"wheel-mesh tool plate-rect LX LY T", "wheel-mesh tool plate-disc R T [SEGMENTS]",
          "wheel-mesh tool frame LX LY WALL H", "wheel-mesh tool ring RI RO H [SEGMENTS]"}) {
      EXPECT_NE(r.output.find(syntax), std::string::npos) << args << ": " << r.output;
    }
  }
  const CliResult r = run_cli("tool ring --help");
  EXPECT_EQ(r.status, 0) << r.output;
  for (const char *item : {"Usage: wheel-mesh tool ring [OPTIONS] RI RO H [SEGMENTS]",
                           "inner radius [m]", "--chord-error", "--max-edge"}) {
    EXPECT_NE(r.output.find(item), std::string::npos) << item << " in: " << r.output;
  }
  const CliResult v = run_cli("tool frame --version");
  EXPECT_EQ(v.status, 0) << v.output;
  EXPECT_EQ(v.output.rfind("wheel-mesh ", 0), 0u) << v.output;
}
