// Soft-soil parameters of the SCM terrain and of the Wong–Reece model (TERRAMECHANICS.md §1, §6).
// Names follow Project Chrono's SCMTerrain (STYLE.md); units are SI, angles in radians in code
// (degrees in soil files). The soil files (inputs/scm_soils/*.toml) and their loader are
// documented in docs/scm-soils.md (loader: wheelsim/scm/soil_file.h).
#pragma once

#include <string>

namespace wheelsim::scm {

/// One soil. Bekker (1956, 1969) pressure–sinkage p = (kc/b + kφ) z^n; Mohr–Coulomb shear
/// strength τmax = c + p tan φ; Janosi & Hanamoto (1961) shear τ = τmax (1 − exp(−j/K)).
struct SoilParameters {
  std::string name;           ///< e.g. "LETE sand"
  double Bekker_n = 1.0;      ///< sinkage exponent n [-]
  double Bekker_Kc = 0.0;     ///< cohesive modulus kc [N/m^(n+1)]
  double Bekker_Kphi = 0.0;   ///< frictional modulus kφ [N/m^(n+2)]
  double Mohr_cohesion = 0.0; ///< cohesion c [Pa]
  double Mohr_friction = 0.0; ///< internal friction angle φ [rad]
  double Janosi_shear = 0.01; ///< shear deformation modulus K [m]
  /// SCM only: elastic unloading/reloading stiffness Ke [Pa/m] (Krenn & Hirzinger 2009).
  double elastic_K = 2e8;
  /// SCM only: normal damping R [Pa s/m], pressure −R·v_n added while in contact.
  double damping_R = 3e4;

  /// Bekker pressure [Pa] at sinkage z [m] (z ≤ 0 gives 0) for a patch of width b [m] > 0.
  double bekker_pressure(double z_m, double b_m) const;
  /// Mohr–Coulomb shear strength [Pa] at normal pressure σ [Pa].
  double shear_strength(double sigma_Pa) const;
  /// Janosi–Hanamoto shear stress [Pa] at normal pressure σ [Pa] and shear displacement j [m] ≥ 0.
  double shear_stress(double sigma_Pa, double j_m) const;
};

} // namespace wheelsim::scm
