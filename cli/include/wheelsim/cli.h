// The command-line conventions of every wheelsim executable, in one place:
//   --help / -h   prints the usage and exits 0
//   --version     prints "<program> <version> (git <revision>)" and exits 0
//   exit status   0 success, 1 a failure while running, 2 bad command line or input
//   bad usage     "<program>: unknown option '--raduis' (did you mean '--radius'?)" on stderr,
//                 then a pointer to --help; exit 2
// The CLI11 tools call setup() and parse(); liggghts-wheel, whose command line is LIGGGHTS' own,
// uses version_line(), unknown_option_message() and report_usage_error().
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace CLI {
class App;
class ParseError;
} // namespace CLI

namespace wheelsim::cli {

/// Exit statuses (documented on each tool's page).
inline constexpr int kExitSuccess = 0; ///< done; also after --help and --version
inline constexpr int kExitFailure = 1; ///< the run or computation failed
inline constexpr int kExitUsage = 2;   ///< bad command line or input (option, config, file)

/// A usage problem a tool finds after parsing (an option missing or contradicting another, a
/// value out of range): report it with report_usage_error() and exit kExitUsage.
class UsageError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// "<program> <version> (git <revision>)", from wheelsim_version.h.
std::string version_line(const std::string &program);

/// The one of `valid` (option names with their dashes, e.g. "--radius") nearest to `given`, or ""
/// when none is plausibly meant. Compares the names without dashes and without "=value", by
/// wheelsim::config::closest (the suggestion of the config files).
std::string nearest_option(const std::string &given, const std::vector<std::string> &valid);

/// "unknown option '<given>'", plus " (did you mean '<nearest>'?)" when one is near.
std::string unknown_option_message(const std::string &given, const std::vector<std::string> &valid);

/// Prints "<program>: <message>" and "Run '<program> --help' for the options." to stderr;
/// returns kExitUsage.
int report_usage_error(const std::string &program, const std::string &message);

/// Names `app` `program`, adds --version (version_line) and a footer with the exit statuses.
/// CLI11's own -h/--help stays.
void setup(CLI::App &app, const std::string &program);

/// Parses the command line. Returns std::nullopt when the tool should go on, otherwise the status
/// main() returns: kExitSuccess after printing the help or the version (stdout), kExitUsage after
/// printing a usage error (stderr). An unknown option is reported before anything else (CLI11
/// itself would first report a required option that the misspelt one was meant to give).
std::optional<int> parse(CLI::App &app, int argc, const char *const *argv);

/// The message for a CLI11 parse error: an unknown option with the nearest valid one (of the app
/// and of the subcommand given) if any argument was left over, an unknown command with the nearest
/// subcommand for a tool with subcommands, else CLI11's own message.
std::string describe_parse_error(const CLI::App &app, const CLI::ParseError &error);

/// Every option name of `app` and of its parsed subcommands, with the dashes ("--radius", "-h").
std::vector<std::string> option_names(const CLI::App &app);

} // namespace wheelsim::cli
