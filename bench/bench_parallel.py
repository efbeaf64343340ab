#!/usr/bin/python3
"""Parallel efficiency of LIGGGHTS with fix wheel/cosim: wall time per step on np 1 and np 2 (or
the ranks of --nps) on the same bed, same deck (tests/wheel_cosim/in.wheel_roll), same
prescribed wheel motion; efficiency(np) = t(1) / (np t(np)), printed against the goal of issue 12
item 5 (np 1 -> 2 at ~100 000 particles: >= 0.85).

  bench_parallel.py --exe liggghts-wheel --inputs DIR --mesh test_small.stl --work DIR
                    [--size large|small | --bed BED.restart] [--nps 1,2] [--steps 1000]

  --size large: the 1.08 x 0.36 x 0.035 m ci bed of bench_wheel_cosim.py (104 623 spheres; made
                once with inputs/in.soilbin into WORK/bed_large, shared with that benchmark;
                about 3 min on 2 idle cores, far longer on a busy machine)
  --bed FILE:   any prepared bed (with its .vars), e.g. the wheel_cosim test bed, to check that
                the benchmark works in seconds (the efficiency of a 4 000-sphere bed says little)

Per rank count it prints LIGGGHTS' own timing breakdown (Loop time; Pair, Neigh, Comm, Outpt,
Modify, Other shares) and the fix's own time. Time it on an idle machine: every rank must have a
core of its own, or the efficiency measures the other jobs (the 1-minute load average is printed
before and after, with a warning when the machine is busy). Not a test.
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from bench_wheel_cosim import DECK, SIZES, bed, timing  # noqa: E402  (same deck, beds, parser)

GOAL = 0.85  # issue 12 item 5: np 1 -> 2 parallel efficiency at ~100 000 particles


def bed_length(restart):
    """bin_length [m] from the bed's .vars file (in.soilbin writes it)."""
    for line in open(restart + ".vars"):
        tok = line.split()
        if tok[:2] == ["variable", "bin_length"]:
            return float(tok[3])
    sys.exit(f"bench: no bin_length in {restart}.vars")


def load_note(own=0):
    """(1-minute load average, cores, busy): busy when the load exceeds this benchmark's own
    ranks (own: the 1-minute average still counts the runs just ended) by more than 0.5."""
    load1 = os.getloadavg()[0]
    cores = os.cpu_count() or 1
    return load1, cores, load1 > own + 0.5


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--exe", required=True, help="liggghts-wheel")
    p.add_argument("--inputs", required=True, help="the inputs/ directory")
    p.add_argument("--mesh", required=True, help="wheel mesh (test_small.stl)")
    p.add_argument("--work", required=True, help="work directory (beds are cached here)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--size", choices=sorted(SIZES), default="large",
                   help="bed made (once) like bench_wheel_cosim.py's (default large)")
    g.add_argument("--bed", help="use this prepared bed instead (its .vars beside it)")
    p.add_argument("--nps", default="1,2", help="rank counts, the first is the reference")
    p.add_argument("--steps", type=int, default=1000, help="steps per run (default 1000)")
    p.add_argument("--mpiexec", default="mpiexec")
    p.add_argument("--bed-np", type=int, default=2, help="ranks for making the bed")
    a = p.parse_args()
    nps = [int(x) for x in a.nps.split(",")]
    os.makedirs(a.work, exist_ok=True)
    exe = os.path.abspath(a.exe)
    if os.geteuid() == 0:  # OpenMPI refuses root without these (docs/building.md, CI machines)
        os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")

    load0, cores, busy = load_note()
    print(f"bench: load average {load0:.2f} on {cores} core(s) at the start"
          + (" -- BUSY: the numbers below measure the other jobs too; time on an idle machine"
             if busy else ""), flush=True)
    if a.bed:
        restart = os.path.abspath(a.bed)
    else:
        a.launch = [a.mpiexec, "-n", str(a.bed_np), exe]
        restart = bed(a, a.size)
    x0 = 0.5 * bed_length(restart) - 0.05
    print(f"bench: deck {os.path.normpath(DECK)}, bed {restart}, mesh {a.mesh}, {a.steps} steps "
          "per run; fix wheel/cosim, wheel starts 4 mm above the bed mid-bin and sinks at "
          "0.1 m/s while rolling (1.5 rad/s, slip 0.25); neighbour lists by distance check")

    res = {}
    for n in nps:
        v = {"inputs_dir": a.inputs, "restart_file": restart, "mesh": a.mesh, "impl": "cosim",
             "steps": a.steps, "vz": -0.1, "neigh_every_step": 0, "thermo_every": 1000,
             "x0": x0, "gap": 0.004}
        cmd = [a.mpiexec, "-n", str(n), exe, "-in", DECK, "-log", "none", "-echo", "none"]
        for k, val in v.items():
            cmd += ["-var", k, str(val)]
        r = subprocess.run(cmd, cwd=a.work, capture_output=True, text=True)
        if r.returncode != 0 or "ERROR" in r.stdout:
            sys.exit(f"bench: np {n} run failed (exit {r.returncode}):\n{r.stdout[-2000:]}"
                     f"{r.stderr[-1000:]}")
        t, atoms, share = timing(r.stdout, a.steps)
        res[n] = t
        grid = re.search(r"(\d+ by \d+ by \d+) MPI processor grid", r.stdout)
        fix = share.pop("wheel/cosim", None)
        print(f"bench: np {n}: {atoms} particles, grid {grid.group(1) if grid else '?'}: "
              f"{t * 1e3:.4g} ms/step (LIGGGHTS' Loop time / {a.steps}), "
              f"{atoms / t:.3g} particle-steps/s")
        print(f"bench:   np {n} time shares %: "
              + ", ".join(f"{k} {s[1]:.1f}" for k, s in share.items())
              + (f"; fix wheel/cosim {fix[1]:.1f} ({1e6 * fix[0] / a.steps:.0f} us/step)"
                 if fix else ""), flush=True)

    t1 = res[nps[0]]
    for n in nps[1:]:
        eff = t1 * nps[0] / (n * res[n])
        ref = f"goal >= {GOAL} (issue 12 item 5, np 1 -> 2 at ~100 000 particles)" \
            if n == 2 and nps[0] == 1 else "no goal for this rank count"
        print(f"bench: parallel efficiency np {nps[0]} -> {n} = t{nps[0]} / ({n // nps[0]} t{n}) "
              f"= {t1 * 1e3:.4g} / ({n // nps[0]} x {res[n] * 1e3:.4g}) ms = {eff:.3f}; "
              f"compared to {ref}: {'meets' if eff >= GOAL else 'below'}")
    load1, _, busy1 = load_note(own=max(nps))
    print(f"bench: load average {load1:.2f} at the end"
          + (" -- BUSY: not a measurement for the record" if busy or busy1 else ""))


if __name__ == "__main__":
    main()
