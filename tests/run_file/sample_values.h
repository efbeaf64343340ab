// Known values written by the tests and by run_file_write_sample, checked on reading (C API and
// check_run_file.py use the same formulas). All values are exact in binary floating point.
#pragma once

#include <cstdint>

namespace sample {
inline double time_s(std::int64_t step) { return 0.5e-4 * static_cast<double>(step); }
inline double value(std::int64_t step, int component) {
  return static_cast<double>(step) + 0.125 * component + 0.5;
}
} // namespace sample
