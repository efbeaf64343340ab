"""soil-lab's command line (soil_lab_py.cli) on bad input: one line on stderr naming the option,
file or field and what was expected, exit 2, no traceback.

`run`: every option check that needs no soil is made before anything is created or started (the
output directory, in.lab_soilinfo's LIGGGHTS run: here Lab.soil_info is replaced by a stub that
fails the test if it is reached). `report` and `scm` on a synthetic lab directory (two plates,
three shear boxes, a bed) damaged one file at a time: a corrupt soil.toml or done.json, a binary,
malformed or truncated CSV, a soil.toml field of the wrong type; `scm --out` into a directory that
does not exist. Nothing here starts LIGGGHTS: the build directories are empty stand-ins or do not
exist."""

import contextlib
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path
from unittest import mock

from soil_lab_py import cli, runner
from synthetic import plate_run, shear_run

REPO = Path(__file__).resolve().parents[2]
SOIL_LAB = REPO / "soil_lab" / "soil-lab"


def main(*args):
    """(exit status, stdout, stderr) of cli.main(args)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = cli.main([str(a) for a in args])
    return rc, out.getvalue(), err.getvalue()


class RunChecksFirst(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name)
        self.build = self.root / "build"
        (self.build / "bin").mkdir(parents=True)
        for exe in ("liggghts-wheel", "wheel-mesh"):  # the Lab checks they exist; nothing runs
            (self.build / "bin" / exe).write_text("")
        self.out = self.root / "lab"

    def tearDown(self):
        self.tmp.cleanup()

    def run_lab(self, *args, soil_info=AssertionError("in.lab_soilinfo (LIGGGHTS) was started")):
        """soil-lab run with Lab.soil_info (the lab's first LIGGGHTS run) and any other LIGGGHTS
        run replaced by `soil_info` raised; (exit status, stderr, seconds)."""
        t0 = time.monotonic()
        with mock.patch.object(runner.Lab, "soil_info", side_effect=soil_info), \
                mock.patch.object(runner.Lab, "_liggghts", side_effect=AssertionError("LIGGGHTS")):
            rc, _, err = main("run", *args, "--out", self.out, "--build-dir", self.build)
        return rc, err, time.monotonic() - t0

    def assertRefusedFirst(self, args, message):
        self.cases = getattr(self, "cases", 0) + 1
        self.out = self.root / f"lab{self.cases}"  # each case its own (a regression's) directory
        rc, err, seconds = self.run_lab(*args)
        self.assertEqual(rc, 2, err)
        self.assertEqual(err.count("\n"), 1, err)  # one line
        self.assertIn(message, err)
        self.assertTrue(err.startswith("soil-lab: error: "), err)
        self.assertLess(seconds, 1.0)
        self.assertFalse(self.out.exists(), "the output directory was created")

    def test_the_stub_is_reached_by_a_good_command(self):
        # The control: good options get as far as in.lab_soilinfo, after the output directory.
        rc, err, _ = self.run_lab("ci", "--tests", "plate", soil_info=runner.LabRunError("stub"))
        self.assertEqual((rc, err), (1, "soil-lab: error: stub\n"))
        self.assertTrue(self.out.is_dir())

    def test_options_that_need_no_soil_are_refused_before_anything_starts(self):
        cases = {
            ("--plate-speed", "0"): "--plate-speed 0 m/s is outside (0, 0.1] m/s",
            ("--shear-speed", "0"): "--shear-speed 0 m/s is outside (0, 0.1] m/s",
            ("--shear-travel", "0.9"): "--shear-travel 0.9 is outside (0, 0.5]",
            ("--plate-widths", "0.1,0.1"): "--plate-widths: expected two different widths > 0 m",
            ("--plate-hold", "100"): "--plate-hold 100 s is outside (0, 60] s",
            ("--plate-hold-stages", "2"): "--plate-hold-stages 2 without --plate-hold",
            ("--plate-depth", "0"): "--plate-depth 0 m: expected a finite depth > 0 m",
            ("--plate-depth=-0.01",): "--plate-depth -0.01 m: expected a finite depth > 0 m",
            ("--plate-bin", "nan"): "--plate-bin nan m: expected a finite side > 0 m",
            ("--normal-stresses", "5e3,1e4"): "--normal-stresses: the shear test needs >= 3",
            ("--normal-stresses", ""): "--normal-stresses: expected numbers in Pa, got ''",
            ("--plate-widths", ""): "--plate-widths: expected two widths in m, got ''",
            ("--tests", ""): "--tests: expected a comma-separated list, got ''",
            ("--tests", "plate,sheer"): "--tests: unknown test 'sheer' (did you mean 'shear'?)",
            ("--checkpoints", "-1"): "--checkpoints: expected a number >= 0",
            ("--np", "0"): "--np must be >= 1, got 0",
            ("--bed-np", "0"): "--bed-np must be >= 1, got 0",
            ("--shear-replicates", "0"): "--shear-replicates 0: expected a whole number in 1..5",
            ("--tests", "plate", "--shear-replicates", "2"):
                "--shear-replicates repeats the shear boxes: add shear to --tests",
            ("--park",): "--park keeps checkpoints in the archive: it needs --archive DIR",
            ("--estimate", "--park", "--archive", "a"):
                "--estimate runs nothing: not with --park or --accept-change",
            ("--accept-change", "inputs/soils/common/derived.in"):
                "--accept-change needs --reason TEXT",
            ("--reason", "comment"): "--reason goes with --accept-change",
            ("--accept-change", "no/such.in", "--reason", "x"):
                "--accept-change no/such.in: no such file",
            # the soil file itself is part of every step's inputs hash: it always re-runs
            ("--accept-change", f"{REPO}/inputs/soils/ci.in", "--reason", "x"):
                f"--accept-change {REPO}/inputs/soils/ci.in: not a file the soil file or the "
                "lab's decks include",
        }
        for args, message in cases.items():
            with self.subTest(" ".join(args)):
                self.assertRefusedFirst(("ci", *args), message)

    def test_an_included_file_can_be_accepted(self):
        # the control of the refusals above: a file ci.in includes gets as far as the soil
        rc, err, _ = self.run_lab("ci", "--accept-change", REPO / "inputs/soils/common/derived.in",
                                  "--reason", "comment only", soil_info=runner.LabRunError("stub"))
        self.assertEqual((rc, err), (1, "soil-lab: error: stub\n"))

    def test_a_soil_file_that_does_not_exist_is_refused_before_anything_starts(self):
        missing = self.root / "no_such_soil.in"
        self.assertRefusedFirst((missing,), f"soil file '{missing}' not found")
        self.assertRefusedFirst(("no_such_soil",), "unknown soil 'no_such_soil'")

    def test_a_missing_build_is_refused_before_the_output_directory_is_made(self):
        shutil.rmtree(self.build)
        self.assertRefusedFirst(("ci",), "liggghts-wheel not found: build wheelsim first")

    def test_the_command_exits_2_with_one_line(self):
        # The real command (a fresh interpreter, as a user runs it); the build directory does not
        # exist, so not even a regression could start LIGGGHTS.
        r = subprocess.run([sys.executable, str(SOIL_LAB), "run", "ci", "--plate-speed", "0",
                            "--out", str(self.out), "--build-dir", str(self.root / "nobuild")],
                           capture_output=True, text=True, timeout=60,
                           env={**os.environ, "MPLBACKEND": "Agg"})
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(r.stderr, "soil-lab: error: --plate-speed 0 m/s is outside (0, 0.1] m/s "
                         "(a quasi-static tool speed in m/s; default 0.02)\n")
        self.assertFalse(self.out.exists())


SOIL_TOML = '''name = "synthetic"
file = "inputs/soils/synthetic.in"
preset = "standard"
tests = ["bulk", "plate", "shear"]
dmin_m = 0.002
dmax_m = 0.004
dref_m = 0.003
density_kg_m3 = 2650.0
multisphere = false
dt_s = 1e-5
youngs_Pa = 5e7

[[invocations]]
command = "soil-lab run synthetic.in"
'''


class DamagedLab(unittest.TestCase):
    """soil-lab report and scm on a lab directory with one damaged file."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        d = self.lab = Path(self.tmp.name) / "lab"
        d.mkdir()
        (d / "soil.toml").write_text(SOIL_TOML)
        for b in (0.02, 0.032):
            plate_run(d, b, False)
        for sigma in (5e3, 1e4, 2e4):
            shear_run(d, sigma)
        (d / "beds" / "plate").mkdir(parents=True)
        (d / "beds" / "plate" / "done.json").write_text(json.dumps(
            {"inputs": "bed", "wall_s": 10.0, "result": {"bulk_density": "1500", "porosity": "0.43",
                                                         "bed_depth": "0.05", "spheres": "800"}}))

    def tearDown(self):
        self.tmp.cleanup()

    def assertRefused(self, message, *args):
        """`soil-lab report LAB` (or the command `args`) exits 2 with `message` in one line."""
        rc, _, err = main(*(args or ("report", self.lab, "--quiet")))
        self.assertEqual(rc, 2, err)
        self.assertEqual(err.count("\n"), 1, err)
        self.assertTrue(err.startswith("soil-lab: error: "), err)
        self.assertIn(message, err)

    def test_the_intact_lab_reports_and_writes_its_scm_file(self):
        # The control: every damage below is what the report refuses.
        rc, _, err = main("report", self.lab, "--quiet")
        self.assertEqual((rc, err), (0, ""))
        scm = Path(self.tmp.name) / "scm.toml"
        rc, out, err = main("scm", self.lab, "--out", scm)
        self.assertEqual((rc, err), (0, ""))
        self.assertTrue(scm.is_file())

    def test_replicate_boxes_are_reported(self):
        # a second bed's boxes, 10 % stronger: the report's lines per stress and per bed
        for sigma in (5e3, 1e4, 2e4):
            shear_run(self.lab, sigma, tau_scale=1.1, replicate=2)
        # the first bed's 10 kPa box again at half speed, 30 % stronger: 3.4 sd from the mean
        # of the two same-speed boxes (1.0 and 1.1: mean 1.05, sd 0.0707)
        shear_run(self.lab, 1e4, name="shear_s10000_half", tau_scale=1.3)
        rc, out, err = main("report", self.lab)
        self.assertEqual((rc, err), (0, ""))
        self.assertIn("soil-lab: shear replicates at 10 kPa: 2 boxes, peak ", out)
        self.assertIn("spread 9.5 %", out)  # (1.1 - 1) / 1.05
        self.assertIn("soil-lab: shear replicates, each bed's own fit: bed 1: phi 30.00 deg", out)
        self.assertIn("bed 2: phi 32.42 deg", out)
        self.assertIn("quasi-static: shear_s10000: its replicates at the same speed (other beds) "
                      "peak +10.0 % from it; the half-speed peak is +23.8 % from the mean of the 2 "
                      "same-speed boxes (+3.54 sd): outside 2 sd of their scatter: a rate effect",
                      out)
        # the second bed's box at half speed too, 28 % stronger than its own: the paired check
        # over the two beds (+30 %, +28 %: mean +29 %, se 1 %, t 12.7: +16.3 .. +41.7 %)
        shear_run(self.lab, 1e4, name="shear_s10000_r2_half", tau_scale=1.1 * 1.28, replicate=2)
        rc, out, err = main("report", self.lab)
        self.assertEqual((rc, err), (0, ""))
        self.assertIn("soil-lab: quasi-static over 2 beds at 10 kPa (each bed's box at half speed "
                      "against its box at full speed: +30.0 %, +28.0 %): mean +29.0 % ± 1.0 % "
                      "(standard error), 95 % interval +16.3 to +41.7 % against the tolerance "
                      "±5 %: a rate effect (the whole interval outside it): NOT quasi-static", out)
        # both beds' boxes at half the time step, +3 % and -2 %: the time-step check paired over
        # the two beds (mean +0.5 %, se 2.5 %, t 12.7: -31.3 .. +32.3 %), its own line
        shear_run(self.lab, 1e4, name="shear_s10000_halfdt", tau_scale=1.03)
        shear_run(self.lab, 1e4, name="shear_s10000_r2_halfdt", tau_scale=1.1 * 0.98, replicate=2)
        rc, out, err = main("report", self.lab)
        self.assertEqual((rc, err), (0, ""))
        self.assertIn("soil-lab: time step over 2 beds at 10 kPa (each bed's box at half the step "
                      "against its box at the soil's step: +3.0 %, -2.0 %): mean +0.5 % ± 2.5 % "
                      "(standard error), 95 % interval -31.3 to +32.3 % against the tolerance "
                      "±5 %: cannot tell (the interval straddles the tolerance; more beds narrow "
                      "it)", out)

    def test_a_corrupt_soil_toml(self):
        (self.lab / "soil.toml").write_text('name = "synthetic"\ndmax_m = = 0.004\n')
        self.assertRefused(f"{self.lab / 'soil.toml'}: not valid TOML: ")
        self.assertRefused("(at line 2, column 10)")

    def test_soil_toml_fields_of_the_wrong_type_or_range(self):
        cases = {
            'dt_s = "fast"': "dt_s = 'fast': expected the time step, a number > 0 [s]",
            "dt_s = -1e-5": "dt_s = -1e-05: expected the time step, a number > 0 [s]",
            "dmax_m = 0.0": "dmax_m = 0.0: expected the largest grain diameter, a number > 0 [m]",
            'dmax_m = "4 mm"': "dmax_m = '4 mm': expected the largest grain diameter",
            "dmax_m = 0.001": "dmin_m = 0.002 is larger than dmax_m = 0.001",
            "name = 3": "name = 3: expected the soil's name, a non-empty string",
            'preset = "fast"': "preset = 'fast': expected one of standard, quick",
            'tests = ["plate", "sheer"]': "tests = ['plate', 'sheer']: expected a list of tests",
            "multisphere = 0": "multisphere = 0: expected true or false",
            "youngs_Pa = 0.0": "youngs_Pa = 0.0: expected the particles' Young's modulus",
            "density_kg_m3 = nan": "density_kg_m3 = nan: expected the particle density",
        }
        for line, message in cases.items():
            key = line.split(" =")[0]
            with self.subTest(line):
                text = "\n".join(line if row.startswith(key + " =") else row
                                 for row in SOIL_TOML.splitlines())
                (self.lab / "soil.toml").write_text(text + "\n")
                self.assertRefused(f"{self.lab / 'soil.toml'}: {message}")
        (self.lab / "soil.toml").write_text('name = "synthetic"\n')
        self.assertRefused(f"{self.lab / 'soil.toml'}: dmax_m is missing: expected the largest "
                           "grain diameter")

    def test_a_corrupt_done_json(self):
        done = self.lab / "shear_s10000" / "done.json"
        done.write_text('{"meta": {"normal_stress_Pa": 10000.0,\n "box_m": 0.1')
        self.assertRefused(f"{done}: not valid JSON: Expecting ',' delimiter (line 2, column 14)")
        done.write_text("[1, 2]")
        self.assertRefused(f"{done}: expected a JSON object")
        done.write_text('{"meta": {"normal_stress_Pa": "ten kPa"}}')
        self.assertRefused(f"{done}: meta.normal_stress_Pa = 'ten kPa': expected the normal "
                           "stress, a number > 0 [Pa]")
        done.write_text('{"meta": {"normal_stress_Pa": 1e4}, "steps": "many", "wall_s": 1.0}')
        self.assertRefused(f"{done}: steps = 'many': expected a number >= 0")
        done = self.lab / "plate_b0.02" / "done.json"
        done.write_text('{"wall_s": 1.0}')
        self.assertRefused(f"{done}: meta = None: expected a table of the run's sizes (with b_m)")
        done = self.lab / "beds" / "plate" / "done.json"
        done.write_text(json.dumps({"result": {"bulk_density": "dense", "porosity": "0.4",
                                               "bed_depth": "0.05"}}))
        self.assertRefused(f"{done}: result.bulk_density = 'dense': expected a number")

    def test_a_binary_or_malformed_csv(self):
        csv = self.lab / "plate_b0.02" / "plate.csv"
        lines = csv.read_text().splitlines(keepends=True)
        csv.write_bytes("".join(lines[:5]).encode() + bytes(range(128, 256)) + b"\n")
        self.assertRefused(f"{csv}, line 6: byte 0x80 is not UTF-8 text: expected a text file")
        fields = lines[6].split()
        fields[2] = "abc"
        csv.write_text("".join(lines[:6]) + " ".join(fields) + "\n" + "".join(lines[7:]))
        self.assertRefused(f"{csv}, line 7, column 3 (force_N): 'abc' is not a finite number: "
                           "expected rows of 6 numbers (time_s sinkage_m force_N pressure_Pa "
                           "contacts phase)")
        fields[2] = "nan"
        csv.write_text("".join(lines[:6]) + " ".join(fields) + "\n" + "".join(lines[7:]))
        self.assertRefused(f"{csv}, line 7, column 3 (force_N): 'nan' is not a finite number")
        csv.write_text("".join(lines[:6]) + " ".join(fields[:4]) + "\n" + "".join(lines[7:]))
        self.assertRefused(f"{csv}, line 7: 4 columns, expected rows of 6 numbers")
        csv.write_text(lines[0])
        self.assertRefused(f"{csv}: no data rows: expected rows of 6 numbers")

    def test_a_truncated_csv(self):
        csv = self.lab / "shear_s5000" / "shear.csv"
        lines = csv.read_text().splitlines(keepends=True)
        csv.write_text("".join(lines[:41]))  # the header and 40 rows of the consolidation
        self.assertRefused(f"{csv}: no rows of the shear (phase 2) in its 40 rows: expected a "
                           "finished run's record (a truncated file?)")
        csv.write_text("".join(lines[:53]))  # 2 rows into the shear
        self.assertRefused(f"{csv}: its shear rows (phase 2) cannot be fitted: ")
        csv = self.lab / "plate_b0.032" / "plate.csv"
        csv.write_text("".join(csv.read_text().splitlines(keepends=True)[:3]))
        self.assertRefused(f"{csv}: fewer than 2 rows of the loading (phase 1) below the surface")

    def test_scm_out_in_a_directory_that_does_not_exist(self):
        out = Path(self.tmp.name) / "no_such_dir" / "x.toml"
        self.assertRefused(f"--out {out}: its directory {out.parent} does not exist",
                           "scm", self.lab, "--out", out)
        self.assertFalse(out.parent.exists())
        self.assertRefused(f"--out {self.lab}: is a directory", "scm", self.lab, "--out", self.lab)

    def test_shear_soil_needs_shear_from(self):
        out = Path(self.tmp.name) / "x.toml"
        self.assertRefused("--shear-soil: only with --shear-from", "scm", self.lab, "--out", out,
                           "--shear-soil", "trial")
        self.assertFalse(out.exists())


if __name__ == "__main__":
    unittest.main()
