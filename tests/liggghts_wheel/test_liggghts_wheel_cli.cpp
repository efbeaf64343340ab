// The liggghts-wheel command line: LIGGGHTS' own switches pass through; -h/--help (wheelsim's
// styles, then LIGGGHTS' help) and --version exit 0; a misspelt switch or one without its value
// exits 2 naming it (wheelsim/cli.h), where LIGGGHTS alone says "Invalid command-line argument".
#include "wheelsim/cli.h"

#include "cli_test_util.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using wheelsim::cli_test::CommandResult;

/// Runs liggghts-wheel (a singleton MPI process) in `dir`.
CommandResult liggghts_wheel(const std::string &args, const fs::path &dir) {
  return wheelsim::cli_test::run_command("cd " + dir.string() + " && " LIGGGHTS_WHEEL_EXE " " +
                                         args);
}

class LiggghtsWheelCli : public testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("liggghts_wheel_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(LiggghtsWheelCli, HelpExitsZeroWithOurStylesAndLiggghtsHelp) {
  for (const char *flag : {"-h", "-help", "--help"}) {
    const CommandResult r = liggghts_wheel(flag, dir_);
    EXPECT_EQ(r.status, 0) << flag << ": " << r.output;
    EXPECT_NE(r.output.find("Styles added by wheelsim:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("fix wheel/cosim"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Command line options"), std::string::npos) << r.output; // LIGGGHTS'
    EXPECT_FALSE(fs::exists(dir_ / "log.liggghts")) << "a help request writes no log";
  }
}

TEST_F(LiggghtsWheelCli, VersionExitsZero) {
  const CommandResult r = liggghts_wheel("--version", dir_);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, wheelsim::cli::version_line("liggghts-wheel") + "\n");
}

TEST_F(LiggghtsWheelCli, MisspeltSwitchIsNamedWithTheNearestOne) {
  CommandResult r = liggghts_wheel("-inn in.deck -log none", dir_);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("liggghts-wheel: unknown option '-inn' (did you mean '-in'?)"),
            std::string::npos)
      << r.output;
  r = liggghts_wheel("-in in.deck -screne none", dir_);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("unknown option '-screne' (did you mean '-screen'?)"), std::string::npos)
      << r.output;
  r = liggghts_wheel("in.deck", dir_);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("unexpected argument 'in.deck'"), std::string::npos) << r.output;
}

TEST_F(LiggghtsWheelCli, SwitchWithoutItsValueIsNamed) {
  CommandResult r = liggghts_wheel("-log none -in", dir_);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("liggghts-wheel: -in needs the input deck"), std::string::npos)
      << r.output;
  r = liggghts_wheel("-in in.deck -var bed", dir_);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("-var needs a name and its value(s)"), std::string::npos) << r.output;
}

} // namespace
