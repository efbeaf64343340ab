// In-process tests of style registration: a LAMMPS instance from Debian's libliggghts, our styles
// registered into it, then used through LIGGGHTS' own command interpreter.
#include "style_registration.h"

#include "input.h"
#include "lammps.h"
#include "modify.h"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::unique_ptr<LAMMPS_NS::LAMMPS> make_quiet_lammps() {
  const char *args[] = {"test", "-screen", "none", "-log", "none"};
  std::vector<char *> argv;
  for (const char *a : args)
    argv.push_back(const_cast<char *>(a));
  int argc = static_cast<int>(argv.size());
  char **argvp = argv.data();
  return std::make_unique<LAMMPS_NS::LAMMPS>(argc, argvp, MPI_COMM_WORLD);
}

TEST(StyleRegistration, ListsTheSelftestStyle) {
  const std::vector<std::string> names = wheelsim::wheelsim_fix_style_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "wheelsim/selftest"), names.end());
}

TEST(StyleRegistration, RegisteredStyleIsUsableFromCommands) {
  auto lmp = make_quiet_lammps();
  wheelsim::register_wheelsim_styles(lmp.get());
  for (const char *cmd :
       {"atom_style granular", "atom_modify map array sort 0 0", "units si",
        "region box block 0 1 0 1 0 1 units box", "create_box 1 box",
        "create_atoms 1 single 0.5 0.5 0.5 units box",
        "create_atoms 1 single 0.2 0.5 0.5 units box", "fix st all wheelsim/selftest"})
    lmp->input->one(cmd);
  const int ifix = lmp->modify->find_fix("st");
  ASSERT_GE(ifix, 0);
  EXPECT_STREQ(lmp->modify->fix[ifix]->style, "wheelsim/selftest");
  EXPECT_DOUBLE_EQ(lmp->modify->fix[ifix]->compute_scalar(), 2.0);
}

TEST(StyleRegistration, RefusesToRegisterTwice) {
  auto lmp = make_quiet_lammps();
  wheelsim::register_wheelsim_styles(lmp.get());
  try {
    wheelsim::register_wheelsim_styles(lmp.get());
    FAIL() << "second registration should throw";
  } catch (const std::runtime_error &e) {
    // names the first of our styles it met again
    EXPECT_NE(std::string(e.what()).find("'" + wheelsim::wheelsim_fix_style_names().front() + "'"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("already exists"), std::string::npos) << e.what();
  }
}

TEST(StyleRegistration, UnregisteredInstanceDoesNotKnowTheStyle) {
  // Guards against the test above passing for the wrong reason (a style LIGGGHTS already had):
  // on a fresh instance the first registration succeeds, i.e. no name of ours was in the map.
  auto lmp = make_quiet_lammps();
  EXPECT_NO_THROW(wheelsim::register_wheelsim_styles(lmp.get()));
}

} // namespace

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  MPI_Finalize();
  return result;
}
