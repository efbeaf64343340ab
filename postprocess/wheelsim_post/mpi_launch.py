"""How wheelsim's tools start LIGGGHTS under MPI (wheel-sweep's beds and rate benchmark, the soil
lab; scripts/wheel-cosim does the same in bash). Reference: docs/coupled-runs.md, "MPI launch".

Open MPI 4 binds the ranks of every `mpirun -np 1` (and `-np 2`) to the first cores by default,
so two runs started side by side (wheel-sweep --jobs 2, two soil-lab runs) share core 0 and each
gets half of it while core 1 idles (measured 2026-11-26: two np-1 shear boxes at 53 % CPU each,
94 % each once one was moved to core 1). wheelsim therefore launches with `--bind-to none`
unless $WHEELSIM_MPI_BIND names another policy (e.g. `core` on a cluster node given to one job).
"""

import ctypes
import functools
import os
import signal
import subprocess

BIND_ENV = "WHEELSIM_MPI_BIND"
PR_SET_PDEATHSIG = 1


def mpirun(np_):
    """The `mpirun` words before the executable for np_ ranks: oversubscription allowed (small
    machines), the binding policy of $WHEELSIM_MPI_BIND (default none), and root allowed when
    running as root (containers)."""
    cmd = ["mpirun", "-np", str(np_), "--oversubscribe",
           "--bind-to", os.environ.get(BIND_ENV) or "none"]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd


def die_with_parent(parent_pid, new_session=False, who="wheelsim"):
    """A preexec_fn: the child gets SIGKILL when the thread that started it dies
    (PR_SET_PDEATHSIG), also on SIGKILL; if the parent `parent_pid` died before prctl took effect,
    the child kills itself. new_session: also a session of its own (wheel-sweep's watchdog kills
    whole sessions). libc is loaded here, in the parent, not in the forked child."""
    prctl = ctypes.CDLL(None, use_errno=True).prctl

    def preexec():
        if new_session:
            os.setsid()
        if prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) != 0:
            os.write(2, f"{who}: prctl(PR_SET_PDEATHSIG) failed\n".encode())
            os._exit(127)
        if os.getppid() != parent_pid:
            os.kill(os.getpid(), signal.SIGKILL)

    return preexec


@functools.lru_cache(maxsize=None)
def rank_death_prefix():
    """The words before a rank's executable that make it die (SIGKILL) with mpirun: util-linux
    `setpriv --pdeathsig KILL`, as scripts/wheel-cosim does; () where setpriv lacks it. Asked
    once per process."""
    try:
        text = subprocess.run(["setpriv", "--help"], capture_output=True, text=True).stdout
    except OSError:
        return ()
    return ("setpriv", "--pdeathsig", "KILL") if "--pdeathsig" in text else ()
