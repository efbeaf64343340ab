#!/usr/bin/python3
"""The active domain (fix wheel/active, docs/fix-wheel-active.md): speed-up against bin length, and
the wheel's answer with and without it.

  bench_active_domain.py --exe liggghts-wheel --inputs DIR --mesh test_small.stl --work DIR
                         [--lengths 0.5,1,2] [--steps 4000] [--np 1] [--active-args "..."]
                         [--active-fixes 0|1]
                         [--coupled-rig RIG.toml --wheel-cosim scripts/wheel-cosim]

1. Speed-up: for each bin length L, a ci bed 0.10 m wide, fill 0.025 m (tiled from 0.25 m blocks
   with inputs/in.soilbin, made once into WORK/bed_L<L>), the lugged test wheel at mid-bin
   sinking at 0.05 m/s while rolling at slip 0.25 (tests/active_domain/in.active_domain,
   prescribed motion; first contact after ~1650 steps), the same deck with and without
   `fix wheel/active` (default distance unless --active-args). Prints per L: particles, time per
   step (LIGGGHTS' Loop time / steps) without and with, the speed-up, the mean active share, and
   the window means of the wheel force and torque (from step 2500 on) with their differences.
2. With --coupled-rig: one coupled run (scripts/wheel-cosim, inputs/examples/in.wheel_coupled,
   the rig's imposed slip) on the longest bed with and without the active domain: the means of
   drawbar pull, driving torque and sinkage over the rig's test phase (run file), their
   differences (goal: within 2 %, issue 12 item 1) and the wall times.

Wall-clock timing: prints the 1-minute load average before and after each run (another job on
the machine slows both runs alike only if it is steady). Not a test.
"""
import argparse
import os
import re
import subprocess
import sys
import time

import numpy as np

from liggghts_log_path import liggghts_log, loops  # the shared parser of LIGGGHTS' output

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DECK = os.path.join(ROOT, "tests", "active_domain", "in.active_domain")
WINDOW_FROM = 2500  # steps: the window of the force means starts here (contact from ~1650)


def load():
    return os.getloadavg()[0]


def git_hash():
    r = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                       text=True)
    return r.stdout.strip() or "unknown"


def launcher(a):
    if a.np == 1:
        return [a.exe]
    return [a.mpiexec, "-n", str(a.np), "--oversubscribe", "--allow-run-as-root", a.exe]


def make_bed(a, length):
    work = os.path.join(a.work, f"bed_L{length:g}")
    restart = os.path.join(work, "soilbin_ci.restart")
    if os.path.exists(restart) and os.path.exists(restart + ".vars"):
        return restart
    os.makedirs(work, exist_ok=True)
    cmd = launcher(a) + ["-in", os.path.join(a.inputs, "in.soilbin"), "-var", "inputs_dir",
                         a.inputs, "-var", "soil", "ci", "-var", "bin_length", f"{length:g}",
                         "-var", "bin_width", "0.1", "-var", "fill_height", "0.025",
                         "-var", "tile_length", "0.25", "-var", "out_dir", ".",
                         "-log", "log.bed", "-echo", "none"]
    t0 = time.time()
    with open(os.path.join(work, "out.txt"), "w") as fh:
        r = subprocess.run(cmd, cwd=work, stdout=fh, stderr=subprocess.STDOUT)
    if r.returncode != 0 or not os.path.exists(restart):
        sys.exit(f"bench: bed L={length:g} failed (see {work}/out.txt)")
    print(f"bench: bed L = {length:g} m made in {time.time() - t0:.0f} s")
    return restart


def run_wheel(a, restart, length, active):
    name = os.path.join(a.work, f"roll_L{length:g}_{'on' if active else 'off'}")
    os.makedirs(name, exist_ok=True)
    variables = {"inputs_dir": a.inputs, "restart_file": restart, "mesh": a.mesh,
                 "x0": length / 2, "vx": 0.1125, "vz": -0.05, "wy": 1.5,
                 "steps1": a.steps, "thermo_every": 10,
                 "active": 1 if active else 0, "active_args": a.active_args,
                 "active_fixes": a.active_fixes}
    cmd = launcher(a) + ["-in", DECK, "-log", "none", "-echo", "none"]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    l0 = load()
    with open(os.path.join(name, "out.txt"), "w") as fh:
        r = subprocess.run(cmd, cwd=name, stdout=fh, stderr=subprocess.STDOUT)
    text = open(os.path.join(name, "out.txt")).read()
    if r.returncode != 0 or "active_domain: done" not in text:
        sys.exit(f"bench: {name} failed (see its out.txt)")
    seconds, _procs, steps, atoms = [r for r in loops(text) if r.steps > 0][-1]
    share = re.findall(r"([0-9.]+) of ([0-9.]+) particles active on average", text)
    wheel = liggghts_log.merged(text, "fx")   # in.active_domain's thermo_style
    step = np.array(wheel.values("Step"))
    window = step >= step[0] + WINDOW_FROM
    means = {k: np.array(wheel.values(k))[window].mean() for k in ("fx", "fz", "ty")}
    return {"ms_per_step": 1e3 * seconds / steps, "atoms": atoms,
            "active": float(share[-1][0]) if share else float(atoms), "means": means,
            "load": (l0, load())}


def speedup(a):
    print(f"bench: git {git_hash()}, np {a.np}, {a.steps} steps per run, wheel test_small "
          f"(R 0.1 m), active-domain keywords '{a.active_args or '(defaults)'}', active_fixes "
          f"{a.active_fixes}")
    print("bench: L [m] | particles | ms/step without | with | speed-up | active share | "
          "dFx/|F|, dFz/|F|, dTy/(|F| R) | load avg before/after (without; with)")
    results = []
    for length in a.lengths:
        restart = make_bed(a, length)
        off = run_wheel(a, restart, length, False)
        on = run_wheel(a, restart, length, True)
        f = np.hypot(off["means"]["fx"], off["means"]["fz"])
        d = [(on["means"][k] - off["means"][k]) / (f * (0.1 if k == "ty" else 1.0))
             for k in ("fx", "fz", "ty")]
        ratio = off["ms_per_step"] / on["ms_per_step"]
        results.append((length, off["atoms"], ratio))
        print(f"bench: {length:g} | {off['atoms']} | {off['ms_per_step']:.3f} | "
              f"{on['ms_per_step']:.3f} | {ratio:.2f}x | {on['active'] / on['atoms']:.3f} | "
              f"{d[0]:+.2e}, {d[1]:+.2e}, {d[2]:+.2e} | {off['load'][0]:.1f}/{off['load'][1]:.1f}; "
              f"{on['load'][0]:.1f}/{on['load'][1]:.1f}")
    if len(results) > 1:
        (l0, n0, r0), (l1, n1, r1) = results[0], results[-1]
        print(f"bench: speed-up grows from {r0:.2f}x at {l0:g} m to {r1:.2f}x at {l1:g} m "
              f"({n0} -> {n1} particles)")


def coupled(a):
    """Coupled runs with and without the active domain on the longest bed: run-file means."""
    import h5py  # Debian's python3-h5py

    length = max(a.lengths)
    restart = make_bed(a, length)
    means, walls = {}, {}
    for active in (0, 1):
        work = os.path.join(a.work, f"coupled_L{length:g}_{'on' if active else 'off'}")
        out = os.path.join(work, "run.h5")
        if os.path.exists(out) and not os.path.exists(os.path.join(work, "finished")):
            os.remove(out)  # an interrupted run: run it again
        if not os.path.exists(out):
            cmd = [a.wheel_cosim, "--rig", a.coupled_rig, "--bed", restart, "--deck",
                   os.path.join(a.inputs, "examples", "in.wheel_coupled"), "--np", str(a.np),
                   "--work", work, "--out", out, "--", "-var", "x0", f"{length / 2:g}",
                   "-var", "active_domain", str(active), "-var", "active_args", a.active_args,
                   "-var", "output_every", "0"]
            t0, l0 = time.time(), load()
            # wheel-cosim takes its executables from WHEELSIM_BUILD_DIR (default <repo>/build)
            env = dict(os.environ, WHEELSIM_BUILD_DIR=os.path.dirname(os.path.dirname(a.exe)))
            r = subprocess.run(cmd, capture_output=True, text=True, env=env)
            if r.returncode != 0:
                sys.exit(f"bench: coupled run failed: {r.stdout[-2000:]}{r.stderr[-2000:]}")
            walls[active] = (time.time() - t0, l0, load())
            open(os.path.join(work, "finished"), "w").write(f"{walls[active][0]:.1f} s wall\n")
        with h5py.File(out, "r") as h:
            phase = h["/observables/phase/value"][()] if "/observables/phase" in h else None
            vals = {}
            for name in ("drawbar_pull", "driving_torque", "sinkage"):
                v = h[f"/observables/{name}/value"][()]
                sel = (phase == phase.max()) if phase is not None else slice(len(v) // 2, None)
                vals[name] = float(np.mean(v[sel]))
            means[active] = vals
    print(f"bench: coupled, {a.coupled_rig}, bed L = {length:g} m, np {a.np}:")
    for name in ("drawbar_pull", "driving_torque", "sinkage"):
        off, on = means[0][name], means[1][name]
        print(f"bench:   {name}: without {off:.6g}, with {on:.6g}, difference "
              f"{(on - off) / abs(off) * 100:+.2f} %")
    for active, (wall, l0, l1) in sorted(walls.items()):
        print(f"bench:   wall time {'with' if active else 'without'}: {wall:.0f} s "
              f"(load average {l0:.1f} -> {l1:.1f})")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--exe", required=True)
    p.add_argument("--inputs", required=True)
    p.add_argument("--mesh", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--lengths", default="0.5,1,2",
                   type=lambda s: [float(x) for x in s.split(",")])
    p.add_argument("--steps", type=int, default=6000)
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--mpiexec", default="mpiexec")
    p.add_argument("--active-args", default="", help="fix wheel/active keywords")
    p.add_argument("--active-fixes", type=int, choices=(0, 1), default=1,
                   help="1: gravity, walls and integrator on the active group only (deck "
                        "variable active_fixes); 0: on every particle")
    p.add_argument("--coupled-rig", help="rig config: also compare a coupled run")
    p.add_argument("--wheel-cosim", default=os.path.join(ROOT, "scripts", "wheel-cosim"))
    p.add_argument("--skip-speedup", action="store_true")
    a = p.parse_args()
    for k in ("exe", "inputs", "mesh", "work", "coupled_rig", "wheel_cosim"):
        if getattr(a, k):
            setattr(a, k, os.path.abspath(getattr(a, k)))
    os.makedirs(a.work, exist_ok=True)
    if not a.skip_speedup:
        speedup(a)
    if a.coupled_rig:
        coupled(a)


if __name__ == "__main__":
    main()
