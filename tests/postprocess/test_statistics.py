"""Standard errors of steady-state means from autocorrelated samples (batch means).

The reference is the AR(1) process x_t = a x_(t-1) + e_t with innovations of std sigma, whose
mean of N samples has the exact variance sigma²/(1 - a²)/N · [(1 + a)/(1 - a) - 2a(1 - a^N)/
(N (1 - a)²)] ≈ sigma²/((1 - a)² N) for long N. One batch-means estimate from 20 batches
scatters by about 16 % (a chi distribution with 19 degrees of freedom), so the check averages
the squared estimate over 32 fixed seeds (their root mean square must be within 10 %).
"""

import math
import re
import unittest

import numpy as np

import synthetic as syn
from helpers import TempDirTestCase
from wheelsim_post.runfile import RunFile
from wheelsim_post.steady import DEFAULT_WINDOW, batch_sem, make_window, steady_state

N = 200_000
SEEDS = range(1000, 1032)
TOLERANCE = 0.10


class BatchMeansTest(unittest.TestCase):
    def check_ar1(self, a):
        exact = syn.ar1_sem(a, N)
        estimates = np.array(
            [batch_sem(syn.ar1(a, N, np.random.default_rng(seed))) for seed in SEEDS]
        )
        rms = math.sqrt(float(np.mean(estimates**2)))
        print(f"\nAR(1) a = {a}: exact SEM {exact:.5g}, batch means (rms of "
              f"{len(SEEDS)} seeds) {rms:.5g}, ratio {rms / exact:.4f}")
        self.assertAlmostEqual(rms / exact, 1.0, delta=TOLERANCE)
        # the old '±' (std of the raw signal) is off by a factor ~ sqrt(N (1-a)/(1+a))
        x = syn.ar1(a, N, np.random.default_rng(0))
        self.assertGreater(np.std(x) / exact, 20.0)

    def test_ar1_a_0_9(self):
        self.check_ar1(0.9)

    def test_ar1_a_0_99(self):
        self.check_ar1(0.99)

    def test_white_noise_gives_the_textbook_sem(self):
        estimates = [
            batch_sem(np.random.default_rng(seed).normal(0.0, 2.0, 100_000))
            for seed in SEEDS
        ]
        rms = math.sqrt(float(np.mean(np.square(estimates))))
        self.assertAlmostEqual(rms / (2.0 / math.sqrt(100_000)), 1.0, delta=TOLERANCE)

    def test_too_few_samples(self):
        self.assertTrue(math.isnan(batch_sem(np.array([1.0]))))
        self.assertTrue(math.isnan(batch_sem(np.array([]))))
        self.assertGreater(batch_sem(np.array([1.0, 2.0, 4.0])), 0.0)


class RunFileSemTest(TempDirTestCase):
    """The SEM reaches steady_state(), the curves CSV and the normalised columns."""

    def setUp(self):
        super().setUp()
        self.a, self.n_test = 0.99, 100_000
        noise = 5.0 * syn.ar1(self.a, self.n_test, np.random.default_rng(7))
        time, phase, series = syn.steady_run_series(
            self.n_test, 1e-3, 2.0, 0.2, 100.0 + noise, 60.0 + 0.1 * noise, load=1000.0
        )
        self.noise = noise
        self.run_path = self.path("ar1.h5")
        syn.write_run(self.run_path, time, phase, series)

    def test_sem_of_the_window_samples(self):
        with RunFile(self.run_path) as run:
            s = steady_state(run, make_window(None, None, (0.5, 1.0)))
        window = self.noise[self.n_test // 2 :]  # t0 + D/2 (index 49999.5) .. t1
        self.assertEqual(s["n_samples"], len(window))
        dp = s["drawbar_pull"]
        self.assertAlmostEqual(dp.mean, 100.0 + float(np.mean(window)), delta=1e-9)
        self.assertAlmostEqual(dp.sem, batch_sem(window + 100.0), delta=1e-9)
        exact = 5.0 * syn.ar1_sem(self.a, len(window))
        # one series: within the scatter of a 20-batch estimate (16 % rms), far from std
        self.assertLess(abs(dp.sem / exact - 1.0), 0.5)
        self.assertGreater(dp.std / dp.sem, 10.0)
        # normalised by W = 1000 N (the vertical_load observable) and W R_eff
        self.assertAlmostEqual(s["dp_over_w"].mean, dp.mean / 1000.0, delta=1e-12)
        self.assertAlmostEqual(s["dp_over_w"].sem, dp.sem / 1000.0, delta=1e-12)
        torque = s["driving_torque"]
        self.assertAlmostEqual(
            s["torque_over_w_reff"].mean, torque.mean / (1000.0 * syn.R_EFF), delta=1e-12
        )
        self.assertAlmostEqual(
            s["torque_over_w_reff"].sem, torque.sem / (1000.0 * syn.R_EFF), delta=1e-12
        )
        self.assertEqual(s["vertical_load_source"], "observable vertical_load")

    def test_note_when_batches_are_shorter_than_the_correlation_time(self):
        # a = 0.999: correlation time ~2000 samples, batches of 100 -> correlated batch means
        notes = {}
        for a in (0.999, 0.0):
            noise = 5.0 * syn.ar1(a, 4000, np.random.default_rng(11))
            time, phase, series = syn.steady_run_series(4000, 1e-3, 2.0, 0.2, 100 + noise, 60)
            path = self.path(f"corr{a}.h5")
            syn.write_run(path, time, phase, series)
            with RunFile(path) as run:
                s = steady_state(run, make_window(None, None, (0.5, 1.0)))
            notes[a] = [n for n in s["span"].notes if "batch means" in n]
        self.assertEqual(len(notes[0.999]), 1, notes)
        self.assertIn("SEMs are probably too small", notes[0.999][0])
        self.assertEqual(notes[0.0], [])

    def test_note_names_a_drift_when_it_correlates_the_batches(self):
        # white noise (sd 1 N) on a drift of -4 N over the window: the batch means follow the
        # drift (lag-1 ~0.8), but about a fitted line they are independent: the note keeps its
        # warning and adds that number and the drift
        rng = np.random.default_rng(5)
        n = 4000
        drift = np.linspace(0.0, -8.0, n)  # -4 N over the second half, the window
        time, phase, series = syn.steady_run_series(n, 1e-3, 2.0, 0.2,
                                                    100 + drift + rng.normal(0, 1.0, n), 60)
        path = self.path("drift.h5")
        syn.write_run(path, time, phase, series)
        with RunFile(path) as run:
            s = steady_state(run, make_window(None, None, (0.5, 1.0)))
        notes = [x for x in s["span"].notes if "batch means" in x]
        self.assertEqual(len(notes), 1, s["span"].notes)
        self.assertIn("probably too small", notes[0])
        m = re.search(r"fitted to them they correlate ([-0-9.]+): if the window drifts "
                      r"\(([-+0-9.e]+) N over it\)", notes[0])
        self.assertIsNotNone(m, notes[0])
        self.assertLess(float(m.group(1)), 0.5)
        self.assertAlmostEqual(float(m.group(2)), -4.0, delta=0.3)
        self.assertGreater(s["dp_batch_correlation"], 0.5)

    def test_load_from_the_rig_config_without_the_observable(self):
        time, phase, series = syn.steady_run_series(2000, 1e-3, 2.0, 0.2, 100.0, 60.0)
        path = self.path("config_load.h5")
        config = syn.rig_config(0.2) + "[rig]\nvertical_load = 500.0\n"
        syn.write_run(path, time, phase, series, config=config)
        with RunFile(path) as run:
            s = steady_state(run, DEFAULT_WINDOW)
        self.assertAlmostEqual(s["dp_over_w"].mean, 0.2, delta=1e-12)
        self.assertEqual(s["vertical_load_source"], "rig.vertical_load")


if __name__ == "__main__":
    unittest.main()
