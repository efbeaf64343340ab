#!/usr/bin/python3
"""Tests of scripts/wheel-sweep on the flat test ground (fast, real wheel-rig runs).

  test_sweep.py CASE --sweep scripts/wheel-sweep --build-dir BUILD --work DIR

CASE: matrix, resume_marker, resume_sigterm, bad_config, examples_dry_run, scm_smoke, kill_flat,
kill_dem, dem_soil_file, dem_tiled_bed, dem_resume, wheel_speed_flat, ... (see each function and tests/sweep/CMakeLists.txt).
Exit 0 pass, 1 fail, 77 skip (wheel-rig or the wheel meshes not built).
"""

import argparse
import csv
import hashlib
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np

SKIP = 77
SLIPS = [0.1, 0.25, 0.5]
FRICTION = 0.5
# the one soil: on the flat ground with regularized friction DP = mu W once v_j >> v_c
SOIL = (f'{{ name = "mu05", friction = {FRICTION}, friction_model = "regularized", '
        'slip_velocity_scale = 1.0e-3 }')
# s simulated: a point takes ~1.5 s of wall time on 2 idle cores (100 s took 0.5 s on 2026-12-03,
# after mesh loading got 4x faster, and the second point finished before the SIGTERM came)
DURATION_SIGTERM = 300.0
DURATION_KILL = 1.0e5  # s simulated: ~10 min of wall time, far longer than a kill test


class Fail(Exception):
    pass


def check(cond, msg):
    if not cond:
        raise Fail(msg)


def base_rig(path, duration, every=10):
    """A flat-ground rig without effective_radius (R_eff = the mesh's outer radius)."""
    path.write_text(f"""# test base rig (flat ground)
[wheel]
mass = 205.0
inertia = 72.0
[rig]
vertical_load = 13200.0
[motor]
omega = 1.05
ramp_time = 0.1
[carriage]
mode = "imposed_slip"
[run]
dt = 1.0e-4
duration = {duration}
[terrain]
type = "flat"
damping = 1.1e5
[output]
every = {every}
flush_interval = 100
""")


def sweep_config(path, build, duration=0.2, every=10, slips=SLIPS, extra="", wheels=None):
    """2 wheels (a catalogue name and a mesh path with a label) x 1 soil x len(slips) slips."""
    base_rig(path.parent / "base.toml", duration, every)
    wheels = wheels or f'["wheel1", {{ name = "small", mesh = "{build}/meshes/test_small.stl" }}]'
    path.write_text(f"""description = "test sweep"
terrain = "flat"
base = "base.toml"
wheels = {wheels}
soils = [{SOIL}]
slips = {json.dumps(slips)}
{extra}""")


def run_sweep(a, cfg, *args, timeout=60):
    r = subprocess.run([a.sweep, str(cfg), "--build-dir", a.build_dir, *args],
                       capture_output=True, text=True, timeout=timeout)
    print(f"$ wheel-sweep {cfg.name} {' '.join(args)}  -> exit {r.returncode}")
    print(r.stdout + r.stderr)
    return r


def manifest(out):
    with open(out / "manifest.csv", newline="") as f:
        return list(csv.DictReader(f))


def check_complete(out, wheels, slips, soil="mu05"):
    rows = manifest(out)
    check(len(rows) == len(wheels) * len(slips), f"manifest has {len(rows)} rows")
    expect = [(w, soil, s) for w in wheels for s in slips]
    got = [(r["wheel"], r["soil"], float(r["slip"])) for r in rows]
    check(got == expect, f"manifest points {got} != {expect}")
    for r in rows:
        check(r["terrain"] == "flat" and r["status"] == "done" and r["exit_status"] == "0",
              f"manifest row {r}")
        rf = out / r["run_file"]
        check(rf.is_file(), f"run file {rf} missing")
        d = rf.parent
        check(not (d / "run.part.h5").exists(), f"{d}/run.part.h5 left behind")
        done = json.loads((d / "done.json").read_text())
        check(done["exit_status"] == 0 and done["wheel"] == r["wheel"] and done["soil"] == soil
              and done["slip"] == float(r["slip"]) and done["wall_time_s"] > 0, f"done.json {done}")
        with h5py.File(rf, "r") as f:
            p = f["parameters/sweep"]
            par = {k: p[k].asstr()[()] for k in ("wheel", "soil", "slip", "terrain")}
            check(par == {"wheel": r["wheel"], "soil": soil, "slip": r["slip"], "terrain": "flat"},
                  f"{rf}: /parameters/sweep = {par}")
            o = f["observables"]
            test = o["phase/value"][()] == 3
            check(test.sum() > 10, f"{rf}: {test.sum()} test-phase records")
            slip = o["slip/value"][()][test]
            check(np.allclose(slip, float(r["slip"]), atol=1e-9),
                  f"{rf}: slip {slip.mean()} != {r['slip']}")
            # the soil's terrain keys reach the rig: on the flat ground DP = mu W at s > 0
            half = test & (np.cumsum(test) > test.sum() // 2)  # last half of the test phase
            mu = (o["drawbar_pull/value"][()][half] / o["vertical_load/value"][()][half]).mean()
            check(abs(mu - FRICTION) < 0.02, f"{rf}: DP/W = {mu}, expected {FRICTION}")
            cfg = f["parameters/rig_config"].asstr()[()]
            check(f"/meshes/{'wheel1' if r['wheel'] == 'wheel1' else 'test_small'}.stl" in cfg,
                  f"{rf}: rig config lacks the wheel's mesh")
    return rows


def case_matrix(a, work):
    """2 x 1 x 3 matrix: all points run, manifest, done.json and the run files' parameters."""
    cfg = work / "sweep.toml"
    sweep_config(cfg, a.build_dir)
    out = work / "out"
    r = run_sweep(a, cfg, "--out-dir", str(out), "--jobs", "2")
    check(r.returncode == 0, "sweep failed")
    check_complete(out, ["wheel1", "small"], SLIPS)
    check(len(re.findall(r"^\[\d/6\] .* done in ", r.stdout, re.M)) == 6, "6 'done in' lines")
    check(re.search(r"ETA", r.stdout), "no ETA in the progress lines")
    check(f"manifest {out}/manifest.csv" in r.stdout, "summary does not name the manifest")
    check((out / "sweep.toml").is_file(), "config copy missing")


def case_points_filter(a, work):
    """--points runs only the matching points (and lists only them); a pattern that matches
    none exits 2 listing the points; a later run without it skips those and runs the rest."""
    cfg = work / "sweep.toml"
    sweep_config(cfg, a.build_dir)
    out = work / "out"
    r = run_sweep(a, cfg, "--out-dir", str(out), "--points", "wheel1/*/s0.250,small/*/s0.5*")
    check(r.returncode == 0, "sweep --points failed")
    rows = manifest(out)
    got = sorted((m["wheel"], float(m["slip"]), m["status"]) for m in rows)
    check(got == [("small", 0.5, "done"), ("wheel1", 0.25, "done")],
          f"--points ran {got}, expected wheel1 s0.25 and small s0.5")
    r = run_sweep(a, cfg, "--out-dir", str(out), "--points", "wheel2/*")
    check(r.returncode == 2, f"a pattern matching nothing: exit {r.returncode}, expected 2")
    check("--points 'wheel2/*' matches none of the sweep's points: wheel1/mu05/s0.100" in r.stderr,
          f"the error does not name the pattern and list the points: {r.stderr!r}")
    r = run_sweep(a, cfg, "--out-dir", str(out), "--jobs", "2")
    check(r.returncode == 0, "the whole sweep after --points failed")
    check("skipping 2 finished point(s)" in r.stdout, "the points run with --points were not skipped")
    check_complete(out, ["wheel1", "small"], SLIPS)


def case_resume_marker(a, work):
    """A lost done.json with a partial temp file, and a failed point, are re-run; the rest is
    skipped; a changed config re-runs everything; --force re-runs all."""
    cfg = work / "sweep.toml"
    sweep_config(cfg, a.build_dir)
    out = work / "out"
    check(run_sweep(a, cfg, "--out-dir", str(out)).returncode == 0, "first sweep failed")
    lost = out / "small/mu05/s0.250"
    (lost / "done.json").unlink()
    (lost / "run.h5").unlink()
    (lost / "run.part.h5").write_bytes(b"half a run file")
    failed = out / "wheel1/mu05/s0.500"
    done = json.loads((failed / "done.json").read_text())
    done.update(exit_status=1, status="failed")
    (failed / "done.json").write_text(json.dumps(done))
    keep = {p: p.stat().st_mtime_ns for p in out.glob("*/mu05/*/run.h5")
            if p.parent not in (lost, failed)}
    check(len(keep) == 4, f"{len(keep)} untouched points")
    r = run_sweep(a, cfg, "--out-dir", str(out))
    check(r.returncode == 0, "resumed sweep failed")
    check("skipping 4 finished point(s)" in r.stdout, "does not say it skips 4 points")
    check("running 2 point(s)" in r.stdout, "does not run exactly 2 points")
    check("small mu05 s=0.25 (unfinished)" in r.stdout
          and "wheel1 mu05 s=0.5 (failed before (exit 1))" in r.stdout,
          "does not say why it re-runs the two points")
    for p, t in keep.items():
        check(p.stat().st_mtime_ns == t, f"{p} was re-run")
    check_complete(out, ["wheel1", "small"], SLIPS)
    # dry run after completion: nothing to run
    r = run_sweep(a, cfg, "--out-dir", str(out), "--dry-run")
    check(r.returncode == 0 and "0 point(s) to run, 6 finished" in r.stdout, "dry run")
    # a changed input re-runs the points it changes
    text = (work / "base.toml").read_text().replace("duration = 0.2", "duration = 0.25")
    (work / "base.toml").write_text(text)
    r = run_sweep(a, cfg, "--out-dir", str(out))
    check(r.returncode == 0 and "running 6 point(s)" in r.stdout
          and "(inputs changed since it finished)" in r.stdout,
          "a changed base config did not re-run the points (saying why)")
    r = run_sweep(a, cfg, "--out-dir", str(out), "--force")
    check(r.returncode == 0 and "running 6 point(s)" in r.stdout, "--force did not re-run all")
    check_complete(out, ["wheel1", "small"], SLIPS)


def write_health(path, status, findings=()):
    """Replaces /health of a run file: `status` and rows (code, severity); None: no /health."""
    with h5py.File(path, "r+") as f:
        if "health" in f:
            del f["health"]
        if status is None:
            return
        g = f.create_group("health")
        g.attrs["status"] = status
        n = len(findings)
        g["step"] = np.arange(n, dtype=np.int64) * 10
        g["time"] = np.arange(n, dtype=np.float64) * 1e-3
        text = h5py.string_dtype()
        g.create_dataset("code", data=[c for c, _ in findings], dtype=text)
        g.create_dataset("severity", data=[v for _, v in findings], dtype=text)
        g.create_dataset("message", data=[f"{c}: what was seen" for c, _ in findings],
                         dtype=text)


def case_health_listing(a, work):
    """The end of a sweep lists the points whose run is not healthy, with their codes; an
    unhealthy or crashed ("running") run makes the exit status 1; no /health is "unchecked"."""
    cfg = work / "sweep.toml"
    slips = [0.1, 0.2, 0.3, 0.4, 0.5]
    sweep_config(cfg, a.build_dir, slips=slips, wheels='["wheel1"]')
    out = work / "out"
    check(run_sweep(a, cfg, "--out-dir", str(out)).returncode == 0, "first sweep failed")
    pts = [out / f"wheel1/mu05/s{s:.3f}/run.h5" for s in slips]
    write_health(pts[0], "unhealthy", [("nonfinite_state", "error"),
                                       ("slip_not_held", "error"), ("nonfinite_state", "error")])
    write_health(pts[1], "warnings", [("settle_timeout", "warning")])
    write_health(pts[2], None)
    write_health(pts[3], "running", [])
    write_health(pts[4], "healthy", [])
    r = run_sweep(a, cfg, "--out-dir", str(out))
    check(r.returncode == 1, f"exit {r.returncode}: an unhealthy run must count as failed")
    check("skipping 5 finished point(s)" in r.stdout, "the points were not skipped")
    check("4 point(s) whose run is not healthy" in r.stdout, "no listing of 4 points")
    for rx in (r"wheel1/mu05/s0\.100 +unhealthy +nonfinite_state;slip_not_held\n",
               r"wheel1/mu05/s0\.200 +warnings +settle_timeout\n",
               r"wheel1/mu05/s0\.300 +unchecked +-\n", r"wheel1/mu05/s0\.400 +running +-\n"):
        check(re.search(rx, r.stdout), f"listing lacks /{rx}/")
    check("s0.500" not in r.stdout.split("not healthy")[1], "a healthy point is listed")
    check("of which 2 not to be trusted" in r.stdout, "summary does not count 2 untrusted")
    rows = manifest(out)
    got = [(x["health"], x["health_codes"]) for x in rows]
    check(got == [("unhealthy", "nonfinite_state;slip_not_held"), ("warnings", "settle_timeout"),
                  ("unchecked", ""), ("running", ""), ("healthy", "")], f"manifest health {got}")
    # warnings and unchecked are listed but do not fail the sweep
    write_health(pts[0], "healthy", [])
    write_health(pts[3], "healthy", [])
    r = run_sweep(a, cfg, "--out-dir", str(out))
    check(r.returncode == 0 and "2 point(s) whose run is not healthy" in r.stdout,
          f"exit {r.returncode}: warnings / unchecked must be listed, not fail")


def procs_under(path):
    """PIDs whose command line mentions path (children left behind)."""
    found = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit() and int(d.name) != os.getpid():
            try:
                if str(path) in (d / "cmdline").read_bytes().replace(b"\0", b" ").decode():
                    found.append(int(d.name))
            except OSError:
                pass
    return found


def case_resume_sigterm(a, work):
    """SIGTERM after the first point finished: the driver kills its child, exits 143, marks only
    finished points done; the re-run skips them and completes the rest."""
    cfg = work / "sweep.toml"
    sweep_config(cfg, a.build_dir, duration=DURATION_SIGTERM, every=1000, slips=[0.1, 0.2])
    out = work / "out"
    cmd = [a.sweep, str(cfg), "--build-dir", a.build_dir, "--out-dir", str(out), "--jobs", "1"]
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines, t0 = [], time.monotonic()
    for line in p.stdout:
        print(line, end="")
        lines.append(line)
        if re.match(r"\[1/4\] .* done in ", line):
            break
        check(time.monotonic() - t0 < 40, "no point finished within 40 s")
    check(any(re.match(r"\[1/4\]", x) for x in lines), "first point never finished")
    for line in p.stdout:  # wait until the second point started
        print(line, end="")
        if line.startswith("[started 2/4]"):
            break
    # ... and its wheel-rig is running (a fixed sleep raced the point's end on a fast machine)
    t1, rig = time.monotonic(), []
    while not rig and time.monotonic() - t1 < 10:
        rig = procs_under(out / "wheel1/mu05/s0.200")
        time.sleep(0.02)
    check(rig, "the second point's wheel-rig was never seen running")
    p.send_signal(signal.SIGTERM)
    rest = p.stdout.read()
    print(rest, end="")
    rc = p.wait(timeout=30)
    check(rc == 128 + signal.SIGTERM, f"driver exit {rc}, expected {128 + signal.SIGTERM}")
    check(re.search(r"interrupted after", rest), "the running point was not reported interrupted")
    time.sleep(0.2)
    left = procs_under(out)
    check(not left, f"child processes left running: {left}")
    rows = manifest(out)
    st = [r["status"] for r in rows]
    check(st.count("done") == 1 and st.count("interrupted") == 1 and st.count("pending") == 2,
          f"manifest statuses {st}")
    marked = sorted(str(d.parent.relative_to(out)) for d in out.glob("*/*/*/done.json"))
    check(marked == ["wheel1/mu05/s0.100"], f"points marked done: {marked}")
    check(not (out / "wheel1/mu05/s0.200/run.h5").exists(), "interrupted point has a run.h5")
    r = run_sweep(a, cfg, "--out-dir", str(out), "--jobs", "2", timeout=120)
    check(r.returncode == 0, "resumed sweep failed")
    check("skipping 1 finished point(s)" in r.stdout and "running 3 point(s)" in r.stdout,
          "resume did not skip exactly the finished point")
    check_complete(out, ["wheel1", "small"], [0.1, 0.2])


def _proc_stat(pid):
    """(ppid, session, start time) of a process, or None if it is gone or a zombie (dead; the
    init of a container may take seconds to reap an orphan)."""
    try:
        text = Path(f"/proc/{pid}/stat").read_bytes()
    except OSError:
        return None
    f = text[text.rindex(b")") + 2:].split()
    return None if f[0] == b"Z" else (int(f[1]), int(f[3]), int(f[19]))


def _cmdline(pid):
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode().strip()
    except OSError:
        return "?"


def descendants(root):
    """{pid: (start time, command line)} of every descendant of `root` and every process in
    the session of one of them (the tree of each point)."""
    procs = {}
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            st = _proc_stat(int(d.name))
            if st is not None:
                procs[int(d.name)] = st
    found, todo = set(), [root]
    while todo:
        parent = todo.pop()
        for pid, (ppid, _, _) in procs.items():
            if ppid == parent and pid not in found:
                found.add(pid)
                todo.append(pid)
    sessions = {procs[p][1] for p in found} - {procs.get(root, (0, -1, 0))[1]}
    found |= {pid for pid, (_, sid, _) in procs.items() if sid in sessions}
    return {pid: (procs[pid][2], _cmdline(pid)) for pid in found if pid != os.getpid()}


def still_alive(snapshot):
    return {pid: cmd for pid, (start, cmd) in snapshot.items()
            if (_proc_stat(pid) or (0, 0, None))[2] == start}


def kill_driver_and_check(a, cmd, wait_for, need, timeout=40):
    """Starts the driver, waits until `need(descendants)` holds, SIGKILLs the driver and checks
    that every descendant (and every process of a child's session) is gone within 5 s."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    tree = {}
    try:
        t0 = time.monotonic()
        for line in p.stdout:
            print(line, end="")
            if wait_for in line:
                break
        while time.monotonic() - t0 < timeout:
            tree = descendants(p.pid)
            if need(tree):
                break
            time.sleep(0.2)
        print("driver's tree before SIGKILL:")
        for pid, (_, c) in sorted(tree.items()):
            print(f"  {pid} {c[:150]}")
        check(need(tree), "the sweep's children did not start")
        time.sleep(0.5)
        tree.update(descendants(p.pid))
        p.kill()
        p.wait()
        t1 = time.monotonic()
        left = still_alive(tree)
        while left and time.monotonic() - t1 < 5.0:
            time.sleep(0.1)
            left = still_alive(tree)
        check(not left, "processes left 5 s after SIGKILL of the driver: "
              + "; ".join(f"{pid} {c[:100]}" for pid, c in left.items()))
        print(f"all {len(tree)} processes gone {time.monotonic() - t1:.2f} s after SIGKILL")
    finally:
        if p.poll() is None:
            p.kill()
        for pid in still_alive(tree):  # leave nothing behind when the check failed
            os.kill(pid, signal.SIGKILL)


def case_kill_flat(a, work):
    """SIGKILL of the driver while 2 wheel-rig points run: no child outlives it."""
    cfg = work / "sweep.toml"
    sweep_config(cfg, a.build_dir, duration=DURATION_KILL, every=100000, slips=[0.1, 0.2])
    cmd = [a.sweep, str(cfg), "--build-dir", a.build_dir, "--out-dir", str(work / "out"),
           "--jobs", "2"]
    kill_driver_and_check(a, cmd, "[started 2/", lambda t: sum(
        "wheel-rig" in c for _, c in t.values()) == 2)


def stand_in_build(a, work, standin=False):
    """work/build: a build dir of links to the real wheel-rig and meshes; its liggghts-wheel is
    liggghts_standin.py with standin, else left to the caller."""
    build = work / "build"
    (build / "bin").mkdir(parents=True)
    (build / "bin" / "wheel-rig").symlink_to(Path(a.build_dir).resolve() / "bin" / "wheel-rig")
    (build / "meshes").symlink_to(Path(a.build_dir).resolve() / "meshes")
    if standin:
        (build / "bin" / "liggghts-wheel").symlink_to(Path(__file__).resolve().parent
                                                      / "liggghts_standin.py")
    return build


def case_kill_dem(a, work):
    """SIGKILL of the driver during 2 DEM points: wheel-cosim, its rig, mpirun and mpirun's 2
    ranks each (a stand-in liggghts-wheel that sleeps, in a build dir of links) all die."""
    if shutil.which("mpirun") is None:
        raise Skip("mpirun not found (Debian openmpi-bin)")
    build = stand_in_build(a, work)
    fake = build / "bin" / "liggghts-wheel"
    fake.write_text("#!/bin/sh\nexec sleep 300\n")
    fake.chmod(0o755)
    bed = work / "soilbin_ci.restart"
    bed.write_text("not a restart\n")
    Path(f"{bed}.vars").write_text("variable bed_depth equal 0.035\nvariable soil string ci\n")
    (work / "in.deck").write_text("# never read: liggghts-wheel is a stand-in\n")
    repo = Path(a.sweep).resolve().parents[1]
    cfg = work / "sweep.toml"
    cfg.write_text(f"""terrain = "dem"
base = "{repo}/inputs/rigs/ci_small_wheel.toml"
wheels = ["test_small"]
soils = ["{bed}"]
slips = [0.1, 0.2]
[dem]
np = 2
deck = "in.deck"
""")
    cmd = [a.sweep, str(cfg), "--build-dir", str(build), "--out-dir", str(work / "out"),
           "--jobs", "2"]

    def started(tree):
        cmds = [c for _, c in tree.values()]
        return (sum(c.startswith("sleep 300") for c in cmds) == 4
                and sum("bin/wheel-rig" in c and "--endpoint" in c for c in cmds) == 2)
    kill_driver_and_check(a, cmd, "[started 2/", started)


STALL_MIN = "0.05"  # --stall-timeout [min]: 3 s
STALL_S = 3.0


def stall_sweep(a, work):
    """A one-point DEM sweep on a ci bin recipe with a build dir whose liggghts-wheel is
    tests/sweep/liggghts_standin.py (wheel-rig and the meshes linked to the real build); returns
    the command of `wheel-sweep --beds-only --stall-timeout 0.05` (3 s) and its output dir."""
    if shutil.which("mpirun") is None:
        raise Skip("mpirun not found (Debian openmpi-bin)")
    build = stand_in_build(a, work, standin=True)
    (work / "in.deck").write_text("# never read: no point runs (--beds-only)\n")
    repo = Path(a.sweep).resolve().parents[1]
    cfg = work / "sweep.toml"
    cfg.write_text(f"""terrain = "dem"
base = "{repo}/inputs/rigs/ci_small_wheel.toml"
wheels = ["test_small"]
soils = [{{ soil = "ci", bin_length = 0.12, bin_width = 0.08, fill_height = 0.03 }}]
slips = [0.2]
[dem]
np = 1
bed_np = 1
deck = "in.deck"
""")
    out = work / "out"
    return [a.sweep, str(cfg), "--build-dir", str(build), "--out-dir", str(out), "--beds-only",
            "--stall-timeout", STALL_MIN], out


def run_stalling(cmd, env, work):
    """Runs the sweep (stand-in behaviour in env); returns (exit status, output, wall time [s])
    after checking that none of its processes is left."""
    t0 = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=60,
                       env=dict(os.environ, **env))
    wall = time.monotonic() - t0
    print(f"$ {' '.join(cmd)}  ({env}) -> exit {r.returncode} after {wall:.1f} s")
    print(r.stdout + r.stderr)
    left = procs_under(work / "build")
    deadline = time.monotonic() + 2.0
    while left and time.monotonic() < deadline:
        time.sleep(0.1)
        left = procs_under(work / "build")
    for pid in left:
        os.kill(pid, signal.SIGKILL)
    check(not left, "processes of the stalled run left: "
          + "; ".join(f"{pid} {_cmdline(pid)[:100]}" for pid in left))
    return r.returncode, r.stdout + r.stderr, wall


def stall_message(text, what, log):
    """Checks the stall guard's one-line error: what, the timeout, the log, the option."""
    lines = [x for x in text.splitlines() if "made no progress" in x]
    check(len(lines) == 1, f"no one stall error line naming {what}")
    m = re.fullmatch(r"wheel-sweep: error: (.*) made no progress for 0\.05 min \(log (\S+) "
                     r"unchanged since \d\d:\d\d:\d\d\): killed; .*--stall-timeout MIN.*",
                     lines[0])
    check(m is not None, f"stall error not as documented: {lines[0]}")
    check(m.group(1) == what and m.group(2) == str(log),
          f"stall error names {m.group(1)!r} and {m.group(2)}, expected {what!r} and {log}")


def case_bed_stall(a, work):
    """The stall guard on a bed's preparation: liggghts-wheel (a stand-in under mpirun) prints one
    line and hangs; with --stall-timeout 0.05 (3 s) wheel-sweep kills its session, stops with one
    line naming in.soilbin and its log, exit 1, no process left, no bed written."""
    cmd, out = stall_sweep(a, work)
    rc, text, wall = run_stalling(cmd, {"STANDIN_STALL_DECKS": "in.soilbin"}, work)
    check(rc == 1, f"exit {rc}, expected 1")
    bdir = out / "beds" / "ci"
    stall_message(text, "bed 'ci': in.soilbin", bdir / "soilbin.log")
    check(STALL_S <= wall < STALL_S + 15, f"took {wall:.1f} s for a {STALL_S} s stall timeout")
    check("stand-in liggghts-wheel" in (bdir / "soilbin.log").read_text(),
          "the stand-in's line is not in the bed's log")
    check(not (bdir / "soilbin_ci.restart").exists(), "a bed restart was written")


def case_rate_stall(a, work):
    """The stall guard on --measure-rate: its first run (in.soilbin, a stand-in that prints one
    line and hangs) is killed after --stall-timeout 0.05 (3 s): one error line naming the
    benchmark step, its last lines after it, exit 1, no process left, no rate cached."""
    build = stand_in_build(a, work, standin=True)
    cache = work / "dem_rate.toml"
    cmd = [a.sweep, "--measure-rate", "--build-dir", str(build), "--stall-timeout", STALL_MIN]
    rc, text, wall = run_stalling(cmd, {"STANDIN_STALL_DECKS": "in.soilbin",
                                        "WHEELSIM_RATE_CACHE": str(cache)}, work)
    check(rc == 1, f"exit {rc}, expected 1")
    lines = [x for x in text.splitlines() if "made no progress" in x]
    check(len(lines) == 1 and lines[0].startswith(
        "wheel-sweep: error: --measure-rate: rate benchmark: bed (in.soilbin, 1 rank) made no "
        "progress for 0.05 min (log "), f"stall error not as documented: {lines}")
    check("stand-in liggghts-wheel" in text, "the run's last lines are not in the error")
    check(STALL_S <= wall < STALL_S + 15, f"took {wall:.1f} s for a {STALL_S} s stall timeout")
    check(not cache.exists(), "a rate was cached")


def case_bed_steady(a, work):
    """A bed's in.soilbin that prints a line every 0.25 s for 6 s (twice the 3 s stall timeout)
    is not killed: the bed is made; then its bed-hold check prints one line and hangs, and is
    killed: one line naming in.bedhold and its log, exit 1, no process left."""
    cmd, out = stall_sweep(a, work)
    rc, text, wall = run_stalling(cmd, {"STANDIN_STALL_DECKS": "in.bedhold",
                                        "STANDIN_STEADY_S": "6"}, work)
    bdir = out / "beds" / "ci"
    check("in.soilbin made no progress" not in text, "the steadily printing in.soilbin was killed")
    check(re.search(r"^bed ci: ready in ", text, re.M), "the bed was not made")
    check((bdir / "soilbin_ci.restart").is_file(), "no bed restart")
    check(rc == 1, f"exit {rc}, expected 1 (the bed-hold check stalled)")
    stall_message(text, "bed 'ci': in.bedhold", bdir / "bedhold.log")
    check(not (bdir / "soilbin_ci.restart.hold.json").exists(), "a bed-hold record was written")


def dem_repo(a):
    """The repository of the sweep under test, for a case that runs LIGGGHTS (Skip without mpirun
    or liggghts-wheel)."""
    if shutil.which("mpirun") is None:
        raise Skip("mpirun not found (Debian openmpi-bin)")
    if not (Path(a.build_dir) / "bin" / "liggghts-wheel").exists():
        raise Skip("liggghts-wheel not built")
    return Path(a.sweep).resolve().parents[1]


NO_BED_HOLD = ("--bed-hold", "0")  # small_dem_sweep's unsettled beds


def small_dem_sweep(path, repo, soil, deck, fill=0.03, soil_keys=""):
    """A one-point DEM sweep: test_small at 20 % on a 0.12 x 0.08 m bin recipe of `soil` (fill
    height `fill`, more recipe keys `soil_keys`), 150 coupled steps of `deck` on one rank. Its bed's
    settling is cut short (max_settle_time 0.006 s), so wheel-sweep's bed-hold check refuses it:
    run it with --bed-hold 0 (NO_BED_HOLD) unless that is what is tested."""
    extra = f", {soil_keys}" if soil_keys else ""
    path.write_text(f"""terrain = "dem"
base = "{repo}/inputs/rigs/ci_small_wheel.toml"
wheels = ["test_small"]
soils = [{{ soil = "{soil}", bin_length = 0.12, bin_width = 0.08, fill_height = {fill}, \
check_time = 0.002, max_settle_time = 0.006{extra} }}]
slips = [0.2]
[dem]
np = 1
bed_np = 1
deck = "{deck}"
liggghts_args = ["-var", "motion", "coupled", "-var", "steps", "150"]
""")


def case_dem_soil_file(a, work):
    """A DEM bin recipe with a soil include file outside the repository, by a path relative to
    the config (soil = "elsewhere/my_sand.in": inputs/soils/ci.in with soil_name my_sand): the bed
    is prepared with it and named after soil_name, its .vars records the absolute path, the
    coupled point (tests/cosim/in.motion_compare, 150 steps, 1 rank) includes the same file and
    its run file records bed/soil and bed/soil_file; the bed is prepared with soil_preparing_bed 1,
    the point sees 0; the bed, its settling cut short for speed, is first refused by the bed-hold
    check (exit 1, "had not settled", no point run) and then used with --bed-hold 0; a changed soil
    file (same path) makes the finished point re-run and the bed be prepared again (--dry-run)."""
    repo = dem_repo(a)
    soil = work / "elsewhere" / "my_sand.in"
    soil.parent.mkdir()
    text = (repo / "inputs" / "soils" / "ci.in").read_text()
    check("variable soil_name string ci\n" in text, "inputs/soils/ci.in has no soil_name line")
    soil.write_text(text.replace("variable soil_name string ci\n",
                                 'variable soil_name string my_sand\nprint "my_sand.in: included"\n'
                                 'variable soil_preparing_bed index 0\n'
                                 'print "my_sand.in: soil_preparing_bed ${soil_preparing_bed}"\n'))
    # the deck (tests/cosim/in.motion_compare) with one more include, by absolute path
    extra = work / "extra.in"
    extra.write_text('print "extra.in: included"\n')
    deck = work / "in.motion_compare"
    deck_text = (repo / "tests" / "cosim" / "in.motion_compare").read_text()
    resume_line = "include ${inputs_dir}/soilbin/resume.in\n"
    check(resume_line in deck_text, "tests/cosim/in.motion_compare does not include resume.in")
    deck.write_text(deck_text.replace(resume_line, f"{resume_line}include {extra}\n"))
    cfg = work / "sweep.toml"
    small_dem_sweep(cfg, repo, "elsewhere/my_sand.in", deck)
    out = work / "out"
    cmd = [a.sweep, str(cfg), "--build-dir", a.build_dir, "--out-dir", str(out), "--jobs", "1"]
    # the recipe cuts the bed's settling short (max_settle_time 0.006 s, for speed): the bed-hold
    # check (docs/soil-bins.md) sees it fall and stops the sweep before any point, naming why
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    print(r.stdout[-3000:], r.stderr[-2000:])
    bed = out / "beds" / "my_sand" / "soilbin_my_sand.restart"
    check(r.returncode == 1 and "wheel-sweep: error: bed 'my_sand' had not settled when it was "
          "prepared (in.soilbin: settled = 0" in r.stdout and "--bed-hold 0" in r.stdout
          and Path(f"{bed}.hold.json").is_file()
          and not (out / "test_small" / "my_sand" / "s0.200" / "done.json").exists(),
          "the unsettled bed was not stopped by the bed-hold check, with its reason")
    cmd += NO_BED_HOLD  # a bed meant to be unsettled
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    print(r.stdout[-3000:], r.stderr[-2000:])
    check(r.returncode == 0 and f"bed my_sand: reusing {bed}" in r.stdout,
          "with --bed-hold 0 the sweep did not go on on the same bed")
    check(bed.is_file() and Path(f"{bed}.vars").is_file(),
          f"no bed {bed} named after the file's soil_name")
    bvars = Path(f"{bed}.vars").read_text()
    check(f"variable soil_file index {soil}\n" in bvars and "variable soil index my_sand\n" in bvars,
          f"the bed's .vars does not record the soil file:\n{bvars}")
    pdir = out / "test_small" / "my_sand" / "s0.200"
    done = json.loads((pdir / "done.json").read_text())
    check(done["exit_status"] == 0, f"the point failed: {done} (log {pdir / 'run.log'})")
    check("my_sand.in: included" in (pdir / "cosim" / "liggghts.log").read_text(),
          "the coupled run's LIGGGHTS did not include the soil file")
    # the bed is prepared with soil_preparing_bed 1, the point runs without it (docs/soils.md
    # "Preparing the bed with other contact settings")
    check("my_sand.in: soil_preparing_bed 1" in (bed.parent / "soilbin.log").read_text(),
          "the bed was not prepared with -var soil_preparing_bed 1")
    check("my_sand.in: soil_preparing_bed 0" in (pdir / "cosim" / "liggghts.log").read_text(),
          "the coupled run did not see soil_preparing_bed 0")
    with h5py.File(pdir / "run.h5", "r") as f:
        par = {k: f[f"parameters/bed/{k}"].asstr()[()] for k in ("soil", "soil_file")}
    check(par == {"soil": "my_sand", "soil_file": str(soil)}, f"run file /parameters/bed: {par}")
    check("extra.in: included" in (pdir / "cosim" / "liggghts.log").read_text(),
          "the coupled run's LIGGGHTS did not include the deck's extra file")
    included = done.get("included_sha256", {})
    # keyed by path with the sweep file's directory and the checkout as <config> and <repo>
    # (docs/sweeps.md "Resume semantics")
    for f in (f"<config>/{extra.name}", "<repo>/inputs/soilbin/resume.in",
              "<repo>/inputs/soilbin/bed_fixes.in"):
        check(f in included, f"done.json's included_sha256 misses {f}: {sorted(included)}")
    r = subprocess.run(cmd + ["--dry-run"], capture_output=True, text=True, timeout=120)
    check("finished  test_small my_sand s=0.2" in r.stdout, f"not finished on a re-run:\n{r.stdout}")
    # a file the deck includes changed (same path): the point re-runs, the bed stays
    extra.write_text('print "extra.in: included, changed"\n')
    r = subprocess.run(cmd + ["--dry-run"], capture_output=True, text=True, timeout=120)
    check(f"would run test_small my_sand s=0.2 (included file {extra} changed since it finished)"
          in r.stdout and f"bed my_sand: reusing {bed}" in r.stdout,
          f"a changed included file (same path) does not re-run the point:\n{r.stdout}")
    soil.write_text(soil.read_text() + "# changed\n")
    r = subprocess.run(cmd + ["--dry-run"], capture_output=True, text=True, timeout=120)
    check("would run test_small my_sand s=0.2 (inputs changed since it finished)" in r.stdout,
          f"a changed soil file (same path) does not re-run the point:\n{r.stdout}")
    check(f"bed my_sand: would prepare {bed} again: its soil file, inputs/in.soilbin or a file "
          "they include changed"
          in r.stdout, f"a changed soil file (same path) does not re-prepare the bed:\n{r.stdout}")


def case_dem_tiled_bed(a, work):
    """A tiled DEM bin recipe (tile_length; docs/soil-bins.md "Tiled beds"): ci, 0.12 x 0.08 m
    in 3 blocks of 0.04 m (short settling and relaxation bounds: the test is about the driver).
    wheel-sweep --beds-only prepares it alone (the bed log says tiles = 3, its .vars records
    tile_length 0.04; no point runs), then one coupled point (150 steps, 1 rank) runs on it; a re-run skips the point, --force re-runs
    it on the same bed (reused, untouched); a changed tile_length (0.06: 2 blocks) re-prepares the bed, says which key changed,
    and re-runs the point; a changed non-tile key is still an error."""
    repo = dem_repo(a)
    cfg = work / "sweep.toml"

    def write(tile, fill=0.03):
        small_dem_sweep(cfg, repo, "ci", repo / "tests" / "cosim" / "in.motion_compare", fill,
                        f"tile_length = {tile}, tile_relax_time = 0.002, tile_relax_max = 0.004")
    out = work / "out"
    cmd = [a.sweep, str(cfg), "--build-dir", a.build_dir, "--out-dir", str(out), "--jobs", "1",
           *NO_BED_HOLD]
    bed = out / "beds" / "ci" / "soilbin_ci.restart"
    pdir = out / "test_small" / "ci" / "s0.200"

    def run(*extra):
        r = subprocess.run(cmd + list(extra), capture_output=True, text=True, timeout=300)
        print(f"$ wheel-sweep {' '.join(extra)} -> exit {r.returncode}\n{r.stdout[-3000:]}"
              f"{r.stderr[-2000:]}")
        return r

    def check_bed(tile, tiles):
        bvars = Path(f"{bed}.vars").read_text()
        check(f"variable tile_length index {tile}\n" in bvars,
              f"the bed's .vars does not record tile_length {tile}:\n{bvars}")
        log = (bed.parent / "soilbin.log").read_text()
        check(f"soilbin: tiles = {tiles}\n" in log, f"the bed log does not say tiles = {tiles}")
        done = json.loads((pdir / "done.json").read_text())
        check(done["exit_status"] == 0, f"the point failed: {done} (log {pdir / 'run.log'})")

    write(0.04)
    r = run("--beds-only")  # the bed job of a cluster's one-job-per-point layout
    check(r.returncode == 0 and f"bed ci: preparing {bed}" in r.stdout and bed.is_file()
          and "--beds-only: the beds are ready; 1 point(s) left to run" in r.stdout
          and not pdir.exists(), "--beds-only did not prepare the bed alone")
    r = run()
    check(r.returncode == 0 and f"bed ci: reusing {bed}" in r.stdout,
          "the bed --beds-only prepared was not reused")
    check_bed("0.04", 3)
    r = run()
    check(r.returncode == 0 and "skipping 1 finished point(s)" in r.stdout,
          "the finished point was not skipped")
    mtime = bed.stat().st_mtime_ns
    r = run("--force")
    check(r.returncode == 0 and f"bed ci: reusing {bed}" in r.stdout
          and bed.stat().st_mtime_ns == mtime, "the bed was not reused (--force)")
    write(0.06)
    r = run("--dry-run")
    check(f"bed ci: would prepare {bed} again: its preparation keys changed (tile_length 0.04 -> "
          "0.06)" in r.stdout, "a changed tile_length does not re-prepare the bed (--dry-run)")
    check("would run test_small ci s=0.2 (inputs changed since it finished)" in r.stdout,
          "a changed tile_length does not re-run the point")
    r = run()
    check(r.returncode == 0 and f"bed ci: preparing {bed} again: its preparation keys changed"
          in r.stdout, "the bed was not prepared again")
    check_bed("0.06", 2)
    write(0.06, fill=0.035)
    r = run("--dry-run")
    check(r.returncode != 0 and "was prepared from another recipe" in r.stdout + r.stderr,
          "a changed fill_height (not a preparation key) was not an error")


def case_spheres_per_particle(a, work):
    """A multisphere soil's spheres per particle from its distribution, its weights evaluated by
    LIGGGHTS: the shipped loose sand (20 % clumps by number, half boxes of 8 spheres, half hulls
    of 5: 0.8 + 0.1 x 8 + 0.1 x 5 = 2.1; its lab bed held 67 348 spheres in 32 067 particles,
    2.100), a trial variant that sets 30 % clumps first (2.65), clayey loam's 5 % trial (1.275),
    a sphere soil 1.0."""
    if not (Path(a.build_dir) / "bin" / "liggghts-wheel").exists():
        raise Skip("liggghts-wheel not built")
    repo = Path(a.sweep).resolve().parents[1]
    sys.path[:0] = [str(repo / "scripts"), str(repo / "postprocess")]   # as wheel-sweep
    from wheelsim_sweep import estimate as E
    liggghts = Path(a.build_dir).resolve() / "bin" / "liggghts-wheel"
    for soil, want in (("inputs/soils/loose_sand.in", 2.1),
                       ("soil_lab/trials/upland_sand_clump030.in", 2.65),
                       ("soil_lab/trials/clayey_loam_clump005.in", 1.275),
                       ("inputs/soils/dry_sand.in", 1.0)):
        got, how = E.spheres_per_particle(liggghts, repo / soil, repo / "inputs")
        print(f"{soil}: {got} ({how})")
        check(got is not None and abs(got - want) < 1e-9, f"{soil}: {got} ({how}), expected {want}")


def case_estimate_example(a, work):
    """--estimate on inputs/sweeps/dem_small_slips.toml with an empty output directory and no
    rate cache prints every field: the rate and its source (the default, saying no rate was
    measured), each point's particles (from the recipe: 11 625, LIGGGHTS inserts 11 624), dt
    (run.dt), simulated time with release, settle, ramp and test, steps (whole chunks of the
    deck's 1000) and wall time, the bed to prepare, the sweep total; exit 0, nothing written."""
    if not (Path(a.build_dir) / "bin" / "liggghts-wheel").exists():
        raise Skip("liggghts-wheel not built")
    repo = Path(a.sweep).resolve().parents[1]
    out = work / "out"
    env = dict(os.environ, WHEELSIM_RATE_CACHE=str(work / "no_cache.toml"))
    r = subprocess.run([a.sweep, str(repo / "inputs" / "sweeps" / "dem_small_slips.toml"),
                        "--build-dir", a.build_dir, "--out-dir", str(out), "--estimate",
                        "--jobs", "2", "--cores", "2"],
                       capture_output=True, text=True, timeout=60, env=env)
    print(r.stdout, r.stderr)
    check(r.returncode == 0, f"--estimate exited {r.returncode}")
    lines = r.stdout.splitlines()
    check(any(line.startswith("estimate: rate 2.9e+06 particle-steps/s per rank") and "DEFAULT"
              in line and "no rate measured on this machine" in line for line in lines),
          "no rate line with the default and why")
    points = [line for line in lines if line.startswith("estimate: point ")]
    check(len(points) == 3, f"{len(points)} point lines, expected 3")
    num = r"([0-9.e+-]+)"
    for line in points:
        m = re.search(r"particles ([0-9 ]+) \(recipe: .*\); dt 4\.89543e-05 s \(run\.dt\); "
                      rf"simulated {num} s = release {num} \+ settle <= 0\.2 \+ ramp 0\.05 \+ "
                      rf"test 0\.3; steps ([0-9 ]+); wall .* \({num} s\)$", line)
        check(m is not None, f"point line lacks a field: {line}")
        n = int(m.group(1).replace(" ", ""))
        check(abs(n - 11624) <= 0.01 * 11624, f"particles {n}, expected 11 624 +- 1 %")
        sim, rel = float(m.group(2)), float(m.group(3))
        # release: the 4 mm gap + 0.15 x R_eff (0.10 m) = 19 mm at 0.05 m/s reached over 0.1 s
        # = 0.1 + 16.5 mm / 0.05 m/s = 0.43 s
        check(abs(rel - 0.43) < 1e-9 and abs(sim - (rel + 0.55)) < 1e-3, f"phases: {line}")
        # 0.98 s / dt = 20 019 steps, in whole chunks of 1000 (in.wheel_coupled's chunk)
        steps = math.ceil(math.ceil(0.98 / 4.89543219523472e-05) / 1000) * 1000
        check(int(m.group(4).replace(" ", "")) == steps == 21000, f"steps ({steps}): {line}")
        check(float(m.group(5)) > 0, f"wall: {line}")
    check(any(line.startswith("estimate: bed ci_small (to prepare, 2 rank(s)): particles")
              and "steps <= " in line and "wall <= " in line for line in lines), "no bed line")
    check(any(line.startswith("estimate: sweep: 3 point(s)") and "= points" in line
              and "beds <=" in line for line in lines), "no sweep line")
    check(not out.exists(), "--estimate wrote the output directory")
    # A variant soil whose sieve classes live in the base soil file it includes
    # (dry_sand_coarse.in includes dry_sand.in): the recipe's count uses those classes, not one
    # sphere of d_ref (which gave 4 074 for the 6 722 spheres LIGGGHTS inserted, 2026-11-26).
    r = subprocess.run([a.sweep, str(repo / "validation" / "study_wheels" / "sweep_smoke.toml"),
                        "--build-dir", a.build_dir, "--out-dir", str(out), "--estimate"],
                       capture_output=True, text=True, timeout=60, env=env)
    print(r.stdout, r.stderr)
    bed = [line for line in r.stdout.splitlines() if line.startswith("estimate: bed ")]
    m = re.search(r"particles ([0-9 ]+) \(recipe: .*\(4 sieve classes by mass fraction\)\)",
                  bed[0] if bed else "")
    check(m is not None, f"the coarse soil's bed is not counted from its 4 sieve classes: {bed}")
    n = int(m.group(1).replace(" ", ""))
    check(abs(n - 6722) <= 0.03 * 6722, f"particles {n}, expected 6 722 +- 3 %")


BAD = [
    # (name, config text after the valid header lines replaced/added, expected message regex)
    ("unknown_key", 'slip = [0.1]\n', r"unknown key 'slip'; did you mean 'slips'\?"),
    ("override_key", '[override.run]\ndurration = 1.0\n',
     r"unknown key 'override\.run\.durration'; did you mean 'duration'\?"),
    ("override_table", '[override.motors]\nomega = 1.0\n', r"unknown table 'override\.motors'"),
    ("slip_range", None, r"slips\[1\] must be in \[-1, 1\], got 1\.5"),
    ("wheel_name", None, r"wheels\[0\]: no catalogue wheel 'no_such_wheel'"),
    ("wheel_key", None, r"unknown key 'wheels\[1\]\.mas'; did you mean 'mass'\?"),
    ("dem_table_flat", '[dem]\nnp = 2\n', r"\[dem\] is only used with terrain = \"dem\""),
    ("terrain", None, r"terrain must be one of flat, dem, scm \(wheel-rig's terrain types\), "
                      r"got 'sand'"),
    ("scm_soils_missing", None, r"missing key 'soils'"),
    ("dem_recipe_key", None, r"unknown key 'soils\[0\]\.bin_lenght'; did you mean 'bin_length'\?"),
    ("toml_syntax", 'slips = [0.1,\n', r"TOML syntax error"),
    ("dem_checkpoint_steps", None,
     r"dem\.checkpoint_every_steps must be an integer >= 0 \(0: not by steps\), got -5"),
    ("dem_checkpoint_s", None, r"dem\.checkpoint_every_s must be a wall time in s >= 0"),
]


def case_bad_config(a, work):
    """Bad configs exit 2 with a message naming the file and the key."""
    base_rig(work / "base.toml", 0.2)
    good = ('terrain = "flat"\nbase = "base.toml"\nwheels = ["wheel1"]\nslips = [0.1, 0.2]\n')
    for name, extra, regex in BAD:
        text = good + (extra or "")
        if name == "slip_range":
            text = text.replace("[0.1, 0.2]", "[0.1, 1.5]")
        elif name == "wheel_name":
            text = text.replace('["wheel1"]', '["no_such_wheel"]')
        elif name == "wheel_key":
            text = text.replace('["wheel1"]', '["wheel1", { name = "w", mas = 3.0 }]')
        elif name == "terrain":
            text = text.replace('"flat"', '"sand"')
        elif name == "scm_soils_missing":
            text = ('terrain = "scm"\nwheels = ["wheel1"]\nslips = [0.1]\n'
                    '[override.run]\ndt = 1e-3\n')
        elif name == "dem_recipe_key":
            text = ('terrain = "dem"\nwheels = ["wheel1"]\nslips = [0.1]\n'
                    'soils = [{ soil = "ci", bin_lenght = 0.3 }]\n[override.run]\ndt = 1e-3\n')
        elif name == "toml_syntax":
            text = good.replace("slips = [0.1, 0.2]\n", "") + extra
        elif name.startswith("dem_checkpoint"):
            value = "checkpoint_every_steps = -5" if name.endswith("steps") else \
                'checkpoint_every_s = "1h"'
            text = ('terrain = "dem"\nwheels = ["wheel1"]\nslips = [0.1]\n'
                    'soils = [{ soil = "ci" }]\n[override.run]\ndt = 1e-3\n'
                    f'[dem]\n{value}\n')
        cfg = work / f"{name}.toml"
        cfg.write_text(text)
        r = run_sweep(a, cfg, "--out-dir", str(work / "out"), "--dry-run")
        check(r.returncode == 2, f"{name}: exit {r.returncode}, expected 2")
        check(re.search(re.escape(str(cfg)) + ".*" + regex, r.stderr),
              f"{name}: message does not match /{regex}/")
    check(not (work / "out").exists(), "a bad config wrote output")


def case_override_schema(a, work):
    """[override.<table>] keys are checked against the schema wheel-rig --list-keys prints: a
    misspelt key (also in [override.terrain], once passed through) exits 2 with a did-you-mean;
    a stand-in wheel-rig whose schema has one more key makes that key valid, and one with one more
    terrain type makes that `terrain` valid (the lists are read from wheel-rig, not copied); a
    wheel-rig without --list-keys is an error that names it."""
    base_rig(work / "base.toml", 0.2)
    good = 'terrain = "flat"\nbase = "base.toml"\nwheels = ["wheel1"]\nslips = [0.1]\n'
    rig = Path(a.build_dir) / "bin" / "wheel-rig"
    schema = json.loads(subprocess.run([str(rig), "--list-keys"], capture_output=True,
                                       text=True, check=True).stdout)
    cases = [("terrain_key", "[override.terrain]\nstifness = 1e7\n",
              r"unknown key 'override\.terrain\.stifness'; did you mean 'stiffness'\?"),
             ("carriage_key", "[override.carriage]\nslipp = 0.1\n",
              r"unknown key 'override\.carriage\.slipp'; did you mean 'slip'\?"),
             ("new_key", "[override.run]\nsettle_extra = 1.0\n",
              r"unknown key 'override\.run\.settle_extra'")]
    for name, extra, regex in cases:
        cfg = work / f"{name}.toml"
        cfg.write_text(good + extra)
        r = run_sweep(a, cfg, "--out-dir", str(work / "out"), "--dry-run")
        check(r.returncode == 2, f"{name}: exit {r.returncode}, expected 2")
        check(re.search(re.escape(str(cfg)) + ".*" + regex, r.stderr),
              f"{name}: message does not match /{regex}/: {r.stderr}")
    # A stand-in wheel-rig with run.settle_extra in its schema: the sweep config now loads.
    build = work / "build"
    (build / "bin").mkdir(parents=True, exist_ok=True)
    (build / "meshes").symlink_to(Path(a.build_dir).resolve() / "meshes")
    schema["keys"].append({**schema["keys"][0], "name": "run.settle_extra", "table": "run",
                           "key": "settle_extra"})
    (build / "schema.json").write_text(json.dumps(schema))
    stand_in = build / "bin" / "wheel-rig"
    stand_in.write_text(f"#!/bin/sh\ncat '{build / 'schema.json'}'\n")
    stand_in.chmod(0o755)
    sys.path.insert(0, str(Path(a.sweep).resolve().parent))
    sys.path.insert(1, str(Path(a.sweep).resolve().parents[1] / "postprocess"))  # as wheel-sweep
    from wheelsim_sweep import config
    repo = Path(a.sweep).resolve().parents[1]
    sweep = config.load(work / "new_key.toml", repo, build)
    check(sweep.points[0].rig["run"]["settle_extra"] == 1.0, "the stand-in's key was not taken")
    # ... and the terrain type "mud" in its registry: a sweep on it loads (one soil named after
    # it, as for flat), refused by the real wheel-rig's list, which the message names
    mud = work / "mud.toml"
    mud.write_text(good.replace('terrain = "flat"', 'terrain = "mud"')
                   + '[override.terrain]\ntype = "mud"\n')
    try:
        config.load(mud, repo, Path(a.build_dir))
        check(False, "terrain = \"mud\" accepted by the real wheel-rig's list")
    except config.ConfigError as e:
        want = ", ".join(schema["terrain_types"])
        check(f"terrain must be one of {want} (wheel-rig's terrain types), got 'mud'" in str(e),
              f"message: {e}")
    schema["terrain_types"]["mud"] = {"summary": "a stand-in's terrain", "in_process": True}
    (build / "schema.json").write_text(json.dumps(schema))
    config._SCHEMAS.clear()
    sweep = config.load(mud, repo, build)
    check(sweep.terrain == "mud" and [s.label for s in sweep.soils] == ["mud"]
          and sweep.points[0].rig["terrain"]["type"] == "mud",
          f"the stand-in's terrain was not taken: {sweep.terrain}, {sweep.points[0].rig}")
    stand_in.write_text("#!/bin/sh\necho 'no such option' >&2\nexit 2\n")
    config._SCHEMAS.clear()
    try:
        config.load(work / "new_key.toml", repo, build)
        check(False, "a wheel-rig without --list-keys was accepted")
    except config.ConfigError as e:
        check("--list-keys did not print the rig-config schema" in str(e) and str(stand_in)
              in str(e), f"message: {e}")


def case_dry_run_check(a, work):
    """--dry-run runs `wheel-rig --check` on every point's rig config: a bad value or a misspelt
    key exits 2 naming the point and the key; a valid sweep exits 0; nothing is written."""
    out = work / "out"
    cfg = work / "sweep.toml"
    sweep_config(cfg, a.build_dir)
    r = run_sweep(a, cfg, "--out-dir", str(out), "--dry-run")
    check(r.returncode == 0 and "the 6 rig config(s) pass wheel-rig --check" in r.stdout,
          "a valid sweep does not pass --dry-run")
    cases = [
        # (name, sweep config text, base rig text change, [(point, message regex)])
        ("dt", "[override.run]\ndt = -1\n", None,
         [(p, r"run\.dt must be > 0 s, got -1") for p in (
             "wheel1/mu05/s0.100", "small/mu05/s0.500")]),
        ("base_key", "", ("duration", "durration"),
         [("wheel1/mu05/s0.250", r"unknown key 'run\.durration'; did you mean 'run\.duration'")]),
        ("one_wheel", "", None, [("small/mu05/s0.100", r"wheel\.mass")]),
    ]
    for name, extra, change, expect in cases:
        sweep_config(cfg, a.build_dir, extra=extra)
        if change:
            base = work / "base.toml"
            base.write_text(base.read_text().replace(*change))
        if name == "one_wheel":
            text = cfg.read_text().replace('name = "small",', 'name = "small", mass = -3.0,')
            cfg.write_text(text)
        r = run_sweep(a, cfg, "--out-dir", str(out), "--dry-run")
        check(r.returncode == 2, f"{name}: exit {r.returncode}, expected 2")
        for point, regex in expect:
            rx = (r"wheel-sweep: error: point " + re.escape(point) + r" \(.*\): "
                  + re.escape(f"{out}/{point}/rig.toml") + r":\d+: .*" + regex)
            check(re.search(rx, r.stderr), f"{name}: stderr does not match /{rx}/")
        n_bad = len(re.findall(r"^wheel-sweep: error: point ", r.stderr, re.M))
        check(n_bad == (6 if name != "one_wheel" else 3), f"{name}: {n_bad} points reported")
    check(not out.exists(), "--dry-run wrote output")


def case_examples_dry_run(a, work):
    """The example configs of inputs/sweeps/ load and list their points (no runs)."""
    repo = Path(a.sweep).resolve().parents[1]
    expect = {"scm_wheel2_dry_sand.toml": 8, "dem_small_slips.toml": 3, "study_scm.toml": 60}
    for name, n in expect.items():
        # study_scm.toml's 60 points each load a full-size wheel mesh in wheel-rig --check: 24 s
        # on a fast machine, ~40 s on a slow one, over 60 s there beside the other tests (a
        # failure at random under the old 60 s limit)
        r = run_sweep(a, repo / "inputs" / "sweeps" / name, "--out-dir", str(work / name),
                      "--dry-run", timeout=240)
        check(r.returncode == 0, f"{name}: exit {r.returncode}")
        check(f"= {n} point(s)" in r.stdout, f"{name}: expected {n} points")
        check(not (work / name).exists(), f"{name}: dry run wrote output")


def case_scm_smoke(a, work):
    """SCM: wheel 2 on dry sand at two slips with the example base rig, shortened (skips while
    the built wheel-rig has no SCM terrain)."""
    repo = Path(a.sweep).resolve().parents[1]
    cfg = work / "sweep.toml"
    cfg.write_text(f"""terrain = "scm"
base = "{repo}/inputs/sweeps/scm_study_rig.toml"
wheels = ["wheel2"]
soils = ["dry_sand"]
slips = [0.1, 0.3]
[override.motor]
ramp_time = 0.2
[override.run]
duration = 0.3
[override.terrain]
grid_length = 3.0
""")
    out = work / "out"
    r = run_sweep(a, cfg, "--out-dir", str(out), "--jobs", "2", timeout=100)
    check(r.returncode == 0, "SCM sweep failed")
    rows = manifest(out)
    # the soil's name is the one wheel-rig records (the soil file's `name`), not the file stem
    check([(x["soil"], x["slip"], x["status"], x["point_dir"]) for x in rows]
          == [("dry sand", "0.1", "done", "wheel2/dry_sand/s0.100"),
              ("dry sand", "0.3", "done", "wheel2/dry_sand/s0.300")], f"manifest {rows}")
    for x in rows:
        with h5py.File(out / x["run_file"], "r") as f:
            check(f["parameters/sweep/terrain"].asstr()[()] == "scm", "sweep/terrain")
            names = [f[f"parameters/{k}"].asstr()[()] for k in ("sweep/soil", "terrain/soil_name")]
            check(names == ["dry sand", "dry sand"],
                  f"/parameters/sweep/soil and terrain/soil_name differ: {names}")
            check("dry_sand.toml" in f["parameters/rig_config"].asstr()[()], "soil file in config")
            o = f["observables"]
            test = o["phase/value"][()] == 3
            slip = o["slip/value"][()][test]
            check(test.sum() > 0 and np.allclose(slip, float(x["slip"]), atol=1e-9),
                  f"imposed slip {x['slip']} not held")
            check(np.all(o["sinkage/value"][()][test] > 0), "no sinkage on soft soil")


SPEED = 0.2  # m/s, the carriage speed of case wheel_speed_flat
SKID_SLIP_TOL = 1e-6  # slip_skid (and signed slip) of the window means vs the target: both speeds
# are imposed exactly after the ramp, so only rounding remains; a wrong omega is off by > 1e-3


def case_wheel_speed_flat(a, work):
    """slip_control = "wheel_speed" end to end on the flat ground (regularized friction, v_c 1 mm/s,
    wheel1, R_eff = its mesh's outer radius): carriage speed 0.2 m/s imposed and motor.omega set
    per point for a driving slip 0.5, a skid slip -0.5 and a locked wheel -1. Known answers
    (RigSimulation.LockedWheelPulledAtConstantSpeedGivesMinusMuW, rig-config.md): driving DP =
    +mu W; skid and locked DP = -mu W (the slip velocity 0.1 and 0.2 m/s >> v_c). wheelsim-post
    curves --results reports slip_skid = -0.5 and -1 and slip_driving = 0.5 within SKID_SLIP_TOL;
    each run's rig config carries the omega that was set."""
    repo = Path(a.sweep).resolve().parents[1]
    base_rig(work / "base.toml", duration=0.4)
    base = (work / "base.toml").read_text().replace(
        'mode = "imposed_slip"', f'mode = "imposed_speed"\nspeed = {SPEED}')
    (work / "base.toml").write_text(base)
    slips = [0.5, -0.5, -1.0]
    cfg = work / "sweep.toml"
    cfg.write_text(f"""description = "slip set by the wheel speed"
terrain = "flat"
slip_control = "wheel_speed"
base = "base.toml"
wheels = ["wheel1"]
soils = [{SOIL}]
slips = {json.dumps(slips)}
""")
    out = work / "out"
    r = run_sweep(a, cfg, "--out-dir", str(out), "--jobs", "2")
    check(r.returncode == 0, "wheel_speed sweep failed")
    rows = manifest(out)
    check([(x["slip"], x["status"]) for x in rows] == [(repr(s), "done") for s in slips],
          f"manifest {rows}")
    runs = [str(out / x["run_file"]) for x in rows]
    for x, rf in zip(rows, runs):
        with h5py.File(rf, "r") as f:
            check(f["parameters/sweep/slip_control"].asstr()[()] == "wheel_speed",
                  f"{rf}: /parameters/sweep/slip_control")
            text = f["parameters/rig_config"].asstr()[()]
            r_eff = float(f["parameters/wheel/effective_radius"][()])
        omega = SPEED / ((1 - float(x["slip"])) * r_eff) if float(x["slip"]) >= 0 else \
            SPEED * (1 + float(x["slip"])) / r_eff
        check('slip_control = "wheel_speed": motor.omega = ' in text and
              f"for slip {x['slip']} (" in text, f"{rf}: the rig config header lacks the setting")
        got = float(re.search(r"^omega = (\S+)", text, re.M).group(1))
        check(abs(got - omega) <= 1e-12 * max(1.0, omega), f"{rf}: motor.omega {got} != {omega}")
    res = work / "results.csv"
    p = subprocess.run([str(repo / "postprocess" / "wheelsim-post"), "curves", *runs,
                        "--window-start", "0.2", "--window-end", "0.38", "--results", str(res)],
                       capture_output=True, text=True, timeout=60)
    print(p.stdout + p.stderr)
    check(p.returncode == 0, "wheelsim-post curves --results failed")
    with open(res, newline="") as f:
        table = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
    by_target = {float(t["target_slip"]): t for t in table}
    check(sorted(by_target) == sorted(slips), f"results targets {sorted(by_target)}")
    for s in slips:
        t = by_target[s]
        W = float(t["normal_load_N"])
        dp = float(t["drawbar_pull_N"])
        want_dp = FRICTION * W if s > 0 else -FRICTION * W
        print(f"target {s}: slip {t['slip']} driving {t['slip_driving']} skid {t['slip_skid']} "
              f"DP {dp:.2f} N (expected {want_dp:.2f}), W {W:.1f} N")
        check(abs(float(t["slip"]) - s) <= SKID_SLIP_TOL, f"target {s}: signed slip {t['slip']}")
        if s < 0:
            check(abs(float(t["slip_skid"]) - s) <= SKID_SLIP_TOL,
                  f"target {s}: slip_skid {t['slip_skid']} not within {SKID_SLIP_TOL}")
        else:
            check(abs(float(t["slip_driving"]) - s) <= SKID_SLIP_TOL,
                  f"target {s}: slip_driving {t['slip_driving']}")
        if s == -1.0:
            check(math.isnan(float(t["slip_driving"])), "locked: slip_driving not nan")
        # DP = +-mu W within 1 % (the known answer; regularized tanh(v_j / v_c) = 1 - 1e-80)
        check(abs(dp - want_dp) <= 0.01 * FRICTION * W, f"target {s}: DP {dp}, want {want_dp}")


def scm_tiny_config(cfg, repo, soils, wheels='["wheel2"]', slips="[0.2]", extra=""):
    """A tiny SCM sweep (a fraction of a second of test phase on a short grid)."""
    cfg.write_text(f"""terrain = "scm"
base = "{repo}/inputs/sweeps/scm_study_rig.toml"
wheels = {wheels}
soils = {soils}
slips = {slips}
[override.motor]
ramp_time = 0.1
[override.run]
duration = 0.1
[override.terrain]
grid_length = 2.0
{extra}""")


def case_resume_contents(a, work):
    """The resume hash covers file contents: a changed soil file (same path) re-runs the point,
    an unchanged one is skipped; a changed mesh file shows as 'inputs changed' in --dry-run."""
    repo = Path(a.sweep).resolve().parents[1]
    soil = work / "soil.toml"
    shutil.copyfile(repo / "inputs" / "scm_soils" / "dry_sand.toml", soil)
    mesh = work / "wheel.stl"
    shutil.copyfile(Path(a.build_dir) / "meshes" / "wheel2.stl", mesh)
    cfg = work / "sweep.toml"
    scm_tiny_config(cfg, repo, '["soil.toml"]', wheels='["wheel.stl"]')
    out = work / "out"
    r = run_sweep(a, cfg, "--out-dir", str(out), timeout=100)
    check(r.returncode == 0 and "running 1 point(s)" in r.stdout, "first sweep failed")
    run_h5 = out / "wheel/soil/s0.200/run.h5"
    t0 = run_h5.stat().st_mtime_ns
    r = run_sweep(a, cfg, "--out-dir", str(out), timeout=100)
    check(r.returncode == 0 and "skipping 1 finished point(s)" in r.stdout
          and "running" not in r.stdout, "unchanged inputs: the point was not skipped")
    check(run_h5.stat().st_mtime_ns == t0, "unchanged inputs: run.h5 rewritten")
    # same path, other contents: a higher cohesion
    text = soil.read_text()
    check("cohesion = 1040.0" in text, "dry_sand.toml has no 'cohesion = 1040.0' line")
    soil.write_text(text.replace("cohesion = 1040.0", "cohesion = 1500.0"))
    r = run_sweep(a, cfg, "--out-dir", str(out), timeout=100)
    check(r.returncode == 0 and "running 1 point(s)" in r.stdout
          and "(inputs changed since it finished)" in r.stdout,
          "a changed soil file (same path) did not re-run the point")
    with h5py.File(run_h5, "r") as f:
        check("cohesion = 1500.0" in f["parameters/terrain/soil_file_text"].asstr()[()],
              "the re-run did not read the changed soil file")
    r = run_sweep(a, cfg, "--out-dir", str(out), "--dry-run")
    check(r.returncode == 0 and "0 point(s) to run, 1 finished" in r.stdout,
          "after the re-run the point is not finished")
    with open(mesh, "ab") as f:  # the dry run only hashes the mesh: any change will do
        f.write(b"\0")
    r = run_sweep(a, cfg, "--out-dir", str(out), "--dry-run")
    check(r.returncode == 0 and "would run wheel soil s=0.2 (inputs changed since it finished)"
          in r.stdout, "a changed mesh file (same path) does not make the point re-run")


class Skip(Exception):
    pass


def case_dem_archive_bed(a, work):
    """--archive on a DEM sweep: the archived point records its bed's sha256; restored into an
    output directory whose bed is the same file it is not named; restored where the bed file
    differs (here: the same bed with bytes appended), it is named as having run on another
    preparation of its bed. One coupled point of 150 steps on a small ci bed, 1 rank."""
    repo = dem_repo(a)
    cfg = work / "sweep.toml"
    small_dem_sweep(cfg, repo, "ci", repo / "tests" / "cosim" / "in.motion_compare")
    out, arch = work / "out", work / "archive"
    r = run_sweep(a, cfg, "--out-dir", str(out), "--archive", str(arch), *NO_BED_HOLD,
                  timeout=300)
    check(r.returncode == 0, "the DEM sweep failed")
    bed = out / "beds" / "ci" / "soilbin_ci.restart"
    rel = "test_small/ci/s0.200"
    record = json.loads((arch / rel / "archived.json").read_text())
    want = {bed.name: hashlib.sha256(bed.read_bytes()).hexdigest()}
    check(record["bed_sha256"] == want, f"archived.json bed_sha256 {record['bed_sha256']} != {want}")
    shutil.rmtree(out / rel)
    r = run_sweep(a, cfg, "--out-dir", str(out), "--archive", str(arch), *NO_BED_HOLD,
                  "--beds-only", timeout=120)
    check(r.returncode == 0 and "restored 1 finished point(s)" in r.stdout
          and "another preparation" not in r.stdout, "restored onto the same bed: wrong report")
    shutil.rmtree(out / rel)
    with open(bed, "ab") as f:
        f.write(b"another preparation")
    r = run_sweep(a, cfg, "--out-dir", str(out), "--archive", str(arch), *NO_BED_HOLD,
                  "--beds-only", timeout=120)
    check(r.returncode == 0 and f"{rel} (restored from the archive) ran on another preparation "
          "of its bed" in r.stdout, "a point restored onto a different bed file is not named")


def resume_config(a, work):
    """(config, its one point's folder under OUT) of the checkpointed DEM point: test_small at
    20 % on the ci bed of tests/wheel_cosim, 0.05 s of test phase, checkpoints every 300 steps,
    1 rank."""
    repo = dem_repo(a)
    bed = Path(a.build_dir) / "tests" / "wheel_cosim" / "bed" / "soilbin_ci.restart"
    if not bed.is_file():
        raise Skip(f"the ci bed {bed} is not prepared (test wheel_cosim.bed)")
    cfg = work / "sweep.toml"
    cfg.write_text(f"""terrain = "dem"
base = "{repo}/inputs/rigs/ci_small_wheel.toml"
wheels = ["test_small"]
soils = ["{bed}"]
slips = [0.2]
[override.run]
duration = 0.05
release_gap = 0.002
[dem]
np = 1
deck = "{repo}/inputs/examples/in.wheel_coupled"
liggghts_args = ["-var", "output_every", "0"]
checkpoint_every_steps = 300
""")
    return cfg, Path("test_small") / "soilbin_ci" / "s0.200"


def kill_after_checkpoint(cmd, ckpt, before_kill=None):
    """Runs the sweep `cmd` until `ckpt` holds a checkpoint pair, lets it go on 2 s (calls
    before_kill(pid of the driver) then, if given), SIGKILLs the driver (its children die with it)
    and checks that nothing is left; returns (the pairs' steps, seconds until the kill)."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         start_new_session=True)
    t0 = time.monotonic()
    try:
        pairs = []
        while time.monotonic() - t0 < 240 and p.poll() is None:
            if ckpt.is_dir():
                rig = {m.group(1) for f in os.listdir(ckpt)
                       if (m := re.fullmatch(r"rig-(\d+)\.ckpt", f))}
                lmp = {m.group(1) for f in os.listdir(ckpt)
                       if (m := re.fullmatch(r"liggghts-(\d+)\.restart\.info", f))}
                pairs = sorted(rig & lmp, key=int)
                if pairs:
                    break
            time.sleep(0.2)
        check(pairs, f"no checkpoint pair in {ckpt} after {time.monotonic() - t0:.0f} s "
              f"(driver exit {p.poll()})")
        time.sleep(2.0)  # the attempt goes on past its checkpoint: that part is redone
        if before_kill is not None:
            before_kill(p.pid)
        tree = descendants(p.pid)
        p.kill()  # SIGKILL: the driver's children die with it (PR_SET_PDEATHSIG)
        first = time.monotonic() - t0
        print(p.communicate()[0])
        deadline = time.monotonic() + 10
        while still_alive(tree) and time.monotonic() < deadline:
            time.sleep(0.1)
        check(not still_alive(tree), f"processes left after SIGKILL: {still_alive(tree)}")
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
    return pairs, first


def case_dem_resume(a, work):
    """A DEM point stopped by SIGKILL of the driver after its first checkpoint
    (dem.checkpoint_every_steps = 300) is resumed by the same command: it says "resuming from its
    checkpoint", its run file records /parameters/resume/1, and done.json's wall_time_s is the
    run's (/parameters/run/wall_time: the stopped attempt up to its checkpoint plus the last
    one; the driver's clock for this attempt beside it). test_small at 20 % on the ci bed of
    tests/wheel_cosim (0.05 s of test phase), 1 rank; ~1 min."""
    cfg, rel = resume_config(a, work)
    out = work / "out"
    point = out / rel
    cmd = [a.sweep, str(cfg), "--build-dir", a.build_dir, "--out-dir", str(out)]
    pairs, first = kill_after_checkpoint(cmd, point / "cosim" / "checkpoints")
    print(f"first attempt killed after {first:.1f} s, checkpoints at steps {pairs}")
    check(not (point / "done.json").exists(), "the killed point has a done.json")
    r = run_sweep(a, cfg, "--out-dir", str(out), timeout=600)
    check(r.returncode == 0, "the resumed sweep failed")
    check("resuming from its checkpoint" in r.stdout, "the point was not resumed")
    done = json.loads((point / "done.json").read_text())
    with h5py.File(point / "run.h5", "r") as f:
        run_wall = float(f["parameters/run/wall_time"][()])
        check("parameters/resume/1/step" in f, "the run file records no resume")
        resume_step = int(f["parameters/resume/1/step"][()])
        session_wall = float(f["parameters/resume/1/wall_time"][()])
    print(f"done.json {done}; run/wall_time {run_wall:.3f} s (this session's {session_wall:.3f} s), "
          f"resumed at step {resume_step}")
    check(done.get("resumed_from_checkpoint") is True, "done.json does not say resumed")
    # the driver's own clock (this attempt, with LIGGGHTS' start-up) never equals the rig's record
    # to 1 ms: before the fix wall_time_s was the former
    check(abs(done["wall_time_s"] - run_wall) < 1e-3,
          f"done.json wall_time_s {done['wall_time_s']} != the run file's {run_wall}")
    check(run_wall > session_wall, f"the run file's wall time {run_wall} s does not count the "
          f"attempt before the checkpoint (this session's {session_wall} s)")
    check(done["wall_time_s_this_attempt"] > 0, "done.json lacks this attempt's wall time")
    check(r.stdout.count("in this attempt, resumed from its checkpoint") == 1,
          "the progress line does not give both wall times")


def case_dem_park(a, work):
    """--park on a new machine: the point of dem_resume, run with --archive ARCH, is parked while
    it runs (scripts/park-running PID: its command line with --park) and SIGKILLed after a
    checkpoint; `--archive ARCH --park` keeps its newest checkpoint pair and partial run file
    there (xz-compressed, parked.json last; a second --park changes nothing); a sweep into a new,
    empty output directory with the same archive restores the checkpoint, resumes from it
    (the run file records the parked step) and finishes, and the finished point's archive folder
    then holds no parked copy. A parked record naming another bed: --beds-only removes the
    restored checkpoint with a warning (the point would run from scratch). ~1 min."""
    cfg, rel = resume_config(a, work)
    out1, out2, out3, arch = work / "out1", work / "out2", work / "out3", work / "archive"
    base = [a.sweep, str(cfg), "--build-dir", a.build_dir, "--archive", str(arch)]
    park_running = Path(a.sweep).resolve().parent / "park-running"

    def park_while_running(pid):
        r = subprocess.run([str(park_running), str(pid)], capture_output=True, text=True,
                           timeout=120)
        print(r.stdout, r.stderr)
        check(r.returncode == 0 and f"parked {rel} at step" in r.stdout
              and "--park" in r.stdout, "park-running PID did not park the running point")

    kill_after_checkpoint(base + ["--out-dir", str(out1)], out1 / rel / "cosim" / "checkpoints",
                          before_kill=park_while_running)
    # after the kill: a newer checkpoint (written after park-running's) is parked, or none is
    r = run_sweep(a, cfg, "--out-dir", str(out1), "--archive", str(arch), "--park", timeout=120)
    check(r.returncode == 0 and (f"parked {rel} at step" in r.stdout
                                 or "is parked already" in r.stdout), "--park failed")
    record = json.loads((arch / rel / "parked" / "parked.json").read_text())
    step = record["step"]
    names = sorted(f["path"] for f in record["files"])
    want = sorted(["run.part.h5", f"cosim/checkpoints/rig-{step}.ckpt"]
                  + [f"cosim/checkpoints/liggghts-{step}.restart{x}" for x in ("", ".wheel", ".info")])
    check(names == want, f"parked files {names}, expected {want}")
    for f in record["files"]:
        check((arch / rel / "parked" / f"{f['path']}.xz").is_file(), f"{f['path']}.xz missing")
    check(record["inputs_hash"] and record["bed_sha256"], f"parked.json {record}")
    r = run_sweep(a, cfg, "--out-dir", str(out1), "--archive", str(arch), "--park", timeout=120)
    check(r.returncode == 0 and f"step {step} is parked already" in r.stdout,
          "a second --park re-parked the same step")
    # the progress, read off the real rig's checkpoint (its phase; in the test phase the test time)
    check(re.search(rf"step {step} is parked already \(((release|settle|ramp) phase,|test phase, "
                    r"[\d.]+ of [\d.]+ s, \d+ %;) t [\d.]+ s simulated(, the [\d.]+ s test phase "
                    r"to come)?\)", r.stdout) is not None,
          f"--park names the point's phase and progress ({r.stdout[-300:]})")
    # a new machine: nothing of out1
    r = run_sweep(a, cfg, "--out-dir", str(out2), "--archive", str(arch), timeout=600)
    check(r.returncode == 0, "the sweep resumed from the parked checkpoint failed")
    check(f"its checkpoint at step {step}" in r.stdout and "restored from the archive" in r.stdout
          and "resuming from its checkpoint" in r.stdout, "the parked checkpoint was not resumed")
    with h5py.File(out2 / rel / "run.h5", "r") as f:
        got = int(f["parameters/resume/1/step"][()])
    check(got == step, f"resumed at step {got}, parked {step}")
    check((arch / rel / "done.json").is_file() and not (arch / rel / "parked").exists(),
          "the finished point's archive folder still holds its parked copy (or no done.json)")
    # parked again from out1 (still stopped), then restored onto a 'different' bed
    shutil.rmtree(arch / rel)
    r = run_sweep(a, cfg, "--out-dir", str(out1), "--archive", str(arch), "--park", timeout=120)
    check(r.returncode == 0, "--park failed")
    pj = arch / rel / "parked" / "parked.json"
    record = json.loads(pj.read_text())
    record["bed_sha256"] = {k: "0" * 64 for k in record["bed_sha256"]}
    pj.write_text(json.dumps(record))
    r = run_sweep(a, cfg, "--out-dir", str(out3), "--archive", str(arch), "--beds-only",
                  timeout=120)
    check(r.returncode == 0 and "ran on another preparation of its bed" in r.stdout
          and "it runs from scratch" in r.stdout
          and not (out3 / rel / "cosim" / "checkpoints").exists(),
          "a checkpoint parked on another bed was not refused")


def case_dem_park_unpoured(a, work):
    """A parked point resumes on a new machine without its bed being poured: test_small at 20 %
    on a ci bin recipe (0.20 x 0.10 m, fill 0.025 m: the bed of tests/wheel_cosim), 0.05 s of
    test phase, checkpoints every 300 steps, 1 rank, --archive ARCH (--bed-hold 0); SIGKILLed after a
    checkpoint and parked (parked.json records the bed's sha256 and .vars and the point's
    inputs). Into a new output directory: --dry-run and --estimate pour nothing ("would not
    pour", no bed to prepare); the run says "not poured", resumes at the parked step through
    wheel-cosim --bed-sha256, finishes, and no restart is written; the archived point names the
    bed it ran on. A point that must start from the bed (a second slip) or changed inputs (a
    longer test phase) make it be poured (--dry-run). wheel-cosim --bed-sha256 refuses a run
    from scratch without the restart, and a restart of another sha256. ~1.5 min."""
    repo = dem_repo(a)
    cfg, arch = work / "sweep.toml", work / "archive"
    out1, out2 = work / "out1", work / "out2"

    def write(slips="[0.2]", duration=0.05):
        cfg.write_text(f"""terrain = "dem"
base = "{repo}/inputs/rigs/ci_small_wheel.toml"
wheels = ["test_small"]
soils = [{{ soil = "ci", bin_length = 0.20, bin_width = 0.10, fill_height = 0.025 }}]
slips = {slips}
[override.run]
duration = {duration}
release_gap = 0.002
[dem]
np = 1
bed_np = 1
deck = "{repo}/inputs/examples/in.wheel_coupled"
liggghts_args = ["-var", "output_every", "0"]
checkpoint_every_steps = 300
""")

    write()
    rel = Path("test_small") / "ci" / "s0.200"
    bed = "beds/ci/soilbin_ci.restart"
    kill_after_checkpoint([a.sweep, str(cfg), "--build-dir", a.build_dir, "--archive", str(arch),
                           "--out-dir", str(out1), *NO_BED_HOLD],  # (not what is tested)
                          out1 / rel / "cosim" / "checkpoints")
    check((out1 / bed).is_file(), "the first machine did not pour its bed")
    r = run_sweep(a, cfg, "--out-dir", str(out1), "--archive", str(arch), "--park", timeout=120)
    check(r.returncode == 0 and f"parked {rel} at step" in r.stdout, "--park failed")
    record = json.loads((arch / rel / "parked" / "parked.json").read_text())
    sha = hashlib.sha256((out1 / bed).read_bytes()).hexdigest()
    check(record.get("bed_sha256") == {"soilbin_ci.restart": sha}
          and record.get("bed_vars") == (out1 / f"{bed}.vars").read_text()
          and record.get("point_inputs_sha256") and record.get("point_included_sha256"),
          f"parked.json lacks the bed's sha256 and .vars or the point's inputs: {sorted(record)}")
    # a new machine: nothing of out1
    r = run_sweep(a, cfg, "--out-dir", str(out2), "--archive", str(arch), "--dry-run", timeout=120)
    check(r.returncode == 0 and "bed ci: would not pour: its 1 point(s) to run resume from "
          "checkpoints parked on it" in r.stdout and "would prepare" not in r.stdout,
          "--dry-run would pour the bed of a parked point")
    r = run_sweep(a, cfg, "--out-dir", str(out2), "--archive", str(arch), "--estimate",
                  timeout=120)
    check(r.returncode == 0 and "estimate: bed ci" not in r.stdout,
          "--estimate prices the pour of a parked point's bed (or its bed-hold check)")
    r = run_sweep(a, cfg, "--out-dir", str(out2), "--archive", str(arch), timeout=600)
    check(r.returncode == 0 and "bed ci: not poured" in r.stdout
          and "resuming from its checkpoint" in r.stdout and "preparing" not in r.stdout,
          "the parked point did not resume without its bed")
    check(not (out2 / bed).exists() and not (out2 / "beds" / "ci" / "soilbin.log").exists(),
          "a bed was poured on the new machine")
    check(json.loads((out2 / rel / "done.json").read_text())["exit_status"] == 0,
          "the resumed point did not finish")
    with h5py.File(out2 / rel / "run.h5", "r") as f:
        got = int(f["parameters/resume/1/step"][()])
    check(got == record["step"], f"resumed at step {got}, parked {record['step']}")
    archived = json.loads((arch / rel / "archived.json").read_text())
    check(archived["bed_sha256"] == {"soilbin_ci.restart": sha},
          f"the archived point names bed {archived['bed_sha256']}, it ran on {sha}")
    # parked again from out1 (still stopped): a point that must start, or changed inputs, pour it
    shutil.rmtree(arch / rel)
    r = run_sweep(a, cfg, "--out-dir", str(out1), "--archive", str(arch), "--park", timeout=120)
    check(r.returncode == 0 and f"parked {rel} at step" in r.stdout, "--park failed")
    out3 = work / "out3"
    for slips, duration, why in (("[0.2, 0.3]", 0.05, "a point that must start from it"),
                                 ("[0.2]", 0.06, "changed inputs")):
        write(slips, duration)
        r = run_sweep(a, cfg, "--out-dir", str(out3), "--archive", str(arch), "--dry-run",
                      timeout=120)
        check(r.returncode == 0 and "bed ci: would prepare" in r.stdout
              and "would not pour" not in r.stdout, f"{why}: the bed would not be poured")
    # wheel-cosim itself: no restart and nothing to resume; a restart of another sha256
    write()
    cosim = Path(a.sweep).resolve().parent / "wheel-cosim"
    base = [str(cosim), "--rig", str(out1 / rel / "rig.toml"), "--deck",
            str(repo / "inputs" / "examples" / "in.wheel_coupled"), "--work", str(work / "w"),
            "--mesh", str(Path(a.build_dir) / "meshes" / "test_small.stl"), "--resume"]
    vars_only = work / "vars_only" / "soilbin_ci.restart"
    vars_only.parent.mkdir()
    shutil.copy(out1 / f"{bed}.vars", f"{vars_only}.vars")
    r = subprocess.run(base + ["--bed", str(vars_only), "--bed-sha256", sha],
                       capture_output=True, text=True, timeout=120)
    check(r.returncode == 2 and "no checkpoint" in r.stderr and "is not here to start from"
          in r.stderr, f"a run from scratch without the restart was not refused: {r.stderr}")
    r = subprocess.run(base + ["--bed", str(out1 / bed), "--bed-sha256", "0" * 64],
                       capture_output=True, text=True, timeout=120)
    check(r.returncode == 2 and "is another bed" in r.stderr,
          f"a restart of another sha256 was not refused: {r.stderr}")


def case_point_archive(a, work):
    """--archive DIR: each finished point's done.json, run.h5, rig.toml and run.log are kept in
    DIR with an archived.json record; a fresh output directory run with the same archive gets them
    back and skips them (run files byte for byte); a point finished without --archive is added to
    the archive on the next run with it; a restored point whose inputs changed is run again and
    its archived files replaced."""
    cfg = work / "sweep.toml"
    sweep_config(cfg, a.build_dir, slips=[0.1, 0.25], wheels='["wheel1"]')
    out1, out2, arch = work / "out1", work / "out2", work / "archive"
    r = run_sweep(a, cfg, "--out-dir", str(out1), "--archive", str(arch))
    check(r.returncode == 0, "first sweep failed")
    points = ["wheel1/mu05/s0.100", "wheel1/mu05/s0.250"]
    got = sorted(str(d.parent.relative_to(arch)) for d in arch.rglob("done.json"))
    check(got == points, f"archived {got}, expected {points}")
    for rel in points:
        kept = sorted(f.name for f in (arch / rel).iterdir())
        check(kept == ["archived.json", "done.json", "rig.toml", "run.h5", "run.log"],
              f"{rel}: archived files {kept}")
        record = json.loads((arch / rel / "archived.json").read_text())
        check(record["bed_sha256"] == {} and len(record["git_commit"]) in (7, 40, len("unknown"))
              and record["archived_utc"].endswith("Z"), f"{rel}: archived.json {record}")
    for rel in points:  # the archived run file: compressed, the same contents
        with h5py.File(out1 / rel / "run.h5", "r") as f0, h5py.File(arch / rel / "run.h5", "r") as f1:
            names = []
            f0.visit(names.append)
            for name in names:
                if isinstance(f0[name], h5py.Dataset):
                    x0, x1 = f0[name][()], f1[name][()]
                    numeric = np.asarray(x0).dtype.kind in "fc"
                    check(f0[name].dtype == f1[name].dtype
                          and np.array_equal(x0, x1, equal_nan=numeric),
                          f"{rel}: archived run.h5 differs in {name}")
                a0, a1 = f0[name].attrs, f1[name].attrs
                check(sorted(a0) == sorted(a1)
                      and all(np.array_equal(a0[k], a1[k]) for k in a0),
                      f"{rel}: archived run.h5 attributes differ in {name}")
            check(f1["observables/drawbar_pull/value"].compression == "gzip",
                  f"{rel}: archived run.h5 not compressed")
    r = run_sweep(a, cfg, "--out-dir", str(out2), "--archive", str(arch))
    check(r.returncode == 0 and "restored 2 finished point(s)" in r.stdout
          and "skipping 2 finished point(s)" in r.stdout and "[started" not in r.stdout,
          "the archived points were not restored and skipped")
    for rel in points:
        check((out2 / rel / "run.h5").read_bytes() == (arch / rel / "run.h5").read_bytes(),
              f"{rel}: run.h5 differs from the archived one")
    r = run_sweep(a, cfg, "--out-dir", str(work / "dry"), "--archive", str(arch), "--dry-run")
    check(r.returncode == 0 and "2 finished" in r.stdout and not (work / "dry").exists(),
          "--dry-run with --archive: the archived points are not counted finished, or it wrote")
    sweep_config(cfg, a.build_dir, slips=[0.1, 0.25, 0.5], wheels='["wheel1"]')
    check(run_sweep(a, cfg, "--out-dir", str(out2)).returncode == 0, "sweep without --archive")
    check(not (arch / "wheel1/mu05/s0.500").exists(), "archived without --archive")
    r = run_sweep(a, cfg, "--out-dir", str(out2), "--archive", str(arch))
    check(r.returncode == 0 and "archived 1 finished point(s) the archive lacked" in r.stdout
          and (arch / "wheel1/mu05/s0.500/run.h5").is_file() and "[started" not in r.stdout,
          "a point finished without --archive was not added to the archive")
    before = (arch / points[0] / "done.json").read_text()
    sweep_config(cfg, a.build_dir, duration=0.15, slips=[0.1], wheels='["wheel1"]')
    out3 = work / "out3"
    r = run_sweep(a, cfg, "--out-dir", str(out3), "--archive", str(arch))
    check(r.returncode == 0 and "restored" not in r.stdout
          and "inputs changed since it finished" in r.stdout and "[started 1/1]" in r.stdout,
          "an archived point with changed inputs was not run again")
    check((arch / points[0] / "done.json").read_text() != before,
          "the archive still holds the point's old result")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case")
    ap.add_argument("--sweep", required=True)
    ap.add_argument("--build-dir", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    build = Path(a.build_dir)
    for need in (build / "bin" / "wheel-rig", build / "meshes" / "wheel1.stl",
                 build / "meshes" / "test_small.stl"):
        if not need.exists():
            print(f"SKIP: {need} not built (cmake --build {build} --target wheel-rig wheel_meshes)")
            return SKIP
    work = Path(a.work)
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    try:
        globals()[f"case_{a.case}"](a, work)
    except Fail as e:
        print(f"FAIL: {a.case}: {e}")
        return 1
    except Skip as e:
        print(f"SKIP: {a.case}: {e}")
        return SKIP
    print(f"PASS: {a.case}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
