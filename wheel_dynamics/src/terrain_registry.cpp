// The terrain registry: the list of terrain types (one file each in terrains/, declared and
// listed here) and the [terrain] table's parser, which chooses the type through it.
#include "wheelsim/rig/terrain_registry.h"

#include "config_table.h"

namespace wheelsim::rig {

namespace terrains {
TerrainKind flat_terrain(); ///< terrains/flat_terrain.cpp
TerrainKind dem_terrain();  ///< terrains/dem_terrain.cpp
TerrainKind scm_terrain();  ///< terrains/scm_terrain.cpp
} // namespace terrains

using detail::Table;

const std::vector<TerrainKind> &terrain_kinds() {
  static const std::vector<TerrainKind> kinds = {terrains::flat_terrain(), terrains::dem_terrain(),
                                                 terrains::scm_terrain()};
  return kinds;
}

const TerrainKind &terrain_kind(TerrainType type) {
  for (const TerrainKind &k : terrain_kinds())
    if (k.type == type)
      return k;
  throw std::logic_error("terrain_kind: a TerrainType without an entry in terrain_kinds()");
}

std::vector<std::string> terrain_names() {
  std::vector<std::string> names;
  for (const TerrainKind &k : terrain_kinds())
    names.emplace_back(k.name);
  return names;
}

std::vector<ConfigKey> common_terrain_keys() {
  std::string types;
  for (const std::string &n : terrain_names())
    types += (types.empty() ? "one of \"" : ", \"") + n + "\"";
  return {{"terrain", "type", "string", "", "", types},
          {"terrain", "surface_height", "number", "m",
           detail::fmt(TerrainConfig{}.surface_height_m),
           "undisturbed soil surface level (sinkage reference)"}};
}

void parse_terrain_table(const Table &t, const std::string &base_dir, RigConfig &c) {
  const std::string name = t.choice("type", terrain_names(), std::nullopt);
  const TerrainKind *kind = nullptr;
  for (const TerrainKind &k : terrain_kinds())
    if (name == k.name)
      kind = &k;
  c.terrain.type = kind->type;
  c.terrain.surface_height_m = t.number("surface_height", "m").value_or(c.terrain.surface_height_m);
  for (const TerrainKind &other : terrain_kinds()) // keys of the other types
    for (const ConfigKey &k : other.keys)
      if (std::none_of(kind->keys.begin(), kind->keys.end(),
                       [&](const ConfigKey &own) { return own.key == k.key; }))
        t.only_with({k.key}, "type", name);
  kind->parse(t, base_dir, c);
}

} // namespace wheelsim::rig
