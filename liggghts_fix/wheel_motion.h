// How fix wheel/cosim's wheel moves: the state of the rigid wheel and the interface through which
// a motion source (prescribed here; the coupled rig next) advances it by one step.
//
// Frames and units: everything in the LIGGGHTS world frame, SI. The wheel frame is the mesh frame
// (for meshes from wheel-mesh: origin at the wheel centre, axle along +y); `orientation` rotates
// wheel-frame vectors into the world frame (R_WB), `position_m` is the wheel centre p_WoBo_W.
#ifndef WHEELSIM_WHEEL_MOTION_H
#define WHEELSIM_WHEEL_MOTION_H

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <string>

namespace wheelsim {

/// Pose and twist of the rigid wheel at one step.
struct WheelState {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();             ///< wheel centre [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< R_WB, unit
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();           ///< centre velocity [m/s]
  Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero(); ///< ω [rad/s], world frame

  /// Velocity [m/s] of the wheel's material point at `point_m` (world frame).
  Eigen::Vector3d velocity_at(const Eigen::Vector3d &point_m) const {
    return velocity_m_s + angular_velocity_rad_s.cross(point_m - position_m);
  }
};

/// Contact wrench on the wheel, summed over all particles and ranks (world frame).
struct WheelWrench {
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque_Nm = Eigen::Vector3d::Zero(); ///< about the wheel centre
  long contacts = 0;
};

/// Advances the pose by one step of length dt [s] with the given twist held constant: position
/// by v·dt, orientation by the rotation exp(ω dt) applied in the world frame. The twist itself
/// is left as given.
WheelState advance_pose(const WheelState &now, const Eigen::Vector3d &velocity_m_s,
                        const Eigen::Vector3d &angular_velocity_rad_s, double dt_s);

/// A source of wheel motion. The fix calls, on every rank, in this order each step:
///   wrench_computed(step n, wrench at n)   from end_of_step, after the wrench is reduced;
///   next_state(state at n, n + 1, dt)      from initial_integrate of step n + 1.
/// A coupled source sends the wrench in the first call and receives the pose in the second, so
/// the partner computes while LIGGGHTS integrates the particles.
class WheelMotion {
public:
  virtual ~WheelMotion() = default;
  /// One line for the log, e.g. "prescribed: v = (0.1, 0, 0) m/s, omega = v_w rad/s".
  virtual std::string describe() const = 0;
  virtual void wrench_computed(std::int64_t step, double time_s, const WheelWrench &wrench) {
    (void)step, (void)time_s, (void)wrench;
  }
  /// The wheel state at `next_step`, one time step dt [s] after `now`.
  virtual WheelState next_state(const WheelState &now, std::int64_t next_step, double dt_s) = 0;
};

} // namespace wheelsim

#endif
