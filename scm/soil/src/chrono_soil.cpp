// Chrono's SCM soil JSON, read and written (chrono_soil.h, docs/chrono-interop.md). The key
// names and units are Chrono's: ChVehicleCosimTerrainNodeSCM::SetFromSpecfile (terrain-node
// layout) and the SCM soil-parameter files of Chrono::Vehicle's data (soil-parameters layout),
// both passing their values to SCMTerrain::SetSoilParameters (SI, friction angle in degrees).
#include "wheelsim/scm/chrono_soil.h"

#include "json_reader.h"
#include "number_text.h"

#include "wheelsim/config_messages.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

namespace wheelsim::scm {
namespace {

bool positive(double v) { return v > 0; }
bool non_negative(double v) { return v >= 0; }
bool exponent(double v) { return v > 0 && v <= 2; }
bool friction_deg(double v) { return v >= 0 && v < 90; }

// Ranges as in the soil files (docs/scm-soils.md), so that every imported soil loads.
const std::vector<ChronoSoilKey> kKeys = {
    {"Bekker Kphi", "Bekker Kphi", "N/m^(n+2)", ">= 0", "frictional modulus", non_negative,
     &ChronoSoil::Bekker_Kphi, "bekker.kphi"},
    {"Bekker Kc", "Bekker Kc", "N/m^(n+1)", ">= 0", "cohesive modulus", non_negative,
     &ChronoSoil::Bekker_Kc, "bekker.kc"},
    {"Bekker n exponent", "Bekker n", "", "in (0, 2]", "sinkage exponent", exponent,
     &ChronoSoil::Bekker_n, "bekker.n"},
    {"Mohr cohesive limit", "Mohr Cohesion", "Pa", ">= 0", "cohesion", non_negative,
     &ChronoSoil::Mohr_cohesion, "mohr_coulomb.cohesion"},
    {"Mohr friction limit", "Mohr Friction", "deg", "in [0, 90)", "internal friction angle",
     friction_deg, &ChronoSoil::Mohr_friction, "mohr_coulomb.friction_angle"},
    {"Janosi shear coefficient", "Janosi Shear", "m", "> 0", "Janosi shear deformation modulus",
     positive, &ChronoSoil::Janosi_shear, "janosi.shear_modulus"},
    {"Elastic stiffness", "Elastic K", "Pa/m", "> 0", "elastic unloading stiffness", positive,
     &ChronoSoil::elastic_K, "scm.elastic_stiffness"},
    {"Damping", "Dampening R", "Pa s/m", ">= 0", "normal damping", non_negative,
     &ChronoSoil::damping_R, "scm.damping"},
};

/// What distinguishes the two layouts: the soil object's name and the other top-level keys.
struct Layout {
  ChronoLayout id;
  const char *soil_object;
  const char *described; ///< for messages
  std::vector<std::string> top_level;
};

const Layout kTerrainNode{
    ChronoLayout::terrain_node,
    "Soil parameters",
    "a Chrono SCM terrain-node file",
    {"Name", "Type", "Patch dimensions", "Grid spacing", "Soil parameters", "Simulation settings"}};
const Layout kSoilParameters{ChronoLayout::soil_parameters,
                             "Soil Parameters",
                             "a Chrono SCM soil-parameter file",
                             {"Name", "Type", "Template", "Soil Parameters"}};

const char *key_name(const ChronoSoilKey &k, ChronoLayout layout) {
  return layout == ChronoLayout::terrain_node ? k.terrain_node_name : k.soil_parameters_name;
}

std::string quoted(const std::string &s) { return "\"" + s + "\""; }

std::string lower(std::string s) {
  for (char &c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string join_quoted(const std::vector<std::string> &v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + quoted(v[i]);
  return s;
}

/// The one of `known` closest to `given`, ignoring case; "" if none is near.
std::string suggestion(const std::string &given, const std::vector<std::string> &known) {
  std::vector<std::string> low;
  for (const auto &k : known)
    low.push_back(lower(k));
  const std::string best = config::closest(lower(given), low);
  for (std::size_t i = 0; i < known.size(); ++i)
    if (!best.empty() && low[i] == best)
      return known[i];
  return "";
}

class Reader {
public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const json::Value *where, const std::string &message) const {
    std::string s = source_;
    if (where && where->line > 0)
      s += ":" + std::to_string(where->line);
    throw ChronoSoilError(s + ": " + message);
  }

  /// Every member of `object` must be in `known`; `path` is the object's quoted name + ".".
  void check_members(const json::Value &object, const std::string &path,
                     const std::vector<std::string> &known, const std::string &hint) const {
    for (const auto &[name, value] : object.object) {
      if (std::find(known.begin(), known.end(), name) != known.end())
        continue;
      std::string msg = "unknown key " + path + quoted(name);
      const std::string near = suggestion(name, known);
      if (!near.empty())
        msg += "; did you mean " + quoted(near) + "?";
      else
        msg += "; " + hint;
      fail(&value, msg);
    }
  }

  const json::Value &member(const json::Value &object, const std::string &path,
                            const std::string &name, json::Value::Type type,
                            const std::string &expected) const {
    const json::Value *v = object.find(name);
    if (!v)
      fail(&object, "missing key " + path + quoted(name) + ": write " + quoted(name) + ": <" +
                        expected + ">");
    if (v->type != type)
      fail(v, path + quoted(name) + " must be " + json::type_name(type) + " (" + expected +
                  "), got " + json::type_name(v->type));
    return *v;
  }

private:
  std::string source_;
};

/// The soil keys of `layout` by name, and the hint for an unknown one.
std::vector<std::string> soil_key_names(ChronoLayout layout) {
  std::vector<std::string> out;
  for (const auto &k : kKeys)
    out.push_back(key_name(k, layout));
  return out;
}

void read_soil_object(const Reader &r, const json::Value &soil_object, const Layout &layout,
                      ChronoSoil &soil) {
  const std::string path = quoted(layout.soil_object) + ".";
  if (soil_object.type != json::Value::Type::object)
    r.fail(&soil_object, quoted(layout.soil_object) +
                             " must be an object with the soil keys, got " +
                             json::type_name(soil_object.type));
  if (layout.id == ChronoLayout::soil_parameters) {
    // SCMPlane.json style: the soil is in another file.
    if (const json::Value *in = soil_object.find("Input File"))
      r.fail(in, path + "\"Input File\" refers to another file" +
                     (in->type == json::Value::Type::string ? " (" + quoted(in->string) + ")"
                                                            : std::string()) +
                     ": import that file, which holds the soil parameters");
  }
  const auto names = soil_key_names(layout.id);
  const ChronoLayout other = layout.id == ChronoLayout::terrain_node ? ChronoLayout::soil_parameters
                                                                     : ChronoLayout::terrain_node;
  // A key of the other layout gets its name in this one.
  for (const auto &[name, value] : soil_object.object) {
    if (std::find(names.begin(), names.end(), name) != names.end())
      continue;
    for (const auto &k : kKeys)
      if (name == key_name(k, other) && name != key_name(k, layout.id))
        r.fail(&value, "unknown key " + path + quoted(name) + "; in " + layout.described + " (" +
                           quoted(layout.soil_object) + ") the " + k.what + " is " +
                           quoted(key_name(k, layout.id)));
  }
  r.check_members(soil_object, path, names,
                  "the keys of " + quoted(layout.soil_object) + " are " + join_quoted(names));
  for (const auto &k : kKeys) {
    const std::string name = key_name(k, layout.id);
    const std::string expected =
        std::string(k.what) + (*k.unit ? " in " : "") + k.unit + ", " + k.range;
    const json::Value &v = r.member(soil_object, path, name, json::Value::Type::number, expected);
    if (!k.in_range(v.number))
      r.fail(&v, path + quoted(name) + " must be " + k.range + (*k.unit ? " " : "") + k.unit +
                     ", got " + config::fmt(v.number));
    soil.*k.field = v.number;
  }
  if (!(soil.Bekker_Kc + soil.Bekker_Kphi > 0))
    r.fail(&soil_object, path + quoted(key_name(kKeys[0], layout.id)) + " + " +
                             quoted(key_name(kKeys[1], layout.id)) +
                             " must be > 0 (the soil must resist sinkage), got 0 and 0");
}

} // namespace

const char *chrono_layout_name(ChronoLayout layout) {
  return layout == ChronoLayout::terrain_node ? "terrain-node" : "soil-parameters";
}

ChronoLayout chrono_layout_from_name(const std::string &name) {
  for (const ChronoLayout l : {ChronoLayout::terrain_node, ChronoLayout::soil_parameters})
    if (name == chrono_layout_name(l))
      return l;
  throw std::invalid_argument("unknown Chrono layout '" + name +
                              "' (expected terrain-node or soil-parameters)");
}

const std::vector<ChronoSoilKey> &chrono_soil_keys() { return kKeys; }

ChronoSoil parse_chrono_soil(const std::string &text, const std::string &source_name,
                             ChronoLayout *layout_out) {
  const Reader r(source_name);
  json::Value doc;
  try {
    doc = json::parse(text);
  } catch (const json::SyntaxError &e) {
    throw ChronoSoilError(source_name + ":" + std::to_string(e.line()) +
                          ": JSON syntax error: " + e.what());
  }
  if (doc.type != json::Value::Type::object)
    r.fail(&doc, std::string("a Chrono SCM JSON file is an object ({ ... }), got ") +
                     json::type_name(doc.type));

  const bool node = doc.find(kTerrainNode.soil_object) != nullptr;
  const bool params = doc.find(kSoilParameters.soil_object) != nullptr;
  if (node && params)
    r.fail(doc.find(kSoilParameters.soil_object),
           "both \"Soil parameters\" (terrain-node layout) and \"Soil Parameters\" "
           "(soil-parameter layout): keep one");
  if (!node && !params) {
    const std::string msg =
        "missing key \"Soil parameters\": a Chrono SCM JSON file has "
        "\"Soil parameters\" (co-simulation terrain node) or \"Soil Parameters\" "
        "(SCM soil-parameter file) with the soil keys";
    for (const auto &m : doc.object)
      if (!suggestion(m.first, {"Soil parameters"}).empty())
        r.fail(&m.second, "unknown key " + quoted(m.first) +
                              "; did you mean \"Soil parameters\" "
                              "or \"Soil Parameters\"?");
    r.fail(&doc, msg);
  }
  const Layout &layout = node ? kTerrainNode : kSoilParameters;
  r.check_members(doc, "", layout.top_level,
                  std::string("the top-level keys of ") + layout.described + " are " +
                      join_quoted(layout.top_level));

  ChronoSoil soil;
  if (const json::Value *name = doc.find("Name")) {
    if (name->type != json::Value::Type::string)
      r.fail(name, std::string("\"Name\" must be a string, got ") + json::type_name(name->type));
    soil.name = name->string;
  }
  const std::string expected_type = node ? "SCM" : "Terrain Properties";
  if (const json::Value *type = doc.find("Type"))
    if (type->type != json::Value::Type::string || type->string != expected_type)
      r.fail(type, "\"Type\" must be " + quoted(expected_type) + " in " + layout.described +
                       ", got " +
                       (type->type == json::Value::Type::string ? quoted(type->string)
                                                                : json::type_name(type->type)));
  if (const json::Value *t = doc.find("Template"))
    if (t->type != json::Value::Type::string || t->string != "SCM Soil Parameters")
      r.fail(t, "\"Template\" must be \"SCM Soil Parameters\", got " +
                    (t->type == json::Value::Type::string ? quoted(t->string)
                                                          : json::type_name(t->type)));
  if (node) {
    // Not soil: checked for shape, not used (the rig config's [terrain] sets our grid).
    if (const json::Value *p = doc.find("Patch dimensions")) {
      if (p->type != json::Value::Type::object)
        r.fail(p, std::string("\"Patch dimensions\" must be an object, got ") +
                      json::type_name(p->type));
      r.check_members(*p, "\"Patch dimensions\".", {"Length", "Width"},
                      "its keys are \"Length\" and \"Width\" [m]");
    }
    if (const json::Value *g = doc.find("Grid spacing"))
      if (g->type != json::Value::Type::number)
        r.fail(g, std::string("\"Grid spacing\" must be a number (m), got ") +
                      json::type_name(g->type));
    if (const json::Value *s = doc.find("Simulation settings")) {
      if (s->type != json::Value::Type::object)
        r.fail(s, std::string("\"Simulation settings\" must be an object, got ") +
                      json::type_name(s->type));
      r.check_members(*s, "\"Simulation settings\".", {"Proxy contact radius", "Fix proxies"},
                      "its keys are \"Proxy contact radius\" [m] and \"Fix proxies\"");
    }
  }
  read_soil_object(r, *doc.find(layout.soil_object), layout, soil);
  if (layout_out)
    *layout_out = layout.id;
  return soil;
}

ChronoSoil load_chrono_soil(const std::string &path, ChronoLayout *layout) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw ChronoSoilError(path + ": cannot open the Chrono JSON file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_chrono_soil(text.str(), path, layout);
}

std::string write_chrono_soil(const ChronoSoil &soil, ChronoLayout layout,
                              const ChronoTerrainNodeSettings &settings) {
  using detail::number_text;
  std::ostringstream os;
  os << "{\n";
  if (!soil.name.empty() || layout == ChronoLayout::soil_parameters)
    os << "  \"Name\": " << config::json_string(soil.name) << ",\n";
  if (layout == ChronoLayout::terrain_node) {
    os << "  \"Type\": \"SCM\",\n\n"
       << "  \"Patch dimensions\": {\n"
       << "    \"Length\": " << number_text(settings.patch_length_m) << ",\n"
       << "    \"Width\": " << number_text(settings.patch_width_m) << "\n  },\n\n"
       << "  \"Grid spacing\": " << number_text(settings.grid_spacing_m) << ",\n\n";
  } else {
    os << "  \"Type\": \"Terrain Properties\",\n"
       << "  \"Template\": \"SCM Soil Parameters\",\n\n";
  }
  os << "  "
     << config::json_string(layout == ChronoLayout::terrain_node ? kTerrainNode.soil_object
                                                                 : kSoilParameters.soil_object)
     << ": {\n";
  for (std::size_t i = 0; i < kKeys.size(); ++i)
    os << "    " << config::json_string(key_name(kKeys[i], layout)) << ": "
       << number_text(soil.*kKeys[i].field) << (i + 1 < kKeys.size() ? ",\n" : "\n");
  os << "  }";
  if (layout == ChronoLayout::terrain_node)
    os << ",\n\n  \"Simulation settings\": {\n"
       << "    \"Proxy contact radius\": " << number_text(settings.proxy_contact_radius_m) << ",\n"
       << "    \"Fix proxies\": " << (settings.fix_proxies ? "true" : "false") << "\n  }";
  os << "\n}\n";
  return os.str();
}

SoilParameters to_soil_parameters(const ChronoSoil &c) {
  SoilParameters s;
  s.name = c.name;
  s.Bekker_n = c.Bekker_n;
  s.Bekker_Kc = c.Bekker_Kc;
  s.Bekker_Kphi = c.Bekker_Kphi;
  s.Mohr_cohesion = c.Mohr_cohesion;
  s.Mohr_friction = c.Mohr_friction * M_PI / 180.0;
  s.Janosi_shear = c.Janosi_shear;
  s.elastic_K = c.elastic_K;
  s.damping_R = c.damping_R;
  return s;
}

ChronoSoil to_chrono_soil(const SoilParameters &s) {
  ChronoSoil c;
  c.name = s.name;
  c.Bekker_n = s.Bekker_n;
  c.Bekker_Kc = s.Bekker_Kc;
  c.Bekker_Kphi = s.Bekker_Kphi;
  c.Mohr_cohesion = s.Mohr_cohesion;
  c.Mohr_friction = s.Mohr_friction * 180.0 / M_PI;
  c.Janosi_shear = s.Janosi_shear;
  c.elastic_K = s.elastic_K;
  c.damping_R = s.damping_R;
  return c;
}

} // namespace wheelsim::scm
