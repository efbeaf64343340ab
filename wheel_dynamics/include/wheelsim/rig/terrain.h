// The wheel's state as the rig reports it, the contact wrench a terrain returns, and the interface
// of in-process terrains (the flat ground, SCM; terrain_registry.h). A remote terrain (LIGGGHTS
// through the coupler) does not implement Terrain: its main loop hands the received wrench to
// Rig::step or RigSimulation::advance directly. See docs/rig-config.md ("Frames").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace wheelsim::scm {
class ScmTerrain;
}

namespace wheelsim::rig {

/// Kinematic state of the wheel body B at one step, world frame W (x forward, y left, z up).
/// B is the wheel (= mesh) frame: origin Bo at the wheel centre, axle +y, x forward, z up at
/// θ = 0. Forward rolling along +x is a positive rotation about +y.
struct WheelState {
  /// Position of the wheel centre Bo in W [m].
  Eigen::Vector3d p_WBo_W = Eigen::Vector3d::Zero();
  /// Orientation of B in W (unit quaternion).
  Eigen::Quaterniond R_WB = Eigen::Quaterniond::Identity();
  /// Velocity of Bo in W, expressed in W [m/s].
  Eigen::Vector3d v_WBo_W = Eigen::Vector3d::Zero();
  /// Angular velocity of B in W, expressed in W [rad/s].
  Eigen::Vector3d w_WB_W = Eigen::Vector3d::Zero();
};

/// The total contact wrench the terrain exerts on the wheel, world frame.
struct ContactWrench {
  /// Contact force on the wheel [N], expressed in W.
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  /// Contact torque on the wheel about its centre Bo [N m], expressed in W.
  Eigen::Vector3d torque_Nm = Eigen::Vector3d::Zero();
};

/// An in-process terrain: the contact wrench for a wheel state. Called once per step with the
/// state of step n and its time; may keep history (tangential springs, soil deformation), so it
/// must be called exactly once per step, in order.
class Terrain {
public:
  virtual ~Terrain() = default;
  /// Contact wrench on the wheel in state `state` at time `time_s` [s].
  virtual ContactWrench contact(const WheelState &state, double time_s) = 0;
  /// Contacts of the last call (run health, the contact/count series): nodes for SCM; 1 for a
  /// terrain that does not count them.
  virtual double contact_count() const { return 1.0; }
  /// The soil height grid, for terrains that have one (SCM: /terrain snapshots); else nullptr.
  virtual const scm::ScmTerrain *height_grid() const { return nullptr; }
};

} // namespace wheelsim::rig
