"""The default steady-state window: whole lug passes (or revolutions) ending at the end of the
test phase, the lug count's sources, the printed window and the note below 3 passes.

Run: test phase 3 s (dt 1 ms, samples at 0.3 .. 3.3 s), ω = 5 rad/s, 12 lugs: one lug pass
is 2π/12 rad = 0.10472 s; the second half of the test phase (1.5 s, 7.5 rad) holds 14 whole
passes (7.3304 rad), so the window is 3.3 s − 14·0.10472 s = 1.83392 s .. 3.3 s. The drawbar
pull is 100 N + 30 N·sin(12 θ + 1): a whole number of passes averages the lug ripple out; the
old default (the whole second half, 14.32 passes) keeps part of it.
"""

import csv
import math
import os
import unittest

import numpy as np

import synthetic as syn
from helpers import TempDirTestCase, run_cli
from wheelsim_post.runfile import RunFile
from wheelsim_post.steady import DEFAULT_WINDOW, make_window, steady_state
from wheelsim_post.wheelinfo import lug_count

OMEGA, LUGS, DT, N_TEST = 5.0, 12, 1e-3, 3001
PASS_TIME = 2 * math.pi / LUGS / OMEGA
T1 = 0.3 + (N_TEST - 1) * DT


def write_lugged(path, lugs_parameter=LUGS, n_test=N_TEST, parameters=None):
    t_test = np.arange(n_test) * DT
    theta = OMEGA * t_test
    dp = 100.0 + 30.0 * np.sin(LUGS * theta + 1.0)
    time, phase, series = syn.steady_run_series(n_test, DT, OMEGA, 0.2, dp, 60.0)
    params = dict(parameters or {})
    if lugs_parameter is not None:
        params["wheel/lug_count"] = (lugs_parameter, "1")
    syn.write_run(path, time, phase, series, parameters=params)


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


class LugPassWindowTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.run_path = self.path("lugged.h5")
        write_lugged(self.run_path)

    def stats(self, window=DEFAULT_WINDOW, count=LUGS):
        with RunFile(self.run_path) as run:
            return steady_state(run, window, count, "test")

    def test_whole_lug_passes_ending_at_the_test_end(self):
        s = self.stats()
        span = s["span"]
        self.assertAlmostEqual(span.end, T1, places=9)
        self.assertAlmostEqual(span.start, T1 - 14 * PASS_TIME, delta=1e-9)
        self.assertEqual(span.passes, 14)
        self.assertEqual(span.notes, [])
        # the lug ripple averages out to the sampling error (old default: 0.3 N off)
        self.assertAlmostEqual(s["drawbar_pull"].mean, 100.0, delta=0.05)
        old = self.stats(make_window(None, None, (0.5, 1.0)))
        self.assertAlmostEqual(old["span"].passes, 7.5 / (2 * math.pi / LUGS), places=3)
        self.assertGreater(abs(old["drawbar_pull"].mean - 100.0), 0.1)

    def test_unknown_lug_count_counts_revolutions(self):
        s = self.stats(count=None)
        span = s["span"]
        # 7.5 rad in the second half: one whole revolution, 2π/5 s = 1.2566 s
        self.assertAlmostEqual(span.start, T1 - 2 * math.pi / OMEGA, delta=1e-9)
        self.assertEqual(span.passes, 1)
        self.assertEqual(span.pass_name, "revolutions")
        self.assertTrue(any("(< 3)" in note for note in span.notes), span.notes)

    def test_user_window_is_kept_and_its_passes_reported(self):
        s = self.stats(make_window(1.0, 2.0, None))
        self.assertAlmostEqual(s["span"].start, 1.3, places=9)
        self.assertAlmostEqual(s["span"].end, 2.3, places=9)
        self.assertAlmostEqual(s["span"].passes, 5.0 / (2 * math.pi / LUGS), places=3)

    def test_cli_prints_the_window_and_writes_the_columns(self):
        out = self.path("curves.csv")
        result = run_cli("curves", self.run_path, "--csv", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertRegex(
            result.stdout,
            r"lugged.h5: window 1.8339\d* s .. 3.3 s, 14 lug passes \(12 lugs from "
            r"/parameters/wheel/lug_count\)",
        )
        row = read_rows(out)[0]
        self.assertEqual(row["lug_count"], "12")
        self.assertEqual(float(row["window_passes"]), 14.0)
        self.assertEqual(row["window_notes"], "")
        # --lugs overrides the file: 6 lugs -> 7 passes of 0.20944 s, the same span
        result = run_cli("curves", self.run_path, "--csv", out, "--lugs", "6")
        self.assertIn("7 lug passes (6 lugs from --lugs)", result.stdout)

    def test_short_window_note_in_output_and_csv(self):
        short = self.path("short.h5")
        # lug count unknown: the window counts revolutions, 10 rad in the second half
        write_lugged(short, lugs_parameter=None, n_test=4001)
        out, png = self.path("short.csv"), self.path("short.png")
        result = run_cli("curves", short, "--csv", out, "--png", png)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("1 revolutions (lug count unknown", result.stdout)
        self.assertIn("note: the window holds 1 revolutions (< 3)", result.stdout)
        row = read_rows(out)[0]
        self.assertIn("(< 3)", row["window_notes"])
        with open(out) as f:
            lines = f.read().splitlines()
        footer = lines[lines.index("# notes:") :]  # after the data rows
        self.assertTrue(all(line.startswith("# ") for line in footer))
        self.assertTrue(
            any("short.h5: the window holds 1 revolutions (< 3)" in x for x in footer)
        )


    def test_no_short_window_note_for_a_smooth_wheel(self):
        # lug count 0 (a smooth wheel): no angular period, so no note on the window's length
        smooth = self.path("smooth.h5")
        write_lugged(smooth, lugs_parameter=0, n_test=4001)
        out = self.path("smooth.csv")
        result = run_cli("curves", smooth, "--csv", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("1 revolutions (lug count 0", result.stdout)
        self.assertNotIn("(< 3)", result.stdout)
        self.assertEqual(read_rows(out)[0]["window_notes"], "")


class LugCountSourceTest(TempDirTestCase):
    def test_props_file_next_to_the_mesh(self):
        mesh = self.path("w12.obj")
        with open(os.path.splitext(mesh)[0] + ".props.toml", "w") as f:
            f.write("[wheel]\nname = 'w12'\nlug_count = 12\nsmooth = false\n")
        path = self.path("props.h5")
        write_lugged(path, lugs_parameter=None, parameters={"wheel/mesh_file": mesh})
        with RunFile(path) as run:
            self.assertEqual(lug_count(run, "w12"), (12, mesh[:-4] + ".props.toml"))

    def test_catalog_by_wheel_name(self):
        path = self.path("catalog.h5")
        write_lugged(path, lugs_parameter=None)
        with RunFile(path) as run:
            count, source = lug_count(run, "wheel2")
            self.assertEqual(count, 15)
            self.assertIn("catalog.toml", source)
            self.assertEqual(lug_count(run, "smooth_1234")[0], 0)
            self.assertEqual(lug_count(run, "no such wheel"), (None, "unknown"))
            self.assertEqual(lug_count(run, "wheel2", override=4), (4, "--lugs"))


if __name__ == "__main__":
    unittest.main()
