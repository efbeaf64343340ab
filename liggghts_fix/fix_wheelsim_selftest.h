/* fix wheelsim/selftest — a minimal style that proves liggghts-wheel's style registration works
   (docs/liggghts-wheel.md). It does nothing to the particles.

   Syntax:  fix ID group-ID wheelsim/selftest [abort_at STEP]
   Output:  global scalar = number of atoms in the group, summed over all MPI ranks.
            On `init` rank 0 prints "wheelsim/selftest: fix ID active on N MPI ranks, M atoms".
   abort_at STEP: at the end of STEP the highest rank raises a one-rank error (error->one), the
            path a socket timeout will take later; used to test that such an error message reaches
            the screen and the log file before MPI_Abort ends the job.
   Restart: stores nothing.

   The FixStyle block below is in the form LIGGGHTS' Make.sh expects, so this file can also be
   dropped into a LIGGGHTS source tree (docs/building.md). */

#ifdef FIX_CLASS

// The style name is stringified (#key): clang-format must not space the slash.
// clang-format off
FixStyle(wheelsim/selftest,FixWheelsimSelftest)
// clang-format on

#else

#ifndef LMP_FIX_WHEELSIM_SELFTEST_H
#define LMP_FIX_WHEELSIM_SELFTEST_H

#include "fix.h"

namespace LAMMPS_NS {

class FixWheelsimSelftest : public Fix {
public:
  FixWheelsimSelftest(class LAMMPS *lmp, int narg, char **arg);
  int setmask() override;
  void init() override;
  void end_of_step() override;
  double compute_scalar() override;

private:
  bigint abort_at_step_; // step at which to raise error->one; -1 = never
};

} // namespace LAMMPS_NS

#endif
#endif
