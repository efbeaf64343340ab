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

inline void apply(const ContactStep &c, const NormalPart &np, double Fn, ContactResult &out) {
  const Eigen::Vector3d &n = c.state.normal;
  Eigen::Map<Eigen::Vector3d> shear(c.history.shear);
  if (c.updateHistory) {
    shear += c.vt * c.dt;
    shear -= shear.dot(n) * n; // rotate into the current tangent plane (projection, no rescale)
  }
  const double shearMag = shear.norm();
  Eigen::Vector3d Ft = -np.kt * shear;
  const double FtSpring = np.kt * shearMag;
  const double FtCap = c.pc.pair.coefficientFriction * std::fabs(Fn);
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

} // namespace wheelsim::contact::tangential_history
