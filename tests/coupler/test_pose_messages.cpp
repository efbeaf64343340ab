// coupler/pose_messages.h: the wire structs <-> WheelPose / WheelWrench, field by field and bit
// for bit (also through encode/decode), and the renormalisation rule for quaternions.
#include "coupler/pose_messages.h"
#include "coupler/protocol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace wheelsim::coupler {
namespace {

WheelPose sample_pose() {
  WheelPose s;
  s.p_WB_W = Eigen::Vector3d(0.1, -0.0123, 0.144);
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.2, 1.0, -0.1).normalized()));
  s.v_WB_W = Eigen::Vector3d(0.1125, 1e-7, -0.2);
  s.w_WB_W = Eigen::Vector3d(-3e-3, 1.5, 0.25);
  return s;
}

template <typename T> bool same_bits(const T &a, const T &b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

void expect_same_bits(const WheelPose &a, const WheelPose &b) {
  EXPECT_TRUE(same_bits(a.p_WB_W, b.p_WB_W));
  EXPECT_TRUE(same_bits(a.q_WB.coeffs(), b.q_WB.coeffs()));
  EXPECT_TRUE(same_bits(a.v_WB_W, b.v_WB_W));
  EXPECT_TRUE(same_bits(a.w_WB_W, b.w_WB_W));
}

TEST(PoseMessages, PoseFieldsMapOneToOne) {
  const WheelPose s = sample_pose();
  const WheelState m = to_message(s);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(m.p_WC_W[k], s.p_WB_W[k]);
    EXPECT_EQ(m.v_WC_W[k], s.v_WB_W[k]);
    EXPECT_EQ(m.w_WB_W[k], s.w_WB_W[k]);
  }
  // (w, x, y, z) on the wire; Eigen stores (x, y, z, w)
  EXPECT_EQ(m.q_WB[0], s.q_WB.w());
  EXPECT_EQ(m.q_WB[1], s.q_WB.x());
  EXPECT_EQ(m.q_WB[2], s.q_WB.y());
  EXPECT_EQ(m.q_WB[3], s.q_WB.z());
}

TEST(PoseMessages, PoseRoundTripIsBitForBit) {
  const WheelPose s = sample_pose();
  expect_same_bits(from_message(to_message(s)), s);
  // ... also through the wire format, as the rig's Pose reaches the fix.
  Pose pose;
  pose.step = 1234;
  pose.state = to_message(s);
  const Pose received = decode_pose(encode(pose));
  EXPECT_EQ(received.step, 1234);
  expect_same_bits(from_message(received.state), s);
}

TEST(PoseMessages, OnlyAVisiblyOffQuaternionIsRenormalised) {
  WheelState m = to_message(sample_pose());
  // |q|^2 - 1 = 2e-13: kept bit for bit (a unit quaternion's last bits are not touched)
  const double tiny = 1.0 + 1e-13;
  for (double &c : m.q_WB)
    c *= tiny;
  const WheelPose kept = from_message(m);
  EXPECT_EQ(kept.q_WB.w(), m.q_WB[0]);
  EXPECT_EQ(kept.q_WB.y(), m.q_WB[2]);
  // |q|^2 - 1 = 2e-7 (inside the protocol's 1e-6 on |q|): renormalised
  for (double &c : m.q_WB)
    c *= 1.0 + 1e-7;
  validate(Pose{7, m});
  const WheelPose fixed = from_message(m);
  EXPECT_NEAR(fixed.q_WB.norm(), 1.0, 1e-15);
  EXPECT_LT(fixed.q_WB.angularDistance(sample_pose().q_WB), 1e-15);
}

TEST(PoseMessages, HelloGivesTheInitialPoseWithZeroTwist) {
  Hello hello;
  hello.p_WC_W = {0.5, 0.25, 0.144};
  hello.q_WB = {std::cos(0.25), 0.0, std::sin(0.25), 0.0};
  const WheelPose s = from_message(hello);
  EXPECT_EQ(s.p_WB_W, Eigen::Vector3d(0.5, 0.25, 0.144));
  EXPECT_EQ(s.q_WB.w(), std::cos(0.25));
  EXPECT_EQ(s.q_WB.y(), std::sin(0.25));
  EXPECT_EQ(s.q_WB.x(), 0.0);
  EXPECT_EQ(s.v_WB_W, Eigen::Vector3d::Zero());
  EXPECT_EQ(s.w_WB_W, Eigen::Vector3d::Zero());
}

TEST(PoseMessages, WrenchRoundTripIsBitForBit) {
  WheelWrench w;
  w.f_B_W = Eigen::Vector3d(1.5, -0.1 / 3.0, 30.000001);
  w.t_B_W = Eigen::Vector3d(0.125, -2.0 / 7.0, 1e-9);
  const Wrench m = to_message(w, 4321, 0.04321, 57);
  EXPECT_EQ(m.step, 4321);
  EXPECT_EQ(m.time_s, 0.04321);
  EXPECT_EQ(m.n_contacts, 57);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(m.f_C_W[k], w.f_B_W[k]);
    EXPECT_EQ(m.t_C_W[k], w.t_B_W[k]);
  }
  const WheelWrench back = from_message(decode_wrench(encode(m)));
  EXPECT_TRUE(same_bits(back.f_B_W, w.f_B_W));
  EXPECT_TRUE(same_bits(back.t_B_W, w.t_B_W));
}

} // namespace
} // namespace wheelsim::coupler
