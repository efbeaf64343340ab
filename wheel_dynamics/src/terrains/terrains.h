// Private to wheelsim_rig: what the entries of the terrain registry share. Each entry is one file
// in this folder (built from there: wheel_dynamics/CMakeLists.txt takes every .cpp here), defining
// `TerrainKind <name>_terrain()`; terrain_registry.cpp declares and lists them. An entry keeps its
// helpers in namespace `<name>_entry`, not an anonymous one: the entries share helper names (keys,
// parse, make) and a unity build (the sanitizer tier's) compiles them in one translation unit.
#pragma once

#include "wheelsim/rig/config_schema.h"
#include "wheelsim/rig/terrain_registry.h"

#include <utility>

namespace wheelsim::rig::terrains {

/// A [terrain] key that applies when terrain.type = `type` (the entries' key lists use it).
inline ConfigKey terrain_key(const char *type, ConfigKey key) {
  key.table = "terrain";
  return key_for("terrain.type", type, std::move(key));
}

} // namespace wheelsim::rig::terrains
