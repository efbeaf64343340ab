// `rolling_friction epsd2`: elastic-plastic rolling spring, torque capped at μr R |Fn| (LIGGGHTS
// rolling_model_epsd2.h, wall branch). docs/contact-law.md, "Rolling: rolling_friction epsd2".
#pragma once

#include "contact_model.h"

namespace wheelsim::contact::rolling_epsd2 {

constexpr PropertySpec kProperties[] = {kCoefficientRollingFriction};

inline void setTorsionTorque(ContactSettings &s, bool on) { s.torsionTorque = on; }

constexpr SwitchSpec kSwitches[] = {
    {"torsionTorque", "keep the normal (twisting) part of the spin in the rolling spring", false,
     setTorsionTorque},
};

constexpr ModelSpec spec{"epsd2",
                         nullptr,
                         "elastic-plastic rolling spring, capped at μr R |Fn|",
                         "rolling_model_epsd2.h",
                         kProperties,
                         kSwitches};

inline void apply(const ContactStep &c, const NormalPart &np, double Fn, ContactResult &out) {
  const ContactState &s = c.state;
  const Eigen::Vector3d &n = s.normal;
  const double R = s.radius;
  const double r = R - s.overlap;
  Eigen::Vector3d wr = (c.cr / r) * s.omega; // surface_model_default.h: wr = c_r ω / r
  if (!c.pc.settings.torsionTorque)
    wr -= wr.dot(n) * n;
  const double kr = np.kt * R * R;
  Eigen::Map<Eigen::Vector3d> rollTorque(c.history.rollTorque);
  Eigen::Vector3d Mr = rollTorque + (c.dt * kr) * wr;
  const double MrMag = Mr.norm();
  const double MrCap = std::fabs(Fn) * R * c.pc.pair.coefficientRollingFriction;
  if (MrMag > MrCap)
    Mr *= MrCap / MrMag;
  if (c.updateHistory)
    rollTorque = Mr;
  out.torque -= Mr;
}

} // namespace wheelsim::contact::rolling_epsd2
