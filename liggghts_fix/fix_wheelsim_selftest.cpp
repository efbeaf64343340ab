#include "fix_wheelsim_selftest.h"

#include "fix_output.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "update.h"

#include <cstdio>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixWheelsimSelftest::FixWheelsimSelftest(LAMMPS *lmp, int narg, char **arg)
    : Fix(lmp, narg, arg), abort_at_step_(-1) {
  scalar_flag = 1;
  global_freq = 1;
  extscalar = 1;

  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "abort_at") == 0) {
      if (iarg + 1 >= narg)
        error->fix_error(FLERR, this, "keyword 'abort_at' expects a step number (integer >= 0)");
      abort_at_step_ = force->inumeric(FLERR, arg[iarg + 1]);
      if (abort_at_step_ < 0)
        error->fix_error(FLERR, this, "keyword 'abort_at' expects a step number >= 0");
      iarg += 2;
    } else {
      char msg[256];
      snprintf(msg, sizeof(msg), "unknown keyword '%s'; expected: abort_at STEP", arg[iarg]);
      error->fix_error(FLERR, this, msg);
    }
  }
  if (abort_at_step_ >= 0)
    nevery = 1;
}

int FixWheelsimSelftest::setmask() {
  int mask = 0;
  if (abort_at_step_ >= 0)
    mask |= END_OF_STEP;
  return mask;
}

void FixWheelsimSelftest::init() {
  const double natoms_in_group = compute_scalar();
  if (comm->me == 0) {
    char line[256];
    snprintf(line, sizeof(line), "wheelsim/selftest: fix %s active on %d MPI ranks, %.0f atoms\n",
             id, comm->nprocs, natoms_in_group);
    wheelsim::print_line(lmp, comm->me, line);
  }
}

void FixWheelsimSelftest::end_of_step() {
  if (update->ntimestep == abort_at_step_ && comm->me == comm->nprocs - 1) {
    char msg[256];
    snprintf(msg, sizeof(msg),
             "wheelsim/selftest: deliberate one-rank error at step %ld on rank %d (abort_at)",
             static_cast<long>(update->ntimestep), comm->me);
    error->one(FLERR, msg);
  }
}

double FixWheelsimSelftest::compute_scalar() {
  int *mask = atom->mask;
  bigint local = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit)
      local++;
  bigint total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return static_cast<double>(total);
}
