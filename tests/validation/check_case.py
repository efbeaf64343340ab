#!/usr/bin/python3
"""Runs a validation case's smoke version and checks its outputs.

    check_case.py RUN_SH OUT_DIR --slips S1[,S2...] [--slip-tolerance 0.005]
                  [--outputs comparison.png,provenance.toml] [--tables-check]

Runs `RUN_SH --smoke --out-dir OUT_DIR` from an empty OUT_DIR, then checks: results.csv has one
row per expected slip with the issue-11 columns, finite drawbar pull, torque, sinkage and SEM,
the measured slip equal to the imposed one within the tolerance (the rig holds it), a positive
normal load, wall time and particle count; the --outputs files (default comparison.png and
provenance.toml; a blind case has a prediction plot instead of a comparison) exist. With
--tables-check, `RUN_SH --smoke --tables` must then write the same results rows again from the
finished points alone, without running any (every run.h5 untouched). The slips are
in the signed convention of results.csv's `slip` column (driving for s >= 0, skid for s < 0), so a
skid point is checked in the skid convention. Exit 0 when all hold, 1 otherwise (each failure
printed).
"""
import argparse
import csv
import math
import shutil
import subprocess
import sys
from pathlib import Path

COLUMNS = ["slip", "drawbar_pull_N", "drawbar_pull_sem_N", "driving_torque_Nm", "traction_force_N",
           "sinkage_m", "normal_load_N", "wall_s", "particles", "np"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run_sh")
    ap.add_argument("out_dir")
    ap.add_argument("--slips", required=True)
    ap.add_argument("--slip-tolerance", type=float, default=0.005)
    ap.add_argument("--outputs", default="comparison.png,provenance.toml",
                    help="files OUT_DIR must hold afterwards (comma-separated)")
    ap.add_argument("--tables-check", action="store_true",
                    help="then check RUN_SH --tables (tables from the finished points only)")
    a = ap.parse_args()
    out = Path(a.out_dir)
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    proc = subprocess.run([a.run_sh, "--smoke", "--out-dir", str(out)])
    failures = []
    if proc.returncode != 0:
        failures.append(f"{a.run_sh} --smoke exited {proc.returncode}")
    results = out / "results.csv"
    rows = []
    if results.exists():
        with open(results, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    else:
        failures.append(f"{results} missing")
    expected = [float(s) for s in a.slips.split(",")]
    if len(rows) != len(expected):
        failures.append(f"results.csv: {len(rows)} rows, expected {len(expected)}")
    for row in rows:
        missing = [c for c in COLUMNS if c not in row]
        if missing:
            failures.append(f"results.csv: columns missing: {missing}")
            continue
        for c in COLUMNS:
            try:
                v = float(row[c])
            except ValueError:
                failures.append(f"results.csv: {c} = '{row[c]}' is not a number")
                continue
            if not math.isfinite(v):
                failures.append(f"results.csv: {c} = {v} is not finite")
        s = float(row["slip"])
        if not any(abs(s - e) <= a.slip_tolerance for e in expected):
            failures.append(f"results.csv: slip {s} is not an imposed slip {expected} "
                            f"within {a.slip_tolerance}: not held")
        for c in ("normal_load_N", "wall_s", "particles"):
            if not float(row[c]) > 0:
                failures.append(f"results.csv: {c} = {row[c]} must be > 0")
        # physical bounds a short run still meets: the soil cannot pull or hold the wheel back
        # by more than the load (|DP| <= W: friction below 1), the traction force T/R_eff stays
        # within 2 W, and the wheel ends in the soil, not above it
        w = float(row["normal_load_N"])
        if not abs(float(row["drawbar_pull_N"])) <= w:
            failures.append(f"results.csv: |drawbar pull| {row['drawbar_pull_N']} N exceeds the "
                            f"load {w} N")
        if not abs(float(row["traction_force_N"])) <= 2.0 * w:
            failures.append(f"results.csv: |T/R_eff| {row['traction_force_N']} N exceeds 2 x the "
                            f"load {w} N")
        if not float(row["sinkage_m"]) > -0.005:
            failures.append(f"results.csv: sinkage {row['sinkage_m']} m: the wheel is above the "
                            "surface")
        print(f"slip {s:.4f}: DP {float(row['drawbar_pull_N']):.3f} ± "
              f"{float(row['drawbar_pull_sem_N']):.3f} N, T {float(row['driving_torque_Nm']):.4f}"
              f" N m, sinkage {1000 * float(row['sinkage_m']):.2f} mm, W "
              f"{float(row['normal_load_N']):.2f} N, {row['particles']} particles, "
              f"{float(row['wall_s']):.0f} s")
    for name in a.outputs.split(","):
        if not (out / name).is_file():
            failures.append(f"{out / name} missing")
    if a.tables_check and results.exists():
        failures += tables_check(a.run_sh, out, results)
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


def tables_check(run_sh, out, results):
    """RUN_SH --smoke --tables rewrites results.csv with the same rows, running nothing."""
    def rows(path):
        return [l for l in path.read_text(encoding="utf-8").splitlines() if not l.startswith("#")]
    before = rows(results)
    runs = {p: p.stat().st_mtime_ns for p in out.rglob("run.h5")}
    results.unlink()
    proc = subprocess.run([run_sh, "--smoke", "--tables", "--out-dir", str(out)])
    failures = []
    if proc.returncode != 0:
        failures.append(f"{run_sh} --smoke --tables exited {proc.returncode}")
    if not results.exists():
        return failures + [f"--tables: {results} not written"]
    if rows(results) != before:
        failures.append("--tables: results.csv rows differ from the run's")
    after = {p: p.stat().st_mtime_ns for p in out.rglob("run.h5")}
    if after != runs:
        failures.append(f"--tables ran or changed points: run.h5 files {sorted(map(str, runs))} "
                        f"became {sorted(map(str, after))}")
    print(f"--tables: {len(before) - 1} row(s) written again from {len(runs)} finished run(s)")
    return failures


if __name__ == "__main__":
    sys.exit(main())
