// Shared by the Wong–Reece tests: the shipped soils and the reference wheel of TERRAMECHANICS.md
// §7 (wheel 1: D0 = 1.234 m, w = 0.479 m) under the 13.2 kN test load.
#pragma once

#include "wheelsim/scm/soil_file.h"

#include <string>

namespace wr_test {

constexpr double kRadius = 0.617; ///< m
constexpr double kWidth = 0.479;  ///< m
constexpr double kLoad = 13200.0; ///< N

inline wheelsim::scm::SoilParameters soil(const std::string &name) {
  return wheelsim::scm::load_soil_file(std::string(SCM_SOILS_DIR) + "/" + name + ".toml");
}

} // namespace wr_test
