// Validation of soil, settings and step (see settings_check.h).
#include "settings_check.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace wheelsim::scm::detail {

namespace {
[[noreturn]] void fail(const std::string &what, const std::string &expected, double got) {
  std::ostringstream os;
  os.precision(12);
  os << "scm " << what << " must be " << expected << ", got " << got;
  throw std::invalid_argument(os.str());
}
} // namespace

void check_soil(const SoilParameters &s) {
  if (!(s.Bekker_n > 0.0 && std::isfinite(s.Bekker_n)))
    fail("soil Bekker_n", "> 0 (sinkage exponent, -)", s.Bekker_n);
  if (!(s.Bekker_Kc >= 0.0 && std::isfinite(s.Bekker_Kc)))
    fail("soil Bekker_Kc", ">= 0 N/m^(n+1)", s.Bekker_Kc);
  if (!(s.Bekker_Kphi >= 0.0 && std::isfinite(s.Bekker_Kphi)))
    fail("soil Bekker_Kphi", ">= 0 N/m^(n+2)", s.Bekker_Kphi);
  if (!(s.Bekker_Kc + s.Bekker_Kphi > 0.0))
    fail("soil Bekker_Kc + Bekker_Kphi", "> 0 (a soil that carries load)",
         s.Bekker_Kc + s.Bekker_Kphi);
  if (!(s.Mohr_cohesion >= 0.0 && std::isfinite(s.Mohr_cohesion)))
    fail("soil Mohr_cohesion", ">= 0 Pa", s.Mohr_cohesion);
  if (!(s.Mohr_friction >= 0.0 && s.Mohr_friction < M_PI / 2))
    fail("soil Mohr_friction", "in [0, pi/2) rad", s.Mohr_friction);
  if (!(s.Janosi_shear > 0.0 && std::isfinite(s.Janosi_shear)))
    fail("soil Janosi_shear", "> 0 m", s.Janosi_shear);
  if (!(s.elastic_K > 0.0 && std::isfinite(s.elastic_K)))
    fail("soil elastic_K", "> 0 Pa/m", s.elastic_K);
  if (!(s.damping_R >= 0.0 && std::isfinite(s.damping_R)))
    fail("soil damping_R", ">= 0 Pa s/m", s.damping_R);
}

void check_settings(const ScmSettings &s) {
  if (!(s.grid_spacing_m > 0.0 && std::isfinite(s.grid_spacing_m)))
    fail("grid_spacing", "> 0 m", s.grid_spacing_m);
  if (!std::isfinite(s.surface_height_m))
    fail("surface_height", "finite (m)", s.surface_height_m);
  const BulldozingSettings &b = s.bulldozing;
  if (!(b.erosion_angle_deg > 0.0 && b.erosion_angle_deg < 90.0))
    fail("bulldozing erosion_angle", "in (0, 90) deg", b.erosion_angle_deg);
  if (!(b.flow_factor >= 0.0 && std::isfinite(b.flow_factor)))
    fail("bulldozing flow_factor", ">= 0", b.flow_factor);
  if (b.erosion_iterations < 0)
    fail("bulldozing erosion_iterations", ">= 0", b.erosion_iterations);
  if (b.erosion_rings < 1)
    fail("bulldozing erosion_rings", ">= 1", b.erosion_rings);
  if (s.shear_radius_m && !(*s.shear_radius_m > 0.0 && std::isfinite(*s.shear_radius_m)))
    fail("shear_radius", "> 0 m (unset: the wheel surface)", *s.shear_radius_m);
  if (s.domain_m) {
    const Eigen::Vector4d &d = *s.domain_m;
    if (!d.allFinite())
      throw std::invalid_argument("scm domain must be finite (x_min, x_max, y_min, y_max) in m");
    if (!(d[0] < d[1]))
      fail("domain x_max", "> x_min = " + std::to_string(d[0]) + " m", d[1]);
    if (!(d[2] < d[3]))
      fail("domain y_max", "> y_min = " + std::to_string(d[2]) + " m", d[3]);
  }
}

void check_time_step(double dt) {
  if (!(dt > 0.0 && std::isfinite(dt)))
    fail("time step dt", "> 0 s", dt);
}

} // namespace wheelsim::scm::detail
