// Project Chrono's SCM soil JSON (wheelsim/scm/chrono_soil.h, docs/chrono-interop.md): Chrono's
// own sample files import to the values typed in by hand from them, Chrono JSON -> soil file ->
// Chrono JSON keeps every number, every shipped soil file exports and re-imports unchanged, and
// bad files give messages that name the key and its unit. The soil-file writer is checked here too.
#include "wheelsim/scm/chrono_soil.h"
#include "wheelsim/scm/soil_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace wheelsim::scm;

// Hand-copied from Project Chrono, data/vehicle/cosim/terrain/scm_hard.json (the co-simulation
// SCM terrain node's sample spec; the leading comment is Chrono's, its reader accepts comments).
const char *kChronoCosimScmHard = R"(// Sample SCM terrain specification file for co-simulation
{
    "Type": "SCM",

    "Patch dimensions": {
        "Length": 4,
        "Width": 1
    },

    "Grid spacing": 0.05,

    "Soil parameters": {
        "Bekker Kphi": 2e7,
        "Bekker Kc": 0,
        "Bekker n exponent": 1.1,
        "Mohr cohesive limit": 0,
        "Mohr friction limit": 20,
        "Janosi shear coefficient": 0.01,
        "Elastic stiffness": 2e8,
        "Damping": 3e4
    },

    "Simulation settings": {
        "Proxy contact radius": 0.002,
        "Fix proxies": true
    }
}
)";

// Hand-copied from Project Chrono, data/vehicle/terrain/scm_soil_parameters/scm_hard.json
// (Chrono::Vehicle's SCM soil-parameter file; LETE-sand-like values with K = 1.2 mm).
const char *kChronoVehicleScmHard = R"({
  "Name": "Dirt-Like SCM Parameters",
  "Type": "Terrain Properties",
  "Template": "SCM Soil Parameters",

  "Soil Parameters": {
    "Bekker Kphi": 5301e3,
    "Bekker Kc": 102e3,
    "Bekker n": 0.793,
    "Mohr Cohesion": 1.3e3,
    "Mohr Friction": 31.1,
    "Janosi Shear": 1.2e-3,
    "Elastic K": 4e8,
    "Dampening R": 3e4
  }
}
)";

void expect_same(const ChronoSoil &a, const ChronoSoil &b) {
  for (const ChronoSoilKey &k : chrono_soil_keys())
    EXPECT_EQ(a.*k.field, b.*k.field) << k.terrain_node_name;
}

void expect_same(const SoilParameters &a, const SoilParameters &b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.Bekker_n, b.Bekker_n);
  EXPECT_EQ(a.Bekker_Kc, b.Bekker_Kc);
  EXPECT_EQ(a.Bekker_Kphi, b.Bekker_Kphi);
  EXPECT_EQ(a.Mohr_cohesion, b.Mohr_cohesion);
  EXPECT_EQ(a.Mohr_friction, b.Mohr_friction);
  EXPECT_EQ(a.Janosi_shear, b.Janosi_shear);
  EXPECT_EQ(a.elastic_K, b.elastic_K);
  EXPECT_EQ(a.damping_R, b.damping_R);
}

/// The message of the ChronoSoilError `text` raises ("" if none).
std::string chrono_error_of(const std::string &text) {
  try {
    parse_chrono_soil(text, "c.json");
  } catch (const ChronoSoilError &e) {
    return e.what();
  }
  return "";
}

TEST(ChronoSoil, CosimSampleImportsToTheHandCheckedValues) {
  ChronoLayout layout = ChronoLayout::soil_parameters;
  const ChronoSoil c = parse_chrono_soil(kChronoCosimScmHard, "scm_hard.json", &layout);
  EXPECT_EQ(layout, ChronoLayout::terrain_node);
  EXPECT_EQ(c.name, "");
  const SoilParameters s = to_soil_parameters(c);
  EXPECT_EQ(s.Bekker_Kphi, 2e7);
  EXPECT_EQ(s.Bekker_Kc, 0.0);
  EXPECT_EQ(s.Bekker_n, 1.1);
  EXPECT_EQ(s.Mohr_cohesion, 0.0);
  EXPECT_NEAR(s.Mohr_friction, 20.0 * M_PI / 180.0, 1e-15); // Chrono: degrees; ours: radians
  EXPECT_NEAR(s.Mohr_friction, 0.3490658503988659, 1e-15);
  EXPECT_EQ(s.Janosi_shear, 0.01);
  EXPECT_EQ(s.elastic_K, 2e8);
  EXPECT_EQ(s.damping_R, 3e4);
}

TEST(ChronoSoil, VehicleSoilParameterSampleImportsToTheHandCheckedValues) {
  ChronoLayout layout = ChronoLayout::terrain_node;
  const SoilParameters s =
      to_soil_parameters(parse_chrono_soil(kChronoVehicleScmHard, "scm_hard.json", &layout));
  EXPECT_EQ(layout, ChronoLayout::soil_parameters);
  EXPECT_EQ(s.name, "Dirt-Like SCM Parameters");
  EXPECT_EQ(s.Bekker_Kphi, 5301000.0);
  EXPECT_EQ(s.Bekker_Kc, 102000.0);
  EXPECT_EQ(s.Bekker_n, 0.793);
  EXPECT_EQ(s.Mohr_cohesion, 1300.0);
  EXPECT_NEAR(s.Mohr_friction, 0.5427973973702365, 1e-15); // 31.1 deg
  EXPECT_EQ(s.Janosi_shear, 0.0012);
  EXPECT_EQ(s.elastic_K, 4e8);
  EXPECT_EQ(s.damping_R, 3e4);
}

TEST(ChronoSoil, ChronoToSoilFileToChronoKeepsEveryNumber) {
  for (const char *text : {kChronoCosimScmHard, kChronoVehicleScmHard}) {
    ChronoLayout layout;
    ChronoSoil original = parse_chrono_soil(text, "in.json", &layout);
    SCOPED_TRACE(chrono_layout_name(layout));
    original.name = "round trip";
    // Chrono JSON -> SoilParameters -> soil file text -> SoilParameters -> Chrono JSON.
    const std::string toml = write_soil_file(to_soil_parameters(original));
    const SoilParameters loaded = parse_soil_file(toml, "written.toml");
    ChronoLayout layout_back;
    const std::string json = write_chrono_soil(to_chrono_soil(loaded), layout);
    const ChronoSoil back = parse_chrono_soil(json, "out.json", &layout_back);
    EXPECT_EQ(layout_back, layout);
    EXPECT_EQ(back.name, "round trip");
    expect_same(back, original);
    // The friction angle is written as it was typed in, not as 31.099999999999998.
    EXPECT_NE(json.find(layout == ChronoLayout::terrain_node ? "\"Mohr friction limit\": 20,\n"
                                                             : "\"Mohr Friction\": 31.1,\n"),
              std::string::npos)
        << json;
  }
}

TEST(ChronoSoil, EveryShippedSoilExportsAndReimportsUnchanged) {
  int files = 0;
  for (const auto &entry : std::filesystem::recursive_directory_iterator(SCM_SOILS_DIR)) {
    if (entry.path().extension() != ".toml")
      continue;
    SCOPED_TRACE(entry.path().string());
    const SoilParameters original = load_soil_file(entry.path().string());
    for (const ChronoLayout layout : {ChronoLayout::terrain_node, ChronoLayout::soil_parameters}) {
      const std::string json = write_chrono_soil(to_chrono_soil(original), layout);
      ChronoLayout found;
      const SoilParameters back = to_soil_parameters(parse_chrono_soil(json, "x.json", &found));
      EXPECT_EQ(found, layout);
      expect_same(back, original);
    }
    // And our own writer: soil file -> text -> soil file.
    expect_same(parse_soil_file(write_soil_file(original), "rewritten.toml"), original);
    ++files;
  }
  EXPECT_GE(files, 10); // the ten table-1 soils at least
}

TEST(ChronoSoil, KeyTableMatchesTheSoilFileKeys) {
  const std::vector<std::string> soil_keys = soil_file_keys();
  ASSERT_EQ(chrono_soil_keys().size(), soil_keys.size());
  for (const ChronoSoilKey &k : chrono_soil_keys())
    EXPECT_NE(std::find(soil_keys.begin(), soil_keys.end(), k.soil_file_key), soil_keys.end())
        << k.soil_file_key;
}

TEST(ChronoSoil, WriterKeepsNotesAndEscapesStrings) {
  SoilParameters s;
  s.name = "a \"quoted\" soil\\x";
  s.Bekker_Kphi = 1e6;
  s.Mohr_friction = 30 * M_PI / 180;
  const std::string toml = write_soil_file(s, {"from a test", {{"bekker.kphi", "typed in"}}});
  const SoilParameters back = parse_soil_file(toml, "t.toml");
  expect_same(back, s);
  EXPECT_NE(toml.find("friction_angle = 30.0 "), std::string::npos) << toml;
  EXPECT_NE(toml.find("[source.bekker]\nkphi = \"typed in\""), std::string::npos) << toml;
  EXPECT_NE(toml.find("description = \"from a test\""), std::string::npos) << toml;
  const ChronoSoil c = parse_chrono_soil(
      write_chrono_soil(to_chrono_soil(s), ChronoLayout::soil_parameters), "t.json");
  EXPECT_EQ(c.name, s.name);
}

TEST(ChronoSoil, MissingKeysNameTheKeyAndItsUnit) {
  std::string text = kChronoCosimScmHard;
  text.replace(text.find("        \"Mohr friction limit\": 20,\n"),
               std::string("        \"Mohr friction limit\": 20,\n").size(), "");
  EXPECT_EQ(chrono_error_of(text),
            "c.json:12: missing key \"Soil parameters\".\"Mohr friction limit\": write "
            "\"Mohr friction limit\": <internal friction angle in deg, in [0, 90)>");
  text = kChronoVehicleScmHard;
  text.replace(text.find("    \"Janosi Shear\": 1.2e-3,\n"),
               std::string("    \"Janosi Shear\": 1.2e-3,\n").size(), "");
  EXPECT_NE(
      chrono_error_of(text).find("missing key \"Soil Parameters\".\"Janosi Shear\": write "
                                 "\"Janosi Shear\": <Janosi shear deformation modulus in m, > 0>"),
      std::string::npos)
      << chrono_error_of(text);
  EXPECT_NE(chrono_error_of(R"({"Type": "SCM"})").find("missing key \"Soil parameters\""),
            std::string::npos);
}

TEST(ChronoSoil, UnknownKeysAreNamedWithTheIntendedOne) {
  std::string text = kChronoCosimScmHard;
  text.replace(text.find("\"Damping\""), 9, "\"Dampng\"");
  EXPECT_EQ(chrono_error_of(text),
            "c.json:20: unknown key \"Soil parameters\".\"Dampng\"; did you mean "
            "\"Damping\"?");
  // A key of the other layout: its name in this one.
  text = kChronoCosimScmHard;
  text.replace(text.find("\"Mohr friction limit\""), 21, "\"Mohr Friction\"");
  EXPECT_EQ(chrono_error_of(text),
            "c.json:17: unknown key \"Soil parameters\".\"Mohr Friction\"; in a Chrono SCM "
            "terrain-node file (\"Soil parameters\") the internal friction angle is "
            "\"Mohr friction limit\"");
  text = kChronoCosimScmHard;
  text.replace(text.find("\"Grid spacing\""), 14, "\"Grid spaceing\"");
  EXPECT_NE(
      chrono_error_of(text).find("unknown key \"Grid spaceing\"; did you mean \"Grid spacing\"?"),
      std::string::npos)
      << chrono_error_of(text);
  text = kChronoCosimScmHard;
  text.replace(text.find("\"Soil parameters\""), 17, "\"Soil paramters\"");
  EXPECT_NE(chrono_error_of(text).find("unknown key \"Soil paramters\"; did you mean"),
            std::string::npos)
      << chrono_error_of(text);
}

TEST(ChronoSoil, RangeTypeAndSyntaxErrors) {
  std::string text = kChronoVehicleScmHard;
  text.replace(text.find("31.1"), 4, "95");
  EXPECT_EQ(chrono_error_of(text),
            "c.json:11: \"Soil Parameters\".\"Mohr Friction\" must be in [0, 90) deg, got 95");
  text = kChronoVehicleScmHard;
  text.replace(text.find("0.793"), 5, "\"0.8\"");
  EXPECT_NE(chrono_error_of(text).find("\"Soil Parameters\".\"Bekker n\" must be a number (sinkage "
                                       "exponent, in (0, 2]), got a string"),
            std::string::npos)
      << chrono_error_of(text);
  text = kChronoCosimScmHard;
  text.replace(text.find("\"Bekker Kphi\": 2e7"), 18, "\"Bekker Kphi\": 0");
  EXPECT_NE(chrono_error_of(text).find("must be > 0 (the soil must resist sinkage)"),
            std::string::npos);
  text = kChronoCosimScmHard;
  text.replace(text.find("0.01,"), 5, "0.01");
  EXPECT_EQ(chrono_error_of(text),
            "c.json:19: JSON syntax error: expected ',' or '}' in an object");
  text = kChronoCosimScmHard;
  text.replace(text.find("\"SCM\""), 5, "\"Rigid\"");
  EXPECT_NE(chrono_error_of(text).find("\"Type\" must be \"SCM\""), std::string::npos);
  EXPECT_NE(chrono_error_of("[1, 2]").find("is an object"), std::string::npos);
  // SCMPlane.json style: the soil is in another file.
  EXPECT_NE(chrono_error_of(R"({"Soil Parameters": {"Input File": "terrain/scm_soft.json"}})")
                .find("\"Input File\" refers to another file (\"terrain/scm_soft.json\")"),
            std::string::npos);
  EXPECT_THROW(load_chrono_soil("/nonexistent/chrono.json"), ChronoSoilError);
}

} // namespace
