// `model eepa` (LIGGGHTS `model edinburgh`): the Edinburgh elasto-plastic adhesive model
// (Thakur et al. 2014; LIGGGHTS normal_model_edinburgh.h, NormalModel<EDINBURGH>::
// surfacesIntersect). docs/contact-law.md, "Normal: model edinburgh".
#pragma once

#include "contact_model.h"

#include <sstream>
#include <stdexcept>

namespace wheelsim::contact::normal_eepa {

constexpr PropertySpec kProperties[] = {
    kYoungsModulus,
    kPoissonsRatio,
    kCoefficientRestitution,
    {"UnloadingStiffness",
     PropertyStyle::PerTypePair,
     "-",
     "k2/k1: unloading over loading stiffness (> 1 with fixKc)",
     {1.0, kInf, true, false},
     nullptr,
     &PairMaterial::UnloadingStiffness},
    {"coefficientAdhesionStiffness",
     PropertyStyle::PerTypePair,
     "-",
     "kc/k1: adhesive over loading stiffness (fixKc on)",
     {0.0, kInf, true, false},
     nullptr,
     &PairMaterial::coefficientAdhesionStiffness},
    {"pullOffForce",
     PropertyStyle::PerTypePair,
     "N",
     "constant pull-off force f0 added to Fn (usually <= 0)",
     {-kInf, kInf, false, false},
     nullptr,
     &PairMaterial::pullOffForce},
    {"surfaceEnergy",
     PropertyStyle::PerTypePair,
     "J/m^2",
     "surface energy Δγ of the adhesive stiffness (no effect on a wall)",
     {0.0, kInf, true, false},
     nullptr,
     &PairMaterial::surfaceEnergy},
    {"overlapExponent",
     PropertyStyle::Scalar,
     "-",
     "n of the loading curve F = k1 δ^n",
     {1.0, kInf, true, false},
     nullptr,
     &PairMaterial::overlapExponent},
    {"adhesionExponent",
     PropertyStyle::Scalar,
     "-",
     "X of the adhesive branch F = -kc δ^X",
     {0.0, kInf, false, false},
     nullptr,
     &PairMaterial::adhesionExponent},
};

inline void setFixKc(ContactSettings &s, bool on) { s.fixKc = on; }

constexpr SwitchSpec kSwitches[] = {
    {"tangential_damping", "damp the tangential spring while sticking (γt = γn)", true,
     setTangentialDamping},
    {"limitForce", "clamp a net attractive Fn to 0 when no adhesion is active", true,
     setLimitForce},
    {"fixKc", "adhesive stiffness kc = coefficientAdhesionStiffness k1 (else from surfaceEnergy)",
     false, setFixKc},
};

/// The normal damping coefficient γn [N·s/m] for a particle of radius R [m] and mass m [kg]:
/// from ln e and the (overlap-independent) loading coefficient k1, as LIGGGHTS does.
inline double damping(const PairConstants &pc, double R, double m) {
  const double dex = pc.pair.overlapExponent;
  const double kn = dex == 1.0 ? 2.0 * pc.Yeff * R : 4.0 / 3.0 * pc.Yeff * std::sqrt(R);
  const double piOverLogE = pc.logE == 0.0 ? HUGE_VAL : M_PI / pc.logE;
  return std::sqrt(4.0 * m * kn / (1.0 + piOverLogE * piOverLogE));
}

/// The damping does not shrink with the overlap: the explicit update is unstable once
/// γn dt / m approaches 1 (seen in LIGGGHTS' own pair style as in the fix).
constexpr double kMaxDampingRatio = 1.0;
inline double maxTimestep(const PairConstants &pc, double radius_m, double mass_kg) {
  return kMaxDampingRatio * mass_kg / damping(pc, radius_m, mass_kg);
}

/// UnloadingStiffness must exceed 1 with fixKc (the reload line divides by k2 − k1).
inline void check(const PairMaterial &pair, const ContactSettings &settings) {
  if (settings.fixKc && !(pair.UnloadingStiffness > 1.0)) {
    std::ostringstream msg;
    msg << "contact law: UnloadingStiffness must be > 1 with fixKc, got "
        << pair.UnloadingStiffness;
    throw std::invalid_argument(msg.str());
  }
}

constexpr ModelSpec spec{"eepa",
                         "edinburgh",
                         "Edinburgh elasto-plastic adhesive (EEPA)",
                         "normal_model_edinburgh.h",
                         kProperties,
                         kSwitches,
                         maxTimestep,
                         "the normal damping needs gamma_n dt / m <= 1 (LIGGGHTS forms gamma_n "
                         "from the loading coefficient k1: it does not shrink with the overlap)",
                         check};

/// Bound on the re-evaluation after a reload from the adhesive branch. LIGGGHTS loops with a
/// goto and no bound; on a wall it re-evaluates at most once (the adhesive stiffness is 0 there).
constexpr int kMaxReevaluations = 4;

/// The adhesive stiffness from the surface energy (calculate_k_adh): the JKR-like minimum force
/// f_min = 1.5 π Δγ a, with a the radius of the circle where a sphere of radius ri at distance d
/// meets one of radius rj; for a wall rj = 0 and d = ri, so a = 0.
inline double adhesionStiffnessFromSurfaceEnergy(const PairConstants &pc, double d, double ri,
                                                 double rj, double fMinLimit, double dpeMax,
                                                 double dpMax, double k2) {
  const double dsq = d * d, risq = ri * ri, rjsq = rj * rj;
  const double chord = dsq - rjsq + risq;
  const double a = std::sqrt(std::fmax(4.0 * dsq * risq - chord * chord, 0.0)) / (2.0 * d);
  double fMin = 1.5 * M_PI * pc.pair.surfaceEnergy * a;
  double deltaMin;
  if (fMin > fMinLimit) {
    fMin = fMinLimit;
    deltaMin = 0.5 * dpMax;
  } else {
    deltaMin = std::pow((k2 * dpeMax - fMin) / k2, 1.0 / pc.pair.overlapExponent);
  }
  return fMin / std::pow(deltaMin, pc.pair.adhesionExponent);
}

inline NormalPart apply(const ContactStep &c) {
  const PairConstants &pc = c.pc;
  ContactHistory &h = c.history;
  const double R = c.state.radius, m = c.state.mass, delta = c.state.overlap;
  const double dex = pc.pair.overlapExponent, cex = pc.pair.adhesionExponent;
  const double sqrtRd = std::sqrt(R * delta);
  double kn, kt;
  if (dex == 1.0) { // linear EEPA: k1 = 2 Yeff R [N/m], kt = 2 Yeff sqrt(R δ)
    kn = 2.0 * pc.Yeff * R;
    kt = 2.0 * pc.Yeff * sqrtRd;
  } else { // k1 = 4/3 Yeff sqrt(R) [N/m^1.5], used as F = k1 δ^n; kt = 8 Geff sqrt(R δ)
    kn = 4.0 / 3.0 * pc.Yeff * std::sqrt(R);
    kt = 8.0 * pc.Geff * sqrtRd;
  }
  const double k1 = kn;
  const double k2 = kn * pc.pair.UnloadingStiffness;
  const double gamman = damping(pc, R, m);
  const double gammat = pc.settings.tangentialDamping ? gamman : 0.0;

  const double de = std::pow(delta, dex);  // δ^n
  const double dce = std::pow(delta, cex); // δ^X
  double Fc = 0.0;
  double kAdh = 0.0; // the adhesive stiffness seen by the limitForce test below

  if (!pc.settings.fixKc) {
    // Plastic overlap reached on the unloading line from the current point: δp = λ δ with
    // λ = (1 - k1/k2)^(1/n); remember its maximum.
    const double lambda = std::pow(1.0 - k1 / k2, 1.0 / dex);
    if (lambda * delta > h.deltaMax)
      h.deltaMax = lambda * delta;
    double dpMax = h.deltaMax;
    for (int pass = 0;; ++pass) {
      const double dpeMax = std::pow(dpMax, dex);
      const double fMinLimit = 0.5 * k2 * dpeMax;
      const double fUnload = k2 * (de - dpeMax); // unloading/reloading line
      if (fUnload >= k1 * de) {                  // on the virgin loading curve
        Fc = k1 * de;
        break;
      }
      kAdh = adhesionStiffnessFromSurfaceEnergy(pc, R, R, 0.0, fMinLimit, dpeMax, dpMax, k2);
      h.kc = kAdh;
      if (fUnload > -kAdh * dce) { // between loading curve and adhesive branch
        Fc = fUnload;
        break;
      }
      if (delta > h.oldDelta && pass < kMaxReevaluations) {
        // Reloading from the adhesive branch: restart the unloading line from the overlap of the
        // previous evaluation and re-evaluate.
        dpMax =
            std::pow(std::pow(h.oldDelta, dex) + kAdh / k2 * std::pow(h.oldDelta, cex), 1.0 / dex);
        h.deltaMax = dpMax;
        continue;
      }
      Fc = -kAdh * dce; // adhesive branch
      break;
    }
    h.oldDelta = delta;
  } else {
    // fixKc: kc = coefficientAdhesionStiffness * k1; the memory is the maximum total overlap.
    const double kc = pc.pair.coefficientAdhesionStiffness * kn;
    h.kc = kc;
    if (delta > h.deltaMax)
      h.deltaMax = delta;
    const double dMaxE = std::pow(h.deltaMax, dex);
    const double fUnload = k2 * (de - dMaxE) + k1 * dMaxE;
    if (fUnload >= k1 * de) {
      Fc = k1 * de;
    } else if (fUnload > -kc * dce) {
      Fc = fUnload;
    } else {
      Fc = -kc * dce;
      h.deltaMax = (k2 + kc) / (k2 - k1) * delta;
    }
    // LIGGGHTS declares this branch's kc in an inner scope, so the limitForce test below still
    // sees an adhesive stiffness of 0: kAdh stays 0 here on purpose.
  }

  const double f0 = pc.pair.pullOffForce;
  double Fn = -gamman * c.vn + Fc + f0;
  h.fo = f0;
  if (pc.limitForce && Fn < 0.0 && kAdh == 0.0 && f0 == 0.0)
    Fn = 0.0;
  return {Fn, kt, gammat, kn * delta};
}

} // namespace wheelsim::contact::normal_eepa
