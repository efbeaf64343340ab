// Numbers as the soil writers (soil_file.cpp, chrono_soil.cpp) print them: 15 significant
// digits (DBL_DIG), so a decimal of up to 15 digits read into a double and written back is the
// same text, and a value that went through a degree/radian conversion and back (a few ulp off)
// prints as it was written.
#pragma once

#include <cstdio>
#include <string>

namespace wheelsim::scm::detail {

/// "%.15g" (e.g. 0.012, 31.1, 1528430, 2e+08).
inline std::string number_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.15g", v);
  return buffer;
}

/// number_text, with ".0" appended when it reads as an integer (TOML: a float stays a float).
inline std::string float_text(double v) {
  std::string s = number_text(v);
  if (s.find_first_of(".eEn") == std::string::npos)
    s += ".0";
  return s;
}

} // namespace wheelsim::scm::detail
