// Argument parsing and printing shared by our LIGGGHTS fixes (fix_wheel_cosim.cpp,
// fix_wheel_active.cpp, fix_wheelsim_selftest.cpp): one place for the number rule of a keyword
// value, the error that names a bad argument, and a line printed to screen and log file.
#pragma once

#include "error.h"
#include "fix.h"
#include "lammps.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>

namespace wheelsim {

/// A keyword's number: the whole text is a finite decimal (strtod).
inline bool parse_finite(const char *text, double &value) {
  char *end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(value);
}

/// Stops the run with "Fix <style> (id <ID>): <message>" (LIGGGHTS' fix_error), the message
/// formatted from `fmt` and `args`.
[[noreturn]] inline void fix_argument_error(LAMMPS_NS::Error *error, LAMMPS_NS::Fix *fix,
                                            const char *fmt, va_list args) {
  char msg[1024];
  vsnprintf(msg, sizeof(msg), fmt, args);
  error->fix_error(FLERR, fix, msg);
  std::abort(); // not reached: fix_error ends the run
}

/// The same message for a condition one rank may meet alone (its own atoms, a file only it
/// reads): LIGGGHTS' fix_error and Error::all wait in a barrier for every rank first, so called
/// on some ranks they hang the run silently; Error::one prints "ERROR on proc N: Fix <style> (id
/// <ID>): <message>" and aborts every rank (MPI_Abort).
[[noreturn]] inline void fix_local_error(LAMMPS_NS::Error *error, LAMMPS_NS::Fix *fix,
                                         const char *fmt, va_list args) {
  char body[1024], msg[1200];
  vsnprintf(body, sizeof(body), fmt, args);
  snprintf(msg, sizeof(msg), "Fix %s (id %s): %s", fix->style, fix->id, body);
  error->one(FLERR, msg);
  std::abort(); // not reached: Error::one aborts
}

/// Prints `line` (with its newline) to the screen and the log file, on rank 0 only.
inline void print_line(LAMMPS_NS::LAMMPS *lmp, int rank, const char *line) {
  if (rank != 0)
    return;
  if (lmp->screen)
    fputs(line, lmp->screen);
  if (lmp->logfile)
    fputs(line, lmp->logfile);
}

} // namespace wheelsim
