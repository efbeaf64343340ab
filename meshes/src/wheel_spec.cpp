#include "wheel_spec.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace wheelsim::meshes {

double estimated_triangle_count(const WheelSpec &s) {
  const double pi = std::acos(-1.0);
  const Resolution &r = s.resolution;
  const double outer = 0.5 * s.diameter_m;
  const double segment_rad = std::min(r.max_arc_m / outer, r.max_angle_deg * pi / 180.0);
  const double segments = std::ceil(2.0 * pi / segment_rad);
  const double bands = std::ceil(s.width_m / r.max_width_edge_m) + (s.smooth ? 0 : 4);
  const double rings = std::ceil(s.rim_radius_m() / r.max_width_edge_m) + 1;
  return segments * (2.0 * bands * (s.smooth ? 1.0 : 2.0) + 2.0 * 2.0 * rings);
}

const char *to_string(LugType type) {
  switch (type) {
  case LugType::straight:
    return "straight";
  case LugType::combined:
    return "combined";
  case LugType::nondirectional:
    return "nondirectional";
  }
  return "?";
}

LugType parse_lug_type(const std::string &name) {
  if (name == "straight")
    return LugType::straight;
  if (name == "combined")
    return LugType::combined;
  if (name == "nondirectional")
    return LugType::nondirectional;
  throw WheelSpecError("--type '" + name + "': expected straight, combined or nondirectional");
}

namespace {

void check_triangle_count(const WheelSpec &s) {
  const double n = estimated_triangle_count(s);
  if (n <= kMaxEstimatedTriangles)
    return;
  std::ostringstream os;
  os << "--max-arc " << s.resolution.max_arc_m << " m, --max-angle " << s.resolution.max_angle_deg
     << " deg, --max-width-edge " << s.resolution.max_width_edge_m << " m: the mesh of this "
     << s.diameter_m << " m x " << s.width_m << " m wheel would have about " << n
     << " triangles (at most " << kMaxEstimatedTriangles
     << "); coarsen the resolution (the study wheels use 0.008 m, 3 deg, 0.02 m)";
  throw WheelSpecError(os.str());
}

} // namespace

void validate(const WheelSpec &s) {
  if (!(s.diameter_m > 0.0) || !std::isfinite(s.diameter_m)) {
    fail_value<WheelSpecError>("--diameter", s.diameter_m, "m", "the outer diameter must be > 0 m");
  }
  if (!(s.width_m > 0.0) || !std::isfinite(s.width_m)) {
    fail_value<WheelSpecError>("--width", s.width_m, "m", "the width must be > 0 m");
  }
  check_plausible<WheelSpecError>("--diameter", s.diameter_m, kPlausibleDiameter_m,
                                  "a wheel diameter");
  check_plausible<WheelSpecError>("--width", s.width_m, kPlausibleWidth_m, "a wheel width");
  const Resolution &r = s.resolution;
  if (!(r.max_arc_m > 0.0))
    fail_value<WheelSpecError>("--max-arc", r.max_arc_m, "m", "must be > 0 m");
  if (!(r.max_angle_deg > 0.0 && r.max_angle_deg <= 45.0)) {
    fail_value<WheelSpecError>("--max-angle", r.max_angle_deg, "deg", "must be in (0, 45] deg");
  }
  if (!(r.max_width_edge_m > 0.0)) {
    fail_value<WheelSpecError>("--max-width-edge", r.max_width_edge_m, "m", "must be > 0 m");
  }
  if (s.smooth) {
    if (s.lug_count != 0) {
      fail_value<WheelSpecError>("--lugs", s.lug_count, "",
                                 "a smooth wheel has no lugs: drop --lugs or --smooth");
    }
    check_triangle_count(s);
    return;
  }
  if (s.lug_count < 1) {
    std::ostringstream os;
    os << "--lugs " << s.lug_count << " with --type " << to_string(s.type)
       << ": a lugged wheel needs at least 1 lug (use --smooth for a smooth cylinder)";
    throw WheelSpecError(os.str());
  }
  if (s.lug_count > 1000)
    fail_value<WheelSpecError>("--lugs", s.lug_count, "", "at most 1000 lugs");
  if (!(s.lug_height_m > 0.0)) {
    fail_value<WheelSpecError>("--lug-height", s.lug_height_m, "m",
                               "must be > 0 m (use --smooth for no lugs)");
  }
  if (!(s.lug_height_m < 0.5 * s.diameter_m)) {
    std::ostringstream os;
    os << "must be less than the outer radius D0/2 = " << 0.5 * s.diameter_m
       << " m (the rim radius D0/2 - lh must stay > 0)"
       << metres_hint("--lug-height", s.lug_height_m, kPlausibleLugHeight_m);
    fail_value<WheelSpecError>("--lug-height", s.lug_height_m, "m", os.str());
  }
  check_plausible<WheelSpecError>("--lug-height", s.lug_height_m, kPlausibleLugHeight_m,
                                  "a lug height");
  if (!(s.lug_width_m > 0.0))
    fail_value<WheelSpecError>("--lug-width", s.lug_width_m, "m", "must be > 0 m");
  check_plausible<WheelSpecError>("--lug-width", s.lug_width_m, kPlausibleLugWidth_m,
                                  "a lug width");
  if (!(s.lug_angle_deg >= 0.0 && s.lug_angle_deg <= 70.0)) {
    fail_value<WheelSpecError>("--lug-angle", s.lug_angle_deg, "deg",
                               "must be in [0, 70] deg (angle to the axle)");
  }
  if (s.type != LugType::straight) {
    if (!(s.centre_length_m >= 0.0 && s.centre_length_m < s.width_m)) {
      std::ostringstream os;
      os << "the centre length must be in [0, w) = [0, " << s.width_m << ") m for "
         << to_string(s.type) << " lugs";
      fail_value<WheelSpecError>("--centre-length", s.centre_length_m, "m", os.str());
    }
  }
  check_triangle_count(s);
}

std::string describe(const WheelSpec &s) {
  std::ostringstream os;
  os << "D0 " << s.diameter_m << " m, w " << s.width_m << " m, ";
  if (s.smooth) {
    os << "smooth";
  } else {
    os << s.lug_count << " " << to_string(s.type) << " lugs, lh " << s.lug_height_m
       << " m, lug width " << s.lug_width_m << " m, angle " << s.lug_angle_deg << " deg";
    if (s.type != LugType::straight)
      os << ", h " << s.centre_length_m << " m";
  }
  return os.str();
}

} // namespace wheelsim::meshes
