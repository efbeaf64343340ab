// The reference test rig (TERRAMECHANICS.md §8) as a multibody model in generalized coordinates:
//   q = (x, z, z_m, θ),  u = dq/dt = (v_x, v_z, v_m, ω)
// x    carriage position along world x [m]; the spindle, the suspended mass and the wheel move
//      with it longitudinally;
// z    height of the spindle = wheel centre (the wheel turns on the spindle) [m];
// z_m  height coordinate of the suspended mass [m], measured so that the spring (stiffness k,
//      damper c, between spindle and mass) is unstretched at z_m = z (the spring's rest length is
//      absorbed in the coordinate: extension e = z_m - z);
// θ    wheel rotation about the axle +y [rad] (forward rolling is θ increasing).
// Lateral (y) translation, roll (about x) and yaw (about z) are held by the rig: their contact
// loads are reported, not integrated. In these coordinates the mass matrix is diagonal,
//   M = diag(m_c + m_w + m_s + m_m,  m_w + m_s,  m_m,  I_axle),
// and there are no constraints, hence no drift.
//
// Integrator: semi-implicit (symplectic) Euler, u_{n+1} = u_n + dt M^-1 f(q_n, u_n, t_n),
// q_{n+1} = q_n + dt u_{n+1}. One force evaluation per step at state n, which is exactly what the
// staggered coupling delivers (the terrain's wrench at pose n); symplectic, so without damping the
// energy error stays bounded (first order in dt, oscillating, no secular drift); for conservative
// position-dependent forces it is the leapfrog / velocity-Verlet scheme LIGGGHTS itself uses,
// with velocities read at half steps. See docs/rig-config.md ("Integrator").
#pragma once

#include "wheelsim/rig/terrain.h"

namespace wheelsim::rig {

/// Masses, inertia, suspension of the rig. Checked by the Rig constructor.
struct RigParameters {
  double wheel_mass_kg = 205.0;           ///< wheel mass [kg], > 0
  double wheel_axle_inertia_kg_m2 = 72.0; ///< wheel moment of inertia about the axle [kg m^2], > 0
  double spindle_mass_kg = 100.0;         ///< spindle block [kg], >= 0
  double suspended_mass_kg = 1000.0;      ///< spring-suspended mass [kg], > 0
  double carriage_mass_kg = 0.0;          ///< extra longitudinal mass of the carriage [kg], >= 0
  double spring_k_N_m = 12000.0;          ///< suspension stiffness [N/m], > 0
  double spring_c_N_s_m = 800.0;          ///< suspension damping [N s/m], >= 0
  double gravity_m_s2 = 9.81;             ///< gravitational acceleration along -z [m/s^2], > 0
};

/// Generalized coordinates (see the file comment).
struct RigCoordinates {
  double x_m = 0.0;       ///< carriage position along world x [m]
  double z_m = 0.0;       ///< wheel centre (spindle) height [m]
  double mass_z_m = 0.0;  ///< suspended-mass coordinate z_m [m] (spring unstretched at z_m = z)
  double theta_rad = 0.0; ///< wheel rotation about +y [rad]
};

/// Generalized velocities, d/dt of RigCoordinates.
struct RigVelocities {
  double x_m_s = 0.0;       ///< carriage speed along world x [m/s]
  double z_m_s = 0.0;       ///< spindle vertical speed [m/s]
  double mass_z_m_s = 0.0;  ///< suspended-mass vertical speed [m/s]
  double omega_rad_s = 0.0; ///< wheel angular speed about +y [rad/s]
};

/// How a degree of freedom is driven during one step.
enum class Drive {
  free,             ///< integrated under the applied force/torque
  imposed_velocity, ///< velocity at n+1 prescribed; the reaction is reported
  follow_wheel,     ///< carriage only: v_{n+1} = ratio * ω_{n+1} (imposed slip); reaction reported
};

/// Per-step commands. Defaults: everything free and unloaded.
struct RigDrives {
  Drive carriage = Drive::free;
  /// free: force the carriage applies to the rig along +x [N] (a drawbar load L is -L);
  /// imposed_velocity: the carriage speed at n+1 [m/s]; follow_wheel: the ratio v/ω [m/rad].
  double carriage_value = 0.0;
  Drive spindle = Drive::free; ///< free or imposed_velocity (release phase: lowering)
  /// imposed_velocity: spindle vertical speed at n+1 [m/s]; free: ignored.
  double spindle_velocity_m_s = 0.0;
  Drive wheel = Drive::free; ///< free (motor torque) or imposed_velocity (motor imposes ω)
  /// free: motor torque on the wheel about +y [N m]; imposed_velocity: ω at n+1 [rad/s].
  double wheel_value = 0.0;
};

/// Generalized forces of the drives during the last step (applied or reaction), and the contact
/// loads the rig holds.
struct RigReactions {
  /// Force of the carriage on the rig along +x [N] (applied in free mode, reaction otherwise).
  double carriage_force_N = 0.0;
  /// Upward force of the spindle holder on the spindle [N] (0 when the spindle is free).
  double spindle_support_force_N = 0.0;
  /// Motor torque on the wheel about +y [N m] (applied, or the reaction of an imposed ω).
  double motor_torque_Nm = 0.0;
  /// Contact loads in the held directions (the rig exerts the opposite): force along world y
  /// [N], torque about world x and world z, about the wheel centre [N m].
  double held_force_y_N = 0.0;
  double held_torque_x_Nm = 0.0;
  double held_torque_z_Nm = 0.0;
};

/// Energy of the rig [J]; gravity potential zero at z = 0, spring potential zero unstretched.
struct RigEnergy {
  double kinetic_J = 0.0;
  double gravity_J = 0.0;
  double spring_J = 0.0;
  double total_J() const { return kinetic_J + gravity_J + spring_J; }
};

/// The rig: state n, and a step to n+1 with the contact wrench computed at state n.
class Rig {
public:
  /// Throws std::invalid_argument naming the offending parameter and value.
  Rig(const RigParameters &parameters, const RigCoordinates &q0, const RigVelocities &u0,
      double time0_s = 0.0);

  /// Drives used by the following steps (kept until changed).
  void set_drives(const RigDrives &drives);
  const RigDrives &drives() const { return drives_; }

  /// Advances state n -> n+1 by `dt` [s] (> 0, finite) with the contact wrench at state n. The
  /// time is t0 + n dt while dt stays the same (no accumulated rounding).
  void step(const WheelWrench &wrench_at_current_state, double dt);

  /// The wheel body's state (pose, twist) at the current step, world frame.
  WheelPose wheel_state() const;

  const RigCoordinates &coordinates() const { return q_; }
  const RigVelocities &velocities() const { return u_; }
  double time_s() const { return time_s_; }
  long long step_count() const { return steps_; }
  /// Drive and held loads of the last step (zero before the first step).
  const RigReactions &reactions() const { return reactions_; }
  const RigParameters &parameters() const { return p_; }

  /// Longitudinal mass (carriage + wheel + spindle + suspended mass) [kg].
  double longitudinal_mass_kg() const;
  /// Vertical mass of the spindle DOF (wheel + spindle) [kg].
  double spindle_dof_mass_kg() const;
  /// Total weight carried by the wheel at rest, (m_w + m_s + m_m) g [N].
  double vertical_load_N() const;
  /// Spring extension e = z_m - z [m] (negative: compressed) and the force the spring exerts on
  /// the suspended mass along +z [N] (stiffness and damper).
  double spring_extension_m() const { return q_.mass_z_m - q_.z_m; }
  double spring_force_on_mass_N() const;

  RigEnergy energy() const;

  /// The whole state of the rig between two steps (checkpoints): restoring it continues the run
  /// bit for bit.
  struct Snapshot {
    RigCoordinates q;
    RigVelocities u;
    RigDrives drives;
    RigReactions reactions;
    double time_s = 0.0;
    long long steps = 0;
    double segment_time0_s = 0.0;
    long long segment_step0 = 0;
    double segment_dt_s = 0.0;
  };
  Snapshot snapshot() const;
  void restore(const Snapshot &snapshot);

private:
  RigParameters p_;
  RigCoordinates q_;
  RigVelocities u_;
  RigDrives drives_;
  RigReactions reactions_;
  double time_s_ = 0.0;
  long long steps_ = 0;
  // Time is t0 + (n - n0) dt over a run of steps of equal dt, not a sum of dt's (which drifts:
  // 4000 steps of 5e-4 s summed fall short of 2.0 s).
  double segment_time0_s_ = 0.0;
  long long segment_step0_ = 0;
  double segment_dt_s_ = 0.0;
};

} // namespace wheelsim::rig
