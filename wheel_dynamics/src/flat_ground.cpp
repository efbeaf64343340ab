#include "wheelsim/rig/flat_ground.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wheelsim::rig {
namespace {
void check(bool ok, const char *name, const char *expected, double value) {
  if (ok && std::isfinite(value))
    return;
  std::ostringstream os;
  os << "FlatGround: " << name << " must be " << expected << ", got " << value;
  throw std::invalid_argument(os.str());
}
} // namespace

FlatGround::FlatGround(const FlatGroundParameters &p) : p_(p) {
  check(true, "surface_height_m", "finite", p.surface_height_m);
  check(p.radius_m > 0, "radius_m", "> 0 m", p.radius_m);
  check(p.stiffness_N_m > 0, "stiffness_N_m", "> 0 N/m", p.stiffness_N_m);
  check(p.damping_N_s_m >= 0, "damping_N_s_m", ">= 0 N s/m", p.damping_N_s_m);
  check(p.friction >= 0, "friction", ">= 0", p.friction);
  check(p.tangential_stiffness_N_m > 0, "tangential_stiffness_N_m", "> 0 N/m",
        p.tangential_stiffness_N_m);
  check(p.tangential_damping_N_s_m >= 0, "tangential_damping_N_s_m", ">= 0 N s/m",
        p.tangential_damping_N_s_m);
  check(p.slip_velocity_scale_m_s > 0, "slip_velocity_scale_m_s", "> 0 m/s",
        p.slip_velocity_scale_m_s);
}

WheelWrench FlatGround::contact(const WheelPose &s, double time_s) {
  const double dt = has_last_time_ ? time_s - last_time_s_ : 0.0;
  last_time_s_ = time_s;
  has_last_time_ = true;

  WheelWrench w;
  const double R = p_.radius_m;
  const double penetration = p_.surface_height_m - (s.p_WB_W.z() - R);
  if (penetration <= 0.0) {
    slip_displacement_m_.setZero();
    return w;
  }
  const double N = std::max(0.0, p_.stiffness_N_m * penetration - p_.damping_N_s_m * s.v_WB_W.z());
  const Eigen::Vector3d r(0.0, 0.0, -R); // centre -> lowest point, world
  const Eigen::Vector3d v_contact = s.v_WB_W + s.w_WB_W.cross(r);
  const Eigen::Vector2d v_slip(v_contact.x(), v_contact.y());
  const double cap = p_.friction * N;

  Eigen::Vector2d Ft = Eigen::Vector2d::Zero();
  if (p_.friction_model == FrictionModel::coulomb) {
    slip_displacement_m_ += dt * v_slip;
    Ft = -p_.tangential_stiffness_N_m * slip_displacement_m_ - p_.tangential_damping_N_s_m * v_slip;
    const double norm = Ft.norm();
    if (norm > cap) { // sliding: force at the cap, spring kept consistent with it
      Ft *= cap / norm;
      slip_displacement_m_ = -Ft / p_.tangential_stiffness_N_m;
    }
  } else {
    const double speed = v_slip.norm();
    if (speed > 0.0)
      Ft = -cap * std::tanh(speed / p_.slip_velocity_scale_m_s) * v_slip / speed;
  }
  w.f_B_W = Eigen::Vector3d(Ft.x(), Ft.y(), N);
  w.t_B_W = r.cross(w.f_B_W);
  return w;
}

} // namespace wheelsim::rig
