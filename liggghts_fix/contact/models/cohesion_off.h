// `cohesion off`: no cohesion.
#pragma once

#include "contact_model.h"

namespace wheelsim::contact::cohesion_off {

constexpr ModelSpec spec{"off", nullptr, "no cohesion", "", {}, {}};

inline void apply(const ContactStep &, double &, ContactResult &) {}

} // namespace wheelsim::contact::cohesion_off
