"""``wheelsim-post curves``: the CSV (header comment, columns, groups) and the PNG; windows without
a finite sample."""

import csv
import math
import unittest

import h5py
import numpy as np

import synthetic as syn
from helpers import TempDirTestCase, is_png, run_cli
from wheelsim_post.cmd_curves import csv_header


def read(path):
    with open(path) as f:
        lines = f.read().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    return comments, rows


class CurvesTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        # two wheels on one soil at two slips, and one wheel on a second soil
        self.runs = syn.write_sweep_runs(
            lambda wheel, soil, slip, i: self.path(f"{wheel}_{soil}_{slip}.h5"),
            (
                ("W2", "S1", 0.3, 130.0),
                ("W1", "S1", 0.3, 120.0),
                ("W1", "S1", 0.1, 80.0),
                ("W1", "S2", 0.1, 60.0),
            ),
            terrain="dem",
        )

    def test_csv_groups_sorted_by_slip_with_window_in_header(self):
        out, png = self.path("curves.csv"), self.path("curves.png")
        result = run_cli(
            "curves", *self.runs, "--csv", out, "--png", png, "--window-fraction", "0.5", "1"
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn(
            "steady-state window: test phase (phase == 3) from 0.5 to 1", result.stdout
        )
        comments, rows = read(out)
        self.assertTrue(any("from 0.5 to 1 of its duration" in c for c in comments))
        with open(out) as f:
            header = next(line for line in f if not line.startswith("#")).strip()
        self.assertEqual(header.split(","), csv_header())
        groups = [r["group"] for r in rows]
        self.assertEqual(
            groups,
            [
                "wheel=W2, soil=S1, terrain=dem",
                "wheel=W1, soil=S1, terrain=dem",
                "wheel=W1, soil=S1, terrain=dem",
                "wheel=W1, soil=S2, terrain=dem",
            ],
        )
        w1 = [r for r in rows if r["group"] == "wheel=W1, soil=S1, terrain=dem"]
        self.assertEqual([float(r["target_slip"]) for r in w1], [0.1, 0.3])
        self.assertAlmostEqual(float(w1[0]["slip_mean"]), 0.1, places=9)
        self.assertAlmostEqual(float(w1[0]["drawbar_pull_mean_N"]), 80.0, places=6)
        self.assertAlmostEqual(
            float(w1[1]["drawbar_pull_std_N"]), 20 * math.sqrt(syn.SIN2_MEAN), places=6
        )
        self.assertAlmostEqual(float(w1[1]["window_start_s"]), 0.8, places=9)
        self.assertAlmostEqual(float(w1[1]["window_end_s"]), 1.3, places=9)
        self.assertEqual(w1[1]["n_samples"], "501")
        self.assertAlmostEqual(float(w1[1]["traction_force_mean_N"]), 600.0, places=6)
        v0 = 0.7 * syn.OMEGA * syn.R_EFF
        self.assertAlmostEqual(
            float(w1[1]["tractive_efficiency_of_means"]), 120 * v0 / 120.0, places=9
        )
        self.assertTrue(is_png(png))

    def test_group_by_wheel_merges_soils(self):
        out = self.path("curves.csv")
        result = run_cli("curves", *self.runs, "--group-by", "wheel", "--csv", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        _, rows = read(out)
        self.assertEqual(sorted({r["group"] for r in rows}), ["wheel=W1", "wheel=W2"])
        self.assertEqual(sum(r["group"] == "wheel=W1" for r in rows), 3)

    def test_stated_window_is_written(self):
        out = self.path("curves.csv")
        result = run_cli(
            "curves",
            self.runs[0],
            "--window-start",
            "0.55",
            "--window-end",
            "0.65",
            "--csv",
            out,
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        comments, rows = read(out)
        self.assertTrue(any("t0 + 0.55 s to t0 + 0.65 s" in c for c in comments))
        self.assertEqual(rows[0]["n_samples"], "101")
        self.assertAlmostEqual(float(rows[0]["window_start_s"]), 0.85, places=9)

    def test_sinkage_offset_moves_the_sinkage_mean_only(self):
        # read against a surface 5 mm lower: every sinkage mean 5 mm less, its std and SEM, the
        # other quantities and the health as without; the tables say so in their header
        plain, shifted = self.path("plain.csv"), self.path("shifted.csv")
        results = self.path("results.csv")
        self.assertEqual(run_cli("curves", *self.runs, "--csv", plain).returncode, 0)
        result = run_cli("curves", *self.runs, "--csv", shifted, "--results", results,
                         "--sinkage-offset", "0.005")
        self.assertEqual(result.returncode, 0, result.stderr)
        _, before = read(plain)
        comments, after = read(shifted)
        self.assertEqual(len(before), len(after))
        for b, a in zip(before, after):
            self.assertAlmostEqual(float(a["sinkage_mean_m"]), float(b["sinkage_mean_m"]) - 0.005,
                                   places=12)
            for column in ("sinkage_std_m", "sinkage_sem_m", "drawbar_pull_mean_N", "health_codes"):
                self.assertEqual(a[column], b[column], column)
        self.assertTrue(any("surface 0.005 m below the one each run recorded" in c
                            for c in comments))
        comments, table = read(results)
        self.assertTrue(any("(--sinkage-offset)" in c for c in comments))
        self.assertEqual(sorted(float(r["sinkage_m"]) for r in table),
                         sorted(float(r["sinkage_mean_m"]) for r in after))
        result = run_cli("curves", self.runs[0], "--sinkage-offset", "inf")
        self.assertOneLineError(result, "--sinkage-offset: expected a finite length [m], got inf")


class NonFiniteWindowTest(TempDirTestCase):
    """A window in which an observable has no finite sample is an error, not a row of NaN."""

    def write(self, name, value):
        path = self.path("run.h5")
        syn.write_rig_run(path)
        with h5py.File(path, "a") as f:
            f[f"observables/{name}/value"][...] = value
        return path

    def test_drawbar_pull_all_nan_names_the_run_the_observable_and_the_window(self):
        result = run_cli("curves", self.write("drawbar_pull", np.nan))
        self.assertOneLineError(
            result,
            "run.h5': observable 'drawbar_pull' has no finite sample in the window "
            "0.8 s .. 1.3 s",
            "501 samples there are all NaN or inf",
        )
        self.assertNotIn("DP nan", result.stdout)

    def test_torque_all_inf_and_sinkage_all_nan(self):
        for name, value in (("driving_torque", np.inf), ("sinkage", np.nan)):
            with self.subTest(name=name):
                result = run_cli("curves", self.write(name, value))
                self.assertOneLineError(result, f"observable '{name}' has no finite sample")

    def test_an_observable_without_rows_in_the_window(self):
        path = self.path("run.h5")
        syn.write_rig_run(path, omit=("sinkage",))
        with h5py.File(path, "a") as f:
            syn.write_observable(f, "sinkage", [0, 1], [0.0, 0.001], [0.01, 0.01], "m")
        result = run_cli("curves", path)
        self.assertOneLineError(result, "observable 'sinkage' has no finite sample",
                                "it has no sample there")

    def test_a_value_shorter_than_time_is_a_malformed_file_without_a_numpy_warning(self):
        path = self.path("run.h5")
        syn.write_rig_run(path)
        with h5py.File(path, "a") as f:
            del f["observables/drawbar_pull/value"]
            f["observables/drawbar_pull"].create_dataset("value", data=np.ones(500))
        result = run_cli("curves", path)
        self.assertOneLineError(  # one line: no RuntimeWarning either
            result, "observable 'drawbar_pull' has datasets of different lengths",
            "time 1301, value 500 rows")


if __name__ == "__main__":
    unittest.main()
