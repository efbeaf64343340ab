"""``wheelsim-post compare`` on a real ``wong-reece --csv`` table (a script: exit 77 = skip
when wong-reece is not built; usage: test_compare_wong_reece.py [--build-dir DIR]).

The simulated curve is a curves CSV made by ``wheelsim-post curves`` from synthetic runs with
W = 13.2 kN whose drawbar pull is the Wong–Reece value + 100 N; the reference is wong-reece
for LETE sand, R 0.617 m, b 0.479 m, W 13.2 kN at slips 0 .. 0.4. Near s = 0.02 the reference
DP (274 N) is below 0.1 W, so that point has a normalised difference (100 N / W) but no
relative error.
"""

import argparse
import csv
import os
import subprocess
import sys
import unittest

import numpy as np

import synthetic as syn
from helpers import TempDirTestCase, run_cli
from wheelsim_post.usage import find_project_root

ROOT = find_project_root()
BUILD_DIR = os.path.join(ROOT, "build") if ROOT else "build"
LOAD = 13200.0
SLIPS = (0.0, 0.02, 0.05, 0.1, 0.2, 0.3, 0.4)


def wong_reece_binary():
    for rel in ("bin/wong-reece", "scm/wong_reece/wong-reece"):
        path = os.path.join(BUILD_DIR, rel)
        if os.access(path, os.X_OK):
            return path
    return None


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


class CompareWongReeceTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.reference = self.path("wr_lete.csv")
        subprocess.run(
            [
                wong_reece_binary(),
                "--soil",
                os.path.join(ROOT, "inputs", "scm_soils", "lete_sand.toml"),
                "--radius",
                "0.617",
                "--width",
                "0.479",
                "--load",
                str(LOAD),
                "--slips",
                ",".join(str(s) for s in SLIPS),
                "--csv",
                self.reference,
            ],
            check=True,
            capture_output=True,
            timeout=120,
        )
        self.wr = {float(r["slip"]): r for r in read_rows(self.reference)}

    def curves_csv(self, slips):
        paths = []
        for index, slip in enumerate(slips):
            dp = float(self.wr[slip]["drawbar_pull_N"]) + 100.0
            time, phase, series = syn.steady_run_series(
                2000, 1e-3, 2.0, slip, dp, 60.0, load=LOAD
            )
            path = self.path(f"run{index}.h5")
            syn.write_run(path, time, phase, series, parameters={"sweep/wheel": "W"})
            paths.append(path)
        out = self.path("curves.csv")
        result = run_cli("curves", *paths, "--group-by", "wheel", "--csv", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        return out

    def test_curves_against_wong_reece(self):
        curves = self.curves_csv((0.0, 0.02, 0.1, 0.3))
        out = self.path("cmp.csv")
        result = run_cli(
            "compare", curves, self.reference, "--quantity", "drawbar_pull", "--csv", out
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("reference: wr_lete", result.stdout)
        self.assertNotIn("measured", result.stdout)
        self.assertIn("normalised by W = 13200", result.stdout)
        rows = {float(r["slip"]): r for r in read_rows(out)}
        self.assertEqual(sorted(rows), sorted(SLIPS))
        # in range 0 .. 0.3; 0.05 and 0.2 are interpolated (DP is not linear: not +100 N)
        for slip in (0.0, 0.02, 0.1, 0.3):
            r = rows[slip]
            self.assertEqual(r["in_range"], "1")
            self.assertAlmostEqual(float(r["difference_drawbar_pull_N"]), 100.0, places=4)
            self.assertAlmostEqual(float(r["normalised_difference"]), 100.0 / LOAD, places=8)
        self.assertEqual(rows[0.4]["in_range"], "0")
        # |DP_ref| < 0.1 W near DP = 0: no relative error there, but the normalised one
        self.assertTrue(np.isnan(float(rows[0.02]["error_percent"])))
        self.assertTrue(np.isnan(float(rows[0.0]["error_percent"])))
        ref_dp = float(self.wr[0.3]["drawbar_pull_N"])
        self.assertAlmostEqual(
            float(rows[0.3]["error_percent"]), 100.0 * 100.0 / ref_dp, places=6
        )
        self.assertIn("mean |sim − ref|/W:", result.stdout)

    def test_wong_reece_torque_column_and_measured_mapping(self):
        measured = self.path("rig_2024.csv")
        with open(measured, "w") as f:
            f.write("# bench test\nSlip,DP_N,Torque\n0.1,2500,2700\n0.25,4000,3700\n")
        result = run_cli(
            "compare",
            self.reference,
            measured,
            "--quantity",
            "driving_torque",
            "--columns",
            "slip=Slip,driving_torque=Torque",
            "--reference-label",
            "bench 2024",
            "--load",
            str(LOAD),
            "--r-eff",
            "0.617",
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("simulated: wr_lete", result.stdout)
        self.assertIn("reference: bench 2024", result.stdout)
        self.assertIn("normalised by W*R_eff", result.stdout)
        bad = run_cli(
            "compare", self.reference, measured, "--quantity", "drawbar_pull"
        )
        self.assertEqual(bad.returncode, 2)
        self.assertIn(
            "it has: Slip, DP_N, Torque; map columns with --columns slip=COLUMN", bad.stderr
        )


def main():
    global BUILD_DIR
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-dir", default=BUILD_DIR)
    args, rest = parser.parse_known_args()
    BUILD_DIR = args.build_dir
    if ROOT is None or wong_reece_binary() is None:
        print(f"SKIP: wong-reece is not built in {BUILD_DIR} (bin/ or scm/wong_reece/)")
        sys.exit(77)
    unittest.main(argv=[sys.argv[0], "-v"] + rest)


if __name__ == "__main__":
    main()
