#include "catalog.h"

#include <set>

#include <toml++/toml.h>

namespace wheelsim::meshes {
namespace {

double number(const toml::node &node, const std::string &where) {
  if (auto v = node.value<double>())
    return *v;
  throw WheelSpecError(where + ": expected a number");
}

// Applies one key of a [[wheel]] or [defaults] table.
void apply(CatalogEntry &e, const std::string &key, const toml::node &node,
           const std::string &where) {
  const std::string at = where + ": key '" + key + "'";
  WheelSpec &s = e.spec;
  if (key == "name") {
    if (auto v = node.value<std::string>())
      e.name = *v;
    else
      throw WheelSpecError(at + ": expected a string");
  } else if (key == "comment") {
    if (auto v = node.value<std::string>())
      e.comment = *v;
    else
      throw WheelSpecError(at + ": expected a string");
  } else if (key == "type") {
    auto v = node.value<std::string>();
    if (!v)
      throw WheelSpecError(at + ": expected a string");
    s.type = parse_lug_type(*v);
  } else if (key == "smooth") {
    auto v = node.value<bool>();
    if (!v)
      throw WheelSpecError(at + ": expected true or false");
    s.smooth = *v;
  } else if (key == "lugs") {
    auto v = node.value<int64_t>();
    if (!v)
      throw WheelSpecError(at + ": expected an integer");
    s.lug_count = static_cast<int>(*v);
  } else if (key == "diameter") {
    s.diameter_m = number(node, at);
  } else if (key == "width") {
    s.width_m = number(node, at);
  } else if (key == "lug-height") {
    s.lug_height_m = number(node, at);
  } else if (key == "lug-width") {
    s.lug_width_m = number(node, at);
  } else if (key == "lug-angle") {
    s.lug_angle_deg = number(node, at);
  } else if (key == "centre-length") {
    s.centre_length_m = number(node, at);
  } else if (key == "max-arc") {
    s.resolution.max_arc_m = number(node, at);
  } else if (key == "max-angle") {
    s.resolution.max_angle_deg = number(node, at);
  } else if (key == "max-width-edge") {
    s.resolution.max_width_edge_m = number(node, at);
  } else if (key == "density") {
    e.density_kg_m3 = number(node, at);
  } else {
    throw WheelSpecError(at + ": unknown key (expected name, comment, diameter, width, lugs, "
                              "lug-height, lug-width, lug-angle, centre-length, type, smooth, "
                              "max-arc, max-angle, max-width-edge, density)");
  }
}

} // namespace

std::vector<CatalogEntry> read_catalog(const std::string &path) {
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error &err) {
    throw WheelSpecError(path + ": " + std::string(err.description()));
  }
  for (const auto &[key, node] : root) {
    if (key.str() != "defaults" && key.str() != "wheel") {
      throw WheelSpecError(path + ": unknown top-level key '" + std::string(key.str()) +
                           "' (expected [defaults] and [[wheel]])");
    }
    (void)node;
  }
  CatalogEntry defaults;
  if (const toml::table *d = root["defaults"].as_table()) {
    for (const auto &[key, node] : *d) {
      apply(defaults, std::string(key.str()), node, path + ": [defaults]");
    }
  }
  const toml::array *wheels = root["wheel"].as_array();
  if (wheels == nullptr || wheels->empty()) {
    throw WheelSpecError(path + ": no [[wheel]] entries");
  }
  std::vector<CatalogEntry> entries;
  std::set<std::string> names;
  int index = 0;
  for (const toml::node &w : *wheels) {
    ++index;
    const toml::table *t = w.as_table();
    if (t == nullptr)
      throw WheelSpecError(path + ": [[wheel]] " + std::to_string(index) + " is not a table");
    CatalogEntry e = defaults;
    e.name.clear();
    std::string where = path + ": [[wheel]] " + std::to_string(index);
    if (auto n = (*t)["name"].value<std::string>())
      where += " (" + *n + ")";
    for (const auto &[key, node] : *t)
      apply(e, std::string(key.str()), node, where);
    if (e.name.empty())
      throw WheelSpecError(where + ": missing key 'name'");
    if (!names.insert(e.name).second)
      throw WheelSpecError(where + ": duplicate name '" + e.name + "'");
    try {
      validate(e.spec);
    } catch (const WheelSpecError &err) {
      throw WheelSpecError(where + ": " + err.what());
    }
    entries.push_back(e);
  }
  return entries;
}

} // namespace wheelsim::meshes
