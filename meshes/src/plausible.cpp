#include "plausible.h"

#include <sstream>

namespace wheelsim::meshes {

std::string metres_hint(const std::string &name, double value, PlausibleRange range) {
  std::ostringstream os;
  os << "; the generator takes metres";
  const double in_metres = value / 1000.0;
  if (value >= 1.0 && in_metres >= range.min_m && in_metres <= range.max_m)
    os << ": did you mean " << name << " " << in_metres << "?";
  return os.str();
}

std::optional<std::string> implausible_size(const std::string &name, double value,
                                            PlausibleRange range, const char *what) {
  if (value >= range.min_m && value <= range.max_m)
    return std::nullopt;
  std::ostringstream os;
  os << name << " " << value << " m is implausible for " << what << " (expected " << range.min_m
     << "–" << range.max_m << " m)" << metres_hint(name, value, range);
  return os.str();
}

std::string bad_value_message(const std::string &name, double value, const char *unit,
                              const std::string &expected) {
  std::ostringstream os;
  os << name << " " << value << (unit[0] ? " " : "") << unit << ": " << expected;
  return os.str();
}

} // namespace wheelsim::meshes
