// The schema assembled from its declarations, and its JSON form (wheel-rig --list-keys).
#include "wheelsim/rig/config_schema.h"

#include "wheelsim/config_messages.h"

#include "rig_tables.h"
#include "wheelsim/rig/slip_modes.h"
#include "wheelsim/rig/terrain_registry.h"

#include <algorithm>

namespace wheelsim::rig {
namespace {

void append(std::vector<ConfigKey> &out, const std::vector<ConfigKey> &more) {
  out.insert(out.end(), more.begin(), more.end());
}

std::string json_strings(const std::vector<std::string> &v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i)
    out += (i ? ", " : "") + config::json_string(v[i]);
  return out + "]";
}

} // namespace

ConfigKey key_for(const std::string &when_key, const std::string &value, ConfigKey key) {
  key.when_key = when_key;
  key.when_values = {value};
  return key;
}

const std::vector<ConfigKey> &rig_config_schema() {
  static const std::vector<ConfigKey> schema = [] {
    std::vector<ConfigKey> s;
    append(s, detail::wheel_keys());
    append(s, detail::rig_keys());
    append(s, detail::motor_keys());
    append(s,
           {{"carriage", "mode", "string", "", "", "one of " + json_strings(slip_mode_names())}});
    for (const SlipMode &m : slip_modes())
      append(s, m.keys);
    append(s, detail::run_keys());
    append(s, common_terrain_keys());
    for (const TerrainKind &k : terrain_kinds())
      append(s, k.keys);
    append(s, detail::output_keys());
    return s;
  }();
  return schema;
}

std::vector<std::string> rig_config_tables() {
  std::vector<std::string> tables;
  for (const ConfigKey &k : rig_config_schema())
    if (std::find(tables.begin(), tables.end(), k.table) == tables.end())
      tables.push_back(k.table);
  return tables;
}

std::vector<std::string> rig_config_table_keys(const std::string &table) {
  std::vector<std::string> keys;
  for (const ConfigKey &k : rig_config_schema()) {
    if (!table.empty() && k.table != table)
      continue;
    const std::string name = table.empty() ? k.table + "." + k.key : k.key;
    if (std::find(keys.begin(), keys.end(), name) == keys.end())
      keys.push_back(name);
  }
  return keys;
}

std::string rig_config_schema_json() {
  std::string out = "{\n  \"program\": \"wheel-rig\",\n  \"schema\": \"rig-config\",\n";
  out += "  \"tables\": " + json_strings(rig_config_tables()) + ",\n";
  out += "  \"terrain_types\": {";
  for (std::size_t i = 0; i < terrain_kinds().size(); ++i) {
    const TerrainKind &k = terrain_kinds()[i];
    out += (i ? ", " : "") + config::json_string(k.name) +
           ": {\"summary\": " + config::json_string(k.summary) +
           ", \"in_process\": " + (k.make ? "true" : "false") + "}";
  }
  out += "},\n  \"carriage_modes\": {";
  for (std::size_t i = 0; i < slip_modes().size(); ++i) {
    const SlipMode &m = slip_modes()[i];
    out += (i ? ", " : "") + config::json_string(m.name) +
           ": {\"summary\": " + config::json_string(m.summary) + "}";
  }
  out += "},\n  \"keys\": [\n";
  const auto &schema = rig_config_schema();
  for (std::size_t i = 0; i < schema.size(); ++i) {
    const ConfigKey &k = schema[i];
    out += "    {\"name\": " + config::json_string(k.table + "." + k.key) +
           ", \"table\": " + config::json_string(k.table) +
           ", \"key\": " + config::json_string(k.key) +
           ", \"type\": " + config::json_string(k.type) +
           ", \"unit\": " + config::json_string(k.unit) + ", \"default\": " +
           (k.default_value.empty() ? "null" : config::json_string(k.default_value)) +
           ", \"range\": " + config::json_string(k.range) + ", \"when\": ";
    out += k.when_key.empty()
               ? "null"
               : "{" + config::json_string(k.when_key) + ": " + json_strings(k.when_values) + "}";
    out += i + 1 < schema.size() ? "},\n" : "}\n";
  }
  return out + "  ]\n}\n";
}

} // namespace wheelsim::rig
