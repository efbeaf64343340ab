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
// Read like rolling_model_krot.h (once with ROLLING_MODEL defined, once for the class); only
// precompiled_contact_models.cpp instantiates it and registers the keyword (kEpsdtRollingModelId).
#ifdef ROLLING_MODEL

ROLLING_MODEL(ROLLING_EPSDT, epsdt, 21)

#else

#ifndef WHEELSIM_ROLLING_MODEL_EPSDT_H
#define WHEELSIM_ROLLING_MODEL_EPSDT_H

#include "contact/rolling_spring.h"
#include "contact_models.h"
#include "global_properties.h"
#include "rolling_model_base.h"

#include <cmath>

namespace LIGGGHTS {
namespace ContactModels {

/// The id of `rolling_friction epsdt` in LIGGGHTS' hash codes (6 bits; LIGGGHTS' own rolling
/// models use 1-6, krot 20). Must equal the ROLLING_MODEL line above.
constexpr int kEpsdtRollingModelId = 21;

template <> class RollingModel<ROLLING_EPSDT> : public RollingModelBase {
public:
  RollingModel(LAMMPS_NS::LAMMPS *lmp, IContactHistorySetup *hsetup, ContactModelBase *c)
      : RollingModelBase(lmp, hsetup, c) {
    // the slots of epsd2 and krot; "1": the values change sign when the pair's i and j swap
    history_offset_ = hsetup->add_history_value("r_torquex_old", "1");
    hsetup->add_history_value("r_torquey_old", "1");
    hsetup->add_history_value("r_torquez_old", "1");
  }

  void registerSettings(Settings &) override {}
  void postSettings(IContactHistorySetup *, ContactModelBase *) override {}

  void connectToProperties(PropertyRegistry &registry) override {
    registry.registerProperty("coeffRollFrict", &MODEL_PARAMS::createCoeffRollFrict);
    registry.connect("coeffRollFrict", coeff_roll_frict_, "rolling_model epsdt");
    if (force->cg_active())
      error->cg(FLERR, "rolling model epsdt");
  }

  void surfacesIntersect(SurfacesIntersectData &sidata, ForceData &i_forces,
                         ForceData &j_forces) override {
    if (sidata.contact_flags)
      *sidata.contact_flags |= CONTACT_ROLLING_MODEL;
    const double reff =
        sidata.is_wall ? sidata.radi : sidata.radi * sidata.radj / (sidata.radi + sidata.radj);
    const double *const *const omega = atom->omega;
    double w[3] = {omega[sidata.i][0], omega[sidata.i][1], omega[sidata.i][2]};
    if (!sidata.is_wall)
      for (int k = 0; k < 3; ++k)
        w[k] -= omega[sidata.j][k];
    double *const hist = &sidata.contact_history[history_offset_];
    double M[3] = {hist[0], hist[1], hist[2]};
    const double kr = sidata.kt * reff * reff; // epsd2's spring
    wheelsim::contact::advance_rolling_spring(M, sidata.en, w, update->dt * kr);
    wheelsim::contact::cap_rolling_moment(
        M, std::fabs(sidata.Fn) * reff * coeff_roll_frict_[sidata.itype][sidata.jtype]);
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
  double **coeff_roll_frict_ = nullptr;
  int history_offset_ = 0;
};

} // namespace ContactModels
} // namespace LIGGGHTS

#endif // WHEELSIM_ROLLING_MODEL_EPSDT_H
#endif // ROLLING_MODEL
