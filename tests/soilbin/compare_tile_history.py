#!/usr/bin/python3
"""Tiled beds keep their contact histories (fix wheelsim/tile_history, docs/soil-bins.md "Tiled
beds"): the same ci bin tiled with tile_history 1 (KEEP) and 0 (DROP), each result.txt written by
run_soilbin.cmake. Fails unless
  - KEEP carried contact histories (tile_history_kept > 0) and DROP none (0);
  - the fix's force check (rms over the grains that kept every contact of the block of the
    difference between their force after the remap and at the block's last step) is at least
    FACTOR times smaller with KEEP than with DROP. Measured (ci 0.24 x 0.08 m, 4 blocks, np 2):
    KEEP 7.2e-4 N, DROP 7.4e-3 N (10x); the block itself, remapped onto itself, gives 7.0e-4 N
    (the check's floor: the set-up's damping sees other velocities than the step did).

usage: compare_tile_history.py KEEP/result.txt DROP/result.txt [--factor 4]
"""
import argparse
import sys


def read(path):
    values = {}
    try:
        with open(path) as f:
            for line in f:
                if line.startswith("soilbin: ") and " = " in line:
                    key, value = line[len("soilbin: "):].split(" = ", 1)
                    values[key.strip()] = value.strip()
    except OSError as e:
        sys.exit(f"compare_tile_history: {path}: {e} (did the run it comes from fail?)")
    for key in ("tile_history_kept", "tile_force_rms"):
        if key not in values:
            sys.exit(f"compare_tile_history: {path} has no '{key}'")
    return {k: float(values[k]) for k in ("tile_history_kept", "tile_force_rms")}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("keep")
    ap.add_argument("drop")
    ap.add_argument("--factor", type=float, default=4.0)
    a = ap.parse_args()
    keep, drop = read(a.keep), read(a.drop)
    print(f"kept histories: keep {keep['tile_history_kept']:.0f}, drop {drop['tile_history_kept']:.0f}; "
          f"force check rms: keep {keep['tile_force_rms']:.3g} N, drop {drop['tile_force_rms']:.3g} N")
    failures = []
    if keep["tile_history_kept"] <= 0:
        failures.append("tile_history 1 carried no contact history")
    if drop["tile_history_kept"] != 0:
        failures.append("tile_history 0 reports carried histories")
    if not keep["tile_force_rms"] > 0 or not drop["tile_force_rms"] > 0:
        failures.append("the force check did not run (rms <= 0)")
    elif keep["tile_force_rms"] * a.factor > drop["tile_force_rms"]:
        failures.append(f"force check: keep {keep['tile_force_rms']:.3g} N is not {a.factor:g}x "
                        f"below drop {drop['tile_force_rms']:.3g} N")
    if failures:
        sys.exit("compare_tile_history: " + "; ".join(failures))


if __name__ == "__main__":
    main()
