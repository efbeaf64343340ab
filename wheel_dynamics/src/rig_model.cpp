#include "wheelsim/rig/rig_model.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace wheelsim::rig {
namespace {

void check(bool ok, const std::string &name, const char *expected, double value) {
  if (ok)
    return;
  std::ostringstream os;
  os << "Rig: " << name << " must be " << expected << ", got " << value;
  throw std::invalid_argument(os.str());
}

void check_finite(double v, const char *name) { check(std::isfinite(v), name, "finite", v); }

} // namespace

Rig::Rig(const RigParameters &p, const RigCoordinates &q0, const RigVelocities &u0, double time0_s)
    : p_(p), q_(q0), u_(u0), time_s_(time0_s), segment_time0_s_(time0_s) {
  check(p.wheel_mass_kg > 0 && std::isfinite(p.wheel_mass_kg), "wheel_mass_kg", "> 0 kg",
        p.wheel_mass_kg);
  check(p.wheel_axle_inertia_kg_m2 > 0 && std::isfinite(p.wheel_axle_inertia_kg_m2),
        "wheel_axle_inertia_kg_m2", "> 0 kg m^2", p.wheel_axle_inertia_kg_m2);
  check(p.spindle_mass_kg >= 0 && std::isfinite(p.spindle_mass_kg), "spindle_mass_kg", ">= 0 kg",
        p.spindle_mass_kg);
  check(p.suspended_mass_kg > 0 && std::isfinite(p.suspended_mass_kg), "suspended_mass_kg",
        "> 0 kg", p.suspended_mass_kg);
  check(p.carriage_mass_kg >= 0 && std::isfinite(p.carriage_mass_kg), "carriage_mass_kg", ">= 0 kg",
        p.carriage_mass_kg);
  check(p.spring_k_N_m > 0 && std::isfinite(p.spring_k_N_m), "spring_k_N_m", "> 0 N/m",
        p.spring_k_N_m);
  check(p.spring_c_N_s_m >= 0 && std::isfinite(p.spring_c_N_s_m), "spring_c_N_s_m", ">= 0 N s/m",
        p.spring_c_N_s_m);
  check(p.gravity_m_s2 > 0 && std::isfinite(p.gravity_m_s2), "gravity_m_s2", "> 0 m/s^2",
        p.gravity_m_s2);
  for (double v : {q0.x_m, q0.z_m, q0.mass_z_m, q0.theta_rad, u0.x_m_s, u0.z_m_s, u0.mass_z_m_s,
                   u0.omega_rad_s, time0_s})
    check_finite(v, "initial state");
}

void Rig::set_drives(const RigDrives &d) {
  check(d.spindle != Drive::follow_wheel, "spindle drive", "free or imposed_velocity", 0);
  check(d.wheel != Drive::follow_wheel, "wheel drive", "free or imposed_velocity", 0);
  check_finite(d.carriage_value, "carriage_value");
  check_finite(d.spindle_velocity_m_s, "spindle_velocity_m_s");
  check_finite(d.wheel_value, "wheel_value");
  drives_ = d;
}

double Rig::longitudinal_mass_kg() const {
  return p_.carriage_mass_kg + p_.wheel_mass_kg + p_.spindle_mass_kg + p_.suspended_mass_kg;
}
double Rig::spindle_dof_mass_kg() const { return p_.wheel_mass_kg + p_.spindle_mass_kg; }
double Rig::vertical_load_N() const {
  return (p_.wheel_mass_kg + p_.spindle_mass_kg + p_.suspended_mass_kg) * p_.gravity_m_s2;
}
double Rig::spring_force_on_mass_N() const {
  return -p_.spring_k_N_m * spring_extension_m() - p_.spring_c_N_s_m * (u_.mass_z_m_s - u_.z_m_s);
}

void Rig::step(const WheelWrench &w, double dt) {
  check(dt > 0 && std::isfinite(dt), "dt", "> 0 s and finite", dt);
  for (int i = 0; i < 3; ++i) {
    check_finite(w.f_B_W[i], "contact force component");
    check_finite(w.t_B_W[i], "contact torque component");
  }
  const double g = p_.gravity_m_s2;
  const double Mx = longitudinal_mass_kg(), Mz = spindle_dof_mass_kg(), Mm = p_.suspended_mass_kg;
  const double I = p_.wheel_axle_inertia_kg_m2;

  // Generalized forces at state n, without the drives.
  const double spring_on_mass = spring_force_on_mass_N();
  const double fx = w.f_B_W.x();
  const double fz = w.f_B_W.z() - Mz * g - spring_on_mass;
  const double fm = -Mm * g + spring_on_mass;
  const double ft = w.t_B_W.y();

  RigReactions r;
  r.held_force_y_N = w.f_B_W.y();
  r.held_torque_x_Nm = w.t_B_W.x();
  r.held_torque_z_Nm = w.t_B_W.z();

  // Wheel first: the carriage may follow the new ω.
  RigVelocities u = u_;
  if (drives_.wheel == Drive::imposed_velocity) {
    u.omega_rad_s = drives_.wheel_value;
    r.motor_torque_Nm = I * (u.omega_rad_s - u_.omega_rad_s) / dt - ft;
  } else {
    r.motor_torque_Nm = drives_.wheel_value;
    u.omega_rad_s += dt * (ft + r.motor_torque_Nm) / I;
  }

  switch (drives_.carriage) {
  case Drive::free:
    r.carriage_force_N = drives_.carriage_value;
    u.x_m_s += dt * (fx + r.carriage_force_N) / Mx;
    break;
  case Drive::imposed_velocity:
  case Drive::follow_wheel:
    u.x_m_s = drives_.carriage == Drive::imposed_velocity ? drives_.carriage_value
                                                          : drives_.carriage_value * u.omega_rad_s;
    r.carriage_force_N = Mx * (u.x_m_s - u_.x_m_s) / dt - fx;
    break;
  }

  if (drives_.spindle == Drive::imposed_velocity) {
    u.z_m_s = drives_.spindle_velocity_m_s;
    r.spindle_support_force_N = Mz * (u.z_m_s - u_.z_m_s) / dt - fz;
  } else {
    u.z_m_s += dt * fz / Mz;
  }
  u.mass_z_m_s += dt * fm / Mm;

  q_.x_m += dt * u.x_m_s;
  q_.z_m += dt * u.z_m_s;
  q_.mass_z_m += dt * u.mass_z_m_s;
  q_.theta_rad += dt * u.omega_rad_s;
  u_ = u;
  reactions_ = r;
  if (dt != segment_dt_s_) { // a new run of equal steps starts at the current time
    segment_time0_s_ = time_s_;
    segment_step0_ = steps_;
    segment_dt_s_ = dt;
  }
  ++steps_;
  time_s_ = segment_time0_s_ + static_cast<double>(steps_ - segment_step0_) * dt;
}

WheelPose Rig::wheel_state() const {
  WheelPose s;
  s.p_WB_W = Eigen::Vector3d(q_.x_m, 0.0, q_.z_m);
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(q_.theta_rad, Eigen::Vector3d::UnitY()));
  s.v_WB_W = Eigen::Vector3d(u_.x_m_s, 0.0, u_.z_m_s);
  s.w_WB_W = Eigen::Vector3d(0.0, u_.omega_rad_s, 0.0);
  return s;
}

RigEnergy Rig::energy() const {
  RigEnergy e;
  const double Mz = spindle_dof_mass_kg(), Mm = p_.suspended_mass_kg;
  e.kinetic_J = 0.5 * (longitudinal_mass_kg() * u_.x_m_s * u_.x_m_s + Mz * u_.z_m_s * u_.z_m_s +
                       Mm * u_.mass_z_m_s * u_.mass_z_m_s +
                       p_.wheel_axle_inertia_kg_m2 * u_.omega_rad_s * u_.omega_rad_s);
  e.gravity_J = p_.gravity_m_s2 * (Mz * q_.z_m + Mm * q_.mass_z_m);
  const double ext = spring_extension_m();
  e.spring_J = 0.5 * p_.spring_k_N_m * ext * ext;
  return e;
}

Rig::Snapshot Rig::snapshot() const {
  return Snapshot{q_,           u_,     drives_,          reactions_,
                  time_s_,      steps_, segment_time0_s_, segment_step0_,
                  segment_dt_s_};
}

void Rig::restore(const Snapshot &s) {
  q_ = s.q;
  u_ = s.u;
  drives_ = s.drives;
  reactions_ = s.reactions;
  time_s_ = s.time_s;
  steps_ = s.steps;
  segment_time0_s_ = s.segment_time0_s;
  segment_step0_ = s.segment_step0;
  segment_dt_s_ = s.segment_dt_s;
}

} // namespace wheelsim::rig
