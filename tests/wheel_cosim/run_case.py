#!/usr/bin/python3
"""Driver of the tests/wheel_cosim integration tests (see CMakeLists.txt, docs/validation-fix.md).

  run_case.py bed     --launch "mpiexec;-n;1;liggghts-wheel" --inputs DIR --work DIR
  run_case.py compare --launch ... --inputs DIR --work DIR --bed BED --mesh STL --model hertz|eepa|sjkr|adhesive
                      --steps N [--early-window S --early-tol X --floor N] [--window-from K --window-tol X]
  run_case.py restart --launch ... --bed BED --mesh STL --n N --m M --tol X
  run_case.py vtk     --launch ... --bed BED --mesh STL
  run_case.py candidates --launch ... --bed BED --mesh STL --steps N --tol X [--need-arrivals]
  run_case.py ranks   --launch "mpiexec;-n;4;liggghts-wheel" --launch-ref "mpiexec;-n;1;..."
                      --bed BED --mesh STL --steps N --early-window S --tol X

Runs liggghts-wheel on tests/wheel_cosim/in.wheel_roll, then compare_wrench.py. Exit 0 = pass.
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
DECK = os.path.join(HERE, "in.wheel_roll")
COMPARE = os.path.join(HERE, "compare_wrench.py")

# The wheel-particle contact model in both spellings, and the extra material include.
MODELS = {
    "hertz": ("model hertz rolling_friction off", "model hertz tangential history", "props_none.in", 1.0),
    "sjkr": ("model hertz cohesion sjkr rolling_friction off",
             "model hertz tangential history cohesion sjkr", "props_sjkr.in", 1.0),
    # wheelsim's tangential history_adhesive on both sides (the mesh wall: liggghts-wheel's
    # LIGGGHTS-side model), with the sjkr case's soil-wheel adhesion
    "adhesive": ("model hertz tangential history_adhesive cohesion sjkr rolling_friction off",
                 "model hertz tangential history_adhesive cohesion sjkr", "props_sjkr.in", 1.0),
    # EEPA with n = 1 needs half the soil time step (props_eepa.in)
    "eepa": ("model eepa rolling_friction off", "model edinburgh tangential history",
             "props_eepa.in", 0.5),
}


def run(launch, work, out, variables):
    cmd = list(launch) + ["-in", DECK, "-log", "none", "-echo", "none"]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    with open(os.path.join(work, out), "w") as fh:
        r = subprocess.run(cmd, cwd=work, stdout=fh, stderr=subprocess.STDOUT)
    text = open(os.path.join(work, out), errors="replace").read()
    if r.returncode != 0 or "ERROR" in text:
        sys.stdout.write(text[-3000:])
        raise SystemExit(f"run_case: {out}: liggghts-wheel failed (exit {r.returncode})")
    return text


def compare(args, rest):
    r = subprocess.run(["/usr/bin/python3", COMPARE] + rest)
    return r.returncode


def main():
    p = argparse.ArgumentParser()
    p.add_argument("mode", choices=["bed", "compare", "restart", "vtk", "candidates", "ranks"])
    p.add_argument("--launch", required=True, help="launcher and executable, ';'-separated")
    p.add_argument("--launch-ref", help="ranks: the reference launcher (np 1), ';'-separated")
    p.add_argument("--inputs", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--bed")
    p.add_argument("--mesh")
    p.add_argument("--model", default="hertz")
    p.add_argument("--steps", type=int, default=4000)
    p.add_argument("--vz", default="-0.05")
    p.add_argument("--early-window", type=int, default=0)
    p.add_argument("--early-tol", type=float, default=0.01)
    p.add_argument("--floor", type=float, default=1.0)
    p.add_argument("--window-from", type=int, default=-1)
    p.add_argument("--window-tol", type=float, default=0.03)
    p.add_argument("--n", type=int, default=500)
    p.add_argument("--m", type=int, default=300)
    p.add_argument("--tol", type=float, default=1e-6)
    p.add_argument("--need-arrivals", action="store_true",
                   help="candidates: fail unless particles moved between ranks during the run")
    a = p.parse_args()
    launch = a.launch.split(";")
    os.makedirs(a.work, exist_ok=True)
    common = {"inputs_dir": a.inputs, "restart_file": a.bed, "mesh": a.mesh}

    if a.mode == "bed":
        # A bin just longer than the contact patch's path; ~3800 particles of the ci soil.
        for f in ("soilbin_ci.restart", "soilbin_ci.restart.vars"):   # this run's, not a stale one
            if os.path.exists(os.path.join(a.work, f)):
                os.remove(os.path.join(a.work, f))
        cmd = launch + ["-in", os.path.join(a.inputs, "in.soilbin"), "-log", "none",
                        "-var", "inputs_dir", a.inputs, "-var", "soil", "ci",
                        "-var", "bin_length", "0.2", "-var", "bin_width", "0.1",
                        "-var", "fill_height", "0.025", "-var", "max_settle_time", "1.0",
                        "-var", "out_dir", a.work]
        r = subprocess.run(cmd, cwd=a.work, capture_output=True, text=True)
        sys.stdout.write("\n".join(l for l in r.stdout.splitlines() if l.startswith("soilbin:")))
        ok = r.returncode == 0 and os.path.exists(os.path.join(a.work, "soilbin_ci.restart.vars"))
        if not ok:
            sys.stdout.write(r.stdout[-3000:] + r.stderr[-2000:])
        return 0 if ok else 1

    if a.mode == "compare":
        cosim_model, mesh_model, props, dt_factor = MODELS[a.model]
        v = dict(common, steps=a.steps, vz=a.vz, cosim_model=cosim_model, mesh_model=mesh_model,
                 props=os.path.join(HERE, props), dt_factor=dt_factor,
                 neigh_every_step=1 if a.early_window else 0,
                 thermo_every=1 if a.early_window else 10)
        for impl in ("cosim", "mesh"):
            run(launch, a.work, f"out.{impl}", dict(v, impl=impl))
        rc = 0
        ours, ref = os.path.join(a.work, "out.cosim"), os.path.join(a.work, "out.mesh")
        if a.early_window:
            rc |= compare(a, ["early", ours, ref, "--window", str(a.early_window), "--tol",
                              str(a.early_tol), "--force-floor", str(a.floor), "--lever", "0.1",
                              "--label", a.model])
        if a.window_from >= 0:
            rc |= compare(a, ["window", ours, ref, "--from-offset", str(a.window_from), "--tol",
                              str(a.window_tol), "--lever", "0.1", "--label", a.model])
        return rc

    if a.mode == "restart":
        # Elastic contacts, no rolling friction: see props_elastic.in for why a continued granular
        # run can match only without velocity-dependent forces.
        v = dict(common, vz="-0.2", neigh_every_step=1, thermo_every=1,
                 props=os.path.join(HERE, "props_elastic.in"))
        run(launch, a.work, "out.full", dict(v, impl="cosim", steps=a.n + a.m))
        run(launch, a.work, "out.first", dict(v, impl="cosim", steps=a.n, restart_out=1))
        v2 = dict(v, impl="cosim", steps=a.m, restart_in=1,
                  restart_file=os.path.join(a.work, "restart.out"))
        text = run(launch, a.work, "out.second", v2)
        if "pose restored from the restart file" not in text:
            print("run_case: the continued run did not restore the wheel pose FAIL")
            return 1
        return compare(a, ["equal", os.path.join(a.work, "out.second"),
                           os.path.join(a.work, "out.full"), "--from-offset", "1",
                           "--tol", str(a.tol), "--force-floor", "1e-3", "--lever", "0.1",
                           "--label", "restart"])

    if a.mode == "candidates":
        return check_candidates(a, launch, common)

    if a.mode == "ranks":
        return check_ranks(a, launch, a.launch_ref.split(";"), common)

    if a.mode == "vtk":
        steps, every = 400, 100
        vx, vz, wy = 0.1125, -0.2, 1.5
        for f in os.listdir(a.work):   # no VTK file of an earlier run may pass for this one's
            if (f.startswith("wheel_") and f.endswith(".vtk")) or f == "wheel.pvd":
                os.remove(os.path.join(a.work, f))
        text = run(launch, a.work, "out.vtk",
                   dict(common, impl="cosim", steps=steps, vz=vz, vx=vx, wy=wy,
                        neigh_every_step=0, thermo_every=100,
                        cosim_extra=f"vtk {every} {os.path.join(a.work, 'wheel')}"))
        return check_vtk(a, text, steps, every, vx, vz, wy)
    return 2


def check_candidates(a, launch, common):
    """fix wheel/cosim with its candidate list (candidates yes) against the scan of every particle
    (candidates no), same deck: the wrench must agree to a relative 1e-12 (the same particles are
    tested in the same order, so it is expected bit for bit), the contact counts exactly. The run
    must exercise what could break the list: rebuilds at LIGGGHTS' neighbour-list builds, rebuilds
    after the wheel alone moved a skin, and (np 2) particles moving between ranks."""
    import re
    # sinks fast (0.2 m/s) and rolls: contact from about step 250, and the wheel centre moves
    # one skin (2 mm for the ci soil) about every 180 steps; neighbour lists by distance check
    v = dict(common, impl="cosim", steps=a.steps, vz="-0.2", vx="0.1125", wy="1.5",
             neigh_every_step=0, thermo_every=1)
    outs = {}
    for mode in ("no", "yes"):
        outs[mode] = run(launch, a.work, f"out.candidates_{mode}",
                         dict(v, cosim_extra=f"candidates {mode}"))
    stats = re.search(r"candidate list: (\S+) of (\S+) particles tested per step \(all ranks\); "
                      r"list builds: (\d+) with LIGGGHTS' neighbour lists, (\d+) in between "
                      r"\(wheel surface moved > (\S+) m\); (\S+) particles arrived", outs["yes"])
    if not stats:
        print("run_case: candidates: no candidate-list summary in the output of 'candidates yes' "
              "FAIL")
        return 1
    listed, natoms, at_neigh, between, travel, arrived = stats.groups()
    print(f"run_case: candidates: {listed} of {natoms} particles tested per step; list builds: "
          f"{at_neigh} with LIGGGHTS' neighbour lists, {between} in between (wheel surface moved > "
          f"{travel} m); {arrived} particles arrived from other ranks")
    ok = int(at_neigh) > 1 and int(between) > 0 and float(listed) < float(natoms)
    if a.need_arrivals and float(arrived) == 0:
        ok = False
        print("run_case: candidates: no particle changed rank: migration not exercised FAIL")
    if not ok:
        print("run_case: candidates: the run did not exercise the list's rebuilds FAIL")
    # the contact counts (thermo column nc), step by step
    counts = {}
    for mode, text in outs.items():
        rows, header = {}, None
        for line in text.splitlines():
            tok = line.split()
            if tok[:1] == ["Step"]:
                header = tok if "nc" in tok else None
            elif header and len(tok) == len(header) and tok[0].isdigit():
                rows[int(tok[0])] = float(tok[header.index("nc")])
        counts[mode] = rows
    steps = sorted(set(counts["no"]) & set(counts["yes"]))
    differ = [s for s in steps if counts["no"][s] != counts["yes"][s]]
    touching = sum(1 for s in steps if counts["no"][s] > 0)
    print(f"run_case: candidates: contact counts over {len(steps)} steps ({touching} with "
          f"contacts, up to {max(counts['no'].values()):.0f}): {len(differ)} steps differ "
          f"{'ok' if not differ and touching > 100 else 'FAIL'}")
    ok &= not differ and touching > 100
    rc = compare(a, ["equal", os.path.join(a.work, "out.candidates_yes"),
                     os.path.join(a.work, "out.candidates_no"), "--from", "0", "--tol",
                     str(a.tol), "--force-floor", "1e-9", "--lever", "0.1",
                     "--label", "candidates yes vs no"])
    return rc if ok else 1


def thermo_column(text, name):
    """{step: value} of one thermo column of a run's screen output (every table that has it)."""
    return {k: v for t in liggghts_log.thermo(text) if name in t.columns
            for k, v in t.column(name).items()}


def check_ranks(a, launch, launch_ref, common):
    """The same prescribed-motion run (lugged wheel sinking while rolling at slip 0.25, hertz,
    neighbour lists by distance check, as in production) on the ranks of --launch (np 4) and of
    --launch-ref (np 1): the wheel wrench over the first --early-window steps after first contact
    must agree to --tol (relative, floors 1 N / 0.1 N m) and the contact counts exactly. The
    wheel is centred on y = 0, so a processor grid split in y (np 4: 2 x 2 x 1) puts its contact
    patch on several ranks; the run must say so, and particles must move between ranks."""
    import re
    # contact from about step 100 (gap 1 mm closed at 0.3 m/s with dt 4.9e-5 s); sinkage ~4.4 mm
    # after 300 steps of contact
    v = dict(common, impl="cosim", steps=a.steps, vz=a.vz, vx="0.1125", wy="1.5", gap="0.001",
             neigh_every_step=0, thermo_every=1)
    out = {"ref": run(launch_ref, a.work, "out.np_ref", v),
           "par": run(launch, a.work, "out.np_par", v)}
    ok = True
    grid = re.search(r"(\d+) by (\d+) by (\d+) MPI processor grid", out["par"])
    if not grid or int(grid.group(2)) < 2:
        print(f"run_case: ranks: processor grid {grid.group(0) if grid else 'not printed'}: the "
              "wheel (centred on y = 0) is not split between ranks FAIL")
        ok = False
    else:
        print(f"run_case: ranks: {grid.group(0)} (the wheel's contact patch spans the y split)")
    stats = re.search(r"(\S+) particles arrived", out["par"])
    if not stats or float(stats.group(1)) == 0:
        print("run_case: ranks: no particle changed rank during the run FAIL")
        ok = False
    else:
        print(f"run_case: ranks: {stats.group(1)} particles arrived from other ranks")
    counts = {k: thermo_column(t, "nc") for k, t in out.items()}
    steps = sorted(set(counts["ref"]) & set(counts["par"]))
    touching = [s for s in steps if counts["ref"][s] > 0]
    differ = [s for s in steps if counts["ref"][s] != counts["par"][s]]
    enough = len(touching) > a.early_window
    print(f"run_case: ranks: contact counts over {len(steps)} steps ({len(touching)} with "
          f"contacts, up to {max(counts['ref'].values()):.0f}): {len(differ)} steps differ "
          f"{'ok' if not differ and enough else 'FAIL'}")
    ok &= not differ and enough
    rc = compare(a, ["early", os.path.join(a.work, "out.np_par"),
                     os.path.join(a.work, "out.np_ref"), "--window", str(a.early_window),
                     "--tol", str(a.tol), "--force-floor", "1.0", "--lever", "0.1", "--label", "np ranks vs np 1"])
    return rc if ok else 1


def read_vtk(path):
    """Points and the cell-data arrays of a legacy ASCII VTK polydata file."""
    tok = open(path).read().split()
    i = tok.index("POINTS")
    n = int(tok[i + 1])
    pts = np.array(tok[i + 3:i + 3 + 3 * n], dtype=float).reshape(n, 3)
    fields = {}
    j = 0
    while True:
        try:
            j = tok.index("SCALARS", j + 1)
        except ValueError:
            break
        name = tok[j + 1]
        k = j + 3
        if tok[k] != "LOOKUP_TABLE":
            k += 1
        k += 2
        vals = []
        while k < len(tok):
            try:
                vals.append(float(tok[k]))
            except ValueError:
                break
            k += 1
        fields[name] = np.array(vals)
    return pts, fields


def check_pvd(work, files, dt):
    """wheel.pvd (written by the fix beside its VTK files) lists every one of them once, in step
    order, with LIGGGHTS' simulation time: t(step) - t(step0) = (step - step0) dt to 1e-12
    relative (step0: the first file's), and t(step0) as in that file's title (9 digits); no
    temporary file is left."""
    import xml.etree.ElementTree as ET
    pvd = os.path.join(work, "wheel.pvd")
    if not os.path.exists(pvd):
        print("run_case: no wheel.pvd beside the VTK files FAIL")
        return False
    root = ET.parse(pvd).getroot()
    sets = root.findall("./Collection/DataSet")
    listed = [d.get("file") for d in sets]
    times = [float(d.get("timestep")) for d in sets]
    steps = [int(f[len("wheel_"):-4]) for f in listed]
    ok = root.get("type") == "Collection" and sorted(listed) == sorted(files)
    ok &= steps == sorted(steps) and len(set(steps)) == len(steps)
    step0, t0 = steps[0], times[0]
    worst = 0.0
    for step, t in zip(steps, times):
        if step != step0:
            want = (step - step0) * dt
            worst = max(worst, abs((t - t0) - want) / abs(want))
    title = open(os.path.join(work, f"wheel_{step0}.vtk")).read().splitlines()[1]
    t0_title = float(title.split("time ")[1].split()[0])
    ok &= worst < 1e-12 and abs(t0 - t0_title) <= 1e-8 * max(abs(t0), 1e-30)
    leftovers = [f for f in os.listdir(work) if f.endswith(".tmp")]
    ok &= not leftovers
    print(f"run_case: wheel.pvd: {len(listed)} data sets for {len(files)} VTK files, steps "
          f"{steps}, times {times} s, max relative error of t - t0 against (step - step0) dt "
          f"{worst:.3g} (tol 1e-12), t0 {t0!r} vs title {t0_title!r}, temporary files "
          f"{leftovers} {'ok' if ok else 'FAIL'}")
    return ok


def check_vtk(a, text, steps, every, vx, vz, wy):
    import re
    m = re.search(r"centre start (\S+) 0 (\S+) m, dt (\S+) s", text)
    x0, z0, dt = float(m.group(1)), float(m.group(2)), float(m.group(3))
    m = re.search(r"Step\s+Atoms.*?\n\s*(\d+)\s", text)
    step0 = int(m.group(1))
    ref = np.array([[float(t) for t in l.split()[1:]] for l in open(a.mesh)
                    if l.split()[:1] == ["vertex"]])
    ok = True
    files = sorted(f for f in os.listdir(a.work) if f.startswith("wheel_") and f.endswith(".vtk"))
    print(f"run_case: vtk files {files}")
    if len(files) < 2:
        print("run_case: expected VTK files every 100 steps FAIL")
        return 1
    any_pressure = False
    for f in files:
        step = int(f[len("wheel_"):-4])
        t = (step - step0) * dt
        c = np.array([x0 + vx * t, 0.0, z0 + vz * t])
        th = wy * t
        Ry = np.array([[np.cos(th), 0, np.sin(th)], [0, 1, 0], [-np.sin(th), 0, np.cos(th)]])
        pts, fields = read_vtk(os.path.join(a.work, f))
        expected = (Ry @ ref.T).T + c
        # every written point must be a mesh vertex moved by the prescribed pose (nearest match)
        d = np.array([np.min(np.linalg.norm(expected - q, axis=1)) for q in pts])
        # and the vertex with the largest wheel-frame x, moved: a known point
        pressure = next((v for k, v in fields.items() if "pressure" in k.lower()), None)
        if pressure is None:
            print(f"run_case: {f}: no pressure array (fields {list(fields)}) FAIL")
            return 1
        neg = int((pressure < 0).sum())
        pos = int((pressure > 0).sum())
        any_pressure |= pos > 0
        good = d.max() < 1e-6 and neg == 0
        ok &= good
        print(f"run_case: {f}: t = {t:.6g} s, {len(pts)} points, max distance to the posed mesh "
              f"{d.max():.3g} m (tol 1e-6: STL vertices are single precision), pressure "
              f"min {pressure.min():.4g} max {pressure.max():.4g} Pa, {pos} cells > 0, {neg} < 0 "
              f"{'ok' if good else 'FAIL'}")
    if not any_pressure:
        print("run_case: no cell with a pressure > 0 although the wheel touches the bed FAIL")
    ok &= any_pressure
    ok &= check_pvd(a.work, files, dt)
    print(f"run_case: vtk {'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
