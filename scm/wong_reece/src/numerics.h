// Numerical helpers of the Wong–Reece library (internal): tanh–sinh quadrature, which integrates
// the endpoint singularities of the Bekker stresses ((θ1 − θ)^n, n < 1) to machine precision,
// Brent's bracketed root finder, and the library's argument checks.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace wheelsim::scm::detail {

/// `v` with 10 significant digits, for error messages that name a value.
inline std::string fmt10(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

/// Throws std::invalid_argument "<function>: <argument> must be <range>, got <v>" unless `ok`.
inline void require(bool ok, const char *function, const std::string &argument, const char *range,
                    double v) {
  if (!ok)
    throw std::invalid_argument(std::string(function) + ": " + argument + " must be " + range +
                                ", got " + fmt10(v));
}

/// ∫_a^b f(x) dx by the tanh–sinh (double-exponential) rule with `points` nodes (odd, ≥ 3; an
/// even count is raised by one). Nodes near the ends are placed by their distance to the end, so
/// f is never evaluated outside [a, b]; f may be singular (integrably) at either end.
inline double tanh_sinh(const std::function<double(double)> &f, double a, double b, int points) {
  if (!(b > a))
    return 0.0;
  constexpr double half_pi = 1.57079632679489661923;
  // Beyond t = 3.15 the nodes are closer to the ends than double precision resolves.
  constexpr double t_max = 3.15;
  const int m = std::max(1, points / 2);
  const double h = t_max / m;
  const double d = 0.5 * (b - a);
  double sum = 0.0;
  for (int k = -m; k <= m; ++k) {
    const double t = k * h;
    const double u = half_pi * std::sinh(t);
    const double cu = std::cosh(u);
    const double w = h * d * half_pi * std::cosh(t) / (cu * cu);
    if (w == 0.0)
      continue;
    // Distance of the node from the nearer end: d (1 − tanh|u|) = 2 d / (exp(2|u|) + 1).
    const double gap = 2.0 * d / (std::exp(2.0 * std::abs(u)) + 1.0);
    const double x = k == 0 ? a + d : (k > 0 ? b - gap : a + gap);
    sum += w * f(x);
  }
  return sum;
}

/// ∫_a^b f dx to relative tolerance `rel_tol`: tanh–sinh with the node count doubled until two
/// successive results agree (at most 2^14 + 1 nodes; throws std::runtime_error if not reached).
inline double tanh_sinh_adaptive(const std::function<double(double)> &f, double a, double b,
                                 double rel_tol) {
  double prev = tanh_sinh(f, a, b, 33);
  for (int points = 65; points <= (1 << 14) + 1; points = 2 * points - 1) {
    const double cur = tanh_sinh(f, a, b, points);
    if (std::abs(cur - prev) <= rel_tol * std::abs(cur) || cur == 0.0)
      return cur;
    prev = cur;
  }
  throw std::runtime_error("tanh-sinh quadrature did not converge to the requested tolerance");
}

/// A root of g in [a, b] (g(a), g(b) of opposite sign or zero) by Brent's method (inverse
/// quadratic interpolation safeguarded by bisection), to |x − root| ≤ rel_tol |x| + abs_tol.
inline double brent_root(const std::function<double(double)> &g, double a, double b, double fa,
                         double fb, double rel_tol, double abs_tol) {
  if (fa == 0.0)
    return a;
  if (fb == 0.0)
    return b;
  if ((fa > 0) == (fb > 0))
    throw std::logic_error("brent_root: the interval does not bracket a root");
  double c = a, fc = fa, d = b - a, e = d;
  for (int iter = 0; iter < 200; ++iter) {
    if ((fb > 0) == (fc > 0)) { // keep the root between b and c
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) { // b is the best estimate
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tol = 2.0 * std::numeric_limits<double>::epsilon() * std::abs(b) +
                       0.5 * (rel_tol * std::abs(b) + abs_tol);
    const double mid = 0.5 * (c - b);
    if (std::abs(mid) <= tol || fb == 0.0)
      return b;
    if (std::abs(e) >= tol && std::abs(fa) > std::abs(fb)) {
      // Interpolation: secant (a == c) or inverse quadratic.
      double p, q;
      const double s = fb / fa;
      if (a == c) {
        p = 2.0 * mid * s;
        q = 1.0 - s;
      } else {
        const double qa = fa / fc, r = fb / fc;
        p = s * (2.0 * mid * qa * (qa - r) - (b - a) * (r - 1.0));
        q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0)
        q = -q;
      else
        p = -p;
      if (2.0 * p < std::min(3.0 * mid * q - std::abs(tol * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = mid;
        e = d;
      }
    } else {
      d = mid;
      e = d;
    }
    a = b;
    fa = fb;
    b += std::abs(d) > tol ? d : (mid > 0 ? tol : -tol);
    fb = g(b);
  }
  throw std::runtime_error("brent_root: no convergence in 200 iterations");
}

} // namespace wheelsim::scm::detail
