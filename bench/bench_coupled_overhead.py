#!/usr/bin/python3
"""Wall time of a coupled run against the same run with prescribed motion.

  bench_coupled_overhead.py --root REPO --build BUILD --bed BED.restart --work DIR
                            [--np 1] [--steps 2000] [--exchange-every 1]

Both runs use tests/cosim/in.motion_compare with the same fixed twist; the coupled one goes
through scripts/wheel-cosim with the rig in --kinematic mode (the rig then does almost nothing,
so the ratio measures the coupling: ZeroMQ round trips, MPI broadcast, the handshake). Times are
LIGGGHTS' "Loop time" of the run (set-up and the bed's read excluded). Target: ratio <= 1.05.
Not a test: timings depend on the machine's load.
"""
import argparse
import os
import re
import subprocess
import sys

from liggghts_log_path import loops  # the shared parser of LIGGGHTS' "Loop time" lines


def loop_time(text):
    last = loops(text)[-1]
    return last.seconds, last.steps


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--root", required=True)
    p.add_argument("--build", required=True)
    p.add_argument("--bed", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--np", type=int, default=1)
    p.add_argument("--steps", type=int, default=2000)
    p.add_argument("--exchange-every", type=int, default=1)
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    deck = os.path.join(a.root, "tests", "cosim", "in.motion_compare")
    twist = "0.1125 0 -0.2 0 1.5 0"
    rig = open(os.path.join(a.root, "inputs", "rigs", "ci_small_wheel.toml")).read()
    rig = re.sub(r"(?m)^duration\s*=.*$", "duration = 1000.0", rig)
    rig = re.sub(r"(?m)^progress_interval\s*=.*$", "progress_interval = 0.0", rig)
    rig_path = os.path.join(a.work, "rig.toml")
    open(rig_path, "w").write(rig)
    common = ["-var", "steps", str(a.steps)]
    coupled = subprocess.run(
        [os.path.join(a.root, "scripts", "wheel-cosim"), "--rig", rig_path, "--bed", a.bed,
         "--deck", deck, "--np", str(a.np), "--work", os.path.join(a.work, "coupled"),
         "--kinematic", twist, "--", "-var", "motion", "coupled"] + common,
        capture_output=True, text=True)
    if coupled.returncode != 0:
        sys.exit("bench: coupled run failed:\n" + coupled.stdout[-2000:] + coupled.stderr[-2000:])
    t_coupled, n = loop_time(open(os.path.join(a.work, "coupled", "liggghts.log")).read())
    dt = re.search(r"dt (\S+) s", coupled.stdout).group(1)
    launch = ["mpirun", "-np", str(a.np), "--oversubscribe"]
    if os.geteuid() == 0:
        launch.append("--allow-run-as-root")
    prescribed = subprocess.run(
        launch + [os.path.join(a.build, "bin", "liggghts-wheel"), "-in", deck, "-log", "none",
                  "-var", "inputs_dir", os.path.join(a.root, "inputs"), "-var", "restart", a.bed,
                  "-var", "mesh", os.path.join(a.build, "meshes", "test_small.stl"),
                  "-var", "motion", "prescribed", "-var", "dt", dt] + common,
        capture_output=True, text=True, cwd=a.work)
    if prescribed.returncode != 0:
        sys.exit("bench: prescribed run failed:\n" + prescribed.stdout[-2000:])
    t_prescribed, _ = loop_time(prescribed.stdout)
    ratio = t_coupled / t_prescribed
    print(f"bench: {n} steps, np {a.np}: coupled {t_coupled:.3f} s "
          f"({1e6 * t_coupled / n:.1f} us/step), prescribed {t_prescribed:.3f} s "
          f"({1e6 * t_prescribed / n:.1f} us/step)")
    print(f"bench: coupled / prescribed wall time = {ratio:.3f} (target <= 1.05); coupling cost "
          f"{1e6 * (t_coupled - t_prescribed) / n:.1f} us/step")


if __name__ == "__main__":
    main()
