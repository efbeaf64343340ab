// `rolling_friction epsdt` for LIGGGHTS' own pair style and walls (wheelsim's addition): LIGGGHTS'
// elastic-plastic spring-dashpot model epsd2 (spring k_r = k_t R*², moment capped at μr R* |Fn|,
// no dashpot), with its stored moment turned into the current tangent plane every step as
// `rolling_friction krot` turns it (contact/rolling_spring.h). epsd2 only adds to the stored
// moment, so a contact that turns keeps a growing normal (twisting) part, which drove the twist
// instability that made the soils give up epsd2 (docs/soils.md "Rolling friction"); cdt, their
// replacement, has no spring and cannot hold a moment at rest (it switches sign every step), which
// lets a bed creep at a rate that grows with the time step (soil_lab/trials README "Bed creep
// and the time step"). epsdt holds a moment below its cap statically and slips plastically at it.
// Per contact and step: M turned, M += k_r dt ω_rel,t, |M| capped at μr R* |Fn|, on
// ω_rel = ω_i − ω_j (a wall: ω_i; LIGGGHTS' walls do not spin); torque −M on i, +M on j. The
// same model on the wheel is contact/models/rolling_epsdt.h. docs/contact-law.md, "Rolling:
// rolling_friction epsdt".
//
// The history slots, spins and torques are rolling_spring_model.h's (shared with krot). Read like
// rolling_model_krot.h (once with ROLLING_MODEL defined, once for the class); only
// precompiled_contact_models.cpp instantiates it and registers the keyword (kEpsdtRollingModelId).
#ifdef ROLLING_MODEL

ROLLING_MODEL(ROLLING_EPSDT, epsdt, 21)

#else

#ifndef WHEELSIM_ROLLING_MODEL_EPSDT_H
#define WHEELSIM_ROLLING_MODEL_EPSDT_H

#include "global_properties.h"
#include "rolling_spring_model.h"

#include <cmath>

namespace LIGGGHTS {
namespace ContactModels {

/// The id of `rolling_friction epsdt` in LIGGGHTS' hash codes (6 bits; LIGGGHTS' own rolling
/// models use 1-6, krot 20). Must equal the ROLLING_MODEL line above.
constexpr int kEpsdtRollingModelId = 21;

template <>
class RollingModel<ROLLING_EPSDT> : public RollingSpringModel<RollingModel<ROLLING_EPSDT>> {
public:
  RollingModel(LAMMPS_NS::LAMMPS *lmp, IContactHistorySetup *hsetup, ContactModelBase *c)
      : RollingSpringModel(lmp, hsetup, c) {}

  void connectToProperties(PropertyRegistry &registry) override {
    registry.registerProperty("coeffRollFrict", &MODEL_PARAMS::createCoeffRollFrict);
    registry.connect("coeffRollFrict", coeff_roll_frict_, "rolling_model epsdt");
    if (force->cg_active())
      error->cg(FLERR, "rolling model epsdt");
  }

  /// M turned into the tangent plane, M += k_t R*² dt ω_rel,t, then |M| <= μr R* |Fn|.
  void step(const SurfacesIntersectData &sidata, double M[3], const double spin[3]) const {
    const double reff =
        sidata.is_wall ? sidata.radi : sidata.radi * sidata.radj / (sidata.radi + sidata.radj);
    wheelsim::contact::advance_rolling_spring(M, sidata.en, spin,
                                              update->dt * sidata.kt * reff * reff);
    wheelsim::contact::cap_rolling_moment(M, std::fabs(sidata.Fn) * reff *
                                                 coeff_roll_frict_[sidata.itype][sidata.jtype]);
  }

private:
  double **coeff_roll_frict_ = nullptr;
};

} // namespace ContactModels
} // namespace LIGGGHTS

#endif // WHEELSIM_ROLLING_MODEL_EPSDT_H
#endif // ROLLING_MODEL
