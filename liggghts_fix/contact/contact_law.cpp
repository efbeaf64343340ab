// The sphere–rigid-surface contact law (see contact_law.h and docs/contact-law.md).
//
// Written from the LIGGGHTS 3.8 sources as a specification, not copied: each block names the
// LIGGGHTS file whose behaviour it reproduces. The wall case throughout: reff = R, meff = m,
// the "other radius" is 0, area_ratio = 1, force->nktv2p = 1 (SI).
#include "contact_law.h"

#include <cassert>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace wheelsim::contact {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// sqrt(5/6), the factor between the Hertz damping coefficient and the critical damping of the
/// linearised spring (normal_model_hertz.h: sqrtFiveOverSix).
const double kSqrtFiveOverSix = std::sqrt(5.0 / 6.0);
/// Bound on EEPA's re-evaluation after a reload from the adhesive branch. LIGGGHTS loops with a
/// goto and no bound; on a wall it re-evaluates at most once (the adhesive stiffness is 0 there).
constexpr int kMaxEepaReevaluations = 4;

void require(bool ok, const char *name, double value, const char *expected) {
  if (ok)
    return;
  std::ostringstream msg;
  msg << "contact law: " << name << " must be " << expected << ", got " << value;
  throw std::invalid_argument(msg.str());
}

/// Normal-model output consumed by the later sub-models (LIGGGHTS sidata.Fn/kt/gammat).
struct NormalPart {
  double Fn;      ///< normal force incl. damping [N]
  double kt;      ///< tangential stiffness [N/m]
  double gammat;  ///< tangential damping coefficient [N·s/m]
  double knDelta; ///< sidata.kn · δ, the "normal force" of rolling model cdt [N]
};

// --- model hertz (normal_model_hertz.h, NormalModel<HERTZ>::surfacesIntersect) ---
NormalPart hertzNormal(const PairConstants &pc, double R, double m, double delta, double vn) {
  const double sqrtRd = std::sqrt(R * delta);
  const double Sn = 2.0 * pc.Yeff * sqrtRd; // normal contact stiffness dF/dδ [N/m]
  const double St = 8.0 * pc.Geff * sqrtRd; // tangential (Mindlin) stiffness [N/m]
  const double kn = 4.0 / 3.0 * pc.Yeff * sqrtRd;
  const double gamman = -2.0 * kSqrtFiveOverSix * pc.betaeff * std::sqrt(Sn * m);
  const double gammat = pc.settings.tangentialDamping
                            ? -2.0 * kSqrtFiveOverSix * pc.betaeff * std::sqrt(St * m)
                            : 0.0;
  double Fn = kn * delta - gamman * vn;
  if (pc.limitForce && Fn < 0.0)
    Fn = 0.0;
  return {Fn, St, gammat, kn * delta};
}

/// EEPA adhesive stiffness from the surface energy (normal_model_edinburgh.h, calculate_k_adh):
/// the JKR-like minimum force f_min = 1.5 π Δγ a, with a the radius of the circle where a sphere
/// of radius ri at distance d meets one of radius rj; for a wall rj = 0 and d = ri, so a = 0.
double adhesionStiffnessFromSurfaceEnergy(const PairConstants &pc, double d, double ri, double rj,
                                          double fMinLimit, double dpeMax, double dpMax,
                                          double k2) {
  const double dsq = d * d, risq = ri * ri, rjsq = rj * rj;
  const double chord = dsq - rjsq + risq;
  const double a = std::sqrt(std::fmax(4.0 * dsq * risq - chord * chord, 0.0)) / (2.0 * d);
  double fMin = 1.5 * kPi * pc.gammaSurf * a;
  double deltaMin;
  if (fMin > fMinLimit) {
    fMin = fMinLimit;
    deltaMin = 0.5 * dpMax;
  } else {
    deltaMin = std::pow((k2 * dpeMax - fMin) / k2, 1.0 / pc.dex);
  }
  return fMin / std::pow(deltaMin, pc.cex);
}

} // namespace

double eepaNormalDamping(const PairConstants &pc, double R, double m) {
  // Damping from ln e and the (overlap-independent) loading coefficient k1, as LIGGGHTS does.
  const double kn = pc.dex == 1.0 ? 2.0 * pc.Yeff * R : 4.0 / 3.0 * pc.Yeff * std::sqrt(R);
  const double piOverLogE = pc.logE == 0.0 ? HUGE_VAL : kPi / pc.logE;
  return std::sqrt(4.0 * m * kn / (1.0 + piOverLogE * piOverLogE));
}

namespace {

// --- model edinburgh (normal_model_edinburgh.h, NormalModel<EDINBURGH>::surfacesIntersect) ---
NormalPart eepaNormal(const PairConstants &pc, double R, double m, double delta, double vn,
                      ContactHistory &h) {
  const double sqrtRd = std::sqrt(R * delta);
  double kn, kt;
  if (pc.dex == 1.0) { // linear EEPA: k1 = 2 Yeff R [N/m], kt = 2 Yeff sqrt(R δ)
    kn = 2.0 * pc.Yeff * R;
    kt = 2.0 * pc.Yeff * sqrtRd;
  } else { // k1 = 4/3 Yeff sqrt(R) [N/m^1.5], used as F = k1 δ^n; kt = 8 Geff sqrt(R δ)
    kn = 4.0 / 3.0 * pc.Yeff * std::sqrt(R);
    kt = 8.0 * pc.Geff * sqrtRd;
  }
  const double k1 = kn;
  const double k2 = kn * pc.kn2k1;
  const double gamman = eepaNormalDamping(pc, R, m);
  const double gammat = pc.settings.tangentialDamping ? gamman : 0.0;

  const double de = std::pow(delta, pc.dex);  // δ^n
  const double dce = std::pow(delta, pc.cex); // δ^X
  double Fc = 0.0;
  double kAdh = 0.0; // the adhesive stiffness seen by the limitForce test below

  if (!pc.settings.fixKc) {
    // Plastic overlap reached on the unloading line from the current point: δp = λ δ with
    // λ = (1 - k1/k2)^(1/n); remember its maximum.
    const double lambda = std::pow(1.0 - k1 / k2, 1.0 / pc.dex);
    if (lambda * delta > h.deltaMax)
      h.deltaMax = lambda * delta;
    double dpMax = h.deltaMax;
    for (int pass = 0;; ++pass) {
      const double dpeMax = std::pow(dpMax, pc.dex);
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
      if (delta > h.oldDelta && pass < kMaxEepaReevaluations) {
        // Reloading from the adhesive branch: restart the unloading line from the overlap of the
        // previous evaluation and re-evaluate.
        dpMax = std::pow(std::pow(h.oldDelta, pc.dex) + kAdh / k2 * std::pow(h.oldDelta, pc.cex),
                         1.0 / pc.dex);
        h.deltaMax = dpMax;
        continue;
      }
      Fc = -kAdh * dce; // adhesive branch
      break;
    }
    h.oldDelta = delta;
  } else {
    // fixKc: kc = coefficientAdhesionStiffness * k1; the memory is the maximum total overlap.
    const double kc = pc.kn2kc * kn;
    h.kc = kc;
    if (delta > h.deltaMax)
      h.deltaMax = delta;
    const double dMaxE = std::pow(h.deltaMax, pc.dex);
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

  double Fn = -gamman * vn + Fc + pc.f0;
  h.fo = pc.f0;
  if (pc.limitForce && Fn < 0.0 && kAdh == 0.0 && pc.f0 == 0.0)
    Fn = 0.0;
  return {Fn, kt, gammat, kn * delta};
}

} // namespace

PairConstants makePairConstants(const Material &particle, const Material &wheel,
                                const PairMaterial &pair, const ContactSettings &settings) {
  for (const Material *mat : {&particle, &wheel}) {
    const bool isParticle = mat == &particle;
    require(mat->youngsModulus > 0.0 && std::isfinite(mat->youngsModulus),
            isParticle ? "particle youngsModulus [Pa]" : "wheel youngsModulus [Pa]",
            mat->youngsModulus, "> 0");
    require(mat->poissonsRatio >= 0.0 && mat->poissonsRatio <= 0.5,
            isParticle ? "particle poissonsRatio" : "wheel poissonsRatio", mat->poissonsRatio,
            "in [0, 0.5]");
  }
  require(pair.coefficientRestitution > 0.05 && pair.coefficientRestitution <= 1.0,
          "coefficientRestitution", pair.coefficientRestitution, "in (0.05, 1]");
  require(pair.coefficientFriction >= 0.0, "coefficientFriction", pair.coefficientFriction, ">= 0");
  require(pair.coefficientRollingFriction >= 0.0, "coefficientRollingFriction",
          pair.coefficientRollingFriction, ">= 0");
  require(pair.cohesionEnergyDensity >= 0.0, "cohesionEnergyDensity [J/m^3]",
          pair.cohesionEnergyDensity, ">= 0");
  if (settings.normal == NormalModel::Eepa) {
    if (settings.fixKc)
      require(pair.UnloadingStiffness > 1.0, "UnloadingStiffness (k2/k1)", pair.UnloadingStiffness,
              "> 1 with fixKc");
    else
      require(pair.UnloadingStiffness >= 1.0, "UnloadingStiffness (k2/k1)", pair.UnloadingStiffness,
              ">= 1");
    require(pair.coefficientAdhesionStiffness >= 0.0, "coefficientAdhesionStiffness",
            pair.coefficientAdhesionStiffness, ">= 0");
    require(pair.surfaceEnergy >= 0.0, "surfaceEnergy [J/m^2]", pair.surfaceEnergy, ">= 0");
    require(pair.overlapExponent >= 1.0, "overlapExponent", pair.overlapExponent, ">= 1");
    require(pair.adhesionExponent > 0.0, "adhesionExponent", pair.adhesionExponent, "> 0");
    require(std::isfinite(pair.pullOffForce), "pullOffForce [N]", pair.pullOffForce, "finite");
  }

  PairConstants pc;
  pc.settings = settings;
  const double E1 = particle.youngsModulus, v1 = particle.poissonsRatio;
  const double E2 = wheel.youngsModulus, v2 = wheel.poissonsRatio;
  // global_properties.cpp: createYeff, createGeff, createCoeffRestLog, createBetaEff
  pc.Yeff = 1.0 / ((1.0 - v1 * v1) / E1 + (1.0 - v2 * v2) / E2);
  pc.Geff = 1.0 / (2.0 * (2.0 - v1) * (1.0 + v1) / E1 + 2.0 * (2.0 - v2) * (1.0 + v2) / E2);
  pc.logE = std::log(pair.coefficientRestitution);
  pc.betaeff = pc.logE / std::sqrt(pc.logE * pc.logE + kPi * kPi);
  pc.mu = pair.coefficientFriction;
  pc.muRoll = pair.coefficientRollingFriction;
  pc.kCoh = pair.cohesionEnergyDensity;
  pc.kn2k1 = pair.UnloadingStiffness;
  pc.kn2kc = pair.coefficientAdhesionStiffness;
  pc.f0 = pair.pullOffForce;
  pc.gammaSurf = pair.surfaceEnergy;
  pc.dex = pair.overlapExponent;
  pc.cex = pair.adhesionExponent;
  switch (settings.limitForce) {
  case Switch::On:
    pc.limitForce = true;
    break;
  case Switch::Off:
    pc.limitForce = false;
    break;
  case Switch::ModelDefault: // hertz: registerOnOff("limitForce", ..., false); edinburgh: true
    pc.limitForce = settings.normal == NormalModel::Eepa;
    break;
  }
  return pc;
}

Eigen::Vector3d relativeContactVelocity(const Eigen::Vector3d &vParticle,
                                        const Eigen::Vector3d &omega, const Eigen::Vector3d &vWall,
                                        const Eigen::Vector3d &n, double radius, double overlap) {
  // surface_model_default.h (wall branch): the spin acts on c_r = R - δ/2.
  const double cr = radius - 0.5 * overlap;
  return vParticle - vWall - cr * omega.cross(n);
}

ContactResult evaluate(const PairConstants &pc, const ContactState &s, double dt,
                       bool updateHistory, ContactHistory &h) {
  assert(s.overlap > 0.0 && s.radius > s.overlap && s.mass > 0.0);
  const Eigen::Vector3d &n = s.normal;
  const double R = s.radius;
  const double delta = s.overlap;
  ContactResult out;

  // Surface model (surface_model_default.h): normal and tangential relative velocity.
  const double vn = s.vRel.dot(n); // < 0 approaching
  const Eigen::Vector3d vt = s.vRel - vn * n;
  const double cr = R - 0.5 * delta; // lever arm of the contact point

  // Normal model.
  const NormalPart np = pc.settings.normal == NormalModel::Hertz
                            ? hertzNormal(pc, R, s.mass, delta, vn)
                            : eepaNormal(pc, R, s.mass, delta, vn, h);
  double Fn = np.Fn;
  out.force = Fn * n;

  // Cohesion (cohesion_model_sjkr.h, wall branch): F = -k_coh * π (R² - r²), r = R - δ the
  // distance from the particle centre to the surface.
  if (pc.settings.cohesion == CohesionModel::Sjkr) {
    const double r = R - delta;
    const double area = (R * R - r * r) * kPi;
    out.cohesionForce = -pc.kCoh * area;
    out.force += out.cohesionForce * n;
    if (pc.settings.tangentialReduce)
      Fn += out.cohesionForce;
  }
  out.normalForce = Fn;

  // Tangential model (tangential_model_history.h).
  Eigen::Map<Eigen::Vector3d> shear(h.shear);
  if (updateHistory) {
    shear += vt * dt;
    shear -= shear.dot(n) * n; // rotate into the current tangent plane (projection, no rescale)
  }
  const double shearMag = shear.norm();
  Eigen::Vector3d Ft = -np.kt * shear;
  const double FtSpring = np.kt * shearMag;
  const double FtCap = pc.mu * std::fabs(Fn);
  if (FtSpring > FtCap) { // Coulomb cap, damping not included
    if (shearMag != 0.0) {
      Ft *= FtCap / FtSpring;
      if (updateHistory)
        shear = -Ft / np.kt;
    } else {
      Ft.setZero();
    }
    out.sliding = true;
  } else {
    Ft -= np.gammat * vt; // damping only while sticking
  }
  out.force += Ft;
  out.torque = -cr * n.cross(Ft);

  // Rolling model (rolling_model_epsd2.h, wall branch).
  if (pc.settings.rolling == RollingModel::Epsd2) {
    const double r = R - delta;
    Eigen::Vector3d wr = (cr / r) * s.omega; // surface_model_default.h: wr = c_r ω / r
    if (!pc.settings.torsionTorque)
      wr -= wr.dot(n) * n;
    const double kr = np.kt * R * R;
    Eigen::Map<Eigen::Vector3d> rollTorque(h.rollTorque);
    Eigen::Vector3d Mr = rollTorque + (dt * kr) * wr;
    const double MrMag = Mr.norm();
    const double MrCap = std::fabs(Fn) * R * pc.muRoll;
    if (MrMag > MrCap)
      Mr *= MrCap / MrMag;
    if (updateHistory)
      rollTorque = Mr;
    out.torque -= Mr;
  }
  // Rolling model (rolling_model_cdt.h, wall branch): a constant torque μr (kn δ) c_r opposing
  // the spin, its normal (torsion) part removed. kn δ is the elastic Hertz force for hertz; for
  // edinburgh it is k1 δ (k1 the loading coefficient), as LIGGGHTS' sidata.kn is k1 there.
  if (pc.settings.rolling == RollingModel::Cdt) {
    const Eigen::Vector3d wr = (cr / (R - delta)) * s.omega;
    const double wrMag = wr.norm();
    if (wrMag > 0.0) {
      Eigen::Vector3d rTorque = (pc.muRoll * np.knDelta * cr / wrMag) * wr;
      rTorque -= rTorque.dot(n) * n;
      out.torque -= rTorque;
    }
  }
  return out;
}

} // namespace wheelsim::contact
