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
// The history slots, spins and torques are rolling_spring_model.h's (shared with epsdt). This
// header is read like one of LIGGGHTS' own model headers, once with ROLLING_MODEL defined (the id
// line, via contact_model_styles/style_rolling_model.h) and once for the class. Only
// precompiled_contact_models.cpp instantiates it; it registers the keyword (kKrotRollingModelId).
#ifdef ROLLING_MODEL

ROLLING_MODEL(ROLLING_KROT, krot, 20)

#else

#ifndef WHEELSIM_ROLLING_MODEL_KROT_H
#define WHEELSIM_ROLLING_MODEL_KROT_H

#include "global_properties.h"
#include "rolling_spring_model.h"

namespace LIGGGHTS {
namespace ContactModels {

/// The id of `rolling_friction krot` in LIGGGHTS' hash codes (6 bits; LIGGGHTS' own rolling
/// models use 1-6). Must equal the ROLLING_MODEL line above.
constexpr int kKrotRollingModelId = 20;

template <>
class RollingModel<ROLLING_KROT> : public RollingSpringModel<RollingModel<ROLLING_KROT>> {
public:
  RollingModel(LAMMPS_NS::LAMMPS *lmp, IContactHistorySetup *hsetup, ContactModelBase *c)
      : RollingSpringModel(lmp, hsetup, c) {}

  void connectToProperties(PropertyRegistry &registry) override {
    registry.registerProperty("rollingSpringStiffness", &createRollingSpringStiffness);
    registry.connect("rollingSpringStiffness", stiffness_, "rolling_model krot");
    if (force->cg_active())
      error->cg(FLERR, "rolling model krot");
  }

  /// M turned into the tangent plane, then M += k_r dt ω_rel,t.
  void step(const SurfacesIntersectData &sidata, double M[3], const double spin[3]) const {
    wheelsim::contact::advance_rolling_spring(M, sidata.en, spin,
                                              update->dt * stiffness_[sidata.itype][sidata.jtype]);
  }

private:
  /// `fix property/global rollingSpringStiffness peratomtypepair N k_11 k_12 ...` [N·m/rad], >= 0.
  static MatrixProperty *createRollingSpringStiffness(PropertyRegistry &registry,
                                                      const char *caller, bool sanity_checks) {
    return MODEL_PARAMS::createPerTypePairProperty(registry, "rollingSpringStiffness", caller,
                                                   sanity_checks, 0.0);
  }

  double **stiffness_ = nullptr;
};

} // namespace ContactModels
} // namespace LIGGGHTS

#endif // WHEELSIM_ROLLING_MODEL_KROT_H
#endif // ROLLING_MODEL
