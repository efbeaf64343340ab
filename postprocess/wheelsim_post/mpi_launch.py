"""How wheelsim's tools start LIGGGHTS under MPI (wheel-sweep's beds and rate benchmark, the soil
lab; scripts/wheel-cosim does the same in bash), and how they wait for it (the stall guard,
wait_watching). Reference: docs/coupled-runs.md, "MPI launch".

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
import time

BIND_ENV = "WHEELSIM_MPI_BIND"
PR_SET_PDEATHSIG = 1

# The stall guard's default [min]: a LIGGGHTS run whose output has not grown for this long is
# taken for hung (a rank stuck, an MPI deadlock) and killed. The longest silence of a healthy run
# of the shipped decks is one quarter of the bed-hold check (inputs/in.bedhold prints at each
# quarter's end only): hold_s / (4 dt) = 0.2 s / (4 x 1.18e-5 s) = 4 251 steps for the soil with
# the smallest time step, loose_sand_1330, at the default --bed-hold 0.2; in.soilbin prints every
# 1 000 steps, the lab decks every 2 000. At 15 steps/s (220 000 particles on a slow machine) 4 251
# steps take 4.7 min, so 20 min leaves a factor 4. Measured on the study_wheels bed (221 408
# particles, 2 ranks, 2026-12-01): at most 62 s between two lines of its in.soilbin, 53 s of its
# bed-hold check; lab logs in soil_lab/archive: at most 25 s. A longer bed-hold (--bed-hold S
# prints every S/4 of simulated time) may need a longer timeout.
DEFAULT_STALL_MIN = 20.0
WAIT_POLL_S = 5.0  #: [s] how often wait_watching looks at the output and calls while_running


def mpirun(np_):
    """The `mpirun` words before the executable for np_ ranks: oversubscription allowed (small
    machines), the binding policy of $WHEELSIM_MPI_BIND (default none), and root allowed when
    running as root (containers)."""
    cmd = ["mpirun", "-np", str(np_), "--oversubscribe",
           "--bind-to", os.environ.get(BIND_ENV) or "none"]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd


AUTOGROUP = "/proc/self/autogroup"


def autogroup_nice(path=AUTOGROUP):
    """The nice value of this process's scheduler autogroup (Linux with
    kernel.sched_autogroup_enabled: `/autogroup-N nice K`), or None where there is none."""
    try:
        with open(path) as f:
            return int(f.read().split()[-1])
    except (OSError, ValueError, IndexError):
        return None


def session_nice():
    """The autogroup nice a new session started from this process should have, so that it runs
    as niced as this process (docs/dem-performance.md "Sharing the cores"): the larger of this
    process's own nice and its autogroup's, or None when there is nothing to carry (both 0, or
    no autogroups)."""
    group = autogroup_nice()
    if group is None:
        return None
    want = max(group, os.getpriority(os.PRIO_PROCESS, 0))
    return want if want > 0 else None


def die_with_parent(parent_pid, new_session=False, who="wheelsim"):
    """A preexec_fn: the child gets SIGKILL when the thread that started it dies
    (PR_SET_PDEATHSIG), also on SIGKILL; if the parent `parent_pid` died before prctl took effect,
    the child kills itself. new_session: also a session of its own (wheel-sweep's watchdog kills
    whole sessions), whose scheduler autogroup gets this process's niceness (session_nice): a
    new session is a new autogroup at nice 0, and under autogroups nice acts only within a group,
    so a point of `nice -n 19 wheel-sweep` would otherwise take a core's share from a run beside
    it as if it were not niced. libc is loaded here, in the parent, not in the forked child."""
    prctl = ctypes.CDLL(None, use_errno=True).prctl
    carry = session_nice() if new_session else None

    def preexec():
        if new_session:
            os.setsid()
            if carry is not None:
                try:  # raising a group's nice needs no privilege; where it fails, run as is
                    fd = os.open(AUTOGROUP, os.O_WRONLY)
                    try:
                        os.write(fd, str(carry).encode())
                    finally:
                        os.close(fd)
                except OSError:
                    pass
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


class Stalled(RuntimeError):
    """A child whose output did not grow for the stall timeout, killed (wait_watching); the
    message names it, its log and the option that sets the timeout."""


def stall_seconds(minutes):
    """The stall timeout [s] of a --stall-timeout MIN value (0: no guard); ValueError naming the
    value unless it is a number of minutes >= 0."""
    if not minutes >= 0 or minutes == float("inf"):  # also NaN
        raise ValueError(f"expected a number of minutes >= 0 (0: no limit), got {minutes:g}")
    return 60.0 * minutes


def wait_watching(proc, out, stall_s, kill, what, option, while_running=None):
    """Waits for `proc` to exit and returns its exit status. `out` is the open file its output
    goes to; when `stall_s` > 0 [s] and that file has not grown for stall_s seconds, `kill()` is
    called (it must end proc and every process it started), proc is reaped and Stalled is raised:
    '<what> made no progress for N min (log LOG unchanged since HH:MM:SS): killed; ...', naming
    `option` (e.g. '--stall-timeout') as the way to allow more. `while_running()` is called every
    WAIT_POLL_S seconds meanwhile."""
    step = WAIT_POLL_S if stall_s <= 0 else min(WAIT_POLL_S, max(0.05, stall_s / 10.0))
    size = os.fstat(out.fileno()).st_size
    grew = called = time.monotonic()
    while True:
        try:
            return proc.wait(timeout=step)
        except subprocess.TimeoutExpired:
            pass
        now = time.monotonic()
        if while_running is not None and now - called >= WAIT_POLL_S:
            while_running()
            called = now
        if stall_s <= 0:
            continue
        st = os.fstat(out.fileno())
        if st.st_size != size:
            size, grew = st.st_size, now
        elif now - grew >= stall_s:
            kill()
            proc.wait()
            since = time.strftime("%H:%M:%S", time.localtime(st.st_mtime))
            raise Stalled(f"{what} made no progress for {stall_s / 60.0:g} min (log {out.name} "
                          f"unchanged since {since}): killed; a hung run (an MPI rank stuck or "
                          f"deadlocked) prints nothing. If it was only slow, allow longer "
                          f"silences with {option} MIN (0: no limit)")
