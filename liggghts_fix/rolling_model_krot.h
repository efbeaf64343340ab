// `rolling_friction krot` for LIGGGHTS' own pair style and walls (wheelsim's addition: LIGGGHTS
// 3.8 has no force-independent rolling spring). A linear rotational spring of stiffness k_r
// [N·m/rad] (per type pair property `rollingSpringStiffness`) on the relative rolling rotation,
// without a cap: Yade's Hertz–Mindlin moment law with krot set, ktwist 0 and eta 0, as the
// Nakanishi et al. 2020 wheel case uses it. Per contact and step the spring of
// contact/rolling_spring.h (turned into the tangent plane, then M += k_r dt ω_rel,t) on
// ω_rel = ω_i − ω_j (a wall: ω_i; LIGGGHTS' walls do not spin); torque −M on i, +M on j. The same
// spring on the wheel is contact/models/rolling_krot.h (there ω_rel is relative to the wheel's
// spin). docs/contact-law.md, "Rolling: rolling_friction krot".
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

#include "contact/rolling_spring.h"
#include "contact_models.h"
#include "global_properties.h"
#include "rolling_model_base.h"

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
    double *const hist = &sidata.contact_history[history_offset_];
    double M[3] = {hist[0], hist[1], hist[2]};
    wheelsim::contact::advance_rolling_spring(M, sidata.en, w,
                                              update->dt * stiffness_[sidata.itype][sidata.jtype]);
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
