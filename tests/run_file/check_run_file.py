#!/usr/bin/python3
"""Read run files written by run_file_write_sample with h5py and check them.

Checks shapes, dtypes, values, the unit attributes, /h5md (version, creator, author), the
/parameters text round trip, a terrain snapshot, and a file whose writer was killed with SIGKILL
after N flushed and M unflushed steps (exactly N rows must be there).
Exit 0: all checks passed; 1: a check failed; 77: h5py or numpy missing (ctest reports a skip).
"""
import argparse
import pathlib
import signal
import subprocess
import sys

try:
    import h5py
    import numpy as np
except ImportError as exc:  # a skip with a reason, never a silent pass
    print(f"SKIP: {exc} (install Debian's python3-h5py and python3-numpy)")
    sys.exit(77)

TOML = '# rig config (verbatim)\n[wheel]\nmesh = "wheel.obj"\nradius = 0.15 # m, \u00b5-wheel\n'
SERIES = {  # name: (unit, components) — as in write_sample.cpp
    "slip": ("1", 1),
    "wheel/position": ("m", 3),
    "wheel/orientation": ("1", 4),
    "drawbar_pull": ("N", 1),
}
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print(f"FAIL: {what}")


def expected(n, components):
    """Steps 1..n, their times and values (sample_values.h)."""
    step = np.arange(1, n + 1, dtype=np.int64)
    time = 0.5e-4 * step.astype(np.float64)
    value = step[:, None].astype(np.float64) + 0.125 * np.arange(components)[None, :] + 0.5
    return step, time, (value[:, 0] if components == 1 else value)


def check_series(f, rows):
    for name, (unit, comps) in SERIES.items():
        g = f["observables"][name]
        step, time, value = expected(rows, comps)
        shape = (rows,) if comps == 1 else (rows, comps)
        check(g["step"].dtype == np.int64, f"{name}/step dtype {g['step'].dtype}")
        check(g["time"].dtype == np.float64, f"{name}/time dtype {g['time'].dtype}")
        check(g["value"].dtype == np.float64, f"{name}/value dtype {g['value'].dtype}")
        check(g["step"].shape == (rows,), f"{name}/step shape {g['step'].shape} != {(rows,)}")
        check(g["time"].shape == (rows,), f"{name}/time shape {g['time'].shape}")
        check(g["value"].shape == shape, f"{name}/value shape {g['value'].shape} != {shape}")
        check(g["value"].maxshape[0] is None, f"{name}/value not extendable")
        check(g["value"].chunks is not None, f"{name}/value not chunked")
        check(g["value"].attrs.get("unit") == unit, f"{name}/value unit {g['value'].attrs.get('unit')!r}")
        check(g["time"].attrs.get("unit") == "s", f"{name}/time unit {g['time'].attrs.get('unit')!r}")
        if g["value"].shape == shape:
            check(np.array_equal(g["step"][()], step), f"{name}/step values")
            check(np.array_equal(g["time"][()], time), f"{name}/time values")
            check(np.array_equal(g["value"][()], value), f"{name}/value values")


def check_header(f, author):
    check(list(f["h5md"].attrs["version"]) == [1, 0], f"h5md version {f['h5md'].attrs['version']}")
    creator = f["h5md/creator"].attrs
    check(creator["name"] == "run_file_write_sample", f"creator name {creator['name']!r}")
    check(creator["version"] == "1.2.3", f"creator version {creator['version']!r}")
    check(creator["git_revision"] == "abc1234", f"git revision {creator['git_revision']!r}")
    if author is not None:
        check(f["h5md/author"].attrs["name"] == author, "author name")
    text = f["parameters/rig.toml"].asstr()[()]
    check(text == TOML, f"rig.toml text round trip: {text!r}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--writer", required=True, help="the run_file_write_sample executable")
    ap.add_argument("--workdir", required=True, help="directory for the files")
    ap.add_argument("--flushed", type=int, default=1500, help="steps flushed before the kill")
    ap.add_argument("--unflushed", type=int, default=700, help="steps appended after the flush")
    args = ap.parse_args()
    work = pathlib.Path(args.workdir)
    work.mkdir(parents=True, exist_ok=True)

    sample = work / "sample.h5"
    subprocess.run([args.writer, "sample", str(sample)], check=True)
    with h5py.File(sample, "r") as f:
        check_header(f, "Tester")
        check_series(f, 2100)
        p = f["parameters"]
        check(p["liggghts/arguments"].asstr()[()] == "-in in.wheel -var seed 7", "deck arguments")
        check(p["rig/spring_k"][()] == 2.5e4 and p["rig/spring_k"].attrs["unit"] == "N/m", "spring_k")
        check(p["rig/seed"][()] == 42 and p["rig/seed"].dtype == np.int64, "seed")
        snap = f["terrain/height/002100"]
        check(snap["value"].shape == (4, 6), f"snapshot shape {snap['value'].shape}")
        check(np.array_equal(snap["value"][()], 0.5 * np.arange(24.0).reshape(4, 6)), "snapshot")
        check(snap["value"].attrs["unit"] == "m" and snap["dx"][()] == 0.25, "snapshot unit, dx")
        check(snap["step"][()] == 2100 and snap["time"].attrs["unit"] == "s", "snapshot step, time")

    crashed = work / "crashed.h5"
    proc = subprocess.run([args.writer, "crash", str(crashed), str(args.flushed),
                           str(args.unflushed)])
    check(proc.returncode == -signal.SIGKILL, f"writer should die by SIGKILL, got {proc.returncode}")
    with h5py.File(crashed, "r") as f:  # a plain open: no SWMR flag, no h5clear needed
        check_header(f, None)
        check_series(f, args.flushed)  # exactly the flushed steps

    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all h5py checks passed (sample: 2100 rows x 4 series; crash: "
          f"{args.flushed} flushed rows kept, {args.unflushed} unflushed rows absent)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
