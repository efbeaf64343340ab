"""Shared by the tests of the validation cases' scripts (test_dem_vs_scm.py,
test_nakanishi_compare.py, test_study_wheels_compare.py): the work directory from --work, a
script run on this interpreter with its call and output echoed to the test log, and the
verdict."""
import argparse
import subprocess
import sys
from pathlib import Path


def work_dir():
    """The directory given by --work, created if missing."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    work = Path(ap.parse_args().work)
    work.mkdir(parents=True, exist_ok=True)
    return work


def run_script(script, *args, timeout=60):
    """Runs `script` with `args` (str() of each); echoes the call, exit status and output."""
    r = subprocess.run([sys.executable, str(script), *map(str, args)], capture_output=True,
                       text=True, timeout=timeout)
    print(f"$ {Path(script).name} {' '.join(map(str, args))} -> {r.returncode}\n"
          f"{r.stdout}{r.stderr}")
    return r


def checker():
    """(failures, check): check(cond, msg) records msg in failures when cond is false."""
    failures = []

    def check(cond, msg):
        if not cond:
            failures.append(msg)

    return failures, check


def report(failures):
    """Prints each failure and the verdict; returns the exit status (0 pass, 1 fail)."""
    for f in failures:
        print("FAIL:", f)
    print("PASS" if not failures else f"{len(failures)} failure(s)")
    return 1 if failures else 0
