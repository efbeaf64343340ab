#!/usr/bin/python3
"""scripts/test_times.py on synthetic ctest JUnit reports (tests/scripts/CMakeLists.txt)."""
import importlib.util
import os
import subprocess
import sys
import tempfile

SCRIPT = sys.argv[1]
spec = importlib.util.spec_from_file_location("test_times", SCRIPT)
tt = importlib.util.module_from_spec(spec)
spec.loader.exec_module(tt)

# ctest 3.25's layout: status="run" passed, "fail" failed, "notrun" with <skipped> for a skip
REPORT = """<?xml version="1.0" encoding="UTF-8"?>
<testsuite name="(empty)" tests="4" failures="1" disabled="0" skipped="1" time="100">
  <testcase name="a.fast" classname="a.fast" time="10" status="run"><system-out/></testcase>
  <testcase name="b.slow" classname="b.slow" time="60" status="run"><system-out/></testcase>
  <testcase name="c.broken" classname="c.broken" time="25" status="fail">
    <failure message="Failed"/></testcase>
  <testcase name="d.skip" classname="d.skip" time="5" status="notrun">
    <skipped message="SKIP_RETURN_CODE=77"/></testcase>
</testsuite>
"""
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


with tempfile.TemporaryDirectory() as d:
    report = os.path.join(d, "junit.xml")
    with open(report, "w") as f:
        f.write(REPORT)
    rows = tt.read_times(report)
    check(rows == [("a.fast", 10.0, "passed"), ("b.slow", 60.0, "passed"),
                   ("c.broken", 25.0, "failed"), ("d.skip", 5.0, "skipped")], f"rows {rows}")
    text = tt.summary(rows, top=2, wall_s=70.4)
    lines = text.splitlines()
    check(lines[0] == "test times: the 2 slowest of 4 tests (sum of all test times 100 s, "
          "suite wall time 70 s)", f"header {lines[0]!r}")
    check(len(lines) == 3, f"{len(lines)} lines, expected 3")
    check(lines[1].split() == ["60.0", "s", "60.0", "%", "b.slow"], f"first {lines[1]!r}")
    check(lines[2].split() == ["25.0", "s", "25.0", "%", "c.broken", "[failed]"],
          f"second {lines[2]!r}")
    # the command line: exit 0 and the same text; a non-JUnit file and a missing one exit 2
    run = subprocess.run([sys.executable, SCRIPT, report, "--top", "2", "--wall", "70.4"],
                         capture_output=True, text=True)
    check(run.returncode == 0 and run.stdout.strip() == text, f"cli: {run}")
    bad = os.path.join(d, "bad.xml")
    with open(bad, "w") as f:
        f.write("<html><body/></html>")
    run = subprocess.run([sys.executable, SCRIPT, bad], capture_output=True, text=True)
    check(run.returncode == 2 and "bad.xml" in run.stderr and "not a JUnit report" in run.stderr,
          f"non-JUnit: {run.returncode} {run.stderr!r}")
    run = subprocess.run([sys.executable, SCRIPT, os.path.join(d, "missing.xml")],
                         capture_output=True, text=True)
    check(run.returncode == 2 and "missing.xml" in run.stderr, f"missing: {run.stderr!r}")
    run = subprocess.run([sys.executable, SCRIPT, report, "--top", "0"], capture_output=True,
                         text=True)
    check(run.returncode == 2 and "--top 0" in run.stderr, f"--top 0: {run.stderr!r}")

for f in failures:
    print("FAIL:", f)
print("test_times:", "ok" if not failures else f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
