// liggghts-wheel: LIGGGHTS 3.8 (Debian's libliggghts, unmodified) with wheelsim's styles.
//
// The command line is LIGGGHTS' own (-in, -var, -log, -screen, -echo, ... are passed through to
// the LAMMPS constructor untouched); `-h` / `-help` first lists the styles this build adds, then
// LIGGGHTS' own help. Works under mpirun. See docs/liggghts-wheel.md.
#include "flush_before_abort.h"
#include "style_registration.h"
#include "wheelsim_version.h"

#include "input.h"
#include "lammps.h"

#include <mpi.h>

#include <cstdio>
#include <cstring>
#include <exception>

namespace {

bool wants_help(int argc, char **argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "-h") == 0 || std::strcmp(argv[i], "-help") == 0)
      return true;
  return false;
}

void print_project_help() {
  std::printf("liggghts-wheel %s (wheelsim, git %s): LIGGGHTS 3.8 with wheelsim's styles.\n"
              "Usage: [mpirun -np N] liggghts-wheel -in DECK [-var NAME VALUE ...] [-log FILE]\n"
              "       [-screen FILE|none] [-echo none|screen|log|both] [other LIGGGHTS flags]\n\n"
              "Styles added by wheelsim:\n",
              WHEELSIM_VERSION, WHEELSIM_GIT_REVISION);
  for (const std::string &name : wheelsim::wheelsim_fix_style_names())
    std::printf("  fix %s\n", name.c_str());
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

  if (wants_help(argc, argv) && rank == 0)
    print_project_help(); // then LIGGGHTS prints its help and exits from its constructor

  LAMMPS_NS::LAMMPS *lmp = new LAMMPS_NS::LAMMPS(argc, argv, MPI_COMM_WORLD);
  if (lmp->screen != stdout)
    line_buffer(lmp->screen);
  line_buffer(lmp->logfile);

  try {
    wheelsim::register_wheelsim_styles(lmp);
  } catch (const std::exception &e) {
    if (rank == 0)
      std::fprintf(stderr, "liggghts-wheel: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  if (rank == 0) {
    char banner[160];
    std::snprintf(banner, sizeof(banner), "liggghts-wheel: wheelsim %s (git %s) styles registered\n",
                  WHEELSIM_VERSION, WHEELSIM_GIT_REVISION);
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
