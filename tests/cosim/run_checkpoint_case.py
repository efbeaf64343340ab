#!/usr/bin/python3
"""ctest driver for checkpoint and resume of a coupled run (docs/coupled-runs.md, "Checkpoint and
resume"): real wheel-rig, real LIGGGHTS (np 1 or 2), the launcher.

  run_checkpoint_case.py --root REPO --build BUILD --bed BED.restart --work DIR [--np N]
                         [--every STEPS] [--pos-tol M] [--mean-tol REL]

1. reference: an uninterrupted run (scripts/wheel-cosim, checkpoints every --every steps; the rig
   of inputs/rigs/ci_small_wheel.toml with a 0.05 s test phase: release, settle, ramp and test).
2. killed: the same run, SIGKILLed (the rig and every LIGGGHTS rank) once its first checkpoint
   pair of the test phase is complete (found in the reference's rig.log); the LIGGGHTS half of
   that newest pair is then deleted, as if the kill had hit LIGGGHTS while it wrote it, so the
   resume must fall back to the pair before it (ramp or test phase) while the run file holds
   committed rows up to the newest: rows after the checkpoint must be discarded.
3. bad inputs, each on a copy of the killed run's work dir, each refused with a message naming
   what differs: no LIGGGHTS half at all; the rig config changed (inputs hash); the halves' inputs
   hashes differ; a LIGGGHTS restart of another step under the checkpoint's name (the launcher
   sees its .info; with a forged .info the rig refuses LIGGGHTS' start step at the handshake).
4. resumed: scripts/wheel-cosim --resume finishes the run. Its run file must look like the
   reference's: every observable with the same steps and times (continuous: no gap, no repeated
   row); every value before the checkpoint and in the checkpoint's row (the wrench LIGGGHTS
   computed in that step, the rig's state) identical; after it (LIGGGHTS' restart is not bit for
   bit) the wheel centre within --pos-tol and the means over the resumed part of the contact
   force and torque, drawbar pull, driving torque and sinkage within --mean-tol;
   /parameters/resume/1/step = the checkpoint's step; /health as the reference's. The
   differences are printed (MEASURED lines).
5. `wheelsim-post surface` reads the newest LIGGGHTS checkpoint (set aside in 2.): its step, the
   bed's sphere count, the wheel centre placed in the box.
"""
import argparse
import glob
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np


def rig_config(a, path, **changes):
    text = open(os.path.join(a.root, "inputs", "rigs", "ci_small_wheel.toml")).read()
    for key, value in changes.items():
        text, n = re.subn(rf"(?m)^{key}\s*=.*$", f"{key} = {value}", text)
        if n != 1:
            raise SystemExit(f"run_checkpoint_case: key {key} not found once in the rig config")
    open(path, "w").write(text)
    return path


def cosim(a, work, rig, *extra):
    return [os.path.join(a.root, "scripts", "wheel-cosim"), "--rig", rig, "--bed", a.bed,
            "--deck", os.path.join(a.root, "inputs", "examples", "in.wheel_coupled"),
            "--np", str(a.np), "--work", work, "--checkpoint-every-steps", str(a.every),
            *extra, "--", "-var", "output_every", "0"]


def env(a):
    e = dict(os.environ)
    e["WHEELSIM_BUILD_DIR"] = a.build
    return e


def descendants(pid):
    """Every process below pid (from /proc), children first found breadth-first."""
    children = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                ppid = int(open(f"/proc/{d}/stat").read().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(d))
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        for c in children.get(p, []):
            out.append(c)
            todo.append(c)
    return out


def comm(pid):
    try:
        return open(f"/proc/{pid}/comm").read().strip()
    except OSError:
        return ""


def complete_pairs(ckpt):
    rig = {int(m.group(1)) for f in os.listdir(ckpt) if (m := re.fullmatch(r"rig-(\d+)\.ckpt", f))}
    lmp = {int(m.group(1)) for f in os.listdir(ckpt)
           if (m := re.fullmatch(r"liggghts-(\d+)\.restart\.info", f))}
    return sorted(rig & lmp)


def read_run(path):
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Group) and "step" in obj and "value" in obj:
                out[name] = (obj["step"][()], obj["time"][()], obj["value"][()])
        f["observables"].visititems(visit)
        health = f["health"].attrs["status"] if "health" in f else None
        codes = [c.decode() for c in f["health/code"][()]] if "health" in f else []
        resume = {k: f[f"parameters/resume/1/{k}"][()] for k in ("step", "time", "wall_time")} \
            if "parameters/resume/1" in f else None
        if resume is not None:
            resume["run_wall_time"] = f["parameters/run/wall_time"][()]
    return out, health, codes, resume


def expect_refused(a, name, cmd, needle):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env(a))
    text = r.stdout + r.stderr
    ok = r.returncode != 0 and needle in text
    print(f"bad input '{name}': exit {r.returncode}, message "
          f"{'names' if needle in text else 'does NOT name'} '{needle}' {'ok' if ok else 'FAIL'}")
    if not ok:
        print(text[-2500:])
    return ok


def surface_of_checkpoint(a, restart, step, run):
    """5. `wheelsim-post surface` reads a LIGGGHTS checkpoint of a coupled run (the newest one, set
    aside in 2.; docs/postprocess.md "surface"): its step, the bed's sphere count, and the wheel
    centre placed in the box from the run file (recorded x + coupling/origin_x at that step)."""
    import h5py

    with h5py.File(run, "r") as f:
        g = f["observables/wheel/position"]
        x = float(g["value"][list(g["step"][()]).index(step), 0])
        x_box = x + float(f["parameters/coupling/origin_x"][()])
    r = subprocess.run(
        ["/usr/bin/python3", os.path.join(a.root, "postprocess", "wheelsim-post"), "surface",
         restart, "--bed-vars", a.bed + ".vars", "--reference", a.bed, "--run", run,
         "--build-dir", a.build], capture_output=True, text=True, timeout=300, env=env(a))
    print(r.stdout[-1500:], r.stderr[-1500:])
    bed = re.search(r"(?m)^soilbin: spheres = (\d+)", "".join(
        open(q).read() for q in glob.glob(os.path.join(os.path.dirname(a.bed), "log.*"))))
    read = re.search(r": step (\d+), (\d+) spheres;", r.stdout)
    shown = re.search(r"wheel centre at x = (\S+) m", r.stdout)
    # every sphere of the bed (a coupled run may lose a few grains over the box's top: 1 %)
    ok = (r.returncode == 0 and bed is not None and read is not None and shown is not None
          and int(read.group(1)) == step
          and 0.99 * int(bed.group(1)) <= int(read.group(2)) <= int(bed.group(1))
          and abs(float(shown.group(1)) - x_box) < 1e-4)
    print(f"run_checkpoint_case: surface of the checkpoint at step {step}: exit {r.returncode}, "
          f"{read and read.group(2)} of the bed's {bed and bed.group(1)} spheres, wheel centre {shown and shown.group(1)} m, expected {x_box:.4f} m (recorded {x:.4f} + "
          f"origin) {'ok' if ok else 'FAIL'}")
    return ok


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--root", required=True)
    p.add_argument("--build", required=True)
    p.add_argument("--bed", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--every", type=int, default=1000, help="steps between checkpoints")
    p.add_argument("--pos-tol", type=float, default=1e-4,
                   help="largest wheel-centre difference after the checkpoint [m]")
    p.add_argument("--mean-tol", type=float, default=0.05,
                   help="relative difference of the means over the resumed part (contact force "
                        "and torque, drawbar pull, driving torque, sinkage)")
    a = p.parse_args()
    if not os.path.exists(a.bed):
        print(f"run_checkpoint_case: bed {a.bed} missing (fixture wheel_cosim_bed) FAIL")
        return 1
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    # release at 0.2 m/s instead of the config's 0.05: the lowering was most of each run's steps,
    # and the checkpoints that matter lie in the ramp and test phases
    rig = rig_config(a, os.path.join(a.work, "rig.toml"), duration="0.05", release_gap="0.002",
                     release_speed="0.2")

    # 1. reference
    ref = os.path.join(a.work, "reference")
    t0 = time.time()
    r = subprocess.run(cosim(a, ref, rig), capture_output=True, text=True, timeout=600, env=env(a))
    if r.returncode != 0:
        print(r.stdout[-3000:], r.stderr[-3000:])
        print("run_checkpoint_case: the reference run failed FAIL")
        return 1
    print(f"reference run: {time.time() - t0:.1f} s")
    # Kill once the first checkpoint of the test phase is complete: the resume then starts from
    # the one before it (ramp or test phase: the wheel turning, contacts with history).
    written = re.findall(r"checkpoint \S+ at step (\d+) \(t = \S+ s, (\w+) phase\)",
                         open(os.path.join(ref, "rig.log")).read())
    kill_after = next((int(s) for s, phase in written if phase == "test"), None)
    if kill_after is None or int(written[0][0]) >= kill_after:
        print(f"run_checkpoint_case: the reference run has no checkpoint in its test phase after "
              f"another one ({written}) FAIL")
        return 1

    # 2. killed after its third complete checkpoint pair
    killed = os.path.join(a.work, "killed")
    ckpt = os.path.join(killed, "checkpoints")
    launcher = subprocess.Popen(cosim(a, killed, rig), stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, env=env(a), start_new_session=True)
    deadline = time.time() + 400
    while time.time() < deadline and launcher.poll() is None:
        if os.path.isdir(ckpt) and kill_after in complete_pairs(ckpt):
            break
        time.sleep(0.02)
    if launcher.poll() is not None or kill_after not in complete_pairs(ckpt):
        print(f"run_checkpoint_case: the run ended or timed out before its checkpoint at step "
              f"{kill_after} FAIL")
        launcher.kill()
        return 1
    victims = [q for q in descendants(launcher.pid) if comm(q) in ("wheel-rig", "liggghts-wheel")]
    for q in victims:
        os.kill(q, signal.SIGKILL)
    launcher.wait(timeout=60)
    print(f"killed {len(victims)} processes (wheel-rig and {len(victims) - 1} LIGGGHTS ranks, "
          f"SIGKILL) after the checkpoints at steps {complete_pairs(ckpt)}")
    if len(victims) != 1 + a.np:
        print(f"run_checkpoint_case: expected to kill 1 rig and {a.np} ranks FAIL")
        return 1
    pairs = complete_pairs(ckpt)
    newest, resume_step = pairs[-1], pairs[-2]
    for f in glob.glob(os.path.join(ckpt, f"liggghts-{newest}.restart*")):
        shutil.move(f, a.work)  # kept aside for the bad-input case of another step
    steps_killed = read_run(os.path.join(killed, "run.h5"))[0]["contact/force"][0]
    print(f"killed run file: {len(steps_killed)} committed rows up to step {steps_killed[-1]}; "
          f"resuming must fall back to step {resume_step} (the newest pair, {newest}, lost its "
          f"LIGGGHTS half)")
    ok = steps_killed[-1] >= resume_step
    if not ok:
        print("run_checkpoint_case: the killed run file holds no row after the checkpoint FAIL")

    # 3. bad inputs, on copies
    def copy(name):
        d = os.path.join(a.work, name)
        shutil.copytree(killed, d, symlinks=True, ignore=shutil.ignore_patterns("*.sock"))
        return d
    d = copy("bad_missing")
    for f in glob.glob(os.path.join(d, "checkpoints", "liggghts-*")):
        os.remove(f)
    ok &= expect_refused(a, "no LIGGGHTS half", cosim(a, d, rig, "--resume"),
                         "LIGGGHTS halves (restart + .wheel + .info) at steps none")
    d = copy("bad_config")
    rig2 = rig_config(a, os.path.join(a.work, "rig_changed.toml"), duration="0.05",
                      release_gap="0.002", release_speed="0.2", spring_c="31.0")
    ok &= expect_refused(a, "rig config changed", cosim(a, d, rig2, "--resume"),
                         "an input changed")
    d = copy("bad_hash")
    info = os.path.join(d, "checkpoints", f"liggghts-{resume_step}.restart.info")
    text = re.sub(r"(?m)^inputs_hash .*$", "inputs_hash 0123abcd", open(info).read())
    open(info, "w").write(text)
    ok &= expect_refused(a, "halves' hashes differ", cosim(a, d, rig, "--resume"),
                         "the halves differ in their inputs hash")
    d = copy("bad_step")
    c = os.path.join(d, "checkpoints")
    older = newest  # LIGGGHTS' restart of another step under the checkpoint's name
    for suffix in ("", ".info", ".wheel"):
        shutil.copy(os.path.join(a.work, f"liggghts-{newest}.restart{suffix}"),
                    os.path.join(c, f"liggghts-{resume_step}.restart{suffix}"))
    ok &= expect_refused(a, "LIGGGHTS restart of another step", cosim(a, d, rig, "--resume"),
                         f"says step {older}")
    info = os.path.join(c, f"liggghts-{resume_step}.restart.info")
    text = re.sub(r"(?m)^step .*$", f"step {resume_step}", open(info).read())
    open(info, "w").write(text)
    ok &= expect_refused(a, "forged .info (rig handshake)", cosim(a, d, rig, "--resume"),
                         f"LIGGGHTS starts at step {older}, the rig's checkpoint")

    # 4. resume and compare with the reference
    t0 = time.time()
    r = subprocess.run(cosim(a, killed, rig, "--resume"), capture_output=True, text=True,
                       timeout=600, env=env(a))
    if r.returncode != 0 or f"resuming from the checkpoint at step {resume_step}" not in r.stdout:
        print(r.stdout[-3000:], r.stderr[-3000:])
        print("run_checkpoint_case: the resumed run failed FAIL")
        return 1
    print(f"resumed run: {time.time() - t0:.1f} s")
    ref_run, ref_health, ref_codes, _ = read_run(os.path.join(ref, "run.h5"))
    res_run, res_health, res_codes, resume = read_run(os.path.join(killed, "run.h5"))
    if resume is None or int(resume["step"]) != resume_step:
        print(f"/parameters/resume/1/step is {resume and resume['step']}, expected {resume_step} "
              "FAIL")
        ok = False
    elif not 0.0 < resume["wall_time"] < resume["run_wall_time"]:
        print(f"run/wall_time {resume['run_wall_time']} s should add the stopped session's time to "
              f"the resumed session's resume/1/wall_time {resume['wall_time']} s FAIL")
        ok = False
    if set(ref_run) != set(res_run):
        print(f"observables differ: {sorted(set(ref_run) ^ set(res_run))} FAIL")
        return 1
    worst_before, at_checkpoint, after = 0.0, 0.0, {}
    for name in sorted(ref_run):
        s0, t0_, v0 = ref_run[name]
        s1, t1, v1 = res_run[name]
        if not (np.array_equal(s0, s1) and np.array_equal(t0_, t1)):
            print(f"{name}: steps/times differ ({len(s0)} vs {len(s1)} rows) FAIL")
            ok = False
            continue
        if np.any(np.diff(s1) != 1):
            print(f"{name}: the step axis is not continuous FAIL")
            ok = False
        before, at = s1 < resume_step, s1 == resume_step
        d = np.abs(v1 - v0)
        d[np.isnan(v0) & np.isnan(v1)] = 0.0
        d[np.isnan(d)] = np.inf  # NaN in one run only
        worst_before = max(worst_before, float(d[before].max(initial=0.0)))
        at_checkpoint = max(at_checkpoint, float(d[at].max(initial=0.0)))
        after[name] = (v0[~before], v1[~before], float(d[~before].max(initial=0.0)))
    rows = int(np.sum(~before))
    print(f"MEASURED np {a.np}: checkpoint at step {resume_step}; {len(s1)} rows, {rows} of them "
          f"from the resumed run; max |resumed - reference| before the checkpoint "
          f"{worst_before:.3g}, in the checkpoint's row {at_checkpoint:.3g}")
    ok &= worst_before == 0.0 and at_checkpoint == 0.0
    # After the checkpoint: LIGGGHTS' restart is not bit for bit (see docs/coupled-runs.md), so
    # single rows of a granular contact force drift apart; the wheel's path and the means over
    # the resumed part must agree.
    v0, v1, dpos = after["wheel/position"]
    print(f"MEASURED np {a.np}: wheel/position max |diff| after the checkpoint {dpos:.3g} m "
          f"(tolerance {a.pos_tol:g} m)")
    ok &= dpos <= a.pos_tol
    for name, tol in (("contact/force", a.mean_tol), ("contact/torque", a.mean_tol),
                      ("drawbar_pull", a.mean_tol), ("driving_torque", a.mean_tol),
                      ("sinkage", a.mean_tol)):
        v0, v1, dmax = after[name]
        m0, m1 = np.atleast_1d(v0.mean(axis=0)), np.atleast_1d(v1.mean(axis=0))
        # relative to the reference mean's magnitude, or to the contact force for force-like
        # components near zero (a lateral force of 0.03 N on a 15 N wheel)
        scale = max(float(np.linalg.norm(m0)), 1e-12)
        rel = float(np.linalg.norm(m1 - m0)) / scale
        print(f"MEASURED np {a.np}: {name}: mean over the resumed part {m1} vs {m0}, |diff| / "
              f"|mean| = {rel:.3g} (tolerance {tol:g}); largest single-row |diff| {dmax:.3g}")
        ok &= rel <= tol
    if ref_health != res_health or ref_codes != res_codes:
        print(f"health: reference {ref_health} {ref_codes}, resumed {res_health} {res_codes} FAIL")
        ok = False
    ok &= surface_of_checkpoint(a, os.path.join(a.work, f"liggghts-{newest}.restart"), newest,
                                os.path.join(ref, "run.h5"))
    print("run_checkpoint_case:", "ok" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
