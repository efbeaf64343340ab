// The contact-model descriptor table (contact_model.h), built from model_list.h.
#include "contact_law.h"
#include "contact_model.h"

// the model headers (their `spec`), after the types they use
#define WHEELSIM_CONTACT_MODEL_HEADERS
#include "model_list.h"

#include <cstring>
#include <iterator>
#include <set>
#include <sstream>

namespace wheelsim::contact {

namespace {

#define WHEELSIM_NORMAL_ENTRY(Enumerator, name)                                                    \
  {ModelKind::Normal, static_cast<int>(NormalModel::Enumerator), &name::spec},
#define WHEELSIM_TANGENTIAL_ENTRY(Enumerator, name)                                                \
  {ModelKind::Tangential, static_cast<int>(TangentialModel::Enumerator), &name::spec},
#define WHEELSIM_COHESION_ENTRY(Enumerator, name)                                                  \
  {ModelKind::Cohesion, static_cast<int>(CohesionModel::Enumerator), &name::spec},
#define WHEELSIM_ROLLING_ENTRY(Enumerator, name)                                                   \
  {ModelKind::Rolling, static_cast<int>(RollingModel::Enumerator), &name::spec},

constexpr ModelEntry kTable[] = {
    WHEELSIM_NORMAL_MODELS(WHEELSIM_NORMAL_ENTRY)         //
    WHEELSIM_TANGENTIAL_MODELS(WHEELSIM_TANGENTIAL_ENTRY) //
    WHEELSIM_COHESION_MODELS(WHEELSIM_COHESION_ENTRY)     //
    WHEELSIM_ROLLING_MODELS(WHEELSIM_ROLLING_ENTRY)       //
};

/// Enumerators per kind, for the consistency check (each must have exactly one row).
#define WHEELSIM_COUNT(Enumerator, name) +1
constexpr int kEnumCount[] = {
    0 WHEELSIM_NORMAL_MODELS(WHEELSIM_COUNT), 0 WHEELSIM_TANGENTIAL_MODELS(WHEELSIM_COUNT),
    0 WHEELSIM_COHESION_MODELS(WHEELSIM_COUNT), 0 WHEELSIM_ROLLING_MODELS(WHEELSIM_COUNT)};

int selected_id(const ContactSettings &s, ModelKind kind) {
  switch (kind) {
  case ModelKind::Normal:
    return static_cast<int>(s.normal);
  case ModelKind::Tangential:
    return static_cast<int>(s.tangential);
  case ModelKind::Cohesion:
    return static_cast<int>(s.cohesion);
  case ModelKind::Rolling:
    return static_cast<int>(s.rolling);
  }
  return -1;
}

bool empty(const char *text) { return text == nullptr || *text == '\0'; }

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

} // namespace

const char *kind_keyword(ModelKind kind) {
  switch (kind) {
  case ModelKind::Normal:
    return "model";
  case ModelKind::Tangential:
    return "tangential";
  case ModelKind::Cohesion:
    return "cohesion";
  case ModelKind::Rolling:
    return "rolling_friction";
  }
  return "?";
}

const char *style_keyword(PropertyStyle style) {
  switch (style) {
  case PropertyStyle::PerType:
    return "peratomtype";
  case PropertyStyle::PerTypePair:
    return "peratomtypepair";
  case PropertyStyle::Scalar:
    return "scalar";
  }
  return "?";
}

bool Range::contains(double v) const {
  return (loInclusive ? v >= lo : v > lo) && (hiInclusive ? v <= hi : v < hi);
}

std::string Range::text() const {
  const bool openLo = lo == -kInf, openHi = hi == kInf;
  if (openLo && openHi)
    return "finite";
  if (openHi)
    return (loInclusive ? ">= " : "> ") + number(lo);
  if (openLo)
    return (hiInclusive ? "<= " : "< ") + number(hi);
  return std::string("in ") + (loInclusive ? "[" : "(") + number(lo) + ", " + number(hi) +
         (hiInclusive ? "]" : ")");
}

bool ModelEntry::matches(const char *word) const {
  return std::strcmp(word, spec->name) == 0 || (spec->alias && std::strcmp(word, spec->alias) == 0);
}

List<ModelEntry> contact_models() { return List<ModelEntry>(kTable); }

const ModelEntry *find_model(ModelKind kind, const char *word) {
  for (const ModelEntry &e : kTable)
    if (e.kind == kind && e.matches(word))
      return &e;
  return nullptr;
}

std::string model_names(ModelKind kind) {
  std::string names;
  for (const ModelEntry &e : kTable) {
    if (e.kind != kind)
      continue;
    if (!names.empty())
      names += ", ";
    names += e.spec->name;
    if (e.spec->alias)
      names += std::string(" (alias ") + e.spec->alias + ")";
  }
  return names;
}

void select_model(ContactSettings &s, const ModelEntry &e) {
  switch (e.kind) {
  case ModelKind::Normal:
    s.normal = static_cast<NormalModel>(e.id);
    break;
  case ModelKind::Tangential:
    s.tangential = static_cast<TangentialModel>(e.id);
    break;
  case ModelKind::Cohesion:
    s.cohesion = static_cast<CohesionModel>(e.id);
    break;
  case ModelKind::Rolling:
    s.rolling = static_cast<RollingModel>(e.id);
    break;
  }
}

std::vector<const ModelEntry *> selected_models(const ContactSettings &s) {
  std::vector<const ModelEntry *> out;
  for (ModelKind kind : kModelKinds)
    for (const ModelEntry &e : kTable)
      if (e.kind == kind && e.id == selected_id(s, kind))
        out.push_back(&e);
  return out;
}

const SwitchSpec *find_switch(const char *keyword) {
  for (const ModelEntry &e : kTable)
    for (const SwitchSpec &w : e.spec->switches)
      if (std::strcmp(w.keyword, keyword) == 0)
        return &w;
  return nullptr;
}

std::string switch_keywords() {
  std::string out;
  std::set<std::string> seen;
  for (const ModelEntry &e : kTable)
    for (const SwitchSpec &w : e.spec->switches)
      if (seen.insert(w.keyword).second)
        out += (out.empty() ? "" : ", ") + std::string(w.keyword);
  return out;
}

bool switch_default(const ContactSettings &s, const char *keyword) {
  for (const ModelEntry *e : selected_models(s))
    for (const SwitchSpec &w : e->spec->switches)
      if (std::strcmp(w.keyword, keyword) == 0)
        return w.defaultOn;
  return false;
}

std::vector<const PropertySpec *> required_properties(const ContactSettings &s) {
  std::vector<const PropertySpec *> out;
  std::set<std::string> seen;
  for (const ModelEntry *e : selected_models(s))
    for (const PropertySpec &p : e->spec->properties)
      if (seen.insert(p.name).second)
        out.push_back(&p);
  return out;
}

std::vector<std::string> table_problems() {
  std::vector<std::string> problems;
  auto problem = [&](const std::string &text) { problems.push_back(text); };
  for (ModelKind kind : kModelKinds) {
    int rows = 0;
    for (const ModelEntry &e : kTable)
      rows += e.kind == kind;
    if (rows != kEnumCount[static_cast<int>(kind)])
      problem(std::string(kind_keyword(kind)) + ": rows and enumerators differ");
  }
  // Properties and switches are compared by name across the whole table: one name, one thing.
  std::vector<const PropertySpec *> properties;
  std::vector<const SwitchSpec *> switches;
  for (const ModelEntry &e : kTable) {
    const ModelSpec &m = *e.spec;
    const std::string where = std::string(kind_keyword(e.kind)) + " " +
                              (empty(m.name) ? std::string("<unnamed>") : m.name);
    if (empty(m.name) || empty(m.summary) || m.liggghts == nullptr)
      problem(where + ": name, summary and liggghts must be set");
    for (const ModelEntry &o : kTable) {
      if (&o == &e || o.kind != e.kind)
        continue;
      if (o.matches(m.name) || (m.alias && o.matches(m.alias)))
        problem(where + ": keyword value (or alias) used twice");
      if (&o < &e && o.id == e.id)
        problem(where + ": enum value used twice");
    }
    if ((m.timestep == nullptr) != empty(m.timestepRule))
      problem(where + ": a time-step rule needs both the function and its text");
    for (const PropertySpec &p : m.properties) {
      if (empty(p.name) || empty(p.unit) || empty(p.meaning))
        problem(where + ": a property without name, unit or meaning");
      if ((p.material == nullptr) == (p.pair == nullptr) ||
          (p.material != nullptr) != (p.style == PropertyStyle::PerType))
        problem(where + ": property " + p.name +
                " needs exactly one destination: Material for peratomtype, else PairMaterial");
      if (!(p.range.lo <= p.range.hi))
        problem(where + ": property " + p.name + " has an empty range");
      for (const PropertySpec *q : properties)
        if (std::strcmp(q->name, p.name) == 0 &&
            (q->style != p.style || q->material != p.material || q->pair != p.pair ||
             std::strcmp(q->unit, p.unit) != 0 || q->range.lo != p.range.lo ||
             q->range.hi != p.range.hi || q->range.loInclusive != p.range.loInclusive ||
             q->range.hiInclusive != p.range.hiInclusive))
          problem(where + ": property " + p.name + " declared differently by another model");
      properties.push_back(&p);
    }
    for (const SwitchSpec &w : m.switches) {
      if (empty(w.keyword) || empty(w.meaning) || w.set == nullptr)
        problem(where + ": a switch without keyword, meaning or setter");
      for (const SwitchSpec *v : switches)
        if (std::strcmp(v->keyword, w.keyword) == 0 && v->set != w.set)
          problem(where + ": switch " + w.keyword + " sets something else in another model");
      switches.push_back(&w);
    }
  }
  // The default models of ContactSettings are rows of the table.
  const ContactSettings defaults;
  if (selected_models(defaults).size() != std::size(kModelKinds))
    problem("ContactSettings' default models are not all in the table");
  return problems;
}

} // namespace wheelsim::contact
