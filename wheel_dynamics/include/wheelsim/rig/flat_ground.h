// A rigid flat ground for tests of the rig: the wheel is a cylinder of radius R (the effective
// radius) touching the horizontal plane z = surface height at its lowest point.
//   normal:     N = max(0, k_n δ + c_n dδ/dt), δ = surface - (z_c - R) (penetration) [N]
//   tangential (contact-point slip velocity v_s = v_x - ω R along x, and v_y):
//     coulomb:     a tangential spring-damper (k_t, c_t) on the accumulated slip displacement,
//                  capped at μ N (no slip below the cap: the contact sticks; above it, it slides
//                  and the spring is kept at the cap, Cundall–Strack style);
//     regularized: F_t = -μ N tanh(|v_s| / v_c) v_s/|v_s| (a smooth slip law with a known
//                  steady-state slip for a given load, used to test the free-carriage modes).
// The force acts at the lowest point r = (0, 0, -R) from the centre: torque = r × F.
#pragma once

#include <string>

#include "wheelsim/rig/terrain.h"

namespace wheelsim::rig {

enum class FrictionModel { coulomb, regularized };

struct FlatGroundParameters {
  double surface_height_m = 0.0; ///< height of the ground plane [m]
  double radius_m = 0.6;         ///< contact radius R (the wheel's R_eff) [m], > 0
  double stiffness_N_m = 1.0e7;  ///< normal penalty stiffness k_n [N/m], > 0
  double damping_N_s_m = 2.0e4;  ///< normal damping c_n [N s/m], >= 0
  double friction = 0.6;         ///< Coulomb coefficient μ [-], >= 0
  FrictionModel friction_model = FrictionModel::coulomb;
  double tangential_stiffness_N_m = 1.0e6; ///< coulomb: k_t [N/m], > 0
  double tangential_damping_N_s_m = 0.0;   ///< coulomb: c_t [N s/m], >= 0
  double slip_velocity_scale_m_s = 0.01;   ///< regularized: v_c [m/s], > 0
};

class FlatGround : public Terrain {
public:
  /// Throws std::invalid_argument naming the offending parameter.
  explicit FlatGround(const FlatGroundParameters &parameters);
  WheelWrench contact(const WheelPose &state, double time_s) override;
  const FlatGroundParameters &parameters() const { return p_; }

private:
  FlatGroundParameters p_;
  Eigen::Vector2d slip_displacement_m_ = Eigen::Vector2d::Zero(); // coulomb spring (x, y)
  double last_time_s_ = 0.0;
  bool has_last_time_ = false;
};

} // namespace wheelsim::rig
