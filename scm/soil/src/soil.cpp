// The three soil laws of TERRAMECHANICS.md §1 (Bekker; Mohr–Coulomb; Janosi & Hanamoto).
#include "wheelsim/scm/soil.h"

#include <cmath>

namespace wheelsim::scm {

double SoilParameters::bekker_pressure(double z_m, double b_m) const {
  if (z_m <= 0.0)
    return 0.0;
  return (Bekker_Kc / b_m + Bekker_Kphi) * std::pow(z_m, Bekker_n);
}

double SoilParameters::shear_strength(double sigma_Pa) const {
  return Mohr_cohesion + sigma_Pa * std::tan(Mohr_friction);
}

double SoilParameters::shear_stress(double sigma_Pa, double j_m) const {
  return shear_strength(sigma_Pa) * (1.0 - std::exp(-j_m / Janosi_shear));
}

} // namespace wheelsim::scm
