// The terrain types of the rig, each declared once (one file each under src/terrains/): its name,
// its [terrain] keys with units, defaults and ranges, its parser, its factory (in-process
// terrains) and what it writes to the run file's /parameters. wheel-rig and the config parser
// choose the terrain through this table; docs/extending.md, "Adding a terrain".
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "wheelsim/rig/config_schema.h"
#include "wheelsim/rig/rig_config.h"
#include "wheelsim/rig/terrain.h"
#include "wheelsim/rig/time_step.h"

namespace wheelsim::rig {

struct WheelProperties;
class RunHealth;
namespace detail {
class Table;
}

/// Where a terrain writes its /parameters entries (wheel-rig: the run file).
class ParameterSink {
public:
  virtual ~ParameterSink() = default;
  virtual void number(const std::string &name, double value, const std::string &unit) = 0;
  virtual void text(const std::string &name, const std::string &value) = 0;
  /// A long text (a file's contents), stored as such.
  virtual void long_text(const std::string &name, const std::string &text) = 0;
};

struct TerrainKind {
  const char *name; ///< terrain.type
  TerrainType type;
  const char *summary; ///< one line for --list-keys and messages
  /// Its [terrain] keys beyond the common `type` and `surface_height`.
  std::vector<ConfigKey> keys;
  /// Reads its keys into c.terrain (other types' keys are rejected before); relative paths
  /// resolve against `base_dir`. Throws RigConfigError naming the key.
  void (*parse)(const detail::Table &t, const std::string &base_dir, RigConfig &c);
  /// The in-process terrain (throws RigConfigError naming the key); nullptr for a remote terrain
  /// (dem: LIGGGHTS over the coupler, run by wheel-rig's coupling loop).
  std::unique_ptr<Terrain> (*make)(const RigConfig &c, const WheelProperties &wheel);
  /// Called once after `make`: writes the terrain's /parameters entries and gives the run's
  /// health checks the terrain's scales. nullptr: nothing to write.
  void (*start)(const RigConfig &c, const Terrain &terrain, ParameterSink &out, RunHealth &health);
  /// Its contact as a spring-damper whose stiffness the config fixes, for the time-step bound
  /// (time_step.h; wheel-rig --check). nullptr where the config does not fix it (the SCM contact
  /// stiffens with its area: the run health checks it at every step; DEM: LIGGGHTS').
  OscillatorMode (*contact_mode)(const RigConfig &c, const Rig &rig);
};

/// Every terrain type, in the order of the docs.
const std::vector<TerrainKind> &terrain_kinds();
/// The entry of `type`.
const TerrainKind &terrain_kind(TerrainType type);
/// Their names ("flat", "dem", "scm").
std::vector<std::string> terrain_names();

/// The [terrain] keys every type has (type, surface_height).
std::vector<ConfigKey> common_terrain_keys();

/// Parses [terrain]: the type through the registry, then that type's keys. Keys of other types
/// are rejected ("terrain.soil is not used with terrain.type = \"dem\"").
void parse_terrain_table(const detail::Table &t, const std::string &base_dir, RigConfig &c);

} // namespace wheelsim::rig
