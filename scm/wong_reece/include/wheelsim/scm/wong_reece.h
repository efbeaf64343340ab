// The Wong–Reece semi-analytic model of a driven rigid wheel on soft soil (Wong & Reece 1967;
// TERRAMECHANICS.md §3): the normal stress σ(θ) and shear stress τ(θ) on the contact arc,
// integrated to the vertical load, the drawbar pull and the driving torque; the entry angle θ1
// (the sinkage) is solved so that the vertical balance holds. Reference: docs/wong-reece.md.
//
// Angles [rad] from the downward vertical through the axle, positive towards the direction of
// travel: the soil is met at the entry angle θ1 > 0 and left at the exit angle θ2 ≤ 0.
//   θ1 = acos(1 − z/R), θ2 = −acos(1 − λ z/R), θm = (c1 + c2 s) θ1
//   σ1(θ) = (kc/b + kφ) R^n (cos θ − cos θ1)^n                                    θm ≤ θ ≤ θ1
//   σ2(θ) = (kc/b + kφ) R^n (cos(θ1 − (θ − θ2)(θ1 − θm)/(θm − θ2)) − cos θ1)^n    θ2 ≤ θ < θm
//   j(θ) = R [(θ1 − θ) − (1 − s)(sin θ1 − sin θ)],  τ = (c + σ tan φ)(1 − exp(−j/K))
//   W = R b ∫ (σ cos θ + τ sin θ) dθ,  DP = R b ∫ (τ cos θ − σ sin θ) dθ,  T = R² b ∫ τ dθ
// b is the wheel width (also in the Bekker term kc/b).
#pragma once

#include "wheelsim/scm/bekker_closed_forms.h"
#include "wheelsim/scm/soil.h"

#include <vector>

namespace wheelsim::scm {

/// A smooth rigid wheel.
struct WongReeceWheel {
  double radius_m = 0.0; ///< R [m], > 0
  double width_m = 0.0;  ///< b [m], > 0
};

struct WongReeceOptions {
  double c1 = 0.43;           ///< θm = (c1 + c2 s) θ1 [-]; c1 in [0, 1)
  double c2 = 0.32;           ///< [-]; c1 + c2 s must stay in [0, 1)
  double rebound_ratio = 0.0; ///< λ in [0, 1]: rear contact to θ2 = −acos(1 − λ z/R)
  /// Tanh–sinh nodes on each of the two stress regions (≥ 9; 129 gives ~1e-13 relative).
  int quadrature_points = 129;
  /// If > 0: σ, τ and j sampled at this many equally spaced angles from θ2 to θ1 (≥ 2).
  int distribution_points = 0;
};

/// One sample of the stress distribution.
struct WongReeceStress {
  double theta_rad = 0.0;            ///< θ [rad]
  double sigma_Pa = 0.0;             ///< normal stress σ [Pa]
  double tau_Pa = 0.0;               ///< shear stress τ [Pa]
  double shear_displacement_m = 0.0; ///< j [m]
};

struct WongReeceResult {
  double load_N = 0.0;               ///< the vertical load W asked for [N]
  double slip = 0.0;                 ///< s = 1 − v/(ωR) [-]
  double entry_angle_rad = 0.0;      ///< θ1 [rad]
  double exit_angle_rad = 0.0;       ///< θ2 [rad] (≤ 0)
  double max_stress_angle_rad = 0.0; ///< θm [rad]
  double sinkage_m = 0.0;            ///< z = R (1 − cos θ1) [m]
  double vertical_force_N = 0.0; ///< R b ∫ (σ cos θ + τ sin θ) dθ at the solution [N] (= W)
  double drawbar_pull_N = 0.0;   ///< DP [N], positive = pulling
  double torque_Nm = 0.0;        ///< driving torque T about the axle [N m]
  double traction_force_N = 0.0; ///< F_T = T/R [N]
  /// η = DP (1 − s) / (T/R) = DP v / (T ω) [-]; negative when DP < 0; 0 when T = 0.
  double tractive_efficiency = 0.0;
  std::vector<WongReeceStress> distribution; ///< when options.distribution_points > 0
};

/// The forces at a given entry angle θ1 [rad] in (0, π/2] and slip s in [0, 1] (no balance
/// solved: load_N is set to the vertical force). Throws std::invalid_argument on bad input.
WongReeceResult evaluate_wong_reece(const SoilParameters &soil, const WongReeceWheel &wheel,
                                    double entry_angle_rad, double slip,
                                    const WongReeceOptions &options = {});

/// Solves θ1 so the vertical force equals load_N [N] (> 0) at slip s in [0, 1]: bracketed by a
/// scan of θ1 over (0, π/2], then Brent's method to 1e-12 relative in θ1. Throws
/// std::invalid_argument on bad input (naming it, its range and value) and TerramechanicsError
/// when the load cannot be carried before θ1 reaches π/2 (sinkage = R).
WongReeceResult solve_wong_reece(const SoilParameters &soil, const WongReeceWheel &wheel,
                                 double load_N, double slip, const WongReeceOptions &options = {});

} // namespace wheelsim::scm
