#!/usr/bin/python3
"""ctest driver for the coupled runs (real wheel-rig, real LIGGGHTS, real ZeroMQ sockets).

  run_cosim_case.py MODE --root REPO --build BUILD --bed BED.restart --work DIR [--np N]

MODE
  compare        the coupled run (scripts/wheel-cosim, rig --kinematic with a fixed twist) and
                 the same deck with motion prescribed give the same thermo rows (force, torque,
                 contacts, centre) to --tol relative, step by step.
  kill_rig       the rig is SIGKILLed mid-run: LIGGGHTS must stop with an error naming the rig
                 and the awaited Pose within its timeout (+ margin).
  kill_liggghts  LIGGGHTS is SIGKILLed mid-run: the rig must stop with an error naming LIGGGHTS
                 and the awaited Wrench (or the Pose it could not send) within its timeout
                 (+ margin), and its run file must read
                 back (h5py) with the rows of its last flush.
  launcher_fail  scripts/wheel-cosim with a rig config that the rig rejects exits 2 with the
                 rig's message before starting either side (wheel-rig --check; no LIGGGHTS log).
  dt_from_bed    a rig config without run.dt: wheel-cosim takes the bed's time step (bed_dt of
                 its .vars) for both sides; the run file records it and its source. Its work
                 dir is too deep for <work>/rig.sock (over 107 bytes): the socket goes to a
                 short private dir under TMPDIR, removed at the end.
  cost_recorded  the run file of a coupled run records its cost for `wheelsim-post results`:
                 /parameters/liggghts/atoms and atoms_start = the bed's sphere count (the bed's
                 own log, 'soilbin: spheres = N'; none lost), liggghts/np = --np,
                 run/wall_time in (0, the launcher's elapsed time]; and, its rig config setting run.dt, that dt and
                 "the rig config's run.dt" as its source (launcher line and run file).
"""
import argparse
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from wheelsim_post import liggghts_log  # noqa: E402  (the shared thermo-table parser)

TIMEOUT_S = 3.0   # coupling timeout used by the fault tests [s]
MARGIN_S = 10.0   # process start-up and MPI shutdown allowance on a loaded 2-core machine [s]


def rig_config(a, name, **changes):
    """A copy of inputs/rigs/ci_small_wheel.toml with some values changed (key = value lines)."""
    text = open(os.path.join(a.root, "inputs", "rigs", "ci_small_wheel.toml")).read()
    for key, value in changes.items():
        text, n = re.subn(rf"(?m)^{key}\s*=.*$", f"{key} = {value}", text)
        if n != 1:
            raise SystemExit(f"run_cosim_case: key {key} not found once in the rig config")
    path = os.path.join(a.work, name)
    open(path, "w").write(text)
    return path


def mpirun(a):
    cmd = ["mpirun", "-np", str(a.np), "--oversubscribe"]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd


def thermo_rows(text):
    """{step: [the fix's columns]} of in.motion_compare's thermo tables (step atoms f_wheel[...])."""
    return {int(r[0]): r[2:] for t in liggghts_log.thermo(text)
            if t.columns[2:3] == ["wheel[1]"] for r in t.rows}


def compare(a):
    twist = "0.1125 0 -0.2 0 1.5 0"
    deck = os.path.join(a.root, "tests", "cosim", "in.motion_compare")
    rig = rig_config(a, "rig.toml", duration="100.0")
    coupled = subprocess.run(
        [os.path.join(a.root, "scripts", "wheel-cosim"), "--rig", rig, "--bed", a.bed,
         "--deck", deck, "--np", str(a.np), "--work", os.path.join(a.work, "coupled"),
         "--kinematic", twist, "--", "-var", "motion", "coupled", "-var", "steps", str(a.steps),
         "-var", "exchange_every", str(a.exchange_every)],
        capture_output=True, text=True, timeout=600)
    if coupled.returncode != 0:
        print(coupled.stdout[-3000:], coupled.stderr[-3000:])
        print("run_cosim_case: coupled run failed FAIL")
        return 1
    coupled_rows = thermo_rows(open(os.path.join(a.work, "coupled", "liggghts.log"), errors="replace").read())
    dt = re.search(r"dt (\S+) s", coupled.stdout).group(1)
    prescribed = subprocess.run(
        mpirun(a) + [os.path.join(a.build, "bin", "liggghts-wheel"), "-in", deck, "-log", "none",
                     "-var", "inputs_dir", os.path.join(a.root, "inputs"), "-var", "restart", a.bed,
                     "-var", "mesh", os.path.join(a.build, "meshes", "test_small.stl"),
                     "-var", "motion", "prescribed", "-var", "dt", dt, "-var", "steps",
                     str(a.steps)],
        capture_output=True, text=True, timeout=600, cwd=a.work)
    if prescribed.returncode != 0:
        print(prescribed.stdout[-3000:], prescribed.stderr[-3000:])
        print("run_cosim_case: prescribed run failed FAIL")
        return 1
    prescribed_rows = thermo_rows(prescribed.stdout)
    steps = sorted(set(coupled_rows) & set(prescribed_rows))
    if len(steps) < a.steps:
        print(f"run_cosim_case: only {len(steps)} common thermo rows FAIL")
        return 1
    worst, worst_step, contacts = 0.0, None, 0
    for s in steps:
        c, p = coupled_rows[s], prescribed_rows[s]
        contacts = max(contacts, p[6])
        for i in range(len(c)):
            scale = max(abs(p[i]), 1e-3 if i < 6 else 1e-6)
            d = abs(c[i] - p[i]) / scale
            if d > worst:
                worst, worst_step = d, s
    ok = worst <= a.tol and contacts >= 20  # the wheel must really be in the bed
    print(f"run_cosim_case: {len(steps)} steps, up to {contacts:.0f} contacts; max relative "
          f"difference {worst:.3e} (step {worst_step}); tolerance {a.tol} "
          f"{'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


def start_pair(a, rig, steps):
    """Starts the rig and LIGGGHTS (not through the launcher, to kill them one by one)."""
    endpoint = "ipc://" + os.path.join(a.work, "rig.sock")
    vars_text = open(a.bed + ".vars").read()
    surface = re.search(r"variable bed_depth index (\S+)", vars_text).group(1)
    rig_log = open(os.path.join(a.work, "rig.log"), "w")
    rig_proc = subprocess.Popen(
        [os.path.join(a.build, "bin", "wheel-rig"), "--config", rig, "--endpoint", endpoint,
         "--surface-height", surface, "--out", os.path.join(a.work, "run.h5")],
        stdout=rig_log, stderr=subprocess.STDOUT)
    lmp_log = open(os.path.join(a.work, "liggghts.log"), "w")
    deck = os.path.join(a.root, "inputs", "examples", "in.wheel_coupled")
    lmp_proc = subprocess.Popen(
        mpirun(a) + [os.path.join(a.build, "bin", "liggghts-wheel"), "-in", deck, "-log", "none",
                     "-var", "inputs_dir", os.path.join(a.root, "inputs"), "-var", "restart",
                     a.bed, "-var", "mesh", os.path.join(a.build, "meshes", "test_small.stl"),
                     "-var", "endpoint", endpoint, "-var", "timeout", str(TIMEOUT_S),
                     "-var", "dt", "4.89543219523472e-05", "-var", "output_every", "0"],
        stdout=lmp_log, stderr=subprocess.STDOUT, cwd=a.work, start_new_session=True)
    return rig_proc, lmp_proc


def wait_for_progress(path, pattern, limit_s):
    t0 = time.time()
    while time.time() - t0 < limit_s:
        if os.path.exists(path) and re.search(pattern, open(path, errors="replace").read()):
            return True
        time.sleep(0.2)
    return False


def start_running_pair(a):
    """Starts the rig and LIGGGHTS with the fault tests' short timeout and waits until the run is
    under way; returns (rig, liggghts) processes, or None (both stopped) if it never started."""
    rig = rig_config(a, "rig.toml", timeout=TIMEOUT_S, progress_interval="0.5",
                     flush_interval="200")
    rig_proc, lmp_proc = start_pair(a, rig, 100000)
    if not wait_for_progress(os.path.join(a.work, "rig.log"), r"t = 0\.0[2-9]", 120):
        rig_proc.kill(); os.killpg(lmp_proc.pid, signal.SIGKILL)
        print("run_cosim_case: the coupled run did not start FAIL")
        return None
    return rig_proc, lmp_proc


def kill_rig(a):
    pair = start_running_pair(a)
    if pair is None:
        return 1
    rig_proc, lmp_proc = pair
    rig_proc.send_signal(signal.SIGKILL)
    t_kill = time.time()
    try:
        rc = lmp_proc.wait(timeout=TIMEOUT_S + MARGIN_S)
    except subprocess.TimeoutExpired:
        os.killpg(lmp_proc.pid, signal.SIGKILL)
        print(f"run_cosim_case: LIGGGHTS still running {TIMEOUT_S + MARGIN_S} s after the rig "
              "died FAIL")
        return 1
    elapsed = time.time() - t_kill
    log = open(os.path.join(a.work, "liggghts.log"), errors="replace").read()
    m = re.search(r"ERROR[^\n]*coupling with the rig failed[^\n]*", log)
    ok = rc != 0 and m is not None and "Pose" in m.group(0) and "the rig" in m.group(0)
    print(f"run_cosim_case: LIGGGHTS exited {rc} {elapsed:.1f} s after the rig was killed "
          f"(timeout {TIMEOUT_S} s): {m.group(0) if m else 'no coupling error message'} "
          f"{'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


def kill_liggghts(a):
    pair = start_running_pair(a)
    if pair is None:
        return 1
    rig_proc, lmp_proc = pair
    os.killpg(lmp_proc.pid, signal.SIGKILL)  # mpirun and every rank
    lmp_proc.wait()
    t_kill = time.time()
    try:
        rc = rig_proc.wait(timeout=TIMEOUT_S + MARGIN_S)
    except subprocess.TimeoutExpired:
        rig_proc.kill()
        print("run_cosim_case: the rig still running after LIGGGHTS died FAIL")
        return 1
    elapsed = time.time() - t_kill
    log = open(os.path.join(a.work, "rig.log"), errors="replace").read()
    m = re.search(r"wheel-rig: error:[^\n]*", log)
    # Where the kill lands decides which of the rig's two waits notices it: the receive of the
    # next Wrench ("no Wrench for step N from LIGGGHTS ... within T s") or, when the rig was
    # between a Wrench and its Pose, the send of that Pose ("sending Pose for step N: could not
    # hand a message to LIGGGHTS ... no peer connected"), or a receive that fails outright
    # ("receiving Wrench for step N from LIGGGHTS ... failed"). Each is the right error.
    ok = (rc != 0 and m is not None and "LIGGGHTS" in m.group(0)
          and any(k in m.group(0) for k in ("no Wrench", "receiving Wrench", "sending Pose")))
    import h5py
    with h5py.File(os.path.join(a.work, "run.h5"), "r") as f:
        steps = f["observables/slip/step"][:]
        rows = int((steps >= 0).sum())
        creator = f["h5md/creator"].attrs["name"]
        # the DEM run's health (docs/run-health.md): unhealthy, the failure recorded
        status = f["health"].attrs["status"] if "health" in f else None
        findings = ([(c.decode(), msg.decode()) for c, msg in
                     zip(f["health/code"][()], f["health/message"][()])] if "health" in f else [])
    failed = [msg for code, msg in findings if code == "run_failed"]
    ok = (ok and rows >= 200 and status == "unhealthy" and len(failed) == 1
          and "LIGGGHTS" in failed[0])
    print(f"run_cosim_case: the rig exited {rc} {elapsed:.1f} s after LIGGGHTS was killed "
          f"(timeout {TIMEOUT_S} s): {m.group(0) if m else 'no error message'}; run file by "
          f"{creator!s} reads back with {rows} rows; /health {status}, run_failed {failed} "
          f"{'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


def launcher_fail(a):
    rig = rig_config(a, "rig.toml", spring_k="-3.0")
    r = subprocess.run(
        [os.path.join(a.root, "scripts", "wheel-cosim"), "--rig", rig, "--bed", a.bed, "--deck",
         os.path.join(a.root, "inputs", "examples", "in.wheel_coupled"), "--work",
         os.path.join(a.work, "run")], capture_output=True, text=True, timeout=300)
    text = r.stdout + r.stderr
    # the launcher checks the rig config (wheel-rig --check) before it starts either side: exit 2
    # with the rig's message, and no LIGGGHTS run (no log of it in the work dir)
    ok = (r.returncode == 2 and "--rig: wheel-rig: " in text
          and "spring_k must be > 0 N/m, got -3" in text
          and not os.path.exists(os.path.join(a.work, "run", "log.liggghts")))
    print(text[-1500:])
    print(f"run_cosim_case: launcher exit {r.returncode} {'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


def dt_from_bed(a):
    rig = rig_config(a, "rig.toml", duration="100.0")
    text, n = re.subn(r"(?m)^dt\s*=.*\n", "", open(rig).read())
    if n != 1:
        raise SystemExit("run_cosim_case: no run.dt line in the rig config")
    open(rig, "w").write(text)
    # A work dir deep enough that <work>/rig.sock is over the 107-byte socket-path limit:
    # wheel-cosim must put the socket in a short private dir and remove it afterwards.
    work = os.path.join(os.path.abspath(a.work), "deep_" + "d" * 100, "run")
    bed_dt = re.search(r"(?m)^variable bed_dt index (\S+)", open(a.bed + ".vars").read()).group(1)
    run = subprocess.run(
        [os.path.join(a.root, "scripts", "wheel-cosim"), "--rig", rig, "--bed", a.bed,
         "--deck", os.path.join(a.root, "tests", "cosim", "in.motion_compare"), "--np",
         str(a.np), "--work", work, "--kinematic", "0.1125 0 -0.2 0 1.5 0",
         "--", "-var", "motion", "coupled", "-var", "steps", str(a.steps)],
        capture_output=True, text=True, timeout=600)
    print(run.stdout[-2000:], run.stderr[-2000:])
    import h5py

    m = re.search(r"endpoint ipc://(\S+)/rig\.sock;", run.stdout)
    socket_dir = m.group(1) if m else None
    short_socket = (socket_dir is not None and len(socket_dir) + 9 <= 107
                    and not os.path.exists(socket_dir))
    print(f"run_cosim_case: work dir {len(work)} bytes; socket dir {socket_dir} "
          f"({'short and removed' if short_socket else 'NOT short and removed'})")
    with h5py.File(os.path.join(work, "run.h5"), "r") as f:
        dt = float(f["parameters/run/dt"][()])
        source = f["parameters/run/dt_source"].asstr()[()]
        steps = len(f["observables/wheel/position/step"])
        # --kinematic records the box frame itself: its origin is (0, 0)
        origin = (float(f["parameters/coupling/origin_x"][()]),
                  float(f["parameters/coupling/origin_y"][()]))
    ok = (run.returncode == 0 and f"dt {bed_dt} s from the bed's time step" in run.stdout
          and dt == float(bed_dt) and "--dt" in source and steps >= a.steps and short_socket
          and origin == (0.0, 0.0))
    print(f"run_cosim_case: --kinematic positions' origin {origin} m (expected (0, 0))")
    print(f"run_cosim_case: bed_dt {bed_dt} s, run file dt {dt!r} s from '{source}', {steps} rows "
          f"{'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


def cost_recorded(a):
    rig = rig_config(a, "rig.toml", duration="100.0")
    bed_dir = os.path.dirname(os.path.abspath(a.bed))
    spheres = None
    for name in sorted(os.listdir(bed_dir)):
        if name.startswith("log."):
            text = open(os.path.join(bed_dir, name)).read()
            m = re.search(r"(?m)^soilbin: spheres = (\d+)", text)
            spheres = int(m.group(1)) if m else spheres
    if spheres is None:
        print(f"run_cosim_case: no 'soilbin: spheres = N' in a log.* of {bed_dir}")
        return 1
    start = time.monotonic()
    run = subprocess.run(
        [os.path.join(a.root, "scripts", "wheel-cosim"), "--rig", rig, "--bed", a.bed,
         "--deck", os.path.join(a.root, "tests", "cosim", "in.motion_compare"), "--np",
         str(a.np), "--work", os.path.join(a.work, "run"), "--kinematic", "0.1125 0 -0.2 0 1.5 0",
         "--", "-var", "motion", "coupled", "-var", "steps", str(a.steps)],
        capture_output=True, text=True, timeout=600,
        env=dict(os.environ, WHEELSIM_BUILD_DIR=a.build))
    elapsed = time.monotonic() - start
    print(run.stdout[-2000:], run.stderr[-2000:])
    import h5py

    with h5py.File(os.path.join(a.work, "run", "run.h5"), "r") as f:
        p = f["parameters"]
        atoms = int(p["liggghts/atoms"][()]) if "liggghts/atoms" in p else None
        atoms_start = int(p["liggghts/atoms_start"][()]) if "liggghts/atoms_start" in p else None
        ranks = p["liggghts/np"].asstr()[()] if "liggghts/np" in p else None
        wall = float(p["run/wall_time"][()]) if "run/wall_time" in p else None
        dt = float(p["run/dt"][()])
        dt_source = p["run/dt_source"].asstr()[()]
    # the rig config sets run.dt: both sides use it, and the launcher and run file say so
    rig_dt = float(re.search(r"(?m)^dt\s*=\s*(\S+)", open(rig).read()).group(1))
    dt_ok = (dt == rig_dt and dt_source == "the rig config's run.dt"
             and f"dt {rig_dt!r} s from the rig config's run.dt" in run.stdout)
    ok = (run.returncode == 0 and atoms == spheres and atoms_start == spheres
          and ranks == str(a.np)
          and wall is not None and 0.0 < wall <= elapsed and dt_ok)
    print(f"run_cosim_case: atoms {atoms}, at the start {atoms_start} (bed: {spheres} spheres), "
          f"np {ranks} (--np {a.np}), "
          f"wall_time {wall} s (launcher {elapsed:.2f} s), dt {dt!r} s from '{dt_source}' "
          f"(rig config {rig_dt!r}) {'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


def active_coupled(a):
    """The wheel deck (inputs/examples/in.wheel_coupled) with the active domain and its active
    group (active_fixes 1: gravity, walls and integrator redeclared on act_active): the coupled
    run completes, soil far from the wheel is frozen, and the run file has its test phase and
    the domain's sinkage allowance (/parameters/liggghts/active_sinkage_allowance)."""
    rig = rig_config(a, "rig.toml", duration="0.02")
    work = os.path.join(os.path.abspath(a.work), "run")
    run = subprocess.run(
        [os.path.join(a.root, "scripts", "wheel-cosim"), "--rig", rig, "--bed", a.bed,
         "--deck", os.path.join(a.root, "inputs", "examples", "in.wheel_coupled"), "--np",
         str(a.np), "--work", work, "--no-checkpoints",
         "--", "-var", "active_domain", "1", "-var", "active_args", "distance 0.03",
         "-var", "output_every", "0"],
        capture_output=True, text=True, timeout=600,
        env=dict(os.environ, WHEELSIM_BUILD_DIR=a.build))
    print(run.stdout[-2000:], run.stderr[-2000:])
    screen = ""
    for name in ("liggghts.log", "log.liggghts"):
        path = os.path.join(work, name)
        if os.path.exists(path):
            screen += open(path, errors="replace").read()
    m = re.search(r"([0-9.]+) of ([0-9.]+) particles active on average", screen)
    import h5py

    rows, recorded, origin, x_first = 0, None, None, None
    if os.path.exists(os.path.join(work, "run.h5")):
        with h5py.File(os.path.join(work, "run.h5"), "r") as f:
            rows = len(f["observables/wheel/position/step"])
            name = "parameters/liggghts/active_sinkage_allowance"
            recorded = float(f[name][()]) if name in f else None
            # the rig records x from the wheel's start and the start itself (hdf5-layout.md)
            if "parameters/coupling/origin_x" in f:
                origin = (float(f["parameters/coupling/origin_x"][()]),
                          float(f["parameters/coupling/origin_y"][()]))
            x_first = float(f["observables/wheel/position/value"][0, 0]) if rows else None
    frozen = m is not None and float(m.group(1)) < float(m.group(2))
    regrouped = "unfix wall_z0" in screen or "act_active" in screen
    # The sinkage allowance of 'distance 0.03' (the sinkage whose default distance 0.5 R + 2 z it
    # is, at least 0), as the fix prints it and wheel-cosim records it in the run file.
    radius = re.search(r"wheel/active \S+: wheel \S+ \(bounding radius ([0-9.e+-]+) m\)", screen)
    expected = max(0.0, (0.03 - 0.5 * float(radius.group(1))) / 2) if radius else None
    allowance_ok = (recorded is not None and expected is not None
                    and abs(recorded - expected) <= 1e-4 * max(1.0, expected))
    # in.wheel_coupled's default x0 0.10 m: the wheel starts there in the box, at x = 0 recorded
    origin_ok = origin == (0.10, 0.0) and x_first is not None and abs(x_first) < 1e-12
    ok = run.returncode == 0 and frozen and rows > 0 and allowance_ok and origin_ok
    print(f"run_cosim_case: positions' origin in the box {origin} m (expected (0.1, 0.0)), first "
          f"recorded x {x_first} m (expected 0)")
    print(f"run_cosim_case: exit {run.returncode}; active on average "
          f"{m.group(1) + ' of ' + m.group(2) if m else 'not reported'}; run file rows {rows}; "
          f"active group in the log: {regrouped}; sinkage allowance recorded {recorded} m, "
          f"expected {expected} m {'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


def main():
    p = argparse.ArgumentParser()
    p.add_argument("mode", choices=["compare", "kill_rig", "kill_liggghts", "launcher_fail",
                                    "dt_from_bed", "cost_recorded", "active_coupled"])
    p.add_argument("--root", required=True)
    p.add_argument("--build", required=True)
    p.add_argument("--bed", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--steps", type=int, default=400)
    p.add_argument("--tol", type=float, default=1e-9)
    p.add_argument("--exchange-every", type=int, default=1)
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    return {"compare": compare, "kill_rig": kill_rig, "kill_liggghts": kill_liggghts,
            "launcher_fail": launcher_fail, "dt_from_bed": dt_from_bed,
            "cost_recorded": cost_recorded, "active_coupled": active_coupled}[a.mode](a)


if __name__ == "__main__":
    sys.exit(main())
