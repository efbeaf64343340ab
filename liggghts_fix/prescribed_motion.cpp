#include "prescribed_motion.h"

#include <utility>

namespace wheelsim {

PrescribedMotion::PrescribedMotion(std::array<Component, 3> velocity_m_s,
                                   std::array<Component, 3> angular_velocity_rad_s,
                                   std::string description)
    : velocity_(std::move(velocity_m_s)), angular_velocity_(std::move(angular_velocity_rad_s)),
      description_(std::move(description)) {}

Eigen::Vector3d PrescribedMotion::velocity_m_s() const {
  return {velocity_[0](), velocity_[1](), velocity_[2]()};
}

Eigen::Vector3d PrescribedMotion::angular_velocity_rad_s() const {
  return {angular_velocity_[0](), angular_velocity_[1](), angular_velocity_[2]()};
}

WheelPose PrescribedMotion::next_state(const WheelPose &now, std::int64_t next_step, double dt_s) {
  (void)next_step;
  WheelPose moving = now;
  moving.v_WB_W = velocity_m_s();
  moving.w_WB_W = angular_velocity_rad_s();
  return integrate_pose(moving, dt_s);
}

} // namespace wheelsim
