// Unit tests of integrate_pose (wheelsim/pose.h): n steps of a constant twist against the closed
// form, composition of steps, the rotation applied in the world frame, zero ω, velocity_at.
#include "wheelsim/pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace wheelsim {
namespace {

using Eigen::AngleAxisd;
using Eigen::Quaterniond;
using Eigen::Vector3d;

/// A pose with a general orientation and a twist about a general axis.
WheelPose sample_pose() {
  WheelPose s;
  s.p_WB_W = Vector3d(0.3, -1.2, 0.45);
  s.q_WB = Quaterniond(AngleAxisd(0.7, Vector3d(1, -2, 0.5).normalized()));
  s.v_WB_W = Vector3d(0.11, -0.02, 0.035);
  s.w_WB_W = Vector3d(0.4, 2.5, -0.3);
  return s;
}

TEST(IntegratePose, ConstantTwistOverNStepsEqualsTheClosedForm) {
  // n steps of constant ω: q(t) = exp(ω t) q0 = rotation by |ω| t about ω/|ω|, then q0;
  // p(t) = p0 + v t.
  const WheelPose s0 = sample_pose();
  const double dt = 2e-5;
  const int n = 20000;
  WheelPose s = s0;
  for (int i = 0; i < n; ++i)
    s = integrate_pose(s, dt);
  const double t = n * dt;
  const Quaterniond expected =
      Quaterniond(AngleAxisd(s0.w_WB_W.norm() * t, s0.w_WB_W.normalized())) * s0.q_WB;
  // n steps, each exact to a few ulp: the error grows at most like n * eps = 4e-12 rad
  EXPECT_LT(s.q_WB.angularDistance(expected), 1e-11);
  EXPECT_NEAR(s.q_WB.norm(), 1.0, 1e-15);
  EXPECT_LT((s.p_WB_W - (s0.p_WB_W + s0.v_WB_W * t)).norm(), 1e-12);
  // The rotated angle itself: |ω| t = 2.56 rad, as a relative rotation from q0.
  EXPECT_NEAR(s.q_WB.angularDistance(s0.q_WB), s0.w_WB_W.norm() * t, 1e-11);
  // The twist is carried over unchanged, bit for bit.
  EXPECT_EQ(s.v_WB_W, s0.v_WB_W);
  EXPECT_EQ(s.w_WB_W, s0.w_WB_W);
}

TEST(IntegratePose, TwoStepsComposeToOneStepOfTheirSum) {
  // Constant twist: exp(ω dt2) exp(ω dt1) = exp(ω (dt1 + dt2)).
  const WheelPose s0 = sample_pose();
  const WheelPose two = integrate_pose(integrate_pose(s0, 1e-3), 3e-3);
  const WheelPose one = integrate_pose(s0, 4e-3);
  EXPECT_LT(two.q_WB.angularDistance(one.q_WB), 1e-15);
  EXPECT_LT((two.p_WB_W - one.p_WB_W).norm(), 1e-15);
}

TEST(IntegratePose, StepsWithDifferentTwistsComposeInTheWorldFrame) {
  // ω1 for dt, then ω2 for dt: q = exp(ω2 dt) exp(ω1 dt) q0 — each rotation is applied on the
  // left (in W), not on the right (in B); for non-commuting rotations the two differ.
  WheelPose s = sample_pose();
  const Quaterniond q0 = s.q_WB;
  const Vector3d p0 = s.p_WB_W;
  const double dt = 0.1;
  const Vector3d w1(0, 0, 5.0), w2(3.0, 0, 0), v1(1, 0, 0), v2(0, 0, -2);
  s.v_WB_W = v1;
  s.w_WB_W = w1;
  s = integrate_pose(s, dt);
  s.v_WB_W = v2;
  s.w_WB_W = w2;
  s = integrate_pose(s, dt);
  const Quaterniond R1(AngleAxisd(5.0 * dt, Vector3d::UnitZ())),
      R2(AngleAxisd(3.0 * dt, Vector3d::UnitX()));
  EXPECT_LT(s.q_WB.angularDistance(R2 * R1 * q0), 1e-15);
  EXPECT_GT(s.q_WB.angularDistance(q0 * R1 * R2), 1e-2); // the body-frame order is not it
  EXPECT_LT((s.p_WB_W - (p0 + v1 * dt + v2 * dt)).norm(), 1e-15);
}

TEST(IntegratePose, ZeroAngularVelocityLeavesTheOrientationBitForBit) {
  WheelPose s = sample_pose();
  s.q_WB = Quaterniond(0.5, 0.5, 0.5, 0.5000001); // not renormalised when ω = 0
  s.w_WB_W.setZero();
  const WheelPose next = integrate_pose(s, 1e-3);
  EXPECT_EQ(std::memcmp(next.q_WB.coeffs().data(), s.q_WB.coeffs().data(), 4 * sizeof(double)), 0);
  EXPECT_EQ(next.p_WB_W, s.p_WB_W + s.v_WB_W * 1e-3);
}

TEST(IntegratePose, RollingWheelPointVelocity) {
  // Forward rolling along +x is a positive rotation about +y (axle +y): the top of a wheel of
  // radius 0.5 m moves at v + ω R, the contact point at v − ω R.
  WheelPose s;
  s.p_WB_W = Vector3d(1, 0, 0.5);
  s.v_WB_W = Vector3d(0.2, 0, 0);
  s.w_WB_W = Vector3d(0, 0.4, 0);
  EXPECT_DOUBLE_EQ(s.velocity_at(s.p_WB_W + Vector3d(0, 0, 0.5)).x(), 0.2 + 0.4 * 0.5);
  EXPECT_DOUBLE_EQ(s.velocity_at(s.p_WB_W - Vector3d(0, 0, 0.5)).x(), 0.2 - 0.4 * 0.5);
  // One step later a body point fixed in B has moved by that velocity to first order.
  const Vector3d top_B(0, 0, 0.5);
  const double dt = 1e-6;
  const WheelPose next = integrate_pose(s, dt);
  const Vector3d moved = (next.p_WB_W + next.q_WB * top_B) - (s.p_WB_W + s.q_WB * top_B);
  EXPECT_LT((moved / dt - s.velocity_at(s.p_WB_W + top_B)).norm(), 1e-6);
}

} // namespace
} // namespace wheelsim
