// Project Chrono interoperability: SCM soil parameters in Chrono's JSON files, read and written
// with Chrono's key names and units (docs/chrono-interop.md). Chrono keeps SCM soils in two JSON
// layouts, both read here (the layout is recognised from the keys) and both written:
//
//  - terrain_node: the co-simulation terrain specification of Chrono::Vehicle's SCM terrain node
//    (ChVehicleCosimTerrainNodeSCM; sample data/vehicle/cosim/terrain/scm.json): "Type": "SCM",
//    "Patch dimensions", "Grid spacing", "Soil parameters" { "Bekker Kphi", "Bekker Kc",
//    "Bekker n exponent", "Mohr cohesive limit", "Mohr friction limit",
//    "Janosi shear coefficient", "Elastic stiffness", "Damping" }, "Simulation settings".
//  - soil_parameters: Chrono::Vehicle's SCM soil-parameter file (samples
//    data/vehicle/terrain/scm_soil_parameters/*.json): "Name", "Type": "Terrain Properties",
//    "Template": "SCM Soil Parameters", "Soil Parameters" { "Bekker Kphi", "Bekker Kc",
//    "Bekker n", "Mohr Cohesion", "Mohr Friction", "Janosi Shear", "Elastic K", "Dampening R" }.
//
// Units are Chrono's, i.e. SI as in SCMTerrain::SetSoilParameters, with the friction angle in
// degrees; they equal our soil files' units (inputs/scm_soils/*.toml), so every number maps
// unchanged and only the friction angle is converted for SoilParameters (radians).
#pragma once

#include "wheelsim/scm/soil.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace wheelsim::scm {

/// A Chrono JSON file that cannot be read or is invalid; what() is "<file>[:<line>]: <message>".
class ChronoSoilError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// The two JSON layouts of Chrono that carry SCM soil parameters (see the file comment).
enum class ChronoLayout { terrain_node, soil_parameters };

/// "terrain-node" or "soil-parameters" (the names scm-soil's --format takes).
const char *chrono_layout_name(ChronoLayout layout);

/// The layout named `name` ("terrain-node", "soil-parameters"); throws std::invalid_argument.
ChronoLayout chrono_layout_from_name(const std::string &name);

/// SCM soil values as Chrono's JSON holds them (Chrono's SetSoilParameters arguments).
struct ChronoSoil {
  std::string name;           ///< "Name" (optional in the terrain-node layout)
  double Bekker_Kphi = 0.0;   ///< frictional modulus [N/m^(n+2)] (Pa/m^n)
  double Bekker_Kc = 0.0;     ///< cohesive modulus [N/m^(n+1)] (Pa/m^(n-1))
  double Bekker_n = 1.0;      ///< sinkage exponent [-]
  double Mohr_cohesion = 0.0; ///< cohesion [Pa]
  double Mohr_friction = 0.0; ///< internal friction angle [deg] (Chrono's unit)
  double Janosi_shear = 0.01; ///< Janosi–Hanamoto shear deformation modulus [m]
  double elastic_K = 2e8;     ///< elastic unloading stiffness [Pa/m]
  double damping_R = 3e4;     ///< normal damping [Pa s/m]
};

/// What a terrain-node file carries besides the soil; written on export, ignored on import (the
/// rig config's [terrain] sets our grid). Defaults: Chrono's sample
/// data/vehicle/cosim/terrain/scm.json.
struct ChronoTerrainNodeSettings {
  double patch_length_m = 4.0;           ///< "Patch dimensions" "Length" [m]
  double patch_width_m = 1.0;            ///< "Patch dimensions" "Width" [m]
  double grid_spacing_m = 0.05;          ///< "Grid spacing" [m]
  double proxy_contact_radius_m = 0.002; ///< "Simulation settings" "Proxy contact radius" [m]
  bool fix_proxies = true;               ///< "Simulation settings" "Fix proxies"
};

/// One soil key of Chrono's JSON: its name in each layout, unit, range and meaning.
struct ChronoSoilKey {
  const char *terrain_node_name;    ///< e.g. "Mohr friction limit"
  const char *soil_parameters_name; ///< e.g. "Mohr Friction"
  const char *unit;                 ///< e.g. "deg" ("" for dimensionless)
  const char *range;                ///< e.g. "in [0, 90)"
  const char *what;                 ///< e.g. "internal friction angle"
  bool (*in_range)(double);         ///< the check `range` describes
  double ChronoSoil::*field;
  const char *soil_file_key; ///< the same value in a soil file, e.g. "mohr_coulomb.friction_angle"
};

/// The eight soil keys in Chrono's SetSoilParameters order (docs/chrono-interop.md lists them).
const std::vector<ChronoSoilKey> &chrono_soil_keys();

/// Parses Chrono JSON text (either layout; comments allowed). Every soil key is required and
/// range-checked; unknown keys are errors naming the key, with a suggestion. `source_name` is
/// used in messages. `layout` (if given) receives the layout found. Throws ChronoSoilError.
ChronoSoil parse_chrono_soil(const std::string &text, const std::string &source_name,
                             ChronoLayout *layout = nullptr);

/// Reads a Chrono JSON file (see parse_chrono_soil). Throws ChronoSoilError.
ChronoSoil load_chrono_soil(const std::string &path, ChronoLayout *layout = nullptr);

/// The JSON text of `soil` in `layout` (numbers with 15 significant digits, which every decimal
/// of up to 15 digits survives unchanged). `settings` are used by the terrain-node layout only.
std::string write_chrono_soil(const ChronoSoil &soil, ChronoLayout layout,
                              const ChronoTerrainNodeSettings &settings = {});

/// Chrono's values as our SoilParameters (friction angle degrees -> radians).
SoilParameters to_soil_parameters(const ChronoSoil &soil);

/// Our SoilParameters as Chrono's values (friction angle radians -> degrees).
ChronoSoil to_chrono_soil(const SoilParameters &soil);

} // namespace wheelsim::scm
