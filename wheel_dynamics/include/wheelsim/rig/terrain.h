// The interface of in-process terrains (the flat ground, SCM; terrain_registry.h): the contact
// wrench on the wheel for its pose. The pose (WheelPose) and the wrench (WheelWrench) are the
// types of wheelsim/pose.h shared with fix wheel/cosim, SCM and the coupler. In the rig, W is the
// rig's world frame (x forward, y left, z up) and B the wheel (= mesh) frame: origin Bo at the
// wheel centre, axle +y, x forward, z up at θ = 0; forward rolling along +x is a positive rotation
// about +y. A remote terrain (LIGGGHTS through the coupler) does not implement Terrain: its main
// loop hands the received wrench to Rig::step or RigSimulation::advance directly. See
// docs/rig-config.md ("Frames").
#pragma once

#include "wheelsim/pose.h"

namespace wheelsim::scm {
class ScmTerrain;
}

namespace wheelsim::rig {

/// An in-process terrain: the contact wrench for a wheel state. Called once per step with the
/// state of step n and its time; may keep history (tangential springs, soil deformation), so it
/// must be called exactly once per step, in order.
class Terrain {
public:
  virtual ~Terrain() = default;
  /// Contact wrench on the wheel (about its centre, W) at pose `state` and time `time_s` [s].
  virtual WheelWrench contact(const WheelPose &state, double time_s) = 0;
  /// Contacts of the last call (run health, the contact/count series): nodes for SCM; 1 for a
  /// terrain that does not count them.
  virtual double contact_count() const { return 1.0; }
  /// The soil height grid, for terrains that have one (SCM: /terrain snapshots); else nullptr.
  virtual const scm::ScmTerrain *height_grid() const { return nullptr; }
};

} // namespace wheelsim::rig
