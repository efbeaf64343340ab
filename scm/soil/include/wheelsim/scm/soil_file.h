// Soil files (inputs/scm_soils/*.toml): TOML, SI units with the unit in each key's doc, angles in
// degrees. Every key, unit, range and default: docs/scm-soils.md. Errors read
// "<file>:<line>: <message>" and name the key, the expected range with its unit and the value;
// an unknown key is an error with a "did you mean" suggestion.
#pragma once

#include "wheelsim/scm/soil.h"

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace wheelsim::scm {

/// A soil file that cannot be read or is invalid; what() is "<file>[:<line>]: <message>".
class SoilFileError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Reads and validates a soil file. Throws SoilFileError (also when the file cannot be opened).
SoilParameters load_soil_file(const std::string &path);

/// Parses soil-file text; `source_name` is the file name used in error messages.
/// Throws SoilFileError.
SoilParameters parse_soil_file(const std::string &text, const std::string &source_name);

/// What a written soil file says besides the values: a description and, per value key
/// ("bekker.kc", as soil_file_keys() names them), where the value comes from ([source.<table>]).
struct SoilFileNotes {
  std::string description;
  std::vector<std::pair<std::string, std::string>> sources;
};

/// The text of a soil file with every value of `soil` (numbers with 15 significant digits, the
/// friction angle in degrees, [scm] included) that load_soil_file reads back to the same values.
std::string write_soil_file(const SoilParameters &soil, const SoilFileNotes &notes = {});

/// Every value key of a soil file as "table.key" (e.g. "bekker.kc"), in documentation order.
/// The optional [source.<table>] tables take the same keys (the source of each value).
std::vector<std::string> soil_file_keys();

} // namespace wheelsim::scm
