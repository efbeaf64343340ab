// wheelsim_cli in process: the nearest-option suggestion, and parse()'s exit statuses and
// messages on a small CLI11 app.
#include "wheelsim/cli.h"

#include <CLI/CLI.hpp>

#include <gtest/gtest.h>

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace wheelsim::cli;

/// Parses `args` with an app like the tools' (one required option, one optional), capturing
/// stdout and stderr.
struct Parsed {
  std::optional<int> status;
  std::string out, err;
};

Parsed parse_args(std::vector<std::string> args) {
  CLI::App app{"test tool"};
  double radius = 0, width = 0;
  app.add_option("--radius", radius, "radius [m]")->required();
  app.add_option("--width", width, "width [m]");
  setup(app, "tool");
  args.insert(args.begin(), "tool");
  std::vector<const char *> argv;
  for (const auto &a : args)
    argv.push_back(a.c_str());
  Parsed p;
  std::ostringstream out;
  auto *old_out = std::cout.rdbuf(out.rdbuf());
  testing::internal::CaptureStderr();
  p.status = parse(app, static_cast<int>(argv.size()), argv.data());
  p.err = testing::internal::GetCapturedStderr();
  std::cout.rdbuf(old_out);
  p.out = out.str();
  return p;
}

TEST(Cli, NearestOption) {
  const std::vector<std::string> valid{"--radius", "--width", "--load", "-h", "--help"};
  EXPECT_EQ(nearest_option("--raduis", valid), "--radius");
  EXPECT_EQ(nearest_option("--raduis=0.3", valid), "--radius");
  EXPECT_EQ(nearest_option("--widht", valid), "--width");
  EXPECT_EQ(nearest_option("-loda", valid), "--load");
  EXPECT_EQ(nearest_option("--zzzzzzzz", valid), "");
  // Single letters are never suggested (they are contained in most words).
  EXPECT_EQ(nearest_option("--hhhhhhh", {"-h"}), "");
  EXPECT_EQ(unknown_option_message("--raduis=0.3", valid),
            "unknown option '--raduis' (did you mean '--radius'?)");
  EXPECT_EQ(unknown_option_message("--zzzzzzzz", valid), "unknown option '--zzzzzzzz'");
}

TEST(Cli, VersionLine) {
  const std::string v = version_line("tool");
  EXPECT_EQ(v.rfind("tool ", 0), 0u) << v;
  EXPECT_NE(v.find(" (git "), std::string::npos) << v;
}

TEST(Cli, HelpAndVersionExitZero) {
  Parsed p = parse_args({"--help"});
  ASSERT_TRUE(p.status);
  EXPECT_EQ(*p.status, kExitSuccess);
  EXPECT_NE(p.out.find("--radius"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find("Exit status"), std::string::npos) << p.out;
  p = parse_args({"--version"});
  ASSERT_TRUE(p.status);
  EXPECT_EQ(*p.status, kExitSuccess);
  EXPECT_EQ(p.out, version_line("tool") + "\n");
}

TEST(Cli, MisspeltOptionIsNamedBeforeTheRequiredOneItWasMeantToGive) {
  const Parsed p = parse_args({"--raduis", "0.3"});
  ASSERT_TRUE(p.status);
  EXPECT_EQ(*p.status, kExitUsage);
  EXPECT_EQ(p.err, "tool: unknown option '--raduis' (did you mean '--radius'?)\n"
                   "Run 'tool --help' for the options.\n");
}

TEST(Cli, UsageErrorsExitTwo) {
  Parsed p = parse_args({"--width", "1"});
  ASSERT_TRUE(p.status);
  EXPECT_EQ(*p.status, kExitUsage);
  EXPECT_NE(p.err.find("tool: --radius is required"), std::string::npos) << p.err;
  p = parse_args({"--radius", "abc"});
  ASSERT_TRUE(p.status);
  EXPECT_EQ(*p.status, kExitUsage);
  EXPECT_NE(p.err.find("--radius"), std::string::npos) << p.err;
  p = parse_args({"--radius", "1", "stray"});
  ASSERT_TRUE(p.status);
  EXPECT_EQ(*p.status, kExitUsage);
  EXPECT_NE(p.err.find("unexpected argument 'stray'"), std::string::npos) << p.err;
  p = parse_args({"--radius", "-1"}); // a negative number is a value, not an option
  EXPECT_FALSE(p.status) << p.err;
}

TEST(Cli, ValidCommandLineGoesOn) {
  const Parsed p = parse_args({"--radius", "0.3", "--width=0.2"});
  EXPECT_FALSE(p.status);
  EXPECT_EQ(p.out, "");
  EXPECT_EQ(p.err, "");
}

} // namespace
