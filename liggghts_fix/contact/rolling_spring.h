// The update of wheelsim's rolling springs (`rolling_friction krot` and `epsdt`), shared by their
// two sides: the wheel contact of fix wheel/cosim (models/rolling_krot.h, models/rolling_epsdt.h)
// and LIGGGHTS' pair style and walls (../rolling_model_krot.h, ../rolling_model_epsdt.h). Plain
// doubles, no Eigen and no LIGGGHTS headers, so that both sides include it and compute the same
// numbers. docs/contact-law.md, "Rolling: rolling_friction krot" and "... epsdt".
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

/// The plastic limit of `epsdt` (as epsd2's): a moment longer than `cap` [N·m] (>= 0) is scaled
/// back to length `cap`, keeping its direction. In place.
inline void cap_rolling_moment(double moment[3], double cap) {
  const double mag =
      std::sqrt(moment[0] * moment[0] + moment[1] * moment[1] + moment[2] * moment[2]);
  if (mag > cap) {
    const double factor = cap / mag;
    for (int k = 0; k < 3; ++k)
      moment[k] *= factor;
  }
}

} // namespace wheelsim::contact
