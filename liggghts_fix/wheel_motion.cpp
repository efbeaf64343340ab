#include "wheel_motion.h"

#include <cmath>

namespace wheelsim {

WheelState advance_pose(const WheelState &now, const Eigen::Vector3d &velocity_m_s,
                        const Eigen::Vector3d &angular_velocity_rad_s, double dt_s) {
  WheelState next = now;
  next.velocity_m_s = velocity_m_s;
  next.angular_velocity_rad_s = angular_velocity_rad_s;
  next.position_m = now.position_m + velocity_m_s * dt_s;
  const double angle = angular_velocity_rad_s.norm() * dt_s;
  if (angle > 0.0) {
    const Eigen::Quaterniond step(Eigen::AngleAxisd(angle, angular_velocity_rad_s.normalized()));
    next.orientation = (step * now.orientation).normalized();
  }
  return next;
}

} // namespace wheelsim
