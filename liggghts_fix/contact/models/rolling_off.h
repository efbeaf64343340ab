// `rolling_friction off`: no rolling resistance.
#pragma once

#include "contact_model.h"

namespace wheelsim::contact::rolling_off {

constexpr ModelSpec spec{"off", nullptr, "no rolling resistance", "", {}, {}};

inline void apply(const ContactStep &, const NormalPart &, double, ContactResult &) {}

} // namespace wheelsim::contact::rolling_off
