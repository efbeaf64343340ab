// The keys (with the defaults of rig_config.h's structs) and the parsers of [wheel], [rig],
// [motor], [run] and [output] (docs/rig-config.md, "Configuration keys").
#include "rig_tables.h"

namespace wheelsim::rig::detail {
namespace {

ConfigKey in(const char *table, ConfigKey k) {
  k.table = table;
  return k;
}

} // namespace

std::vector<ConfigKey> wheel_keys() {
  const WheelConfig d;
  return {
      in("wheel", {"", "mesh", "path", "", "", "OBJ/STL/PLY in the wheel frame"}),
      in("wheel",
         {"", "mesh_scale", "number", "mesh units -> m", fmt(d.mesh_scale), "> 0; only with mesh"}),
      in("wheel", {"", "mass", "number", "kg", "", "> 0; with inertia (not with density)"}),
      in("wheel", {"", "inertia", "number", "kg m^2", "", "> 0; about the axle"}),
      in("wheel", {"", "density", "number", "kg/m^3", "", "> 0; needs mesh"}),
      in("wheel", {"", "effective_radius", "number", "m", "mesh's outer radius",
                   "> 0; required without mesh"}),
  };
}

void parse_wheel(const Table &t, const std::string &base_dir, RigConfig &c) {
  WheelConfig &w = c.wheel;
  if (auto m = t.string("mesh")) {
    if (m->empty())
      t.fail("mesh", "wheel.mesh must be a file name (OBJ, STL or PLY), got \"\"");
    w.mesh = resolve(*m, base_dir);
  }
  w.mesh_scale = t.positive("mesh_scale", "(mesh units -> m)").value_or(w.mesh_scale);
  w.mass_kg = t.positive("mass", "kg");
  w.inertia_kg_m2 = t.positive("inertia", "kg m^2");
  w.density_kg_m3 = t.positive("density", "kg/m^3");
  w.effective_radius_m = t.positive("effective_radius", "m");
  if (t.has("mesh_scale") && w.mesh.empty())
    t.fail("mesh_scale", "wheel.mesh_scale needs wheel.mesh = \"<file>\"; remove it");
  if (w.density_kg_m3) {
    if (w.mesh.empty())
      t.fail("density", "wheel.density needs wheel.mesh = \"<file>\" (mass and inertia come "
                        "from the mesh); without a mesh give wheel.mass and wheel.inertia");
    if (w.mass_kg || w.inertia_kg_m2)
      t.fail(w.mass_kg ? "mass" : "inertia",
             "give either wheel.density (with the mesh) or wheel.mass and wheel.inertia, not both");
  } else {
    if (!w.mass_kg)
      t.parser().fail(nullptr, "missing key 'wheel.mass' (kg, > 0) with 'wheel.inertia' (kg m^2 "
                               "about the axle), or 'wheel.density' (kg/m^3) with 'wheel.mesh'");
    if (!w.inertia_kg_m2)
      t.fail("mass", "missing key 'wheel.inertia': the wheel's moment of inertia about the axle "
                     "in kg m^2 (> 0), required with wheel.mass");
  }
  if (w.mesh.empty() && !w.effective_radius_m)
    t.parser().fail(nullptr, "missing key 'wheel.effective_radius' (m, > 0): required without "
                             "wheel.mesh (with a mesh it defaults to the mesh's outer radius)");
}

std::vector<ConfigKey> rig_keys() {
  const RigSection d;
  return {
      in("rig", {"", "spindle_mass", "number", "kg", fmt(d.spindle_mass_kg), ">= 0"}),
      in("rig", {"", "suspended_mass", "number", "kg", "",
                 "> 0; exactly one of suspended_mass, vertical_load"}),
      in("rig", {"", "vertical_load", "number", "N", "", "> 0 and > (wheel + spindle) weight"}),
      in("rig", {"", "carriage_mass", "number", "kg", fmt(d.carriage_mass_kg), ">= 0"}),
      in("rig", {"", "spring_k", "number", "N/m", fmt(d.spring_k_N_m), "> 0"}),
      in("rig", {"", "spring_c", "number", "N s/m", fmt(d.spring_c_N_s_m), ">= 0"}),
      in("rig", {"", "gravity", "number", "m/s^2", fmt(d.gravity_m_s2), "> 0"}),
  };
}

void parse_rig(const Table &t, RigConfig &c) {
  RigSection &r = c.rig;
  r.spindle_mass_kg = t.non_negative("spindle_mass", "kg").value_or(r.spindle_mass_kg);
  r.suspended_mass_kg = t.positive("suspended_mass", "kg");
  r.vertical_load_N = t.positive("vertical_load", "N");
  if (r.suspended_mass_kg && r.vertical_load_N)
    t.fail("vertical_load", "give either rig.suspended_mass (kg) or rig.vertical_load (N), "
                            "not both");
  if (!r.suspended_mass_kg && !r.vertical_load_N)
    t.parser().fail(nullptr, "missing key 'rig.suspended_mass' (kg, > 0) or 'rig.vertical_load' "
                             "(N, the total weight on the wheel; the suspended mass is sized "
                             "from it)");
  r.carriage_mass_kg = t.non_negative("carriage_mass", "kg").value_or(r.carriage_mass_kg);
  r.spring_k_N_m = t.positive("spring_k", "N/m").value_or(r.spring_k_N_m);
  r.spring_c_N_s_m = t.non_negative("spring_c", "N s/m").value_or(r.spring_c_N_s_m);
  r.gravity_m_s2 = t.positive("gravity", "m/s^2").value_or(r.gravity_m_s2);
}

std::vector<ConfigKey> motor_keys() {
  const MotorConfig d;
  return {
      in("motor", {"", "omega", "number", "rad/s", "",
                   "> 0 (>= 0 with carriage.mode = \"imposed_speed\"); exactly one of omega, "
                   "torque"}),
      in("motor", {"", "torque", "number", "N m", "", "!= 0"}),
      in("motor", {"", "ramp_time", "number", "s", fmt(d.ramp_time_s), ">= 0"}),
  };
}

void parse_motor(const Table &t, const std::string &carriage_mode, RigConfig &c) {
  // A locked wheel (omega = 0) is driven by the carriage alone: only with an imposed speed.
  const bool speed_imposed = carriage_mode == "imposed_speed";
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
    t.parser().fail(nullptr, "missing key 'motor.omega' (imposed angular speed in rad/s, > 0; 0 "
                             "with carriage.mode = \"imposed_speed\": a locked wheel) or "
                             "'motor.torque' (imposed torque in N m)");
  if (torque && *torque == 0.0)
    t.fail("torque", "motor.torque must be != 0 N m, got 0");
  c.motor.mode = omega ? MotorMode::omega : MotorMode::torque;
  c.motor.omega_rad_s = omega.value_or(0.0);
  c.motor.torque_Nm = torque.value_or(0.0);
  c.motor.ramp_time_s = t.non_negative("ramp_time", "s").value_or(c.motor.ramp_time_s);
}

std::vector<ConfigKey> run_keys() {
  const RunConfig d;
  return {
      in("run", {"", "dt", "number", "s", "",
                 "> 0; required for flat and scm (dem: the bed's, via wheel-rig --dt)"}),
      in("run", {"", "duration", "number", "s", "", ">= dt"}),
      in("run", {"", "release_gap", "number", "m", fmt(d.release_gap_m), ">= 0"}),
      in("run", {"", "release_speed", "number", "m/s", fmt(d.release_speed_m_s), "> 0"}),
      in("run", {"", "release_timeout", "number", "s", fmt(d.release_timeout_s), "> 0"}),
      in("run", {"", "settle_velocity", "number", "m/s", fmt(d.settle_velocity_m_s), "> 0"}),
      in("run", {"", "settle_window", "number", "s", fmt(d.settle_window_s), ">= 0"}),
      in("run", {"", "settle_min_time", "number", "s", fmt(d.settle_min_time_s), ">= 0"}),
      in("run", {"", "settle_max_time", "number", "s", fmt(d.settle_max_time_s),
                 "> 0, >= settle_min_time"}),
  };
}

void parse_run(const Table &t, RigConfig &c) {
  RunConfig &r = c.run;
  // dt may be left out for DEM: the run then takes the bed's LIGGGHTS time step (wheel-rig
  // --dt, which scripts/wheel-cosim passes from the bed's .vars); required otherwise (rig_config).
  r.dt_s = t.positive("dt", "s").value_or(0.0);
  r.duration_s = t.required(t.positive("duration", "s"), "duration", "test phase length, s");
  if (r.dt_s > 0.0 && r.duration_s < r.dt_s)
    t.fail("duration",
           "run.duration must be >= run.dt (" + fmt(r.dt_s) + " s), got " + fmt(r.duration_s));
  r.release_gap_m = t.non_negative("release_gap", "m").value_or(r.release_gap_m);
  r.release_speed_m_s = t.positive("release_speed", "m/s").value_or(r.release_speed_m_s);
  r.release_timeout_s = t.positive("release_timeout", "s").value_or(r.release_timeout_s);
  r.settle_velocity_m_s = t.positive("settle_velocity", "m/s").value_or(r.settle_velocity_m_s);
  r.settle_window_s = t.non_negative("settle_window", "s").value_or(r.settle_window_s);
  r.settle_min_time_s = t.non_negative("settle_min_time", "s").value_or(r.settle_min_time_s);
  r.settle_max_time_s = t.positive("settle_max_time", "s").value_or(r.settle_max_time_s);
  if (r.settle_max_time_s < r.settle_min_time_s)
    t.fail("settle_max_time", "run.settle_max_time must be >= run.settle_min_time (" +
                                  fmt(r.settle_min_time_s) + " s), got " +
                                  fmt(r.settle_max_time_s));
}

std::vector<ConfigKey> output_keys() {
  const OutputConfig d;
  return {
      in("output", {"", "file", "path", "", "\"" + d.file + "\"", "non-empty; --out overrides"}),
      in("output", {"", "every", "integer", "steps", std::to_string(d.every), ">= 1"}),
      in("output", {"", "flush_interval", "integer", "recorded steps",
                    std::to_string(d.flush_interval), ">= 1"}),
      in("output", {"", "progress_interval", "number", "s (wall clock)", fmt(d.progress_interval_s),
                    ">= 0; 0 = no progress line"}),
  };
}

void parse_output(const Table &t, RigConfig &c) {
  OutputConfig &o = c.output;
  if (auto f = t.string("file")) {
    if (f->empty())
      t.fail("file", "output.file must be a file name, e.g. \"run.h5\", got \"\"");
    o.file = *f;
  }
  auto at_least_one = [&](const char *key, long long fallback) {
    const auto v = t.integer(key, "steps");
    if (v && *v < 1)
      t.fail(key, t.full(key) + " must be >= 1 steps, got " + std::to_string(*v));
    return v.value_or(fallback);
  };
  o.every = at_least_one("every", o.every);
  o.flush_interval = at_least_one("flush_interval", o.flush_interval);
  o.progress_interval_s = t.non_negative("progress_interval", "s").value_or(o.progress_interval_s);
}

} // namespace wheelsim::rig::detail
