#!/usr/bin/python3
"""A 2-rank LIGGGHTS run sharing the 2 cores with one busy process: wall time per step of a
prepared bed (inputs/soilbin/resume.in, no wheel) with Open MPI busy-waiting
(mpi_yield_when_idle 0, its default when it sees no oversubscription) and yielding (1), alone and
beside one busy process of three kinds:

  same group, nice 10   started from this benchmark's session at nice 10 (what `nice` does where
                        the Linux scheduler groups processes by session: kernel.sched_autogroup)
  own session           in a session of its own, i.e. its own autogroup at nice 0 (a wheel-sweep
                        point, a run started from another terminal or by nohup setsid)
  own session, nice 19  the same with its autogroup niced (echo 19 > /proc/self/autogroup; what
                        wheel-sweep now gives its points when it runs niced)

  bench_mpi_yield.py --exe liggghts-wheel --inputs DIR --bed BED.restart [--bed ...]
                     [--steps 1000] [--repeats 2] [--work DIR]

Under autogroups, nice acts only between processes of one group: a busy process in a group of
its own takes a whole core's share from the 2-rank job, whose ranks then take turns on one core;
a busy-waiting rank spins through its slice while the rank it waits for is descheduled. The
benchmark prints, per bed, the median ms/step of each case (repeats interleaved) and its ratio to
the run alone. Time it with nothing else running: the 1-minute load average is printed before and
after. Not a test.
"""
import argparse
import os
import statistics
import subprocess
import sys
import time

from liggghts_log_path import loops  # puts postprocess/ on the path
from wheelsim_post import mpi_launch  # noqa: E402  (the tools' own launch words)

BUSY = "while True: pass"
# name -> (extra Popen keywords, the busy process's own prologue)
COMPETITORS = {
    "alone": None,
    "same group, nice 10": ({"preexec_fn": lambda: os.nice(10)}, ""),
    "own session": ({"start_new_session": True}, ""),
    "own session, nice 19": ({"start_new_session": True},
                             "open('/proc/self/autogroup', 'w').write('19')\n"),
}


def run(exe, inputs, bed, steps, yield_idle, work):
    """(ms per step, atoms) of one 2-rank resume of `bed` for `steps` steps."""
    cmd = mpi_launch.mpirun(2) + ["--mca", "mpi_yield_when_idle", str(yield_idle)]
    cmd += [exe, "-in", os.path.join(inputs, "soilbin", "resume.in"), "-log", "none",
            "-var", "inputs_dir", inputs, "-var", "restart_file", bed,
            "-var", "resume_steps", str(steps), "-var", "resume_thermo", str(steps)]
    out = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    summary = loops(out.stdout)
    if out.returncode != 0 or not summary:
        sys.exit(f"bench: {' '.join(cmd)} failed ({out.returncode}):\n{out.stdout[-2000:]}"
                 f"{out.stderr[-2000:]}")
    loop = summary[-1]
    return 1e3 * loop.seconds / loop.steps, loop.atoms


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--exe", required=True, help="liggghts-wheel")
    p.add_argument("--inputs", required=True, help="the inputs/ directory")
    p.add_argument("--bed", action="append", required=True,
                   help="a prepared bed's restart (its .vars beside it); repeat for several")
    p.add_argument("--steps", type=int, default=1000, help="steps per run (default 1000)")
    p.add_argument("--repeats", type=int, default=2, help="runs per case, interleaved (default 2)")
    p.add_argument("--work", default=".", help="where LIGGGHTS runs (writes nothing there)")
    a = p.parse_args()
    if a.steps < 1 or a.repeats < 1:
        p.error("--steps and --repeats must be at least 1")
    exe, inputs = os.path.abspath(a.exe), os.path.abspath(a.inputs)
    group = mpi_launch.autogroup_nice()
    group = "none (this kernel has none)" if group is None else f"nice {group}"
    print(f"bench_mpi_yield: load average before {os.getloadavg()[0]:.2f} on {os.cpu_count()} "
          f"cores; this benchmark's autogroup: {group}; {a.steps} steps per run, "
          f"{a.repeats} repeats")
    for bed in a.bed:
        bed = os.path.abspath(bed)
        times = {}
        atoms = 0
        for _ in range(a.repeats):
            for name, competitor in COMPETITORS.items():
                hog = None
                if competitor:  # one core kept busy for the length of the two runs
                    kw, prologue = competitor
                    hog = subprocess.Popen([sys.executable, "-c", prologue + BUSY], **kw)
                    time.sleep(0.5)
                try:
                    for y in (0, 1):
                        ms, atoms = run(exe, inputs, bed, a.steps, y, a.work)
                        times.setdefault((name, y), []).append(ms)
                finally:
                    if hog:
                        hog.kill()
                        hog.wait()
        med = {k: statistics.median(v) for k, v in times.items()}
        ref = med[("alone", 0)]
        print(f"\n{bed}: {atoms} spheres, 2 ranks; ratio = ms/step over alone with yield 0 "
              f"({ref:.3f} ms/step)")
        print("| beside | yield 0 [ms/step] | ratio | yield 1 [ms/step] | ratio |")
        print("|---|---|---|---|---|")
        for name in COMPETITORS:
            print(f"| {name} | {med[(name, 0)]:.3f} | {med[(name, 0)] / ref:.2f} | "
                  f"{med[(name, 1)]:.3f} | {med[(name, 1)] / ref:.2f} |")
        print("runs [ms/step]: " + "; ".join(
            f"{name} yield {y}: " + ", ".join(f"{t:.3f}" for t in times[(name, y)])
            for name in COMPETITORS for y in (0, 1)))
    print(f"\nbench_mpi_yield: load average after {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
