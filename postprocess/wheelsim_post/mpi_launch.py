"""How wheelsim's tools start LIGGGHTS under MPI (wheel-sweep's beds and rate benchmark, the soil
lab; scripts/wheel-cosim does the same in bash). Reference: docs/coupled-runs.md, "MPI launch".

Open MPI 4 binds the ranks of every `mpirun -np 1` (and `-np 2`) to the first cores by default,
so two runs started side by side (wheel-sweep --jobs 2, two soil-lab runs) share core 0 and each
gets half of it while core 1 idles (measured 2026-11-26: two np-1 shear boxes at 53 % CPU each,
94 % each once one was moved to core 1). wheelsim therefore launches with `--bind-to none`
unless $WHEELSIM_MPI_BIND names another policy (e.g. `core` on a cluster node given to one job).
"""

import os

BIND_ENV = "WHEELSIM_MPI_BIND"


def mpirun(np_):
    """The `mpirun` words before the executable for np_ ranks: oversubscription allowed (small
    machines), the binding policy of $WHEELSIM_MPI_BIND (default none), and root allowed when
    running as root (containers)."""
    cmd = ["mpirun", "-np", str(np_), "--oversubscribe",
           "--bind-to", os.environ.get(BIND_ENV) or "none"]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd
