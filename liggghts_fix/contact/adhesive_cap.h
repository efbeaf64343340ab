// The Coulomb cap of `tangential history_adhesive` (Thornton 1991), shared by its two sides: the
// wheel contact of fix wheel/cosim (models/tangential_history_adhesive.h) and LIGGGHTS' pair style
// and walls (../tangential_model_history_adhesive.h). Plain doubles, no Eigen and no LIGGGHTS
// headers, so that both sides include it and compute the same numbers. docs/contact-law.md,
// "Tangential: tangential history_adhesive".
#pragma once

#include <algorithm>
#include <cmath>

namespace wheelsim::contact {

/// Pull-off force [N] of a Hertz–SJKR contact of effective radius r_eff [m], cohesion energy
/// density k_coh [J/m³] and effective modulus y_eff [Pa] (small overlaps: SJKR's area 2π R* δ):
/// the largest pull of C δ − K δ^1.5, 4 C³ / (27 K²) with C = 2π r_eff k_coh and
/// K = 4/3 y_eff √r_eff, i.e. (2/3) π³ k_coh³ r_eff² / y_eff².
inline double sjkr_pull_off_force(double r_eff, double k_coh, double y_eff) {
  return 2.0 / 3.0 * M_PI * M_PI * M_PI * k_coh * k_coh * k_coh * r_eff * r_eff / (y_eff * y_eff);
}

/// Thornton's cap μ max(0, F_net + 2 F_po) [N], F_net the net normal force (repulsive > 0:
/// elastic + damping − the cohesive pull) and f_po the pull-off force.
inline double adhesive_coulomb_cap(double mu, double f_net, double f_po) {
  return mu * std::max(0.0, f_net + 2.0 * f_po);
}

} // namespace wheelsim::contact
