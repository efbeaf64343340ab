// `rolling_friction epsdt`: epsd2's elastic-plastic rolling spring (k_r = k_t R², moment capped at
// μr R |Fn|, no dashpot) with its stored moment turned into the current tangent plane every step,
// as krot's is (rolling_spring.h), on the rotation relative to the wheel's. A moment below the cap
// is held statically (cdt cannot: its torque switches sign every step at rest). Its LIGGGHTS side
// is liggghts_fix/rolling_model_epsdt.h (particle pairs and LIGGGHTS walls). docs/contact-law.md,
// "Rolling: rolling_friction epsdt".
#pragma once

#include "contact_model.h"
#include "rolling_spring.h"

#include <cmath>

namespace wheelsim::contact::rolling_epsdt {

constexpr PropertySpec kProperties[] = {kCoefficientRollingFriction};

constexpr ModelSpec spec{"epsdt",
                         nullptr,
                         "elastic-plastic rolling spring k_t R², turned into the tangent plane, "
                         "capped at μr R |Fn|",
                         "",
                         kProperties,
                         {}};

/// The spring of rolling_spring.h on ω_rel = ω_particle − ω_wheel, then the cap: the particle
/// feels −M.
inline void apply(const ContactStep &c, const NormalPart &np, double Fn, ContactResult &out) {
  const ContactState &s = c.state;
  const Eigen::Vector3d wRel = s.omega - s.omegaSurface;
  Eigen::Vector3d M(c.history.rollTorque[0], c.history.rollTorque[1], c.history.rollTorque[2]);
  const double R = s.radius;
  advance_rolling_spring(M.data(), s.normal.data(), wRel.data(), c.dt * np.kt * R * R);
  cap_rolling_moment(M.data(), std::fabs(Fn) * R * c.pc.pair.coefficientRollingFriction);
  if (c.updateHistory)
    Eigen::Map<Eigen::Vector3d>(c.history.rollTorque) = M;
  out.torque -= M;
}

} // namespace wheelsim::contact::rolling_epsdt
