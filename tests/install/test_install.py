"""`cmake --install` into a temporary prefix, then the tools run from there (docs/building.md,
"Install"; cmake/WheelsimInstall.cmake).

Usage: test_install.py --build-dir DIR --version X.Y.Z --tools T1,T2,...

Checks, with the source tree out of the way (the tools are started by their installed paths, from
a working directory outside both trees, with WHEELSIM_BUILD_DIR unset):
1. every tool is in <prefix>/bin and `<tool> --version` prints "<tool> <version>" (exit 0);
2. wheel-rig runs the shipped SCM example (wheel_dynamics/examples/rig_scm.toml, installed under
   share/wheelsim) shortened to a 0.5 s test phase, with the config's relative mesh and soil
   paths resolved inside the prefix; the run file records the soil's friction angle in degrees,
   as the installed soil file gives it;
3. `wheelsim-post curves` on that run file writes one row for wheel2 on LETE sand whose lug count
   comes from the installed wheel catalogue;
4. the demo's SCM half (scripts/demo.sh step 2 and its curves, step 3) runs from the prefix:
   `wheel-sweep` on the installed inputs/sweeps/demo_scm.toml as it is (6 slips, 2 s test
   phases; its base rig, soil and wheel mesh are the installed ones, by the config's relative
   paths), then `wheelsim-post curves --group-by terrain,soil` on its run files: one row per
   slip, wheel test_small, soil ci_fitted, terrain scm, every mean and the radius and load
   finite; about 7 s on 2 cores;
5. the Python tools find their data installed: `soil-lab --help`, and `scm-soil export` of an
   installed soil.
"""

import argparse
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

import h5py


def run(cmd, cwd, env, what, timeout=120):
    r = subprocess.run([str(c) for c in cmd], cwd=cwd, env=env, capture_output=True, text=True,
                       timeout=timeout)
    if r.returncode != 0:
        sys.exit(f"FAIL: {what}: exit {r.returncode}\n$ {' '.join(map(str, cmd))}\n"
                 f"{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return r


def demo_scm_half(prefix, share, work, env):
    """scripts/demo.sh's SCM half (step 2 and the curves of step 3) from the prefix, as the demo
    runs it: the installed sweep config, unchanged (6 slips, 2 s test phases; about 7 s on 2
    cores), then the curves CSV of its runs."""
    config = share / "inputs" / "sweeps" / "demo_scm.toml"
    slips = sorted(tomllib.loads(config.read_text())["slips"])
    out = work / "demo" / "scm"
    run([prefix / "bin" / "wheel-sweep", config, "--out-dir", out], work, env,
        "wheel-sweep on the installed demo_scm.toml", timeout=240)
    runs = sorted(out.rglob("run.h5"))
    if len(runs) != len(slips):
        sys.exit(f"FAIL: the sweep wrote {len(runs)} run files, expected {len(slips)}")
    curves = work / "demo" / "traction_curves.csv"
    run([prefix / "bin" / "wheelsim-post", "curves", *runs, "--group-by", "terrain,soil",
         "--csv", curves], work, env, "wheelsim-post curves on the demo's SCM runs")
    rows = list(csv.DictReader(line for line in curves.open() if not line.startswith("#")))
    if len(rows) != len(slips):
        sys.exit(f"FAIL: {curves} has {len(rows)} rows, expected {len(slips)}")
    means = [c for c in rows[0] if "_mean" in c and not c.endswith("_sem")]
    if not any(c.startswith("drawbar_pull_mean") for c in means):
        sys.exit(f"FAIL: {curves} has no drawbar pull mean column: {list(rows[0])}")
    rows.sort(key=lambda r: float(r["target_slip"]))
    for row, slip in zip(rows, slips):
        bad = [c for c in means + ["r_eff_m", "vertical_load_N"]
               if not math.isfinite(float(row[c]))]
        if ((row["wheel"], row["soil"], row["terrain"]) != ("test_small", "ci_fitted", "scm")
                or float(row["target_slip"]) != slip or bad):
            sys.exit(f"FAIL: unexpected curves row for slip {slip}: wheel {row['wheel']}, soil "
                     f"{row['soil']}, terrain {row['terrain']}, target slip "
                     f"{row['target_slip']}, not finite: {bad}")
    dp = ", ".join(f"{float(r['drawbar_pull_mean_N']):.2f}" for r in rows)
    print(f"ok: the demo's SCM half from the prefix: {len(rows)} slips, DP {dp} N")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build-dir", required=True)
    ap.add_argument("--version", required=True)
    ap.add_argument("--tools", required=True)
    a = ap.parse_args()
    tools = a.tools.split(",")

    tmp = Path(tempfile.mkdtemp(prefix="wheelsim_install_"))
    try:
        prefix, work = tmp / "prefix", tmp / "work"
        work.mkdir()
        env = {k: v for k, v in os.environ.items()
               if k not in ("WHEELSIM_BUILD_DIR", "PYTHONPATH")}
        env["MPLBACKEND"] = "Agg"
        build = Path(a.build_dir).resolve()
        run(["cmake", "--install", build, "--prefix", prefix], work, env, "cmake --install")
        share = prefix / "share" / "wheelsim"

        # 1. every tool, --version
        for tool in tools:
            exe = prefix / "bin" / tool
            if not os.access(exe, os.X_OK):
                sys.exit(f"FAIL: {exe} is not installed (or not executable)")
            out = run([exe, "--version"], work, env, f"{tool} --version").stdout.strip()
            if not out.startswith(f"{tool} {a.version}"):
                sys.exit(f"FAIL: {tool} --version printed '{out}', "
                         f"expected '{tool} {a.version} ...'")
            print(f"ok: {out}")
        # The Python tools run from share/wheelsim, not from the source tree.
        for tool in ("wheelsim-post", "wheel-sweep", "park-running", "soil-lab", "wheel-cosim"):
            if tool in tools and share not in Path(os.path.realpath(prefix / "bin" / tool)).parents:
                sys.exit(f"FAIL: {prefix / 'bin' / tool} does not lead into {share}")

        # 2. the SCM example, shortened, beside the installed original (its relative paths)
        examples = share / "wheel_dynamics" / "examples"
        text = (examples / "rig_scm.toml").read_text()
        short, n1 = re.subn(r"(?m)^duration = [0-9.]+", "duration = 0.5", text)
        short, n2 = re.subn(r"(?m)^snapshot_times = \[.*\]", "snapshot_times = [0.25]", short)
        if n1 != 1 or n2 != 1:
            sys.exit("FAIL: rig_scm.toml no longer has one 'duration =' and one "
                     "'snapshot_times =' line to shorten; update this test")
        config = examples / "rig_scm_short.toml"
        config.write_text(short)
        run_h5 = work / "run.h5"
        run([prefix / "bin" / "wheel-rig", "--config", config, "--out", run_h5, "--quiet"], work,
            env, "wheel-rig on the shortened SCM example")
        soil_rel = tomllib.loads(short)["terrain"]["soil"]
        soil = tomllib.loads((examples / soil_rel).resolve().read_text())
        with h5py.File(run_h5, "r") as f:
            phi = f["parameters/terrain/soil/Mohr_friction"]
            unit = phi.attrs["unit"]
            unit = unit.decode() if isinstance(unit, bytes) else str(unit)
            if unit != "deg" or abs(float(phi[()]) - soil["mohr_coulomb"]["friction_angle"]) > 1e-9:
                sys.exit(f"FAIL: /parameters/terrain/soil/Mohr_friction = {phi[()]} {unit}, "
                         f"expected {soil['mohr_coulomb']['friction_angle']} deg (the soil file)")
            soil_file = f["parameters/terrain/soil_file"].asstr()[()]
        if share not in Path(soil_file).resolve().parents:
            sys.exit(f"FAIL: the run used the soil file {soil_file}, not the installed one")
        phi_deg = soil["mohr_coulomb"]["friction_angle"]
        print(f"ok: wheel-rig, run file {run_h5}, friction angle {phi_deg} deg")

        # 3. wheelsim-post curves on it
        curves = work / "curves.csv"
        run([prefix / "bin" / "wheelsim-post", "curves", run_h5, "--csv", curves], work, env,
            "wheelsim-post curves")
        rows = list(csv.DictReader(line for line in curves.open() if not line.startswith("#")))
        if len(rows) != 1:
            sys.exit(f"FAIL: curves.csv has {len(rows)} rows, expected 1")
        row = rows[0]
        catalog = tomllib.loads((share / "meshes" / "catalog.toml").read_text())
        lugs = [w for w in catalog["wheel"] if w["name"] == "wheel2"][0]["lugs"]
        dp = float(row["drawbar_pull_mean_N"])
        if ((row["wheel"], row["soil"], row["terrain"]) != ("wheel2", soil["name"], "scm")
                or int(row["lug_count"]) != lugs or not math.isfinite(dp)):
            sys.exit(f"FAIL: unexpected curves row: wheel {row['wheel']}, soil {row['soil']}, "
                     f"terrain {row['terrain']}, lugs {row['lug_count']} (catalogue {lugs}), "
                     f"DP {row['drawbar_pull_mean_N']}")
        print(f"ok: wheelsim-post curves, DP {float(row['drawbar_pull_mean_N']):.0f} N, "
              f"{row['lug_count']} lugs")

        # 4. the demo's SCM half
        if "wheel-sweep" in tools:
            demo_scm_half(prefix, share, work, env)

        # 5. the Python tools' data lookups, installed
        if "soil-lab" in tools:
            run([prefix / "bin" / "soil-lab", "--help"], work, env, "soil-lab --help")
        if "scm-soil" in tools:
            out = run([prefix / "bin" / "scm-soil", "export",
                       share / "inputs" / "scm_soils" / "lete_sand.toml"], work, env,
                      "scm-soil export").stdout
            if '"Mohr friction limit": 31.1' not in out:
                sys.exit(f"FAIL: scm-soil export printed\n{out}")
        if (work / "runs").exists() or (share / "runs").exists():
            sys.exit("FAIL: a tool wrote a default runs/ directory")
        print("PASS")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
