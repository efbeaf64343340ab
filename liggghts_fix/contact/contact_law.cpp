// The sphere–rigid-surface contact law (see contact_law.h and docs/contact-law.md).
//
// Written from the LIGGGHTS 3.8 sources as a specification, not copied: each model's header
// (models/*.h) names the LIGGGHTS file whose behaviour it reproduces. The wall case throughout:
// reff = R, meff = m, the "other radius" is 0, area_ratio = 1, force->nktv2p = 1 (SI).
#include "contact_law.h"
#include "contact_model.h"

// the model headers (kernels), after the types they use
#define WHEELSIM_CONTACT_MODEL_HEADERS
#include "model_list.h"

#include <cassert>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace wheelsim::contact {

namespace {

void require(const PropertySpec &p, const char *side, double value) {
  if (p.range.contains(value))
    return;
  std::ostringstream msg;
  msg << "contact law: " << side << p.name;
  if (std::string(p.unit) != "-")
    msg << " [" << p.unit << "]";
  msg << " must be " << p.range.text() << ", got " << value;
  throw std::invalid_argument(msg.str());
}

} // namespace

double eepaNormalDamping(const PairConstants &pc, double R, double m) {
  return normal_eepa::damping(pc, R, m);
}

PairConstants makePairConstants(const Material &particle, const Material &wheel,
                                const PairMaterial &pair, const ContactSettings &settings) {
  // Each selected model's properties against their declared ranges, then its own checks.
  for (const PropertySpec *p : required_properties(settings)) {
    if (p->material) {
      require(*p, "particle ", particle.*(p->material));
      require(*p, "wheel ", wheel.*(p->material));
    } else {
      require(*p, "", pair.*(p->pair));
    }
  }
  for (const ModelEntry *m : selected_models(settings))
    if (m->spec->check)
      m->spec->check(pair, settings);

  PairConstants pc;
  pc.settings = settings;
  pc.pair = pair;
  const double E1 = particle.youngsModulus, v1 = particle.poissonsRatio;
  const double E2 = wheel.youngsModulus, v2 = wheel.poissonsRatio;
  // global_properties.cpp: createYeff, createGeff, createCoeffRestLog, createBetaEff
  pc.Yeff = 1.0 / ((1.0 - v1 * v1) / E1 + (1.0 - v2 * v2) / E2);
  pc.Geff = 1.0 / (2.0 * (2.0 - v1) * (1.0 + v1) / E1 + 2.0 * (2.0 - v2) * (1.0 + v2) / E2);
  pc.logE = std::log(pair.coefficientRestitution);
  pc.betaeff = pc.logE / std::sqrt(pc.logE * pc.logE + M_PI * M_PI);
  switch (settings.limitForce) {
  case Switch::On:
    pc.limitForce = true;
    break;
  case Switch::Off:
    pc.limitForce = false;
    break;
  case Switch::ModelDefault: // the normal model's default (hertz: off, edinburgh: on)
    pc.limitForce = switch_default(settings, "limitForce");
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

// The dispatch: one switch per model kind over the enum, each case an inlined kernel.
#define WHEELSIM_NORMAL_CASE(Enumerator, name)                                                     \
  case NormalModel::Enumerator:                                                                    \
    np = name::apply(c);                                                                           \
    break;
#define WHEELSIM_COHESION_CASE(Enumerator, name)                                                   \
  case CohesionModel::Enumerator:                                                                  \
    name::apply(c, Fn, out);                                                                       \
    break;
#define WHEELSIM_TANGENTIAL_CASE(Enumerator, name)                                                 \
  case TangentialModel::Enumerator:                                                                \
    name::apply(c, np, Fn, out);                                                                   \
    break;
#define WHEELSIM_ROLLING_CASE(Enumerator, name)                                                    \
  case RollingModel::Enumerator:                                                                   \
    name::apply(c, np, Fn, out);                                                                   \
    break;

ContactResult evaluate(const PairConstants &pc, const ContactState &s, double dt,
                       bool updateHistory, ContactHistory &h) {
  assert(s.overlap > 0.0 && s.radius > s.overlap && s.mass > 0.0);
  ContactResult out;

  // Surface model (surface_model_default.h): normal and tangential relative velocity.
  const double vn = s.vRel.dot(s.normal); // < 0 approaching
  const Eigen::Vector3d vt = s.vRel - vn * s.normal;
  const ContactStep c{pc, s, vn, vt, s.radius - 0.5 * s.overlap, dt, updateHistory, h};

  // LIGGGHTS' order (contact_models.h, surfacesIntersect): normal, cohesion, tangential,
  // rolling. Later models read the normal model's Fn, kt and gammat.
  NormalPart np{0.0, 0.0, 0.0, 0.0};
  switch (pc.settings.normal) { WHEELSIM_NORMAL_MODELS(WHEELSIM_NORMAL_CASE) }
  double Fn = np.Fn;
  out.force = Fn * s.normal;
  switch (pc.settings.cohesion) { WHEELSIM_COHESION_MODELS(WHEELSIM_COHESION_CASE) }
  out.normalForce = Fn;
  switch (pc.settings.tangential) { WHEELSIM_TANGENTIAL_MODELS(WHEELSIM_TANGENTIAL_CASE) }
  switch (pc.settings.rolling) { WHEELSIM_ROLLING_MODELS(WHEELSIM_ROLLING_CASE) }
  return out;
}

} // namespace wheelsim::contact
