// The bound on the rig's time step (docs/rig-config.md, "Time step"). The integrator (semi-implicit
// Euler with the forces at state n, rig_model.h) advances a spring k with a damper c on a mass m
// stably only if
//   (ω dt)² + 2 (c/m) dt < 4,   ω = sqrt(k/m),
// i.e. dt < 4 / (c/m + sqrt((c/m)² + 4 ω²)): 2/ω = T/π without damping (T the natural period),
// 2 m/c without a spring. (The amplification matrix of one step has determinant 1 − (c/m) dt
// and trace 2 − (ω dt)² − (c/m) dt; the Jury conditions give the bound.) check_time_step applies
// it to every spring-damper whose stiffness the config fixes: the suspension, and the terrain's
// contact where the terrain declares one (TerrainKind::contact_mode: the flat ground). The SCM
// contact stiffens with its area, which is known only while running: the run health checks it, and
// the flat ground's, with the same bound at every step (dt_unstable); a DEM contact is LIGGGHTS'.
#pragma once

#include <string>
#include <vector>

#include "wheelsim/rig/rig_config.h"
#include "wheelsim/rig/rig_model.h"

namespace wheelsim::rig {

/// A spring-damper of the rig or of its contact, as a one-degree-of-freedom oscillator on the
/// lightest mass it moves (so that its frequency bounds the real modes' from above).
struct OscillatorMode {
  std::string name;           ///< what it is, with its keys, values and mass (for messages)
  double stiffness_N_m = 0.0; ///< k [N/m], >= 0
  double damping_N_s_m = 0.0; ///< c [N s/m], >= 0
  double mass_kg = 0.0;       ///< m [kg], > 0

  /// 2π sqrt(m/k) [s]; infinite without a spring.
  double natural_period_s() const;
  /// The largest time step [s] the integrator advances this oscillator stably with (file comment).
  double stable_time_step_s() const;
};

/// The suspension: rig.spring_k and rig.spring_c between the wheel + spindle and the suspended
/// mass, on their reduced mass (the relative motion with the spindle free; the spindle held in the
/// release phase, or carried by the contact, leaves a slower mode on the suspended mass alone).
OscillatorMode suspension_mode(const Rig &rig);

/// The modes of `config` whose stiffness it fixes: the suspension, and the terrain's contact if its
/// registry entry declares one.
std::vector<OscillatorMode> oscillator_modes(const RigConfig &config, const Rig &rig);

/// Throws RigConfigError if config.run.dt_s is at or above the smallest stable step of the modes,
/// naming the time step as `dt_name` ("run.dt", or "--dt" when the command line set it), its value,
/// that limit and the mode it comes from. A time step of 0 (not set: a DEM run's comes with --dt)
/// is not checked.
void check_time_step(const RigConfig &config, const Rig &rig, const std::string &dt_name);

} // namespace wheelsim::rig
