// `rolling_friction krot`: a linear rotational spring of fixed stiffness k_r [N·m/rad] on the
// relative rolling rotation, without a cap (Yade's Hertz–Mindlin moment law with krot set and
// eta = 0, as the Nakanishi et al. 2020 / Yade wheel case uses it). Its LIGGGHTS side is
// liggghts_fix/rolling_model_krot.h (particle pairs and LIGGGHTS walls). docs/contact-law.md,
// "Rolling: rolling_friction krot".
#pragma once

#include "contact_model.h"
#include "rolling_spring.h"

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

/// The spring of rolling_spring.h on ω_rel = ω_particle − ω_wheel: the particle feels −M.
inline void apply(const ContactStep &c, const NormalPart &, double, ContactResult &out) {
  const ContactState &s = c.state;
  const Eigen::Vector3d wRel = s.omega - s.omegaSurface;
  Eigen::Vector3d M(c.history.rollTorque[0], c.history.rollTorque[1], c.history.rollTorque[2]);
  advance_rolling_spring(M.data(), s.normal.data(), wRel.data(),
                         c.dt * c.pc.pair.rollingSpringStiffness);
  if (c.updateHistory)
    Eigen::Map<Eigen::Vector3d>(c.history.rollTorque) = M;
  out.torque -= M;
}

} // namespace wheelsim::contact::rolling_krot
