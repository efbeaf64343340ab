// The soil-file loader (docs/scm-soils.md). The error style follows the rig configuration
// (wheel_dynamics/src/rig_config.cpp): "<file>:<line>: <message>", unknown keys with a
// suggestion, range errors naming the key, the expected range with its unit and the value.
#include "wheelsim/scm/soil_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <utility>

#include <toml++/toml.h>

#include "number_text.h"
#include "wheelsim/config_messages.h"

namespace wheelsim::scm {
namespace {

using config::closest;
using config::fmt;
using config::type_name;

/// One value key: its table, name, unit (as written in messages) and what it is.
struct KeySpec {
  const char *table;
  const char *key;
  const char *unit;
  const char *what;
};

// ---- the schema (docs/scm-soils.md lists the same, in this order) ----
const std::vector<KeySpec> &value_keys() {
  static const std::vector<KeySpec> k = {
      {"bekker", "n", "", "sinkage exponent"},
      {"bekker", "kc", "N/m^(n+1)", "cohesive modulus"},
      {"bekker", "kphi", "N/m^(n+2)", "frictional modulus"},
      {"mohr_coulomb", "cohesion", "Pa", "cohesion"},
      {"mohr_coulomb", "friction_angle", "deg", "internal friction angle"},
      {"janosi", "shear_modulus", "m", "shear deformation modulus K"},
      {"scm", "elastic_stiffness", "Pa/m", "elastic unloading stiffness Ke"},
      {"scm", "damping", "Pa s/m", "normal damping"},
  };
  return k;
}
const std::vector<std::string> &value_tables() {
  static const std::vector<std::string> t = {"bekker", "mohr_coulomb", "janosi", "scm"};
  return t;
}
const std::vector<std::string> &top_level_names() {
  static const std::vector<std::string> t = {"name",   "description", "bekker", "mohr_coulomb",
                                             "janosi", "scm",         "source"};
  return t;
}
std::vector<std::string> keys_of(const std::string &table) {
  std::vector<std::string> out;
  for (const auto &k : value_keys())
    if (table == k.table)
      out.push_back(k.key);
  return out;
}

std::string join(const std::vector<std::string> &v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + v[i];
  return s;
}

class Parser {
public:
  explicit Parser(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const toml::node *where, const std::string &message) const {
    throw SoilFileError(config::located(source_, where, message));
  }

private:
  std::string source_;
};

/// "unknown key 'a.b'; did you mean 'a.c'?" (or the list of keys of the table).
std::string unknown_key_message(const std::string &prefix, const std::string &key,
                                const std::vector<std::string> &known) {
  std::string msg = "unknown key '" + prefix + key + "'";
  const std::string c = closest(key, known);
  if (!c.empty())
    return msg + "; did you mean '" + prefix + c + "'?";
  for (const auto &k : value_keys())
    if (key == k.key && prefix != std::string(k.table) + ".")
      return msg + "; '" + key + "' belongs in [" + k.table + "]";
  return msg + "; the keys here are " + join(known);
}

void check_known_keys(const Parser &p, const toml::table &doc) {
  for (const auto &[k, node] : doc) {
    const std::string key(k.str());
    const auto &names = top_level_names();
    if (std::find(names.begin(), names.end(), key) == names.end()) {
      std::string msg = "unknown " + std::string(node.is_table() ? "table [" + key + "]"
                                                                 : "top-level key '" + key + "'");
      std::string c = closest(key, names);
      if (!c.empty())
        msg += "; did you mean '" + c + "'?";
      else {
        for (const auto &vk : value_keys())
          if (key == vk.key) {
            c = vk.table;
            break;
          }
        if (!c.empty())
          msg += "; '" + key + "' belongs in [" + c + "]";
        else
          msg += "; a soil file has name, description and the tables [bekker], [mohr_coulomb], "
                 "[janosi], [scm], [source]";
      }
      p.fail(&node, msg);
    }
    if (key == "name" || key == "description") {
      if (!node.is_string())
        p.fail(&node, "'" + key + "' must be a string, got " + type_name(node));
      continue;
    }
    if (!node.is_table())
      p.fail(&node, "'" + key + "' must be a table: write [" + key + "] and its keys below it");
    if (key == "source") {
      // [source.<table>] with the value keys of <table>, each a string.
      for (const auto &[sk, snode] : *node.as_table()) {
        const std::string sub(sk.str());
        const auto &tables = value_tables();
        if (std::find(tables.begin(), tables.end(), sub) == tables.end()) {
          std::string msg = "unknown key 'source." + sub + "'";
          const std::string c = closest(sub, tables);
          msg += c.empty() ? "; [source] holds the tables [source.bekker], "
                             "[source.mohr_coulomb], [source.janosi], [source.scm]"
                           : "; did you mean [source." + c + "]?";
          p.fail(&snode, msg);
        }
        if (!snode.is_table())
          p.fail(&snode, "'source." + sub + "' must be a table: write [source." + sub +
                             "] and, for each value of [" + sub + "], key = \"<its source>\"");
        const auto known = keys_of(sub);
        for (const auto &[vk, vnode] : *snode.as_table()) {
          const std::string v(vk.str());
          if (std::find(known.begin(), known.end(), v) == known.end())
            p.fail(&vnode, unknown_key_message("source." + sub + ".", v, known));
          if (!vnode.is_string())
            p.fail(&vnode, "source." + sub + "." + v +
                               " must be a string (where the value comes from), got " +
                               type_name(vnode));
        }
      }
      continue;
    }
    const auto known = keys_of(key);
    for (const auto &[sk, snode] : *node.as_table()) {
      const std::string sub(sk.str());
      if (std::find(known.begin(), known.end(), sub) == known.end())
        p.fail(&snode, unknown_key_message(key + ".", sub, known));
    }
  }
}

/// The number at table.key (integers accepted), or nullopt when absent.
std::optional<double> number(const Parser &p, const toml::table &doc, const KeySpec &k) {
  const toml::table *t = doc.get_as<toml::table>(k.table);
  const toml::node *n = t ? t->get(k.key) : nullptr;
  if (!n)
    return std::nullopt;
  const std::string full = std::string(k.table) + "." + k.key;
  const std::string unit = *k.unit ? std::string(" in ") + k.unit : std::string();
  double v;
  if (auto i = n->as_integer())
    v = static_cast<double>(i->get());
  else if (auto f = n->as_floating_point())
    v = f->get();
  else
    p.fail(n, full + " must be a number" + unit + ", got " + type_name(*n));
  if (!std::isfinite(v))
    p.fail(n, full + " must be a finite number" + unit + ", got " + fmt(v));
  return v;
}

const KeySpec &spec(const char *table, const char *key) {
  for (const auto &k : value_keys())
    if (std::string(table) == k.table && std::string(key) == k.key)
      return k;
  throw std::logic_error("soil_file: no key " + std::string(table) + "." + key);
}

} // namespace

std::vector<std::string> soil_file_keys() {
  std::vector<std::string> out;
  for (const auto &k : value_keys())
    out.push_back(std::string(k.table) + "." + k.key);
  return out;
}

SoilParameters parse_soil_file(const std::string &text, const std::string &source_name) {
  const Parser p(source_name);
  toml::table doc;
  try {
    doc = toml::parse(text, source_name);
  } catch (const toml::parse_error &e) {
    throw SoilFileError(config::syntax_error(e, source_name));
  }
  check_known_keys(p, doc);

  // A required or optional number with its range check. `range` reads like "in (0, 2]".
  auto get = [&](const char *table, const char *key, bool required, const char *range,
                 const std::function<bool(double)> &ok) -> std::optional<double> {
    const KeySpec &k = spec(table, key);
    const auto v = number(p, doc, k);
    const std::string full = std::string(table) + "." + key;
    if (!v) {
      if (required)
        p.fail(doc.get(table), "missing key '" + full + "': write " + key + " = <" + k.what +
                                   (*k.unit ? std::string(" in ") + k.unit : std::string()) + ", " +
                                   range + "> under [" + table + "]");
      return v;
    }
    if (!ok(*v)) {
      const toml::table *t = doc.get_as<toml::table>(table);
      p.fail(t->get(key),
             full + " must be " + range + (*k.unit ? " " : "") + k.unit + ", got " + fmt(*v));
    }
    return v;
  };

  SoilParameters s;
  const toml::node *name = doc.get("name");
  if (!name)
    p.fail(nullptr, "missing key 'name': write name = \"<soil name>\" at the top of the file");
  s.name = name->as_string()->get();
  if (s.name.empty())
    p.fail(name, "'name' must not be empty");

  s.Bekker_n = *get("bekker", "n", true, "in (0, 2]", [](double v) { return v > 0 && v <= 2; });
  s.Bekker_Kc = *get("bekker", "kc", true, ">= 0", [](double v) { return v >= 0; });
  s.Bekker_Kphi = *get("bekker", "kphi", true, ">= 0", [](double v) { return v >= 0; });
  if (!(s.Bekker_Kc + s.Bekker_Kphi > 0))
    p.fail(doc.get_as<toml::table>("bekker")->get("kphi"),
           "bekker.kc + bekker.kphi must be > 0 (the soil must resist sinkage), got kc = 0 "
           "N/m^(n+1) and kphi = 0 N/m^(n+2)");
  s.Mohr_cohesion = *get("mohr_coulomb", "cohesion", true, ">= 0", [](double v) { return v >= 0; });
  s.Mohr_friction = *get("mohr_coulomb", "friction_angle", true, "in [0, 90)", [](double v) {
    return v >= 0 && v < 90;
  }) * M_PI / 180.0;
  s.Janosi_shear = *get("janosi", "shear_modulus", true, "> 0", [](double v) { return v > 0; });
  s.elastic_K = get("scm", "elastic_stiffness", false, "> 0", [](double v) {
                  return v > 0;
                }).value_or(s.elastic_K);
  s.damping_R =
      get("scm", "damping", false, ">= 0", [](double v) { return v >= 0; }).value_or(s.damping_R);
  return s;
}

namespace {

/// A TOML basic string.
std::string toml_string(const std::string &s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\')
      out += std::string("\\") + c;
    else if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned char>(c));
      out += buffer;
    } else
      out += c;
  }
  return out + "\"";
}

} // namespace

std::string write_soil_file(const SoilParameters &soil, const SoilFileNotes &notes) {
  const std::vector<std::pair<const char *, double>> values = {
      {"n", soil.Bekker_n},
      {"kc", soil.Bekker_Kc},
      {"kphi", soil.Bekker_Kphi},
      {"cohesion", soil.Mohr_cohesion},
      {"friction_angle", soil.Mohr_friction * 180.0 / M_PI},
      {"shear_modulus", soil.Janosi_shear},
      {"elastic_stiffness", soil.elastic_K},
      {"damping", soil.damping_R},
  };
  std::ostringstream os;
  os << "# " << soil.name << ": an SCM soil file (docs/scm-soils.md). Units are SI, angles in "
     << "degrees.\n";
  os << "name = " << toml_string(soil.name) << "\n";
  if (!notes.description.empty())
    os << "description = " << toml_string(notes.description) << "\n";
  const auto &keys = value_keys();
  for (const std::string &table : value_tables()) {
    os << "\n[" << table << "]\n";
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (table != keys[i].table)
        continue;
      if (std::string(values[i].first) != keys[i].key)
        throw std::logic_error("write_soil_file: values out of the schema's order");
      std::string line = std::string(keys[i].key) + " = " + detail::float_text(values[i].second);
      line.resize(std::max<std::size_t>(line.size() + 1, 26), ' ');
      os << line << "# " << keys[i].what << " [" << (*keys[i].unit ? keys[i].unit : "-") << "]\n";
    }
  }
  for (const std::string &table : value_tables()) {
    bool header = false;
    for (const auto &k : keys) {
      if (table != k.table)
        continue;
      const std::string full = table + "." + k.key;
      for (const auto &[key, text] : notes.sources) {
        if (key != full)
          continue;
        if (!header)
          os << "\n[source." << table << "]\n";
        header = true;
        os << k.key << " = " << toml_string(text) << "\n";
      }
    }
  }
  return os.str();
}

SoilParameters load_soil_file(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw SoilFileError(path + ": cannot open the soil file (see inputs/scm_soils/ for examples)");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_soil_file(text.str(), path);
}

} // namespace wheelsim::scm
