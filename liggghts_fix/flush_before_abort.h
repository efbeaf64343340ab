// See flush_before_abort.cpp: keeps every output stream's content when the job is aborted.
#ifndef WHEELSIM_FLUSH_BEFORE_ABORT_H
#define WHEELSIM_FLUSH_BEFORE_ABORT_H

namespace wheelsim {
/// Installs a SIGTERM handler that flushes all stdio streams before the process ends (mpirun
/// sends SIGTERM to the surviving ranks when one rank calls MPI_Abort).
void flush_output_on_termination();
} // namespace wheelsim

#endif
