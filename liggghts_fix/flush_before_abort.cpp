// Output is never lost when LIGGGHTS aborts.
//
// LIGGGHTS' error->one() (the only safe error on one rank, e.g. a socket timeout seen by rank 0)
// prints its message and calls MPI_Abort, which ends the process without flushing stdio; the
// other ranks are then terminated by mpirun with SIGTERM. A message or thermo line written to a
// redirected screen or to a log file opened by the deck's `log` command would be lost. main()
// line-buffers stdout, the screen and the -log file; this file covers every other stream:
//  - on the aborting rank: we define MPI_Abort ourselves through the MPI profiling interface
//    (MPI standard, "Profiling Interface": a program may define MPI_Abort and reach the library's
//    implementation as PMPI_Abort). The executable exports the symbol (ENABLE_EXPORTS), so
//    libliggghts' calls bind to it;
//  - on the other ranks: a SIGTERM handler flushes, then lets the default action end the process.
//    fflush is not async-signal-safe: if the signal lands inside stdio the flush may block, and
//    mpirun's SIGKILL (a few seconds after SIGTERM) ends the process, so nothing hangs.
#include "flush_before_abort.h"

#include <mpi.h>

#include <csignal>
#include <cstdio>

extern "C" int MPI_Abort(MPI_Comm comm, int errorcode) {
  std::fflush(nullptr); // every open output stream: screen, logs, dumps
  return PMPI_Abort(comm, errorcode);
}

namespace {

extern "C" void flush_and_terminate(int signal_number) {
  std::fflush(nullptr);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

} // namespace

namespace wheelsim {

void flush_output_on_termination() {
  struct sigaction action {};
  action.sa_handler = flush_and_terminate;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGTERM, &action, nullptr);
}

} // namespace wheelsim
