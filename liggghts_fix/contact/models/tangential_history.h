// `tangential history`: the incremental tangential spring with a Coulomb cap (LIGGGHTS
// tangential_model_history.h). docs/contact-law.md, "Tangential: tangential history".
#pragma once

#include "contact_model.h"

namespace wheelsim::contact::tangential_history {

constexpr PropertySpec kProperties[] = {
    {"coefficientFriction",
     PropertyStyle::PerTypePair,
     "-",
     "sliding friction coefficient μ",
     {0.0, kInf, true, false},
     nullptr,
     &PairMaterial::coefficientFriction},
};

constexpr ModelSpec spec{
    "history",   nullptr, "tangential spring with a Coulomb cap", "tangential_model_history.h",
    kProperties, {}};

/// The spring with a given Coulomb cap FtCap [N] (>= 0): the history step of `tangential history`
/// and of `tangential history_adhesive`, which differ only in the cap.
inline void springWithCap(const ContactStep &c, const NormalPart &np, double FtCap,
                          ContactResult &out) {
  const Eigen::Vector3d &n = c.state.normal;
  Eigen::Map<Eigen::Vector3d> shear(c.history.shear);
  if (c.updateHistory) {
    shear += c.vt * c.dt;
    shear -= shear.dot(n) * n; // rotate into the current tangent plane (projection, no rescale)
  }
  const double shearMag = shear.norm();
  Eigen::Vector3d Ft = -np.kt * shear;
  const double FtSpring = np.kt * shearMag;
  if (FtSpring > FtCap) { // Coulomb cap, damping not included
    if (shearMag != 0.0) {
      Ft *= FtCap / FtSpring;
      if (c.updateHistory)
        shear = -Ft / np.kt;
    } else {
      Ft.setZero();
    }
    out.sliding = true;
  } else {
    Ft -= np.gammat * c.vt; // damping only while sticking
  }
  out.force += Ft;
  out.torque = -c.cr * n.cross(Ft);
}

/// LIGGGHTS' cap μ |Fn|.
inline void apply(const ContactStep &c, const NormalPart &np, double Fn, ContactResult &out) {
  springWithCap(c, np, c.pc.pair.coefficientFriction * std::fabs(Fn), out);
}

} // namespace wheelsim::contact::tangential_history
