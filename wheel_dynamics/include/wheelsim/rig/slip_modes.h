// The carriage (slip) modes of the rig, each declared once in src/slip_modes.cpp: its name, its
// [carriage] keys with units, defaults and ranges, its parser and its drive law (how the carriage
// moves or is loaded at each step). The parser and RigSimulation go through this table; a mode
// writes nothing to /parameters of its own (its keys are in the rig config text stored there).
// docs/extending.md, "Adding a slip mode".
#pragma once

#include <string>
#include <vector>

#include "wheelsim/rig/config_schema.h"
#include "wheelsim/rig/rig_config.h"
#include "wheelsim/rig/rig_model.h"

namespace wheelsim::rig {

namespace detail {
class Table;
}

/// What a mode's drive law sees at a step of the ramp or test phase.
struct CarriageDriveInput {
  bool test_phase = false;       ///< false: the motor's ramp phase
  double ramp_fraction_now = 0;  ///< motor ramp fraction at t (forces) [-]
  double ramp_fraction_next = 0; ///< at t + dt (imposed velocities) [-]
  double time_in_test_s = 0;     ///< t − start of the test phase [s] (test phase only)
  double effective_radius_m = 0; ///< R_eff [m]
};

/// The carriage's drive for the step.
struct CarriageDrive {
  Drive drive = Drive::free;
  double value = 0.0;          ///< as RigDrives::carriage_value
  double load_command_N = 0.0; ///< the drawbar load applied (load modes), else 0 [N]
};

/// The quantities the run health (run_health.h, check `steady_state_trend`) expects steady over
/// the test phase under a mode: those the mode does not impose or ramp (bit flags).
enum SteadyQuantity : unsigned {
  steady_none = 0,
  steady_drawbar_pull = 1u << 0, ///< the drawbar pull [N] (slip or speed imposed)
  steady_slip = 1u << 1,         ///< the slip [-] (a constant load imposed)
  steady_sinkage = 1u << 2,      ///< the sinkage [m]
};

struct SlipMode {
  const char *name; ///< carriage.mode
  CarriageMode mode;
  const char *summary;
  std::vector<ConfigKey> keys; ///< its [carriage] keys beyond `mode`
  /// Reads its keys (other modes' keys are rejected before). Throws RigConfigError.
  void (*parse)(const detail::Table &t, CarriageConfig &c);
  CarriageDrive (*drive)(const CarriageConfig &c, const CarriageDriveInput &in);
  /// The slip [-] (driving convention) the config imposes in the test phase, which the run health
  /// requires the rig to hold (check `slip_not_held`); NaN when the slip is free.
  double (*held_slip)(const RigConfig &c, double effective_radius_m);
  /// SteadyQuantity flags: what the run health checks for a trend in the test phase.
  unsigned steady;
};

const std::vector<SlipMode> &slip_modes();
const SlipMode &slip_mode(CarriageMode mode);
std::vector<std::string> slip_mode_names();

/// Parses [carriage]: the mode through the table, then its keys.
void parse_carriage_table(const detail::Table &t, RigConfig &c);

} // namespace wheelsim::rig
