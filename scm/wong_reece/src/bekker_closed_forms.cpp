// Rigid-wheel closed forms, TERRAMECHANICS.md §2 (Bekker 1956/1969; Wong, Theory of Ground
// Vehicles, ch. 2).
#include "wheelsim/scm/bekker_closed_forms.h"

#include "numerics.h"

#include <cmath>

namespace wheelsim::scm {
namespace {

using detail::fmt10;
using detail::require;

void check_wheel(const char *function, double radius_m, double width_m) {
  require(radius_m > 0 && std::isfinite(radius_m), function, "radius", "> 0 m", radius_m);
  require(width_m > 0 && std::isfinite(width_m), function, "width", "> 0 m", width_m);
}

void check_soil(const char *function, const SoilParameters &soil) {
  require(soil.Bekker_n > 0 && soil.Bekker_n <= 2, function, "soil n", "in (0, 2]", soil.Bekker_n);
  require(soil.Bekker_Kc >= 0, function, "soil kc", ">= 0 N/m^(n+1)", soil.Bekker_Kc);
  require(soil.Bekker_Kphi >= 0, function, "soil kphi", ">= 0 N/m^(n+2)", soil.Bekker_Kphi);
  require(soil.Bekker_Kc + soil.Bekker_Kphi > 0, function, "soil kc + kphi", "> 0",
          soil.Bekker_Kc + soil.Bekker_Kphi);
}

/// b k R^(n+1) ∫_0^θ1 (cos θ − cos θ1)^n cos θ dθ: the front-half load at entry angle θ1.
double front_half_load(const SoilParameters &soil, double radius_m, double width_m,
                       double sinkage_m) {
  if (sinkage_m <= 0)
    return 0.0;
  const double theta1 = std::acos(1.0 - sinkage_m / radius_m);
  const double n = soil.Bekker_n;
  const double c1 = std::cos(theta1);
  const double integral = detail::tanh_sinh_adaptive(
      [&](double th) {
        const double dz = std::cos(th) - c1;
        return dz > 0 ? std::pow(dz, n) * std::cos(th) : 0.0;
      },
      0.0, theta1, 1e-14);
  return width_m * bekker_modulus(soil, width_m) * std::pow(radius_m, n + 1) * integral;
}

/// z0 in (0, R] with load(z0) = W; TerramechanicsError if load(R) < W.
template <class Load>
double solve_sinkage(const char *function, const char *model, double radius_m, double load_N,
                     Load load) {
  require(load_N > 0 && std::isfinite(load_N), function, "load", "> 0 N", load_N);
  const double w_max = load(radius_m);
  if (w_max < load_N)
    throw TerramechanicsError(std::string(function) + ": the " + model + " cannot carry " +
                              fmt10(load_N) + " N: at sinkage = radius (" + fmt10(radius_m) +
                              " m) it carries only " + fmt10(w_max) + " N");
  return detail::brent_root([&](double z) { return load(z) - load_N; }, 0.0, radius_m, -load_N,
                            w_max - load_N, 1e-12, 0.0);
}

} // namespace

double bekker_modulus(const SoilParameters &soil, double width_m) {
  require(width_m > 0, "bekker_modulus", "width", "> 0 m", width_m);
  return soil.Bekker_Kc / width_m + soil.Bekker_Kphi;
}

double rolling_sinkage_closed_form_m(const SoilParameters &soil, double radius_m, double width_m,
                                     double load_N) {
  const char *f = "rolling_sinkage_closed_form_m";
  check_wheel(f, radius_m, width_m);
  check_soil(f, soil);
  require(load_N > 0 && std::isfinite(load_N), f, "load", "> 0 N", load_N);
  require(soil.Bekker_n < 3, f, "soil n", "< 3", soil.Bekker_n);
  const double n = soil.Bekker_n;
  const double diameter = 2.0 * radius_m;
  return std::pow(
      3.0 * load_N /
          ((3.0 - n) * (soil.Bekker_Kc + width_m * soil.Bekker_Kphi) * std::sqrt(diameter)),
      2.0 / (2.0 * n + 1.0));
}

double rolling_closed_form_load_N(const SoilParameters &soil, double radius_m, double width_m,
                                  double sinkage_m) {
  const char *f = "rolling_closed_form_load_N";
  check_wheel(f, radius_m, width_m);
  check_soil(f, soil);
  require(sinkage_m >= 0, f, "sinkage", ">= 0 m", sinkage_m);
  const double n = soil.Bekker_n;
  return (3.0 - n) * (soil.Bekker_Kc + width_m * soil.Bekker_Kphi) * std::sqrt(2.0 * radius_m) *
         std::pow(sinkage_m, (2.0 * n + 1.0) / 2.0) / 3.0;
}

double rolling_load_N(const SoilParameters &soil, double radius_m, double width_m,
                      double sinkage_m) {
  const char *f = "rolling_load_N";
  check_wheel(f, radius_m, width_m);
  check_soil(f, soil);
  require(sinkage_m >= 0 && sinkage_m <= radius_m, f, "sinkage", "in [0, radius] m", sinkage_m);
  return front_half_load(soil, radius_m, width_m, sinkage_m);
}

double standing_load_N(const SoilParameters &soil, double radius_m, double width_m,
                       double sinkage_m) {
  const char *f = "standing_load_N";
  check_wheel(f, radius_m, width_m);
  check_soil(f, soil);
  require(sinkage_m >= 0 && sinkage_m <= radius_m, f, "sinkage", "in [0, radius] m", sinkage_m);
  return 2.0 * front_half_load(soil, radius_m, width_m, sinkage_m);
}

double rolling_sinkage_integral_m(const SoilParameters &soil, double radius_m, double width_m,
                                  double load_N) {
  const char *f = "rolling_sinkage_integral_m";
  check_wheel(f, radius_m, width_m);
  check_soil(f, soil);
  return solve_sinkage(f, "front half of the contact (rolling wheel)", radius_m, load_N,
                       [&](double z) { return front_half_load(soil, radius_m, width_m, z); });
}

double standing_sinkage_m(const SoilParameters &soil, double radius_m, double width_m,
                          double load_N) {
  const char *f = "standing_sinkage_m";
  check_wheel(f, radius_m, width_m);
  check_soil(f, soil);
  return solve_sinkage(f, "full chord of the contact (standing wheel)", radius_m, load_N,
                       [&](double z) { return 2.0 * front_half_load(soil, radius_m, width_m, z); });
}

double compaction_resistance_N(const SoilParameters &soil, double width_m, double sinkage_m) {
  const char *f = "compaction_resistance_N";
  require(width_m > 0, f, "width", "> 0 m", width_m);
  check_soil(f, soil);
  require(sinkage_m >= 0, f, "sinkage", ">= 0 m", sinkage_m);
  const double n = soil.Bekker_n;
  return width_m * bekker_modulus(soil, width_m) * std::pow(sinkage_m, n + 1.0) / (n + 1.0);
}

} // namespace wheelsim::scm
