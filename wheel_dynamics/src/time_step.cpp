// The time-step bound (time_step.h): the stable step of each spring-damper the config fixes.
#include "wheelsim/rig/time_step.h"

#include "wheelsim/config_messages.h"
#include "wheelsim/rig/terrain_registry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wheelsim::rig {

using config::fmt;

double OscillatorMode::natural_period_s() const {
  return stiffness_N_m > 0.0 ? 2.0 * M_PI * std::sqrt(mass_kg / stiffness_N_m)
                             : std::numeric_limits<double>::infinity();
}

double OscillatorMode::stable_time_step_s() const {
  const double damping_rate_1_s = damping_N_s_m / mass_kg; // c/m
  const double omega2_1_s2 = stiffness_N_m / mass_kg;      // ω²
  const double denominator =
      damping_rate_1_s + std::sqrt(damping_rate_1_s * damping_rate_1_s + 4.0 * omega2_1_s2);
  return denominator > 0.0 ? 4.0 / denominator : std::numeric_limits<double>::infinity();
}

OscillatorMode suspension_mode(const Rig &rig) {
  const RigParameters &p = rig.parameters();
  const double spindle_kg = rig.spindle_dof_mass_kg();
  const double reduced_kg = spindle_kg * p.suspended_mass_kg / (spindle_kg + p.suspended_mass_kg);
  return {"the suspension (rig.spring_k = " + fmt(p.spring_k_N_m) +
              " N/m, rig.spring_c = " + fmt(p.spring_c_N_s_m) + " N s/m between wheel + spindle, " +
              fmt(spindle_kg) + " kg, and the suspended mass, " + fmt(p.suspended_mass_kg) +
              " kg: reduced mass " + fmt(reduced_kg) + " kg)",
          p.spring_k_N_m, p.spring_c_N_s_m, reduced_kg};
}

std::vector<OscillatorMode> oscillator_modes(const RigConfig &config, const Rig &rig) {
  std::vector<OscillatorMode> modes = {suspension_mode(rig)};
  if (const TerrainKind &kind = terrain_kind(config.terrain.type); kind.contact_mode)
    modes.push_back(kind.contact_mode(config, rig));
  return modes;
}

void check_time_step(const RigConfig &config, const Rig &rig, const std::string &dt_name) {
  const double dt_s = config.run.dt_s;
  if (dt_s == 0.0)
    return;
  const std::vector<OscillatorMode> modes = oscillator_modes(config, rig);
  const OscillatorMode &mode =
      *std::min_element(modes.begin(), modes.end(), [](const auto &a, const auto &b) {
        return a.stable_time_step_s() < b.stable_time_step_s();
      });
  const double limit_s = mode.stable_time_step_s();
  if (dt_s >= limit_s)
    throw RigConfigError(config.source + ": " + dt_name + " = " + fmt(dt_s) +
                         " s is at or above the stability limit " + fmt(limit_s) + " s of " +
                         mode.name + ", natural period " + fmt(mode.natural_period_s()) +
                         " s: the rig's explicit integrator needs (omega dt)^2 + 2 (c/m) dt < 4 "
                         "(docs/rig-config.md, \"Time step\"); reduce " +
                         dt_name + " below " + fmt(limit_s) + " s");
}

} // namespace wheelsim::rig
