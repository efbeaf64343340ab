// terrain.type = "flat": a rigid ground plane with penalty contact and Coulomb (or regularized)
// friction, for tests and known answers (flat_ground.h, docs/rig-config.md).
#include "terrains.h"

#include "../config_table.h"
#include "wheelsim/rig/rig_simulation.h"
#include "wheelsim/rig/run_health.h"

namespace wheelsim::rig::terrains {
namespace flat_entry {

using detail::fmt;
using detail::Table;

ConfigKey flat(ConfigKey k) { return terrain_key("flat", std::move(k)); }

std::vector<ConfigKey> keys() {
  const FlatGroundParameters d;
  return {
      flat({"", "stiffness", "number", "N/m", fmt(d.stiffness_N_m), "> 0"}),
      flat({"", "damping", "number", "N s/m", fmt(d.damping_N_s_m), ">= 0"}),
      flat({"", "friction", "number", "", fmt(d.friction), ">= 0"}),
      flat({"", "friction_model", "string", "", "\"coulomb\"",
            "one of \"coulomb\", \"regularized\""}),
      flat({"", "tangential_stiffness", "number", "N/m", fmt(d.tangential_stiffness_N_m),
            "> 0; friction_model = \"coulomb\" only"}),
      flat({"", "tangential_damping", "number", "N s/m", fmt(d.tangential_damping_N_s_m),
            ">= 0; friction_model = \"coulomb\" only"}),
      flat({"", "slip_velocity_scale", "number", "m/s", fmt(d.slip_velocity_scale_m_s),
            "> 0; friction_model = \"regularized\" only"}),
  };
}

void parse(const Table &t, const std::string & /*base_dir*/, RigConfig &c) {
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

std::unique_ptr<Terrain> make(const RigConfig &c, const WheelProperties &wheel) {
  return std::make_unique<FlatGround>(make_flat_ground(c, wheel));
}

void start(const RigConfig &c, const Terrain &, ParameterSink &, RunHealth &health) {
  health.set_contact_stiffness(c.terrain.flat.stiffness_N_m, c.terrain.flat.damping_N_s_m);
}

/// The normal penalty contact (k_n, c_n) on the wheel + spindle mass, as the run health's
/// dt_unstable check sees it. The tangential spring is left out: it acts on the carriage and the
/// wheel's rotation, which the usual drives impose.
OscillatorMode contact_mode(const RigConfig &c, const Rig &rig) {
  const FlatGroundParameters &f = c.terrain.flat;
  const double mass_kg = rig.spindle_dof_mass_kg();
  return {"the flat ground's contact (terrain.stiffness = " + fmt(f.stiffness_N_m) +
              " N/m, terrain.damping = " + fmt(f.damping_N_s_m) + " N s/m on wheel + spindle, " +
              fmt(mass_kg) + " kg)",
          f.stiffness_N_m, f.damping_N_s_m, mass_kg};
}

} // namespace flat_entry

TerrainKind flat_terrain() {
  using namespace flat_entry;
  return {
      "flat", TerrainType::flat, "rigid flat ground (tests, known answers)", keys(), parse, make,
      start,  contact_mode};
}

} // namespace wheelsim::rig::terrains
