// Lug footprints on the unrolled lug-top surface: s = R_out * theta [m] along the circumference,
// y [m] along the axle.
#pragma once

#include <vector>

#include "wheel_spec.h"

namespace wheelsim::meshes {

/// One straight piece of a lug centreline, extended to a line: s = a + b y, with the
/// circumferential half-thickness d = (t/2) sqrt(1 + b^2) (the perpendicular half-width t/2
/// measured along s).
struct LugLine {
  double a_m;
  double b;
  double d_m;
};

/// A lug footprint: for y in [y0, y1] the lug covers s in [leading(y), trailing(y)].
/// The centreline is convex in the local coordinate u (u = max of `lines`); the mitred boundaries
/// are u_lo(y) = max_i(a_i + b_i y - d_i), u_hi(y) = max_i(a_i + b_i y + d_i), and
/// s = s0 + sign * u. Lines are ordered by slope b.
struct LugFootprint {
  double y0_m, y1_m;
  std::vector<LugLine> lines;
  double sign; // +1 or -1
  double s0_m;
  /// Smaller-s boundary L(y) [m] (faces -theta).
  double leading(double y) const;
  /// Larger-s boundary T(y) [m] (faces +theta: the face that pushes soil back under forward
  /// driving, the "working face").
  double trailing(double y) const;
  /// y values in (y0, y1) where leading or trailing has a kink.
  std::vector<double> kinks() const;
};

/// All lugs of the wheel (nl for straight and combined, 2 nl half-lugs for nondirectional),
/// lug k (or pair k) placed at s0 = k * 2 pi R_out / nl. Empty for smooth wheels.
std::vector<LugFootprint> lug_layout(const WheelSpec &spec);

} // namespace wheelsim::meshes
