// See style_registration.h. The only file of the project that touches a private member of
// LIGGGHTS: Modify::fix_map, the map from style name to creator function that Modify::add_fix
// consults. We reach it with the explicit-instantiation member-pointer technique: C++ does not
// apply access checks to the names used in an explicit template instantiation
// ([temp.spec]/6 in C++17), so the instantiation below may name &Modify::fix_map, and the friend
// function it defines hands that member pointer out. No layout assumption and no copy of
// LIGGGHTS' class are involved; if a future LIGGGHTS renames the member this fails to compile.
#include "style_registration.h"

#include "lammps.h"
#include "modify.h"

#include <map>
#include <stdexcept>

// The style headers, listed by CMake in wheelsim_style_headers.h (one #include per header of this
// folder that has a `FixStyle(...)` block, found the way LIGGGHTS' Make.sh finds them). They are
// read twice, as LIGGGHTS' modify.cpp reads its style_fix.h: first with FIX_CLASS undefined for
// the class declarations, then with FIX_CLASS defined, where each header shows only its
// FixStyle line, which we expand into a table entry.
#include "wheelsim_style_headers.h"

namespace {

using FixCreator = LAMMPS_NS::Fix *(*)(LAMMPS_NS::LAMMPS *, int, char **);
using FixMap = std::map<std::string, FixCreator>;

template <typename FixClass>
LAMMPS_NS::Fix *create_fix(LAMMPS_NS::LAMMPS *lmp, int narg, char **arg) {
  return new FixClass(lmp, narg, arg);
}

struct StyleEntry {
  const char *name;
  FixCreator creator;
};

const StyleEntry kFixStyles[] = {
#define FIX_CLASS
#define FixStyle(key, Class) {#key, &create_fix<LAMMPS_NS::Class>},
#include "wheelsim_style_headers.h"
#undef FixStyle
#undef FIX_CLASS
};

// Tag type naming the private member's type without naming Modify's private typedef.
struct ModifyFixMapTag {
  using type = FixMap *LAMMPS_NS::Modify::*;
  friend type fix_map_member(ModifyFixMapTag);
};

template <typename Tag, typename Tag::type Member> struct PrivateMemberAccess {
  friend typename Tag::type fix_map_member(Tag) { return Member; }
};

// The explicit instantiation: the one place where the private name appears.
template struct PrivateMemberAccess<ModifyFixMapTag, &LAMMPS_NS::Modify::fix_map>;

} // namespace

namespace wheelsim {

std::vector<std::string> wheelsim_fix_style_names() {
  std::vector<std::string> names;
  for (const StyleEntry &entry : kFixStyles)
    names.emplace_back(entry.name);
  return names;
}

void register_wheelsim_styles(LAMMPS_NS::LAMMPS *lmp) {
  FixMap *fix_map = lmp->modify->*fix_map_member(ModifyFixMapTag{});
  if (fix_map == nullptr)
    throw std::runtime_error("LIGGGHTS' fix style map is not initialised (call after the "
                             "LAMMPS constructor)");
  for (const StyleEntry &entry : kFixStyles) {
    if (fix_map->count(entry.name) != 0)
      throw std::runtime_error(std::string("fix style '") + entry.name +
                               "' already exists in this LIGGGHTS build; refusing to replace it");
    (*fix_map)[entry.name] = entry.creator;
  }
}

} // namespace wheelsim
