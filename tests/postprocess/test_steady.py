"""wheelsim_post.steady: the window and the statistics against the analytic answers."""

import contextlib
import io
import math
import unittest

import numpy as np

import synthetic as syn
from helpers import TempDirTestCase
from wheelsim_post.errors import PostError
from wheelsim_post.quantities import EFFICIENCY_OF_MEANS, SLIP_OF_MEANS
from wheelsim_post.runfile import RunFile
from wheelsim_post.steady import DEFAULT_WINDOW, Window, make_window, steady_state

RTOL = 1e-9


def stats(path, window=DEFAULT_WINDOW):
    with RunFile(path) as run:
        return steady_state(run, window)


class WindowTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.run_path = self.path("run.h5")
        syn.write_rig_run(self.run_path, slip=0.2, dp_mean=100.0, torque=60.0)

    def test_default_is_second_half_of_test_phase(self):
        # The standard run turns 2 rad in its 1 s test phase: not one revolution fits in its
        # second half, so the default window falls back to that half (with a note).
        self.assertEqual(DEFAULT_WINDOW, Window("passes", 0.5, 1.0))
        s = stats(self.run_path)
        span = s["span"]
        self.assertAlmostEqual(span.test_start, 0.3, places=12)
        self.assertAlmostEqual(span.start, 0.8, places=12)
        self.assertAlmostEqual(span.end, 1.3, places=12)
        # both ends included: steps 800..1300
        self.assertEqual(s["n_samples"], 501)
        self.assertEqual(span.steps[0], 800)
        self.assertEqual(span.steps[-1], 1300)

    def test_drawbar_pull_mean_and_std_are_analytic(self):
        mean, std, _ = stats(self.run_path)["drawbar_pull"]
        self.assertAlmostEqual(mean, 100.0, delta=1e-9)
        self.assertAlmostEqual(
            std, syn.DP_AMPLITUDE * math.sqrt(syn.SIN2_MEAN), delta=1e-9
        )

    def test_time_and_fraction_windows_agree(self):
        by_time = stats(self.run_path, make_window(0.5, 1.0, None))
        by_fraction = stats(self.run_path, make_window(None, None, (0.5, 1.0)))
        for s in (by_time, by_fraction):
            self.assertEqual(s["n_samples"], 501)
            self.assertAlmostEqual(s["drawbar_pull"][0], 100.0, delta=1e-9)

    def test_a_window_one_step_wider_takes_in_wild_values(self):
        # The sample just before the window is wild: including it must change the answer,
        # which shows the window (and the check above) are sensitive to one sample.
        s = stats(self.run_path, make_window(0.499, 1.0, None))
        self.assertEqual(s["n_samples"], 502)
        self.assertGreater(s["drawbar_pull"][0], 1000.0)

    def test_a_narrower_window_keeps_its_boundaries(self):
        # 0.55 .. 0.65 s after t0 = steps 850..950: u = sin(2π k/100), k = 50..150
        s = stats(self.run_path, make_window(0.55, 0.65, None))
        self.assertEqual(s["n_samples"], 101)
        u = np.sin(2 * np.pi * np.arange(50, 151) / 100)
        self.assertAlmostEqual(s["drawbar_pull"][0], 100 + 20 * u.mean(), delta=1e-9)
        self.assertAlmostEqual(s["drawbar_pull"][1], 20 * u.std(), delta=1e-9)

    def test_slip_efficiency_and_traction_force_from_v_omega_dp_t(self):
        s = stats(self.run_path)
        v0 = 0.8 * syn.OMEGA * syn.R_EFF
        m2 = syn.SIN2_MEAN
        self.assertAlmostEqual(s["slip"][0], 0.2, delta=1e-12)
        self.assertAlmostEqual(
            s["slip"][1],
            syn.V_AMPLITUDE / (syn.OMEGA * syn.R_EFF) * math.sqrt(m2),
            delta=1e-12,
        )
        self.assertAlmostEqual(s[SLIP_OF_MEANS].mean, 0.2, delta=1e-12)
        # η of the means: DP v / (T ω) with the window means
        self.assertAlmostEqual(s[EFFICIENCY_OF_MEANS].mean, 100 * v0 / (60 * 2), delta=1e-12)
        # mean of the per-step η: mean(DP v) = 100 v0 + 20·0.01·mean(u²)
        eta_mean = (100 * v0 + syn.DP_AMPLITUDE * syn.V_AMPLITUDE * m2) / (60 * 2)
        self.assertAlmostEqual(s["tractive_efficiency"][0], eta_mean, delta=1e-12)
        self.assertNotAlmostEqual(
            s["tractive_efficiency"][0], s[EFFICIENCY_OF_MEANS].mean, places=6
        )
        self.assertAlmostEqual(s["traction_force"][0], 60 / syn.R_EFF, delta=1e-9)
        self.assertAlmostEqual(s["traction_force"][1], 0.0, delta=1e-9)
        self.assertAlmostEqual(s["driving_torque"][0], 60.0, delta=1e-9)
        self.assertAlmostEqual(s["sinkage"][0], syn.SINKAGE, delta=1e-12)
        self.assertAlmostEqual(
            s["sinkage"][1], syn.SINKAGE_AMPLITUDE * math.sqrt(m2), delta=1e-12
        )
        self.assertAlmostEqual(s["lateral_force"][0], syn.LATERAL, delta=1e-9)

    def test_slip_does_not_come_from_the_rig_slip_series(self):
        # The rig's own 'slip' and 'tractive_efficiency' series are ignored: without them the
        # answers are the same.
        other = self.path("no_slip_series.h5")
        syn.write_rig_run(other, omit=("slip", "tractive_efficiency"))
        a, b = stats(self.run_path), stats(other)
        self.assertEqual(a["slip"], b["slip"])
        self.assertEqual(a[EFFICIENCY_OF_MEANS], b[EFFICIENCY_OF_MEANS])

    def test_rows_with_step_minus_one_do_not_leak(self):
        crashed = self.path("crashed.h5")
        syn.write_rig_run(crashed, crashed=True)
        s = stats(crashed)
        self.assertEqual(s["n_samples"], 501)
        self.assertAlmostEqual(s["drawbar_pull"][0], 100.0, delta=1e-9)

    def test_missing_lateral_force_gives_nan(self):
        other = self.path("no_lateral.h5")
        syn.write_rig_run(other, omit=("lateral_force",))
        self.assertTrue(math.isnan(stats(other)["lateral_force"][0]))

    def test_missing_required_observable_is_an_error(self):
        other = self.path("no_dp.h5")
        syn.write_rig_run(other, omit=("drawbar_pull",))
        with self.assertRaisesRegex(
            PostError, "no_dp.h5' has no observable 'drawbar_pull'"
        ):
            stats(other)

    def test_a_window_past_the_last_sample_warns_beyond_one_sample_interval(self):
        # test phase 0.3 .. 1.3 s, one sample per 1 ms: ending the window half a sample after
        # the last one (a window as long as the phase, t0 its first sample) is not warned of;
        # two samples after it is
        for end, warned in ((1.0005, False), (1.002, True)):
            with self.subTest(end=end):
                err = io.StringIO()
                with contextlib.redirect_stderr(err):
                    s = stats(self.run_path, make_window(0.5, end, None))
                self.assertEqual(s["n_samples"], 501)
                self.assertEqual("after the last test-phase sample" in err.getvalue(), warned)

    def test_window_after_the_data_is_an_error(self):
        with self.assertRaisesRegex(PostError, "holds no test-phase sample"):
            stats(self.run_path, make_window(2.0, 3.0, None))


class MakeWindowTest(unittest.TestCase):
    def test_bad_combinations_name_the_option(self):
        cases = [
            ((None, None, (0.6, 0.5)), "--window-fraction"),
            ((None, None, (-0.1, 0.5)), "--window-fraction"),
            ((None, None, (0.5, 1.5)), "--window-fraction"),
            ((0.1, None, None), "--window-start and --window-end"),
            ((0.5, 0.2, None), "--window-start/--window-end"),
            ((0.1, 0.2, (0.1, 0.2)), "cannot be combined"),
        ]
        for args, message in cases:
            with self.subTest(args=args), self.assertRaisesRegex(PostError, message):
                make_window(*args)


if __name__ == "__main__":
    unittest.main()
