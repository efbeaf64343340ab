#!/usr/bin/python3
"""Unit tests of scripts/wheelsim_sweep (no wheel-rig runs; milliseconds to a second each).

  test_sweep_unit.py CASE --sweep scripts/wheel-sweep --work DIR

CASE: toml_roundtrip, cli, soil_names (see each function and tests/sweep/CMakeLists.txt).
Exit 0 pass, 1 fail, 77 skip (a prerequisite missing).
"""

import argparse
import math
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

SKIP = 77


class Fail(Exception):
    pass


class Skip(Exception):
    pass


def check(cond, msg):
    if not cond:
        raise Fail(msg)


def case_toml_roundtrip(a, work):
    """Rig configs with non-ASCII keys and strings, quotes, backslashes and every control
    character read back with tomllib exactly as written (and the header stays a comment)."""
    from wheelsim_sweep import toml_out
    controls = "".join(chr(i) for i in range(32)) + "\x7f"
    doc = {
        "wheel": {"mesh": "/tmp/räder/wheel \"2\".stl", "mass": 205.0, "mesh_scale": 1},
        "run": {"dt": 1e-4, "duration": float("inf"), "flag": True},
        "terrain": {"type": "scm", "soil": "/tmp/böden/sand\\loam.toml",
                    "names": ["ä", "b\nc", controls], "empty": []},
        "sól": {"clé": "valeur", "ключ": 1, "with space": -0.5, "dot.ted": "x",
                "ctl\x01key": "tab\there", "": "empty key"},
        "nested": {"deeper": {"ünïcode": "\u2028\u2029\ufeff\U0001F600"}},
    }
    header = "written by wheel-sweep\npoint ä/ö: \x01 bell \x07 and \x7f\nthird line"
    text = toml_out.dumps(doc, header)
    (work / "rig.toml").write_text(text, encoding="utf-8")
    print(text)
    try:
        back = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise Fail(f"tomllib cannot read what toml_out wrote: {e}")
    inf = back["run"].pop("duration")
    check(math.isinf(inf) and inf > 0, f"run.duration {inf} != inf")
    doc["run"].pop("duration")
    check(back == doc, f"round trip differs:\n{back}\n!=\n{doc}")
    check(text.startswith("# written by wheel-sweep\n# point ä/ö: "), "header not a comment")
    try:
        toml_out.dumps({"run": {"dt": None}})
        raise Fail("None was written")
    except TypeError:
        pass


def _run(a, *args):
    r = subprocess.run([a.sweep, *args], capture_output=True, text=True, timeout=30)
    print(f"$ wheel-sweep {' '.join(args)}  -> exit {r.returncode}\n{r.stdout}{r.stderr}")
    return r


def case_cli(a, work):
    """--version and --help exit 0; bad usage exits 2 with one line naming the bad flag and the
    nearest valid one; nothing is written."""
    r = _run(a, "--version")
    check(r.returncode == 0 and re.match(r"wheel-sweep \d+\.\d+\.\d+", r.stdout),
          "--version: expected exit 0 and 'wheel-sweep X.Y.Z'")
    r = _run(a, "--help")
    check(r.returncode == 0 and "--dry-run" in r.stdout and "Exit status" in r.stdout,
          "--help: expected exit 0 and the options with the exit statuses")
    cfg = work / "sweep.toml"
    cfg.write_text('terrain = "flat"\n')
    bad = [  # (arguments, the bad flag, the suggestion)
        ([str(cfg), "--jbos", "2"], "--jbos", "--jobs"),
        (["--verison"], "--verison", "--version"),
        ([str(cfg), "--dryrun"], "--dryrun", "--dry-run"),
        ([str(cfg), "--out-dri", str(work / "out")], "--out-dri", "--out-dir"),
        ([str(cfg), "--froce"], "--froce", "--force"),
    ]
    for args, flag, near in bad:
        r = _run(a, *args)
        check(r.returncode == 2, f"{args}: exit {r.returncode}, expected 2")
        lines = r.stderr.strip().splitlines()
        check(len(lines) == 1 and f"'{flag}'" in lines[0] and f"'{near}'" in lines[0],
              f"{args}: stderr does not name '{flag}' and '{near}' in one line: {r.stderr!r}")
    r = _run(a, str(cfg), "--jobs", "0")
    check(r.returncode == 2 and "--jobs must be >= 1" in r.stderr, "--jobs 0: expected exit 2")
    r = _run(a)
    check(r.returncode == 2 and "config" in r.stderr, "no config: expected exit 2")
    check(not (work / "out").exists(), "bad usage wrote output")


def case_soil_names(a, work):
    """Each soil's name is the one a direct run records: an SCM soil file's `name` (wheel-rig's
    /parameters/terrain/soil_name), a DEM bed's `soil` variable (wheel-cosim's bed/soil), a
    recipe's soil; an explicit `name` is kept; two soils of one name are an error."""
    from wheelsim_sweep import config
    repo = Path(a.sweep).resolve().parents[1]
    mesh = work / "w.stl"
    mesh.write_text("solid w\nendsolid w\n")  # only its existence is checked here
    (work / "base.toml").write_text("[run]\ndt = 1e-4\n")
    bed = work / "soilbin_x.restart"
    bed.write_text("")
    Path(f"{bed}.vars").write_text("variable bed_depth equal 0.03\nvariable soil string ci\n")

    def load(text):
        (work / "sweep.toml").write_text(f'base = "base.toml"\nwheels = ["w.stl"]\n'
                                         f'slips = [0.1]\n{text}')
        return config.load(work / "sweep.toml", repo, work)

    sw = load('terrain = "scm"\nsoils = ["dry_sand", "lete_sand", '
              '{ name = "fine", soil = "dry_sand", grid_spacing = 0.01 }]\n')
    got = [(x.label, x.name) for x in sw.soils]
    check(got == [("dry_sand", "dry sand"), ("lete_sand", "LETE sand"), ("fine", "fine")],
          f"SCM soil names {got}")
    sw = load(f'terrain = "dem"\nsoils = ["{bed}", {{ name = "mine", restart = "{bed}" }}, '
              '{ name = "loose", soil = "ci" }]\n')
    got = [(x.label, x.name) for x in sw.soils]
    check(got == [("soilbin_x", "ci"), ("mine", "mine"), ("loose", "loose")],
          f"DEM soil names {got}")
    sw = load('terrain = "dem"\nsoils = [{ soil = "ci" }]\n')
    check([(x.label, x.name) for x in sw.soils] == [("ci", "ci")], "DEM recipe soil name")
    try:  # the bed's soil and a recipe's soil are both 'ci'
        load(f'terrain = "dem"\nsoils = ["{bed}", {{ soil = "ci" }}]\n')
        raise Fail("two soils named 'ci' were accepted")
    except config.ConfigError as e:
        check("soils[0] and soils[1] have the same soil name 'ci'" in str(e), str(e))
    # a DEM soil include file by path: named by its soil_name; a missing file or one without
    # soil_name is a config error naming the key and the file
    (work / "my").mkdir()
    (work / "my" / "sand.in").write_text("variable soil_name string my_sand\n")
    (work / "my" / "noname.in").write_text("variable soil_ntypes equal 3\n")
    sw = load('terrain = "dem"\nsoils = [{ soil = "my/sand.in" }, '
              '{ name = "b", soil_file = "my/sand.in" }]\n')
    got = [(x.label, x.dem_soil_name, x.recipe) for x in sw.soils]
    f = str((work / "my" / "sand.in").resolve())
    check(got == [("my_sand", "my_sand", {"soil_file": f}), ("b", "my_sand", {"soil_file": f})],
          f"DEM soil files by path {got}")
    for text, msg in (('{ soil = "my/none.in" }', "soils[0].soil: DEM soil file '"),
                      ('{ soil_file = "my/noname.in" }',
                       "soils[0].soil_file: soil file '" + str(work / "my" / "noname.in")
                       + "' does not define variable soil_name"),
                      ('{ soil = "ci", soil_file = "my/sand.in" }', "not both")):
        try:
            load(f'terrain = "dem"\nsoils = [{text}]\n')
            raise Fail(f"accepted: {text}")
        except config.ConfigError as e:
            check(msg in str(e), f"{text}: {e}")
    shutil.copyfile(repo / "inputs" / "scm_soils" / "dry_sand.toml", work / "dry_copy.toml")
    try:
        load('terrain = "scm"\nsoils = ["dry_sand", "dry_copy.toml"]\n')
        raise Fail("two soils named 'dry sand' were accepted")
    except config.ConfigError as e:
        check("soils[0] and soils[1] have the same soil name 'dry sand'" in str(e), str(e))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case")
    ap.add_argument("--sweep", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    sys.dont_write_bytecode = True
    sys.path.insert(0, str(Path(a.sweep).resolve().parent))
    work = Path(a.work)
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    try:
        globals()[f"case_{a.case}"](a, work)
    except Fail as e:
        print(f"FAIL: {a.case}: {e}")
        return 1
    except Skip as e:
        print(f"SKIP: {a.case}: {e}")
        return SKIP
    print(f"PASS: {a.case}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
