// The catalogue of wheels to generate (meshes/catalog.toml), read with toml++.
#pragma once

#include <string>
#include <vector>

#include "wheel_spec.h"

namespace wheelsim::meshes {

struct CatalogEntry {
  std::string name;    // file stem, e.g. "wheel1"
  std::string comment; // optional note carried into the properties file
  WheelSpec spec;
  double density_kg_m3 = 7850.0;
};

/// Reads a catalogue: an optional [defaults] table and [[wheel]] tables whose keys are the
/// wheel-mesh long option names (diameter, width, lugs, lug-height, lug-width, lug-angle,
/// centre-length, type, smooth, max-arc, max-angle, max-width-edge, density) plus `name` and
/// `comment`. Values in metres and degrees as on the command line. Unknown keys, wrong types and
/// invalid wheels are errors naming the file, the entry and the key.
std::vector<CatalogEntry> read_catalog(const std::string &path);

} // namespace wheelsim::meshes
