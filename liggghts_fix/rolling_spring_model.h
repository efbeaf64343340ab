// The LIGGGHTS side shared by wheelsim's two rolling springs (`rolling_friction krot` and
// `epsdt`: rolling_model_krot.h, rolling_model_epsdt.h): the stored moment in the history slots
// of LIGGGHTS' epsd2 ("r_torquex_old" ..., sign-changing when i and j swap), the relative spin it
// acts on (ω_i − ω_j in a pair, ω_i on a wall: LIGGGHTS' walls do not spin), the torques −M on i
// and +M on j, and the reset when the contact opens. A model derives from
// RollingSpringModel<Model> and gives `void step(const SurfacesIntersectData &, double M[3], const
// double spin[3])`, which advances M in place (contact/rolling_spring.h), and its properties.
// docs/contact-law.md, "Rolling: rolling_friction krot" and "... epsdt".
#ifndef WHEELSIM_ROLLING_SPRING_MODEL_H
#define WHEELSIM_ROLLING_SPRING_MODEL_H

#include "contact/rolling_spring.h"
#include "contact_models.h"
#include "rolling_model_base.h"

namespace LIGGGHTS {
namespace ContactModels {

template <typename Model> class RollingSpringModel : public RollingModelBase {
public:
  RollingSpringModel(LAMMPS_NS::LAMMPS *lmp, IContactHistorySetup *hsetup, ContactModelBase *c)
      : RollingModelBase(lmp, hsetup, c) {
    history_offset_ = hsetup->add_history_value("r_torquex_old", "1");
    hsetup->add_history_value("r_torquey_old", "1");
    hsetup->add_history_value("r_torquez_old", "1");
  }

  void registerSettings(Settings &) override {}
  void postSettings(IContactHistorySetup *, ContactModelBase *) override {}

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
    static_cast<Model *>(this)->step(sidata, M, w);
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
  int history_offset_ = 0;
};

} // namespace ContactModels
} // namespace LIGGGHTS

#endif // WHEELSIM_ROLLING_SPRING_MODEL_H
