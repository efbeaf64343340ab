// The rig configuration: every key's range check, unknown keys and tables with suggestions, mode
// consistency, the example config, wheel mass properties from a mesh, every key documented.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "wheelsim/geometry/mesh_io.h"
#include "wheelsim/rig/config_schema.h"
#include "wheelsim/rig/rig_config.h"
#include "wheelsim/rig/rig_simulation.h"
#include "wheelsim/rig/slip_modes.h"
#include "wheelsim/rig/terrain_registry.h"
#include "wheelsim/rig/time_step.h"

namespace wheelsim::rig {
namespace {

using Tables =
    std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>>;

/// A valid config as tables of (key, TOML literal).
Tables base() {
  return {
      {"wheel", {{"mass", "205.0"}, {"inertia", "72.0"}, {"effective_radius", "0.617"}}},
      {"rig",
       {{"spindle_mass", "100.0"},
        {"suspended_mass", "1040.0"},
        {"spring_k", "12000"},
        {"spring_c", "800.0"}}},
      {"motor", {{"omega", "1.05"}, {"ramp_time", "1.0"}}},
      {"carriage", {{"mode", "\"imposed_slip\""}, {"slip", "0.2"}}},
      {"run", {{"dt", "1e-4"}, {"duration", "2.0"}}},
      {"terrain", {{"type", "\"flat\""}}},
      {"output", {{"file", "\"run.h5\""}}},
  };
}

/// Sets (or with an empty value removes) table.key.
Tables with(Tables t, const std::string &dotted, const std::string &value) {
  const auto dot = dotted.find('.');
  const std::string table = dotted.substr(0, dot), key = dotted.substr(dot + 1);
  for (auto &[name, keys] : t)
    if (name == table) {
      for (auto it = keys.begin(); it != keys.end(); ++it)
        if (it->first == key) {
          if (value.empty())
            keys.erase(it);
          else
            it->second = value;
          return t;
        }
      if (!value.empty())
        keys.emplace_back(key, value);
      return t;
    }
  t.push_back({table, {{key, value}}});
  return t;
}

std::string render(const Tables &t) {
  std::ostringstream os;
  for (const auto &[name, keys] : t) {
    os << "[" << name << "]\n";
    for (const auto &[k, v] : keys)
      os << k << " = " << v << "\n";
  }
  return os.str();
}

std::string error_of(const Tables &t) {
  try {
    parse_rig_config(render(t), "test.toml");
  } catch (const RigConfigError &e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RigConfig, BaseParsesWithDefaults) {
  const RigConfig c = parse_rig_config(render(base()), "test.toml");
  EXPECT_DOUBLE_EQ(c.rig.spring_k_N_m, 12000.0); // integer literal accepted as a number
  EXPECT_DOUBLE_EQ(*c.rig.suspended_mass_kg, 1040.0);
  EXPECT_DOUBLE_EQ(c.rig.gravity_m_s2, 9.81);
  EXPECT_EQ(c.carriage.mode, CarriageMode::imposed_slip);
  EXPECT_DOUBLE_EQ(c.carriage.slip, 0.2);
  EXPECT_DOUBLE_EQ(c.run.release_speed_m_s, 0.01);
  EXPECT_EQ(c.terrain.flat.friction_model, FrictionModel::coulomb);
  EXPECT_EQ(c.output.every, 1);
}

struct RangeCase {
  std::vector<std::pair<std::string, std::string>> setup; // applied first (mode switches)
  std::string key;
  std::string bad;
  std::string message;
};

TEST(RigConfig, EveryKeyRangeCheckNamesKeyRangeUnitAndValue) {
  const std::vector<std::pair<std::string, std::string>> none;
  const std::vector<std::pair<std::string, std::string>> density = {{"wheel.mass", ""},
                                                                    {"wheel.inertia", ""},
                                                                    {"wheel.mesh", "\"w.obj\""},
                                                                    {"wheel.density", "1000"}};
  const std::vector<std::pair<std::string, std::string>> load = {{"rig.suspended_mass", ""}};
  const std::vector<std::pair<std::string, std::string>> torque = {{"motor.omega", ""}};
  const std::vector<std::pair<std::string, std::string>> ramped = {
      {"carriage.mode", "\"ramped_load\""},
      {"carriage.slip", ""},
      {"carriage.load_start", "0"},
      {"carriage.load_end", "100"},
      {"carriage.ramp_time", "2"}};
  const std::vector<std::pair<std::string, std::string>> regularized = {
      {"terrain.friction_model", "\"regularized\""}};
  const std::vector<std::pair<std::string, std::string>> dem = {
      {"terrain.type", "\"dem\""}, {"terrain.endpoint", "\"ipc:///tmp/x\""}};
  const std::vector<std::pair<std::string, std::string>> scm = {{"terrain.type", "\"scm\""},
                                                                {"terrain.soil", "\"soil.toml\""},
                                                                {"terrain.grid_spacing", "0.01"},
                                                                {"terrain.grid_length", "3"},
                                                                {"terrain.grid_width", "1"}};
  const std::vector<RangeCase> cases = {
      {density, "wheel.mesh", "\"\"", "wheel.mesh must be a file name (OBJ, STL or PLY), got \"\""},
      {none, "wheel.mass", "-1", "wheel.mass must be > 0 kg, got -1"},
      {none, "wheel.inertia", "0", "wheel.inertia must be > 0 kg m^2, got 0"},
      {none, "wheel.effective_radius", "-0.5", "wheel.effective_radius must be > 0 m, got -0.5"},
      {density, "wheel.density", "0", "wheel.density must be > 0 kg/m^3, got 0"},
      {density, "wheel.mesh_scale", "-2", "wheel.mesh_scale must be > 0 (mesh units -> m), got -2"},
      {none, "rig.spindle_mass", "-1", "rig.spindle_mass must be >= 0 kg, got -1"},
      {none, "rig.suspended_mass", "0", "rig.suspended_mass must be > 0 kg, got 0"},
      {load, "rig.vertical_load", "-5", "rig.vertical_load must be > 0 N, got -5"},
      {none, "rig.carriage_mass", "-1", "rig.carriage_mass must be >= 0 kg, got -1"},
      {none, "rig.spring_k", "-3", "rig.spring_k must be > 0 N/m, got -3"},
      {none, "rig.spring_c", "-1", "rig.spring_c must be >= 0 N s/m, got -1"},
      {none, "rig.gravity", "0", "rig.gravity must be > 0 m/s^2, got 0"},
      {none, "motor.omega", "-1", "motor.omega must be > 0 rad/s, got -1"},
      {torque, "motor.torque", "0", "motor.torque must be != 0 N m, got 0"},
      {none, "motor.ramp_time", "-1", "motor.ramp_time must be >= 0 s, got -1"},
      {none, "carriage.mode", "\"imposed_skid\"",
       "carriage.mode must be one of \"imposed_slip\", \"imposed_speed\", \"constant_load\", "
       "\"ramped_load\", got \"imposed_skid\"; did you mean \"imposed_slip\"?"},
      {none, "carriage.slip", "1.5", "carriage.slip must be in [-1, 1], got 1.5"},
      {{{"carriage.mode", "\"imposed_speed\""}, {"carriage.slip", ""}},
       "carriage.speed",
       "\"fast\"",
       "carriage.speed must be a number in m/s, got a string"},
      {{{"carriage.mode", "\"constant_load\""}, {"carriage.slip", ""}},
       "carriage.load",
       "inf",
       "carriage.load must be a finite number in N, got inf"},
      {ramped, "carriage.load_start", "true",
       "carriage.load_start must be a number in N, got a boolean"},
      {ramped, "carriage.load_end", "[1]", "carriage.load_end must be a number in N, got an array"},
      {ramped, "carriage.ramp_time", "0", "carriage.ramp_time must be > 0 s, got 0"},
      {none, "run.dt", "0", "run.dt must be > 0 s, got 0"},
      {none, "run.duration", "-1", "run.duration must be > 0 s, got -1"},
      {none, "run.release_gap", "-0.1", "run.release_gap must be >= 0 m, got -0.1"},
      {none, "run.release_speed", "0", "run.release_speed must be > 0 m/s, got 0"},
      {none, "run.release_timeout", "0", "run.release_timeout must be > 0 s, got 0"},
      {none, "run.settle_velocity", "0", "run.settle_velocity must be > 0 m/s, got 0"},
      {none, "run.settle_window", "-1", "run.settle_window must be >= 0 s, got -1"},
      {none, "run.settle_min_time", "-1", "run.settle_min_time must be >= 0 s, got -1"},
      {none, "run.settle_max_time", "0", "run.settle_max_time must be > 0 s, got 0"},
      {none, "terrain.type", "\"sand\"",
       "terrain.type must be one of \"flat\", \"dem\", \"scm\", got \"sand\""},
      {none, "terrain.surface_height", "\"zero\"",
       "terrain.surface_height must be a number in m, got a string"},
      {none, "terrain.stiffness", "0", "terrain.stiffness must be > 0 N/m, got 0"},
      {none, "terrain.damping", "-1", "terrain.damping must be >= 0 N s/m, got -1"},
      {none, "terrain.friction", "-0.1",
       "terrain.friction must be >= 0 (friction coefficient), got -0.1"},
      {none, "terrain.friction_model", "\"coulumb\"", "did you mean \"coulomb\"?"},
      {none, "terrain.tangential_stiffness", "0",
       "terrain.tangential_stiffness must be > 0 N/m, got 0"},
      {none, "terrain.tangential_damping", "-1",
       "terrain.tangential_damping must be >= 0 N s/m, got -1"},
      {regularized, "terrain.slip_velocity_scale", "0",
       "terrain.slip_velocity_scale must be > 0 m/s, got 0"},
      {dem, "terrain.endpoint", "\"localhost:5555\"",
       "terrain.endpoint must start with ipc:// or tcp://, got \"localhost:5555\""},
      {dem, "terrain.timeout", "0", "terrain.timeout must be > 0 s, got 0"},
      {scm, "terrain.soil", "1", "terrain.soil must be a string, got an integer"},
      {scm, "terrain.grid_spacing", "0", "terrain.grid_spacing must be > 0 m, got 0"},
      {scm, "terrain.grid_length", "-3", "terrain.grid_length must be > 0 m, got -3"},
      {scm, "terrain.damping", "-1", "terrain.damping must be >= 0 Pa s/m, got -1"},
      {scm, "terrain.grid_width", "0", "terrain.grid_width must be > 0 m, got 0"},
      {scm, "terrain.normal_direction", "\"normal\"",
       "terrain.normal_direction must be one of \"surface\", \"vertical\", got \"normal\""},
      {scm, "terrain.shear_surface", "\"tips\"",
       "terrain.shear_surface must be one of \"wheel\", \"lug_tips\", got \"tips\""},
      {scm, "terrain.elastic_stiffness", "0", "terrain.elastic_stiffness must be > 0 Pa/m, got 0"},
      {scm, "terrain.bulldozing", "1", "terrain.bulldozing must be true or false, got an integer"},
      {scm, "terrain.erosion_angle", "90", "terrain.erosion_angle must be in (0, 90) deg, got 90"},
      {scm, "terrain.flow_factor", "-1",
       "terrain.flow_factor must be >= 0 (fraction of the displaced volume), got -1"},
      {scm, "terrain.erosion_iterations", "-1", "terrain.erosion_iterations must be >= 0, got -1"},
      {scm, "terrain.erosion_rings", "0", "terrain.erosion_rings must be >= 1, got 0"},
      {scm, "terrain.snapshot_times", "[1, -2]", "terrain.snapshot_times must be >= 0 s, got -2"},
      {scm, "terrain.snapshot_interval", "-1", "terrain.snapshot_interval must be >= 0 s, got -1"},
      {scm, "terrain.snapshot_fields", "[\"heigth\"]",
       "unknown field \"heigth\"; expected some of height"},
      {none, "output.file", "\"\"", "output.file must be a file name, e.g. \"run.h5\", got \"\""},
      {none, "output.every", "0", "output.every must be >= 1 steps, got 0"},
      {none, "output.flush_interval", "-5", "output.flush_interval must be >= 1 steps, got -5"},
      {none, "output.progress_interval", "-1", "output.progress_interval must be >= 0 s, got -1"},
  };
  std::vector<std::string> covered;
  for (const auto &c : cases) {
    Tables t = base();
    for (const auto &[k, v] : c.setup)
      t = with(t, k, v);
    // The setup alone parses, or fails only for want of the key under test.
    const std::string setup_error = error_of(t);
    EXPECT_TRUE(setup_error == "(no error)" || setup_error.find(c.key) != std::string::npos)
        << "setup of " << c.key << ": " << setup_error;
    t = with(t, c.key, c.bad);
    const std::string e = error_of(t);
    EXPECT_NE(e.find(c.message), std::string::npos) << c.key << ": " << e;
    EXPECT_EQ(e.rfind("test.toml:", 0), 0u) << e; // source and line first
    covered.push_back(c.key);
  }
  // Every key of every table is range/type checked here.
  for (const auto &k : rig_config_keys())
    EXPECT_NE(std::find(covered.begin(), covered.end(), k), covered.end()) << "no case for " << k;
}

// A locked wheel (motor.omega = 0) needs an imposed carriage speed; negative ω never.
TEST(RigConfig, LockedWheelOnlyWithImposedSpeed) {
  Tables speed = with(with(base(), "carriage.mode", "\"imposed_speed\""), "carriage.slip", "");
  speed = with(speed, "carriage.speed", "0.2");
  const RigConfig c = parse_rig_config(render(with(speed, "motor.omega", "0")), "test.toml");
  EXPECT_EQ(c.carriage.mode, CarriageMode::imposed_speed);
  EXPECT_EQ(c.motor.mode, MotorMode::omega);
  EXPECT_EQ(c.motor.omega_rad_s, 0.0);
  EXPECT_NE(error_of(with(speed, "motor.omega", "-0.5"))
                .find("motor.omega must be >= 0 rad/s with carriage.mode = \"imposed_speed\" "
                      "(0 = a locked wheel), got -0.5"),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "motor.omega", "0"))
                .find("motor.omega must be > 0 rad/s, got 0 (a locked wheel, omega = 0, needs "
                      "carriage.mode = \"imposed_speed\""),
            std::string::npos);
  EXPECT_NE(error_of(with(with(base(), "carriage.mode", "\"constant_load\""), "motor.omega", "0"))
                .find("motor.omega must be > 0 rad/s"),
            std::string::npos);
}

TEST(RigConfig, UnknownKeysAndTablesSuggestTheRightName) {
  EXPECT_NE(error_of(with(base(), "wheel.radius", "0.6"))
                .find("unknown key 'wheel.radius'; did you mean 'wheel.effective_radius'?"),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "rig.spring_K", "1")).find("did you mean 'rig.spring_k'?"),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "wheel.spring_c", "1"))
                .find("unknown key 'wheel.spring_c'; 'spring_c' belongs in [rig]"),
            std::string::npos);
  EXPECT_NE(
      error_of(with(base(), "whel.mass", "1")).find("unknown table [whel]; did you mean [wheel]?"),
      std::string::npos);
  EXPECT_NE(error_of(with(base(), "output.zzz", "1")).find("the keys of [output] are file, every"),
            std::string::npos);
  // With the line number of the offending key.
  const std::string e = error_of(with(base(), "run.dtt", "1"));
  EXPECT_NE(e.find("test.toml:"), std::string::npos);
  EXPECT_NE(e.find("did you mean 'run.dt'?"), std::string::npos) << e;
}

TEST(RigConfig, ModeConsistencyAndRequiredKeys) {
  EXPECT_NE(error_of(with(base(), "carriage.load", "100"))
                .find("carriage.load is not used with carriage.mode = \"imposed_slip\""),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "terrain.endpoint", "\"ipc:///x\""))
                .find("terrain.endpoint is not used with terrain.type = \"flat\""),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "run.dt", "")).find("missing key 'run.dt'"), std::string::npos);
  EXPECT_NE(error_of(with(base(), "carriage.slip", "")).find("missing key 'carriage.slip'"),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "motor.torque", "5")).find("either motor.omega"),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "rig.vertical_load", "13000")).find("either rig.suspended_mass"),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "wheel.inertia", "")).find("missing key 'wheel.inertia'"),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "wheel.density", "7800")).find("wheel.density needs wheel.mesh"),
            std::string::npos);
  EXPECT_NE(error_of(with(base(), "wheel.effective_radius", "")).find("wheel.effective_radius"),
            std::string::npos);
  EXPECT_NE(
      error_of(with(base(), "run.settle_max_time", "0.01")).find("settle_max_time must be >="),
      std::string::npos);
  Tables no_run = base();
  no_run.erase(no_run.begin() + 4);
  EXPECT_NE(error_of(no_run).find("missing table [run]"), std::string::npos);
  EXPECT_NE(error_of(base()).find("(no error)"), std::string::npos);
  try {
    parse_rig_config("[wheel\nmass = 1", "bad.toml");
    FAIL();
  } catch (const RigConfigError &e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:1: TOML syntax error"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(load_rig_config("/nonexistent/rig.toml"), RigConfigError);
}

TEST(RigConfig, VerticalLoadSizesTheSuspendedMass) {
  const RigConfig c = parse_rig_config(
      render(with(with(base(), "rig.suspended_mass", ""), "rig.vertical_load", "13200")), "t");
  const WheelProperties w = resolve_wheel_properties(c.wheel);
  const RigParameters p = rig_parameters(c, w);
  EXPECT_NEAR((p.wheel_mass_kg + p.spindle_mass_kg + p.suspended_mass_kg) * 9.81, 13200.0, 1e-9);
  const RigConfig small = parse_rig_config(
      render(with(with(base(), "rig.suspended_mass", ""), "rig.vertical_load", "1000")), "t");
  EXPECT_THROW(rig_parameters(small, w), RigConfigError);
}

TEST(RigConfig, ExampleFileLoadsAndRuns) {
  const RigConfig c = load_rig_config(RIG_EXAMPLE_CONFIG);
  EXPECT_EQ(c.terrain.type, TerrainType::flat);
  EXPECT_EQ(c.carriage.mode, CarriageMode::imposed_slip);
  EXPECT_DOUBLE_EQ(*c.rig.vertical_load_N, 13200.0);
  EXPECT_FALSE(c.text.empty());
  RigSimulation sim(c);
  EXPECT_DOUBLE_EQ(sim.wheel().effective_radius_m, 0.617);
  FlatGround g = make_flat_ground(sim.config(), sim.wheel());
  for (int i = 0; i < 1000; ++i)
    sim.advance(g.contact(sim.wheel_state(), sim.time_s()));
  EXPECT_EQ(sim.phase(), Phase::release);
}

// A regular n-gon prism (the wheel frame: axle +y), written as OBJ; mass and axle inertia from the
// density must match the prism's closed form, the rim radius its circumradius.
TEST(RigConfig, WheelMassPropertiesFromMeshAndDensity) {
  const int n = 64;
  const double R = 0.5, w = 0.3, rho = 1000.0;
  geometry::TriangleMesh m;
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      m.vertices_m.emplace_back(R * std::cos(a), side ? w / 2 : -w / 2, R * std::sin(a));
    }
  m.vertices_m.emplace_back(0, -w / 2, 0);
  m.vertices_m.emplace_back(0, w / 2, 0);
  const int c0 = 2 * n, c1 = 2 * n + 1;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    // Outward: the -y cap seen from -y, the +y cap from +y, the side from outside.
    m.triangles.push_back({c0, i, j});
    m.triangles.push_back({c1, n + j, n + i});
    m.triangles.push_back({i, n + i, n + j});
    m.triangles.push_back({i, n + j, j});
  }
  const auto dir = std::filesystem::temp_directory_path() / "wheelsim_test_rig";
  std::filesystem::create_directories(dir);
  geometry::write_obj(m, (dir / "prism.obj").string());
  {
    std::ofstream f(dir / "rig.toml");
    f << render(with(with(with(with(base(), "wheel.mass", ""), "wheel.inertia", ""),
                          "wheel.effective_radius", ""),
                     "wheel.density", "1000"))
      << "";
  }
  // wheel.mesh relative to the config file's directory.
  std::string text;
  {
    std::ifstream f(dir / "rig.toml");
    std::stringstream ss;
    ss << f.rdbuf();
    text = ss.str();
    text.replace(text.find("[wheel]\n"), 8, "[wheel]\nmesh = \"prism.obj\"\n");
    std::ofstream o(dir / "rig.toml");
    o << text;
  }
  const RigConfig c = load_rig_config((dir / "rig.toml").string());
  EXPECT_EQ(c.wheel.mesh, (dir / "prism.obj").string());
  const WheelProperties p = resolve_wheel_properties(c.wheel);
  const double area = 0.5 * n * R * R * std::sin(2 * M_PI / n);
  const double mass = rho * area * w;
  const double I = mass * R * R / 6.0 * (1.0 + 2.0 * std::pow(std::cos(M_PI / n), 2));
  EXPECT_NEAR(p.mass_kg, mass, 1e-6 * mass);
  EXPECT_NEAR(p.axle_inertia_kg_m2, I, 1e-6 * I);
  EXPECT_NEAR(p.rim_radius_m, R, 1e-6);
  EXPECT_NEAR(p.effective_radius_m, R, 1e-6);
  std::filesystem::remove_all(dir);
}

TEST(RigConfig, EveryKeyIsDocumented) {
  std::ifstream f(RIG_CONFIG_DOC);
  ASSERT_TRUE(f) << RIG_CONFIG_DOC;
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string doc = ss.str();
  for (const auto &k : rig_config_keys())
    EXPECT_NE(doc.find("`" + k + "`"), std::string::npos) << k << " missing in docs/rig-config.md";
}

// terrain.grid_length and terrain.grid_width bound the soil together (a bin along x and across
// it): one alone is an error at its line naming the key that is missing.
TEST(RigConfig, GridLengthAndWidthAreGivenTogether) {
  Tables scm = with(base(), "terrain.type", "\"scm\"");
  scm = with(with(scm, "terrain.soil", "\"soil.toml\""), "terrain.grid_spacing", "0.01");
  EXPECT_EQ(error_of(scm), "(no error)");
  EXPECT_EQ(error_of(with(with(scm, "terrain.grid_length", "3"), "terrain.grid_width", "1")),
            "(no error)");
  const std::string length_alone = error_of(with(scm, "terrain.grid_length", "3"));
  EXPECT_NE(length_alone.find("terrain.grid_length is given without terrain.grid_width: a "
                              "bounded soil bin needs both"),
            std::string::npos)
      << length_alone;
  EXPECT_NE(length_alone.find("add terrain.grid_width = <extent in m>"), std::string::npos)
      << length_alone;
  EXPECT_EQ(length_alone.rfind("test.toml:", 0), 0u) << length_alone; // with the key's line
  const std::string width_alone = error_of(with(scm, "terrain.grid_width", "1"));
  EXPECT_NE(width_alone.find("terrain.grid_width is given without terrain.grid_length"),
            std::string::npos)
      << width_alone;
}

/// check_time_step's message for `config` with run.dt = `dt` ("(no error)" if it passes).
std::string time_step_error(Tables t, const std::string &dt, const std::string &dt_name) {
  const RigConfig c = parse_rig_config(render(with(std::move(t), "run.dt", dt)), "test.toml");
  try {
    const Rig rig(rig_parameters(c, resolve_wheel_properties(c.wheel)), RigCoordinates{},
                  RigVelocities{});
    check_time_step(c, rig, dt_name);
  } catch (const RigConfigError &e) {
    return e.what();
  }
  return "(no error)";
}

// The time step against the stiffest spring-damper the config fixes (time_step.h): the base rig's
// suspension (12000 N/m, 800 N s/m on the 235.8 kg reduced mass of 305 kg and 1040 kg: limit
// 0.2215 s) and the flat ground's contact (1e7 N/m, 2e4 N s/m on 305 kg: limit 9.22 ms). The
// message names the time step as given, its value, the binding limit and where it comes from.
TEST(RigConfig, TimeStepAboveTheRigsStabilityLimitIsAnError) {
  EXPECT_EQ(time_step_error(base(), "1e-4", "run.dt"), "(no error)");
  const std::string flat = time_step_error(base(), "1.0", "--dt");
  EXPECT_NE(flat.find("test.toml: --dt = 1 s is at or above the stability limit 0.00922"),
            std::string::npos)
      << flat;
  EXPECT_NE(flat.find("of the flat ground's contact (terrain.stiffness = 1e+07 N/m, "
                      "terrain.damping = 20000 N s/m on wheel + spindle, 305 kg)"),
            std::string::npos)
      << flat;
  EXPECT_NE(flat.find("reduce --dt below 0.00922"), std::string::npos) << flat;
  EXPECT_NE(time_step_error(base(), "0.0093", "run.dt").find("run.dt = 0.0093 s is at or above"),
            std::string::npos);
  EXPECT_EQ(time_step_error(base(), "0.0092", "run.dt"), "(no error)");
  // Without a contact the config fixes (SCM: it stiffens with its area; DEM: LIGGGHTS'), the
  // suspension bounds the step.
  Tables dem = with(base(), "terrain.type", "\"dem\"");
  dem = with(dem, "terrain.endpoint", "\"ipc:///tmp/x\"");
  EXPECT_EQ(time_step_error(dem, "0.2", "--dt"), "(no error)");
  const std::string suspension = time_step_error(dem, "1.0", "--dt");
  EXPECT_NE(suspension.find("--dt = 1 s is at or above the stability limit 0.2215"),
            std::string::npos)
      << suspension;
  EXPECT_NE(suspension.find("of the suspension (rig.spring_k = 12000 N/m, rig.spring_c = 800 N "
                            "s/m between wheel + spindle, 305 kg, and the suspended mass, 1040 "
                            "kg: reduced mass 235.8"),
            std::string::npos)
      << suspension;
  EXPECT_NE(suspension.find("natural period 0.88"), std::string::npos) << suspension;
}

// The terrain types and carriage modes come from their registries (terrain_registry.h,
// slip_modes.h): an unknown name is rejected with the registry's list.
TEST(RigConfig, UnknownTerrainTypeListsTheRegistry) {
  const std::string e = error_of(with(base(), "terrain.type", "\"mud\""));
  EXPECT_NE(e.find("terrain.type must be one of "), std::string::npos) << e;
  ASSERT_EQ(terrain_names().size(), 3u);
  for (const std::string &name : terrain_names())
    EXPECT_NE(e.find("\"" + name + "\""), std::string::npos) << name << " missing in: " << e;
  EXPECT_NE(error_of(with(base(), "terrain.type", "\"flatt\"")).find("did you mean \"flat\"?"),
            std::string::npos);
}

TEST(RigConfig, UnknownCarriageModeListsTheRegistry) {
  const std::string e = error_of(with(base(), "carriage.mode", "\"towed\""));
  ASSERT_EQ(slip_mode_names().size(), 4u);
  for (const std::string &name : slip_mode_names())
    EXPECT_NE(e.find("\"" + name + "\""), std::string::npos) << name << " missing in: " << e;
}

// Each registry entry names its own type/mode, and every key of the schema is one the parser
// accepts; the SCM bulldozing defaults are the SCM module's (one source: scm_terrain.h).
TEST(RigConfig, RegistriesAndSchemaAgree) {
  for (const TerrainKind &k : terrain_kinds())
    EXPECT_STREQ(to_string(k.type), k.name);
  for (const SlipMode &m : slip_modes())
    EXPECT_STREQ(to_string(m.mode), m.name);
  const std::vector<std::string> keys = rig_config_keys();
  for (const ConfigKey &k : rig_config_schema())
    EXPECT_NE(std::find(keys.begin(), keys.end(), k.table + "." + k.key), keys.end()) << k.key;
  const scm::BulldozingSettings scm_defaults;
  const ScmTerrainConfig rig_defaults;
  EXPECT_EQ(rig_defaults.erosion_rings, scm_defaults.erosion_rings);
  EXPECT_EQ(rig_defaults.erosion_rings, 10); // what every wheel-rig SCM run has used
  EXPECT_EQ(rig_defaults.erosion_iterations, scm_defaults.erosion_iterations);
  EXPECT_EQ(rig_defaults.erosion_angle_deg, scm_defaults.erosion_angle_deg);
}

} // namespace
} // namespace wheelsim::rig
