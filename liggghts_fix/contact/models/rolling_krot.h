// `rolling_friction krot`: a linear rotational spring of fixed stiffness k_r [N·m/rad] on the
// relative rolling rotation, without a cap (Yade's Hertz–Mindlin moment law with krot set and
// eta = 0, as the Nakanishi et al. 2020 / Yade wheel case uses it). Its LIGGGHTS side is
// liggghts_fix/rolling_model_krot.h (particle pairs and LIGGGHTS walls). docs/contact-law.md,
// "Rolling: rolling_friction krot".
#pragma once

#include "contact_model.h"

#include <cmath>

namespace wheelsim::contact::rolling_krot {

constexpr PropertySpec kProperties[] = {
    {"rollingSpringStiffness",
     PropertyStyle::PerTypePair,
     "N·m/rad",
     "rolling spring stiffness k_r (krot: M += k_r ω_rel,t dt, no cap)",
     {0.0, kInf, true, false},
     nullptr,
     &PairMaterial::rollingSpringStiffness}};

/// The spring alone on one particle is stable for dt < 2 sqrt(I/k_r) (I = 2/5 m R², explicit
/// update of θ'' = −k_r θ / I); a particle of the bed has several such contacts at once, so the
/// rule keeps a factor 4 below that.
inline double maxTimestep(const PairConstants &pc, double radius_m, double mass_kg) {
  const double kr = pc.pair.rollingSpringStiffness;
  if (!(kr > 0.0))
    return kInf;
  return 0.5 * std::sqrt(0.4 * mass_kg * radius_m * radius_m / kr);
}

constexpr ModelSpec spec{"krot",
                         nullptr,
                         "linear rolling spring k_r on the relative rotation, no cap (Yade krot)",
                         "",
                         kProperties,
                         {},
                         maxTimestep,
                         "the rolling spring needs dt <= 0.5 sqrt(I / k_r), I = 2/5 m R²"};

/// The stored moment M (on the wheel's side of the contact, i.e. the particle feels −M) is first
/// turned into the current tangent plane (its normal part removed, its magnitude kept: the
/// contact frame's rotation, as LIGGGHTS turns the tangential spring), then grows by
/// k_r dt ω_rel,t with ω_rel = ω_particle − ω_wheel and its part along the normal (twist)
/// removed. No cap: the spring is elastic however far it is wound.
inline void apply(const ContactStep &c, const NormalPart &, double, ContactResult &out) {
  const ContactState &s = c.state;
  const Eigen::Vector3d &n = s.normal;
  Eigen::Vector3d wRel = s.omega - s.omegaSurface;
  wRel -= wRel.dot(n) * n;
  Eigen::Map<Eigen::Vector3d> rollTorque(c.history.rollTorque);
  Eigen::Vector3d M = rollTorque;
  const double before = M.norm();
  if (before > 0.0) {
    M -= M.dot(n) * n;
    const double after = M.norm();
    M = after > 0.0 ? Eigen::Vector3d(M * (before / after)) : Eigen::Vector3d::Zero();
  }
  M += (c.dt * c.pc.pair.rollingSpringStiffness) * wRel;
  if (c.updateHistory)
    rollTorque = M;
  out.torque -= M;
}

} // namespace wheelsim::contact::rolling_krot
