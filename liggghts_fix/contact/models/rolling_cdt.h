// `rolling_friction cdt`: constant directional torque μr kn δ (R − δ/2) against the spin
// (LIGGGHTS rolling_model_cdt.h, wall branch). docs/contact-law.md, "Rolling: rolling_friction
// cdt".
#pragma once

#include "contact_model.h"

namespace wheelsim::contact::rolling_cdt {

constexpr PropertySpec kProperties[] = {kCoefficientRollingFriction};

constexpr ModelSpec spec{"cdt",
                         nullptr,
                         "constant torque μr kn δ (R − δ/2) against the spin",
                         "rolling_model_cdt.h",
                         kProperties,
                         {}};

/// The torque's normal (torsion) part is removed. kn δ is the elastic Hertz force for hertz; for
/// edinburgh it is k1 δ (k1 the loading coefficient), as LIGGGHTS' sidata.kn is k1 there.
inline void apply(const ContactStep &c, const NormalPart &np, double, ContactResult &out) {
  const ContactState &s = c.state;
  const Eigen::Vector3d &n = s.normal;
  const Eigen::Vector3d wr = (c.cr / (s.radius - s.overlap)) * s.omega;
  const double wrMag = wr.norm();
  if (wrMag > 0.0) {
    Eigen::Vector3d rTorque =
        (c.pc.pair.coefficientRollingFriction * np.knDelta * c.cr / wrMag) * wr;
    rTorque -= rTorque.dot(n) * n;
    out.torque -= rTorque;
  }
}

} // namespace wheelsim::contact::rolling_cdt
