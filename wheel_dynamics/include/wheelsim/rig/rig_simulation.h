// A rig run: the rig model, its phases (release, settle, ramp-up, test), the motor and the
// carriage (slip) control, and the per-step outputs of TERRAMECHANICS.md §5. Easy to drive from a
// main loop with any terrain:
//
//   RigSimulation sim(config);                 // or (config, wheel properties)
//   while (!sim.finished()) {
//     const WheelWrench w = terrain.contact(sim.wheel_state(), sim.time_s());  // or remote
//     const RigOutputs &out = sim.advance(w);  // outputs of step n; state is now n+1
//     ...record out...
//   }
//
// Phases (docs/rig-config.md "Phases"):
//   release: the spindle is held and lowered at run.release_speed from run.release_gap above the
//            surface, ω = 0, carriage at rest, until the holder's support force drops to <= 0
//            (the contact carries the whole load); then the spindle is let go;
//   settle:  spindle free, ω = 0, carriage at rest, until |v_z| < run.settle_velocity for
//            run.settle_window (and at least run.settle_min_time), or run.settle_max_time
//            (then a warning is recorded); the static sinkage is recorded;
//   ramp:    ω (or the motor torque) ramps linearly to its target over motor.ramp_time, the
//            carriage follows its mode (speeds and the initial load scaled by the same ramp);
//   test:    run.duration at the target; constant_load / ramped_load apply their load law.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "wheelsim/rig/checkpoint.h"
#include "wheelsim/rig/rig_config.h"
#include "wheelsim/rig/rig_model.h"

namespace wheelsim::geometry {
struct TriangleMesh;
}

namespace wheelsim::rig {

/// The wheel's mass properties and radii as used by the run.
struct WheelProperties {
  double mass_kg = 0.0;
  double axle_inertia_kg_m2 = 0.0; ///< about +y through the centre
  double effective_radius_m = 0.0; ///< R_eff: slip, traction force, flat-ground contact
  double rim_radius_m = 0.0;       ///< outer radius: lowest rim point for sinkage
  double width_m = 0.0;            ///< the mesh's extent along the axle (y); 0 without a mesh
  std::string source;              ///< "config" or "mesh <path> (density ...)"
  /// The lugs, from the `<mesh stem>.props.toml` that wheel-mesh writes beside its meshes
  /// ([wheel] lug_count, lug_width_m, lug_height_m); 0 without that file or for a smooth wheel.
  int lug_count = 0;
  double lug_width_m = 0.0;  ///< lug thickness, across the lug [m]
  double lug_height_m = 0.0; ///< [m]
  std::string lug_source;    ///< the props file read, empty if none
  /// The wheel surface as loaded from wheel.mesh (wheel frame, scaled by wheel.mesh_scale), kept
  /// for the terrains that need it (SCM) so that a run loads the mesh once; null without a mesh.
  std::shared_ptr<const geometry::TriangleMesh> mesh;
};

/// From the config: mass/inertia given, or from the mesh and density (wheelsim_geometry). With a
/// mesh, rim_radius is the mesh's largest distance from the axle and R_eff defaults to it; the lugs
/// come from the mesh's props file when there is one (scaled by wheel.mesh_scale). Throws
/// RigConfigError (mesh problems included, naming the file) and if the mesh's centroid is off
/// the axle by more than 1 mm (the model assumes a balanced wheel).
WheelProperties resolve_wheel_properties(const WheelConfig &wheel);

enum class Phase { release, settle, ramp, test, finished };
const char *to_string(Phase phase);

/// Everything a step produces. Units in the names; world frame W; NaN where undefined (slip
/// when ω R_eff = 0, efficiency when T ω = 0).
struct RigOutputs {
  long long step = 0;
  double time_s = 0.0;
  Phase phase = Phase::release;
  WheelPose wheel;                      ///< pose and twist at this step (state n)
  WheelWrench contact;                  ///< contact wrench at state n (about the centre, W)
  double carriage_x_m = 0.0;            ///< carriage position [m]
  double forward_velocity_m_s = 0.0;    ///< carriage = wheel-centre speed along x, v [m/s]
  double omega_rad_s = 0.0;             ///< wheel angular speed about +y, ω [rad/s]
  double theta_rad = 0.0;               ///< wheel rotation [rad]
  double wheel_centre_z_m = 0.0;        ///< wheel-centre height [m]
  double vertical_velocity_m_s = 0.0;   ///< wheel-centre vertical speed [m/s]
  double suspended_mass_z_m = 0.0;      ///< suspended-mass coordinate [m]
  double spring_force_N = 0.0;          ///< force of the suspension on the suspended mass, +z [N]
  double slip = 0.0;                    ///< s = 1 - v/(ω R_eff) [-]
  double slip_velocity_m_s = 0.0;       ///< v_j = ω R_eff - v [m/s]
  double sinkage_m = 0.0;               ///< surface - (z_c - rim radius) [m], > 0 = below surface
  double drawbar_pull_N = 0.0;          ///< DP = -(carriage force on the rig along x) [N]
  double drawbar_load_command_N = 0.0;  ///< load commanded (constant/ramped modes), else 0 [N]
  double driving_torque_Nm = 0.0;       ///< motor torque about the axle (+y), T [N m]
  double traction_force_N = 0.0;        ///< F_T = T / R_eff [N]
  double tractive_efficiency = 0.0;     ///< η = DP v / (T ω) [-]
  double vertical_load_N = 0.0;         ///< weight of wheel + spindle + suspended mass [N]
  double spindle_support_force_N = 0.0; ///< holder force on the spindle, +z (release) [N]
  double lateral_force_N = 0.0;         ///< contact force along y the rig holds [N]
  double roll_torque_Nm = 0.0;          ///< contact torque about x (centre) the rig holds [N m]
  double yaw_torque_Nm = 0.0;           ///< contact torque about z (centre) the rig holds [N m]
};

class RigSimulation {
public:
  /// Resolves the wheel (may load the mesh) and places the wheel at the release height.
  explicit RigSimulation(const RigConfig &config);
  RigSimulation(const RigConfig &config, const WheelProperties &wheel);

  /// State n: what the terrain needs.
  WheelPose wheel_state() const { return rig_.wheel_state(); }
  double time_s() const { return rig_.time_s(); }
  long long step() const { return rig_.step_count(); }
  Phase phase() const { return phase_; }
  bool finished() const { return phase_ == Phase::finished; }

  /// Applies the phase and mode logic, records the outputs of step n (state n, the wrench at n,
  /// the drives' forces during n -> n+1) and advances the rig to n+1. Throws std::runtime_error
  /// if the release does not complete within run.release_timeout, std::logic_error if finished.
  const RigOutputs &advance(const WheelWrench &wrench_at_current_state);

  /// Runs to the end with an in-process terrain, calling `on_step` (if set) after each step.
  template <class OnStep> void run(Terrain &terrain, OnStep on_step) {
    while (!finished()) {
      const RigOutputs &o = advance(terrain.contact(wheel_state(), time_s()));
      on_step(o);
    }
  }

  const Rig &rig() const { return rig_; }
  const RigConfig &config() const { return config_; }
  const WheelProperties &wheel() const { return wheel_; }
  /// Warnings collected during the run (settle not converged, ...), one line each.
  const std::vector<std::string> &warnings() const { return warnings_; }
  /// Static sinkage [m] at the end of the settle phase (NaN before).
  double static_sinkage_m() const { return static_sinkage_m_; }
  /// Time [s] at which the test phase started (NaN before).
  double test_start_s() const { return test_start_s_; }

  /// Checkpoints (wheelsim/rig/checkpoint.h): the rig's state (Rig::Snapshot), the phase and its
  /// timers (phase start, settle detection, test start), the static sinkage, the last load
  /// command and the warnings, under keys "sim/...". restore_checkpoint() continues the run as
  /// if it had not stopped; it throws CheckpointError naming a missing key.
  void save_checkpoint(CheckpointData &data) const;
  void restore_checkpoint(const CheckpointData &data);

private:
  void configure_drives(double t_next);
  void enter(Phase phase);

  RigConfig config_;
  WheelProperties wheel_;
  Rig rig_;
  Phase phase_ = Phase::release;
  double phase_start_s_ = 0.0;
  double settle_quiet_since_s_ = -1.0;
  double static_sinkage_m_;
  double test_start_s_;
  double load_command_N_ = 0.0;
  std::vector<std::string> warnings_;
  RigOutputs out_;
};

/// The parameters of the rig model from a config and the resolved wheel (suspended mass sized
/// from rig.vertical_load if given). Throws RigConfigError if the load is too small.
RigParameters rig_parameters(const RigConfig &config, const WheelProperties &wheel);

/// The flat-ground terrain of a config with terrain.type = "flat" (radius = R_eff).
FlatGround make_flat_ground(const RigConfig &config, const WheelProperties &wheel);

} // namespace wheelsim::rig
