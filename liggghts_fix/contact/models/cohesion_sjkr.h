// `cohesion sjkr`: simplified JKR cohesion, energy density times contact area (LIGGGHTS
// cohesion_model_sjkr.h, wall branch). docs/contact-law.md, "Cohesion: cohesion sjkr".
#pragma once

#include "contact_model.h"

namespace wheelsim::contact::cohesion_sjkr {

constexpr PropertySpec kProperties[] = {
    {"cohesionEnergyDensity",
     PropertyStyle::PerTypePair,
     "J/m^3",
     "cohesion energy density k_coh: F = -k_coh π (R² - (R - δ)²)",
     {0.0, kInf, true, false},
     nullptr,
     &PairMaterial::cohesionEnergyDensity},
};

inline void setTangentialReduce(ContactSettings &s, bool on) { s.tangentialReduce = on; }

constexpr SwitchSpec kSwitches[] = {
    {"tangential_reduce", "add the cohesion force to the Fn of the Coulomb and rolling caps", false,
     setTangentialReduce},
};

constexpr ModelSpec spec{"sjkr",
                         nullptr,
                         "simplified JKR: energy density times contact area",
                         "cohesion_model_sjkr.h",
                         kProperties,
                         kSwitches};

/// F = -k_coh π (R² - r²) along n, r = R - δ the distance from the particle centre to the
/// surface (LIGGGHTS multiplies by area_ratio, 1 for spheres).
inline void apply(const ContactStep &c, double &Fn, ContactResult &out) {
  const double R = c.state.radius, delta = c.state.overlap;
  const double r = R - delta;
  const double area = (R * R - r * r) * M_PI;
  out.cohesionForce = -c.pc.pair.cohesionEnergyDensity * area;
  out.force += out.cohesionForce * c.state.normal;
  if (c.pc.settings.tangentialReduce)
    Fn += out.cohesionForce;
}

} // namespace wheelsim::contact::cohesion_sjkr
