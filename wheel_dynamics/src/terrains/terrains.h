// Private to wheelsim_rig: the entries of the terrain registry, one file each in this folder;
// terrain_registry.cpp lists them.
#pragma once

#include "wheelsim/rig/config_schema.h"
#include "wheelsim/rig/terrain_registry.h"

#include <utility>

namespace wheelsim::rig::terrains {

TerrainKind flat_terrain(); ///< flat_terrain.cpp
TerrainKind dem_terrain();  ///< dem_terrain.cpp
TerrainKind scm_terrain();  ///< scm_terrain.cpp

/// A [terrain] key that applies when terrain.type = `type` (the entries' key lists use it).
inline ConfigKey terrain_key(const char *type, ConfigKey key) {
  key.table = "terrain";
  return key_for("terrain.type", type, std::move(key));
}

} // namespace wheelsim::rig::terrains
