// `model hertz`: Hertz–Mindlin with viscous damping from the restitution coefficient
// (LIGGGHTS normal_model_hertz.h, NormalModel<HERTZ>::surfacesIntersect). docs/contact-law.md,
// "Normal: model hertz".
#pragma once

#include "contact_model.h"

namespace wheelsim::contact::normal_hertz {

constexpr PropertySpec kProperties[] = {kYoungsModulus, kPoissonsRatio, kCoefficientRestitution};

constexpr SwitchSpec kSwitches[] = {
    {"tangential_damping", "damp the tangential spring while sticking (γt)", true,
     setTangentialDamping},
    {"limitForce", "clamp a net attractive normal force to 0", false, setLimitForce},
};

constexpr ModelSpec spec{
    "hertz",     nullptr,  "Hertz–Mindlin, viscous damping from e", "normal_model_hertz.h",
    kProperties, kSwitches};

/// sqrt(5/6), the factor between the Hertz damping coefficient and the critical damping of the
/// linearised spring (normal_model_hertz.h: sqrtFiveOverSix).
inline const double kSqrtFiveOverSix = std::sqrt(5.0 / 6.0);

inline NormalPart apply(const ContactStep &c) {
  const PairConstants &pc = c.pc;
  const double R = c.state.radius, m = c.state.mass, delta = c.state.overlap;
  const double sqrtRd = std::sqrt(R * delta);
  const double Sn = 2.0 * pc.Yeff * sqrtRd; // normal contact stiffness dF/dδ [N/m]
  const double St = 8.0 * pc.Geff * sqrtRd; // tangential (Mindlin) stiffness [N/m]
  const double kn = 4.0 / 3.0 * pc.Yeff * sqrtRd;
  const double gamman = -2.0 * kSqrtFiveOverSix * pc.betaeff * std::sqrt(Sn * m);
  const double gammat = pc.settings.tangentialDamping
                            ? -2.0 * kSqrtFiveOverSix * pc.betaeff * std::sqrt(St * m)
                            : 0.0;
  double Fn = kn * delta - gamman * c.vn;
  if (pc.limitForce && Fn < 0.0)
    Fn = 0.0;
  return {Fn, St, gammat, kn * delta};
}

} // namespace wheelsim::contact::normal_hertz
