"""Runs scripts/demo.sh --quick and checks what it promises: a traction-curve CSV with one row per
sweep point (2 DEM slips in --quick, 6 SCM slips) with finite steady-state values, one series per
terrain naming its soil (DEM ci and the SCM soil fitted to it), its PNG, the SCM maps and the DEM
wheel-pressure map, and the closing lines that say where the results are.

usage: check_demo.py DEMO_SH OUT_DIR   (environment: WHEELSIM_DEMO_DIR=OUT_DIR, build dir, ...)
"""

import csv
import math
import shutil
import subprocess
import sys
from pathlib import Path


def fail(message):
    print(f"check_demo: FAIL: {message}")
    sys.exit(1)


def main():
    demo, out = sys.argv[1], Path(sys.argv[2])
    shutil.rmtree(out, ignore_errors=True)  # from nothing: a re-run would resume and skip points
    proc = subprocess.run(["bash", demo, "--quick"], capture_output=True, text=True, errors="replace")
    print(proc.stdout[-6000:])
    print(proc.stderr[-3000:], file=sys.stderr)
    if proc.returncode != 0:
        fail(f"demo.sh --quick exited {proc.returncode}")
    if f"Results in {out}" not in proc.stdout:
        fail("the demo does not say where its results are")
    progress_lines = ("demo: [1/3] DEM", "demo: [2/3] SCM", "demo: [3/3]", "ci_fitted s=0.5 done")
    for progress in progress_lines:
        if progress not in proc.stdout:
            fail(f"no progress line containing {progress!r}")

    table = out / "traction_curves.csv"
    with open(table, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    by_terrain = {}
    for row in rows:
        by_terrain.setdefault(row["terrain"], []).append(row)
    counts = {t: len(r) for t, r in by_terrain.items()}
    if counts != {"dem": 2, "scm": 6}:
        fail(f"expected 2 DEM and 6 SCM points in {table}, got {counts}")
    # The legend names terrain and soil: the DEM ci bin and the SCM soil fitted to it.
    groups = {row["terrain"]: row["group"] for row in rows}
    for terrain, soil in (("dem", "soil=ci_demo"), ("scm", "soil=ci_fitted")):
        if soil not in groups.get(terrain, ""):
            fail(f"the {terrain} series is not labelled with {soil!r}: {groups}")
    for row in rows:
        for column in ("slip_mean", "drawbar_pull_mean_N", "driving_torque_mean_Nm", "sinkage_mean_m"):
            if not math.isfinite(float(row[column])):
                fail(f"{column} is not finite for {row['terrain']} slip {row['target_slip']}")
        if abs(float(row["slip_mean"]) - float(row["target_slip"])) > 1e-6:
            fail(f"imposed slip not held: {row['slip_mean']} vs {row['target_slip']}")
    # Traction grows with slip on both terrains (largest slip pulls more than the smallest).
    for terrain, members in by_terrain.items():
        members.sort(key=lambda r: float(r["target_slip"]))
        low, high = (float(members[i]["drawbar_pull_mean_N"]) for i in (0, -1))
        if not high > low:
            fail(f"{terrain}: drawbar pull does not rise with slip ({low} -> {high} N)")

    for png in [out / "traction_curves.png"] + sorted((out / "maps").glob("*.png")):
        if png.stat().st_size < 10_000 or png.read_bytes()[:8] != b"\x89PNG\r\n\x1a\n":
            fail(f"{png} is not a plausible PNG")
    names = {p.name for p in (out / "maps").glob("*.png")}
    for prefix in ("sinkage_", "pressure_", "wheel_surface_"):
        if not any(n.startswith(prefix) for n in names):
            fail(f"no {prefix}*.png in {out / 'maps'} (have {sorted(names)})")
    print(f"check_demo: OK: {counts}, maps {sorted(names)}")


if __name__ == "__main__":
    main()
