#include "wheelsim/cli.h"

#include "wheelsim/config_messages.h"
#include "wheelsim_version.h"

#include <CLI/CLI.hpp>

#include <cctype>
#include <cstdio>
#include <iostream>

namespace wheelsim::cli {
namespace {

/// "--raduis=0.3" -> "raduis".
std::string bare(const std::string &option) {
  std::string s = option.substr(0, option.find('='));
  s.erase(0, s.find_first_not_of('-'));
  return s;
}

/// An argument that looks like an option: a dash followed by something that is not a number.
bool looks_like_option(const std::string &arg) {
  return arg.size() > 1 && arg[0] == '-' && !std::isdigit(static_cast<unsigned char>(arg[1])) &&
         arg[1] != '.';
}

} // namespace

std::string version_line(const std::string &program) {
  return program + " " + WHEELSIM_VERSION + " (git " + WHEELSIM_GIT_REVISION + ")";
}

std::string nearest_option(const std::string &given, const std::vector<std::string> &valid) {
  // Single letters are left out: closest() accepts a candidate contained in the word, and "h"
  // is contained in most words.
  std::vector<std::string> words;
  std::vector<const std::string *> names;
  for (const std::string &v : valid) {
    if (bare(v).size() < 2)
      continue;
    words.push_back(bare(v));
    names.push_back(&v);
  }
  const std::string best = config::closest(bare(given), words);
  for (std::size_t i = 0; i < words.size(); ++i)
    if (!best.empty() && words[i] == best)
      return *names[i];
  return "";
}

std::string unknown_option_message(const std::string &given,
                                   const std::vector<std::string> &valid) {
  const std::string shown = given.substr(0, given.find('='));
  std::string message = "unknown option '" + shown + "'";
  const std::string near = nearest_option(given, valid);
  if (!near.empty())
    message += " (did you mean '" + near + "'?)";
  return message;
}

int report_usage_error(const std::string &program, const std::string &message) {
  std::fflush(stdout);
  std::fprintf(stderr, "%s: %s\nRun '%s --help' for the options.\n", program.c_str(),
               message.c_str(), program.c_str());
  return kExitUsage;
}

void setup(CLI::App &app, const std::string &program) {
  app.name(program);
  app.set_version_flag("--version", version_line(program));
  app.footer("Exit status: 0 success (also after --help and --version), 1 failure while "
             "running, 2 bad command line or input.");
}

std::vector<std::string> option_names(const CLI::App &app) {
  std::vector<std::string> names;
  for (const CLI::Option *o : app.get_options()) {
    for (const std::string &l : o->get_lnames())
      names.push_back("--" + l);
    for (const std::string &s : o->get_snames())
      names.push_back("-" + s);
  }
  // The options of the subcommand given on the command line (e.g. scm-soil export --format).
  for (const CLI::App *sub : app.get_subcommands()) {
    const std::vector<std::string> more = option_names(*sub);
    names.insert(names.end(), more.begin(), more.end());
  }
  return names;
}

std::string describe_parse_error(const CLI::App &app, const CLI::ParseError &error) {
  // Arguments CLI11 did not recognise come first: a misspelt option is why a required one is
  // "missing".
  const std::vector<std::string> left = app.remaining(true);
  for (const std::string &arg : left)
    if (looks_like_option(arg))
      return unknown_option_message(arg, option_names(app));
  if (left.empty())
    return error.what();
  // A tool with subcommands and none given: the first word was meant as one.
  const auto commands = app.get_subcommands([](const CLI::App *) { return true; });
  if (!commands.empty() && app.get_subcommands().empty()) {
    std::vector<std::string> names;
    for (const CLI::App *c : commands)
      names.push_back(c->get_name());
    std::string message = "unknown command '" + left.front() + "'";
    const std::string near = config::closest(left.front(), names);
    if (!near.empty())
      return message + " (did you mean '" + near + "'?)";
    for (std::size_t i = 0; i < names.size(); ++i)
      message += (i ? ", " : "; the commands are ") + names[i];
    return message;
  }
  return "unexpected argument '" + left.front() + "'";
}

std::optional<int> parse(CLI::App &app, int argc, const char *const *argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError &e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      app.exit(e); // --help or --version: printed to stdout
      std::cout.flush();
      return kExitSuccess;
    }
    return report_usage_error(app.get_name(), describe_parse_error(app, e));
  }
  return std::nullopt;
}

} // namespace wheelsim::cli
