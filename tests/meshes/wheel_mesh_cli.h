// The wheel-mesh executable of this build (WHEEL_MESH_EXE, tests/meshes/CMakeLists.txt) run with
// `args`: what the CLI tests of its wheel and tool modes share.
#pragma once

#include <string>

#include "cli_test_util.h"

using CliResult = wheelsim::cli_test::CommandResult;

inline CliResult run_cli(const std::string &args) {
  return wheelsim::cli_test::run_command(std::string(WHEEL_MESH_EXE) + " " + args);
}
