// The rig configuration (TOML, DESIGN.md §4.2): every key, its unit, default and range are in
// docs/rig-config.md and in the schema (config_schema.h, `wheel-rig --list-keys`); the terrain
// types and carriage modes are declared in terrain_registry.h and slip_modes.h. Parsing rejects
// unknown tables and keys (with a "did you mean" suggestion), values of the wrong type,
// out-of-range values and keys that do not belong to the chosen mode, with a message that names the
// key, the expected range with its unit, and the value found.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "wheelsim/rig/flat_ground.h"
#include "wheelsim/scm/scm_terrain.h"

namespace wheelsim::rig {

/// Any configuration error; what() is "<source>:<line>: <message>" (line when known).
class RigConfigError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct WheelConfig {
  std::string mesh;                         ///< mesh file (OBJ/STL/PLY), resolved path; "" = none
  double mesh_scale = 1.0;                  ///< mesh units -> m
  std::optional<double> mass_kg;            ///< with inertia_kg_m2 (or density_kg_m3 with a mesh)
  std::optional<double> inertia_kg_m2;      ///< about the axle (+y)
  std::optional<double> density_kg_m3;      ///< mass and inertia from the mesh and this density
  std::optional<double> effective_radius_m; ///< R_eff; default: outer radius of the mesh
};

struct RigSection {
  double spindle_mass_kg = 100.0;
  std::optional<double> suspended_mass_kg; ///< exactly one of suspended_mass / vertical_load
  std::optional<double> vertical_load_N;
  double carriage_mass_kg = 0.0;
  double spring_k_N_m = 12000.0;
  double spring_c_N_s_m = 800.0;
  double gravity_m_s2 = 9.81;
};

enum class MotorMode { omega, torque };
struct MotorConfig {
  MotorMode mode = MotorMode::omega;
  double omega_rad_s = 0.0; ///< target ω (mode omega)
  double torque_Nm = 0.0;   ///< target torque (mode torque)
  double ramp_time_s = 1.0; ///< linear ramp 0 -> target
};

enum class CarriageMode { imposed_slip, imposed_speed, constant_load, ramped_load };
struct CarriageConfig {
  CarriageMode mode = CarriageMode::imposed_slip;
  double slip = 0.0;         ///< imposed_slip [-]
  double speed_m_s = 0.0;    ///< imposed_speed [m/s]
  double load_N = 0.0;       ///< constant_load: drawbar load [N]
  double load_start_N = 0.0; ///< ramped_load [N]
  double load_end_N = 0.0;   ///< ramped_load [N]
  double ramp_time_s = 0.0;  ///< ramped_load: duration of load_start -> load_end [s]
};

struct RunConfig {
  double dt_s = 0.0;       ///< time step [s]; 0: not set (DEM only: the bed's, via wheel-rig --dt)
  double duration_s = 0.0; ///< length of the test phase (after the ω ramp)
  double release_gap_m = 0.002;    ///< initial clearance of the lowest rim point
  double release_speed_m_s = 0.01; ///< lowering speed of the held spindle
  double release_timeout_s = 10.0; ///< the contact must carry the load within this time
  double settle_velocity_m_s = 1e-3;
  double settle_window_s = 0.05;
  double settle_min_time_s = 0.1;
  double settle_max_time_s = 5.0;
};

enum class TerrainType { flat, dem, scm };

/// The SCM terrain's settings (terrain.type = "scm"); units in the names. docs/scm.md.
struct ScmTerrainConfig {
  std::string soil;                    ///< soil file (inputs/scm_soils/*.toml), resolved path
  double grid_spacing_m = 0.0;         ///< Δ [m]
  std::optional<double> grid_length_m; ///< domain along x from -(rim radius) [m]; unset: unbounded
  std::optional<double>
      grid_width_m;             ///< domain along y, centred on the wheel [m]; unset: unbounded
  bool vertical_normal = false; ///< normal_direction = "vertical" (Chrono) vs "surface"
  /// shear_surface = "lug_tips": the soil is sheared at the circle of radius R_eff (the lug tips),
  /// not at the wheel's surface ("wheel", the default, as Chrono); docs/scm.md "Shear surface".
  bool shear_at_lug_tips = false;
  std::optional<double> elastic_stiffness_Pa_m; ///< overrides the soil file's Ke [Pa/m]
  std::optional<double> damping_Pa_s_m;         ///< overrides the soil file's damping R [Pa s/m]
  // The bulldozing defaults are the SCM module's (scm::BulldozingSettings, scm_terrain.h).
  bool bulldozing = scm::BulldozingSettings{}.enabled;
  double erosion_angle_deg = scm::BulldozingSettings{}.erosion_angle_deg; ///< angle of repose [deg]
  double flow_factor = scm::BulldozingSettings{}.flow_factor;             ///< [-]
  long long erosion_iterations = scm::BulldozingSettings{}.erosion_iterations;
  long long erosion_rings = scm::BulldozingSettings{}.erosion_rings;
  std::vector<double> snapshot_times_s; ///< simulated times [s] of terrain snapshots
  double snapshot_interval_s = 0.0;     ///< also one every this many s [s]; 0 = off
  std::vector<std::string> snapshot_fields = {"height", "sinkage", "pressure", "shear_stress"};
};
struct TerrainConfig {
  TerrainType type = TerrainType::flat;
  double surface_height_m = 0.0;
  // dem
  std::string endpoint;
  double timeout_s = 60.0;
  // scm (docs/scm.md): soil file, grid, model settings, snapshots
  ScmTerrainConfig scm;
  // flat (radius and surface height are filled in from the wheel and surface_height)
  FlatGroundParameters flat;
};

struct OutputConfig {
  std::string file = "run.h5";
  long long every = 1;               ///< record every N-th step
  long long flush_interval = 1000;   ///< recorded steps buffered in memory (hdf5-layout.md)
  double progress_interval_s = 10.0; ///< wall-clock seconds between progress lines; 0 = off
};

struct RigConfig {
  std::string source; ///< file name or source name given to the parser
  std::string text;   ///< the TOML text as read (for /parameters of the run file)
  WheelConfig wheel;
  RigSection rig;
  MotorConfig motor;
  CarriageConfig carriage;
  RunConfig run;
  TerrainConfig terrain;
  OutputConfig output;
};

/// Parses and validates `toml_text`; `source_name` prefixes messages. Relative paths (wheel.mesh,
/// terrain.soil) are resolved against `base_dir` (unchanged if empty). Throws RigConfigError.
RigConfig parse_rig_config(const std::string &toml_text, const std::string &source_name,
                           const std::string &base_dir = "");

/// Reads `path` and parses it; relative paths resolve against the file's directory.
RigConfig load_rig_config(const std::string &path);

/// Every key the parser accepts, as "table.key" (the documentation lists the same; the full
/// schema with units, defaults and ranges: config_schema.h).
std::vector<std::string> rig_config_keys();

const char *to_string(CarriageMode mode);
const char *to_string(TerrainType type);

} // namespace wheelsim::rig
