// Wong & Reece (1967) driven rigid wheel, TERRAMECHANICS.md §3. Learned from the structure of
// melanz/wheel-soil and jcmadsen/pyTerramechanics (not copied): the two stress regions are
// integrated separately (tanh–sinh handles σ's (θ1 − θ)^n and (θ − θ2)^n end singularities).
#include "wheelsim/scm/wong_reece.h"

#include "numerics.h"

#include <cmath>

namespace wheelsim::scm {
namespace {

using detail::fmt10;
using detail::require;

constexpr double kHalfPi = 1.57079632679489661923;

void check_inputs(const char *f, const SoilParameters &soil, const WongReeceWheel &wheel,
                  double slip, const WongReeceOptions &o) {
  require(wheel.radius_m > 0 && std::isfinite(wheel.radius_m), f, "wheel radius", "> 0 m",
          wheel.radius_m);
  require(wheel.width_m > 0 && std::isfinite(wheel.width_m), f, "wheel width", "> 0 m",
          wheel.width_m);
  require(soil.Bekker_n > 0 && soil.Bekker_n <= 2, f, "soil n", "in (0, 2]", soil.Bekker_n);
  require(soil.Bekker_Kc >= 0, f, "soil kc", ">= 0 N/m^(n+1)", soil.Bekker_Kc);
  require(soil.Bekker_Kphi >= 0, f, "soil kphi", ">= 0 N/m^(n+2)", soil.Bekker_Kphi);
  require(soil.Bekker_Kc + soil.Bekker_Kphi > 0, f, "soil kc + kphi", "> 0",
          soil.Bekker_Kc + soil.Bekker_Kphi);
  require(soil.Mohr_cohesion >= 0, f, "soil cohesion", ">= 0 Pa", soil.Mohr_cohesion);
  require(soil.Mohr_friction >= 0 && soil.Mohr_friction < kHalfPi, f, "soil friction angle",
          "in [0, pi/2) rad", soil.Mohr_friction);
  require(soil.Janosi_shear > 0, f, "soil shear modulus K", "> 0 m", soil.Janosi_shear);
  require(slip >= 0 && slip <= 1, f, "slip", "in [0, 1] (driven wheel)", slip);
  require(o.c1 >= 0 && o.c1 < 1, f, "c1", "in [0, 1)", o.c1);
  require(o.c1 + o.c2 * slip >= 0 && o.c1 + o.c2 * slip < 1, f,
          "c1 + c2 s (theta_m / theta_1) at slip " + fmt10(slip), "in [0, 1)", o.c1 + o.c2 * slip);
  require(o.rebound_ratio >= 0 && o.rebound_ratio <= 1, f, "rebound ratio", "in [0, 1]",
          o.rebound_ratio);
  require(o.quadrature_points >= 9, f, "quadrature points", ">= 9", o.quadrature_points);
  require(o.distribution_points == 0 || o.distribution_points >= 2, f, "distribution points",
          "0 or >= 2", o.distribution_points);
}

/// The stress field at one entry angle.
struct Field {
  const SoilParameters &soil;
  double R, b, s, k, theta1, theta2, thetam, cos1, sin1, tan_phi;

  Field(const SoilParameters &so, const WongReeceWheel &w, double th1, double slip,
        const WongReeceOptions &o)
      : soil(so), R(w.radius_m), b(w.width_m), s(slip),
        k((so.Bekker_Kc / w.width_m + so.Bekker_Kphi) * std::pow(w.radius_m, so.Bekker_n)),
        theta1(th1), cos1(std::cos(th1)), sin1(std::sin(th1)), tan_phi(std::tan(so.Mohr_friction)) {
    const double z = R * (1.0 - cos1);
    // λ = 0: θ2 = 0 exactly (not −0).
    theta2 = o.rebound_ratio > 0 ? -std::acos(1.0 - o.rebound_ratio * z / R) : 0.0;
    thetam = (o.c1 + o.c2 * slip) * theta1;
  }

  double sigma(double th) const {
    double arg = th;
    if (th < thetam) {
      if (!(thetam > theta2))
        return 0.0;
      arg = theta1 - (th - theta2) * (theta1 - thetam) / (thetam - theta2);
    }
    const double dz = std::cos(arg) - cos1;
    return dz > 0 ? k * std::pow(dz, soil.Bekker_n) : 0.0;
  }
  double j(double th) const { return R * ((theta1 - th) - (1.0 - s) * (sin1 - std::sin(th))); }
  double tau(double th, double sig) const {
    return (soil.Mohr_cohesion + sig * tan_phi) * (1.0 - std::exp(-j(th) / soil.Janosi_shear));
  }
};

struct Forces {
  double vertical, drawbar, torque;
};

Forces integrate(const Field &f, int points) {
  auto region = [&](double a, double b) {
    Forces out{0, 0, 0};
    if (!(b > a))
      return out;
    out.vertical = detail::tanh_sinh(
        [&](double th) {
          const double sg = f.sigma(th);
          return sg * std::cos(th) + f.tau(th, sg) * std::sin(th);
        },
        a, b, points);
    out.drawbar = detail::tanh_sinh(
        [&](double th) {
          const double sg = f.sigma(th);
          return f.tau(th, sg) * std::cos(th) - sg * std::sin(th);
        },
        a, b, points);
    out.torque = detail::tanh_sinh([&](double th) { return f.tau(th, f.sigma(th)); }, a, b, points);
    return out;
  };
  const Forces rear = region(f.theta2, f.thetam), front = region(f.thetam, f.theta1);
  return {f.R * f.b * (rear.vertical + front.vertical), f.R * f.b * (rear.drawbar + front.drawbar),
          f.R * f.R * f.b * (rear.torque + front.torque)};
}

WongReeceResult make_result(const SoilParameters &soil, const WongReeceWheel &wheel, double theta1,
                            double slip, const WongReeceOptions &o) {
  const Field f(soil, wheel, theta1, slip, o);
  const Forces F = integrate(f, o.quadrature_points);
  WongReeceResult r;
  r.slip = slip;
  r.entry_angle_rad = theta1;
  r.exit_angle_rad = f.theta2;
  r.max_stress_angle_rad = f.thetam;
  r.sinkage_m = wheel.radius_m * (1.0 - f.cos1);
  r.vertical_force_N = F.vertical;
  r.load_N = F.vertical;
  r.drawbar_pull_N = F.drawbar;
  r.torque_Nm = F.torque;
  r.traction_force_N = F.torque / wheel.radius_m;
  r.tractive_efficiency =
      r.traction_force_N > 0 ? r.drawbar_pull_N * (1.0 - slip) / r.traction_force_N : 0.0;
  if (o.distribution_points > 0) {
    const int m = o.distribution_points;
    r.distribution.reserve(m);
    for (int i = 0; i < m; ++i) {
      const double th = f.theta2 + (f.theta1 - f.theta2) * i / (m - 1);
      WongReeceStress p;
      p.theta_rad = th;
      p.sigma_Pa = f.sigma(th);
      p.tau_Pa = f.tau(th, p.sigma_Pa);
      p.shear_displacement_m = f.j(th);
      r.distribution.push_back(p);
    }
  }
  return r;
}

} // namespace

WongReeceResult evaluate_wong_reece(const SoilParameters &soil, const WongReeceWheel &wheel,
                                    double entry_angle_rad, double slip,
                                    const WongReeceOptions &options) {
  const char *f = "evaluate_wong_reece";
  check_inputs(f, soil, wheel, slip, options);
  require(entry_angle_rad > 0 && entry_angle_rad <= kHalfPi, f, "entry angle", "in (0, pi/2] rad",
          entry_angle_rad);
  return make_result(soil, wheel, entry_angle_rad, slip, options);
}

WongReeceResult solve_wong_reece(const SoilParameters &soil, const WongReeceWheel &wheel,
                                 double load_N, double slip, const WongReeceOptions &options) {
  const char *f = "solve_wong_reece";
  check_inputs(f, soil, wheel, slip, options);
  require(load_N > 0 && std::isfinite(load_N), f, "load", "> 0 N", load_N);
  WongReeceOptions quiet = options;
  quiet.distribution_points = 0;
  auto residual = [&](double theta1) {
    if (theta1 <= 0)
      return -load_N;
    return integrate(Field(soil, wheel, theta1, slip, quiet), quiet.quadrature_points).vertical -
           load_N;
  };
  // Scan θ1 upwards for the first sign change (the smallest sinkage that carries W).
  constexpr int scan_steps = 64;
  double lo = 0.0, g_lo = -load_N;
  for (int i = 1; i <= scan_steps; ++i) {
    const double hi = kHalfPi * i / scan_steps;
    const double g_hi = residual(hi);
    if (g_hi >= 0) {
      const double theta1 = detail::brent_root(residual, lo, hi, g_lo, g_hi, 1e-12, 0.0);
      WongReeceResult r = make_result(soil, wheel, theta1, slip, options);
      r.load_N = load_N;
      return r;
    }
    lo = hi;
    g_lo = g_hi;
  }
  throw TerramechanicsError(std::string(f) + ": the soil \"" + soil.name + "\" cannot carry " +
                            fmt10(load_N) + " N on this wheel (R = " + fmt10(wheel.radius_m) +
                            " m, b = " + fmt10(wheel.width_m) + " m) at slip " + fmt10(slip) +
                            ": at entry angle 90 deg (sinkage = R) the vertical force is " +
                            fmt10(g_lo + load_N) + " N");
}

} // namespace wheelsim::scm
