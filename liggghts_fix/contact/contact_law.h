// The sphere–rigid-surface contact law of fix wheel/cosim.
//
// One call per particle–wheel contact and time step: given the two materials (reduced once to
// PairConstants), the contact state (overlap, normal, relative velocity, particle spin) and the
// contact's history, it returns the force and torque on the particle and updates the history.
//
// It reproduces LIGGGHTS 3.8's wall contact (`fix wall/gran ... mesh` with `pair_style gran`)
//   model hertz | edinburgh,  tangential history,  cohesion off | sjkr,  rolling_friction off |
//   epsd2 | cdt
// term by term and in the same order (surface model -> normal -> cohesion -> tangential ->
// rolling), so that the fix and LIGGGHTS give the same forces on identical states. It adds
// `rolling_friction krot` (Yade's rolling spring) and `epsdt` (epsd2 with its moment turned with
// the contact), whose LIGGGHTS sides are our own rolling_model_krot.h and rolling_model_epsdt.h,
// and which alone act on the spin relative to the wheel's.
// docs/contact-law.md lists every constant with its formula and the LIGGGHTS file it matches.
// Each model is one header models/<name>.h (its descriptor and its kernel), listed in
// model_list.h; contact_models.h is the descriptor table the fix parses and validates with.
//
// Units: SI throughout (LIGGGHTS `units si`, where force->nktv2p = 1).
// Frames: every vector is in the world frame.
#pragma once

#include "model_list.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <type_traits>

namespace wheelsim::contact {

// The model enums are generated from model_list.h (one enumerator per model there); each
// model's keyword, properties and force kernel are in models/<name>.h (contact_model.h).
#define WHEELSIM_CONTACT_ENUMERATOR(Enumerator, name) Enumerator,

/// Normal force law (LIGGGHTS `model ...`): Hertz (`model hertz`, Hertz–Mindlin with viscous
/// damping from the restitution coefficient), Eepa (`model edinburgh`, elasto-plastic adhesive,
/// Thakur et al. 2014).
enum class NormalModel { WHEELSIM_NORMAL_MODELS(WHEELSIM_CONTACT_ENUMERATOR) };

/// Tangential force law (LIGGGHTS `tangential ...`): History (`tangential history`).
enum class TangentialModel { WHEELSIM_TANGENTIAL_MODELS(WHEELSIM_CONTACT_ENUMERATOR) };

/// Cohesion added along the normal (LIGGGHTS `cohesion ...`): Off, Sjkr (`cohesion sjkr`,
/// energy density times contact area).
enum class CohesionModel { WHEELSIM_COHESION_MODELS(WHEELSIM_CONTACT_ENUMERATOR) };

/// Rolling resistance (LIGGGHTS `rolling_friction ...`): Off, Epsd2 (elastic-plastic spring,
/// torque capped at μr R |Fn|), Cdt (constant torque μr kn δ (R − δ/2) against the spin), Krot
/// (linear spring k_r on the rotation relative to the wheel, no cap: Yade's krot), Epsdt (epsd2's
/// capped spring, turned with the contact, on the rotation relative to the wheel).
enum class RollingModel { WHEELSIM_ROLLING_MODELS(WHEELSIM_CONTACT_ENUMERATOR) };

#undef WHEELSIM_CONTACT_ENUMERATOR

/// An on/off model setting whose LIGGGHTS default depends on the normal model.
enum class Switch { ModelDefault, On, Off };

/// One side of the contact (LIGGGHTS `fix property/global ... peratomtype`).
struct Material {
  double youngsModulus = 0.0; ///< E [Pa], > 0
  double poissonsRatio = 0.0; ///< ν [-], 0 <= ν <= 0.5
};

/// Properties of the particle-type/wheel-type pair (LIGGGHTS `peratomtypepair` and `scalar`
/// properties, named as in the deck). Which model reads which, with its unit, meaning and valid
/// range, is declared by the models (models/*.h, `spec.properties`); a model that needs a
/// property no other model reads adds its field here.
struct PairMaterial {
  double coefficientRestitution = 0.5;     ///< e [-], 0.05 < e <= 1 (LIGGGHTS' sanity range)
  double coefficientFriction = 0.5;        ///< μ [-], sliding friction, >= 0
  double coefficientRollingFriction = 0.0; ///< μr [-], epsd2, cdt and epsdt, >= 0
  double cohesionEnergyDensity = 0.0;      ///< k_coh [J/m³ = Pa], sjkr only, >= 0
  double rollingSpringStiffness = 0.0;     ///< k_r [N·m/rad], krot only, >= 0
  // --- model edinburgh (EEPA) ---
  double UnloadingStiffness = 1.0;           ///< k2/k1 [-]: unloading / loading stiffness, > 1
  double coefficientAdhesionStiffness = 0.0; ///< kc/k1 [-]: adhesive stiffness ratio (fixKc)
  double pullOffForce = 0.0;                 ///< f0 [N]: constant pull-off force (usually <= 0)
  double surfaceEnergy = 0.0;                ///< Δγ [J/m²] (no effect on a wall: see docs)
  double overlapExponent = 1.5;              ///< n [-]: loading curve F = k1 δ^n, >= 1
  double adhesionExponent = 1.5;             ///< X [-]: adhesive branch F = -kc δ^X, > 0
};

/// Model choice and LIGGGHTS' `contact_model ... <setting> on|off` switches.
struct ContactSettings {
  NormalModel normal = NormalModel::Hertz;
  TangentialModel tangential = TangentialModel::History;
  CohesionModel cohesion = CohesionModel::Off;
  RollingModel rolling = RollingModel::Off;
  /// `tangential_damping` (default on for both normal models).
  bool tangentialDamping = true;
  /// `limitForce`: clamp a net attractive normal force to 0. LIGGGHTS' default is off for hertz
  /// and ON for edinburgh (where it acts only when no adhesion is active, see docs).
  Switch limitForce = Switch::ModelDefault;
  /// edinburgh `fixKc`: adhesive stiffness = coefficientAdhesionStiffness * k1 (default off: the
  /// stiffness then follows from surfaceEnergy, which for a wall gives zero).
  bool fixKc = false;
  /// sjkr `tangential_reduce`: include the cohesion force in the Fn of the Coulomb/rolling caps.
  bool tangentialReduce = false;
  /// epsd2 `torsionTorque`: keep the normal (twisting) part of the spin in the rolling spring.
  bool torsionTorque = false;
};

/// Effective pair constants, computed once per material pair by makePairConstants().
struct PairConstants {
  ContactSettings settings;
  PairMaterial pair;       ///< the pair properties as given (checked against their ranges)
  double Yeff = 0.0;       ///< 1/((1-ν1²)/E1 + (1-ν2²)/E2) [Pa]
  double Geff = 0.0;       ///< 1/(2(2-ν1)(1+ν1)/E1 + 2(2-ν2)(1+ν2)/E2) [Pa]
  double logE = 0.0;       ///< ln e [-] (LIGGGHTS CoeffRestLog)
  double betaeff = 0.0;    ///< ln e / sqrt(ln²e + π²) [-] (LIGGGHTS betaeff), <= 0
  bool limitForce = false; ///< the resolved `limitForce` switch
};

/// Reduces the two materials and the pair properties to the constants used per contact.
/// Checks the properties the selected models read (contact_models.h: each property's range)
/// and throws std::invalid_argument naming the offending property, its value and the valid range.
PairConstants makePairConstants(const Material &particle, const Material &wheel,
                                const PairMaterial &pair, const ContactSettings &settings);

/// Per-contact history: a trivially copyable block of kSize doubles, zero when a contact starts
/// (value-initialise it, or call reset()). The fix stores 2–4 of these per particle.
struct ContactHistory {
  static constexpr int kSize = 10;
  double shear[3];      ///< tangential spring displacement [m] (LIGGGHTS shearx/y/z)
  double deltaMax;      ///< EEPA remembered maximum plastic overlap δp,max [m] ("deltaMax")
  double oldDelta;      ///< EEPA overlap at the previous evaluation [m] ("old_delta")
  double kc;            ///< EEPA last adhesive stiffness [N/m^X], diagnostic ("kc")
  double fo;            ///< EEPA pull-off force applied [N], diagnostic ("fo")
  double rollTorque[3]; ///< epsd2/krot/epsdt rolling spring torque [N·m] ("r_torquex_old" ...)

  void reset() { *this = ContactHistory{}; }
  double *data() { return shear; }
  const double *data() const { return shear; }
};
static_assert(std::is_trivially_copyable_v<ContactHistory> &&
                  std::is_standard_layout_v<ContactHistory> &&
                  sizeof(ContactHistory) == ContactHistory::kSize * sizeof(double),
              "ContactHistory must stay a flat block of doubles (it is packed per atom)");

/// The contact at one step.
struct ContactState {
  double radius = 0.0;  ///< particle radius R [m] (LIGGGHTS reff = R for a wall)
  double mass = 0.0;    ///< m [kg] (LIGGGHTS meff = m for a wall; see docs for clumps)
  double overlap = 0.0; ///< δn > 0 [m]
  /// unit contact normal, from the wheel surface towards the particle centre
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /// v_rel: velocity of the particle's contact point minus that of the wheel surface point [m/s]
  /// (see relativeContactVelocity for the lever arm LIGGGHTS uses)
  Eigen::Vector3d vRel = Eigen::Vector3d::Zero();
  /// ω: particle angular velocity [rad/s] (rolling resistance only)
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  /// ω_w: the wheel's angular velocity [rad/s] (rolling_friction krot and epsdt only, which act on
  /// the rotation relative to the wheel; LIGGGHTS' own wall models ignore the wall's spin)
  Eigen::Vector3d omegaSurface = Eigen::Vector3d::Zero();
};

/// What one evaluation returns.
struct ContactResult {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< on the particle [N]
  Eigen::Vector3d torque = Eigen::Vector3d::Zero(); ///< on the particle about its centre [N·m]:
                                                    ///< tangential force lever + rolling torque
  double normalForce = 0.0;   ///< Fn used by the caps (elastic + damping [+ cohesion]) [N]
  double cohesionForce = 0.0; ///< sjkr normal cohesion (negative = attractive) [N]
  bool sliding = false;       ///< the tangential force sits on the Coulomb cap
};

/// The relative contact-point velocity as LIGGGHTS' default surface model forms it for a wall:
///   v_rel = v_p - v_w - c_r ω × n,   c_r = R - δ/2,
/// i.e. the particle spin acts on the lever arm c_r (not R - δ), and v_w is the wheel's velocity
/// at the closest surface point (LIGGGHTS interpolates the mesh node velocities there).
/// @param vParticle particle centre velocity [m/s]; @param omega particle spin [rad/s];
/// @param vWall wheel surface velocity at the contact point [m/s]; @param n unit normal (wheel to
/// particle); @param radius R [m]; @param overlap δ [m].
Eigen::Vector3d relativeContactVelocity(const Eigen::Vector3d &vParticle,
                                        const Eigen::Vector3d &omega, const Eigen::Vector3d &vWall,
                                        const Eigen::Vector3d &n, double radius, double overlap);

/// The normal damping coefficient γn [N·s/m] of `model edinburgh` for a particle of radius R [m]
/// and mass m [kg] against the wheel: LIGGGHTS forms it from ln e and the loading coefficient k1
/// (N/m^n), independent of the overlap. An explicit integrator needs γn dt / m well below 1.
double eepaNormalDamping(const PairConstants &pc, double R, double m);

/// Evaluates one contact. `updateHistory` is LIGGGHTS' `computeflag && shearupdate`: false in
/// `setup()` (forces without advancing the history). Like LIGGGHTS, the EEPA overlap memory is
/// written even when it is false. No allocation, no virtual call.
/// Preconditions (checked only in debug builds): overlap > 0, radius > overlap, mass > 0.
ContactResult evaluate(const PairConstants &pc, const ContactState &state, double dt,
                       bool updateHistory, ContactHistory &history);

} // namespace wheelsim::contact
