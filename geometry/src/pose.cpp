#include "wheelsim/pose.h"

namespace wheelsim {

WheelPose integrate_pose(const WheelPose &now, double dt_s) {
  WheelPose next = now;
  next.p_WB_W = now.p_WB_W + now.v_WB_W * dt_s;
  const double angle_rad = now.w_WB_W.norm() * dt_s;
  if (angle_rad > 0.0) {
    const Eigen::Quaterniond step(Eigen::AngleAxisd(angle_rad, now.w_WB_W.normalized()));
    next.q_WB = (step * now.q_WB).normalized();
  }
  return next;
}

} // namespace wheelsim
