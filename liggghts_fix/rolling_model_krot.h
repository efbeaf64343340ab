// `rolling_friction krot` for LIGGGHTS' own pair style and walls (wheelsim's addition: LIGGGHTS
// 3.8 has no force-independent rolling spring). A linear rotational spring of stiffness k_r
// [N·m/rad] (per type pair property `rollingSpringStiffness`) on the relative rolling rotation,
// without a cap: Yade's Hertz–Mindlin moment law with krot set, ktwist 0 and eta 0, as the
// Nakanishi et al. 2020 wheel case uses it. Per contact and step:
//   M <- M turned into the current tangent plane (normal part removed, magnitude kept),
//   M <- M + k_r dt ω_rel,t,   ω_rel = ω_i − ω_j (a wall: ω_i; LIGGGHTS' walls do not spin),
//   torque −M on i, +M on j;  ω_rel,t is ω_rel without its part along the normal (no twist).
// The same law on the wheel is liggghts_fix/contact/models/rolling_krot.h (there ω_rel is taken
// relative to the wheel's spin). docs/contact-law.md, "Rolling: rolling_friction krot".
//
// Written after LIGGGHTS' rolling_model_epsd2.h (its history slots and hooks): this header is
// read like one of LIGGGHTS' own model headers, once with ROLLING_MODEL defined (the id line,
// via contact_model_styles/style_rolling_model.h) and once for the class. Only
// precompiled_contact_models.cpp instantiates it; it registers the keyword (kKrotRollingModelId).
#ifdef ROLLING_MODEL

ROLLING_MODEL(ROLLING_KROT, krot, 20)

#else

#ifndef WHEELSIM_ROLLING_MODEL_KROT_H
#define WHEELSIM_ROLLING_MODEL_KROT_H

#include "contact_models.h"
#include "global_properties.h"
#include "rolling_model_base.h"

#include <cmath>

namespace LIGGGHTS {
namespace ContactModels {

/// The id of `rolling_friction krot` in LIGGGHTS' hash codes (6 bits; LIGGGHTS' own rolling
/// models use 1-6). Must equal the ROLLING_MODEL line above.
constexpr int kKrotRollingModelId = 20;

template <> class RollingModel<ROLLING_KROT> : public RollingModelBase {
public:
  RollingModel(LAMMPS_NS::LAMMPS *lmp, IContactHistorySetup *hsetup, ContactModelBase *c)
      : RollingModelBase(lmp, hsetup, c) {
    // "1": the values change sign when the pair's i and j swap (as epsd2's)
    history_offset_ = hsetup->add_history_value("r_torquex_old", "1");
    hsetup->add_history_value("r_torquey_old", "1");
    hsetup->add_history_value("r_torquez_old", "1");
  }

  void registerSettings(Settings &) override {}
  void postSettings(IContactHistorySetup *, ContactModelBase *) override {}

  void connectToProperties(PropertyRegistry &registry) override {
    registry.registerProperty("rollingSpringStiffness", &createRollingSpringStiffness);
    registry.connect("rollingSpringStiffness", stiffness_, "rolling_model krot");
    if (force->cg_active())
      error->cg(FLERR, "rolling model krot");
  }

  void surfacesIntersect(SurfacesIntersectData &sidata, ForceData &i_forces,
                         ForceData &j_forces) override {
    if (sidata.contact_flags)
      *sidata.contact_flags |= CONTACT_ROLLING_MODEL;
    const double *const *const omega = atom->omega;
    double w[3] = {omega[sidata.i][0], omega[sidata.i][1], omega[sidata.i][2]};
    if (!sidata.is_wall)
      for (int k = 0; k < 3; ++k)
        w[k] -= omega[sidata.j][k];
    const double *n = sidata.en;
    const double wn = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
    for (int k = 0; k < 3; ++k)
      w[k] -= wn * n[k];

    double *const hist = &sidata.contact_history[history_offset_];
    double M[3] = {hist[0], hist[1], hist[2]};
    const double before = std::sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
    if (before > 0.0) {
      const double mn = M[0] * n[0] + M[1] * n[1] + M[2] * n[2];
      for (int k = 0; k < 3; ++k)
        M[k] -= mn * n[k];
      const double after = std::sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
      const double scale = after > 0.0 ? before / after : 0.0;
      for (int k = 0; k < 3; ++k)
        M[k] *= scale;
    }
    const double step = update->dt * stiffness_[sidata.itype][sidata.jtype];
    for (int k = 0; k < 3; ++k)
      M[k] += step * w[k];

    if (sidata.computeflag && sidata.shearupdate)
      for (int k = 0; k < 3; ++k)
        hist[k] = M[k];
    for (int k = 0; k < 3; ++k) {
      i_forces.delta_torque[k] -= M[k];
      j_forces.delta_torque[k] += M[k];
    }
  }

  void surfacesClose(SurfacesCloseData &scdata, ForceData &, ForceData &) override {
    if (scdata.contact_flags)
      *scdata.contact_flags &= ~CONTACT_ROLLING_MODEL;
    double *const hist = &scdata.contact_history[history_offset_];
    hist[0] = hist[1] = hist[2] = 0.0;
  }

  void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) override {}
  void endPass(SurfacesIntersectData &, ForceData &, ForceData &) override {}

private:
  /// `fix property/global rollingSpringStiffness peratomtypepair N k_11 k_12 ...` [N·m/rad], >= 0.
  static MatrixProperty *createRollingSpringStiffness(PropertyRegistry &registry,
                                                      const char *caller, bool sanity_checks) {
    return MODEL_PARAMS::createPerTypePairProperty(registry, "rollingSpringStiffness", caller,
                                                   sanity_checks, 0.0);
  }

  double **stiffness_ = nullptr;
  int history_offset_ = 0;
};

} // namespace ContactModels
} // namespace LIGGGHTS

#endif // WHEELSIM_ROLLING_MODEL_KROT_H
#endif // ROLLING_MODEL
