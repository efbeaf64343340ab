// Rigid-wheel closed forms of Bekker and Wong (TERRAMECHANICS.md §2): the analytic anchors of
// the SCM and Wong–Reece tests. A rigid wheel of radius R [m] and width b [m] under a vertical
// load W [N] on a soil with Bekker pressure p = (kc/b + kφ) z^n. Reference: docs/wong-reece.md.
//
// Geometry: a wheel sunk by z0 [m] meets the undisturbed surface on the chord x ∈ [−a, a],
// a = sqrt(2 R z0 − z0²); the local sinkage is z(x) = z0 − (R − sqrt(R² − x²)). With x = R sin θ
// the load integrals become b (kc/b + kφ) R^(n+1) ∫ (cos θ − cos θ1)^n cos θ dθ, θ1 = acos(1 −
// z0/R), which is how they are evaluated (tanh–sinh quadrature, exact to ~1e-14 relative).
//
// All functions check their arguments (R > 0, b > 0, W > 0 or z0 ≥ 0) and throw
// std::invalid_argument naming the argument, its range and value. The sinkage solvers throw
// TerramechanicsError when the soil cannot carry the load before z0 reaches R.
#pragma once

#include "wheelsim/scm/soil.h"

#include <stdexcept>

namespace wheelsim::scm {

/// The load cannot be carried (sinkage would exceed the geometric limit of the model).
class TerramechanicsError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Bekker's combined modulus kc/b + kφ [N/m^(n+2)] for a contact of width b [m].
double bekker_modulus(const SoilParameters &soil, double width_m);

/// Closed-form sinkage [m] of a rolling rigid wheel (Bekker; two terms of a series, small
/// sinkage): z0 = [3W / ((3 − n)(kc + b kφ) sqrt(D))]^(2/(2n+1)), D = 2R.
double rolling_sinkage_closed_form_m(const SoilParameters &soil, double radius_m, double width_m,
                                     double load_N);

/// The load [N] that the closed form above carries at sinkage z0 [m] (its definition, inverted):
/// W = (3 − n)(kc + b kφ) sqrt(D) z0^((2n+1)/2) / 3.
double rolling_closed_form_load_N(const SoilParameters &soil, double radius_m, double width_m,
                                  double sinkage_m);

/// Vertical load [N] carried by the front half of the contact (entry point to bottom) at sinkage
/// z0 [m]: W = b ∫_0^a (kc/b + kφ) z(x)^n dx. z0 in [0, R].
double rolling_load_N(const SoilParameters &soil, double radius_m, double width_m,
                      double sinkage_m);

/// Vertical load [N] carried by the whole chord (a wheel standing still) at sinkage z0 [m]:
/// W = b ∫_{−a}^{a} (kc/b + kφ) z(x)^n dx = 2 rolling_load_N. z0 in [0, R].
double standing_load_N(const SoilParameters &soil, double radius_m, double width_m,
                       double sinkage_m);

/// Sinkage [m] of a rolling wheel from the front-half integral (rolling_load_N = W solved for
/// z0; Brent's method, 1e-12 relative). The closed form is a series approximation of this value.
double rolling_sinkage_integral_m(const SoilParameters &soil, double radius_m, double width_m,
                                  double load_N);

/// Sinkage [m] of a wheel standing still (standing_load_N = W solved for z0; Brent, 1e-12
/// relative). Smaller than the rolling sinkage: about 40 % less for LETE sand, 13.2 kN,
/// R = 0.617 m, b = 0.479 m.
double standing_sinkage_m(const SoilParameters &soil, double radius_m, double width_m,
                          double load_N);

/// Compaction resistance [N] of a wheel of width b [m] at sinkage z0 [m] (work of making a rut
/// of depth z0 per unit length): Rc = b (kc/b + kφ) z0^(n+1) / (n + 1).
double compaction_resistance_N(const SoilParameters &soil, double width_m, double sinkage_m);

} // namespace wheelsim::scm
