#!/usr/bin/python3
"""Tiled vs whole-settled soil bed (issue 12 item 2; docs/soil-bins.md "Tiled beds").

Prepares the same bin twice with inputs/in.soilbin — settled whole, and tiled (tile_length) —
and prints what each cost and how the two beds compare:
  - preparation: wall time, LIGGGHTS loop time and sphere-steps (sum over the deck's runs of
    spheres x steps, from its "Loop time of T on P procs for S steps with N atoms" lines), and
    the ratios whole / tiled;
  - the result blocks (spheres, mass, bed depth, bulk densities, steps);
  - bulk density vs depth in the interior (x at least `--zone` d_max from the end walls, |y| at
    most W/2 - d_max; slices of d_max/2, exact sphere-slab volumes);
  - bulk density and surface height along x (slices of 2 d_max; the end zones show here);
  - optionally (--wheel MESH) a short prescribed-motion wheel run on each bed
    (tests/cosim/in.motion_compare: the wheel sinks while rolling) with the mean contact force
    and torque over the second half.

  bench_tiled_bed.py --exe build/bin/liggghts-wheel --inputs inputs --work DIR --soil dry_sand \
      --bin-length 1.0 --bin-width 0.3 --fill-height 0.1 --tile-length 0.25 \
      [--var max_settle_time 5] [--np 1] [--reuse] [--wheel build/meshes/test_small.stl]

--reuse keeps a bed already in WORK/<mode>/ (bed.restart with wall.txt from an earlier run of this
script or its shell equivalent), so the two preparations can be run at different times. The
printout (also WORK/result.txt) names the git revision, the command and the machine with its
load average: on a shared machine the wall times are the machine's, the sphere-steps are not.
"""

import argparse
import math
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from liggghts_log_path import loops  # the shared parser of LIGGGHTS' "Loop time" lines
RESULT_RE = re.compile(r"^soilbin: ([a-z_]+) = (.*)$", re.M)


def run_bed(a, mode, out):
    """Runs in.soilbin for `mode` (whole or tiled) in `out`; writes out/wall.txt."""
    out.mkdir(parents=True, exist_ok=True)
    cmd = []
    if a.np > 1:
        cmd = ["mpirun", "-np", str(a.np), "--oversubscribe"]
        if os.geteuid() == 0:
            cmd.append("--allow-run-as-root")
    cmd += [a.exe, "-in", str(Path(a.inputs) / "in.soilbin"), "-echo", "none", "-log",
            "log.soilbin", "-var", "inputs_dir", str(Path(a.inputs).resolve()), "-var", "out_dir",
            ".", "-var", "restart_file", "./bed.restart", "-var", "soil", a.soil,
            "-var", "bin_length", str(a.bin_length), "-var", "bin_width", str(a.bin_width),
            "-var", "fill_height", str(a.fill_height)]
    for k, v in a.var:
        cmd += ["-var", k, v]
    if mode == "tiled":
        cmd += ["-var", "tile_length", str(a.tile_length)]
    print(f"bench: {mode}: {' '.join(cmd)}", flush=True)
    t0 = time.monotonic()
    with open(out / "screen.txt", "w") as f:
        rc = subprocess.run(cmd, cwd=out, stdout=f, stderr=subprocess.STDOUT).returncode
    wall = time.monotonic() - t0
    (out / "wall.txt").write_text(f"rc {rc} wall {wall:.3f}\n")
    if rc != 0:
        sys.exit(f"bench: {mode} bed failed (exit {rc}); see {out / 'screen.txt'}")


def bed_cost(out):
    """(wall [s], loop time [s], sphere-steps, result dict) of a prepared bed."""
    m = re.match(r"rc (\d+) wall ([0-9.]+)", (out / "wall.txt").read_text())
    if not m or m.group(1) != "0":
        sys.exit(f"bench: {out / 'wall.txt'}: the preparation failed or did not finish")
    screen = (out / "screen.txt").read_text(errors="replace")
    loop = sphere_steps = 0.0
    for r in loops(screen):
        loop += r.seconds
        sphere_steps += float(r.steps) * r.atoms
    res = dict(RESULT_RE.findall(screen))
    return float(m.group(2)), loop, sphere_steps, res


def dump_atoms(a, out):
    """out/atoms.txt: id x y z radius mass of the bed (resume.in + write_dump, serial)."""
    f = out / "atoms.txt"
    if f.is_file() and f.stat().st_mtime >= (out / "bed.restart").stat().st_mtime:
        return f
    deck = out / "in.dump_atoms"
    deck.write_text(f"variable restart_file index {out.resolve()}/bed.restart\n"
                    "variable resume_steps index 0\n"
                    f"include {Path(a.inputs).resolve()}/soilbin/resume.in\n"
                    f"write_dump all custom {f.resolve()} id x y z radius mass\n")
    subprocess.run([a.exe, "-in", str(deck), "-log", "none", "-echo", "none", "-var",
                    "inputs_dir", str(Path(a.inputs).resolve())], cwd=out, check=True,
                   stdout=subprocess.DEVNULL)
    return f


def load_atoms(f):
    d = np.loadtxt(f, skiprows=9)
    return {"x": d[:, 1], "y": d[:, 2], "z": d[:, 3], "r": d[:, 4], "m": d[:, 5]}


def slab_fraction(z, r, lo, hi):
    """Fraction of each sphere's volume (centre z, radius r) between planes lo and hi."""
    def below(h):  # volume fraction of a sphere below the plane at centre-relative height h
        t = np.clip(h / r, -1.0, 1.0)
        return 0.25 * (t + 1.0) ** 2 * (2.0 - t)  # cap volume / sphere volume
    return below(hi - z) - below(lo - z)


def depth_profile(at, L, W, dmax, zone, dz, zmax):
    """Bulk density [kg/m^3] in z slices of the interior cell."""
    sel = (at["x"] >= zone) & (at["x"] <= L - zone) & (np.abs(at["y"]) <= 0.5 * W - dmax)
    area = (L - 2 * zone) * (W - 2 * dmax)
    edges = np.arange(0.0, zmax + 1e-12, dz)
    out = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        frac = slab_fraction(at["z"][sel], at["r"][sel], lo, hi)
        out.append((0.5 * (lo + hi), float((at["m"][sel] * frac).sum() / (area * (hi - lo)))))
    return out


def x_profile(at, L, W, dmax, zlo, zhi, dx):
    """Along x: bulk density of z in [zlo, zhi] and the mean surface height (highest z + r in
    each of a few y columns) per x slice."""
    edges = np.arange(0.0, L + 1e-12, dx)
    ny = max(int(W // (2 * dmax)), 1)
    yedges = np.linspace(-0.5 * W, 0.5 * W, ny + 1)
    out = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        inx = (at["x"] >= lo) & (at["x"] < hi)
        frac = slab_fraction(at["z"][inx], at["r"][inx], zlo, zhi)
        rho = float((at["m"][inx] * frac).sum() / ((hi - lo) * W * (zhi - zlo)))
        tops = []
        for ylo, yhi in zip(yedges[:-1], yedges[1:]):
            c = inx & (at["y"] >= ylo) & (at["y"] < yhi)
            if c.any():
                tops.append(float((at["z"][c] + at["r"][c]).max()))
        out.append((0.5 * (lo + hi), rho, float(np.mean(tops)) if tops else float("nan")))
    return out


def wheel_run(a, out, x0, steps):
    """Mean contact force and torque over the second half of a prescribed-motion wheel run."""
    log = out / f"wheel_x{x0:g}.log"
    if not log.is_file() or "motion_compare: done" not in log.read_text(errors="replace"):
        repo = Path(a.inputs).resolve().parent
        cmd = [a.exe, "-in", str(repo / "tests" / "cosim" / "in.motion_compare"), "-echo",
               "none", "-log", "none", "-var", "inputs_dir", str(Path(a.inputs).resolve()),
               "-var", "restart", str((out / "bed.restart").resolve()), "-var", "mesh",
               str(Path(a.wheel).resolve()), "-var", "motion", "prescribed", "-var", "x0",
               str(x0), "-var", "steps", str(steps)]
        print(f"bench: wheel: {' '.join(cmd)}", flush=True)
        with open(log, "w") as f:
            subprocess.run(cmd, cwd=out, stdout=f, stderr=subprocess.STDOUT, check=True)
    rows = []
    for line in log.read_text(errors="replace").splitlines():
        f = line.split()
        if len(f) == 11 and f[0].isdigit():
            try:
                rows.append([float(v) for v in f])
            except ValueError:
                pass
    d = np.array(rows)
    d = d[d[:, 0] >= d[0, 0] + steps // 2]
    return {"Fx": d[:, 2].mean(), "Fz": d[:, 4].mean(), "My": d[:, 6].mean(),
            "contacts": d[:, 8].mean(), "sd_Fz": d[:, 4].std()}


def tiled_only(a):
    """The cost of a tiled bed alone (a bin too big to settle whole here), and the whole bed's
    estimated: its spheres x the block's settling steps (a bed settles in about the same number
    of steps whatever its length: 57 379 for both on the 1 m dry_sand bin), at the tiled run's
    loop rate."""
    work = Path(a.work).resolve()
    out = work / "tiled"
    load0 = os.getloadavg()[0]
    if a.reuse and (out / "bed.restart").is_file() and (out / "wall.txt").is_file():
        print(f"bench: tiled: reusing {out}", flush=True)
    else:
        run_bed(a, "tiled", out)
    wall, loop, ss, res = bed_cost(out)
    rev = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], capture_output=True,
                         text=True, cwd=Path(__file__).resolve().parent).stdout.strip()
    cpu = next((ln.split(":", 1)[1].strip() for ln in open("/proc/cpuinfo")
                if ln.startswith("model name")), "?")
    lines = [f"bench_tiled_bed (tiled only): git {rev}; {platform.node()}, {os.cpu_count()} "
             f"cores, {cpu}; load average {load0:.2f} now "
             f"({(out / 'wall.txt').read_text().strip()})",
             f"command: {' '.join(sys.argv)}",
             f"bin: {a.soil} {a.bin_length} x {a.bin_width} m, fill_height {a.fill_height} m, "
             f"np {a.np}, extra {a.var}; tile_length {a.tile_length} m", ""]
    for k in ("spheres", "particle_mass", "bed_depth", "bulk_density", "core_bulk_density",
              "settled", "settle_steps", "final_step", "tiles", "tile_length", "tile_spheres",
              "tile_cut", "relax_steps", "relax_zone_steps"):
        lines.append(f"{k:22s} {res.get(k, '?')}")
    n = float(res["spheres"])
    whole_ss = n * float(res["settle_steps"])
    lines += ["", f"preparation: wall {wall:.1f} s, LIGGGHTS loop {loop:.1f} s, sphere-steps "
              f"{ss:.4g} ({ss / loop:.3g} sphere-steps/s)",
              f"whole bed, estimated: {n:.0f} spheres x {res['settle_steps']} steps = "
              f"{whole_ss:.4g} sphere-steps = {whole_ss / ss:.2f} x the tiled bed's; at the "
              f"tiled run's rate {whole_ss / (ss / loop):.0f} s of loop time"]
    print("\n".join(lines))
    (work / "result.txt").write_text("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--inputs", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--soil", default="dry_sand")
    ap.add_argument("--bin-length", type=float, default=1.0)
    ap.add_argument("--bin-width", type=float, default=0.3)
    ap.add_argument("--fill-height", type=float, default=0.1)
    ap.add_argument("--tile-length", type=float, default=0.25)
    ap.add_argument("--var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"))
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--zone", type=float, default=6.0,
                    help="interior cell: at least this many d_max from the end walls")
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--tiled-only", action="store_true",
                    help="prepare (or reuse) only the tiled bed and print its cost, with the "
                    "whole bed's estimated as spheres x the block's settling steps")
    ap.add_argument("--wheel", help="wheel mesh for a prescribed-motion run on each bed")
    ap.add_argument("--wheel-steps", type=int, default=8000)
    ap.add_argument("--wheel-x0", type=float, nargs="+", help="wheel start positions [m] "
                    "(default: mid-bin)")
    a = ap.parse_args()
    a.exe = str(Path(a.exe).resolve())
    if a.tiled_only:
        return tiled_only(a)
    a.inputs = str(Path(a.inputs).resolve())
    work = Path(a.work).resolve()
    load0 = os.getloadavg()[0]
    for mode in ("whole", "tiled"):
        out = work / mode
        if a.reuse and (out / "bed.restart").is_file() and (out / "wall.txt").is_file():
            print(f"bench: {mode}: reusing {out}", flush=True)
        else:
            run_bed(a, mode, out)
    cost = {m: bed_cost(work / m) for m in ("whole", "tiled")}
    screen = (work / "whole" / "screen.txt").read_text(errors="replace")
    m = re.search(r"d = ([0-9.eE+-]+)\.\.([0-9.eE+-]+) m", screen)
    dmax = float(m.group(2))
    L, W = a.bin_length, a.bin_width
    atoms = {mm: load_atoms(dump_atoms(a, work / mm)) for mm in ("whole", "tiled")}
    depth = min(float(cost[mm][3]["bed_depth"]) for mm in cost)
    lines = []

    def say(s=""):
        print(s)
        lines.append(s)

    rev = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], capture_output=True,
                         text=True, cwd=Path(__file__).resolve().parent).stdout.strip()
    cpu = next((ln.split(":", 1)[1].strip() for ln in open("/proc/cpuinfo")
                if ln.startswith("model name")), "?")
    say(f"bench_tiled_bed: git {rev}; {platform.node()}, {os.cpu_count()} cores, {cpu}; "
        f"load average {load0:.2f} at the start, {os.getloadavg()[0]:.2f} at the end")
    say(f"command: {' '.join(sys.argv)}")
    say(f"bin: {a.soil} {L} x {W} m, fill_height {a.fill_height} m, np {a.np}, extra {a.var}; "
        f"tiled: tile_length {a.tile_length} m")
    say()
    keys = ("spheres", "particle_mass", "bed_depth", "bulk_density", "core_bulk_density",
            "settled", "settle_steps", "final_step", "tiles", "tile_length", "tile_spheres",
            "tile_cut", "relax_steps", "relax_zone_steps")
    say(f"{'':22s} {'whole':>16s} {'tiled':>16s} {'tiled/whole-1':>14s}")
    for k in keys:
        w, t = cost["whole"][3].get(k, "?"), cost["tiled"][3].get(k, "?")
        try:
            rel = f"{100.0 * (float(t) / float(w) - 1.0):+.2f} %" if k in (
                "particle_mass", "bed_depth", "bulk_density", "core_bulk_density") else ""
        except (ValueError, ZeroDivisionError):
            rel = ""
        say(f"{k:22s} {w:>16.16s} {t:>16.16s} {rel:>14s}")
    say()
    for i, name in ((0, "wall time [s]"), (1, "LIGGGHTS loop time [s]"), (2, "sphere-steps")):
        w, t = cost["whole"][i], cost["tiled"][i]
        say(f"preparation {name:24s} whole {w:14.4g}  tiled {t:14.4g}  whole/tiled {w / t:6.2f}")
    say()
    dz = 0.5 * dmax
    zone = a.zone * dmax
    pw = depth_profile(atoms["whole"], L, W, dmax, zone, dz, depth)
    pt = depth_profile(atoms["tiled"], L, W, dmax, zone, dz, depth)
    say(f"bulk density vs depth [kg/m^3], interior x in [{zone:.3g}, {L - zone:.3g}] m, "
        f"|y| <= {0.5 * W - dmax:.3g} m, slices {dz:.3g} m")
    say(f"{'z [m]':>8s} {'whole':>9s} {'tiled':>9s} {'diff':>8s}")
    diffs = []
    for (z, w), (_, t) in zip(pw, pt):
        d = 100.0 * (t / w - 1.0) if w > 0 else float("nan")
        if dmax <= z <= depth - 2 * dmax:
            diffs.append(d)
        say(f"{z:8.4f} {w:9.1f} {t:9.1f} {d:+7.2f}%")
    diffs = np.array(diffs)
    say(f"between z = d_max and depth - 2 d_max ({len(diffs)} slices): mean difference "
        f"{diffs.mean():+.2f} %, rms {math.sqrt((diffs ** 2).mean()):.2f} %, max |diff| "
        f"{np.abs(diffs).max():.2f} %")
    say()
    zlo, zhi = dmax, depth - 2 * dmax
    xw = x_profile(atoms["whole"], L, W, dmax, zlo, zhi, 2 * dmax)
    xt = x_profile(atoms["tiled"], L, W, dmax, zlo, zhi, 2 * dmax)
    say(f"along x: bulk density of z in [{zlo:.3g}, {zhi:.3g}] m and mean surface height, "
        f"slices {2 * dmax:.3g} m")
    say(f"{'x [m]':>8s} {'rho whole':>10s} {'rho tiled':>10s} {'top whole':>10s} "
        f"{'top tiled':>10s}")
    for (x, rw, hw), (_, rt, ht) in zip(xw, xt):
        say(f"{x:8.4f} {rw:10.1f} {rt:10.1f} {hw:10.4f} {ht:10.4f}")
    rw = np.array([r for _, r, _ in xw])
    rt = np.array([r for _, r, _ in xt])
    hw = np.array([h for _, _, h in xw])
    ht = np.array([h for _, _, h in xt])
    say(f"along x, all slices: density mean whole {rw.mean():.1f} tiled {rt.mean():.1f} "
        f"({100 * (rt.mean() / rw.mean() - 1):+.2f} %), sd {rw.std():.1f} / {rt.std():.1f}; "
        f"surface mean {hw.mean():.4f} / {ht.mean():.4f} m, sd {hw.std():.4f} / {ht.std():.4f}")
    if a.wheel:
        say()
        x0s = a.wheel_x0 or [0.5 * L]
        say(f"wheel {a.wheel} (tests/cosim/in.motion_compare, prescribed motion: sinking at "
            f"0.2 m/s while rolling, {a.wheel_steps} steps), means over the second half, at "
            f"x0 = {', '.join(f'{x:g}' for x in x0s)} m:")
        runs = {mm: [wheel_run(a, work / mm, x0, a.wheel_steps) for x0 in x0s]
                for mm in ("whole", "tiled")}
        for k in ("Fx", "Fz", "My", "contacts"):
            vals = {mm: np.array([r[k] for r in runs[mm]]) for mm in runs}
            per = "  ".join(f"{w:8.4g}/{t:<8.4g}" for w, t in zip(vals["whole"], vals["tiled"]))
            mw, mt = vals["whole"].mean(), vals["tiled"].mean()
            sw = vals["whole"].std(ddof=1) if len(x0s) > 1 else float("nan")
            st = vals["tiled"].std(ddof=1) if len(x0s) > 1 else float("nan")
            say(f"  {k:9s} whole/tiled per x0: {per}   mean whole {mw:.4g} (sd {sw:.3g}), "
                f"tiled {mt:.4g} (sd {st:.3g}): {100 * (mt / mw - 1):+.1f} %")
    (work / "result.txt").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
