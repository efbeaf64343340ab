#include "lug_layout.h"

#include <algorithm>
#include <cmath>

namespace wheelsim::meshes {
namespace {

double upper_envelope(const std::vector<LugLine> &lines, double y, double offset_sign) {
  double u = -HUGE_VAL;
  for (const LugLine &l : lines) {
    u = std::max(u, l.a_m + l.b * y + offset_sign * l.d_m);
  }
  return u;
}

LugLine make_line(double a_m, double b, double thickness_m) {
  return {a_m, b, 0.5 * thickness_m * std::sqrt(1.0 + b * b)};
}

} // namespace

double LugFootprint::leading(double y) const {
  return sign > 0 ? s0_m + upper_envelope(lines, y, -1.0) : s0_m - upper_envelope(lines, y, +1.0);
}

double LugFootprint::trailing(double y) const {
  return sign > 0 ? s0_m + upper_envelope(lines, y, +1.0) : s0_m - upper_envelope(lines, y, -1.0);
}

std::vector<double> LugFootprint::kinks() const {
  std::vector<double> ys;
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
    const LugLine &p = lines[i], &q = lines[i + 1];
    if (q.b == p.b)
      continue;
    for (double side : {-1.0, +1.0}) {
      // a_p + b_p y + side d_p = a_q + b_q y + side d_q
      const double y = (p.a_m - q.a_m + side * (p.d_m - q.d_m)) / (q.b - p.b);
      if (y > y0_m && y < y1_m)
        ys.push_back(y);
    }
  }
  return ys;
}

std::vector<LugFootprint> lug_layout(const WheelSpec &spec) {
  std::vector<LugFootprint> lugs;
  if (spec.smooth)
    return lugs;
  const double pi = std::acos(-1.0);
  const double tan_d = std::tan(spec.lug_angle_deg * pi / 180.0);
  const double half_w = 0.5 * spec.width_m;
  const double half_h = 0.5 * spec.centre_length_m;
  const double t = spec.lug_width_m;
  const double pitch_m = 2.0 * pi * spec.outer_radius_m() / spec.lug_count;

  for (int k = 0; k < spec.lug_count; ++k) {
    const double s_k = k * pitch_m;
    switch (spec.type) {
    case LugType::straight:
      // One full-width bar s = y tan(delta): its +y end is at larger theta.
      lugs.push_back({-half_w, half_w, {make_line(0.0, tan_d, t)}, +1.0, s_k});
      break;
    case LugType::combined:
      // V in u: arms u = (|y| - h/2) tan(delta), centre u = 0; s = -u puts the centre segment at
      // the largest theta, so it meets the soil first when rolling forward (see docs).
      lugs.push_back({-half_w,
                      half_w,
                      {make_line(-half_h * tan_d, -tan_d, t), make_line(0.0, 0.0, t),
                       make_line(-half_h * tan_d, tan_d, t)},
                      -1.0,
                      s_k});
      break;
    case LugType::nondirectional:
      // Left half-lug over y in [-w/2, h/2] and right half-lug over [-h/2, w/2], both on the
      // line s = y tan(delta) through the tread centre; the right one is shifted by half a pitch.
      // The right half-lug is the point reflection (s, y) -> (-s, -y) of the left one (a 180 deg
      // rotation about the radial axis at the tread centre), so the tread is unchanged by turning
      // the wheel around: it works the same in both rotation directions.
      lugs.push_back({-half_w, half_h, {make_line(0.0, tan_d, t)}, +1.0, s_k});
      lugs.push_back({-half_h, half_w, {make_line(0.0, tan_d, t)}, +1.0, s_k + 0.5 * pitch_m});
      break;
    }
  }
  return lugs;
}

} // namespace wheelsim::meshes
