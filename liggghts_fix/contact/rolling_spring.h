// The update of `rolling_friction krot`'s spring, shared by its two sides: the wheel contact of
// fix wheel/cosim (models/rolling_krot.h) and LIGGGHTS' pair style and walls
// (../rolling_model_krot.h). Plain doubles, no Eigen and no LIGGGHTS headers, so that both include
// it and compute the same numbers. docs/contact-law.md, "Rolling: rolling_friction krot".
#pragma once

#include <cmath>

namespace wheelsim::contact {

/// One step of the spring. `moment` [N·m], the stored moment (the first body feels −moment), is
/// turned into the plane normal to the unit contact normal `n` (its normal part removed, its
/// magnitude kept), then grows by `k_dt` [N·m/rad · s] = k_r dt times the relative spin `spin`
/// [rad/s] without its part along n (no twist). In place.
inline void advance_rolling_spring(double moment[3], const double n[3], const double spin[3],
                                   double k_dt) {
  double w[3] = {spin[0], spin[1], spin[2]};
  const double wn = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
  for (int k = 0; k < 3; ++k)
    w[k] -= wn * n[k];
  const double before =
      std::sqrt(moment[0] * moment[0] + moment[1] * moment[1] + moment[2] * moment[2]);
  if (before > 0.0) {
    const double mn = moment[0] * n[0] + moment[1] * n[1] + moment[2] * n[2];
    for (int k = 0; k < 3; ++k)
      moment[k] -= mn * n[k];
    const double after =
        std::sqrt(moment[0] * moment[0] + moment[1] * moment[1] + moment[2] * moment[2]);
    const double scale = after > 0.0 ? before / after : 0.0;
    for (int k = 0; k < 3; ++k)
      moment[k] *= scale;
  }
  for (int k = 0; k < 3; ++k)
    moment[k] += k_dt * w[k];
}

} // namespace wheelsim::contact
