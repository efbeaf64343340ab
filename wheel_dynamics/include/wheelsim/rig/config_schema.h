// The rig config's schema: every key of every table with its type, unit, default, range and the
// terrain type or carriage mode it applies to. Assembled from the places that declare the keys
// (rig_tables.cpp for [wheel] [rig] [motor] [run] [output], slip_modes.cpp for [carriage],
// terrains/*.cpp for [terrain]); the parser checks keys against it and `wheel-rig --list-keys`
// prints it as JSON (docs/rig-config.md, "The schema").
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace wheelsim::rig {

/// One key of one table. A key that means different things for different terrain types (e.g.
/// terrain.damping: N s/m for flat, Pa s/m for scm) appears once per meaning.
struct ConfigKey {
  ConfigKey(std::string table_, std::string key_, std::string type_, std::string unit_,
            std::string default_value_, std::string range_)
      : table(std::move(table_)), key(std::move(key_)), type(std::move(type_)),
        unit(std::move(unit_)), default_value(std::move(default_value_)), range(std::move(range_)) {
  }
  std::string table;         ///< "wheel", "rig", ..., "terrain"
  std::string key;           ///< "spring_k"
  std::string type;          ///< number, integer, string, path, boolean, array of numbers, ...
  std::string unit;          ///< SI unit; "" for a pure number or a name
  std::string default_value; ///< TOML literal, or a description ("soil file"); "" = none
  std::string range;         ///< "> 0", "in [-1, 1]", "one of ..." and conditions
  std::string when_key;      ///< "" (always) or the selecting key: "terrain.type", "carriage.mode"
  std::vector<std::string> when_values; ///< the values of when_key it applies to
};

/// Shorthand for the declarations: a key that applies to one terrain type or carriage mode.
ConfigKey key_for(const std::string &when_key, const std::string &value, ConfigKey key);

/// Every key, table by table in the order of docs/rig-config.md.
const std::vector<ConfigKey> &rig_config_schema();

/// The tables, in order.
std::vector<std::string> rig_config_tables();

/// The distinct key names of `table` ("" = of all tables, as "table.key").
std::vector<std::string> rig_config_table_keys(const std::string &table);

/// The schema as one JSON document (what `wheel-rig --list-keys` prints): the tables, the terrain
/// types, the carriage modes and every key with type, unit, default, range and "when".
std::string rig_config_schema_json();

} // namespace wheelsim::rig
