#!/usr/bin/python3
"""Cost of fix wheel/cosim against LIGGGHTS' mesh wall (fix mesh/surface/stress + move/mesh +
wall/gran), same bed, same deck (tests/wheel_cosim/in.wheel_roll), same prescribed motion.

  bench_wheel_cosim.py --exe liggghts-wheel --inputs DIR --mesh test_small.stl --work DIR
                       [--sizes small,large] [--np 1] [--steps 2000] [--full-scan]

Per bed size: makes the bed with inputs/in.soilbin (cached in WORK), runs both implementations
and prints from LIGGGHTS' timing summary:
  * cost per step ratio ours / reference = (Loop time / steps) ours / (Loop time / steps) ref;
  * the wheel's share of the step: 'Modify' time share (LIGGGHTS' "Modify time (%)") of each run,
    which contains the wheel contact (our fix's post_force, or the reference's wall/gran +
    mesh neighbour list + move/mesh) plus the other fixes (gravity, bin walls, integration);
    the bare share of the other fixes is measured by a third run without any wheel;
  * with --full-scan, a fourth run of our fix with 'candidates no' (every particle tested every
    step) against the default candidate list: the fix's own time per step in both.
Not a test (a run takes minutes at 100 000 particles).
"""
import argparse
import os
import re
import subprocess
import sys

from liggghts_log_path import loops  # the shared parser of LIGGGHTS' "Loop time" lines

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "..", "tests", "wheel_cosim", "in.wheel_roll")
# bin length, width, fill height [m] -> about 10 000 and 100 000 ci spheres
# the large bed is the small one widened 3 x 3: a deep bin settles far slower (its first try,
# 0.40 x 0.30 x 0.12 m, ran at 0.37 s/step during insertion)
SIZES = {"small": (0.36, 0.12, 0.035), "large": (1.08, 0.36, 0.035)}


def bed(a, size):
    L, W, H = SIZES[size]
    d = os.path.join(a.work, f"bed_{size}")
    os.makedirs(d, exist_ok=True)
    restart = os.path.join(d, "soilbin_ci.restart")
    if not os.path.exists(restart + ".vars"):
        print(f"bench: making the {size} bed ({L} x {W} x {H} m) ...", flush=True)
        subprocess.run(a.launch + ["-in", os.path.join(a.inputs, "in.soilbin"), "-log", "none",
                                   "-var", "inputs_dir", a.inputs, "-var", "soil", "ci",
                                   "-var", "bin_length", str(L), "-var", "bin_width", str(W),
                                   "-var", "fill_height", str(H), "-var", "max_settle_time",
                                   "1.0", "-var", "out_dir", d],
                       cwd=d, check=True, stdout=subprocess.DEVNULL)
    return restart


def timing(text, steps):
    loop, _procs, _steps, atoms = [r for r in loops(text) if r.steps == steps][-1]
    tail = text[text.rfind(f"for {steps} steps"):]
    share = {}
    for key in ("Pair", "Neigh", "Comm", "Outpt", "Modify", "Other"):
        mm = re.search(rf"^{key}\s+time \(%\) = (\S+) \((\S+)\)", tail, re.M)
        if mm:
            share[key] = (float(mm.group(1)), float(mm.group(2)))
    # the fix's own wall time, printed by fix wheel/cosim at the end of each run
    fix = re.findall(r"fix wheel/cosim \S+: (\d+) steps, contacts (\S+) s", text)
    share["wheel/cosim"] = (float(fix[-1][1]), 100.0 * float(fix[-1][1]) / loop) if fix \
        else None
    return loop / steps, atoms, share


def run(a, restart, impl, x0, sink):
    v = {"inputs_dir": a.inputs, "restart_file": restart, "mesh": a.mesh, "impl": impl,
         "steps": a.steps, "vz": sink, "neigh_every_step": 0, "thermo_every": 1000, "x0": x0,
         "gap": 0.004}
    if impl == "none":
        v["impl"] = "none_wheel"
    if impl == "cosim_full_scan":
        v["impl"], v["cosim_extra"] = "cosim", "candidates no"
    cmd = a.launch + ["-in", DECK, "-log", "none", "-echo", "none"]
    for k, val in v.items():
        cmd += ["-var", k, str(val)]
    r = subprocess.run(cmd, cwd=a.work, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"bench: {impl} run failed:\n{r.stdout[-2000:]}")
    return timing(r.stdout, a.steps)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", required=True)
    p.add_argument("--inputs", required=True)
    p.add_argument("--mesh", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--sizes", default="small,large")
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--mpiexec", default="mpiexec")
    p.add_argument("--steps", type=int, default=2000)
    p.add_argument("--full-scan", action="store_true",
                   help="also run our fix with 'candidates no' and compare its own time")
    a = p.parse_args()
    a.launch = ([a.mpiexec, "-n", str(a.np)] if a.np > 1 else []) + [os.path.abspath(a.exe)]
    os.makedirs(a.work, exist_ok=True)
    print(f"bench: deck {os.path.normpath(DECK)}, mesh {a.mesh}, {a.steps} steps, np {a.np}; "
          "wheel starts 4 mm above the bed and sinks at 0.1 m/s while rolling (1.5 rad/s, slip 0.25)")
    for size in a.sizes.split(","):
        restart = bed(a, size)
        x0 = 0.5 * SIZES[size][0] - 0.05
        res = {impl: run(a, restart, impl, x0, -0.1) for impl in ("cosim", "mesh", "none")}
        (t_o, n, s_o), (t_r, _, s_r), (t_n, _, s_n) = res["cosim"], res["mesh"], res["none"]
        print(f"bench: {size}: {n} particles")
        print(f"bench:   time per step: ours {t_o * 1e3:.4g} ms, reference (mesh wall) "
              f"{t_r * 1e3:.4g} ms, no wheel {t_n * 1e3:.4g} ms")
        print(f"bench:   cost per step ratio ours / reference = {t_o / t_r:.3f} "
              f"(compared to 1.0: equal cost; from LIGGGHTS' Loop time)")
        print(f"bench:   wheel cost per step (minus the no-wheel run): ours "
              f"{(t_o - t_n) * 1e3:.4g} ms, reference {(t_r - t_n) * 1e3:.4g} ms, ratio "
              f"{(t_o - t_n) / (t_r - t_n):.3f}")
        for name, s in (("ours", s_o), ("reference", s_r), ("no wheel", s_n)):
            print(f"bench:   {name:9s} time shares %: " +
                  ", ".join(f"{k} {v[1]:.1f}" for k, v in s.items() if v))
        fix_s, fix_pct = s_o["wheel/cosim"]
        print(f"bench:   fix share of the step (ours, measured inside the fix): {fix_pct:.1f} % "
              f"({1e6 * fix_s / a.steps:.0f} us/step); by difference with the no-wheel run: "
              f"ours {(t_o - t_n) / t_o * 100:.1f} %, reference's wheel "
              f"{(t_r - t_n) / t_r * 100:.1f} % (differences below ~3 % are run-to-run noise)",
              flush=True)
        if a.full_scan:
            t_f, _, s_f = run(a, restart, "cosim_full_scan", x0, -0.1)
            list_s, full_s = s_o["wheel/cosim"][0], s_f["wheel/cosim"][0]
            print(f"bench:   fix time per step: candidate list {1e6 * list_s / a.steps:.0f} us, "
                  f"every particle ('candidates no') {1e6 * full_s / a.steps:.0f} us, ratio "
                  f"{list_s / full_s:.3f}; step {t_o * 1e3:.4g} vs {t_f * 1e3:.4g} ms", flush=True)


if __name__ == "__main__":
    main()
