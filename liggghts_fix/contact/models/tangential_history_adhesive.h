// `tangential history_adhesive` (wheelsim's): the spring of `tangential history` with Thornton's
// (1991) Coulomb cap for adhesive contacts, μ max(0, F_net + 2 F_po), F_net the net normal force
// (Hertz + damping − the SJKR pull) and F_po the Hertz–SJKR contact's pull-off force
// (../adhesive_cap.h). The same model for LIGGGHTS' pair style and walls:
// liggghts_fix/tangential_model_history_adhesive.h. docs/contact-law.md, "Tangential: tangential
// history_adhesive".
#pragma once

#include "../adhesive_cap.h"
#include "contact_model.h"
#include "tangential_history.h"

#include <stdexcept>

namespace wheelsim::contact::tangential_history_adhesive {

/// The pull-off force needs the SJKR cohesion (its cohesionEnergyDensity and pull).
inline void check(const PairMaterial &, const ContactSettings &settings) {
  if (settings.cohesion != CohesionModel::Sjkr)
    throw std::invalid_argument("contact law: tangential history_adhesive needs cohesion sjkr "
                                "(its cap adds twice the SJKR pull-off force)");
}

constexpr ModelSpec spec{"history_adhesive",
                         nullptr,
                         "tangential spring with Thornton's adhesive Coulomb cap",
                         "", // wheelsim's (liggghts_fix/tangential_model_history_adhesive.h)
                         tangential_history::kProperties, // μ, as history
                         {},
                         nullptr,
                         "",
                         check};

/// Cap μ max(0, F_net + 2 F_po) on the wheel (a wall: R* = the particle's radius).
inline void apply(const ContactStep &c, const NormalPart &np, double Fn, ContactResult &out) {
  // Fn holds the (negative) SJKR pull already with tangential_reduce; else it is taken off here
  const double net = c.pc.settings.tangentialReduce ? Fn : Fn + out.cohesionForce;
  const double fPo =
      sjkr_pull_off_force(c.state.radius, c.pc.pair.cohesionEnergyDensity, c.pc.Yeff);
  tangential_history::springWithCap(
      c, np, adhesive_coulomb_cap(c.pc.pair.coefficientFriction, net, fPo), out);
}

} // namespace wheelsim::contact::tangential_history_adhesive
