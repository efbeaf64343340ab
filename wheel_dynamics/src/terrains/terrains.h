// Private to wheelsim_rig: the entries of the terrain registry, one file each in this folder;
// terrain_registry.cpp lists them.
#pragma once

#include "wheelsim/rig/terrain_registry.h"

namespace wheelsim::rig::terrains {

TerrainKind flat_terrain(); ///< flat_terrain.cpp
TerrainKind dem_terrain();  ///< dem_terrain.cpp
TerrainKind scm_terrain();  ///< scm_terrain.cpp

} // namespace wheelsim::rig::terrains
