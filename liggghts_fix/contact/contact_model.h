// The contact-model descriptor table of fix wheel/cosim.
//
// Each contact model (normal law, tangential law, cohesion, rolling resistance) is one header
// models/<name>.h, listed in model_list.h. It declares, in one place:
//   - `spec` (a ModelSpec below): the keyword value that selects it, the LIGGGHTS properties it
//     reads from the deck's `fix property/global` (name, per type / per type pair / scalar, unit,
//     meaning, valid range), the contact-model switches it understands (`limitForce on` ...),
//     an optional time-step rule and the LIGGGHTS source it reproduces;
//   - `apply`, its force kernel, called for every contact through a switch over the model enum
//     (contact_law.cpp): the per-contact loop has no virtual call and no table look-up.
// The fix (fix_wheel_cosim.cpp) parses its model keywords, reads and checks the properties and
// runs the time-step rules only through the table below (contact_models()).
//
// Plain static data and plain function pointers: no allocation, no registration at start-up.
#pragma once

#include "contact_law.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace wheelsim::contact {

/// A constant view of a static array (C++17 has no std::span).
template <class T> struct List {
  const T *items = nullptr;
  std::size_t count = 0;
  constexpr List() = default;
  template <std::size_t N> constexpr List(const T (&array)[N]) : items(array), count(N) {}
  constexpr const T *begin() const { return items; }
  constexpr const T *end() const { return items + count; }
  constexpr std::size_t size() const { return count; }
};

/// Which fix keyword selects a model (the LIGGGHTS `pair_style gran` word of the same name).
enum class ModelKind { Normal, Tangential, Cohesion, Rolling };
constexpr ModelKind kModelKinds[] = {ModelKind::Normal, ModelKind::Tangential, ModelKind::Cohesion,
                                     ModelKind::Rolling};
/// "model", "tangential", "cohesion", "rolling_friction".
const char *kind_keyword(ModelKind kind);

/// How a property is stored by LIGGGHTS' `fix property/global NAME STYLE ...`.
enum class PropertyStyle {
  PerType,     ///< `peratomtype`: one value per atom type (both sides: particle and wheel)
  PerTypePair, ///< `peratomtypepair`: an ntypes x ntypes matrix; the (particle, wheel) entry
  Scalar,      ///< `scalar`: one value
};
/// "peratomtype", "peratomtypepair", "scalar" (LIGGGHTS' words).
const char *style_keyword(PropertyStyle style);

/// A valid range lo (<|<=) value (<|<=) hi; an infinite bound is open ("> 0", ">= 0").
struct Range {
  double lo, hi;
  bool loInclusive, hiInclusive;
  bool contains(double v) const;
  std::string text() const; ///< "> 0", ">= 1", "in (0.05, 1]", "finite"
};

/// One LIGGGHTS material property a model reads.
struct PropertySpec {
  const char *name; ///< the LIGGGHTS name, e.g. "coefficientRollingFriction"
  PropertyStyle style;
  const char *unit;    ///< SI unit, "-" if dimensionless
  const char *meaning; ///< one line, with the symbol of the model's formulas
  Range range;
  /// Where the value goes: `material` (per type) or `pair` (per type pair and scalar).
  double Material::*material;
  double PairMaterial::*pair;
};

/// One LIGGGHTS contact-model switch (`<keyword> on|off`) a model understands.
struct SwitchSpec {
  const char *keyword; ///< as in LIGGGHTS' `pair_style gran`, e.g. "tangential_damping"
  const char *meaning;
  bool defaultOn; ///< LIGGGHTS' default when the model is selected
  void (*set)(ContactSettings &settings, bool on);
};

/// A model's own time-step limit: the largest stable dt [s] for the smallest particle of a type
/// (radius [m], mass [kg]) against the wheel. The fix's own check (Rayleigh time and Hertz
/// collision time, docs/fix-wheel-cosim.md) applies to every model in addition.
using TimestepRule = double (*)(const PairConstants &pc, double radius_m, double mass_kg);

/// One contact model: everything the fix and the documentation need to know about it.
struct ModelSpec {
  const char *name;     ///< the keyword value, e.g. "hertz" in `model hertz`
  const char *alias;    ///< a second accepted value (LIGGGHTS' name), or nullptr
  const char *summary;  ///< one line
  const char *liggghts; ///< the LIGGGHTS 3.8 header it reproduces, or "" if none
  List<PropertySpec> properties;
  List<SwitchSpec> switches;
  TimestepRule timestep = nullptr; ///< nullptr: only the fix's own check
  const char *timestepRule = "";   ///< what `timestep` bounds, for the error message and docs
  /// Checks between properties and switches that a single Range cannot say (may be nullptr);
  /// throws std::invalid_argument naming the property, the value and the valid range.
  void (*check)(const PairMaterial &pair, const ContactSettings &settings) = nullptr;
};

// --- Pieces more than one model declares (written once here) ---

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The elastic constants and restitution every normal model reads.
constexpr PropertySpec kYoungsModulus{
    "youngsModulus",           PropertyStyle::PerType,   "Pa",   "Young's modulus E of each side",
    {0.0, kInf, false, false}, &Material::youngsModulus, nullptr};
constexpr PropertySpec kPoissonsRatio{
    "poissonsRatio",        PropertyStyle::PerType,   "-",    "Poisson's ratio ν of each side",
    {0.0, 0.5, true, true}, &Material::poissonsRatio, nullptr};
constexpr PropertySpec kCoefficientRestitution{
    "coefficientRestitution",
    PropertyStyle::PerTypePair,
    "-",
    "coefficient of restitution e (LIGGGHTS' sanity range)",
    {0.05, 1.0, false, true},
    nullptr,
    &PairMaterial::coefficientRestitution};
/// The rolling friction coefficient of the rolling models.
constexpr PropertySpec kCoefficientRollingFriction{"coefficientRollingFriction",
                                                   PropertyStyle::PerTypePair,
                                                   "-",
                                                   "rolling friction coefficient μr",
                                                   {0.0, kInf, true, false},
                                                   nullptr,
                                                   &PairMaterial::coefficientRollingFriction};

/// Setters of the switches several models understand.
inline void setTangentialDamping(ContactSettings &s, bool on) { s.tangentialDamping = on; }
inline void setLimitForce(ContactSettings &s, bool on) {
  s.limitForce = on ? Switch::On : Switch::Off;
}

// --- The kernels' interface (each model's `apply`, inlined into evaluate()) ---

/// One contact at one step, as every kernel sees it (formed once by evaluate()).
struct ContactStep {
  const PairConstants &pc;
  const ContactState &state;
  double vn;                 ///< normal relative velocity (v_rel · n), < 0 approaching [m/s]
  const Eigen::Vector3d &vt; ///< tangential relative velocity [m/s]
  double cr;                 ///< lever arm of the contact point R − δ/2 [m]
  double dt;                 ///< time step [s]
  bool updateHistory;        ///< LIGGGHTS' `shearupdate`
  ContactHistory &history;   ///< this contact's memory
};

/// What the normal model passes to the later ones (LIGGGHTS sidata.Fn, kt, gammat, kn·δ).
struct NormalPart {
  double Fn;      ///< normal force incl. damping [N]
  double kt;      ///< tangential stiffness [N/m]
  double gammat;  ///< tangential damping coefficient [N·s/m]
  double knDelta; ///< sidata.kn · δ, the "normal force" of rolling model cdt [N]
};

// Kernel signatures, by kind (namespace wheelsim::contact::<name>, see model_list.h):
//   normal:     NormalPart apply(const ContactStep &c);
//   cohesion:   void apply(const ContactStep &c, double &Fn, ContactResult &out);
//               (adds its force to out; may change the Fn of the caps)
//   tangential: void apply(const ContactStep &c, const NormalPart &np, double Fn,
//                          ContactResult &out);  (adds force and torque, sets sliding)
//   rolling:    void apply(const ContactStep &c, const NormalPart &np, double Fn,
//                          ContactResult &out);  (adds torque)
// Fn is the normal force the Coulomb and rolling caps use.

/// A row of the table: a model with the keyword and enum value it is selected by.
struct ModelEntry {
  ModelKind kind;
  int id; ///< the NormalModel/TangentialModel/CohesionModel/RollingModel value
  const ModelSpec *spec;
  bool matches(const char *word) const; ///< word is the name or the alias
};

/// The whole table, in model_list.h's order (normal, tangential, cohesion, rolling).
List<ModelEntry> contact_models();
/// The model of `kind` named `word` (name or alias), or nullptr.
const ModelEntry *find_model(ModelKind kind, const char *word);
/// The models of `kind` for messages: "hertz, eepa (alias edinburgh)".
std::string model_names(ModelKind kind);
/// Selects `entry` in `settings`.
void select_model(ContactSettings &settings, const ModelEntry &entry);
/// The selected model of each kind, in kind order (normal, tangential, cohesion, rolling).
std::vector<const ModelEntry *> selected_models(const ContactSettings &settings);

/// The switch `keyword` of any model, or nullptr (the fix accepts every model's switches
/// whatever the models, as LIGGGHTS' soil files pass them in one word list).
const SwitchSpec *find_switch(const char *keyword);
/// Every switch keyword once, in table order: "tangential_damping, limitForce, ...".
std::string switch_keywords();
/// The default of switch `keyword` for the selected models (false if none declares it).
bool switch_default(const ContactSettings &settings, const char *keyword);

/// The properties the selected models read, each name once, in table order.
std::vector<const PropertySpec *> required_properties(const ContactSettings &settings);

/// The table's own consistency (unique names, non-empty fields, one destination per property,
/// one meaning per property and switch name, every enum value has a model): the problems found,
/// one line each; empty if none. Checked by a unit test.
std::vector<std::string> table_problems();

} // namespace wheelsim::contact
