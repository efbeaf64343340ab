#!/usr/bin/python3
"""wheel-rig's run health end to end (docs/run-health.md): the small SCM wheel of
inputs/rigs/small_wheel_scm.toml (0.3 s test phase; --duration sets it) run as a user would,
three ways:

  healthy    as shipped: exit 0, /health status healthy or warnings, no error row
  grid5      terrain.grid_spacing = 5 (metres where millimetres were meant): exit 1 within 5 s,
             status unhealthy, code grid_coarse, message suggesting 0.005
  dt25x      run.dt 25x too large (5e-3 s): exit 1, status unhealthy, an error row naming a step

Exit 0: all checks passed; 1: a check failed; 77: h5py missing (ctest reports a skip).
"""
import argparse
import pathlib
import re
import subprocess
import sys
import time

try:
    import h5py
except ImportError as exc:  # a skip with a reason, never a silent pass
    print(f"SKIP: {exc} (install Debian's python3-h5py)")
    sys.exit(77)

failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def health(path):
    with h5py.File(path, "r") as f:
        g = f["health"]
        rows = [
            (int(s), c, v, m)
            for s, c, v, m in zip(
                g["step"][()],
                g["code"].asstr()[()],
                g["severity"].asstr()[()],
                g["message"].asstr()[()],
            )
        ]
        return g.attrs["status"], rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rig", required=True, help="wheel-rig executable")
    ap.add_argument("--config", required=True, help="inputs/rigs/small_wheel_scm.toml")
    ap.add_argument("--mesh", required=True, help="the built test_small.stl")
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--duration", type=float, default=0.3, help="test phase [s]")
    ap.add_argument("--quick-phases", action="store_true",
                    help="healthy run: lower the wheel at 0.1 m/s (not 0.02) and ramp the motor "
                         "over 0.05 s (not 0.2): 2 100 steps instead of 5 300 (the sanitizer "
                         "tier)")
    a = ap.parse_args()
    work = pathlib.Path(a.workdir)
    work.mkdir(parents=True, exist_ok=True)
    base = pathlib.Path(a.config).read_text()
    base = re.sub(r'(?m)^mesh = ".*"', f'mesh = "{pathlib.Path(a.mesh).resolve()}"', base)
    base = re.sub(r'(?m)^soil = "\.\./', f'soil = "{pathlib.Path(a.config).resolve().parent.parent}/', base)
    base = re.sub(r"(?m)^duration = .*", f"duration = {a.duration}", base)
    healthy = base
    if a.quick_phases:  # the healthy run only: the two others stop within their first steps
        healthy = re.sub(r"(?m)^release_speed = .*", "release_speed = 0.1", healthy)
        healthy = re.sub(r"(?m)^ramp_time = .*", "ramp_time = 0.05", healthy)
    cases = {
        "healthy": healthy,
        "grid5": re.sub(r"(?m)^grid_spacing = \S+", "grid_spacing = 5", base),
        "dt25x": re.sub(r"(?m)^dt = \S+", "dt = 5.0e-3", base),
    }
    results = {}
    for name, text in cases.items():
        cfg = work / f"{name}.toml"
        cfg.write_text(text)
        out = work / f"{name}.h5"
        t0 = time.monotonic()
        p = subprocess.run(
            [a.rig, "--config", str(cfg), "--out", str(out), "--quiet"],
            capture_output=True,
            text=True,
            timeout=300,
        )
        results[name] = (p, time.monotonic() - t0, out)
        print(f"--- {name}: exit {p.returncode} in {results[name][1]:.2f} s\n{p.stderr.strip()}")

    p, _, out = results["healthy"]
    check(p.returncode == 0, "healthy: exit 0")
    status, rows = health(out)
    check(status in ("healthy", "warnings"), f"healthy: status {status} is healthy or warnings")
    check(all(r[2] != "error" for r in rows), "healthy: no error row")

    p, wall, out = results["grid5"]
    check(p.returncode == 1, f"grid5: exit 1 (got {p.returncode})")
    check(wall < 5.0, f"grid5: stopped within 5 s ({wall:.2f} s)")
    check("did you mean 0.005?" in p.stderr, "grid5: the message suggests 0.005")
    status, rows = health(out)
    check(status == "unhealthy", f"grid5: status {status} == unhealthy")
    check([r[1] for r in rows] == ["grid_coarse"], f"grid5: codes {[r[1] for r in rows]}")

    p, _, out = results["dt25x"]
    check(p.returncode == 1, f"dt25x: exit 1 (got {p.returncode})")
    status, rows = health(out)
    check(status == "unhealthy", f"dt25x: status {status} == unhealthy")
    errors = [r for r in rows if r[2] == "error"]
    check(len(errors) == 1 and "at step" in errors[0][3], "dt25x: one error row naming its step")

    print(f"{len(failures)} failed" if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
