#!/usr/bin/python3
"""The soil lab's stall guard (docs/soil-lab.md, --stall-timeout): `soil-lab run ci --np 1
--stall-timeout 0.05` (3 s) with a build dir whose liggghts-wheel is the stand-in
tests/sweep/liggghts_standin.py, started by the lab through mpirun as the real one is.

  stall:  the lab's first run (in.lab_soilinfo) prints one line and hangs: the lab kills it and
          stops with one line 'soil-lab: error: in.lab_soilinfo made no progress for 0.05 min (log
          .../soil_info.log unchanged since HH:MM:SS): killed; ...', exit 1, within a few seconds
          of the timeout, and no process of the run is left.
  steady: the same run prints a line every 0.25 s for 6 s (twice the timeout), then ends without
          the soil line: not killed; the lab stops on the missing line instead (exit 1).

  check_stall_lab.py --case stall|steady --work DIR
Exit 0 pass, 1 fail, 77 skip (no mpirun).
"""

import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import lab_check

ROOT = Path(__file__).resolve().parents[2]
STANDIN = ROOT / "tests" / "sweep" / "liggghts_standin.py"
STALL_S = 3.0  # --stall-timeout 0.05 min


def run_lab(work, env):
    """Runs the lab on the stand-in; returns (exit status, stderr, wall time [s], processes of
    the run still alive 2 s after the lab ended)."""
    build = work / "build"
    (build / "bin").mkdir(parents=True)
    (build / "bin" / "liggghts-wheel").symlink_to(STANDIN)
    mesh = build / "bin" / "wheel-mesh"  # never started: the lab stops before its meshes
    mesh.write_text("#!/bin/sh\nexit 1\n")
    mesh.chmod(0o755)
    cmd = [str(ROOT / "soil_lab" / "soil-lab"), "run", "ci", "--np", "1", "--out",
           str(work / "lab"), "--build-dir", str(build), "--stall-timeout", "0.05"]
    t0 = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=60,
                       env=dict(os.environ, **env))
    wall = time.monotonic() - t0
    print(f"$ {' '.join(cmd)}  ({env}) -> exit {r.returncode} after {wall:.1f} s")
    print(r.stdout + r.stderr, end="")
    left = lab_check.survivors(str(build))
    deadline = time.monotonic() + 2.0
    while left and time.monotonic() < deadline:
        time.sleep(0.1)
        left = lab_check.survivors(str(build))
    for pid in left:  # leave nothing behind when the check fails
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    return r.returncode, r.stderr, wall, left


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", choices=["stall", "steady"], required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    if shutil.which("mpirun") is None:
        print("SKIP: mpirun not found (Debian openmpi-bin)")
        return lab_check.SKIP
    work = Path(a.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    fails = []
    if a.case == "stall":
        rc, err, wall, left = run_lab(work, {"STANDIN_STALL_DECKS": "in.lab_soilinfo"})
        log = work / "lab" / "soil_info.log"
        pattern = (r"soil-lab: error: in\.lab_soilinfo made no progress for 0\.05 min \(log "
                   + re.escape(str(log)) + r" unchanged since \d\d:\d\d:\d\d\): killed; .*"
                   r"--stall-timeout MIN.*")
        if rc != 1:
            fails.append(f"exit {rc}, expected 1")
        if len(err.strip().splitlines()) != 1 or not re.fullmatch(pattern, err.strip()):
            fails.append(f"stderr is not the one stall line: {err.strip()!r}")
        if not STALL_S <= wall < STALL_S + 15:
            fails.append(f"took {wall:.1f} s for a {STALL_S} s stall timeout")
        if not log.is_file() or "stand-in liggghts-wheel" not in log.read_text():
            fails.append(f"the stand-in's line is not in {log}")
    else:
        rc, err, wall, left = run_lab(work, {"STANDIN_STEADY_S": "6"})
        if "made no progress" in err:
            fails.append("the steadily printing run was killed")
        if rc != 1 or "in.lab_soilinfo printed no soil line" not in err:
            fails.append(f"exit {rc}: expected 1 and the missing soil line: {err.strip()!r}")
        if wall < 6.0:
            fails.append(f"the run ended after {wall:.1f} s, before its 6 s of output")
    if left:
        fails.append("processes of the run left: " + "; ".join(
            f"{p} {c[:100]}" for p, c in left.items()))
    for f in fails:
        print(f"FAIL: {a.case}: {f}")
    if not fails:
        print(f"PASS: {a.case}")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
