#include "wheelsim/rig/rig_config.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <toml++/toml.h>

#include "wheelsim/config_messages.h"

namespace wheelsim::rig {
namespace {

using config::closest;
using config::fmt;
using config::type_name;

// ---- the schema: every table and key (docs/rig-config.md lists the same) ----
const std::vector<std::pair<std::string, std::vector<std::string>>> &schema() {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> s = {
      {"wheel", {"mesh", "mesh_scale", "mass", "inertia", "density", "effective_radius"}},
      {"rig",
       {"spindle_mass", "suspended_mass", "vertical_load", "carriage_mass", "spring_k", "spring_c",
        "gravity"}},
      {"motor", {"omega", "torque", "ramp_time"}},
      {"carriage", {"mode", "slip", "speed", "load", "load_start", "load_end", "ramp_time"}},
      {"run",
       {"dt", "duration", "release_gap", "release_speed", "release_timeout", "settle_velocity",
        "settle_window", "settle_min_time", "settle_max_time"}},
      {"terrain",
       {"type",
        "surface_height",
        "endpoint",
        "timeout",
        "soil",
        "grid_spacing",
        "grid_length",
        "grid_width",
        "normal_direction",
        "elastic_stiffness",
        "bulldozing",
        "erosion_angle",
        "flow_factor",
        "erosion_iterations",
        "erosion_rings",
        "snapshot_times",
        "snapshot_interval",
        "snapshot_fields",
        "stiffness",
        "damping",
        "friction",
        "friction_model",
        "tangential_stiffness",
        "tangential_damping",
        "slip_velocity_scale"}},
      {"output", {"file", "every", "flush_interval", "progress_interval"}},
  };
  return s;
}

class Parser {
public:
  Parser(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const toml::node *where, const std::string &message) const {
    throw RigConfigError(config::located(source_, where, message));
  }

  const std::string &source() const { return source_; }

private:
  std::string source_;
};

/// One table of the document, with typed, range-checked getters.
class Table {
public:
  Table(const Parser &p, const toml::table *t, std::string name)
      : p_(p), t_(t), name_(std::move(name)) {}

  bool present() const { return t_ != nullptr; }
  bool has(const std::string &key) const { return t_ && t_->get(key); }
  const toml::node *node(const std::string &key) const { return t_ ? t_->get(key) : nullptr; }
  std::string full(const std::string &key) const { return name_ + "." + key; }

  [[noreturn]] void fail(const std::string &key, const std::string &message) const {
    p_.fail(node(key) ? node(key) : static_cast<const toml::node *>(t_), message);
  }

  std::optional<double> number(const std::string &key, const std::string &unit) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    if (auto i = n->as_integer())
      return static_cast<double>(i->get());
    if (auto f = n->as_floating_point()) {
      if (!std::isfinite(f->get()))
        fail(key, full(key) + " must be a finite number in " + unit + ", got " + fmt(f->get()));
      return f->get();
    }
    fail(key, full(key) + " must be a number in " + unit + ", got " + type_name(*n));
  }

  std::optional<long long> integer(const std::string &key, const std::string &unit) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    if (auto i = n->as_integer())
      return i->get();
    fail(key, full(key) + " must be an integer (" + unit + "), got " + type_name(*n));
  }

  std::optional<std::string> string(const std::string &key) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    if (auto s = n->as_string())
      return s->get();
    fail(key, full(key) + " must be a string, got " + type_name(*n));
  }

  std::optional<bool> boolean(const std::string &key) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    if (auto b = n->as_boolean())
      return b->get();
    fail(key, full(key) + " must be true or false, got " + type_name(*n));
  }

  /// An array of numbers (integers allowed), each finite.
  std::optional<std::vector<double>> numbers(const std::string &key,
                                             const std::string &unit) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    const toml::array *a = n->as_array();
    if (!a)
      fail(key, full(key) + " must be an array of numbers in " + unit + ", got " + type_name(*n));
    std::vector<double> out;
    for (const toml::node &e : *a) {
      if (auto i = e.as_integer())
        out.push_back(static_cast<double>(i->get()));
      else if (auto f = e.as_floating_point(); f && std::isfinite(f->get()))
        out.push_back(f->get());
      else
        fail(key, full(key) + " must be an array of finite numbers in " + unit +
                      ", got an "
                      "element that is " +
                      type_name(e));
    }
    return out;
  }

  std::optional<std::vector<std::string>> strings(const std::string &key) const {
    const toml::node *n = node(key);
    if (!n)
      return std::nullopt;
    const toml::array *a = n->as_array();
    if (!a)
      fail(key, full(key) + " must be an array of strings, got " + type_name(*n));
    std::vector<std::string> out;
    for (const toml::node &e : *a) {
      if (auto str = e.as_string())
        out.push_back(str->get());
      else
        fail(key,
             full(key) + " must be an array of strings, got an element that is " + type_name(e));
    }
    return out;
  }

  std::string choice(const std::string &key, const std::vector<std::string> &allowed,
                     const std::optional<std::string> &fallback) const {
    const auto v = string(key);
    std::string list;
    for (const auto &a : allowed)
      list += (list.empty() ? "\"" : ", \"") + a + "\"";
    if (!v) {
      if (fallback)
        return *fallback;
      p_.fail(t_, "missing key '" + full(key) + "': write " + full(key) + " = one of " + list);
    }
    if (std::find(allowed.begin(), allowed.end(), *v) == allowed.end()) {
      std::string msg = full(key) + " must be one of " + list + ", got \"" + *v + "\"";
      const std::string c = closest(*v, allowed);
      if (!c.empty())
        msg += "; did you mean \"" + c + "\"?";
      fail(key, msg);
    }
    return *v;
  }

  /// A number that must satisfy `ok`; `range` reads like "> 0" and the message is
  /// "<table.key> must be <range> <unit>, got <value>".
  template <class Ok>
  std::optional<double> checked(const std::string &key, const std::string &unit, const char *range,
                                Ok ok) const {
    const auto v = number(key, unit);
    if (v && !ok(*v))
      fail(key,
           full(key) + " must be " + range + (unit.empty() ? "" : " ") + unit + ", got " + fmt(*v));
    return v;
  }
  std::optional<double> positive(const std::string &key, const std::string &unit) const {
    return checked(key, unit, "> 0", [](double v) { return v > 0; });
  }
  std::optional<double> non_negative(const std::string &key, const std::string &unit) const {
    return checked(key, unit, ">= 0", [](double v) { return v >= 0; });
  }
  double required(const std::optional<double> &v, const std::string &key,
                  const std::string &what) const {
    if (!v)
      p_.fail(t_, "missing key '" + full(key) + "': write " + full(key) + " = <" + what + ">");
    return *v;
  }
  /// Rejects keys of this table that the chosen mode does not use.
  void only_with(const std::vector<std::string> &keys, const std::string &mode_key,
                 const std::string &mode) const {
    for (const auto &k : keys)
      if (has(k))
        fail(k, full(k) + " is not used with " + full(mode_key) + " = \"" + mode +
                    "\"; remove it (or choose the " + mode_key + " that uses it)");
  }

private:
  const Parser &p_;
  const toml::table *t_;
  std::string name_;
};

void check_known_keys(const Parser &p, const toml::table &doc) {
  std::vector<std::string> tables;
  for (const auto &[name, keys] : schema())
    tables.push_back(name);
  for (const auto &[k, node] : doc) {
    const std::string key(k.str());
    auto it = std::find_if(schema().begin(), schema().end(),
                           [&](const auto &e) { return e.first == key; });
    if (it == schema().end()) {
      std::string msg = "unknown " + std::string(node.is_table() ? "table [" + key + "]"
                                                                 : "top-level key '" + key + "'");
      const std::string c = closest(key, tables);
      if (!c.empty())
        msg += "; did you mean [" + c + "]?";
      else
        msg += "; the tables are [wheel], [rig], [motor], [carriage], [run], [terrain], [output]";
      p.fail(&node, msg);
    }
    if (!node.is_table())
      p.fail(&node, "'" + key + "' must be a table: write [" + key + "] and its keys below it");
    for (const auto &[sk, snode] : *node.as_table()) {
      const std::string sub(sk.str());
      const auto &known = it->second;
      if (std::find(known.begin(), known.end(), sub) != known.end())
        continue;
      std::string msg = "unknown key '" + key + "." + sub + "'";
      std::string c = closest(sub, known);
      if (!c.empty()) {
        msg += "; did you mean '" + key + "." + c + "'?";
      } else {
        // Maybe it belongs to another table.
        for (const auto &[other, okeys] : schema())
          if (other != key && std::find(okeys.begin(), okeys.end(), sub) != okeys.end()) {
            c = other;
            break;
          }
        if (!c.empty()) {
          msg += "; '" + sub + "' belongs in [" + c + "]";
        } else {
          msg += "; the keys of [" + key + "] are";
          for (std::size_t i = 0; i < known.size(); ++i)
            msg += (i ? ", " : " ") + known[i];
        }
      }
      p.fail(&snode, msg);
    }
  }
}

std::string resolve(const std::string &path, const std::string &base_dir) {
  if (path.empty() || base_dir.empty() || std::filesystem::path(path).is_absolute())
    return path;
  return (std::filesystem::path(base_dir) / path).lexically_normal().string();
}

} // namespace

std::vector<std::string> rig_config_keys() {
  std::vector<std::string> out;
  for (const auto &[table, keys] : schema())
    for (const auto &k : keys)
      out.push_back(table + "." + k);
  return out;
}

const char *to_string(CarriageMode m) {
  switch (m) {
  case CarriageMode::imposed_slip:
    return "imposed_slip";
  case CarriageMode::imposed_speed:
    return "imposed_speed";
  case CarriageMode::constant_load:
    return "constant_load";
  case CarriageMode::ramped_load:
    return "ramped_load";
  }
  return "?";
}

const char *to_string(TerrainType t) {
  switch (t) {
  case TerrainType::flat:
    return "flat";
  case TerrainType::dem:
    return "dem";
  case TerrainType::scm:
    return "scm";
  }
  return "?";
}

RigConfig parse_rig_config(const std::string &text, const std::string &source_name,
                           const std::string &base_dir) {
  const Parser p(source_name);
  toml::table doc;
  try {
    doc = toml::parse(text, source_name);
  } catch (const toml::parse_error &e) {
    throw RigConfigError(config::syntax_error(e, source_name));
  }
  check_known_keys(p, doc);

  auto table = [&](const char *name, bool required) {
    const toml::table *t = doc.get_as<toml::table>(name);
    if (!t && required)
      p.fail(nullptr, std::string("missing table [") + name + "] (see docs/rig-config.md)");
    return Table(p, t, name);
  };

  RigConfig c;
  c.source = source_name;
  c.text = text;

  // [wheel]
  {
    const Table t = table("wheel", true);
    if (auto m = t.string("mesh")) {
      if (m->empty())
        t.fail("mesh", "wheel.mesh must be a file name (OBJ, STL or PLY), got \"\"");
      c.wheel.mesh = resolve(*m, base_dir);
    }
    c.wheel.mesh_scale = t.positive("mesh_scale", "(mesh units -> m)").value_or(1.0);
    c.wheel.mass_kg = t.positive("mass", "kg");
    c.wheel.inertia_kg_m2 = t.positive("inertia", "kg m^2");
    c.wheel.density_kg_m3 = t.positive("density", "kg/m^3");
    c.wheel.effective_radius_m = t.positive("effective_radius", "m");
    if (t.has("mesh_scale") && c.wheel.mesh.empty())
      t.fail("mesh_scale", "wheel.mesh_scale needs wheel.mesh = \"<file>\"; remove it");
    if (c.wheel.density_kg_m3) {
      if (c.wheel.mesh.empty())
        t.fail("density", "wheel.density needs wheel.mesh = \"<file>\" (mass and inertia come "
                          "from the mesh); without a mesh give wheel.mass and wheel.inertia");
      if (c.wheel.mass_kg || c.wheel.inertia_kg_m2)
        t.fail(
            c.wheel.mass_kg ? "mass" : "inertia",
            "give either wheel.density (with the mesh) or wheel.mass and wheel.inertia, not both");
    } else {
      if (!c.wheel.mass_kg)
        p.fail(nullptr, "missing key 'wheel.mass' (kg, > 0) with 'wheel.inertia' (kg m^2 about the "
                        "axle), or 'wheel.density' (kg/m^3) with 'wheel.mesh'");
      if (!c.wheel.inertia_kg_m2)
        t.fail("mass", "missing key 'wheel.inertia': the wheel's moment of inertia about the axle "
                       "in kg m^2 (> 0), required with wheel.mass");
    }
    if (c.wheel.mesh.empty() && !c.wheel.effective_radius_m)
      p.fail(nullptr, "missing key 'wheel.effective_radius' (m, > 0): required without "
                      "wheel.mesh (with a mesh it defaults to the mesh's outer radius)");
  }

  // [rig]
  {
    const Table t = table("rig", true);
    c.rig.spindle_mass_kg = t.non_negative("spindle_mass", "kg").value_or(100.0);
    c.rig.suspended_mass_kg = t.positive("suspended_mass", "kg");
    c.rig.vertical_load_N = t.positive("vertical_load", "N");
    if (c.rig.suspended_mass_kg && c.rig.vertical_load_N)
      t.fail("vertical_load", "give either rig.suspended_mass (kg) or rig.vertical_load (N), "
                              "not both");
    if (!c.rig.suspended_mass_kg && !c.rig.vertical_load_N)
      p.fail(nullptr, "missing key 'rig.suspended_mass' (kg, > 0) or 'rig.vertical_load' (N, the "
                      "total weight on the wheel; the suspended mass is sized from it)");
    c.rig.carriage_mass_kg = t.non_negative("carriage_mass", "kg").value_or(0.0);
    c.rig.spring_k_N_m = t.positive("spring_k", "N/m").value_or(12000.0);
    c.rig.spring_c_N_s_m = t.non_negative("spring_c", "N s/m").value_or(800.0);
    c.rig.gravity_m_s2 = t.positive("gravity", "m/s^2").value_or(9.81);
  }

  // [motor]
  {
    const Table t = table("motor", true);
    // A locked wheel (omega = 0) is driven by the carriage alone: only with an imposed carriage
    // speed (carriage.mode is checked in full below).
    const toml::table *carriage = doc.get_as<toml::table>("carriage");
    const toml::node *carriage_mode = carriage ? carriage->get("mode") : nullptr;
    const bool speed_imposed =
        carriage_mode && carriage_mode->value<std::string>() == std::string("imposed_speed");
    const auto omega = t.number("omega", "rad/s");
    if (omega && speed_imposed && !(*omega >= 0))
      t.fail("omega", "motor.omega must be >= 0 rad/s with carriage.mode = \"imposed_speed\" "
                      "(0 = a locked wheel), got " +
                          fmt(*omega));
    if (omega && !speed_imposed && !(*omega > 0))
      t.fail("omega", "motor.omega must be > 0 rad/s, got " + fmt(*omega) +
                          (*omega == 0 ? " (a locked wheel, omega = 0, needs carriage.mode = "
                                         "\"imposed_speed\" with carriage.speed > 0)"
                                       : ""));
    const auto torque = t.number("torque", "N m");
    if (omega && torque)
      t.fail("torque", "give either motor.omega (rad/s) or motor.torque (N m), not both");
    if (!omega && !torque)
      p.fail(nullptr, "missing key 'motor.omega' (imposed angular speed in rad/s, > 0; 0 with "
                      "carriage.mode = \"imposed_speed\": a locked wheel) or 'motor.torque' "
                      "(imposed torque in N m)");
    if (torque && *torque == 0.0)
      t.fail("torque", "motor.torque must be != 0 N m, got 0");
    c.motor.mode = omega ? MotorMode::omega : MotorMode::torque;
    c.motor.omega_rad_s = omega.value_or(0.0);
    c.motor.torque_Nm = torque.value_or(0.0);
    c.motor.ramp_time_s = t.non_negative("ramp_time", "s").value_or(1.0);
  }

  // [carriage]
  {
    const Table t = table("carriage", true);
    const std::string mode = t.choice(
        "mode", {"imposed_slip", "imposed_speed", "constant_load", "ramped_load"}, std::nullopt);
    if (mode == "imposed_slip") {
      c.carriage.mode = CarriageMode::imposed_slip;
      t.only_with({"speed", "load", "load_start", "load_end", "ramp_time"}, "mode", mode);
      c.carriage.slip = t.required(
          t.checked("slip", "", "in [-1, 1]", [](double v) { return v >= -1 && v <= 1; }), "slip",
          "slip in [-1, 1], e.g. 0.2");
    } else if (mode == "imposed_speed") {
      c.carriage.mode = CarriageMode::imposed_speed;
      t.only_with({"slip", "load", "load_start", "load_end", "ramp_time"}, "mode", mode);
      c.carriage.speed_m_s = t.required(t.number("speed", "m/s"), "speed", "speed in m/s");
    } else if (mode == "constant_load") {
      c.carriage.mode = CarriageMode::constant_load;
      t.only_with({"slip", "speed", "load_start", "load_end", "ramp_time"}, "mode", mode);
      c.carriage.load_N = t.required(t.number("load", "N"), "load", "drawbar load in N");
    } else {
      c.carriage.mode = CarriageMode::ramped_load;
      t.only_with({"slip", "speed", "load"}, "mode", mode);
      c.carriage.load_start_N =
          t.required(t.number("load_start", "N"), "load_start", "drawbar load at the start, N");
      c.carriage.load_end_N =
          t.required(t.number("load_end", "N"), "load_end", "drawbar load at the end, N");
      c.carriage.ramp_time_s =
          t.required(t.positive("ramp_time", "s"), "ramp_time", "duration of the load ramp, s");
    }
  }

  // [run]
  {
    const Table t = table("run", true);
    // dt may be left out for DEM: the run then takes the bed's LIGGGHTS time step (wheel-rig
    // --dt, which scripts/wheel-cosim passes from the bed's .vars); required otherwise (below).
    c.run.dt_s = t.positive("dt", "s").value_or(0.0);
    c.run.duration_s = t.required(t.positive("duration", "s"), "duration", "test phase length, s");
    if (c.run.dt_s > 0.0 && c.run.duration_s < c.run.dt_s)
      t.fail("duration", "run.duration must be >= run.dt (" + fmt(c.run.dt_s) + " s), got " +
                             fmt(c.run.duration_s));
    c.run.release_gap_m = t.non_negative("release_gap", "m").value_or(0.002);
    c.run.release_speed_m_s = t.positive("release_speed", "m/s").value_or(0.01);
    c.run.release_timeout_s = t.positive("release_timeout", "s").value_or(10.0);
    c.run.settle_velocity_m_s = t.positive("settle_velocity", "m/s").value_or(1e-3);
    c.run.settle_window_s = t.non_negative("settle_window", "s").value_or(0.05);
    c.run.settle_min_time_s = t.non_negative("settle_min_time", "s").value_or(0.1);
    c.run.settle_max_time_s = t.positive("settle_max_time", "s").value_or(5.0);
    if (c.run.settle_max_time_s < c.run.settle_min_time_s)
      t.fail("settle_max_time", "run.settle_max_time must be >= run.settle_min_time (" +
                                    fmt(c.run.settle_min_time_s) + " s), got " +
                                    fmt(c.run.settle_max_time_s));
  }

  // [terrain]
  {
    const Table t = table("terrain", true);
    const std::string type = t.choice("type", {"flat", "dem", "scm"}, std::nullopt);
    c.terrain.surface_height_m = t.number("surface_height", "m").value_or(0.0);
    const std::vector<std::string> dem_keys = {"endpoint", "timeout"};
    const std::vector<std::string> scm_keys = {"soil",
                                               "grid_spacing",
                                               "grid_length",
                                               "grid_width",
                                               "normal_direction",
                                               "elastic_stiffness",
                                               "bulldozing",
                                               "erosion_angle",
                                               "flow_factor",
                                               "erosion_iterations",
                                               "erosion_rings",
                                               "snapshot_times",
                                               "snapshot_interval",
                                               "snapshot_fields"};
    // terrain.damping belongs to flat [N s/m] and scm [Pa s/m]
    const std::vector<std::string> flat_keys = {"stiffness",          "friction",
                                                "friction_model",     "tangential_stiffness",
                                                "tangential_damping", "slip_velocity_scale"};
    if (type == "dem") {
      c.terrain.type = TerrainType::dem;
      t.only_with(scm_keys, "type", type);
      t.only_with(flat_keys, "type", type);
      t.only_with({"damping"}, "type", type);
      const auto ep = t.string("endpoint");
      if (!ep)
        p.fail(nullptr, "missing key 'terrain.endpoint': write e.g. terrain.endpoint = "
                        "\"ipc:///tmp/wheelsim.ipc\" or \"tcp://127.0.0.1:5555\"");
      if (ep->rfind("ipc://", 0) != 0 && ep->rfind("tcp://", 0) != 0)
        t.fail("endpoint",
               "terrain.endpoint must start with ipc:// or tcp://, got \"" + *ep + "\"");
      c.terrain.endpoint = *ep;
      c.terrain.timeout_s = t.positive("timeout", "s").value_or(60.0);
    } else if (type == "scm") {
      c.terrain.type = TerrainType::scm;
      t.only_with(dem_keys, "type", type);
      t.only_with(flat_keys, "type", type);
      const auto soil = t.string("soil");
      if (!soil || soil->empty())
        p.fail(nullptr, "missing key 'terrain.soil': the SCM soil file, e.g. terrain.soil = "
                        "\"inputs/scm_soils/lete_sand.toml\"");
      ScmTerrainConfig &m = c.terrain.scm;
      m.soil = resolve(*soil, base_dir);
      m.grid_spacing_m =
          t.required(t.positive("grid_spacing", "m"), "grid_spacing", "grid node spacing in m");
      m.grid_length_m = t.positive("grid_length", "m");
      m.grid_width_m = t.positive("grid_width", "m");
      for (const char *extent : {"grid_length", "grid_width"})
        if (const auto v = t.number(extent, "m"); v && *v < m.grid_spacing_m)
          t.fail(extent, t.full(extent) + " must be >= terrain.grid_spacing (" +
                             fmt(m.grid_spacing_m) + " m), got " + fmt(*v) + " m");
      m.vertical_normal = t.choice("normal_direction", {"surface", "vertical"},
                                   std::string("surface")) == "vertical";
      m.elastic_stiffness_Pa_m = t.positive("elastic_stiffness", "Pa/m");
      m.damping_Pa_s_m = t.non_negative("damping", "Pa s/m"); // flat: N s/m
      m.bulldozing = t.boolean("bulldozing").value_or(true);
      if (!m.bulldozing)
        for (const char *k :
             {"erosion_angle", "flow_factor", "erosion_iterations", "erosion_rings"})
          if (t.has(k))
            t.fail(k, t.full(k) + " is not used with terrain.bulldozing = false; remove it");
      m.erosion_angle_deg = t.checked("erosion_angle", "deg", "in (0, 90)", [](double v) {
                               return v > 0 && v < 90;
                             }).value_or(m.erosion_angle_deg);
      m.flow_factor = t.non_negative("flow_factor", "(fraction of the displaced volume)")
                          .value_or(m.flow_factor);
      m.erosion_iterations =
          t.integer("erosion_iterations", "sweeps per step").value_or(m.erosion_iterations);
      if (m.erosion_iterations < 0)
        t.fail("erosion_iterations", "terrain.erosion_iterations must be >= 0, got " +
                                         std::to_string(m.erosion_iterations));
      m.erosion_rings = t.integer("erosion_rings", "rings of nodes").value_or(m.erosion_rings);
      if (m.erosion_rings < 1)
        t.fail("erosion_rings",
               "terrain.erosion_rings must be >= 1, got " + std::to_string(m.erosion_rings));
      if (auto times = t.numbers("snapshot_times", "s")) {
        for (double v : *times)
          if (v < 0)
            t.fail("snapshot_times", "terrain.snapshot_times must be >= 0 s, got " + fmt(v));
        m.snapshot_times_s = *times;
        std::sort(m.snapshot_times_s.begin(), m.snapshot_times_s.end());
      }
      m.snapshot_interval_s = t.non_negative("snapshot_interval", "s").value_or(0.0);
      if (auto fields = t.strings("snapshot_fields")) {
        const std::vector<std::string> allowed = {"height",   "sinkage",      "plastic_sinkage",
                                                  "pressure", "shear_stress", "shear_displacement"};
        for (const std::string &f : *fields)
          if (std::find(allowed.begin(), allowed.end(), f) == allowed.end()) {
            std::string msg = "terrain.snapshot_fields: unknown field \"" + f +
                              "\"; expected some of height, sinkage, plastic_sinkage, pressure, "
                              "shear_stress, shear_displacement";
            const std::string cl = closest(f, allowed);
            if (!cl.empty())
              msg += "; did you mean \"" + cl + "\"?";
            t.fail("snapshot_fields", msg);
          }
        m.snapshot_fields = *fields;
      }
    } else {
      c.terrain.type = TerrainType::flat;
      t.only_with(dem_keys, "type", type);
      t.only_with(scm_keys, "type", type);
      auto &f = c.terrain.flat;
      f.surface_height_m = c.terrain.surface_height_m;
      f.stiffness_N_m = t.positive("stiffness", "N/m").value_or(f.stiffness_N_m);
      f.damping_N_s_m = t.non_negative("damping", "N s/m").value_or(f.damping_N_s_m);
      f.friction = t.non_negative("friction", "(friction coefficient)").value_or(f.friction);
      const std::string fm =
          t.choice("friction_model", {"coulomb", "regularized"}, std::string("coulomb"));
      f.friction_model = fm == "coulomb" ? FrictionModel::coulomb : FrictionModel::regularized;
      if (f.friction_model == FrictionModel::coulomb)
        t.only_with({"slip_velocity_scale"}, "friction_model", fm);
      else
        t.only_with({"tangential_stiffness", "tangential_damping"}, "friction_model", fm);
      f.tangential_stiffness_N_m =
          t.positive("tangential_stiffness", "N/m").value_or(f.tangential_stiffness_N_m);
      f.tangential_damping_N_s_m =
          t.non_negative("tangential_damping", "N s/m").value_or(f.tangential_damping_N_s_m);
      f.slip_velocity_scale_m_s =
          t.positive("slip_velocity_scale", "m/s").value_or(f.slip_velocity_scale_m_s);
    }
  }

  if (c.run.dt_s == 0.0 && c.terrain.type != TerrainType::dem) {
    const Table t = table("run", true);
    t.required(t.positive("dt", "s"), "dt", "time step in s (only a DEM run may leave it out)");
  }

  // [output]
  {
    const Table t = table("output", false);
    if (auto f = t.string("file")) {
      if (f->empty())
        t.fail("file", "output.file must be a file name, e.g. \"run.h5\", got \"\"");
      c.output.file = *f;
    }
    auto at_least_one = [&](const char *key, long long fallback) {
      const auto v = t.integer(key, "steps");
      if (v && *v < 1)
        t.fail(key, t.full(key) + " must be >= 1 steps, got " + std::to_string(*v));
      return v.value_or(fallback);
    };
    c.output.every = at_least_one("every", 1);
    c.output.flush_interval = at_least_one("flush_interval", 1000);
    c.output.progress_interval_s = t.non_negative("progress_interval", "s").value_or(10.0);
  }
  return c;
}

RigConfig load_rig_config(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw RigConfigError(path + ": cannot open the rig config file (check the path given to "
                                "--config)");
  std::ostringstream ss;
  ss << in.rdbuf();
  const auto dir = std::filesystem::path(path).parent_path().string();
  return parse_rig_config(ss.str(), path, dir.empty() ? "." : dir);
}

} // namespace wheelsim::rig
