// terrain.type = "scm": the SCM soft soil in-process (scm/, docs/scm.md): soil file, grid,
// model settings, snapshots; /parameters/terrain/* records the soil and the grid.
#include "terrains.h"

#include "../config_table.h"
#include "wheelsim/rig/run_health.h"
#include "wheelsim/rig/scm_ground.h"
#include "wheelsim/scm/chrono_soil.h"

#include <fstream>
#include <sstream>

namespace wheelsim::rig::terrains {
namespace scm_entry {

using detail::closest;
using detail::fmt;
using detail::Table;

const std::vector<std::string> kSnapshotFields = {"height",   "sinkage",      "plastic_sinkage",
                                                  "pressure", "shear_stress", "shear_displacement"};

ConfigKey scm(ConfigKey k) { return terrain_key("scm", std::move(k)); }

std::string toml_strings(const std::vector<std::string> &v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i ? ", \"" : "\"") + v[i] + "\"";
  return s + "]";
}

std::vector<ConfigKey> keys() {
  const ScmTerrainConfig d;
  return {
      scm({"", "soil", "path", "", "", "SCM soil file, relative to the config file"}),
      scm({"", "grid_spacing", "number", "m", "", "> 0"}),
      scm({"", "grid_length", "number", "m", "unbounded",
           ">= grid_spacing; with grid_width; >= 2 rim radii + the carriage's travel"}),
      scm({"", "grid_width", "number", "m", "unbounded",
           ">= grid_spacing; with grid_length; >= the wheel's width"}),
      scm({"", "normal_direction", "string", "", "\"surface\"",
           "one of \"surface\", \"vertical\""}),
      scm({"", "shear_surface", "string", "", "\"wheel\"",
           "one of \"wheel\" (the surface point above each node, as Chrono), \"lug_tips\" (the "
           "point at the same angle at R_eff: soil between the lugs turns with the wheel)"}),
      scm({"", "elastic_stiffness", "number", "Pa/m", "soil file", "> 0"}),
      scm({"", "damping", "number", "Pa s/m", "soil file", ">= 0"}),
      scm({"", "bulldozing", "boolean", "", d.bulldozing ? "true" : "false", ""}),
      scm({"", "erosion_angle", "number", "deg", fmt(d.erosion_angle_deg), "in (0, 90)"}),
      scm({"", "flow_factor", "number", "", fmt(d.flow_factor), ">= 0"}),
      scm({"", "erosion_iterations", "integer", "", std::to_string(d.erosion_iterations), ">= 0"}),
      scm({"", "erosion_rings", "integer", "", std::to_string(d.erosion_rings), ">= 1"}),
      scm({"", "snapshot_times", "array of numbers", "s", "[]", "each >= 0"}),
      scm({"", "snapshot_interval", "number", "s", fmt(d.snapshot_interval_s), ">= 0; 0 = off"}),
      scm({"", "snapshot_fields", "array of strings", "", toml_strings(d.snapshot_fields),
           "any of " + toml_strings(kSnapshotFields)}),
  };
}

void parse_bulldozing(const Table &t, ScmTerrainConfig &m) {
  m.bulldozing = t.boolean("bulldozing").value_or(m.bulldozing);
  if (!m.bulldozing)
    for (const char *k : {"erosion_angle", "flow_factor", "erosion_iterations", "erosion_rings"})
      if (t.has(k))
        t.fail(k, t.full(k) + " is not used with terrain.bulldozing = false; remove it");
  m.erosion_angle_deg = t.checked("erosion_angle", "deg", "in (0, 90)", [](double v) {
                           return v > 0 && v < 90;
                         }).value_or(m.erosion_angle_deg);
  m.flow_factor =
      t.non_negative("flow_factor", "(fraction of the displaced volume)").value_or(m.flow_factor);
  m.erosion_iterations =
      t.integer("erosion_iterations", "sweeps per step").value_or(m.erosion_iterations);
  if (m.erosion_iterations < 0)
    t.fail("erosion_iterations",
           "terrain.erosion_iterations must be >= 0, got " + std::to_string(m.erosion_iterations));
  m.erosion_rings = t.integer("erosion_rings", "rings of nodes").value_or(m.erosion_rings);
  if (m.erosion_rings < 1)
    t.fail("erosion_rings",
           "terrain.erosion_rings must be >= 1, got " + std::to_string(m.erosion_rings));
}

void parse_snapshots(const Table &t, ScmTerrainConfig &m) {
  if (auto times = t.numbers("snapshot_times", "s")) {
    for (double v : *times)
      if (v < 0)
        t.fail("snapshot_times", "terrain.snapshot_times must be >= 0 s, got " + fmt(v));
    m.snapshot_times_s = *times;
    std::sort(m.snapshot_times_s.begin(), m.snapshot_times_s.end());
  }
  m.snapshot_interval_s = t.non_negative("snapshot_interval", "s").value_or(m.snapshot_interval_s);
  if (auto fields = t.strings("snapshot_fields")) {
    for (const std::string &f : *fields)
      if (std::find(kSnapshotFields.begin(), kSnapshotFields.end(), f) == kSnapshotFields.end()) {
        std::string msg = "terrain.snapshot_fields: unknown field \"" + f +
                          "\"; expected some of height, sinkage, plastic_sinkage, pressure, "
                          "shear_stress, shear_displacement";
        const std::string cl = closest(f, kSnapshotFields);
        if (!cl.empty())
          msg += "; did you mean \"" + cl + "\"?";
        t.fail("snapshot_fields", msg);
      }
    m.snapshot_fields = *fields;
  }
}

/// grid_length and grid_width bound the soil together (a bin: along x and across it); one alone
/// would leave the other side unbounded, which the SCM domain cannot be.
void check_grid_extents_given_together(const Table &t) {
  const bool length = t.has("grid_length"), width = t.has("grid_width");
  if (length == width)
    return;
  const std::string given = length ? "grid_length" : "grid_width";
  const std::string missing = length ? "grid_width" : "grid_length";
  t.fail(given, t.full(given) + " is given without " + t.full(missing) +
                    ": a bounded soil bin needs both (grid_length along x from one rim radius "
                    "behind the wheel's start, grid_width across it, centred on the wheel); add " +
                    t.full(missing) + " = <extent in m>, or remove " + t.full(given) +
                    " for unbounded soil");
}

void parse(const Table &t, const std::string &base_dir, RigConfig &c) {
  const auto soil = t.string("soil");
  if (!soil || soil->empty())
    t.parser().fail(nullptr, "missing key 'terrain.soil': the SCM soil file, e.g. terrain.soil = "
                             "\"inputs/scm_soils/lete_sand.toml\"");
  ScmTerrainConfig &m = c.terrain.scm;
  m.soil = detail::resolve(*soil, base_dir);
  m.grid_spacing_m =
      t.required(t.positive("grid_spacing", "m"), "grid_spacing", "grid node spacing in m");
  m.grid_length_m = t.positive("grid_length", "m");
  m.grid_width_m = t.positive("grid_width", "m");
  check_grid_extents_given_together(t);
  for (const char *extent : {"grid_length", "grid_width"})
    if (const auto v = t.number(extent, "m"); v && *v < m.grid_spacing_m)
      t.fail(extent, t.full(extent) + " must be >= terrain.grid_spacing (" + fmt(m.grid_spacing_m) +
                         " m), got " + fmt(*v) + " m");
  m.vertical_normal =
      t.choice("normal_direction", {"surface", "vertical"}, std::string("surface")) == "vertical";
  m.shear_at_lug_tips =
      t.choice("shear_surface", {"wheel", "lug_tips"}, std::string("wheel")) == "lug_tips";
  m.elastic_stiffness_Pa_m = t.positive("elastic_stiffness", "Pa/m");
  m.damping_Pa_s_m = t.non_negative("damping", "Pa s/m"); // flat: N s/m
  parse_bulldozing(t, m);
  parse_snapshots(t, m);
}

std::unique_ptr<Terrain> make(const RigConfig &c, const WheelProperties &wheel) {
  return std::make_unique<ScmGround>(c, wheel);
}

/// /parameters/terrain/*: the soil file (name and text), the soil as used (Chrono's names; the
/// friction angle in degrees, docs/hdf5-layout.md) and the grid.
void start(const RigConfig &c, const Terrain &terrain, ParameterSink &out, RunHealth &health) {
  const auto &ground = static_cast<const ScmGround &>(terrain);
  const scm::SoilParameters &soil = ground.terrain().soil();
  const scm::ScmSettings &settings = ground.terrain().settings();
  std::ifstream soil_in(c.terrain.scm.soil, std::ios::binary);
  std::ostringstream soil_text;
  soil_text << soil_in.rdbuf();
  out.text("terrain/soil_file", c.terrain.scm.soil);
  out.long_text("terrain/soil_file_text", soil_text.str());
  out.text("terrain/soil_name", soil.name);
  out.number("terrain/soil/Bekker_n", soil.Bekker_n, "1");
  out.number("terrain/soil/Bekker_Kc", soil.Bekker_Kc, "N/m^(n+1)");
  out.number("terrain/soil/Bekker_Kphi", soil.Bekker_Kphi, "N/m^(n+2)");
  out.number("terrain/soil/Mohr_cohesion", soil.Mohr_cohesion, "Pa");
  out.number("terrain/soil/Mohr_friction", scm::to_chrono_soil(soil).Mohr_friction, "deg");
  out.number("terrain/soil/Janosi_shear", soil.Janosi_shear, "m");
  out.number("terrain/soil/elastic_K", soil.elastic_K, "Pa/m");
  out.number("terrain/soil/damping_R", soil.damping_R, "Pa s/m");
  out.number("terrain/grid_spacing", settings.grid_spacing_m, "m");
  out.text("terrain/normal_direction",
           settings.normal == scm::NormalDirection::vertical ? "vertical" : "surface");
  out.text("terrain/shear_surface", settings.shear_radius_m ? "lug_tips" : "wheel");
  health.set_grid(settings.grid_spacing_m, soil.elastic_K);
}

} // namespace scm_entry

TerrainKind scm_terrain() {
  using namespace scm_entry;
  return {"scm",
          TerrainType::scm,
          "SCM soft soil in-process (Bekker-Wong, Janosi-Hanamoto)",
          keys(),
          parse,
          make,
          start,
          nullptr}; // the contact stiffens with its area: checked per step (run health)
}

} // namespace wheelsim::rig::terrains
