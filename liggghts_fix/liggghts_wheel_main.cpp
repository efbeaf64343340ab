// liggghts-wheel: LIGGGHTS 3.8 (Debian's libliggghts, unmodified) with wheelsim's styles.
//
// The command line is LIGGGHTS' own (-in, -var, -log, -screen, -echo, ... are passed through to
// the LAMMPS constructor untouched); `-h` / `-help` / `--help` first lists the styles this build
// adds, then LIGGGHTS' own help; `--version` prints the wheelsim version. Before LIGGGHTS sees
// the arguments they are checked against LIGGGHTS 3.8's switches (below), so that a misspelt one
// is named with the nearest valid one (LIGGGHTS says only "Invalid command-line argument").
// Exit status (wheelsim/cli.h): 0 done (also help and version), 1 LIGGGHTS stopped with an
// error, 2 bad command line. Works under mpirun. See docs/liggghts-wheel.md.
#include "flush_before_abort.h"
#include "precompiled_contact_models.h"
#include "style_registration.h"
#include "wheelsim/cli.h"
#include "wheelsim_version.h"

#include "input.h"
#include "lammps.h"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

namespace {

/// A command-line switch of LIGGGHTS 3.8 (its LAMMPS constructor, lammps.cpp): name, short
/// alias, number of values it takes, whether more values follow up to the next "-..." argument.
struct Switch {
  const char *name;
  const char *alias;
  int values;
  bool more;
  const char *value_help;
};

constexpr Switch kLiggghtsSwitches[] = {
    {"-echo", "-e", 1, false, "none|screen|log|both"},
    {"-in", "-i", 1, false, "the input deck"},
    {"-help", "-h", 0, false, ""},
    {"-log", "-l", 1, false, "a file or none"},
    {"-nocite", "-nc", 0, false, ""},
    {"-partition", "-p", 1, true, "partition sizes"},
    {"-plog", "-pl", 1, false, "a basename"},
    {"-pscreen", "-ps", 1, false, "a basename"},
    {"-reorder", "-ro", 2, false, "the topology specs"},
    {"-restart", "-r", 2, false, "a restart file and a data file"},
    {"-restart_offset", "-roff", 3, false, "a restart file, a data file and a tag offset"},
    {"-screen", "-sc", 1, false, "a file or none"},
    {"-suffix", "-sf", 1, false, "a style suffix"},
    {"-var", "-v", 2, true, "a name and its value(s)"},
    {"-cuda", "-c", 1, false, "on|off"},
    {"-domain", nullptr, 1, false, "box|wedge"},
    {"-uid", nullptr, 1, false, "an id"},
    {"-thermo", nullptr, 1, false, "a file"},
    {"-seedtolerant", "-st", 0, false, ""},
    {"-wb", nullptr, 0, false, ""},
};

enum class Request { run, help, version, usage_error };

/// What the command line asks for; a usage error's message in `message`.
Request scan_arguments(int argc, char **argv, std::string &message) {
  bool help = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help") {
      help = true;
      continue;
    }
    if (arg == "--version")
      return Request::version;
    const Switch *known = nullptr;
    for (const Switch &s : kLiggghtsSwitches)
      if (arg == s.name || (s.alias && arg == s.alias))
        known = &s;
    if (!known) {
      if (arg.size() > 1 && arg[0] == '-') {
        std::vector<std::string> names{"--help", "--version"};
        for (const Switch &s : kLiggghtsSwitches)
          names.push_back(s.name);
        message = wheelsim::cli::unknown_option_message(arg, names);
      } else {
        message = "unexpected argument '" + arg + "' (LIGGGHTS takes the deck as -in FILE)";
      }
      return Request::usage_error;
    }
    if (i + known->values >= argc) {
      message = std::string(known->name) + " needs " + known->value_help;
      return Request::usage_error;
    }
    i += known->values;
    while (known->more && i + 1 < argc && argv[i + 1][0] != '-')
      ++i;
    if (std::strcmp(known->name, "-help") == 0)
      help = true;
  }
  return help ? Request::help : Request::run;
}

/// LIGGGHTS prints its help from its constructor and then ends the process with status 1
/// (Error::done). Registered with atexit only for -h, this turns that into status 0.
void exit_zero_after_help() {
  std::fflush(nullptr);
  std::_Exit(wheelsim::cli::kExitSuccess);
}

void print_project_help() {
  std::printf("liggghts-wheel %s (wheelsim, git %s): LIGGGHTS 3.8 with wheelsim's styles.\n"
              "Usage: [mpirun -np N] liggghts-wheel -in DECK [-var NAME VALUE ...] [-log FILE]\n"
              "       [-screen FILE|none] [-echo none|screen|log|both] [other LIGGGHTS flags]\n"
              "       liggghts-wheel -h|-help|--help|--version\n"
              "Exit status: 0 done (also help, version), 1 LIGGGHTS stopped with an error, 2 bad\n"
              "command line.\n\n"
              "Styles added by wheelsim:\n",
              WHEELSIM_VERSION, WHEELSIM_GIT_REVISION);
  for (const std::string &name : wheelsim::wheelsim_fix_style_names())
    std::printf("  fix %s\n", name.c_str());
  std::printf("\nContact-model combinations compiled by wheelsim (not in Debian's LIGGGHTS build,\n"
              "which runs them through its slower generic class; %s=1 to use that):\n",
              wheelsim::kGenericContactModelsEnv);
  for (const std::string &keywords : wheelsim::precompiled_contact_model_names())
    std::printf("  pair_style gran / fix wall/gran %s\n", keywords.c_str());
  std::printf("\nLIGGGHTS' own help follows.\n\n");
  std::fflush(stdout);
}

// Line-buffer a stream LIGGGHTS opened, so that what was written before an abort is on disk.
void line_buffer(FILE *stream) {
  if (stream != nullptr)
    std::setvbuf(stream, nullptr, _IOLBF, BUFSIZ);
}

} // namespace

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  // stdout may be a pipe (mpirun, tests); line-buffer it before anything is written to it.
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  wheelsim::flush_output_on_termination();

  std::string message;
  switch (scan_arguments(argc, argv, message)) {
  case Request::run:
    break;
  case Request::version:
  case Request::usage_error: {
    int status = wheelsim::cli::kExitSuccess;
    if (message.empty() && rank == 0)
      std::printf("%s\n", wheelsim::cli::version_line("liggghts-wheel").c_str());
    else if (!message.empty())
      status = rank == 0 ? wheelsim::cli::report_usage_error("liggghts-wheel", message)
                         : wheelsim::cli::kExitUsage;
    MPI_Finalize();
    return status;
  }
  case Request::help: {
    if (rank == 0)
      print_project_help();
    // Then LIGGGHTS' own help (switches and styles), printed by its constructor, which ends the
    // process; "-log none": no log.liggghts for a help request.
    std::atexit(exit_zero_after_help);
    char help[] = "-h", log[] = "-log", none[] = "none";
    char *help_argv[] = {argv[0], help, log, none, nullptr};
    new LAMMPS_NS::LAMMPS(4, help_argv, MPI_COMM_WORLD);
    MPI_Finalize(); // not reached: LIGGGHTS exits after its help
    return wheelsim::cli::kExitSuccess;
  }
  }

  LAMMPS_NS::LAMMPS *lmp = new LAMMPS_NS::LAMMPS(argc, argv, MPI_COMM_WORLD);
  if (lmp->screen != stdout)
    line_buffer(lmp->screen);
  line_buffer(lmp->logfile);

  int precompiled = 0;
  try {
    wheelsim::register_wheelsim_styles(lmp);
    precompiled = wheelsim::register_precompiled_contact_models();
  } catch (const std::exception &e) {
    if (rank == 0)
      std::fprintf(stderr, "liggghts-wheel: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  if (rank == 0) {
    char banner[256];
    std::snprintf(banner, sizeof(banner),
                  "liggghts-wheel: wheelsim %s (git %s) styles registered; %d contact-model "
                  "combination(s) precompiled%s\n",
                  WHEELSIM_VERSION, WHEELSIM_GIT_REVISION, precompiled,
                  precompiled == 0 ? " (WHEELSIM_GENERIC_CONTACT_MODELS=1)" : "");
    if (lmp->screen)
      std::fputs(banner, lmp->screen);
    if (lmp->logfile)
      std::fputs(banner, lmp->logfile);
  }

  lmp->input->file();
  delete lmp;
  MPI_Finalize();
  return 0;
}
