#include "wheelsim/rig/rig_simulation.h"
#include "wheelsim/rig/slip_modes.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>

#include <toml++/toml.h>

#include "wheelsim/config_messages.h"
#include "wheelsim/geometry/mass_properties.h"
#include "wheelsim/geometry/mesh_error.h"
#include "wheelsim/geometry/mesh_io.h"

namespace wheelsim::rig {
namespace {

using config::fmt;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Below these, slip and efficiency are undefined (reported as NaN).
constexpr double kMinRollingSpeed_m_s = 1e-9;
constexpr double kMinPower_W = 1e-9;
/// Largest distance of a mesh's centroid from the axle the balanced-wheel model accepts [m].
constexpr double kMaxCentroidOffset_m = 1e-3;
/// Release: the lowering speed rises linearly from 0 to run.release_speed over this time [s], so
/// the holder's force changes by only (wheel + spindle mass) * release_speed / this (e.g. 30 N
/// for 305 kg at 0.01 m/s) and the suspended mass is barely excited.
constexpr double kReleaseAccelerationTime_s = 0.1;

/// The lugs of a wheel-mesh mesh from `<stem>.props.toml` beside it (see WheelProperties); leaves
/// `p` unchanged if there is no such file. A props file that does not parse is an error naming it.
void read_lug_properties(const std::string &mesh, double mesh_scale, WheelProperties &p) {
  const std::filesystem::path props = std::filesystem::path(mesh).replace_extension(".props.toml");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(props, ec))
    return;
  toml::table t;
  try {
    t = toml::parse_file(props.string());
  } catch (const toml::parse_error &e) {
    throw RigConfigError("wheel.mesh: the mesh's properties file " + props.string() +
                         " does not parse: " + std::string(e.description()));
  }
  const auto *wheel = t["wheel"].as_table();
  if (wheel == nullptr || (*wheel)["smooth"].value_or(false))
    return;
  const auto count = (*wheel)["lug_count"].value<std::int64_t>();
  const auto width = (*wheel)["lug_width_m"].value<double>();
  const auto height = (*wheel)["lug_height_m"].value<double>();
  if (!count || !width || !height || *count < 1 || !(*width > 0) || !(*height > 0))
    return; // not a lugged wheel-mesh wheel: the lug checks stay off
  p.lug_count = static_cast<int>(*count);
  p.lug_width_m = *width * mesh_scale;
  p.lug_height_m = *height * mesh_scale;
  p.lug_source = props.string();
}

} // namespace

const char *to_string(Phase p) {
  switch (p) {
  case Phase::release:
    return "release";
  case Phase::settle:
    return "settle";
  case Phase::ramp:
    return "ramp";
  case Phase::test:
    return "test";
  case Phase::finished:
    return "finished";
  }
  return "?";
}

WheelProperties resolve_wheel_properties(const WheelConfig &w) {
  WheelProperties p;
  p.source = "config";
  if (!w.mesh.empty()) {
    geometry::TriangleMesh mesh;
    try {
      geometry::LoadOptions opt;
      opt.scale = w.mesh_scale;
      mesh = geometry::load_mesh(w.mesh, opt);
    } catch (const geometry::MeshError &e) {
      throw RigConfigError(std::string("wheel.mesh: ") + e.what());
    }
    double y_min_m = std::numeric_limits<double>::infinity();
    double y_max_m = -std::numeric_limits<double>::infinity();
    for (const auto &v : mesh.vertices_m) {
      p.rim_radius_m = std::max(p.rim_radius_m, std::hypot(v.x(), v.z()));
      y_min_m = std::min(y_min_m, v.y());
      y_max_m = std::max(y_max_m, v.y());
    }
    p.width_m = mesh.vertices_m.empty() ? 0.0 : y_max_m - y_min_m;
    p.source = "mesh " + w.mesh;
    read_lug_properties(w.mesh, w.mesh_scale, p);
    if (w.density_kg_m3) {
      geometry::MassProperties mp;
      try {
        mp = geometry::mass_properties(mesh, *w.density_kg_m3);
      } catch (const geometry::MeshError &e) {
        throw RigConfigError(std::string("wheel.mesh: ") + e.what());
      }
      const double off = std::hypot(mp.centroid_m.x(), mp.centroid_m.z());
      if (off > kMaxCentroidOffset_m)
        throw RigConfigError("wheel.mesh: " + w.mesh + ": the centroid is " + fmt(off * 1e3) +
                             " mm off the axle (the rig model needs a balanced wheel, <= 1 mm); "
                             "centre the mesh on the axle or give wheel.mass and wheel.inertia");
      p.mass_kg = mp.mass_kg;
      p.axle_inertia_kg_m2 = geometry::inertia_about_point(mp, Eigen::Vector3d::Zero())(1, 1);
      p.source += " (density " + fmt(*w.density_kg_m3) + " kg/m^3)";
    }
    p.mesh = std::make_shared<const geometry::TriangleMesh>(std::move(mesh));
  }
  if (!w.density_kg_m3) {
    p.mass_kg = w.mass_kg.value();
    p.axle_inertia_kg_m2 = w.inertia_kg_m2.value();
  }
  p.effective_radius_m = w.effective_radius_m.value_or(p.rim_radius_m);
  if (w.mesh.empty())
    p.rim_radius_m = p.effective_radius_m;
  if (!(p.effective_radius_m > 0))
    throw RigConfigError("wheel.effective_radius: the wheel radius must be > 0 m, got " +
                         fmt(p.effective_radius_m));
  return p;
}

RigParameters rig_parameters(const RigConfig &c, const WheelProperties &w) {
  RigParameters p;
  p.wheel_mass_kg = w.mass_kg;
  p.wheel_axle_inertia_kg_m2 = w.axle_inertia_kg_m2;
  p.spindle_mass_kg = c.rig.spindle_mass_kg;
  p.carriage_mass_kg = c.rig.carriage_mass_kg;
  p.spring_k_N_m = c.rig.spring_k_N_m;
  p.spring_c_N_s_m = c.rig.spring_c_N_s_m;
  p.gravity_m_s2 = c.rig.gravity_m_s2;
  if (c.rig.suspended_mass_kg) {
    p.suspended_mass_kg = *c.rig.suspended_mass_kg;
  } else {
    const double W = c.rig.vertical_load_N.value();
    const double own = (w.mass_kg + c.rig.spindle_mass_kg) * c.rig.gravity_m_s2;
    if (!(W > own))
      throw RigConfigError("rig.vertical_load must be > the weight of wheel and spindle (" +
                           fmt(own) + " N), got " + fmt(W) +
                           " N; raise it or give rig.suspended_mass instead");
    p.suspended_mass_kg = (W - own) / c.rig.gravity_m_s2;
  }
  return p;
}

FlatGround make_flat_ground(const RigConfig &c, const WheelProperties &w) {
  if (c.terrain.type != TerrainType::flat)
    throw RigConfigError(std::string("make_flat_ground: terrain.type is \"") +
                         to_string(c.terrain.type) + "\", not \"flat\"");
  FlatGroundParameters p = c.terrain.flat;
  p.surface_height_m = c.terrain.surface_height_m;
  p.radius_m = w.effective_radius_m;
  return FlatGround(p);
}

namespace {
Rig initial_rig(const RigConfig &c, const WheelProperties &w) {
  const RigParameters p = rig_parameters(c, w);
  RigCoordinates q;
  q.z_m = c.terrain.surface_height_m + w.rim_radius_m + c.run.release_gap_m;
  // Suspended mass at its static equilibrium on the held spindle: e = -m_m g / k.
  q.mass_z_m = q.z_m - p.suspended_mass_kg * p.gravity_m_s2 / p.spring_k_N_m;
  return Rig(p, q, RigVelocities{});
}
} // namespace

RigSimulation::RigSimulation(const RigConfig &config)
    : RigSimulation(config, resolve_wheel_properties(config.wheel)) {}

RigSimulation::RigSimulation(const RigConfig &config, const WheelProperties &wheel)
    : config_(config), wheel_(wheel), rig_(initial_rig(config, wheel)), static_sinkage_m_(kNaN),
      test_start_s_(kNaN) {
  enter(Phase::release);
}

void RigSimulation::enter(Phase p) {
  phase_ = p;
  phase_start_s_ = rig_.time_s();
  settle_quiet_since_s_ = -1.0;
  if (p == Phase::ramp && config_.motor.ramp_time_s <= 0.0)
    phase_ = Phase::test;
  if (phase_ == Phase::test)
    test_start_s_ = rig_.time_s();
}

void RigSimulation::configure_drives(double t_next) {
  const double t = rig_.time_s();
  const MotorConfig &m = config_.motor;
  const CarriageConfig &c = config_.carriage;
  RigDrives d;
  load_command_N_ = 0.0;
  if (phase_ == Phase::release || phase_ == Phase::settle) {
    d.spindle = phase_ == Phase::release ? Drive::imposed_velocity : Drive::free;
    d.spindle_velocity_m_s = -config_.run.release_speed_m_s *
                             std::min(1.0, (t_next - phase_start_s_) / kReleaseAccelerationTime_s);
    d.wheel = Drive::imposed_velocity; // the motor holds the wheel
    d.wheel_value = 0.0;
    d.carriage = Drive::imposed_velocity; // the carriage is at rest
    d.carriage_value = 0.0;
    rig_.set_drives(d);
    return;
  }
  // Ramp fraction at t (forces) and at t_next (imposed velocities).
  auto fraction = [&](double time) {
    if (phase_ == Phase::test)
      return 1.0;
    return std::clamp((time - phase_start_s_) / m.ramp_time_s, 0.0, 1.0);
  };
  const double f_now = fraction(t), f_next = fraction(t_next);
  if (m.mode == MotorMode::omega) {
    d.wheel = Drive::imposed_velocity;
    d.wheel_value = f_next * m.omega_rad_s;
  } else {
    d.wheel = Drive::free;
    d.wheel_value = f_now * m.torque_Nm;
  }
  CarriageDriveInput in; // the mode's drive law: slip_modes.cpp
  in.test_phase = phase_ == Phase::test;
  in.ramp_fraction_now = f_now;
  in.ramp_fraction_next = f_next;
  in.time_in_test_s = in.test_phase ? t - test_start_s_ : 0.0;
  in.effective_radius_m = wheel_.effective_radius_m;
  const CarriageDrive carriage = slip_mode(c.mode).drive(c, in);
  d.carriage = carriage.drive;
  d.carriage_value = carriage.value;
  load_command_N_ = carriage.load_command_N;
  rig_.set_drives(d);
}

const RigOutputs &RigSimulation::advance(const WheelWrench &w) {
  if (phase_ == Phase::finished)
    throw std::logic_error("RigSimulation::advance: the run is finished (test phase of " +
                           fmt(config_.run.duration_s) + " s done)");
  const double dt = config_.run.dt_s;
  const double R = wheel_.effective_radius_m;
  RigOutputs o;
  o.step = rig_.step_count();
  o.time_s = rig_.time_s();
  o.phase = phase_;
  o.wheel = rig_.wheel_state();
  o.contact = w;
  const RigCoordinates q = rig_.coordinates();
  const RigVelocities u = rig_.velocities();
  o.carriage_x_m = q.x_m;
  o.forward_velocity_m_s = u.x_m_s;
  o.omega_rad_s = u.omega_rad_s;
  o.theta_rad = q.theta_rad;
  o.wheel_centre_z_m = q.z_m;
  o.vertical_velocity_m_s = u.z_m_s;
  o.suspended_mass_z_m = q.mass_z_m;
  o.spring_force_N = rig_.spring_force_on_mass_N();
  o.slip_velocity_m_s = u.omega_rad_s * R - u.x_m_s;
  o.slip = std::abs(u.omega_rad_s * R) > kMinRollingSpeed_m_s ? 1.0 - u.x_m_s / (u.omega_rad_s * R)
                                                              : kNaN;
  o.sinkage_m = config_.terrain.surface_height_m - (q.z_m - wheel_.rim_radius_m);
  o.vertical_load_N = rig_.vertical_load_N();

  configure_drives(o.time_s + dt);
  rig_.step(w, dt);

  const RigReactions &r = rig_.reactions();
  o.drawbar_pull_N = -r.carriage_force_N;
  o.drawbar_load_command_N = load_command_N_;
  o.driving_torque_Nm = r.motor_torque_Nm;
  o.traction_force_N = r.motor_torque_Nm / R;
  const double input_power = r.motor_torque_Nm * u.omega_rad_s;
  o.tractive_efficiency =
      std::abs(input_power) > kMinPower_W ? o.drawbar_pull_N * u.x_m_s / input_power : kNaN;
  o.spindle_support_force_N = r.spindle_support_force_N;
  o.lateral_force_N = r.held_force_y_N;
  o.roll_torque_Nm = r.held_torque_x_Nm;
  o.yaw_torque_Nm = r.held_torque_z_Nm;
  out_ = o;

  // Phase transitions, decided on the new state n+1.
  const double t = rig_.time_s();
  const double in_phase = t - phase_start_s_;
  switch (phase_) {
  case Phase::release:
    if (r.spindle_support_force_N <= 0.0) {
      enter(Phase::settle);
    } else if (in_phase >= config_.run.release_timeout_s) {
      throw std::runtime_error(
          "release: the terrain did not carry the load within run.release_timeout = " +
          fmt(config_.run.release_timeout_s) + " s (wheel lowered by " +
          fmt(in_phase * config_.run.release_speed_m_s) +
          " m, contact force z = " + fmt(w.f_B_W.z()) + " N of " + fmt(rig_.vertical_load_N()) +
          " N); check terrain.surface_height and the terrain, or raise run.release_timeout");
    }
    break;
  case Phase::settle: {
    const bool quiet = std::abs(rig_.velocities().z_m_s) < config_.run.settle_velocity_m_s;
    if (!quiet)
      settle_quiet_since_s_ = -1.0;
    else if (settle_quiet_since_s_ < 0.0)
      settle_quiet_since_s_ = t;
    const bool settled = quiet && t - settle_quiet_since_s_ >= config_.run.settle_window_s &&
                         in_phase >= config_.run.settle_min_time_s;
    const bool timed_out = in_phase >= config_.run.settle_max_time_s;
    if (settled || timed_out) {
      if (!settled)
        warnings_.push_back("settle: |v_z| did not stay below run.settle_velocity = " +
                            fmt(config_.run.settle_velocity_m_s) + " m/s for run.settle_window = " +
                            fmt(config_.run.settle_window_s) + " s within run.settle_max_time = " +
                            fmt(config_.run.settle_max_time_s) +
                            " s (|v_z| = " + fmt(std::abs(rig_.velocities().z_m_s)) +
                            " m/s now); continuing with the ramp");
      static_sinkage_m_ =
          config_.terrain.surface_height_m - (rig_.coordinates().z_m - wheel_.rim_radius_m);
      enter(Phase::ramp);
    }
    break;
  }
  case Phase::ramp:
    if (in_phase >= config_.motor.ramp_time_s - 0.5 * dt)
      enter(Phase::test);
    break;
  case Phase::test:
    if (t - test_start_s_ >= config_.run.duration_s - 0.5 * dt)
      phase_ = Phase::finished;
    break;
  case Phase::finished:
    break;
  }
  return out_;
}

void RigSimulation::save_checkpoint(CheckpointData &data) const {
  const Rig::Snapshot r = rig_.snapshot();
  data.set_numbers("sim/q", {r.q.x_m, r.q.z_m, r.q.mass_z_m, r.q.theta_rad});
  data.set_numbers("sim/u", {r.u.x_m_s, r.u.z_m_s, r.u.mass_z_m_s, r.u.omega_rad_s});
  const RigDrives &d = r.drives;
  data.set_numbers("sim/drives", {static_cast<double>(d.carriage), d.carriage_value,
                                  static_cast<double>(d.spindle), d.spindle_velocity_m_s,
                                  static_cast<double>(d.wheel), d.wheel_value});
  const RigReactions &x = r.reactions;
  data.set_numbers("sim/reactions",
                   {x.carriage_force_N, x.spindle_support_force_N, x.motor_torque_Nm,
                    x.held_force_y_N, x.held_torque_x_Nm, x.held_torque_z_Nm});
  data.set_number("sim/time", r.time_s);
  data.set_integer("sim/steps", r.steps);
  data.set_number("sim/segment_time0", r.segment_time0_s);
  data.set_integer("sim/segment_step0", r.segment_step0);
  data.set_number("sim/segment_dt", r.segment_dt_s);
  data.set_integer("sim/phase", static_cast<std::int64_t>(phase_));
  data.set_text("sim/phase_name", to_string(phase_));
  data.set_number("sim/phase_start", phase_start_s_);
  data.set_number("sim/settle_quiet_since", settle_quiet_since_s_);
  data.set_number("sim/static_sinkage", static_sinkage_m_);
  data.set_number("sim/test_start", test_start_s_);
  data.set_number("sim/load_command", load_command_N_);
  data.set_integer("sim/warnings", static_cast<std::int64_t>(warnings_.size()));
  for (std::size_t k = 0; k < warnings_.size(); ++k)
    data.set_text("sim/warning/" + std::to_string(k), warnings_[k]);
}

void RigSimulation::restore_checkpoint(const CheckpointData &data) {
  auto exactly = [&](const char *key, std::size_t n) -> const std::vector<double> & {
    const std::vector<double> &v = data.numbers(key);
    if (v.size() != n)
      throw CheckpointError(data.source() + ": '" + key + "' holds " + std::to_string(v.size()) +
                            " numbers, expected " + std::to_string(n));
    return v;
  };
  Rig::Snapshot r;
  const auto &q = exactly("sim/q", 4), &u = exactly("sim/u", 4), &d = exactly("sim/drives", 6),
             &x = exactly("sim/reactions", 6);
  r.q = RigCoordinates{q[0], q[1], q[2], q[3]};
  r.u = RigVelocities{u[0], u[1], u[2], u[3]};
  r.drives.carriage = static_cast<Drive>(static_cast<int>(d[0]));
  r.drives.carriage_value = d[1];
  r.drives.spindle = static_cast<Drive>(static_cast<int>(d[2]));
  r.drives.spindle_velocity_m_s = d[3];
  r.drives.wheel = static_cast<Drive>(static_cast<int>(d[4]));
  r.drives.wheel_value = d[5];
  r.reactions = RigReactions{x[0], x[1], x[2], x[3], x[4], x[5]};
  r.time_s = data.number("sim/time");
  r.steps = data.integer("sim/steps");
  r.segment_time0_s = data.number("sim/segment_time0");
  r.segment_step0 = data.integer("sim/segment_step0");
  r.segment_dt_s = data.number("sim/segment_dt");
  const std::int64_t phase = data.integer("sim/phase");
  if (phase < static_cast<int>(Phase::release) || phase > static_cast<int>(Phase::finished))
    throw CheckpointError(data.source() + ": sim/phase " + std::to_string(phase) +
                          " is not a phase (0 release .. 4 finished)");
  rig_.restore(r);
  phase_ = static_cast<Phase>(phase);
  phase_start_s_ = data.number("sim/phase_start");
  settle_quiet_since_s_ = data.number("sim/settle_quiet_since");
  static_sinkage_m_ = data.number("sim/static_sinkage");
  test_start_s_ = data.number("sim/test_start");
  load_command_N_ = data.number("sim/load_command");
  warnings_.clear();
  const std::int64_t n = data.integer("sim/warnings");
  for (std::int64_t k = 0; k < n; ++k)
    warnings_.push_back(data.text("sim/warning/" + std::to_string(k)));
}

} // namespace wheelsim::rig
