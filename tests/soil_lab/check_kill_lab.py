#!/usr/bin/python3
"""The soil lab's runs die with it: `soil-lab run ci --preset quick --tests shear` is killed with
SIGKILL (or SIGTERM) while LIGGGHTS prepares its bed, and within 5 s no process whose command line
names the lab's output directory is left (mpirun dies through PR_SET_PDEATHSIG, each rank
through `setpriv --pdeathsig KILL`; docs/soil-lab.md "Stopping and resuming").

  check_kill_lab.py --build-dir BUILD --work DIR --signal KILL|TERM
Exit 0 pass, 1 fail, 77 skip (liggghts-wheel not built).
"""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import lab_check

ROOT = Path(__file__).resolve().parents[2]



def main():
    started = lab_check.start(
        lambda ap: ap.add_argument("--signal", choices=["KILL", "TERM"], default="KILL"))
    if started is None:
        return lab_check.SKIP
    a, work = started
    out = work / f"lab_{a.signal.lower()}"
    lab = subprocess.Popen(
        [str(ROOT / "soil_lab" / "soil-lab"), "run", "ci", "--preset", "quick", "--tests",
         "shear", "--np", "1", "--out", str(out), "--build-dir", a.build_dir, "--quiet"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    tag = str(out)
    deadline = time.monotonic() + 120
    while not any("liggghts-wheel" in cmd for cmd in lab_check.survivors(tag).values()):
        if lab.poll() is not None or time.monotonic() > deadline:
            print(f"FAIL: no LIGGGHTS run of the lab seen (lab exit {lab.poll()})")
            return 1
        time.sleep(0.2)
    running = lab_check.survivors(tag)
    lab.send_signal(getattr(signal, f"SIG{a.signal}"))
    lab.wait()
    t0 = time.monotonic()
    left = lab_check.survivors(tag)
    while left and time.monotonic() - t0 < 5.0:
        time.sleep(0.1)
        left = lab_check.survivors(tag)
    print(f"soil-lab killed with SIG{a.signal} while {len(running)} process(es) of its run were "
          f"alive; after {time.monotonic() - t0:.1f} s {len(left)} left")
    for p in left:
        try:
            os.kill(p, signal.SIGKILL)
        except ProcessLookupError:
            pass
    if left:
        print("FAIL: processes outlived the lab:\n" + "\n".join(f"  {p}: {c}" for p, c in left.items()))
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
