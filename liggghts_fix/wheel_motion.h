// How fix wheel/cosim's wheel moves: the interface through which a motion source (prescribed,
// prescribed_motion.h; the coupled rig, coupled_motion.h) advances the wheel by one step.
//
// The wheel's pose and twist (WheelPose) and the contact wrench (WheelWrench) are the types of
// wheelsim/pose.h shared with the rig, SCM and the coupler; here W is the LIGGGHTS world frame and
// B the mesh frame (for meshes from wheel-mesh: origin at the wheel centre, axle along +y). SI.
#ifndef WHEELSIM_WHEEL_MOTION_H
#define WHEELSIM_WHEEL_MOTION_H

#include "wheelsim/pose.h"

#include <cstdint>
#include <string>

namespace wheelsim {

/// A source of wheel motion. The fix calls, on every rank, in this order each step:
///   wrench_computed(step n, wrench at n)   from end_of_step, after the wrench (and the number
///                                          of particle contacts) is reduced over the ranks;
///   next_state(state at n, n + 1, dt)      from post_force of step n + 1, before its contacts.
/// A coupled source sends the wrench in the first call and receives the pose in the second, so
/// the partner computes while LIGGGHTS integrates the particles.
class WheelMotion {
public:
  virtual ~WheelMotion() = default;
  /// One line for the log, e.g. "prescribed: v = (0.1, 0, 0) m/s, omega = v_w rad/s".
  virtual std::string describe() const = 0;
  virtual void wrench_computed(std::int64_t step, double time_s, const WheelWrench &wrench,
                               long contacts) {
    (void)step, (void)time_s, (void)wrench, (void)contacts;
  }
  /// The wheel's pose and twist at `next_step`, one time step dt [s] after `now`.
  virtual WheelPose next_state(const WheelPose &now, std::int64_t next_step, double dt_s) = 0;
};

} // namespace wheelsim

#endif
