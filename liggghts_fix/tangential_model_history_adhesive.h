// `tangential history_adhesive` for LIGGGHTS' own pair style and walls (wheelsim's addition): the
// incremental tangential spring of `tangential history` (shear displacement accumulated from the
// relative tangential velocity and turned into the current tangent plane, spring force k_t s,
// damping −γ_t v_t while sticking) with the Coulomb cap of an adhesive contact after Thornton
// (1991, J. Phys. D 24:1942, "Interparticle sliding in the presence of adhesion"):
//
//     |F_t| <= μ max(0, F_net + 2 F_po),
//
// F_net the contact's net normal force (Hertz + normal damping − the SJKR pull k_coh A, whether
// or not SJKR's `tangential_reduce` has already taken the pull off LIGGGHTS' Fn), F_po the
// pull-off force of the Hertz–SJKR contact, 4 C³ / (27 K²) with C = 2π R* k_coh and
// K = 4/3 Y* √R* (small overlaps: A ≈ 2π R* δ), i.e. F_po = (2/3) π³ k_coh³ R*² / Y*².
// LIGGGHTS' `tangential history` caps at μ |Fn|: without tangential_reduce the Hertz force, which
// in a bonded contact at rest is 27/4 F_po and grows ~3× faster than the load, so bonded contacts
// neither slide nor roll; with it the net force, ~0 in a bonded contact at rest, so a loose
// skeleton cannot hold itself (docs/soils.md "What friction and rolling resistance see in a
// cohesive contact"). This cap is 2 μ F_po at zero load and grows at μ with the load. Without
// cohesion (k_coh 0) it is μ max(0, Fn): `tangential history` for a compressed contact.
// The cap's formulas are contact/adhesive_cap.h's, shared with the same model on the wheel contact
// of fix wheel/cosim (contact/models/tangential_history_adhesive.h). docs/liggghts-wheel.md,
// "tangential history_adhesive".
//
// Read like LIGGGHTS' own model headers, once with TANGENTIAL_MODEL defined (the id line, via
// contact_model_styles/style_tangential_model.h) and once for the class. Only
// precompiled_contact_models.cpp instantiates it (with cohesion sjkr) and registers the keyword
// (kHistoryAdhesiveTangentialModelId). SI units only (LIGGGHTS' nktv2p = 1).
#ifdef TANGENTIAL_MODEL

TANGENTIAL_MODEL(TANGENTIAL_HISTORY_ADHESIVE, history_adhesive, 20)

#else

#ifndef WHEELSIM_TANGENTIAL_MODEL_HISTORY_ADHESIVE_H
#define WHEELSIM_TANGENTIAL_MODEL_HISTORY_ADHESIVE_H

#include "contact/adhesive_cap.h"
#include "contact_models.h"
#include "global_properties.h"
#include "tangential_model_base.h"
#include "update.h"

#include <cmath>

namespace LIGGGHTS {
namespace ContactModels {

/// The id of `tangential history_adhesive` in LIGGGHTS' hash codes (6 bits; LIGGGHTS' own
/// tangential models use 1-4). Must equal the TANGENTIAL_MODEL line above.
constexpr int kHistoryAdhesiveTangentialModelId = 20;

/// SJKR's contact area [m²] as LIGGGHTS' cohesion sjkr takes it: the circle where the two spheres
/// (radii ri, rj, centres r apart) or the sphere and the wall (centre r from it) intersect.
inline double sjkr_contact_area(bool is_wall, double r, double ri, double rj, double area_ratio) {
  if (is_wall)
    return (ri * ri - r * r) * M_PI * area_ratio;
  return -M_PI / 4.0 * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj)) / (r * r);
}

template <> class TangentialModel<TANGENTIAL_HISTORY_ADHESIVE> : public TangentialModelBase {
public:
  TangentialModel(LAMMPS_NS::LAMMPS *lmp, IContactHistorySetup *hsetup, ContactModelBase *c)
      : TangentialModelBase(lmp, hsetup, c) {
    history_offset_ = hsetup->add_history_value("shearx", "1");
    hsetup->add_history_value("sheary", "1");
    hsetup->add_history_value("shearz", "1");
  }

  // SJKR's switch (the same setting: LIGGGHTS shares a name's value among its registrants), only
  // to know whether Fn already holds the pull.
  void registerSettings(Settings &settings) override {
    settings.registerOnOff("tangential_reduce", pull_in_fn_, false);
  }
  void postSettings(IContactHistorySetup *, ContactModelBase *) override {}

  void connectToProperties(PropertyRegistry &registry) override {
    registry.registerProperty("coeffFrict", &MODEL_PARAMS::createCoeffFrict);
    registry.connect("coeffFrict", coeff_frict_, "tangential_model history_adhesive");
    registry.registerProperty("cohEnergyDens", &MODEL_PARAMS::createCohesionEnergyDensity);
    registry.connect("cohEnergyDens", coh_energy_dens_, "tangential_model history_adhesive");
    registry.registerProperty("Yeff", &MODEL_PARAMS::createYeff);
    registry.connect("Yeff", y_eff_, "tangential_model history_adhesive");
    if (force->cg_active())
      error->cg(FLERR, "tangential model history_adhesive");
  }

  void surfacesIntersect(const SurfacesIntersectData &sidata, ForceData &i_forces,
                         ForceData &j_forces) override {
    if (sidata.contact_flags)
      *sidata.contact_flags |= CONTACT_TANGENTIAL_MODEL;
    const double *const en = sidata.en;
    double *const s = &sidata.contact_history[history_offset_];
    if (sidata.computeflag && sidata.shearupdate) {
      const double dt = update->dt;
      s[0] += sidata.vtr1 * dt;
      s[1] += sidata.vtr2 * dt;
      s[2] += sidata.vtr3 * dt;
      const double along_n = s[0] * en[0] + s[1] * en[1] + s[2] * en[2];
      for (int k = 0; k < 3; ++k)
        s[k] -= along_n * en[k]; // into the current tangent plane
    }
    const int it = sidata.itype, jt = sidata.jtype;
    const double k_coh = coh_energy_dens_[it][jt];
    const double r_eff =
        sidata.is_wall ? sidata.radi : sidata.radi * sidata.radj / (sidata.radi + sidata.radj);
    // F_net: LIGGGHTS' Fn, less the SJKR pull unless tangential_reduce has already taken it off
    const double f_net =
        pull_in_fn_ ? sidata.Fn
                    : sidata.Fn - k_coh * sjkr_contact_area(sidata.is_wall, sidata.r, sidata.radi,
                                                            sidata.radj, sidata.area_ratio);
    const double cap = wheelsim::contact::adhesive_coulomb_cap(
        coeff_frict_[it][jt], f_net,
        wheelsim::contact::sjkr_pull_off_force(r_eff, k_coh, y_eff_[it][jt]));

    const double kt = sidata.kt;
    const double s_mag = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    double ft[3] = {-kt * s[0], -kt * s[1], -kt * s[2]};
    if (kt * s_mag > cap) { // sliding: the spring force scaled onto the cap, no damping
      const double scale = s_mag > 0.0 ? cap / (kt * s_mag) : 0.0;
      for (int k = 0; k < 3; ++k)
        ft[k] *= scale;
      if (sidata.computeflag && sidata.shearupdate && kt > 0.0)
        for (int k = 0; k < 3; ++k)
          s[k] = -ft[k] / kt;
    } else { // sticking: spring and damping
      ft[0] -= sidata.gammat * sidata.vtr1;
      ft[1] -= sidata.gammat * sidata.vtr2;
      ft[2] -= sidata.gammat * sidata.vtr3;
    }
    // the torque of the tangential force about each centre (contact radii cri, crj)
    const double en_x_ft[3] = {en[1] * ft[2] - en[2] * ft[1], en[2] * ft[0] - en[0] * ft[2],
                               en[0] * ft[1] - en[1] * ft[0]};
    if (sidata.is_wall) {
      const double a = sidata.area_ratio;
      for (int k = 0; k < 3; ++k) {
        i_forces.delta_F[k] += ft[k] * a;
        i_forces.delta_torque[k] -= sidata.cri * en_x_ft[k] * a;
      }
    } else {
      for (int k = 0; k < 3; ++k) {
        i_forces.delta_F[k] += ft[k];
        j_forces.delta_F[k] -= ft[k];
        i_forces.delta_torque[k] -= sidata.cri * en_x_ft[k];
        j_forces.delta_torque[k] -= sidata.crj * en_x_ft[k];
      }
    }
  }

  void surfacesClose(SurfacesCloseData &scdata, ForceData &, ForceData &) override {
    if (scdata.contact_flags)
      *scdata.contact_flags &= ~CONTACT_TANGENTIAL_MODEL;
    if (!scdata.contact_history)
      return;
    double *const s = &scdata.contact_history[history_offset_];
    s[0] = s[1] = s[2] = 0.0;
  }

  void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) override {}
  void endPass(SurfacesIntersectData &, ForceData &, ForceData &) override {}

private:
  int history_offset_ = 0;
  bool pull_in_fn_ = false;
  double **coeff_frict_ = nullptr;
  double **coh_energy_dens_ = nullptr;
  double **y_eff_ = nullptr;
};

} // namespace ContactModels
} // namespace LIGGGHTS

#endif // WHEELSIM_TANGENTIAL_MODEL_HISTORY_ADHESIVE_H
#endif // TANGENTIAL_MODEL
