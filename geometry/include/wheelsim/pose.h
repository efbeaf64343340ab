// The wheel's pose (with its twist) and the contact wrench on it: one type each, shared by fix
// wheel/cosim, the rig (wheel-rig), the SCM terrain and the coupler (whose wire structs in
// coupler/protocol.h convert to and from these in coupler/pose_messages.h), and the one function
// that integrates a pose over a time step. Eigen only (library wheelsim_pose).
//
// Frames and names (Drake style, STYLE.md): W = world frame (LIGGGHTS' simulation box, or the
// rig's world: x forward, y left, z up), B = wheel body frame = the mesh frame, its origin Bo at
// the wheel centre (for meshes from wheel-mesh: axle along +y). p_WB_W = position of Bo in W,
// q_WB = orientation of B in W (rotates B-frame vectors into W), v_WB_W = velocity of Bo in W,
// w_WB_W = angular velocity of B in W, all expressed in W. SI units.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace wheelsim {

/// Pose and twist of the wheel body B in W at one step.
struct WheelPose {
  /// Position of the wheel centre Bo in W [m].
  Eigen::Vector3d p_WB_W = Eigen::Vector3d::Zero();
  /// Orientation of B in W, unit quaternion.
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();
  /// Velocity of Bo in W, expressed in W [m/s].
  Eigen::Vector3d v_WB_W = Eigen::Vector3d::Zero();
  /// Angular velocity of B in W, expressed in W [rad/s].
  Eigen::Vector3d w_WB_W = Eigen::Vector3d::Zero();

  /// Velocity in W [m/s] of the wheel's material point at p_WP_W (position in W [m]).
  Eigen::Vector3d velocity_at(const Eigen::Vector3d &p_WP_W) const {
    return v_WB_W + w_WB_W.cross(p_WP_W - p_WB_W);
  }
};

/// The total contact wrench the terrain (particles, SCM soil, flat ground) exerts on the wheel.
struct WheelWrench {
  /// Contact force on the wheel [N], expressed in W.
  Eigen::Vector3d f_B_W = Eigen::Vector3d::Zero();
  /// Contact torque on the wheel about its centre Bo [N m], expressed in W.
  Eigen::Vector3d t_B_W = Eigen::Vector3d::Zero();
};

/// The pose after one step dt_s [s] with the twist of `now` held constant: p_WB_W += v_WB_W dt,
/// q_WB <- exp(w_WB_W dt) q_WB (the rotation by |ω| dt about ω/|ω|, applied in W), renormalised;
/// the twist is carried over unchanged. ω = 0 leaves q_WB bit for bit as it is. Used by fix
/// wheel/cosim (motion prescribed, and the zero-order hold of motion coupled) and by wheel-rig
/// --kinematic, so that a coupled run with a fixed twist reproduces the prescribed one exactly.
WheelPose integrate_pose(const WheelPose &now, double dt_s);

} // namespace wheelsim
