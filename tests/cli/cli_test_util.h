// Runs a wheelsim executable as a process, for the command-line tests of every tool: exit status,
// stdout and stderr together, and the wall time (for the "fails at once" checks).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace wheelsim::cli_test {

struct CommandResult {
  int status = -1;    ///< exit status; -1 if the process did not exit normally
  std::string output; ///< stdout and stderr, interleaved
  double seconds = 0; ///< wall time from start to exit [s]
};

/// Runs `command_line` through the shell with stderr joined to stdout.
inline CommandResult run_command(const std::string &command_line) {
  CommandResult r;
  const auto t0 = std::chrono::steady_clock::now();
  FILE *pipe = popen((command_line + " 2>&1").c_str(), "r");
  if (!pipe)
    return r;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe))
    r.output += buffer;
  const int raw = pclose(pipe);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

} // namespace wheelsim::cli_test
