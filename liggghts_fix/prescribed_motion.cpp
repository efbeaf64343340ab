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

WheelState PrescribedMotion::next_state(const WheelState &now, std::int64_t next_step,
                                        double dt_s) {
  (void)next_step;
  return advance_pose(now, velocity_m_s(), angular_velocity_rad_s(), dt_s);
}

} // namespace wheelsim
