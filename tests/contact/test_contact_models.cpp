// Unit tests of the contact-model descriptor table (liggghts_fix/contact/contact_model.h): the
// table is consistent, the fix's look-ups work, and every model and property is documented.
#include "contact_model.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace wc = wheelsim::contact;

namespace {

std::string read_text(const std::string &path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

} // namespace

TEST(ContactModels, TableIsConsistent) {
  for (const std::string &problem : wc::table_problems())
    ADD_FAILURE() << problem;
  // The checks themselves, spelled out for the reader of a failure.
  std::set<std::string> keywords;
  for (const wc::ModelEntry &e : wc::contact_models()) {
    const std::string key = std::string(wc::kind_keyword(e.kind)) + " " + e.spec->name;
    EXPECT_TRUE(keywords.insert(key).second) << key << " twice";
    EXPECT_GT(std::strlen(e.spec->summary), 0u) << key;
    for (const wc::PropertySpec &p : e.spec->properties) {
      EXPECT_GT(std::strlen(p.name), 0u) << key;
      EXPECT_GT(std::strlen(p.unit), 0u) << key << " " << p.name;
      EXPECT_GT(std::strlen(p.meaning), 0u) << key << " " << p.name;
    }
  }
}

TEST(ContactModels, TableHoldsTheModelsOfTheFix) {
  EXPECT_EQ(wc::model_names(wc::ModelKind::Normal), "hertz, eepa (alias edinburgh)");
  EXPECT_EQ(wc::model_names(wc::ModelKind::Tangential), "history, history_adhesive");
  EXPECT_EQ(wc::model_names(wc::ModelKind::Cohesion), "off, sjkr");
  EXPECT_EQ(wc::model_names(wc::ModelKind::Rolling), "off, epsd2, cdt, krot, epsdt");
  EXPECT_EQ(wc::switch_keywords(),
            "tangential_damping, limitForce, fixKc, tangential_reduce, torsionTorque");
}

TEST(ContactModels, LookUpSelectsTheEnumValue) {
  wc::ContactSettings s;
  const wc::ModelEntry *eepa = wc::find_model(wc::ModelKind::Normal, "edinburgh");
  ASSERT_NE(eepa, nullptr);
  EXPECT_STREQ(eepa->spec->name, "eepa");
  wc::select_model(s, *eepa);
  EXPECT_EQ(s.normal, wc::NormalModel::Eepa);
  wc::select_model(s, *wc::find_model(wc::ModelKind::Rolling, "cdt"));
  EXPECT_EQ(s.rolling, wc::RollingModel::Cdt);
  wc::select_model(s, *wc::find_model(wc::ModelKind::Cohesion, "sjkr"));
  EXPECT_EQ(s.cohesion, wc::CohesionModel::Sjkr);
  const auto selected = wc::selected_models(s);
  ASSERT_EQ(selected.size(), 4u);
  EXPECT_STREQ(selected[0]->spec->name, "eepa");
  EXPECT_STREQ(selected[1]->spec->name, "history");
  EXPECT_STREQ(selected[2]->spec->name, "sjkr");
  EXPECT_STREQ(selected[3]->spec->name, "cdt");
  // eepa declares a time-step rule; hertz does not
  EXPECT_NE(eepa->spec->timestep, nullptr);
  EXPECT_EQ(wc::find_model(wc::ModelKind::Normal, "hertz")->spec->timestep, nullptr);
}

TEST(ContactModels, UnknownNamesAreNotFound) {
  EXPECT_EQ(wc::find_model(wc::ModelKind::Normal, "hooke"), nullptr);
  EXPECT_EQ(wc::find_model(wc::ModelKind::Normal, "sjkr"), nullptr); // a cohesion model
  EXPECT_EQ(wc::find_model(wc::ModelKind::Rolling, "epsd"), nullptr);
  EXPECT_EQ(wc::find_model(wc::ModelKind::Cohesion, "sjkr2"), nullptr);
  EXPECT_EQ(wc::find_switch("heating_normal_hertz"), nullptr);
}

TEST(ContactModels, RequiredPropertiesFollowTheSelectedModels) {
  auto names = [](const wc::ContactSettings &s) {
    std::string out;
    for (const wc::PropertySpec *p : wc::required_properties(s))
      out += std::string(out.empty() ? "" : " ") + p->name;
    return out;
  };
  wc::ContactSettings s;
  EXPECT_EQ(names(s), "youngsModulus poissonsRatio coefficientRestitution coefficientFriction");
  s.rolling = wc::RollingModel::Epsd2;
  s.cohesion = wc::CohesionModel::Sjkr;
  EXPECT_EQ(names(s), "youngsModulus poissonsRatio coefficientRestitution coefficientFriction "
                      "cohesionEnergyDensity coefficientRollingFriction");
  s = {};
  s.normal = wc::NormalModel::Eepa;
  EXPECT_EQ(names(s), "youngsModulus poissonsRatio coefficientRestitution UnloadingStiffness "
                      "coefficientAdhesionStiffness pullOffForce surfaceEnergy overlapExponent "
                      "adhesionExponent coefficientFriction");
}

TEST(ContactModels, SwitchDefaultsDependOnTheNormalModel) {
  wc::ContactSettings s;
  EXPECT_FALSE(wc::switch_default(s, "limitForce"));
  EXPECT_TRUE(wc::switch_default(s, "tangential_damping"));
  s.normal = wc::NormalModel::Eepa;
  EXPECT_TRUE(wc::switch_default(s, "limitForce"));
  // ContactSettings' own defaults agree with the table's
  const wc::ContactSettings defaults;
  EXPECT_EQ(defaults.tangentialDamping, wc::switch_default(defaults, "tangential_damping"));
  s.cohesion = wc::CohesionModel::Sjkr;
  s.rolling = wc::RollingModel::Epsd2;
  EXPECT_EQ(defaults.fixKc, wc::switch_default(s, "fixKc"));
  EXPECT_EQ(defaults.tangentialReduce, wc::switch_default(s, "tangential_reduce"));
  EXPECT_EQ(defaults.torsionTorque, wc::switch_default(s, "torsionTorque"));
}

TEST(ContactModels, RangesAreCheckedFromTheTable) {
  const wc::Material particle{5.0e7, 0.3}, wheel{2.0e11, 0.3};
  wc::PairMaterial pair;
  wc::ContactSettings s;
  s.cohesion = wc::CohesionModel::Sjkr;
  pair.cohesionEnergyDensity = -1.0;
  try {
    wc::makePairConstants(particle, wheel, pair, s);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument &err) {
    EXPECT_STREQ(err.what(), "contact law: cohesionEnergyDensity [J/m^3] must be >= 0, got -1");
  }
  s.cohesion = wc::CohesionModel::Off; // not read, not checked
  EXPECT_NO_THROW(wc::makePairConstants(particle, wheel, pair, s));
  pair = {};
  pair.coefficientRestitution = 1.5;
  try {
    wc::makePairConstants(particle, wheel, pair, s);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument &err) {
    EXPECT_STREQ(err.what(), "contact law: coefficientRestitution must be in (0.05, 1], got 1.5");
  }
  EXPECT_THROW(wc::makePairConstants({5.0e7, 0.6}, wheel, {}, s), std::invalid_argument);
}

// Every model has its section in docs/contact-law.md and every property and switch is named in
// docs/fix-wheel-cosim.md (the fix's keyword and materials reference).
TEST(ContactModels, EveryModelPropertyAndSwitchIsDocumented) {
  const std::string law = read_text(WHEELSIM_DOCS_DIR "/contact-law.md");
  const std::string fix = read_text(WHEELSIM_DOCS_DIR "/fix-wheel-cosim.md");
  ASSERT_FALSE(law.empty());
  ASSERT_FALSE(fix.empty());
  for (const wc::ModelEntry &e : wc::contact_models()) {
    const std::string words = std::string(wc::kind_keyword(e.kind)) + " " + e.spec->name;
    static const char *const kHeading[] = {"Normal", "Tangential", "Cohesion", "Rolling"};
    const std::string heading =
        std::string("## ") + kHeading[static_cast<int>(e.kind)] + ": `" + words;
    if (std::strcmp(e.spec->name, "off") != 0) {
      EXPECT_NE(law.find(heading), std::string::npos)
          << "docs/contact-law.md has no section '" << heading << "...'";
    }
    EXPECT_NE(fix.find(e.spec->name), std::string::npos)
        << words << " is not in docs/fix-wheel-cosim.md";
    for (const wc::PropertySpec &p : e.spec->properties)
      EXPECT_NE(fix.find(std::string("`") + p.name + "`"), std::string::npos)
          << "property " << p.name << " of " << words << " is not in docs/fix-wheel-cosim.md";
    for (const wc::SwitchSpec &w : e.spec->switches)
      EXPECT_NE(fix.find(std::string("`") + w.keyword + "`"), std::string::npos)
          << "switch " << w.keyword << " of " << words << " is not in docs/fix-wheel-cosim.md";
  }
}
