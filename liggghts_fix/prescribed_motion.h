// `motion prescribed vx vy vz wx wy wz` of fix wheel/cosim: the wheel centre's velocity [m/s] and
// the wheel's angular velocity [rad/s], world frame, each a constant or an expression the fix
// evaluates every step (a LIGGGHTS equal-style variable `v_name`).
#ifndef WHEELSIM_PRESCRIBED_MOTION_H
#define WHEELSIM_PRESCRIBED_MOTION_H

#include "wheel_motion.h"

#include <array>
#include <functional>
#include <string>

namespace wheelsim {

class PrescribedMotion : public WheelMotion {
public:
  /// A component's value now (a constant, or a variable evaluated at the current step).
  using Component = std::function<double()>;

  PrescribedMotion(std::array<Component, 3> velocity_m_s,
                   std::array<Component, 3> angular_velocity_rad_s, std::string description);

  std::string describe() const override { return description_; }
  /// Evaluates the twist at the new step, then moves the pose over the step with it
  /// (integrate_pose).
  WheelPose next_state(const WheelPose &now, std::int64_t next_step, double dt_s) override;

  /// The twist the components give now [m/s, rad/s].
  Eigen::Vector3d velocity_m_s() const;
  Eigen::Vector3d angular_velocity_rad_s() const;

private:
  std::array<Component, 3> velocity_;
  std::array<Component, 3> angular_velocity_;
  std::string description_;
};

} // namespace wheelsim

#endif
