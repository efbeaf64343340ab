// See precompiled_contact_models.h. Compiled with contact_model_styles/ on its include path (the
// stand-ins for LIGGGHTS' generated style_*_model.h lists) and with hidden visibility, so that the
// template code instantiated here from LIGGGHTS' headers is not exported from liggghts-wheel and
// cannot take the place of the library's own copies (liggghts-wheel exports its symbols).
#include "precompiled_contact_models.h"

// LIGGGHTS (granular_styles.h's includes, without the library's own registration class, which
// reads its generated whitelist):
// fix_insert_stream.h first: Debian's fix_insert_stream_predefined.h, which pair_gran_base.h
// includes, derives from FixInsertStream without including its header.
#include "fix_insert_stream.h"

#include "contact_models.h"                    // GranStyle, ContactModel
#include "fix_wall_gran_base.h"                // Walls::Granular
#include "granular_pair_style.h"               // PairStyles::Factory
#include "granular_wall.h"                     // Walls::Factory
#include "pair_gran_base.h"                    // PairStyles::Granular
#include "rolling_model_epsdt.h"               // wheelsim's rolling_friction epsdt
#include "rolling_model_krot.h"                // wheelsim's rolling_friction krot
#include "tangential_model_history_adhesive.h" // wheelsim's tangential history_adhesive

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace wheelsim {
namespace {

using namespace LIGGGHTS;
using namespace LIGGGHTS::ContactModels;

template <typename T>
PairStyles::IGranularPairStyle *create_pair(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::PairGran *parent,
                                            const int64_t hash) {
  return new T(lmp, parent, hash);
}

template <typename T>
Walls::IGranularWall *create_wall(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::FixWallGran *parent,
                                  const int64_t hash) {
  return new T(lmp, parent, hash);
}

// The factories' creator types (AbstractFactory's own typedef is private).
using PairCreator = PairStyles::IGranularPairStyle *(*)(LAMMPS_NS::LAMMPS *, LAMMPS_NS::PairGran *,
                                                        int64_t);
using WallCreator = Walls::IGranularWall *(*)(LAMMPS_NS::LAMMPS *, LAMMPS_NS::FixWallGran *,
                                              int64_t);

/// One combination: its keywords (for the listing) and the two registrations.
struct Combination {
  const char *keywords;
  int64_t hashcode;
  PairCreator pair_creator;
  WallCreator wall_creator;
};

template <int Normal, int Tangential, int Cohesion, int Rolling, int Surface>
Combination combination(const char *keywords) {
  using Style = GranStyle<Normal, Tangential, Cohesion, Rolling, Surface>;
  using Model = ContactModel<Style>;
  return {keywords, Style::HASHCODE, &create_pair<PairStyles::Granular<Model>>,
          &create_wall<Walls::Granular<Model>>};
}

/// The combinations, each declared once here. A model named here must be listed in
/// contact_model_styles/ (its id is declared there).
/// Every combination with wheelsim's `rolling_friction krot` or `epsdt`, or with `tangential
/// history_adhesive`, must be here: LIGGGHTS' generic class does not know these models and stops
/// with "Unknown rolling model" (or tangential model).
std::vector<Combination> combinations() {
  return {
      combination<HERTZ, TANGENTIAL_HISTORY, COHESION_SJKR, ROLLING_CDT, SURFACE_DEFAULT>(
          "model hertz tangential history cohesion sjkr rolling_friction cdt"),
      combination<HERTZ, TANGENTIAL_HISTORY, COHESION_OFF, ROLLING_KROT, SURFACE_DEFAULT>(
          "model hertz tangential history rolling_friction krot"),
      combination<HERTZ, TANGENTIAL_HISTORY, COHESION_SJKR, ROLLING_KROT, SURFACE_DEFAULT>(
          "model hertz tangential history cohesion sjkr rolling_friction krot"),
      combination<HERTZ, TANGENTIAL_HISTORY, COHESION_OFF, ROLLING_EPSDT, SURFACE_DEFAULT>(
          "model hertz tangential history rolling_friction epsdt"),
      combination<HERTZ, TANGENTIAL_HISTORY, COHESION_SJKR, ROLLING_EPSDT, SURFACE_DEFAULT>(
          "model hertz tangential history cohesion sjkr rolling_friction epsdt"),
      combination<HERTZ, TANGENTIAL_HISTORY_ADHESIVE, COHESION_SJKR, ROLLING_OFF, SURFACE_DEFAULT>(
          "model hertz tangential history_adhesive cohesion sjkr"),
      combination<HERTZ, TANGENTIAL_HISTORY_ADHESIVE, COHESION_SJKR, ROLLING_CDT, SURFACE_DEFAULT>(
          "model hertz tangential history_adhesive cohesion sjkr rolling_friction cdt"),
      combination<HERTZ, TANGENTIAL_HISTORY_ADHESIVE, COHESION_SJKR, ROLLING_EPSDT,
                  SURFACE_DEFAULT>(
          "model hertz tangential history_adhesive cohesion sjkr rolling_friction epsdt")};
}

} // namespace

std::vector<std::string> precompiled_contact_model_names() {
  std::vector<std::string> names;
  for (const Combination &c : combinations())
    names.emplace_back(c.keywords);
  return names;
}

int register_precompiled_contact_models() {
  const char *off = std::getenv(kGenericContactModelsEnv);
  if (off != nullptr && std::strcmp(off, "1") == 0)
    return 0;
  if (off != nullptr && *off != '\0' && std::strcmp(off, "0") != 0)
    throw std::runtime_error(std::string("environment variable ") + kGenericContactModelsEnv +
                             "='" + off +
                             "': expected 1 (LIGGGHTS' own contact-model classes "
                             "only) or 0 / unset (liggghts-wheel's precompiled combinations)");
  static_assert(ROLLING_KROT == kKrotRollingModelId, "rolling_model_krot.h: two ids");
  static_assert(ROLLING_EPSDT == kEpsdtRollingModelId, "rolling_model_epsdt.h: two ids");
  static_assert(TANGENTIAL_HISTORY_ADHESIVE == kHistoryAdhesiveTangentialModelId,
                "tangential_model_history_adhesive.h: two ids");
  ContactModels::Factory::instance().addRollingModel("krot", kKrotRollingModelId);
  ContactModels::Factory::instance().addRollingModel("epsdt", kEpsdtRollingModelId);
  ContactModels::Factory::instance().addTangentialModel("history_adhesive",
                                                        kHistoryAdhesiveTangentialModelId);
  PairStyles::Factory &pairs = PairStyles::Factory::instance();
  Walls::Factory &walls = Walls::Factory::instance();
  int registered = 0;
  for (const Combination &c : combinations()) {
    pairs.addStyle("gran", static_cast<int>(c.hashcode), c.pair_creator);
    walls.addStyle("gran", static_cast<int>(c.hashcode), c.wall_creator);
    ++registered;
  }
  return registered;
}

} // namespace wheelsim
