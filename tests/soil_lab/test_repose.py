"""soil_lab_py.repose on synthetic heaps of particles of known radius (2 mm) with a rough surface
(tops 0-1 mm below the ideal surface): a 30 deg cone and a slot heap with flanks of 25 and
35 deg must give their angles within 0.5 deg; bad input gives clear errors."""

import unittest

import numpy as np

import synthetic as syn
from soil_lab_py.repose import FitInputError, repose_angle, surface_profile

R = 0.002  # particle radius [m]
H = 0.1  # heap height [m]
BIN = 2 * R  # one particle diameter


def profile(x, z):
    edges = np.arange(x.min(), x.max() + BIN, BIN)
    return surface_profile(x, z, R, edges)


class SurfaceProfileTest(unittest.TestCase):
    def test_highest_top_per_bin(self):
        x = np.array([0.1, 0.2, 0.25, 0.9, 0.95])
        z = np.array([1.0, 3.0, 2.0, 0.5, 0.7])
        r = np.array([0.1, 0.1, 1.5, 0.2, 0.0])
        xc, h = surface_profile(x, z, r, bins=[0.0, 0.5, 0.75, 1.0])
        np.testing.assert_allclose(xc, [0.25, 0.875])  # the empty middle bin is left out
        np.testing.assert_allclose(h, [3.5, 0.7])
        xc, h = surface_profile(x, z, 0.5, bins=2, x_range=(0.0, 1.0))
        np.testing.assert_allclose(xc, [0.25, 0.75])
        np.testing.assert_allclose(h, [3.5, 1.2])

    def test_bad_input(self):
        with self.assertRaisesRegex(FitInputError, r"z\[1\] is nan"):
            surface_profile([0.0, 1.0], [0.0, np.nan], 0.1, 4)
        with self.assertRaisesRegex(FitInputError, r"radius\[0\] is -0\.1"):
            surface_profile([0.0, 1.0], [0.0, 1.0], [-0.1, 0.1], 4)
        with self.assertRaisesRegex(FitInputError, r"bins must be a positive integer"):
            surface_profile([0.0, 1.0], [0.0, 1.0], 0.1, 0)


class ReposeAngleTest(unittest.TestCase):
    def check(self, name, fit, left, right):
        print(f"\n  {name}: angle {fit.angle_deg:.3f}, left {fit.left.angle_deg:.3f} "
              f"(true {left}), right {fit.right.angle_deg:.3f} (true {right}), "
              f"RMS {fit.left.rms_m * 1e3:.3f}/{fit.right.rms_m * 1e3:.3f} mm", end=" ")
        self.assertLess(abs(fit.left.angle_deg - left), 0.5)
        self.assertLess(abs(fit.right.angle_deg - right), 0.5)
        self.assertLess(abs(fit.angle_deg - 0.5 * (left + right)), 0.5)
        for flank in (fit.left, fit.right):
            self.assertGreaterEqual(flank.n_points, 10)
            self.assertLess(flank.rms_m, R)  # rougher than the grains would be a wrong fit
        self.assertGreater(fit.left.slope, 0.0)
        self.assertLess(fit.right.slope, 0.0)

    def test_cone_30_deg(self):
        x, _, z = syn.heap_particles(H, 30.0, 30.0, R)
        xc, h = profile(x, z)
        fit = repose_angle(xc, h)
        self.check("cone 30 deg", fit, 30.0, 30.0)
        # The band is 20-80 % of the height above the floor layer's tops (2 R).
        self.assertAlmostEqual(fit.base_m, 2 * R, delta=0.5 * R)
        self.assertAlmostEqual(fit.band_m[0], fit.base_m + 0.2 * (fit.top_m - fit.base_m))

    def test_slot_heap_25_and_35_deg(self):
        x, _, z = syn.heap_particles(H, 25.0, 35.0, R, depth_m=0.02, seed=4)
        xc, h = profile(x, z)
        self.check("slot heap 25/35 deg", repose_angle(xc, h), 25.0, 35.0)

    def test_band_leaves_out_the_rounded_top(self):
        # A heap whose top 15 % is flattened (a plateau): the 20-80 % band ignores it.
        x = np.linspace(-0.2, 0.2, 201)
        h = np.maximum(np.minimum(0.1 - np.tan(np.radians(33.0)) * np.abs(x), 0.085), 0.0)
        fit = repose_angle(x, h)
        self.assertAlmostEqual(fit.angle_deg, 33.0, delta=1e-6)
        self.assertAlmostEqual(fit.top_m, 0.085)

    def test_bad_input(self):
        x = np.linspace(-0.2, 0.2, 41)
        h = np.maximum(0.1 - np.tan(np.radians(30.0)) * np.abs(x), 0.0)
        hn = h.copy()
        hn[5] = np.nan
        with self.assertRaisesRegex(FitInputError, r"h_m\[5\] is nan"):
            repose_angle(x, hn)
        with self.assertRaisesRegex(FitInputError, r"the right flank has 0 profile point"):
            repose_angle(x[x < 0], h[x < 0])
        with self.assertRaisesRegex(FitInputError, r"right slope 0\.25.*is axis_m inside the heap"):
            repose_angle(x, 0.25 * (x + 0.2))  # a ramp, not a heap
        with self.assertRaisesRegex(FitInputError, r"no height"):
            repose_angle(x, np.zeros_like(x))


if __name__ == "__main__":
    unittest.main()
