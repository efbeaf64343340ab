#!/usr/bin/python3
"""Unit tests of scripts/wheelsim_sweep (no wheel-rig runs; milliseconds to a second each).

  test_sweep_unit.py CASE --sweep scripts/wheel-sweep --work DIR

CASE: toml_roundtrip, cli, soil_names, tiled_recipe, estimate_arithmetic, estimate_active,
rate_cache, budget, slip_control, accept_change, included_at_start, terrain_switch,
resumed_wall, parked_beds (see
each function and tests/sweep/CMakeLists.txt).
Exit 0 pass, 1 fail, 77 skip (a prerequisite missing).
"""

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tomllib
import time
from pathlib import Path

SKIP = 77


class Fail(Exception):
    pass


class Skip(Exception):
    pass


def check(cond, msg):
    if not cond:
        raise Fail(msg)


def _stand_in_rig(build, keys=(), otherwise="exit 1\n"):
    """A stand-in `<build>/bin/wheel-rig` (these tests run none): `--list-keys` prints a schema with
    wheel-rig's three terrain types (the sweep's `terrain` names come from it) and `keys`
    ((table, key) pairs, for [override] checks); any other call runs `otherwise`."""
    schema = json.dumps({
        "tables": ["wheel", "rig", "motor", "carriage", "run", "terrain", "output"],
        "terrain_types": {"flat": {}, "dem": {}, "scm": {}},
        "keys": [{"table": t, "key": k} for t, k in keys]})
    (build / "bin").mkdir(parents=True, exist_ok=True)
    rig = build / "bin" / "wheel-rig"
    rig.write_text(f"#!/bin/sh\nif [ \"$1\" = --list-keys ]; then\n  echo '{schema}'\n  exit 0\nfi\n"
                   + otherwise)
    rig.chmod(0o755)


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
    r = _run(a, str(cfg), "--park")
    check(r.returncode == 2 and "--park keeps checkpoints in the archive: it needs --archive DIR"
          in r.stderr, "--park without --archive: expected exit 2 naming --archive")
    r = _run(a, str(cfg), "--park", "--archive", str(work / "a"), "--force")
    check(r.returncode == 2 and "--park runs nothing: not with" in r.stderr,
          "--park --force: expected exit 2")
    # scripts/park-running: a PID that is no sweep or lab run is refused, naming it
    park_running = Path(a.sweep).resolve().parent / "park-running"
    r = subprocess.run([str(park_running), str(os.getpid())], capture_output=True, text=True,
                       timeout=30)
    check(r.returncode == 2 and f"PID {os.getpid()} is not a running wheel-sweep or soil-lab run"
          in r.stderr, f"park-running with this test's PID: exit {r.returncode}, {r.stderr!r}")
    r = _run(a)
    check(r.returncode == 2 and "config" in r.stderr, "no config: expected exit 2")
    r = _run(a, str(cfg), "--beds-only", "--dry-run")
    check(r.returncode == 2 and "--beds-only prepares beds: not with --dry-run" in r.stderr,
          "--beds-only --dry-run: expected exit 2")
    scm = Path(a.sweep).resolve().parents[1] / "inputs" / "sweeps" / "demo_scm.toml"
    r = _run(a, str(scm), "--beds-only", "--out-dir", str(work / "out"))
    check(r.returncode == 2 and "only DEM sweeps have beds" in r.stderr,
          f"--beds-only on an SCM sweep: expected exit 2 naming it, got {r.returncode}: "
          f"{r.stderr!r}")
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
    _stand_in_rig(work)

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


def case_tiled_recipe(a, work):
    """Tiled-bed recipe keys (docs/soil-bins.md "Tiled beds"): tile_length = 0.25 is accepted
    and kept in the recipe; bad values (0, negative, a string, true), the relaxation keys without
    tile_length, and tile_length with a compaction are config errors naming the key and what is
    expected. A recorded recipe that differs in the tile keys only is a re-preparation
    (runner._prep_keys_changed says which), in any other key not. The estimate of a tiled bed
    weights each part by its particles (exact arithmetic)."""
    from types import SimpleNamespace as NS
    from wheelsim_sweep import config, estimate as E, runner
    repo = Path(a.sweep).resolve().parents[1]
    mesh = work / "w.stl"
    mesh.write_text("solid w\nendsolid w\n")
    (work / "base.toml").write_text("[run]\ndt = 1e-4\n")
    _stand_in_rig(work)

    def load(entry):
        (work / "sweep.toml").write_text(f'terrain = "dem"\nbase = "base.toml"\n'
                                         f'wheels = ["w.stl"]\nslips = [0.1]\nsoils = [{entry}]\n')
        return config.load(work / "sweep.toml", repo, work)

    sw = load('{ soil = "ci", bin_length = 1.0, tile_length = 0.25, tile_end_zone = 4 }')
    check(sw.soils[0].recipe == {"soil": "ci", "bin_length": 1.0, "tile_length": 0.25,
                                 "tile_end_zone": 4}, f"recipe {sw.soils[0].recipe}")
    for entry, msg in (
            ('{ soil = "ci", tile_length = 0 }', "soils[0].tile_length must be a number > 0 m"),
            ('{ soil = "ci", tile_length = -0.25 }', "soils[0].tile_length must be a number > 0 m"),
            ('{ soil = "ci", tile_length = "0.25" }', "soils[0].tile_length must be a number > 0"),
            ('{ soil = "ci", tile_length = true }', "soils[0].tile_length must be a number"),
            ('{ soil = "ci", tile_length = 0.25, tile_relax_max = 0 }',
             "soils[0].tile_relax_max must be a number > 0 s"),
            ('{ soil = "ci", tile_length = 0.25, tile_end_zone = -1 }',
             "soils[0].tile_end_zone must be a number >= 0 d_max"),
            ('{ soil = "ci", tile_relax_time = 0.1 }',
             "soils[0]: tile_relax_time only apply to a tiled bed: add tile_length"),
            ('{ soil = "ci", tile_length = 0.25, compaction = "plate" }',
             "soils[0].tile_length needs compaction = \"none\" (got 'plate')"),
            ('{ soil = "ci", tile_lenght = 0.25 }', "did you mean 'tile_length'")):
        try:
            load(entry)
            raise Fail(f"accepted: {entry}")
        except config.ConfigError as e:
            check(msg in str(e), f"{entry}: {e}")
    rec = work / "bed.recipe.json"
    rec.write_text('{"soil": "ci", "bin_length": 1.0, "tile_length": 0.25}')

    def same(value):  # no paths to make portable here
        return value
    got = runner._prep_keys_changed(rec, {"soil": "ci", "bin_length": 1.0, "tile_length": 0.2},
                                    same)
    check(got == "tile_length 0.25 -> 0.2", f"changed tile_length: {got!r}")
    got = runner._prep_keys_changed(rec, {"soil": "ci", "bin_length": 1.0}, same)
    check(got == "tile_length 0.25 -> unset", f"tile_length removed: {got!r}")
    got = runner._prep_keys_changed(rec, {"soil": "ci", "bin_length": 2.0, "tile_length": 0.2},
                                    same)
    check(got is None, f"bin_length changed too: {got!r} (expected None: another bed)")
    # estimate: 1.0 m bin of 4 blocks (0.25 m), d_max 0.02 m, end zones 6 d_max = 0.12 m
    # (weight 0.24), check 0.02 s, max_settle 3 s, relax 0.1 s + bound 0.5 s, dt 1e-4 s:
    # steps 30 000 x 0.25 + 6000 x 0.24 + 5000 x 1 = 13 940, + 1 insertion step
    soilbin = repo / "inputs" / "in.soilbin"
    sv = {"soil_name": "x", "soil_dt": 1e-4, "soil_density": 2500.0, "soil_dref": 0.012,
          "soil_dmax": 0.02, "soil_d1": 0.012, "soil_w1": 1.0}
    soil = NS(label="x", dem_soil_file=None,
              recipe={"soil": "x", "bin_length": 1.0, "bin_width": 0.5, "fill_height": 0.2,
                      "tile_length": 0.25})
    bi = E.bed_info(soil, work / "none" / "x.restart", lambda f: sv, soilbin)
    check(bi.prep_parts.keys() == {"block settle", "end-zone relax", "relax"},
          f"parts {bi.prep_parts}")
    _close(bi.prep_parts["block settle"], 3.0, "block settle", 1e-9)
    _close(bi.prep_parts["end-zone relax"], 0.6, "end-zone relax", 1e-9)
    _close(bi.prep_parts["relax"], 0.5, "relax", 1e-9)
    _close(bi.prep_weights["block settle"], 0.25, "block weight")
    _close(bi.prep_weights["end-zone relax"], 0.24, "end-zone weight")
    check(bi.prep_steps == 13941, f"particle-weighted steps {bi.prep_steps}, expected 13 941")
    whole = NS(label="x", dem_soil_file=None,
               recipe={k: v for k, v in soil.recipe.items() if k != "tile_length"})
    bw = E.bed_info(whole, work / "none" / "x.restart", lambda f: sv, soilbin)
    check(bw.prep_steps == 30001 and not bw.prep_weights, f"whole bed steps {bw.prep_steps}")
    # a multisphere soil's bed is counted in spheres: its particles times the query's spheres
    # per particle (2.1: loose sand's mix), or its particles with the reason when not known
    class Query:
        def __init__(self, mix):
            self.mix = mix

        def __call__(self, soil_file):
            return {**sv, "soil_multisphere": 1.0}

        def spheres_per_particle(self, soil_file):
            return self.mix
    bm = E.bed_info(whole, work / "none" / "x.restart", Query((2.1, "2.1 spheres per particle")),
                    soilbin)
    _close(bm.particles, 2.1 * bw.particles, "multisphere bed in spheres")
    check("multisphere: x 2.1 spheres per particle" in bm.particles_source, bm.particles_source)
    bu = E.bed_info(whole, work / "none" / "x.restart", Query((None, "a mass-based mix")), soilbin)
    _close(bu.particles, bw.particles, "multisphere bed, ratio unknown")
    check("clumps counted once, so low (a mass-based mix)" in bu.particles_source,
          bu.particles_source)


# ---- the DEM cost estimate (scripts/wheelsim_sweep/estimate.py, rate.py) ------------------------
def _close(got, want, what, rel=1e-12):
    check(abs(got - want) <= rel * abs(want), f"{what}: {got!r}, expected {want!r}")


def _synthetic_rig(dt=1e-4):
    """release 0.25 s (gap 2 mm at 10 mm/s reached over 0.1 s: 0.1 + 1.5 mm / 10 mm/s), settle
    <= 0.5 s, ramp 0.25 s, test 1.0 s: 2.0 s simulated = 20 000 steps of 1e-4 s."""
    return {"run": {"dt": dt, "duration": 1.0, "release_gap": 0.002, "release_speed": 0.01,
                    "settle_max_time": 0.5},
            "motor": {"omega": 1.0, "ramp_time": 0.25}}


def case_estimate_arithmetic(a, work):
    """The estimate's arithmetic on a synthetic sweep with known particles, dt, phases and rate:
    exact numbers for the phases, steps, per-point wall (np 1, 2, 4; oversubscribed), the list
    schedule, a bed to prepare, skipped finished points, the mean grain volume, the particle
    count of a recipe and of a prepared bed's log."""
    from types import SimpleNamespace as NS
    from wheelsim_sweep import estimate as E
    _close(E.release_time(0.002, 0.01), 0.25, "release, gap beyond the acceleration")
    _close(E.release_time(0.0002, 0.01), math.sqrt(0.004), "release within the acceleration")
    ph = E.phases(_synthetic_rig())
    check(ph == {"release": ph["release"], "settle": 0.5, "ramp": 0.25, "test": 1.0}, str(ph))
    _close(ph["release"], 0.25, "phases release")
    try:
        E.phases({"run": {"dt": 1e-4}})
        raise Fail("a rig without run.duration was estimated")
    except E.EstimateError as e:
        check("run.duration" in str(e), str(e))
    check(E.efficiency(1, 0.8) == 1.0, "eff(1)")
    _close(E.efficiency(2, 0.8), 0.8, "eff(2)")
    _close(E.efficiency(4, 0.8), 0.64, "eff(4)")
    # 10 000 particles x 20 000 steps = 2e8 particle-steps at 2e6 /s/rank, startup 2 s
    _close(E.run_wall(1e4, 20000, 1, 2e6, 0.8, 2.0), 102.0, "np 1")
    _close(E.run_wall(1e4, 20000, 2, 2e6, 0.8, 2.0), 64.5, "np 2")
    _close(E.run_wall(1e4, 20000, 4, 2e6, 0.8, 2.0), 2.0 + 2e8 / (2e6 * 4 * 0.64), "np 4")
    _close(E.schedule([10.0, 20.0, 30.0], 2), 40.0, "schedule 2 slots")
    _close(E.schedule([10.0, 20.0, 30.0], 5), 30.0, "schedule more slots than points")

    soil = NS(label="bed1")
    pts = [NS(index=i, soil=soil, rig=_synthetic_rig(), reldir=f"w/bed1/s{i}") for i in range(3)]
    info = E.BedInfo("bed1", 1e4, "test", 1e-4, "test", prepared=False, prep_steps=5001,
                     prep_parts={"settle": 0.5})
    rate = E.Rate(2e6, 0.8, 2.0, 1e6, "test")
    # 3 points, 2 jobs x 2 ranks on 2 cores: oversubscribed x2 -> (2 + 62.5 x 2) = 127 s each;
    # two slots: 254 s; the bed (1 rank, 1e6 /s): 2 + 5001 x 1e4 / 1e6 = 52.01 s
    est = E.estimate(pts, {"bed1": info}, rate, 2, 1, 2, 2, overhead_s=0.0)
    check([e.steps for e in est.points] == [20000] * 3, f"steps {[e.steps for e in est.points]}")
    _close(est.points[0].sim_time, 2.0, "simulated time")
    _close(est.points[0].wall, 127.0, "oversubscribed point")
    _close(est.points_wall, 254.0, "points wall")
    _close(est.beds_wall, 52.01, "bed wall")
    _close(est.total, 306.01, "total")
    # the same on 4 cores: not oversubscribed; the first point finished: 2 left, 1 wave
    est = E.estimate(pts, {"bed1": info}, rate, 2, 1, 2, 4, finished=lambda p: p.index == 0,
                     overhead_s=0.0)
    check(len(est.todo) == 2 and est.points[0].finished, "finished point not skipped")
    _close(est.points_wall, 64.5, "points wall, 2 left on 4 cores")
    line = E.summary_line(est)
    check("2 point(s) to run" in line and "10 000 particles" in line
          and "20 000 steps" in line and "1 min 4 s per point" in line, line)
    # a point resuming from a checkpoint at 5 000 of its 20 000 steps: the wall of the rest; a
    # finished point's checkpoint is not counted
    resumed = E.estimate(pts, {"bed1": info}, rate, 2, 1, 2, 4, finished=lambda p: p.index == 0,
                         overhead_s=0.0, steps_done=lambda p: 5000 if p.index < 2 else 0)
    _close(resumed.points[1].wall, 64.5 * 0.75, "a resumed point's wall")
    _close(resumed.points[2].wall, 64.5, "a point without a checkpoint")
    check(resumed.points[0].steps_done == 0 and resumed.points[1].steps_done == 5000,
          f"steps done {[e.steps_done for e in resumed.points]}")
    check("resumes from a checkpoint at step 5 000 of 20 000: the wall is that of the 15 000 "
          "steps left" in "\n".join(E.report(resumed, "synthetic.toml")), "the resume line")
    rep = "\n".join(E.report(est, "synthetic.toml"))
    for want in ("point w/bed1/s0 (finished, skipped)", "point w/bed1/s1 (to run)",
                 "settle <= 0.5", "steps 20 000", "wall 1 min 4 s (64 s)", "bed bed1 (to prepare",
                 "steps <= 5 001", "1 min 56 s (117 s"):
        check(want in rep, f"report lacks {want!r}:\n{rep}")
    # a prepared bed whose bed-hold check is still to run: 0.2 s at its dt 1e-4 = 2000 steps,
    # 2 + 2000 x 1e4 / 1e6 = 22 s on 1 rank
    held = E.BedInfo("bed1", 1e4, "test", 1e-4, "test", prepared=True)
    est = E.estimate(pts, {"bed1": held}, rate, 2, 1, 2, 4, overhead_s=0.0)
    check(not est.beds, "a prepared bed counted")
    E.add_bed_hold(held, 0.2)
    est = E.estimate(pts, {"bed1": held}, rate, 2, 1, 2, 4, overhead_s=0.0)
    _close(est.beds_wall, 22.0, "bed-hold check wall")
    line = E.summary_line(est)
    rep = "\n".join(E.report(est, "synthetic.toml"))
    check("+ 1 bed-hold check(s) <= 22.0 s" in line and "bed to prepare" not in line
          and "bed bed1 (prepared, its bed-hold check to run" in rep
          and "bed-hold check 0.2" in rep, f"the pending bed-hold check:\n{line}\n{rep}")
    # whole chunks of the deck's steps; the per-point overhead
    est = E.estimate(pts, {"bed1": info}, rate, 1, 1, 1, 4, chunk=3000, overhead_s=1.5)
    check(est.points[0].steps == 21000, f"chunked steps {est.points[0].steps}")
    _close(est.points[0].wall, 2.0 + 1.5 + 21000 * 1e4 / 2e6, "wall with chunks and overhead")
    deck = work / "in.deck"
    deck.write_text("variable chunk index 500   # [steps]\n")
    check(E.deck_chunk(deck) == 500 and E.deck_chunk(deck, ["-var", "chunk", "200"]) == 200
          and E.deck_chunk(work / "missing") == 1, "deck_chunk")
    # the release sinks 0.15 x the wheel's outer radius beyond the gap: effective_radius, else
    # the ascii STL's largest distance from the axle (y) x mesh_scale
    stl = work / "w.stl"
    stl.write_text("solid w\nfacet normal 0 0 1\n outer loop\n  vertex 0.3 0.1 0.4\n"
                   "  vertex 0 -0.1 0.2\n  vertex 0.1 0 0\n endloop\nendfacet\nendsolid w\n")
    check(E.wheel_radius({"wheel": {"effective_radius": 0.7}}, stl) == 0.7, "effective_radius")
    _close(E.wheel_radius({"wheel": {"mesh_scale": 2.0}}, stl), 1.0, "mesh radius x scale")
    check(E.wheel_radius({}, work / "missing.stl") is None, "no mesh: no radius")
    _close(E.phases(_synthetic_rig(), 0.1)["release"], 0.1 + (0.002 + 0.015 - 0.0005) / 0.01,
           "release with the sinkage allowance")
    # run.dt missing: the bed's dt
    pts[1].rig["run"].pop("dt")
    est = E.estimate(pts, {"bed1": info}, rate, 1, 1, 1, 1)
    check(est.points[1].dt_source == "test" and est.points[0].dt_source == "run.dt", "dt source")

    # the mean grain volume: ci's classes (mass fractions), equal numbers, d_ref only
    V = [math.pi / 6 * d ** 3 for d in (0.004, 0.006, 0.008)]
    ci = {"soil_d1": 0.004, "soil_d2": 0.006, "soil_d3": 0.008, "soil_w1": 0.25, "soil_w2": 0.5,
          "soil_w3": 0.25, "soil_density": 2500.0, "soil_dt": 4.89543219523472e-05,
          "soil_name": "ci", "soil_dref": 0.006, "soil_multisphere": 0.0}
    _close(E.mean_grain_volume(ci)[0], 1.0 / (0.25 / V[0] + 0.5 / V[1] + 0.25 / V[2]), "ci V")
    eq = {k: v for k, v in ci.items() if not k.startswith("soil_w")}
    _close(E.mean_grain_volume(eq)[0], sum(V) / 3, "equal numbers V")
    _close(E.mean_grain_volume({"soil_dref": 0.01})[0], math.pi / 6 * 1e-6, "d_ref V")
    # a recipe (dem_small_slips' bin): 0.36 x 0.12 x 0.035 x 0.6 / V = 11 625 (LIGGGHTS
    # inserted 11 624, issue 12); in.soilbin's defaults for the keys not given
    repo = Path(a.sweep).resolve().parents[1]
    soilbin = repo / "inputs" / "in.soilbin"
    recipe = NS(label="ci_small", recipe={"soil": "ci", "bin_length": 0.36, "bin_width": 0.12,
                                          "fill_height": 0.035}, dem_soil_file=Path("ci.in"))
    bi = E.bed_info(recipe, work / "none" / "soilbin_ci.restart", lambda f: ci, soilbin)
    n = 0.36 * 0.12 * 0.035 * 0.6 / E.mean_grain_volume(ci)[0]
    _close(bi.particles, n, "recipe particles")
    check(round(bi.particles) == 11625 and not bi.prepared, f"recipe particles {bi.particles}")
    check(bi.prep_parts == {"settle": 3.0} and bi.prep_steps == 1 + math.ceil(3.0 / ci["soil_dt"]),
          f"bed prep (max_settle_time 3 s, in.soilbin's default): {bi.prep_parts} {bi.prep_steps}")
    # the bed-hold check (wheel-sweep --bed-hold 0.2) adds its 0.2 s on the whole bed
    bi = E.bed_info(recipe, work / "none" / "soilbin_ci.restart", lambda f: ci, soilbin, 0.2)
    check(bi.prep_parts == {"settle": 3.0, "bed-hold check": 0.2} and bi.prep_steps ==
          1 + math.ceil(3.0 / ci["soil_dt"]) + math.ceil(0.2 / ci["soil_dt"]),
          f"bed prep with the bed-hold check: {bi.prep_parts} {bi.prep_steps}")
    recipe.recipe.update(compaction="plate", plate_time=0.4, max_settle_time=0.5)
    bi = E.bed_info(recipe, work / "none" / "soilbin_ci.restart", lambda f: ci, soilbin)
    _close(sum(bi.prep_parts.values()), 0.5 + 0.5 + 1.25 * 0.4, "plate compaction")
    # a prepared bed: particles from the in.soilbin log that names it (the driver's temporary
    # name), dt from its .vars; the soil is not asked
    bed = work / "bed" / "soilbin_ci.restart"
    bed.parent.mkdir()
    bed.write_text("x")
    Path(f"{bed}.vars").write_text("variable soil index ci\nvariable bed_dt index 5e-05\n")
    (bed.parent / "soilbin.log").write_text(
        "soilbin: particles = 7\nsoilbin: spheres = 7\nsoilbin: restart = /x/other.restart\n"
        "soilbin: particles = 11624\nsoilbin: spheres = 11624\n"
        f"soilbin: restart = {bed.parent}/soilbin_ci.part.restart\n")

    def no_query(f):
        raise Fail("the soil was asked for a prepared bed with a log")
    bi = E.bed_info(recipe, bed, no_query, soilbin)
    check(bi.prepared and bi.particles == 11624 and bi.dt == 5e-05, f"prepared bed: {bi}")
    # without the log: bulk density x volume / (particle density x V)
    (bed.parent / "soilbin.log").unlink()
    Path(f"{bed}.vars").write_text("variable soil index ci\nvariable bin_length index 0.36\n"
                                   "variable bin_width index 0.12\nvariable bed_depth index 0.035\n"
                                   "variable bulk_density index 1500\n")
    bi = E.bed_info(recipe, bed, lambda f: ci, soilbin)
    _close(bi.particles, 1500 * 0.36 * 0.12 * 0.035 / (2500 * E.mean_grain_volume(ci)[0]),
           ".vars particles")
    check(bi.dt is None, "a .vars without bed_dt gave a dt")


def case_particle_mix(a, work):
    """A soil's particle distribution read from its deck text: `&` continuations and comments,
    the distribution soil_distribution names among two, sphere templates 1 and multisphere ones
    their nspheres, weights as written; a template not found, a multisphere template without
    nspheres, no distribution, a pair missing: a reason, not a number."""
    from wheelsim_sweep import estimate as E
    text = """variable soil_distribution string soil_pdd   # the soil's
fix soil_pt1 all particletemplate/sphere 15485863 atom_type 3 density constant 2000 radius constant 0.005
fix soil_pt_box all particletemplate/multisphere 67867967 atom_type 4 &
    density constant 2000 nspheres 8 ntry 200000 spheres &
    0 0 0 0.003  # a comment with nspheres 99
fix soil_pt_hull all particletemplate/multisphere 67867979 atom_type 5 density constant 2000 nspheres 5 ntry 1 spheres
fix other all particledistribution/discrete 1 1 soil_pt1 1.0
fix soil_pdd all particledistribution/discrete/numberbased 32452867 3 &
    soil_pt1 ${soil_n1} soil_pt_box 0.1 soil_pt_hull $(0.5*v_x)   # boxes and hulls
"""
    got = E.particle_mix(text)
    check(got == (True, [("soil_pt1", "${soil_n1}", 1), ("soil_pt_box", "0.1", 8),
                         ("soil_pt_hull", "$(0.5*v_x)", 5)]), f"the mix: {got}")
    # without soil_distribution the last distribution is the soil's
    got = E.particle_mix(text.replace("variable soil_distribution string soil_pdd", ""))
    check(got[1][0][0] == "soil_pt1" and len(got[1]) == 3, f"the last distribution: {got}")
    check(E.particle_mix(text.replace("string soil_pdd", "string other")) ==
          (False, [("soil_pt1", "1.0", 1)]), "the named mass-based distribution")
    for broken, why in ((text.replace("soil_pt_hull $(0.5*v_x)", "soil_pt_cone 0.2"),
                         "template soil_pt_cone not found"),
                        (text.replace("nspheres 5 ", ""), "template soil_pt_hull: no nspheres"),
                        ("variable x equal 1\n", "no particledistribution/discrete"),
                        (text.replace("numberbased 32452867 3", "numberbased 32452867 4"),
                         "4 templates announced, 3 given")):
        got = E.particle_mix(broken)
        check(isinstance(got, str) and why in got, f"{why!r}: got {got!r}")


def case_estimate_active(a, work):
    """The active domain in the estimate (scripts/wheelsim_sweep/active_domain.py): the share of a
    bed inside the sphere of radius R + D against closed forms (a whole sphere, a half sphere at
    the surface, within 1 %), the fix's defaults (D = 0.5 R + 2 z, z = R / 4: R + D = 2 R), the
    deck's and liggghts_args' settings, the wheel's path (hold, ramp, constant speed; exact), the
    point's cost N x (share + FROZEN_COST x (1 - share)) exactly, and the calibration by the
    sweep's finished points (measured / modelled wall of that bed's points, exact)."""
    from types import SimpleNamespace as NS
    from wheelsim_sweep import active_domain as A
    from wheelsim_sweep import estimate as E
    # a sphere of 0.1 m about (0.5, 0, 0.5) in a 1 x 1 x 1 m bed: 4/3 pi r^3 of it
    whole = 4.0 / 3.0 * math.pi * 0.1 ** 3
    _close(A.sphere_share(1.0, 1.0, 1.0, 0.1, [(0.5, 0.5)]), whole, "whole sphere", rel=0.01)
    # centred on the surface of a 0.5 m deep bed: half of it, of half the volume
    _close(A.sphere_share(1.0, 1.0, 0.5, 0.1, [(0.5, 0.5)]), whole, "half sphere", rel=0.01)
    # above the bed by more than its radius: nothing; a sphere holding the bed: all of it
    check(A.sphere_share(1.0, 1.0, 0.5, 0.1, [(0.5, 0.61)]) == 0.0, "sphere above the bed")
    _close(A.sphere_share(1.0, 1.0, 0.5, 2.0, [(0.5, 0.5)]), 1.0, "bed inside the sphere")
    # the fix's defaults and keywords
    check(A.ActiveSettings().reach(0.3) == 0.6, "default reach 2 R")
    check(A.ActiveSettings(distance=0.1).reach(0.3) == 0.4, "distance")
    _close(A.ActiveSettings(sinkage=0.05).reach(0.3), 0.3 + 0.15 + 0.1, "sinkage allowance")
    deck = work / "in.deck"
    deck.write_text("variable active_domain index 0\nvariable active_args index \"\"\n"
                    "variable x0 index 0.25\n")
    check(A.settings(deck) is None, "the deck's default is off")
    s = A.settings(deck, ["-var", "active_domain", "1", "-var", "active_args",
                          "distance 0.2 hysteresis 0.01 sinkage 0.03"])
    check(s == A.ActiveSettings(distance=0.2, sinkage=0.03), f"settings {s}")
    check(A.start_x(deck) == 0.25 and A.start_x(deck, ["-var", "x0", "1.5"]) == 1.5, "x0")
    # the path: 1 s held, a 1 s ramp to 0.5 m/s (0.25 m), then 0.5 m/s; clipped at the far wall
    ph = {"release": 0.6, "settle": 0.4, "ramp": 1.0, "test": 2.0}
    xs = A.wheel_path(ph, 0.1, 0.5, 10.0, samples=4)  # t = 0.5, 1.5, 2.5, 3.5 s
    for got, want in zip(xs, (0.1, 0.1 + 0.0625, 0.1 + 0.25 + 0.25, 0.1 + 0.25 + 0.75)):
        _close(got, want, "wheel path")
    check(A.wheel_path(ph, 0.1, 0.5, 0.4, samples=4)[-1] == 0.4, "path clipped to the bin")
    _close(A.travel_speed({"motor": {"omega": 2.0}}, 0.25, 0.5), 0.75, "driving speed")
    _close(A.travel_speed({"motor": {"omega": 2.0}}, -0.5, 0.5), 2.0, "skid speed")
    check(A.travel_speed({"carriage": {"speed": 0.3}}, 0.2, 0.5) == 0.3, "imposed speed")
    # an estimate with the active domain: a wheel of bounding radius 0.5 m (vertex (0.3, 0.4, 0)),
    # outer radius 0.5 m; bed 4 x 1 x 0.3 m of 1e5 particles, the wheel held at x0 = 1 (no motor)
    stl = work / "wheel.stl"
    stl.write_text("solid w\nfacet normal 0 0 1\n outer loop\n  vertex 0.3 0 0.4\n"
                   "  vertex 0 0.1 0.2\n  vertex 0.1 0 0\n endloop\nendfacet\nendsolid w\n")
    check(A.mesh_extent(stl) == (0.5, 0.5), f"mesh extent {A.mesh_extent(stl)}")
    soil = NS(label="bed")
    rig = {"run": {"dt": 1e-4, "duration": 1.0, "settle_max_time": 0.5}, "motor": {"ramp_time": 0}}
    pts = [NS(index=i, soil=soil, rig=rig, reldir=f"w/bed/s{i}", slip=0.2,
              wheel=NS(mesh=stl)) for i in range(3)]
    info = E.BedInfo("bed", 1e5, "test", 1e-4, "test", prepared=True, box=(4.0, 1.0, 0.3))
    rate = E.Rate(2e6, 1.0, 0.0, 1e6, "test")
    off = E.estimate(pts, {"bed": info}, rate, 1, 1, 1, 1, overhead_s=0.0)
    on = E.estimate(pts, {"bed": info}, rate, 1, 1, 1, 1, overhead_s=0.0,
                    active=A.ActiveSettings(), x0=1.0)
    share = A.sphere_share(4.0, 1.0, 0.3, 1.0, [(1.0, 0.3 + 0.5 - 0.125)])
    e = on.points[0]
    _close(e.active_share, share, "active share")
    _close(e.wall, off.points[0].wall * (share + E.FROZEN_COST * (1.0 - share)), "active wall")
    check(0.05 < share < 0.5 and "1 m of the wheel centre" in e.active_note, e.active_note)
    # the default sinkage allowance is named with how to set it; an explicit one is not
    check("default sinkage allowance R/4 = 0.125 m" in e.active_note
          and 'active_args "sinkage Z"' in e.active_note, e.active_note)
    own = E.estimate(pts, {"bed": info}, rate, 1, 1, 1, 1, overhead_s=0.0,
                     active=A.ActiveSettings(sinkage=0.2), x0=1.0)
    check("default sinkage" not in own.points[0].active_note, own.points[0].active_note)
    check(off.points[0].active_share is None and not off.points[0].active_note, "off")
    # no bed size: the active domain is left out, and the printout says so
    nobox = E.BedInfo("bed", 1e5, "test", 1e-4, "test", prepared=True)
    left = E.estimate(pts, {"bed": nobox}, rate, 1, 1, 1, 1, overhead_s=0.0,
                      active=A.ActiveSettings(), x0=1.0)
    check(left.points[0].wall == off.points[0].wall
          and "left out" in "\n".join(E.report(left, "s.toml")), "left out")
    # calibration: point 0 finished in 3 x its modelled wall; the others are scaled by 3
    cal = E.estimate(pts, {"bed": info}, rate, 1, 1, 1, 1, overhead_s=0.0,
                     active=A.ActiveSettings(), x0=1.0, finished=lambda p: p.index == 0,
                     measured_wall=lambda p: 3.0 * e.wall if p.index == 0 else None)
    _close(cal.points[1].wall, 3.0 * e.wall, "calibrated wall")
    check(cal.points[1].calibration_points == 1 and cal.points[0].calibration is None,
          "calibration bookkeeping")
    rep = "\n".join(E.report(cal, "s.toml"))
    check("scaled by 3: the measured / estimated wall of 1 finished point(s)" in rep, rep)
    # where the travel ends: no motor, no speed, no note; at omega 2 rad/s, slip 0.2 and outer
    # radius 0.5 m the wheel runs 0.8 m/s for the 1 s test (no ramp) from x0 = 1: centre 1.8 m,
    # rim front 2.3 m, 1.7 m from the far wall of the 4 m bed; in a 2 m bed 0.3 m past it
    check(e.end_gap_m is None and not e.end_note, f"no speed: {e.end_note!r}")
    driven = [NS(index=0, soil=soil, rig={**rig, "motor": {"ramp_time": 0, "omega": 2.0}},
                 reldir="w/bed/s0.2", slip=0.2, wheel=NS(mesh=stl))]
    end = E.estimate(driven, {"bed": info}, rate, 1, 1, 1, 1, overhead_s=0.0, x0=1.0).points[0]
    _close(end.end_gap_m, 1.7, "gap to the far wall")
    check("ends at x = 1.8 m of the 4 m bin, its rim's front 1.7 m from the far wall (3.4 outer "
          "radii)" in end.end_note and end.end_note in "\n".join(E.report(
              E.estimate(driven, {"bed": info}, rate, 1, 1, 1, 1, x0=1.0), "s.toml")),
          end.end_note)
    short = E.BedInfo("bed", 1e5, "test", 1e-4, "test", prepared=True, box=(2.0, 1.0, 0.3))
    past = E.estimate(driven, {"bed": short}, rate, 1, 1, 1, 1, x0=1.0).points[0]
    _close(past.end_gap_m, -0.3, "past the wall")
    check("past the far wall: its rim's front would be 0.3 m beyond it" in past.end_note,
          past.end_note)


def _rate_entry(key, **kw):
    e = dict(key, measured_at="2026-01-01 00:00 UTC", cores=2, load_average_1min=0.5,
             particles=14000, steps=2000, rate_per_rank=1.5e6, efficiency_np2=0.8,
             startup_s=1.0, bed_rate_per_rank=1.2e6)
    e.update(kw)
    return e


def case_rate_cache(a, work):
    """The rate cache: a missing file gives the defaults and says so; a written entry is read
    back for the same host, CPU and liggghts-wheel version, and for another commit of the same
    release (saying so); another release is stale (defaults, naming both versions); writing replaces the entry of the same host and CPU and keeps other
    machines'; a damaged file is an error naming it."""
    from wheelsim_sweep import rate as R
    from wheelsim_sweep.estimate import EstimateError
    path = work / "cache" / "dem_rate.toml"
    os.environ["WHEELSIM_RATE_CACHE"] = str(path)
    check(R.cache_path() == path, f"cache_path {R.cache_path()} ignores WHEELSIM_RATE_CACHE")
    key = R.machine_key("liggghts-wheel 0.1.0 (git aaaa)")
    r = R.lookup(path, key)
    check(r.rate_per_rank == R.DEFAULT["rate_per_rank"] and "DEFAULT" in r.source
          and "missing" in r.source, f"missing cache: {r}")
    R.write_cache(path, _rate_entry(key))
    other = _rate_entry({"host": "elsewhere", "cpu": "x", "liggghts_wheel": "v"},
                        rate_per_rank=9e6)
    R.write_cache(path, other)
    r = R.lookup(path, key)
    check((r.rate_per_rank, r.efficiency_np2, r.startup_s, r.bed_rate_per_rank)
          == (1.5e6, 0.8, 1.0, 1.2e6) and "measured 2026-01-01" in r.source, f"cached: {r}")
    commit = R.machine_key("liggghts-wheel 0.1.0 (git cccc)")
    r = R.lookup(path, commit)
    check(r.rate_per_rank == 1.5e6 and "git aaaa" in r.source and "git cccc" in r.source
          and "re-measure" in r.source, f"another commit of the release: {r.source}")
    stale = R.machine_key("liggghts-wheel 0.2.0 (git bbbb)")
    r = R.lookup(path, stale)
    check(r.rate_per_rank == R.DEFAULT["rate_per_rank"] and "0.1.0 (git aaaa)" in r.source
          and "0.2.0 (git bbbb)" in r.source, f"stale version not reported: {r.source}")
    R.write_cache(path, _rate_entry(stale, rate_per_rank=2.5e6))  # re-measured: replaces
    entries = R.read_cache(path)
    check(len(entries) == 2 and {e["host"] for e in entries} == {key["host"], "elsewhere"},
          f"entries after re-measuring: {entries}")
    check(R.lookup(path, stale).rate_per_rank == 2.5e6, "the re-measured rate is not used")
    check(R.lookup(path, key).rate_per_rank == R.DEFAULT["rate_per_rank"],
          "the replaced version's rate is still used")
    path.write_text("rate = [")
    try:
        R.lookup(path, key)
        raise Fail("a damaged cache was read")
    except EstimateError as e:
        check(str(path) in str(e), str(e))


def _budget_setup(work):
    """A DEM sweep of 2 points on a fake prepared bed (100 000 spheres by its log, dt 1e-4 s),
    2.0 s simulated = 20 000 steps each; the cached rate 1e6 particle-steps/s, startup 0, and
    wheel-cosim's 3 s: 2003 s per point, 1 job: 4006 s = 1 h 6 min. A stand-in liggghts-wheel
    answers --version only."""
    from wheelsim_sweep import rate as R
    build = work / "build"
    (build / "bin").mkdir(parents=True)
    version = "liggghts-wheel 0.1.0 (git unit)"
    (build / "bin" / "liggghts-wheel").write_text(
        f'#!/bin/sh\nif [ "$1" = --version ]; then echo "{version}"; exit 0; fi\nexit 1\n')
    (build / "bin" / "liggghts-wheel").chmod(0o755)
    _stand_in_rig(build)
    cache = work / "dem_rate.toml"
    R.write_cache(cache, _rate_entry(R.machine_key(version), rate_per_rank=1e6, startup_s=0.0))
    bed = work / "bed" / "soilbin_x.restart"
    bed.parent.mkdir()
    bed.write_text("x")
    Path(f"{bed}.vars").write_text("variable soil index ci\nvariable bed_dt index 1e-4\n"
                                   "variable bed_depth index 0.05\n")
    (bed.parent / "soilbin.log").write_text(f"soilbin: spheres = 100000\n"
                                            f"soilbin: restart = {bed}\n")
    (work / "wheel.stl").write_text("solid w\nendsolid w\n")
    (work / "in.deck").write_text("# not run\n")
    rig = work / "rig.toml"
    rig.write_text('[run]\ndt = 1e-4\nduration = 1.0\nrelease_gap = 0.002\nrelease_speed = 0.01\n'
                   'settle_max_time = 0.5\n[motor]\nomega = 1.0\nramp_time = 0.25\n'
                   '[terrain]\ntype = "dem"\n')
    cfg = work / "sweep.toml"
    cfg.write_text(f'terrain = "dem"\nbase = "rig.toml"\nwheels = ["wheel.stl"]\n'
                   f'soils = ["{bed}"]\nslips = [0.1, 0.2]\n'
                   '[dem]\nnp = 1\ndeck = "in.deck"\nbudget_h = 1.0\n')
    env = dict(os.environ, WHEELSIM_RATE_CACHE=str(cache))
    return build, cfg, env


def case_recipe_values(a, work):
    """A bin recipe's in.soilbin variables are checked before anything runs: lengths > 0 m,
    fractions in (0, 1), compaction one of none/plate/drop, seed a prime > 10000, pour_mu >= 0 or
    -1, integers where the deck counts; each error names the key and what is expected. An
    override of what the slip control sets per point (carriage.slip) is refused, and a config that
    is not UTF-8 text is a one-line error, not a traceback."""
    from wheelsim_sweep import config
    repo = Path(a.sweep).resolve().parents[1]
    (work / "w.stl").write_text("solid w\nendsolid w\n")
    (work / "base.toml").write_text("[run]\ndt = 1e-4\n")
    _stand_in_rig(work, keys=[("carriage", "slip"), ("carriage", "mode")])

    def load(entry, extra=""):
        (work / "sweep.toml").write_text(f'terrain = "dem"\nbase = "base.toml"\n'
                                         f'wheels = ["w.stl"]\nslips = [0.1]\nsoils = [{entry}]\n'
                                         + extra)
        return config.load(work / "sweep.toml", repo, work)

    sw = load('{ soil = "ci", bin_length = 0.36, fill_height = 0.035, seed = 49979687, '
              'compaction = "plate", pour_mu = -1, drop_count = 3 }')
    check(sw.soils[0].recipe["seed"] == 49979687, f"recipe {sw.soils[0].recipe}")
    for entry, msg in (
            ('{ soil = "ci", bin_length = -0.36 }', "soils[0].bin_length must be a number > 0 m"),
            ('{ soil = "ci", fill_height = 0 }', "soils[0].fill_height must be a number > 0 m"),
            ('{ soil = "ci", fill_height = nan }', "soils[0].fill_height must be a number > 0 m"),
            ('{ soil = "ci", fill_solid_fraction = 1.2 }',
             "soils[0].fill_solid_fraction must be a number > 0 and < 1"),
            ('{ soil = "ci", compaction = "vibrate" }',
             "soils[0].compaction must be one of none, plate, drop, got 'vibrate'"),
            ('{ soil = "ci", seed = 1.5 }', "soils[0].seed must be a prime integer > 10000"),
            ('{ soil = "ci", seed = 49979688 }', "soils[0].seed must be a prime integer > 10000"),
            ('{ soil = "ci", drop_count = 2.5 }', "soils[0].drop_count must be an integer >= 1"),
            ('{ soil = "ci", pour_mu = -0.5 }', "soils[0].pour_mu must be a friction >= 0, or -1")):
        try:
            load(entry)
            raise Fail(f"accepted: {entry}")
        except config.ConfigError as e:
            check(msg in str(e), f"{entry}: {e}")
    try:
        load('{ soil = "ci" }', "[override.carriage]\nslip = 0.3\n")
        raise Fail("accepted override.carriage.slip")
    except config.ConfigError as e:
        check("override.carriage.slip: set per point from 'slips'" in str(e), str(e))
    bad = work / "latin1.toml"
    bad.write_bytes(b'description = "caf\xe9"\n')
    try:
        config.load(bad, repo, work)
        raise Fail("accepted a Latin-1 config")
    except config.ConfigError as e:
        check("not a TOML file: byte 0xe9 at offset 18 is not UTF-8 text" in str(e), str(e))


def case_budget(a, work):
    """dem.budget_h and --budget: a DEM sweep estimated over the budget exits 2 naming the
    estimate and the budget, before anything is written; --budget overrides the key; --estimate
    says 'exceeds' and exits 0; --yes (and a budget that suffices) go on to the points."""
    build, cfg, env = _budget_setup(work)
    out = work / "out"

    def run(*args):
        r = subprocess.run([a.sweep, str(cfg), "--build-dir", str(build), "--out-dir", str(out),
                            "--jobs", "1", *args], capture_output=True, text=True, timeout=60,
                           env=env)
        print(f"$ wheel-sweep ... {' '.join(args)} -> exit {r.returncode}\n{r.stdout}{r.stderr}")
        return r
    r = run()
    check(r.returncode == 2, f"over budget: exit {r.returncode}, expected 2")
    check("estimated wall time 1 h 6 min (1.11 h: points 1 h 6 min) exceeds "
          "the budget of 1 h (dem.budget_h or --budget); nothing run" in r.stderr
          and "--yes" in r.stderr, f"refusal message: {r.stderr!r}")
    check("estimate: 2 point(s) to run, 100 000 particles" in r.stdout, "no estimate line")
    check(not out.exists(), "a refused sweep wrote its output directory")
    r = run("--budget", "0.5")
    check(r.returncode == 2 and "budget of 0.5 h" in r.stderr, "--budget does not override")
    r = run("--estimate")
    check(r.returncode == 0 and "estimate: budget 1 h: exceeds" in r.stdout
          and "wall 33 min 23 s (2003 s)" in r.stdout, "--estimate over budget")
    check(not out.exists(), "--estimate wrote the output directory")

    # past the check, in-process (the points themselves are not run)
    from wheelsim_sweep import config, estimate, runner
    repo = Path(a.sweep).resolve().parents[1]
    sweep = config.load(cfg, repo, build)
    check(sweep.budget_h == 1.0, f"dem.budget_h read as {sweep.budget_h}")
    rate = estimate.Rate(1e6, 0.8, 0.0, 1e6, "test")
    for budget, yes, want in ((1.0, False, 2), (1.0, True, None), (2.0, False, None)):
        r = runner.Runner(sweep, out, repo, build, 1, cost={"rate": lambda: rate, "cores": 2,
                                                            "budget_h": budget, "yes": yes})
        ran = []
        r.prepare_beds = lambda: ran.append("beds")
        r._run_points = lambda todo: ran.append(len(todo))
        got = r.run()
        if want == 2:
            check(got == 2 and not ran, f"budget {budget}, yes {yes}: exit {got}, ran {ran}")
        else:
            check(ran == ["beds", 2], f"budget {budget}, yes {yes}: points not run ({ran})")
    try:
        config.load(_rewrite(cfg, "budget_h = 1.0", "budget_h = -1"), repo, build)
        raise Fail("dem.budget_h = -1 accepted")
    except config.ConfigError as e:
        check("dem.budget_h must be a number of hours > 0, got -1" in str(e), str(e))


# ---- slip_control = "wheel_speed" (config.wheel_omega, config.load, --dry-run) -------------------
def _signed_slip(v, omega, r_eff):
    """The signed slip of a forward operating point (docs/postprocess.md, "Slip conventions"),
    written out independently of the code under test."""
    u = omega * r_eff
    return 1.0 - v / u if u >= v else (u - v) / v


def _ascii_stl(path, radius, half_width=0.02):
    """A closed-enough ASCII STL whose largest vertex distance from the axle (y) is `radius`:
    only its vertices are read here."""
    tris = [((radius, -half_width, 0.0), (0.0, half_width, radius), (-radius, 0.0, 0.0)),
            ((0.0, -half_width, -radius), (0.5 * radius, half_width, 0.5 * radius),
             (0.1 * radius, 0.0, 0.0))]
    lines = ["solid w"]
    for t in tris:
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += [f"vertex {x:.9g} {y:.9g} {z:.9g}" for x, y, z in t]
        lines += ["endloop", "endfacet"]
    path.write_text("\n".join(lines + ["endsolid w", ""]))


def case_slip_control(a, work):
    """slip_control = "wheel_speed": the mapping target slip -> motor.omega (both conventions,
    the locked wheel), what each point's rig config gets, R_eff from the entry, the base or the
    mesh, every config error naming its key and value, and the --dry-run listing."""
    from wheelsim_sweep import config
    repo = Path(a.sweep).resolve().parents[1]
    v, r = 0.1, 0.058
    # the mapping: exact values, and the signed slip of (v, omega) is the target
    known = {0.0: v / r, 0.5: 2 * v / r, 0.9: 10 * v / r, -0.5: 0.5 * v / r, -1.0: 0.0,
             -0.2: 0.8 * v / r}
    for s, want in known.items():
        got = config.wheel_omega(s, v, r)
        check(abs(got - want) <= 1e-12 * max(1.0, want), f"wheel_omega({s}): {got}, want {want}")
    for s in (0.0, 0.23, 0.5, 0.75, 0.9, 0.999, -0.2, -0.5, -0.7, -1.0, -0.999999):
        om = config.wheel_omega(s, v, r)
        back = _signed_slip(v, om, r)
        check(abs(back - s) <= 1e-12, f"slip {s}: omega {om} gives signed slip {back}")
        check(om >= 0.0, f"slip {s}: omega {om} < 0")
    check(config.wheel_omega(-1.0, v, r) == 0.0, "s = -1 is not a locked wheel (omega 0)")
    for bad in ((1.0, v, r), (1.2, v, r), (-1.0001, v, r), (0.1, 0.0, r), (0.1, v, -1.0)):
        try:
            config.wheel_omega(*bad)
            raise Fail(f"wheel_omega{bad} accepted")
        except ValueError:
            pass

    # config.load: a flat sweep with the carriage speed imposed
    # the terrain and override checks need a wheel-rig --list-keys; otherwise it prints the
    # schema too (no --check in it: the configs are listed, not checked)
    carriage = [("carriage", "mode"), ("carriage", "speed"), ("carriage", "slip")]
    _stand_in_rig(work, carriage, otherwise="exec \"$0\" --list-keys\n")
    _ascii_stl(work / "w.stl", 0.1)
    base = work / "base.toml"
    base_text = ('[wheel]\nmass = 1.0\ninertia = 0.01\n[rig]\nvertical_load = 24.0\n'
                 '[motor]\nomega = 1.0\nramp_time = 0.1\n'
                 '[carriage]\nmode = "imposed_speed"\nspeed = 0.1\n'
                 '[run]\ndt = 1e-4\nduration = 0.5\n[terrain]\ntype = "flat"\n')
    base.write_text(base_text)
    slips = [0.0, 0.23, 0.5, 0.75, 0.9, -0.2, -0.5, -0.7, -1.0]

    def load(top='slip_control = "wheel_speed"\n', wheels='[{ name = "w", mesh = "w.stl", '
             'effective_radius = 0.058 }]', sl=slips, base_file="base.toml"):
        (work / "sweep.toml").write_text(f'terrain = "flat"\nbase = "{base_file}"\n'
                                         f'wheels = {wheels}\nslips = {sl}\n{top}')
        return config.load(work / "sweep.toml", repo, work)

    sw = load()
    check(sw.slip_control == "wheel_speed", f"slip_control {sw.slip_control}")
    check([p.slip for p in sw.points] == slips, "points not in config order")
    for p in sw.points:
        c, m, w = p.rig["carriage"], p.rig["motor"], p.rig["wheel"]
        check(c == {"mode": "imposed_speed", "speed": 0.1},
              f"slip {p.slip}: carriage {c} (the base's imposed speed, no carriage.slip)")
        check(w["effective_radius"] == 0.058, f"slip {p.slip}: R_eff {w}")
        check(m["omega"] == config.wheel_omega(p.slip, 0.1, 0.058) and m["ramp_time"] == 0.1,
              f"slip {p.slip}: motor {m}")
        check(abs(_signed_slip(0.1, m["omega"], 0.058) - p.slip) < 1e-12,
              f"slip {p.slip}: omega {m['omega']} does not give it")
        conv = "driving" if p.slip >= 0 else "skid"
        check(f"motor.omega = {m['omega']!r} rad/s for slip {p.slip!r} ({conv} convention)"
              in p.setting, f"setting {p.setting!r}")
    check(sw.points[-1].rig["motor"]["omega"] == 0.0, "s = -1: omega not 0 (locked)")
    # the default keeps today's behaviour: carriage.slip per point
    (work / "base_slip.toml").write_text(
        base_text.replace('mode = "imposed_speed"\nspeed = 0.1', 'mode = "imposed_slip"'))
    sw = load(top="", sl=[0.1], base_file="base_slip.toml")
    p = sw.points[0]
    check(sw.slip_control == "imposed_slip" and p.rig["carriage"] == {"mode": "imposed_slip",
                                                                       "slip": 0.1}
          and p.rig["motor"]["omega"] == 1.0, f"default slip_control: {p.rig}")
    # R_eff from the base's [wheel], else from the mesh (its outer radius, written into the point)
    base.write_text(base_text.replace("[wheel]\n", "[wheel]\neffective_radius = 0.06\n"))
    sw = load(wheels='["w.stl"]', sl=[0.5])
    check(sw.points[0].rig["wheel"]["effective_radius"] == 0.06
          and sw.points[0].rig["motor"]["omega"] == 0.1 / (0.5 * 0.06), "R_eff from the base")
    base.write_text(base_text)
    sw = load(wheels='["w.stl"]', sl=[0.5])
    re_ = sw.points[0].rig["wheel"]["effective_radius"]
    check(abs(re_ - 0.1) < 1e-9, f"R_eff from the mesh: {re_}, expected 0.1")

    # errors: each names the key and the value and says what is expected
    (work / "bin.stl").write_bytes(b"\0" * 84)  # binary STL: the outer radius cannot be read
    errors = [
        (dict(sl=[0.5, 1.0]), 'slips[1] must be in [-1, 1) with slip_control = "wheel_speed"'),
        (dict(sl=[1.2]), "got 1.2"),
        (dict(sl=[-1.5]), 'slips[0] must be in [-1, 1) with slip_control = "wheel_speed"'),
        (dict(top='slip_control = "wheel"\n'),
         "slip_control must be one of 'imposed_slip', 'wheel_speed'"),
        (dict(top='slip_control = "wheel_speed"\n[override.carriage]\nmode = "imposed_slip"\n'),
         'slip_control = "wheel_speed" needs carriage.mode = "imposed_speed" (the carriage speed '
         'v imposed, the wheel speed set per point) in the base rig config or '
         '[override.carriage], got carriage.mode = "imposed_slip"'),
        (dict(top='slip_control = "wheel_speed"\n[override.carriage]\nspeed = 0.0\n'),
         'carriage.speed must be > 0 m/s with slip_control = "wheel_speed"'),
        (dict(top='slip_control = "wheel_speed"\n[override.carriage]\nspeed = -0.1\n'),
         "got -0.1"),
        (dict(wheels='["bin.stl"]'), "wheels: 'bin': slip_control = \"wheel_speed\" needs R_eff"),
    ]
    for kw, msg in errors:
        try:
            load(**kw)
            raise Fail(f"accepted: {kw}")
        except config.ConfigError as e:
            print(f"  {kw} -> {e}")
            check(msg in str(e), f"{kw}: {e!r} lacks {msg!r}")
    for text, msg in (('[carriage]\nmode = "imposed_speed"\n', "needs carriage.speed"),
                      ('[carriage]\nspeed = 0.1\n', "got no carriage.mode"),
                      ('[carriage]\nmode = "imposed_speed"\nspeed = 0.1\n'
                       '[motor]\ntorque = 1.0\n', "the base rig config has motor.torque")):
        (work / "b2.toml").write_text(text)
        try:
            load(base_file="b2.toml")
            raise Fail(f"accepted base {text!r}")
        except config.ConfigError as e:
            check(msg in str(e), f"base {text!r}: {e!r} lacks {msg!r}")
    try:  # today's default with an imposed_speed base points to the option
        load(top="")
        raise Fail("imposed_speed base accepted without slip_control")
    except config.ConfigError as e:
        check('slip_control = "wheel_speed"' in str(e), str(e))

    # --dry-run: each point lists what it sets; nothing written (a stand-in wheel-rig without
    # --check: the configs are listed, not checked)
    out = work / "out"
    load(sl=[0.5, -1.0])
    r = subprocess.run([a.sweep, str(work / "sweep.toml"), "--build-dir", str(work),
                        "--out-dir", str(out), "--dry-run"], capture_output=True, text=True,
                       timeout=30)
    print(r.stdout + r.stderr)
    check(r.returncode == 0, f"--dry-run exit {r.returncode}")
    om = 0.1 / (0.5 * 0.058)
    for want in (f"motor.omega = {om!r} rad/s for slip 0.5 (driving convention) at "
                 "carriage.speed = 0.1 m/s, wheel.effective_radius = 0.058 m",
                 "motor.omega = 0.0 rad/s for slip -1.0 (skid convention)",
                 "--parameter sweep/slip=-1.0", "--parameter sweep/slip_control=wheel_speed",
                 "w/flat/s-1.000"):
        check(want in r.stdout, f"--dry-run output lacks {want!r}")
    check(not out.exists(), "--dry-run wrote the output directory")


def case_accept_change(a, work):
    """wheel-sweep --accept-change FILE --reason TEXT (docs/sweeps.md "Accepting an edit that
    changes no result"): two finished DEM points and a recipe bed recorded as wheel-sweep records
    them; an edit of a file the deck includes and of one the soil file includes makes the points
    re-run and the bed re-prepare (--dry-run); accepting only one of the two edits touches no
    record (the other still differs, named); accepting both updates the points whose inputs hash
    still matches (one point's does not: named, left) and the bed, records file, hashes, reason and
    time in `accepted_changes`, and --dry-run then finds that point finished and reuses the bed.
    Errors exit 2 naming what is wrong: no --reason, --reason alone, a missing file, a file the
    sweep does not include, --accept-change with --dry-run, a second driver on the output."""
    import fcntl
    import hashlib
    from wheelsim_sweep import config, runner
    repo, build, deck_inc = _dem_project(a, work)
    soil_inc, other = work / "soil_extra.in", work / "other.in"
    for f in (soil_inc, other):
        f.write_text("# v1\n")
    (work / "sand.in").write_text((repo / "inputs" / "soils" / "ci.in").read_text()
                                  + f"include {soil_inc}\n")
    cfg = work / "sweep.toml"
    cfg.write_text('terrain = "dem"\nbase = "rig.toml"\nwheels = ["wheel.stl"]\n'
                   'soils = [{ soil = "sand.in", bin_length = 0.3 }]\nslips = [0.1, 0.2]\n'
                   '[dem]\nnp = 1\ndeck = "in.deck"\n')
    out = work / "out"
    sw = config.load(cfg, repo, build)
    r = runner.Runner(sw, out, repo, build, 1)
    for p in sw.points:  # finished points, recorded as run_point records them
        d = r.point_dir(p)
        d.mkdir(parents=True)
        (d / "run.h5").write_text("")
        (d / "done.json").write_text(json.dumps(
            {"exit_status": 0, "status": "done", "inputs_sha256": r.inputs_hash(p),
             "included_sha256": r.included_hashes(p)}, indent=2) + "\n")
    soil = sw.points[0].soil
    restart = r.bed_restart(soil)
    restart.parent.mkdir(parents=True)
    for f in (restart, Path(f"{restart}.vars")):
        f.write_text("x")
    (restart.parent / f"{restart.name}.recipe.json").write_text(
        json.dumps(soil.recipe, sort_keys=True, indent=2) + "\n")
    r.bed_inputs_file(soil).write_text(json.dumps(r.bed_inputs(soil), sort_keys=True, indent=2)
                                       + "\n")

    def sweep(*args):
        return _run(a, str(cfg), "--out-dir", str(out), "--build-dir", str(build), *args)

    res = sweep("--dry-run")
    check(res.returncode == 0 and "0 point(s) to run, 2 finished" in res.stdout,
          "before the edits: expected 2 finished points")
    deck_inc.write_text("# v1, a comment\n")
    soil_inc.write_text("# v1, another comment\n")
    res = sweep("--dry-run")
    check(f"included file {deck_inc} changed" in res.stdout and "2 point(s) to run" in res.stdout,
          "after the edits: expected both points to re-run, naming the deck's include")
    check("would prepare" in res.stdout, "after the soil include's edit: the bed re-prepares")
    for args, msg in (
            (("--accept-change", str(deck_inc)), "--accept-change needs --reason TEXT"),
            (("--accept-change", str(deck_inc), "--reason", " "), "needs --reason TEXT"),
            (("--reason", "x"), "--reason goes with --accept-change"),
            (("--accept-change", str(work / "nosuch.in"), "--reason", "x"),
             f"--accept-change {work / 'nosuch.in'}: no such file"),
            (("--accept-change", str(other), "--reason", "x"),
             f"--accept-change {other}: not a file the sweep's DEM inputs include"),
            (("--accept-change", str(deck_inc), "--reason", "x", "--dry-run"),
             "--accept-change runs nothing")):
        res = sweep(*args)
        check(res.returncode == 2 and msg in res.stderr, f"{args}: expected exit 2 and '{msg}'")
    records = {f: f.read_bytes() for f in out.rglob("done.json")}
    records[r.bed_inputs_file(soil)] = r.bed_inputs_file(soil).read_bytes()
    res = sweep("--accept-change", str(deck_inc), "--reason", "a comment")
    check(res.returncode == 0 and f"{soil_inc} changed too" in res.stdout
          and "in 0 finished point(s) and 0 bed(s)" in res.stdout,
          "accepting one of two edits: expected no record changed, the other file named")
    check(all(f.read_bytes() == b for f, b in records.items()), "a record changed")
    with open(out / ".wheel-sweep.lock", "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        res = sweep("--accept-change", str(deck_inc), "--accept-change", str(soil_inc),
                    "--reason", "comments")
        check(res.returncode == 2 and "another wheel-sweep is running" in res.stdout,
              "a held lock: expected exit 2")
    second = r.point_dir(sw.points[1]) / "done.json"
    rec = json.loads(second.read_text())
    rec["inputs_sha256"] = "stale"
    second.write_text(json.dumps(rec))
    res = sweep("--accept-change", str(deck_inc), "--accept-change", str(soil_inc),
                "--reason", "comments only")
    check(res.returncode == 0 and "in 1 finished point(s) and 1 bed(s)" in res.stdout
          and "its inputs changed" in res.stdout,
          "accepting both: expected 1 point (the other's inputs changed) and the bed")
    first = json.loads((r.point_dir(sw.points[0]) / "done.json").read_text())
    notes = first.get("accepted_changes", [])
    check(sorted(n["file"] for n in notes) == sorted([str(deck_inc), str(soil_inc)])
          and all(n["reason"] == "comments only" and n["old_sha256"] != n["new_sha256"]
                  and n["new_sha256"] == hashlib.sha256(Path(n["file"]).read_bytes()).hexdigest()
                  and n["utc"].endswith("Z")
                  for n in notes), f"accepted_changes of the first point: {notes}")
    bed = json.loads(r.bed_inputs_file(soil).read_text())
    check(len(bed.get("accepted_changes", [])) == 1, f"bed's accepted_changes: {bed}")
    res = sweep("--dry-run")
    check(res.returncode == 0 and "1 point(s) to run, 1 finished" in res.stdout
          and "reusing" in res.stdout and "inputs changed since it finished" in res.stdout,
          "after accepting: expected the first point finished, the bed reused, the second to run")


def case_moved_tree(a, work):
    """Records that hold when directories move (docs/sweeps.md "Resume semantics"): two finished
    DEM points (of three) and a recipe bed, recorded as wheel-sweep records them, in a project
    directory that holds the sweep file, its deck, mesh and soil file (by path), the output and
    the build directory; --dry-run finds both points finished and reuses the bed for the third,
    and still does after the whole directory is renamed. A record in the form written before
    2026-12-03 (absolute paths: the inputs hash, the included files' keys, the bed's soil_file) is
    accepted where it was written and does not hold once moved (the bed's recipe names the soil
    file's old path: refused, naming it, as before). portable / local on a checkout elsewhere:
    the four directories become <out>, <config>, <build>, <repo> and back, a path outside them
    stays."""
    from wheelsim_sweep import config, runner
    repo = Path(a.sweep).resolve().parents[1]
    first = work / "project"
    build = first / "build"
    _stand_in_rig(build, otherwise="exit 0\n")
    (first / "wheel.stl").write_text("solid w\nendsolid w\n")
    (first / "in.deck").write_text("# not run\n")
    (first / "sand.in").write_text((repo / "inputs" / "soils" / "ci.in").read_text())
    (first / "rig.toml").write_text('[run]\ndt = 1e-4\nduration = 0.5\n[motor]\nomega = 1.0\n'
                                    '[terrain]\ntype = "dem"\n')
    (first / "sweep.toml").write_text(
        'terrain = "dem"\nbase = "rig.toml"\nwheels = ["wheel.stl"]\n'
        'soils = [{ soil = "sand.in", bin_length = 0.3 }]\nslips = [0.1, 0.2, 0.3]\n'
        '[dem]\nnp = 1\ndeck = "in.deck"\n')

    def record(top, legacy=False):
        """Writes the finished points' and the bed's records under `top` as the driver does (with
        absolute paths, as before 2026-12-03, if legacy)."""
        sw = config.load(top / "sweep.toml", repo, top / "build")
        r = runner.Runner(sw, top / "out", repo, top / "build", 1)
        same = (lambda v: v)
        form = same if legacy else r.portable
        for p in sw.points[:2]:  # the third is to run: the bed is checked for it
            d = r.point_dir(p)
            d.mkdir(parents=True, exist_ok=True)
            (d / "run.h5").write_text("")
            ident = r.inputs_ident(p)
            included = {r.local(k): v for k, v in r.included_hashes(p).items()}
            (d / "done.json").write_text(json.dumps(
                {"exit_status": 0, "status": "done",
                 "inputs_sha256": runner._sha256_json(form(ident)),
                 "included_sha256": form(included)}, indent=2) + "\n")
        soil = sw.points[0].soil
        restart = r.bed_restart(soil)
        restart.parent.mkdir(parents=True, exist_ok=True)
        for f in (restart, Path(f"{restart}.vars")):
            f.write_text("x")
        inputs = r.bed_inputs(soil)
        inputs = {**inputs, "soil_file": r.local(inputs["soil_file"]),
                  "included_sha256": {r.local(k): v for k, v in
                                      inputs["included_sha256"].items()}}
        (restart.parent / f"{restart.name}.recipe.json").write_text(
            json.dumps(form(soil.recipe), sort_keys=True, indent=2) + "\n")
        r.bed_inputs_file(soil).write_text(json.dumps(form(inputs), sort_keys=True, indent=2)
                                           + "\n")
        return r, sw

    def dry_run(top):
        return _run(a, str(top / "sweep.toml"), "--out-dir", str(top / "out"), "--build-dir",
                    str(top / "build"), "--bed-hold", "0", "--dry-run")

    r, sw = record(first)
    done = json.loads((r.point_dir(sw.points[0]) / "done.json").read_text())
    ident = r.portable(r.inputs_ident(sw.points[0]))
    bed = json.loads(r.bed_inputs_file(sw.points[0].soil).read_text())
    check(ident["mesh"] == "<config>/wheel.stl" and ident["deck"] == "<config>/in.deck"
          and ident["bed"].startswith("<out>/beds/") and bed["soil_file"] == "<config>/sand.in"
          and done["included_sha256"] and
          all(k.startswith("<repo>/inputs/") for k in done["included_sha256"]),
          f"records name the directories as tokens: {ident}, {bed}, {done}")
    for top, what in ((first, "where they were written"), (work / "moved", "after the move")):
        if top != first:
            first.rename(top)
        res = dry_run(top)
        check(res.returncode == 0 and "1 point(s) to run, 2 finished" in res.stdout
              and "reusing" in res.stdout and "would prepare" not in res.stdout,
              f"{what}: expected both points finished and the bed reused")
    legacy = work / "legacy"
    (work / "moved").rename(legacy)
    shutil.rmtree(legacy / "out")
    record(legacy, legacy=True)
    res = dry_run(legacy)
    check(res.returncode == 0 and "1 point(s) to run, 2 finished" in res.stdout
          and "reusing" in res.stdout, "legacy records where they were written: expected finished")
    legacy.rename(work / "legacy_moved")
    res = dry_run(work / "legacy_moved")
    check(res.returncode != 0 and "exists but was prepared from another recipe" in res.stderr
          and "0 point(s) to run" not in res.stdout,
          "legacy records moved: expected them not to hold (the bed's recipe names the soil "
          "file's old path: refused, as before 2026-12-03)")
    elsewhere = runner.Runner(sw, "/x/runs/out", Path("/x/repo"), Path("/x/repo/build"), 1)
    cfg_dir = str(Path(sw.path).parent)
    paths = {"/x/runs/out/beds/b.restart": "<out>/beds/b.restart",
             "/x/repo/build/meshes/w.stl": "<build>/meshes/w.stl",
             "/x/repo/inputs/in.soilbin": "<repo>/inputs/in.soilbin",
             f"{cfg_dir}/in.deck": "<config>/in.deck", "/data/w.stl": "/data/w.stl"}
    got = elsewhere.portable({"k": list(paths)})["k"]
    check(got == list(paths.values()), f"portable: {got}")
    back = [elsewhere.local(v) for v in got]
    check(back == list(paths), f"local: {back}")


def _dem_project(a, work):
    """A DEM sweep's files in `work` (nothing runs): a stand-in wheel-rig that passes --check,
    wheel.stl, in.deck including deck_extra.in ("# v1"), rig.toml. Returns (the checkout, the
    build dir, deck_extra.in)."""
    repo = Path(a.sweep).resolve().parents[1]
    build = work / "build"
    _stand_in_rig(build, otherwise="exit 0\n")
    (work / "wheel.stl").write_text("solid w\nendsolid w\n")
    inc = work / "deck_extra.in"
    inc.write_text("# v1\n")
    (work / "in.deck").write_text(f"# not run\ninclude {inc}\n")
    (work / "rig.toml").write_text('[run]\ndt = 1e-4\nduration = 0.5\n[motor]\nomega = 1.0\n'
                                   '[terrain]\ntype = "dem"\n')
    return repo, build, inc


def case_included_at_start(a, work):
    """A DEM point records the included files' hashes, and its inputs hash (the soil file's among
    them), as they were when it started, and an edit while the driver runs is seen (file_hash
    keeps a hash only while size and mtime stay): the include is hashed before the point (as the
    driver's start-up check does), edited, the point runs with a stand-in child that edits it and
    the soil file again and writes the run file; done.json holds the hashes of the versions the
    point started with, and the point then counts as stale. (Until 2026-11-28 the inputs hash was
    taken when the point ended: a soil file's comment edited during a long point was recorded as
    what that point ran with.)"""
    import hashlib
    from wheelsim_sweep import config, runner
    repo, build, inc = _dem_project(a, work)
    cfg = work / "sweep.toml"
    soil = work / "my_soil.in"
    soil.write_text((repo / "inputs" / "soils" / "ci.in").read_text())
    cfg.write_text('terrain = "dem"\nbase = "rig.toml"\nwheels = ["wheel.stl"]\n'
                   f'soils = [{{ soil = "{soil}", bin_length = 0.3 }}]\n'
                   'slips = [0.1]\n[dem]\nnp = 1\ndeck = "in.deck"\n')
    sw = config.load(cfg, repo, build)
    r = runner.Runner(sw, work / "out", repo, build, 1)
    p = sw.points[0]
    r.included_hashes(p)  # the driver's start-up check hashes it first (kept: file_hash)
    time.sleep(0.01)
    inc.write_text("# v1: edited after the driver started\n")
    v1 = hashlib.sha256(inc.read_bytes()).hexdigest()
    inputs_at_start = r.inputs_hash(p)

    def child(cmd, log, cwd):  # the point "runs": meanwhile the include and the soil are edited
        inc.write_text("# v2: edited while the point ran\n")
        soil.write_text(soil.read_text() + "# edited while the point ran\n")
        (Path(cwd) / runner.PART_FILE).write_text("")
        return 0
    r.command = lambda p_, resume: ["true"]
    r._run_child = child
    counter = {"started": 0, "finished": 0, "total": 1, "running": {}, "walls": []}
    r.run_point(p, counter)
    done = json.loads((r.point_dir(p) / runner.DONE_FILE).read_text())
    got = done.get("included_sha256", {}).get(r.portable(str(inc.resolve())))
    check(done.get("exit_status") == 0, f"the stand-in point finished ({done})")
    check(got == v1, f"recorded hash of {inc.name} is the one at the start ({got} vs {v1})")
    check(done.get("inputs_sha256") == inputs_at_start,
          "recorded inputs hash is the one at the start (the soil file as the point read it)")
    ok, why = r.finished(p)
    check(not ok and "changed since it finished" in why,
          f"so the point counts as run with the old inputs and re-runs ({why!r})")


def _rewrite(path, old, new):
    p = path.with_name("bad_" + path.name)
    p.write_text(path.read_text().replace(old, new))
    return p


def case_terrain_switch(a, work):
    """override.terrain.type other than the base's: the override's [terrain] replaces the base's
    (none of the base type's keys left: the same rig on another terrain from one rig file); the
    rest of the base is kept; the same type merges key by key; without the switch a base of
    another type is still an error naming override.terrain.type."""
    from wheelsim_sweep import config
    repo = Path(a.sweep).resolve().parents[1]
    _stand_in_rig(work, [("terrain", "type"), ("terrain", "friction"), ("run", "duration")],
                  otherwise="exec \"$0\" --list-keys\n")
    _ascii_stl(work / "w.stl", 0.1)
    rig = ('[wheel]\nmass = 1.0\ninertia = 0.01\n[rig]\nvertical_load = 24.0\n'
           '[motor]\nomega = 1.0\n[carriage]\nmode = "imposed_slip"\n'
           '[run]\ndt = 1e-4\nduration = 0.5\n')
    (work / "base_dem.toml").write_text(
        rig + '[terrain]\ntype = "dem"\nendpoint = "ipc:///tmp/x"\ntimeout = 10.0\n')
    (work / "base_flat.toml").write_text(rig + '[terrain]\ntype = "flat"\nfriction = 0.3\n')

    def load(base, override):
        (work / "sweep.toml").write_text(f'terrain = "flat"\nbase = "{base}"\n'
                                         f'wheels = ["w.stl"]\nslips = [0.2]\n{override}')
        return config.load(work / "sweep.toml", repo, work)

    p = load("base_dem.toml", '[override.terrain]\ntype = "flat"\n[override.run]\n'
             'duration = 2.0\n').points[0]
    check(p.rig["terrain"] == {"type": "flat"},
          f"switch dem -> flat: terrain {p.rig['terrain']}, expected the override's alone")
    check(p.rig["run"] == {"dt": 1e-4, "duration": 2.0} and p.rig["rig"] == {"vertical_load": 24.0},
          f"switch: the rest of the base not kept: {p.rig}")
    p = load("base_flat.toml", '[override.terrain]\ntype = "flat"\n').points[0]
    check(p.rig["terrain"] == {"type": "flat", "friction": 0.3},
          f"same type: terrain {p.rig['terrain']}, expected the base's keys kept")
    p = load("base_flat.toml", '[override.terrain]\nfriction = 0.4\n').points[0]
    check(p.rig["terrain"] == {"type": "flat", "friction": 0.4},
          f"same type, one key: terrain {p.rig['terrain']}")
    try:
        load("base_dem.toml", '[override.run]\nduration = 2.0\n')
        raise Fail("a dem base for a flat sweep without override.terrain.type was accepted")
    except config.ConfigError as e:
        check("override.terrain.type" in str(e) and '"dem"' in str(e), f"message: {e}")


def case_resumed_wall(a, work):
    """The wall time a resumed DEM point records (runner._run_wall_time): the run file's
    /parameters/run/wall_time (synthetic run files, tests/postprocess/synthetic.py); None for a
    run file without it, with a negative or non-numeric value, a file that is not HDF5, and a
    missing file (done.json then keeps the attempt's time and says so)."""
    sys.path.insert(0, str(Path(a.sweep).resolve().parents[1] / "tests" / "postprocess"))
    import synthetic
    from wheelsim_sweep.runner import _run_wall_time
    cases = {"recorded": 10844.14, "absent": None, "negative": -1.0, "text": "ten minutes"}
    for name, value in cases.items():
        path = work / f"{name}.h5"
        synthetic.write_rig_run(path, parameters={} if value is None else
                                {"run/wall_time": value})
        got = _run_wall_time(path)
        want = value if name == "recorded" else None
        check(got == want, f"{name}: run/wall_time {value!r} -> {got!r}, expected {want!r}")
    (work / "not_hdf5.h5").write_text("a stopped attempt's partial file\n")
    check(_run_wall_time(work / "not_hdf5.h5") is None, "a file that is not HDF5: not None")
    check(_run_wall_time(work / "missing.h5") is None, "a missing file: not None")



def case_park_progress(a, work):
    """What --park says of a point's progress (runner._park_progress) from the rig's half of its
    checkpoint: the phase and rig time before the test; in the test the test time of
    run.duration; a missing checkpoint named, not raised."""
    from types import SimpleNamespace as NS
    from wheelsim_sweep.runner import _park_progress
    ckpt = work / "point" / "cosim" / "checkpoints"
    ckpt.mkdir(parents=True)
    point = NS(rig={"run": {"duration": 0.5}})

    def rig(time_s, t0, name):
        (ckpt / "rig-40.ckpt").write_text(f"n sim/time 1 {time_s}\nn sim/test_start 1 {t0}\n"
                                          f"t sim/phase_name {name}\nend\n")
        return _park_progress(point, work / "point", 40)
    for got, want in ((rig(0.3, "nan", "settle"),
                       "settle phase, t 0.300 s simulated, the 0.5 s test phase to come"),
                      (rig(1.0, 0.8, "test"), "test phase, 0.200 of 0.5 s, 40 %; t 1.000 s simulated")):
        check(got == want, f"{got!r}, expected {want!r}")
    got = _park_progress(point, work / "point", 41)
    check(got.startswith("progress unknown:") and "rig-41.ckpt" in got, got)
    # the steps a point resumes from (archive.steps_done, wheel-sweep --estimate): its own newest
    # complete checkpoint, else the parked one (xz), else 0
    import lzma
    from wheelsim_sweep import archive
    for name in ("liggghts-40.restart", "liggghts-40.restart.wheel", "liggghts-40.restart.info"):
        (ckpt / name).write_text("x")
    (ckpt / "rig-40.ckpt").write_text("i sim/steps 1234\nend\n")
    check(archive.steps_done(work / "point") == 1234, "steps done at the own checkpoint")
    kept = work / "arch" / "w" / "parked"
    (kept / "cosim" / "checkpoints").mkdir(parents=True)
    (kept / "parked.json").write_text('{"step": 77, "files": []}')
    (kept / "cosim" / "checkpoints" / "rig-77.ckpt.xz").write_bytes(
        lzma.compress(b"i sim/steps 999\nend\n"))
    check(archive.steps_done(work / "new", work / "arch", "w") == 999, "steps done when parked")
    check(archive.steps_done(work / "new", work / "arch", "other") == 0
          and archive.steps_done(work / "new") == 0, "no checkpoint: 0")


def case_parked_beds(a, work):
    """Which recipe beds a run leaves unpoured (runner.Runner.parked_beds; docs/sweeps.md
    "Parking a stopped point"): two points of one recipe soil, each parked in the archive on the
    same bed with its .vars and its inputs as they are now: the bed is not poured (--dry-run:
    "would not pour"); not when the restart is here, without --archive, when one point to run
    has no parked record, a record from before the bed's .vars was kept, one parked on another
    bed, or one whose inputs or included files changed since it was parked; a finished point
    (not to run) does not count. `--accept-change FILE --archive DIR` of the edited include
    accepts it in the parked record (the bed is again left unpoured) and in a finished point
    found only in the archive (restored, then accepted in both copies)."""
    from wheelsim_sweep import config, runner
    repo, build, inc = _dem_project(a, work)
    cfg = work / "sweep.toml"
    cfg.write_text('terrain = "dem"\nbase = "rig.toml"\nwheels = ["wheel.stl"]\n'
                   'soils = [{ soil = "ci", bin_length = 0.3 }]\nslips = [0.1, 0.2]\n'
                   '[dem]\nnp = 1\ndeck = "in.deck"\n')
    out, arch = work / "out", work / "archive"
    sw = config.load(cfg, repo, build)
    r = runner.Runner(sw, out, repo, build, 1, archive_dir=arch)
    soil = sw.points[0].soil
    restart = r.bed_restart(soil)
    sha, bed_vars = "ab" * 32, "variable bed_depth index 0.05\n"
    todo = [(p, "unfinished") for p in sw.points]

    def park(p, **change):
        rec = {"step": 10, "files": [], "bed_sha256": {restart.name: sha}, "bed_vars": bed_vars,
               "point_inputs_sha256": r.inputs_hash(p),
               "point_included_sha256": r.included_hashes(p)}
        rec.update(change)
        rec = {k: v for k, v in rec.items() if v is not None}
        d = arch / p.reldir / "parked"
        d.mkdir(parents=True, exist_ok=True)
        (d / "parked.json").write_text(json.dumps(rec))

    for p in sw.points:
        park(p)
    got = r.parked_beds(todo)
    check(got == {soil.label: {"sha256": sha, "vars": bed_vars, "points": 2}},
          f"both points parked on one bed: {got}")
    res = _run(a, str(cfg), "--out-dir", str(out), "--build-dir", str(build), "--archive",
               str(arch), "--dry-run")
    check(res.returncode == 0 and f"bed {soil.label}: would not pour: its 2 point(s) to run "
          "resume from checkpoints parked on it" in res.stdout and "would prepare" not in res.stdout,
          f"--dry-run: {res.stdout[-600:]}")
    check(runner.Runner(sw, out, repo, build, 1).parked_beds(todo) == {}, "without --archive")
    restart.parent.mkdir(parents=True)
    restart.write_text("x")
    check(r.parked_beds(todo) == {}, "the restart is here: it is used, not stood in for")
    restart.unlink()
    cases = (("a record from before bed_vars", {"bed_vars": None}),
             ("another bed", {"bed_sha256": {restart.name: "cd" * 32}}),
             ("no sha256", {"bed_sha256": {restart.name: "missing"}}),
             ("inputs changed", {"point_inputs_sha256": "stale"}),
             ("an included file changed", {"point_included_sha256": {str(inc): "stale"}}))
    for what, change in cases:
        park(sw.points[1], **change)
        check(r.parked_beds(todo) == {}, f"{what}: the bed would not be poured")
        check(r.parked_beds(todo[:1]) != {}, f"{what}: the other point alone (the second one "
              "finished) leaves it unpoured")
    shutil.rmtree(arch / sw.points[1].reldir)
    check(r.parked_beds(todo) == {}, "a point to run with nothing parked: the bed is poured")
    park(sw.points[1])
    v1 = r.included_hashes(sw.points[1])
    time.sleep(0.01)
    inc.write_text("# v2\n")
    check(r.parked_beds(todo) == {}, "an included file edited since both were parked")
    # --accept-change with --archive: the second point finished, only in the archive (a new
    # machine): it is restored, and its done.json accepted here and there; the first point's
    # parked record is accepted, so its bed is again left unpoured
    kept = arch / sw.points[1].reldir
    shutil.rmtree(kept)
    kept.mkdir(parents=True)
    (kept / "run.h5").write_text("")
    # first archived with other inputs: a run would re-run it, so it is not restored (nor
    # touched); the parked record is accepted by this run, so it is put back after it
    parked = arch / sw.points[0].reldir / "parked" / "parked.json"
    parked_bytes = parked.read_bytes()
    record = {"exit_status": 0, "status": "done", "inputs_sha256": "0" * 64, "included_sha256": v1}
    (kept / "done.json").write_text(json.dumps(record, indent=2) + "\n")
    res = _run(a, str(cfg), "--out-dir", str(out), "--build-dir", str(build), "--archive",
               str(arch), "--accept-change", str(inc), "--reason", "other inputs")
    check(res.returncode == 0 and "restored" not in res.stdout
          and not (r.point_dir(sw.points[1]) / "done.json").exists()
          and json.loads((kept / "done.json").read_text()) == record,
          f"an archived point with other inputs: restored or touched: {res.stdout[-600:]}")
    parked.write_bytes(parked_bytes)
    record["inputs_sha256"] = r.inputs_hash(sw.points[1])
    (kept / "done.json").write_text(json.dumps(record, indent=2) + "\n")
    res = _run(a, str(cfg), "--out-dir", str(out), "--build-dir", str(build), "--archive",
               str(arch), "--accept-change", str(inc), "--reason", "a comment")
    check(res.returncode == 0 and "restored 1 finished point(s)" in res.stdout
          and "in 1 finished point(s), 1 parked point(s) and 0 bed(s)" in res.stdout,
          f"--accept-change --archive: {res.stdout[-600:]} {res.stderr[-300:]}")
    check(r.parked_beds(todo[:1]) == {soil.label: {"sha256": sha, "vars": bed_vars, "points": 1}},
          "after accepting: the parked point's bed is left unpoured")
    rec = json.loads((arch / sw.points[0].reldir / "parked" / "parked.json").read_text())
    check([n["reason"] for n in rec.get("accepted_changes", [])] == ["a comment"],
          f"parked record's accepted_changes: {rec}")
    done = r.point_dir(sw.points[1]) / "done.json"
    check(done.read_bytes() == (kept / "done.json").read_bytes()
          and json.loads(done.read_text())["included_sha256"] == r.included_hashes(sw.points[1]),
          "the finished point: accepted in the output directory and the archive alike")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case")
    ap.add_argument("--sweep", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    sys.dont_write_bytecode = True
    sys.path.insert(0, str(Path(a.sweep).resolve().parent))
    sys.path.insert(1, str(Path(a.sweep).resolve().parents[1] / "postprocess"))  # as wheel-sweep
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
