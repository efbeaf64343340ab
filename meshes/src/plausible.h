// Plausibility bounds for sizes given in metres, shared by the wheels and the tools: a value
// outside its range is almost surely millimetres given for metres (or a typo).
#pragma once

#include <optional>
#include <string>

namespace wheelsim::meshes {

/// A plausible range of a size [m].
struct PlausibleRange {
  double min_m;
  double max_m;
};

/// Most triangles a wheel or a tool may have by its estimated_triangle_count (about 5 s of
/// generation and 1 GB of ASCII STL; the study wheels have 30 000-70 000).
inline constexpr double kMaxEstimatedTriangles = 1.0e7;

/// "; the generator takes metres: did you mean NAME 0.2?" when `value` looks like millimetres
/// (>= 1, and value / 1000 within `range`), else "; the generator takes metres".
std::string metres_hint(const std::string &name, double value, PlausibleRange range);

/// std::nullopt when `value` lies in `range`, else the message, e.g. "--diameter 200 m is
/// implausible for a wheel diameter (expected 0.05–5 m); the generator takes metres: did you mean
/// --diameter 0.2?". `name` is the option or parameter as the user wrote it, `what` the quantity
/// with its article ("a wheel diameter").
std::optional<std::string> implausible_size(const std::string &name, double value,
                                            PlausibleRange range, const char *what);

/// "NAME VALUE UNIT: EXPECTED" (no unit when `unit` is empty), e.g. "--width -1 m: the width
/// must be > 0 m": the message of a size or count out of its valid range.
std::string bad_value_message(const std::string &name, double value, const char *unit,
                              const std::string &expected);

/// Throws Error (WheelSpecError, ToolSpecError) with bad_value_message(...).
template <class Error>
[[noreturn]] void fail_value(const std::string &name, double value, const char *unit,
                             const std::string &expected) {
  throw Error(bad_value_message(name, value, unit, expected));
}

/// Throws Error with the implausible_size message when `value` is outside `range`.
template <class Error>
void check_plausible(const std::string &name, double value, PlausibleRange range,
                     const char *what) {
  if (auto message = implausible_size(name, value, range, what))
    throw Error(*message);
}

} // namespace wheelsim::meshes
