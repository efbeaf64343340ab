// parse_rig_config: the document's tables and keys checked against the schema, then one parser
// per table (rig_tables.cpp; [carriage] slip_modes.cpp; [terrain] terrain_registry.cpp).
#include "wheelsim/rig/rig_config.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "config_table.h"
#include "rig_tables.h"
#include "wheelsim/rig/config_schema.h"
#include "wheelsim/rig/slip_modes.h"
#include "wheelsim/rig/terrain_registry.h"

namespace wheelsim::rig {
namespace {

using detail::closest;
using detail::Parser;
using detail::Table;

void check_known_keys(const Parser &p, const toml::table &doc) {
  const std::vector<std::string> tables = rig_config_tables();
  for (const auto &[k, node] : doc) {
    const std::string key(k.str());
    if (std::find(tables.begin(), tables.end(), key) == tables.end()) {
      std::string msg = "unknown " + std::string(node.is_table() ? "table [" + key + "]"
                                                                 : "top-level key '" + key + "'");
      const std::string c = closest(key, tables);
      if (!c.empty())
        msg += "; did you mean [" + c + "]?";
      else
        msg += "; the tables are [wheel], [rig], [motor], [carriage], [run], [terrain], [output]";
      p.fail(&node, msg);
    }
    if (!node.is_table())
      p.fail(&node, "'" + key + "' must be a table: write [" + key + "] and its keys below it");
    for (const auto &[sk, snode] : *node.as_table()) {
      const std::string sub(sk.str());
      const std::vector<std::string> known = rig_config_table_keys(key);
      if (std::find(known.begin(), known.end(), sub) != known.end())
        continue;
      std::string msg = "unknown key '" + key + "." + sub + "'";
      std::string c = closest(sub, known);
      if (!c.empty()) {
        msg += "; did you mean '" + key + "." + c + "'?";
      } else {
        // Maybe it belongs to another table.
        for (const std::string &other : tables)
          if (const auto okeys = rig_config_table_keys(other);
              other != key && std::find(okeys.begin(), okeys.end(), sub) != okeys.end()) {
            c = other;
            break;
          }
        if (!c.empty()) {
          msg += "; '" + sub + "' belongs in [" + c + "]";
        } else {
          msg += "; the keys of [" + key + "] are";
          for (std::size_t i = 0; i < known.size(); ++i)
            msg += (i ? ", " : " ") + known[i];
        }
      }
      p.fail(&snode, msg);
    }
  }
}

} // namespace

std::vector<std::string> rig_config_keys() { return rig_config_table_keys(""); }

const char *to_string(CarriageMode m) { return slip_mode(m).name; }

const char *to_string(TerrainType t) { return terrain_kind(t).name; }

RigConfig parse_rig_config(const std::string &text, const std::string &source_name,
                           const std::string &base_dir) {
  const Parser p(source_name);
  toml::table doc;
  try {
    doc = toml::parse(text, source_name);
  } catch (const toml::parse_error &e) {
    throw RigConfigError(config::syntax_error(e, source_name));
  }
  check_known_keys(p, doc);

  auto table = [&](const char *name, bool required) {
    const toml::table *t = doc.get_as<toml::table>(name);
    if (!t && required)
      p.fail(nullptr, std::string("missing table [") + name + "] (see docs/rig-config.md)");
    return Table(p, t, name);
  };

  RigConfig c;
  c.source = source_name;
  c.text = text;

  const toml::table *carriage = doc.get_as<toml::table>("carriage");
  const toml::node *mode = carriage ? carriage->get("mode") : nullptr;
  detail::parse_wheel(table("wheel", true), base_dir, c);
  detail::parse_rig(table("rig", true), c);
  detail::parse_motor(table("motor", true), mode ? mode->value_or(std::string()) : "", c);
  parse_carriage_table(table("carriage", true), c);
  detail::parse_run(table("run", true), c);
  parse_terrain_table(table("terrain", true), base_dir, c);
  if (c.run.dt_s == 0.0 && c.terrain.type != TerrainType::dem) {
    const Table t = table("run", true);
    t.required(t.positive("dt", "s"), "dt", "time step in s (only a DEM run may leave it out)");
  }
  detail::parse_output(table("output", false), c);
  return c;
}

RigConfig load_rig_config(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw RigConfigError(path + ": cannot open the rig config file (check the path given to "
                                "--config)");
  std::ostringstream ss;
  ss << in.rdbuf();
  const auto dir = std::filesystem::path(path).parent_path().string();
  return parse_rig_config(ss.str(), path, dir.empty() ? "." : dir);
}

} // namespace wheelsim::rig
