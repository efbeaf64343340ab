"""``wheelsim-post approach``: means per segment of test-phase travel, on synthetic runs with a
known answer (a drawbar pull linear in travel: each segment's mean is its value at the segment's
middle; a sinkage approaching its steady value exponentially: the changes shrink by exp(-L/λ))."""

import csv
import math
import unittest

import numpy as np

import synthetic
from helpers import TempDirTestCase, run_cli

V = 0.1          # [m/s] carriage speed in the test phase
DT = 1e-4        # [s] sample interval
N_BEFORE = 100   # samples in each of release, settle and ramp
LAMBDA = 0.03    # [m] sinkage approach length


def write(path, travel_m=0.12, carriage=True, wheel=True, nan_before_m=0.0):
    """A run whose drawbar pull is NaN over the first ``nan_before_m`` of travel (all of it
    if larger than the travel)."""
    n_test = int(round(travel_m / V / DT)) + 1
    n = 3 * N_BEFORE + n_test
    time = np.arange(n) * DT
    phase = np.concatenate([np.full(N_BEFORE, c, dtype=float) for c in (0, 1, 2)]
                           + [np.full(n_test, 3.0)])
    x = np.concatenate([np.zeros(3 * N_BEFORE), np.arange(n_test) * V * DT]) + 0.09
    travel = x - 0.09
    series = {
        "drawbar_pull": (-3.0 - 50.0 * travel, "N"),                          # linear
        "sinkage": (0.04 - 0.01 * np.exp(-travel / LAMBDA), "m"),             # exponential
        "driving_torque": (np.full(n, 0.2), "N m"),
    }
    series["drawbar_pull"][0][(3 * N_BEFORE <= np.arange(n)) & (travel < nan_before_m)] = np.nan
    position = np.stack([x, np.zeros(n), np.full(n, 0.1)], axis=1)
    if carriage:
        series["carriage/position"] = (position, "m")
    if wheel:
        series["wheel/position"] = (position + [0.0, 0.0, -0.05], "m")
    synthetic.write_run(path, time, phase, series)


class ApproachTest(TempDirTestCase):
    def rows(self, *args):
        out = self.path("approach.csv")
        result = run_cli("approach", *args, "--csv", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(out) as f:
            return result, list(csv.DictReader(line for line in f if not line.startswith("#")))

    def test_linear_pull_gives_the_segment_middles(self):
        write(self.path("run.h5"))
        result, rows = self.rows(self.path("run.h5"))
        self.assertEqual([(float(r["from_m"]), float(r["to_m"])) for r in rows],
                         [(0.0, 0.025), (0.025, 0.05), (0.05, 0.075), (0.075, 0.1), (0.1, 0.12)])
        for r in rows:
            middle = 0.5 * (float(r["from_m"]) + float(r["to_m"]))
            self.assertAlmostEqual(float(r["drawbar_pull"]), -3.0 - 50.0 * middle, delta=1e-3)
        # the pull changes by -50 N/m x the distance between the middles: -1.25 N per 25 mm
        self.assertTrue(math.isnan(float(rows[0]["drawbar_pull_change"])))
        for r in rows[1:4]:
            self.assertAlmostEqual(float(r["drawbar_pull_change"]), -1.25, delta=1e-3)
        self.assertIn("drawbar_pull [N]", result.stdout)

    def test_exponential_approach_shrinks_by_exp_segment_over_lambda(self):
        write(self.path("run.h5"), travel_m=0.1)
        _, rows = self.rows(self.path("run.h5"), "--segment", "0.02")
        changes = [float(r["sinkage_change"]) for r in rows[1:]]
        for a, b in zip(changes, changes[1:]):
            self.assertAlmostEqual(b / a, math.exp(-0.02 / LAMBDA), delta=2e-3)
        self.assertTrue(all(abs(float(r["driving_torque_change"])) < 1e-12 for r in rows[1:]))

    def test_a_short_last_segment_is_dropped(self):
        write(self.path("run.h5"), travel_m=0.11)  # 10 mm after 100: under half of 25 mm
        _, rows = self.rows(self.path("run.h5"))
        self.assertEqual(float(rows[-1]["to_m"]), 0.1)

    def test_wheel_position_when_no_carriage(self):
        write(self.path("run.h5"), carriage=False)
        _, rows = self.rows(self.path("run.h5"))
        self.assertEqual(len(rows), 5)

    def test_errors_name_the_input(self):
        write(self.path("run.h5"), carriage=False, wheel=False)
        result = run_cli("approach", self.path("run.h5"))
        self.assertEqual(result.returncode, 2)
        self.assertIn("carriage/position, wheel/position", result.stderr)
        write(self.path("ok.h5"))
        result = run_cli("approach", self.path("ok.h5"), "--segment", "0")
        self.assertEqual(result.returncode, 2)
        self.assertIn("--segment: expected a finite length > 0 m", result.stderr)
        result = run_cli("approach", self.path("ok.h5"), "--observables", "carriage/position")
        self.assertEqual(result.returncode, 2)
        self.assertIn("has 3 components, expected 1", result.stderr)

    def test_segments_of_every_observable_line_up_when_one_has_none_in_a_segment(self):
        # the pull is NaN over the first 30 mm: segment 0 has no mean of it, segment 1 (25-50 mm)
        # the mean of 30-50 mm; the sinkage and torque rows are those of a complete run
        write(self.path("run.h5"), nan_before_m=0.03)
        _, rows = self.rows(self.path("run.h5"))
        self.assertEqual(len(rows), 5)
        self.assertTrue(math.isnan(float(rows[0]["drawbar_pull"])))
        self.assertAlmostEqual(float(rows[1]["drawbar_pull"]), -3.0 - 50.0 * 0.04, delta=1e-3)
        self.assertAlmostEqual(float(rows[2]["drawbar_pull"]), -3.0 - 50.0 * 0.0625, delta=1e-3)
        write(self.path("full.h5"))
        _, full = self.rows(self.path("full.h5"))
        self.assertEqual([r["sinkage"] for r in rows], [r["sinkage"] for r in full])

    def test_no_row_is_an_error_that_says_why(self):
        write(self.path("run.h5"))
        result = run_cli("approach", self.path("run.h5"), "--segment", "1000")
        self.assertOneLineError(result, "run.h5': the test phase travels 0.12 m",
                                "less than half a segment of 1000 m (--segment)")
        write(self.path("nan.h5"), nan_before_m=1.0)
        result = run_cli("approach", self.path("nan.h5"))
        self.assertOneLineError(result, "nan.h5': observable 'drawbar_pull' has no finite "
                                "sample in the test phase's 0.12 m of travel")
        result = run_cli("approach", self.path("run.h5"), "--segment", "inf")
        self.assertOneLineError(result, "--segment: expected a finite length > 0 m, got inf")
        result = run_cli("approach", self.path("run.h5"), "--observables", ",")
        self.assertOneLineError(result, "--observables: expected a comma-separated list")


if __name__ == "__main__":
    unittest.main()
