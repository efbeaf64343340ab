// Validation of the SCM inputs: std::invalid_argument naming the setting, the expected range with
// its unit, and the offending value.
#pragma once

#include "wheelsim/scm/scm_terrain.h"

namespace wheelsim::scm::detail {

void check_soil(const SoilParameters &soil);
void check_settings(const ScmSettings &settings);
void check_time_step(double dt_s);

} // namespace wheelsim::scm::detail
