#include "coupler/pose_messages.h"

#include <cmath>

namespace wheelsim::coupler {

namespace {

Vec3 to_array(const Eigen::Vector3d &v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d to_vector(const Vec3 &a) { return {a[0], a[1], a[2]}; }

Eigen::Quaterniond to_quaternion(const Quat &q) {
  Eigen::Quaterniond out(q[0], q[1], q[2], q[3]); // (w, x, y, z)
  if (std::abs(out.squaredNorm() - 1.0) > 1e-12)
    out.normalize();
  return out;
}

} // namespace

WheelState to_message(const WheelPose &pose) {
  WheelState m;
  m.p_WC_W = to_array(pose.p_WB_W);
  m.q_WB = {pose.q_WB.w(), pose.q_WB.x(), pose.q_WB.y(), pose.q_WB.z()};
  m.v_WC_W = to_array(pose.v_WB_W);
  m.w_WB_W = to_array(pose.w_WB_W);
  return m;
}

WheelPose from_message(const WheelState &message) {
  WheelPose pose;
  pose.p_WB_W = to_vector(message.p_WC_W);
  pose.q_WB = to_quaternion(message.q_WB);
  pose.v_WB_W = to_vector(message.v_WC_W);
  pose.w_WB_W = to_vector(message.w_WB_W);
  return pose;
}

WheelPose from_message(const Hello &message) {
  WheelState state;
  state.p_WC_W = message.p_WC_W;
  state.q_WB = message.q_WB;
  return from_message(state);
}

Wrench to_message(const WheelWrench &wrench, std::int64_t step, double time_s,
                  std::int64_t n_contacts) {
  Wrench m;
  m.step = step;
  m.time_s = time_s;
  m.f_C_W = to_array(wrench.f_B_W);
  m.t_C_W = to_array(wrench.t_B_W);
  m.n_contacts = n_contacts;
  return m;
}

WheelWrench from_message(const Wrench &message) {
  WheelWrench wrench;
  wrench.f_B_W = to_vector(message.f_C_W);
  wrench.t_B_W = to_vector(message.t_C_W);
  return wrench;
}

} // namespace wheelsim::coupler
