#!/usr/bin/python3
"""Driver of the tests/active_domain integration tests of fix wheel/active (CMakeLists.txt,
docs/fix-wheel-active.md "Checks").

  run_active.py rest    --launch L --inputs DIR --work DIR --bed BED --mesh STL [--steps N]
  run_active.py history --launch L ... [--frozen-steps N]
  run_active.py roll    --launch L ... [--steps N] [--distance D] [--tol X]
  run_active.py restart --launch L ... [--n N] [--m M] [--tol X]

Each mode runs liggghts-wheel (launcher L: ';'-separated, e.g. "mpiexec;-n;2;liggghts-wheel") on
tests/active_domain/in.active_domain, prints what it measured and exits 0 on pass, 1 on failure.
"""
import argparse
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from wheelsim_post import liggghts_log  # noqa: E402  (the shared thermo-table parser)

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "in.active_domain")


def run(a, name, variables):
    work = os.path.join(a.work, name)
    os.makedirs(work, exist_ok=True)
    for f in ("final.dump", "initial.dump", "frozen.dump"):   # none left from an earlier run
        if os.path.exists(os.path.join(work, f)):
            os.remove(os.path.join(work, f))
    cmd = a.launch.split(";") + ["-in", DECK, "-log", "none", "-echo", "none",
                                 "-var", "inputs_dir", a.inputs, "-var", "mesh", a.mesh]
    variables = dict({"restart_file": a.bed}, **variables)
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    with open(os.path.join(work, "out.txt"), "w") as fh:
        r = subprocess.run(cmd, cwd=work, stdout=fh, stderr=subprocess.STDOUT)
    text = open(os.path.join(work, "out.txt"), errors="replace").read()
    if r.returncode != 0 or "ERROR" in text or "active_domain: done" not in text:
        sys.stdout.write(text[-3000:])
        raise SystemExit(f"run_active: {name}: liggghts-wheel failed (exit {r.returncode})")
    return work, text


def snapshots(path):
    """Per-atom rows (id x y z vx vy vz fx fy fz) of each snapshot of a LIGGGHTS dump, by id."""
    out, lines, i = [], open(path).read().split("\n"), 0
    while i < len(lines):
        if lines[i].startswith("ITEM: NUMBER OF ATOMS"):
            n = int(lines[i + 1])
            while not lines[i].startswith("ITEM: ATOMS"):
                i += 1
            rows = np.array([[float(t) for t in l.split()] for l in lines[i + 1:i + 1 + n]])
            out.append(rows[np.argsort(rows[:, 0])])
            i += n
        i += 1
    return out


def col(table, name):
    """One column of a liggghts_log.Thermo as an array."""
    return np.array(table.values(name))


def verdict(ok, what):
    print(("PASS: " if ok else "FAIL: ") + what)
    return ok


def mode_rest(a):
    """(a) A settled bed with the wheel parked above one end (no contact): the frozen particles do
    not move at all, the active ones move as in the same run without the active domain (the bed
    still creeps by micrometres, and a few loose grains settle by up to a millimetre), and
    freezing never makes the bed move more."""
    common = dict(x0=0.03, gap=0.01, steps1=a.steps, thermo_every=a.steps)
    w_on, _ = run(a, "on", dict(common, active_args="distance 0.03"))
    w_off, _ = run(a, "off", dict(common, active=0))
    x0 = snapshots(os.path.join(w_on, "initial.dump"))[0]
    on = snapshots(os.path.join(w_on, "final.dump"))[0]
    off = snapshots(os.path.join(w_off, "final.dump"))[0]
    frozen = np.isin(on[:, 0], snapshots(os.path.join(w_on, "frozen.dump"))[0][:, 0])
    moved_frozen = np.abs(on[frozen, 1:4] - x0[frozen, 1:4]).max()
    deviation = np.linalg.norm(on[~frozen, 1:4] - off[~frozen, 1:4], axis=1).max()
    d_on = np.linalg.norm(on[:, 1:4] - x0[:, 1:4], axis=1)
    d_off = np.linalg.norm(off[:, 1:4] - x0[:, 1:4], axis=1)
    q = (50, 90, 99, 100)
    p_on, p_off = np.percentile(d_on, q), np.percentile(d_off, q)
    print(f"rest: {frozen.sum()} of {len(on)} particles frozen over {a.steps} steps; frozen "
          f"moved {moved_frozen:.3e} m; active particles deviate from the run without the "
          f"active domain by at most {deviation:.3e} m")
    print("rest: displacement percentiles " + ", ".join(
        f"{k}%: {x:.3e} (without {y:.3e})" for k, x, y in zip(q, p_on, p_off)) + " m")
    ok = verdict(0 < frozen.sum() < len(on), "some particles frozen, some active")
    ok &= verdict(moved_frozen == 0.0, "frozen particles bit for bit where they were")
    ok &= verdict(deviation <= a.tol_m, f"active particles within {a.tol_m:g} m of the run "
                  "without the active domain")
    ok &= verdict(bool(np.all(p_on <= p_off + a.tol_m)), "displacement percentiles not above "
                  f"those without the active domain (+{a.tol_m:g} m)")
    return ok


def mode_history(a):
    """(b) Contact history survives freezing: the bed frozen whole (wheel parked far above) for
    N steps, then the wheel comes near and every particle is active again. The forces of the
    first step after reactivation must equal those of a run in which the frozen pairs were
    still computed (frozen_pairs compute: LIGGGHTS kept their history itself), and differ from
    a run that drops the histories (so the check can fail)."""
    common = dict(sort=0, park_dz=5, jump_dz=-5, steps1=a.frozen_steps, steps2=1,
                  thermo_every=a.frozen_steps)
    runs = {}
    for name, extra in (("keep", ""), ("reference", " frozen_pairs compute"),
                        ("drop", " history drop")):
        w, text = run(a, name, dict(common, active_args="distance 0.3" + extra))
        runs[name] = (snapshots(os.path.join(w, "final.dump"))[1], text)
    ref = runs["reference"][0]
    scale = np.abs(ref[:, 7:10]).max()
    dk = np.abs(runs["keep"][0][:, 7:10] - ref[:, 7:10]).max()
    dd = np.abs(runs["drop"][0][:, 7:10] - ref[:, 7:10]).max()
    dx = np.abs(runs["keep"][0][:, 1:4] - ref[:, 1:4]).max()
    kept = [l for l in runs["keep"][1].split("\n") if "frozen contacts kept" in l]
    print(f"history: after {a.frozen_steps} frozen steps, largest force {scale:.4e} N; "
          f"difference to the reference: kept {dk:.3e} N, dropped {dd:.3e} N; positions "
          f"{dx:.3e} m")
    print("  " + (kept[0] if kept else "(no report of kept contacts)"))
    ok = verdict(dk <= 1e-12 * scale, "kept: forces equal to the reference (1e-12 relative)")
    ok &= verdict(dd >= 1e-2 * scale, "dropped: forces differ by >= 1e-2 relative (the check "
                  "can fail)")
    ok &= verdict(dx == 0.0, "positions unchanged while frozen")
    return ok


def mode_roll(a):
    """(c) The lugged wheel sinking and rolling (slip 0.25) with and without the active domain:
    the time averages of the wheel force and torque over the contact window agree."""
    common = dict(vx=0.1125, vz=-0.2, wy=1.5, steps1=a.steps, thermo_every=1)
    _, t_off = run(a, "off", dict(common, active=0))
    _, t_on = run(a, "on", dict(common, active_args=f"distance {a.distance}"))
    off = liggghts_log.merged(t_off, "fx")
    on = liggghts_log.merged(t_on, "fx")
    contact = np.nonzero(col(off, "nc") > 0)[0]
    if len(contact) == 0:
        return verdict(False, "the wheel touched the bed")
    window = slice(contact[0] + a.window_from, None)
    f_off = np.array([col(off, k)[window].mean() for k in ("fx", "fz")])
    f_on = np.array([col(on, k)[window].mean() for k in ("fx", "fz")])
    t_off_m, t_on_m = col(off, "ty")[window].mean(), col(on, "ty")[window].mean()
    load = np.linalg.norm(f_off)
    df = np.linalg.norm(f_on - f_off) / load
    dt = abs(t_on_m - t_off_m) / (load * a.radius)
    frozen_mean = col(on, "n_frozen")[window].mean()
    total = col(on, "n_active")[0] + col(on, "n_frozen")[0]
    print(f"roll: window of {len(col(off, 'fx')[window])} steps from {a.window_from} steps "
          f"after first contact; mean force (fx, fz) without {f_off} N, with {f_on} N: "
          f"|dF|/|F| = {df:.3e}; torque ty {t_off_m:.5g} vs {t_on_m:.5g} N m: "
          f"|dT|/(|F| R) = {dt:.3e}; {frozen_mean:.0f} of {total:.0f} particles frozen on "
          f"average")
    ok = verdict(frozen_mean >= 0.05 * total, ">= 5 % of the particles frozen")
    ok &= verdict(df <= a.tol, f"force within {a.tol:g} of |F|")
    ok &= verdict(dt <= a.tol, f"torque within {a.tol:g} of |F| R")
    return ok


def mode_restart(a):
    """(d) N + M steps in one go against N steps, write_restart, read_restart, M steps, with
    frozen particles and kept contacts at the restart (elastic contacts: see
    tests/wheel_cosim/props_elastic.in; lists rebuilt every step in both, so that the pair order
    and hence the round-off are the same)."""
    common = dict(vx=0.1125, vz=-0.2, wy=1.5, thermo_every=1, elastic=1, sort=0,
                  neigh_every_step=1, active_args="distance 0.03")
    _, t_whole = run(a, "whole", dict(common, steps1=a.n + a.m))
    w1, _ = run(a, "first", dict(common, steps1=a.n, restart_out=1))
    w2, t_second = run(a, "second", dict(common, steps1=a.m, restart_in=1,
                                         restart_file=os.path.join(w1, "restart.out")))
    # the same continuation dropping the kept histories: must differ (the check can fail)
    _, t_drop = run(a, "second_drop", dict(common, steps1=a.m, restart_in=1,
                                           active_args="distance 0.03 history drop",
                                           restart_file=os.path.join(w1, "restart.out")))
    whole = liggghts_log.merged(t_whole, "fx")
    second = liggghts_log.merged(t_second, "fx")
    steps = col(second, "Step")
    sel = np.isin(col(whole, "Step"), steps)
    ok = verdict(sel.sum() == len(steps) and len(steps) == a.m + 1, "same steps in both runs")
    if not ok:
        return ok
    load = max(np.abs(col(whole, "fz")[sel]).max(), 1.0)
    worst = 0.0
    for k in ("fx", "fz", "ty", "n_active", "n_frozen"):
        d = np.abs(col(whole, k)[sel] - col(second, k)).max()
        scale = load if k in ("fx", "fz") else (load * a.radius if k == "ty" else 1.0)
        worst = max(worst, d / scale)
        print(f"restart: {k}: largest difference {d:.3e} (relative to {scale:.3g}: {d / scale:.3e})")
    drop = liggghts_log.merged(t_drop, "fx")
    d_drop = np.abs(col(whole, "fz")[sel] - col(drop, "fz")).max() / load
    print(f"restart: continued with the kept histories dropped: fz differs by {d_drop:.3e}")
    ok &= verdict(d_drop > 100 * a.tol, "dropping the kept histories changes the continuation "
                  "(the check can fail)")
    updates = [l for l in t_second.split("\n") if "active-set updates" in l]
    print("  " + (updates[-1] if updates else "(no report)"))
    frozen = col(second, "n_frozen")[0]
    kept = col(second, "n_kept")[0]
    print(f"restart: at the restart {frozen:.0f} frozen particles, {kept:.0f} kept contacts")
    ok &= verdict(frozen > 0 and kept > 0, "frozen particles and kept contacts at the restart")
    ok &= verdict(worst <= a.tol, f"continued run equals the uninterrupted one ({a.tol:g})")
    return ok


def main():
    p = argparse.ArgumentParser()
    p.add_argument("mode", choices=["rest", "history", "roll", "restart"])
    p.add_argument("--launch", required=True, help="launcher and executable, ';'-separated")
    p.add_argument("--inputs", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--bed", required=True)
    p.add_argument("--mesh", required=True)
    p.add_argument("--steps", type=int, default=500)
    p.add_argument("--frozen-steps", type=int, default=300)
    p.add_argument("--distance", type=float, default=0.04, help="roll: distance [m]")
    p.add_argument("--window-from", type=int, default=300,
                   help="roll: window start, steps after first contact")
    p.add_argument("--radius", type=float, default=0.1, help="wheel radius [m] (torque scale)")
    p.add_argument("--n", type=int, default=500)
    p.add_argument("--m", type=int, default=300)
    p.add_argument("--tol", type=float, default=0.02)
    p.add_argument("--tol-m", type=float, default=2e-5,
                   help="rest: largest deviation of an active particle [m]")
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    ok = {"rest": mode_rest, "history": mode_history, "roll": mode_roll,
          "restart": mode_restart}[a.mode](a)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
