// The carriage (slip) modes: one entry each (docs/rig-config.md, "Slip modes").
#include "wheelsim/rig/slip_modes.h"

#include "config_table.h"

#include <cmath>

namespace wheelsim::rig {
namespace {

using detail::Table;

ConfigKey mode_key(const char *mode, ConfigKey k) {
  k.table = "carriage";
  return key_for("carriage.mode", mode, std::move(k));
}

// ---- imposed_slip: v = (1 − s) ω R_eff at every step
void parse_imposed_slip(const Table &t, CarriageConfig &c) {
  c.slip =
      t.required(t.checked("slip", "", "in [-1, 1]", [](double v) { return v >= -1 && v <= 1; }),
                 "slip", "slip in [-1, 1], e.g. 0.2");
}
CarriageDrive drive_imposed_slip(const CarriageConfig &c, const CarriageDriveInput &in) {
  return {Drive::follow_wheel, (1.0 - c.slip) * in.effective_radius_m, 0.0};
}
double held_imposed_slip(const RigConfig &c, double) { return c.carriage.slip; }

// ---- imposed_speed: v = carriage.speed (ramped with the motor)
void parse_imposed_speed(const Table &t, CarriageConfig &c) {
  c.speed_m_s = t.required(t.number("speed", "m/s"), "speed", "speed in m/s");
}
CarriageDrive drive_imposed_speed(const CarriageConfig &c, const CarriageDriveInput &in) {
  return {Drive::imposed_velocity, in.ramp_fraction_next * c.speed_m_s, 0.0};
}
/// With a speed motor the slip is 1 − v/(ω R_eff); with a torque motor it is free.
double held_imposed_speed(const RigConfig &c, double effective_radius_m) {
  if (c.motor.mode == MotorMode::omega && c.motor.omega_rad_s * effective_radius_m > 0.0)
    return 1.0 - c.carriage.speed_m_s / (c.motor.omega_rad_s * effective_radius_m);
  return std::nan("");
}

/// A free carriage pulled back by `load` [N].
CarriageDrive loaded(double load_N) { return {Drive::free, -load_N, load_N}; }
/// Slip emerges (load-controlled carriage).
double slip_free(const RigConfig &, double) { return std::nan(""); }

// ---- constant_load: a free carriage, drawbar load carriage.load (ramped with the motor)
void parse_constant_load(const Table &t, CarriageConfig &c) {
  c.load_N = t.required(t.number("load", "N"), "load", "drawbar load in N");
}
CarriageDrive drive_constant_load(const CarriageConfig &c, const CarriageDriveInput &in) {
  return loaded(in.ramp_fraction_now * c.load_N);
}

// ---- ramped_load: load_start -> load_end over ramp_time from the start of the test phase
void parse_ramped_load(const Table &t, CarriageConfig &c) {
  c.load_start_N =
      t.required(t.number("load_start", "N"), "load_start", "drawbar load at the start, N");
  c.load_end_N = t.required(t.number("load_end", "N"), "load_end", "drawbar load at the end, N");
  c.ramp_time_s =
      t.required(t.positive("ramp_time", "s"), "ramp_time", "duration of the load ramp, s");
}
CarriageDrive drive_ramped_load(const CarriageConfig &c, const CarriageDriveInput &in) {
  if (!in.test_phase)
    return loaded(in.ramp_fraction_now * c.load_start_N);
  const double f = std::clamp(in.time_in_test_s / c.ramp_time_s, 0.0, 1.0);
  return loaded(c.load_start_N + (c.load_end_N - c.load_start_N) * f);
}

} // namespace

const std::vector<SlipMode> &slip_modes() {
  static const std::vector<SlipMode> modes = {
      {"imposed_slip",
       CarriageMode::imposed_slip,
       "carriage speed (1 - s) omega R_eff; the drawbar pull is the carriage's reaction",
       {mode_key("imposed_slip", {"", "slip", "number", "", "",
                                  "in [-1, 1], driving convention 1 - v/(omega R_eff)"})},
       parse_imposed_slip,
       drive_imposed_slip,
       held_imposed_slip,
       steady_drawbar_pull | steady_sinkage},
      {"imposed_speed",
       CarriageMode::imposed_speed,
       "carriage speed imposed (ramped with the motor); slip emerges",
       {mode_key("imposed_speed", {"", "speed", "number", "m/s", "", "finite"})},
       parse_imposed_speed,
       drive_imposed_speed,
       held_imposed_speed,
       steady_drawbar_pull | steady_sinkage},
      {"constant_load",
       CarriageMode::constant_load,
       "free carriage pulled back by a constant drawbar load; slip emerges",
       {mode_key("constant_load", {"", "load", "number", "N", "", "finite; positive pulls back"})},
       parse_constant_load,
       drive_constant_load,
       slip_free,
       steady_slip | steady_sinkage},
      {"ramped_load",
       CarriageMode::ramped_load,
       "free carriage, drawbar load ramped from load_start to load_end over ramp_time",
       {mode_key("ramped_load", {"", "load_start", "number", "N", "", "finite"}),
        mode_key("ramped_load", {"", "load_end", "number", "N", "", "finite"}),
        mode_key("ramped_load", {"", "ramp_time", "number", "s", "", "> 0"})},
       parse_ramped_load,
       drive_ramped_load,
       slip_free,
       steady_none}, // the load, and with it slip and sinkage, change by design
  };
  return modes;
}

const SlipMode &slip_mode(CarriageMode mode) {
  for (const SlipMode &m : slip_modes())
    if (m.mode == mode)
      return m;
  throw std::logic_error("slip_mode: a CarriageMode without an entry in slip_modes()");
}

std::vector<std::string> slip_mode_names() {
  std::vector<std::string> names;
  for (const SlipMode &m : slip_modes())
    names.emplace_back(m.name);
  return names;
}

void parse_carriage_table(const Table &t, RigConfig &c) {
  const std::string name = t.choice("mode", slip_mode_names(), std::nullopt);
  const SlipMode *mode = nullptr;
  for (const SlipMode &m : slip_modes())
    if (name == m.name)
      mode = &m;
  for (const SlipMode &other : slip_modes()) // keys of the other modes
    for (const ConfigKey &k : other.keys)
      if (std::none_of(mode->keys.begin(), mode->keys.end(),
                       [&](const ConfigKey &own) { return own.key == k.key; }))
        t.only_with({k.key}, "mode", name);
  c.carriage.mode = mode->mode;
  mode->parse(t, c.carriage);
}

} // namespace wheelsim::rig
