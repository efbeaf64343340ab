"""Slip conventions (slip.py): driving 1 − v/(ωR), skid (ωR − v)/v, signed (issue 11's
``slip``: driving for s ≥ 0, skid for s < 0), with ω = 0 and v = 0; and the three conventions
in steady_state() and the curves CSV of runs at known speeds."""

import csv
import math
import unittest

import numpy as np

import synthetic as syn
from helpers import TempDirTestCase, run_cli
from wheelsim_post.runfile import RunFile
from wheelsim_post.slip import driving_slip, forward_speed, signed_slip, skid_slip
from wheelsim_post.steady import DEFAULT_WINDOW, steady_state


class SlipConventionsTest(unittest.TestCase):
    def test_driving_point(self):
        # v = 0.1 m/s, ω R_eff = 0.2 m/s
        self.assertAlmostEqual(driving_slip(0.1, 0.2), 0.5, places=12)
        self.assertAlmostEqual(skid_slip(0.1, 0.2), 1.0, places=12)
        self.assertAlmostEqual(signed_slip(0.1, 0.2), 0.5, places=12)

    def test_skid_point(self):
        # v = 0.2 m/s, ω R_eff = 0.1 m/s
        self.assertAlmostEqual(driving_slip(0.2, 0.1), -1.0, places=12)
        self.assertAlmostEqual(skid_slip(0.2, 0.1), -0.5, places=12)
        self.assertAlmostEqual(signed_slip(0.2, 0.1), -0.5, places=12)

    def test_locked_wheel(self):
        # ω = 0, v > 0: skid and signed -1; the driving convention is undefined there
        self.assertEqual(skid_slip(0.3, 0.0), -1.0)
        self.assertEqual(signed_slip(0.3, 0.0), -1.0)
        self.assertTrue(math.isnan(driving_slip(0.3, 0.0)))

    def test_spinning_in_place_and_at_rest(self):
        # v = 0, ω > 0: driving and signed 1; the skid convention is undefined there
        self.assertEqual(driving_slip(0.0, 0.2), 1.0)
        self.assertEqual(signed_slip(0.0, 0.2), 1.0)
        self.assertTrue(math.isnan(skid_slip(0.0, 0.2)))
        # at rest every convention is undefined
        for f in (driving_slip, skid_slip, signed_slip):
            self.assertTrue(math.isnan(f(0.0, 0.0)), f.__name__)

    def test_free_rolling_and_reverse_travel(self):
        for f in (driving_slip, skid_slip, signed_slip):
            self.assertEqual(f(0.25, 0.25), 0.0, f.__name__)
        # backwards: v = -0.1, ω R = -0.2 is driving at 0.5; v = -0.2, ω R = -0.1 skids at -0.5
        self.assertAlmostEqual(signed_slip(-0.1, -0.2), 0.5, places=12)
        self.assertAlmostEqual(signed_slip(-0.2, -0.1), -0.5, places=12)

    def test_arrays_and_the_relation_between_conventions(self):
        v = np.array([0.1, 0.2, 0.3, 0.0, 0.0, 0.15])
        rim = np.array([0.2, 0.1, 0.0, 0.2, 0.0, 0.1])
        signed = signed_slip(v, rim)
        self.assertIsInstance(signed, np.ndarray)
        np.testing.assert_allclose(signed[:5], [0.5, -0.5, -1.0, 1.0, np.nan], atol=1e-12)
        # s_skid = s_driving / (1 - s_driving) wherever both are defined
        d, k = driving_slip(v, rim), skid_slip(v, rim)
        both = np.isfinite(d) & np.isfinite(k)
        np.testing.assert_allclose(k[both], d[both] / (1.0 - d[both]), rtol=1e-12)
        # the signed convention stays in [-1, 1] for forward travel
        grid_v, grid_rim = np.meshgrid(np.linspace(0, 1, 21), np.linspace(0, 1, 21))
        s = signed_slip(grid_v, grid_rim)
        finite = s[np.isfinite(s)]
        self.assertEqual(finite.size, 21 * 21 - 1)  # only (0, 0) is undefined
        self.assertTrue(np.all((finite >= -1.0) & (finite <= 1.0)))


def locked_run(path, v=0.05, n_test=1000, dt=0.001):
    """A run with ω = 0 and a constant carriage speed ``v`` [m/s] (a locked wheel)."""
    time, phase, series = syn.steady_run_series(n_test, dt, 0.0, 0.0, -30.0, -3.0, load=50.0)
    series["carriage/velocity"] = (np.full(len(time), v), "m/s")
    syn.write_run(path, time, phase, series)


class ForwardSpeedTest(unittest.TestCase):
    def test_inverse_of_the_signed_slip(self):
        # rim speed 0.5 m/s: driving s 0.2 -> 0.4 m/s, free rolling, skid s -0.5 -> 1.0 m/s
        rim = 0.5
        for s, v in ((0.2, 0.4), (0.0, 0.5), (-0.5, 1.0), (0.9, 0.05)):
            self.assertAlmostEqual(forward_speed(rim, s), v, places=15)
            self.assertAlmostEqual(signed_slip(forward_speed(rim, s), rim), s, places=12)
        self.assertTrue(math.isnan(forward_speed(rim, -1.0)))  # locked: v not set by the rim
        np.testing.assert_allclose(forward_speed(rim, np.array([0.2, -0.5])), [0.4, 1.0])


class SlipInRunsTest(TempDirTestCase):
    def test_skid_run_in_three_conventions(self):
        # standard run with driving slip -1: v = 2 ω R_eff -> skid -0.5
        path = self.path("skid.h5")
        syn.write_rig_run(path, slip=-1.0)
        with RunFile(path) as run:
            stats = steady_state(run, DEFAULT_WINDOW)
        self.assertAlmostEqual(stats["slip_of_means"].mean, -1.0, places=9)
        self.assertAlmostEqual(stats["slip_skid_of_means"].mean, -0.5, places=9)
        self.assertAlmostEqual(stats["slip_signed_of_means"].mean, -0.5, places=9)
        # per-sample means: v = v0 + 0.01 sin, so (ωR - v)/v averages slightly above -0.5
        v0 = 2.0 * syn.OMEGA * syn.R_EFF
        rel = syn.V_AMPLITUDE / v0
        expected = 1.0 / (2.0 * math.sqrt(1.0 - rel**2)) - 1.0  # mean of ωR/(v0 + a sin) - 1
        self.assertAlmostEqual(stats["slip_skid"].mean, expected, delta=1e-5)
        self.assertAlmostEqual(stats["slip"].mean, -1.0, places=9)

    def test_locked_wheel_run_is_minus_one_without_nan(self):
        path = self.path("locked.h5")
        locked_run(path)
        with RunFile(path) as run:
            stats = steady_state(run, DEFAULT_WINDOW)
        self.assertEqual(stats["slip_signed"].mean, -1.0)
        self.assertEqual(stats["slip_skid"].mean, -1.0)
        self.assertEqual(stats["slip_signed_of_means"].mean, -1.0)
        self.assertTrue(math.isnan(stats["slip"].mean))  # driving: undefined at ω = 0

    def test_curves_csv_has_the_three_conventions(self):
        paths = [self.path("drive.h5"), self.path("locked.h5")]
        syn.write_rig_run(paths[0], slip=0.5)
        locked_run(paths[1])
        out = self.path("curves.csv")
        result = run_cli("curves", *paths, "--csv", out, "--png", self.path("c.png"))
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(out) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
        # sorted by signed slip: the locked wheel (-1) first
        self.assertEqual([r["run_file"] for r in rows], [paths[1], paths[0]])
        locked, drive = rows
        self.assertEqual(float(locked["slip_signed_of_means"]), -1.0)
        self.assertEqual(float(locked["slip_skid_mean"]), -1.0)
        self.assertEqual(locked["slip_mean"], "nan")
        self.assertAlmostEqual(float(drive["slip_of_means"]), 0.5, places=9)
        self.assertAlmostEqual(float(drive["slip_signed_of_means"]), 0.5, places=9)
        self.assertAlmostEqual(float(drive["slip_skid_of_means"]), 1.0, places=9)


if __name__ == "__main__":
    unittest.main()
