"""soil_lab_py.fits on synthetic data with known parameters plus noise (fixed seeds), and its
errors for bad input. Tolerances (docs/soil-lab.md, "Fits"): Bekker n within 0.02, kc and kphi
within 5 %; unloading slope within 2 %; Mohr-Coulomb c within 5 % of its value and phi within
0.3 deg; Janosi K within 5 %."""

import unittest

import numpy as np

import synthetic as syn
from soil_lab_py import fits
from soil_lab_py.fits import FitInputError


def report(name, **values):
    print(f"\n  {name}: " + ", ".join(f"{k} {v}" for k, v in values.items()), end=" ")


def rel(a, b):
    return abs(a - b) / abs(b)


class BekkerTest(unittest.TestCase):
    # (n, kc [N/m^(n+1)], kphi [N/m^(n+2)]) of LETE sand and upland sandy loam (TERRAMECHANICS.md
    # §6, kN x 1000), plates of b = 50 and 100 mm, 1 % noise.
    SOILS = {"LETE sand": (0.79, 102e3, 5301e3), "upland sandy loam": (1.1, 74.6e3, 2080e3)}

    def test_recovers_known_parameters(self):
        for seed, (soil, (n, kc, kphi)) in enumerate(self.SOILS.items(), start=1):
            with self.subTest(soil=soil):
                plates = syn.bekker_plates(n, kc, kphi, (0.05, 0.10), noise=0.01, seed=seed)
                f = fits.fit_bekker(plates)
                report(soil, n=f"{f.n:.4f} (true {n})", kc_err=f"{rel(f.kc, kc):.2%}",
                       kphi_err=f"{rel(f.kphi, kphi):.2%}", r2=f"{f.r2:.5f}")
                self.assertLess(abs(f.n - n), 0.02)
                self.assertLess(rel(f.kc, kc), 0.05)
                self.assertLess(rel(f.kphi, kphi), 0.05)
                self.assertEqual(f.at_bound, ())
                self.assertEqual(f.n_points, 2 * 59)  # z = 0 left out
                self.assertEqual(f.widths_m, (0.05, 0.10))
                self.assertGreater(f.r2, 0.99)
                # The RMS is the noise level: 1 % of each plate's largest pressure.
                p_max = np.mean([(kc / b + kphi) * 0.03**n for b in (0.05, 0.10)])
                self.assertLess(abs(f.rms_Pa / (0.01 * p_max) - 1.0), 0.3)

    def test_three_plates_exact_data(self):
        plates = syn.bekker_plates(1.3, 20e3, 800e3, (0.04, 0.07, 0.12), noise=0.0)
        f = fits.fit_bekker(plates)
        self.assertAlmostEqual(f.n, 1.3, places=5)
        self.assertLess(rel(f.kc, 20e3), 1e-4)
        self.assertLess(rel(f.kphi, 800e3), 1e-5)
        self.assertLess(f.rms_Pa, 1e-3)

    def test_negative_kc_is_held_at_zero_and_reported(self):
        # Data of a soil whose pressure rises with plate width: kc < 0 free, 0 when bounded.
        plates = syn.bekker_plates(1.0, -20e3, 1000e3, (0.05, 0.1), noise=0.0)
        f = fits.fit_bekker(plates)
        self.assertEqual(f.kc, 0.0)
        self.assertIn("kc", f.at_bound)
        free = fits.fit_bekker(plates, nonnegative=False)
        self.assertLess(rel(free.kc, -20e3), 1e-4)
        self.assertEqual(free.at_bound, ())

    def test_n_above_2_is_held_at_the_bound(self):
        plates = syn.bekker_plates(2.5, 10e3, 1e6, (0.05, 0.1), noise=0.0)
        f = fits.fit_bekker(plates)
        self.assertEqual(f.n, 2.0)
        self.assertIn("n", f.at_bound)

    def test_bad_input(self):
        good = syn.bekker_plates(0.79, 102e3, 5301e3, (0.05, 0.10))
        with self.assertRaisesRegex(FitInputError, r"at least 2 plates .* got 1 plate"):
            fits.fit_bekker(good[:1])
        b, z, p = good[0]
        with self.assertRaisesRegex(FitInputError, r"different widths .* 0\.05, 0\.05 m"):
            fits.fit_bekker([(b, z, p), (b, z, 1.1 * p)])
        zn = z.copy()
        zn[7] = np.nan
        with self.assertRaisesRegex(FitInputError, r"plates\[1\] z\[7\] is nan"):
            fits.fit_bekker([good[0], (0.1, zn, p)])
        with self.assertRaisesRegex(FitInputError, r"plates\[0\] width b must be > 0 m, got -0\.0"):
            fits.fit_bekker([(-0.05, z, p), good[1]])
        with self.assertRaisesRegex(FitInputError, r"same length"):
            fits.fit_bekker([(0.05, z, p[:-1]), good[1]])
        with self.assertRaisesRegex(FitInputError, r"plates\[1\] .* 1 point\(s\) with z > 0"):
            fits.fit_bekker([good[0], (0.1, [0.0, 0.01], [0.0, 1e3])])


class UnloadTest(unittest.TestCase):
    def test_slope_of_the_upper_part(self):
        # Load to z = 30 mm, then unload: linear (Ke = 2e8 Pa/m) in the upper half, softer below
        # (a bent curve the fit must not use), 0.5 % noise.
        rng = np.random.default_rng(5)
        ke, z0, p_max = 2e8, 0.030, 4e5
        z_load = np.linspace(0.0, z0, 50)
        p_load = p_max * (z_load / z0) ** 0.8
        p_un = np.linspace(p_max, 0.0, 60)
        z_un = z0 - (p_max - p_un) / ke
        soft = p_un < 0.5 * p_max
        z_un[soft] -= (0.5 * p_max - p_un[soft]) ** 2 / (ke * p_max)  # bends below half load
        z = np.concatenate([z_load, z_un[1:]])
        p = np.concatenate([p_load, p_un[1:]]) + rng.normal(0.0, 0.005 * p_max, z.size)
        f = fits.fit_unload_stiffness(z, p)
        report("unload", Ke_err=f"{rel(f.Ke_Pa_m, ke):.2%}", points=f.n_points)
        self.assertLess(rel(f.Ke_Pa_m, ke), 0.02)
        self.assertGreaterEqual(f.n_points, 25)
        self.assertAlmostEqual(f.p_from_Pa, 0.5 * f.p_max_Pa)
        # The whole unloading branch (with the soft part) gives a lower, wrong slope: the window
        # matters.
        whole = fits.fit_unload_stiffness(z, p, upper_fraction=1.0)
        self.assertGreater(rel(whole.Ke_Pa_m, ke), 0.05)

    def test_bad_input(self):
        with self.assertRaisesRegex(FitInputError, r"z_m\[1\] is nan"):
            fits.fit_unload_stiffness([0.03, np.nan, 0.029], [3e5, 2e5, 1e5])
        with self.assertRaisesRegex(FitInputError, r"slope dp/dz is -"):
            fits.fit_unload_stiffness([0.028, 0.029, 0.030, 0.031], [4e5, 3.9e5, 3.8e5, 3.7e5])
        with self.assertRaisesRegex(FitInputError, r"at least 3"):
            fits.fit_unload_stiffness([0.03, 0.0299], [4e5, 3e5])


class MohrCoulombTest(unittest.TestCase):
    def test_recovers_c_and_phi(self):
        # c = 2 kPa, phi = 31 deg; 5 normal stresses 5-40 kPa, 3 tests each, noise 50 Pa.
        rng = np.random.default_rng(7)
        c, phi = 2000.0, 31.0
        s = np.repeat([5e3, 10e3, 20e3, 30e3, 40e3], 3)
        t = c + s * np.tan(np.radians(phi)) + rng.normal(0.0, 50.0, s.size)
        f = fits.fit_mohr_coulomb(s, t)
        report("Mohr-Coulomb", c_err=f"{rel(f.cohesion_Pa, c):.2%}",
               phi_err=f"{abs(f.friction_deg - phi):.3f} deg")
        self.assertLess(rel(f.cohesion_Pa, c), 0.05)
        self.assertLess(abs(f.friction_deg - phi), 0.3)
        self.assertEqual((f.n_points, f.n_stresses), (15, 5))
        self.assertFalse(f.cohesion_clipped)
        self.assertTrue(0 < f.cohesion_se_Pa < 100 and 0 < f.friction_se_deg < 0.3)
        self.assertLess(abs(f.rms_Pa - 50.0), 20.0)

    def test_negative_cohesion_reported_or_clipped(self):
        s = np.array([10e3, 20e3, 30e3])
        t = -500.0 + s * np.tan(np.radians(30.0))
        f = fits.fit_mohr_coulomb(s, t)
        self.assertAlmostEqual(f.cohesion_Pa, -500.0, delta=1e-6)
        self.assertFalse(f.cohesion_clipped)
        g = fits.fit_mohr_coulomb(s, t, clip_negative_cohesion=True)
        self.assertEqual(g.cohesion_Pa, 0.0)
        self.assertTrue(g.cohesion_clipped)
        slope = (s @ t) / (s @ s)  # least squares through the origin
        self.assertAlmostEqual(g.friction_deg, np.degrees(np.arctan(slope)), places=9)

    def test_bad_input(self):
        with self.assertRaisesRegex(FitInputError, r"at least 3 different normal stresses, got 2"):
            fits.fit_mohr_coulomb([1e4, 1e4, 2e4, 2e4], [7e3, 7.1e3, 13e3, 13.2e3])
        with self.assertRaisesRegex(FitInputError, r"tau_Pa\[2\] is nan"):
            fits.fit_mohr_coulomb([1e4, 2e4, 3e4], [7e3, 13e3, np.nan])
        with self.assertRaisesRegex(FitInputError, r"sigma_n_Pa\[0\] is inf"):
            fits.fit_mohr_coulomb([np.inf, 2e4, 3e4], [7e3, 13e3, 19e3])
        with self.assertRaisesRegex(FitInputError, r"same length"):
            fits.fit_mohr_coulomb([1e4, 2e4, 3e4], [7e3, 13e3])


class JanosiTest(unittest.TestCase):
    K, TAU_MAX = 0.012, 10e3  # m, Pa

    def curve(self, seed=11, noise=100.0):
        rng = np.random.default_rng(seed)
        j = np.linspace(0.0, 0.06, 120)
        return j, self.TAU_MAX * (1 - np.exp(-j / self.K)) + rng.normal(0.0, noise, j.size)

    def test_recovers_K_and_tau_max(self):
        j, t = self.curve()
        f = fits.fit_janosi(j, t)
        report("Janosi", K_err=f"{rel(f.K_m, self.K):.2%}",
               tau_max_err=f"{rel(f.tau_max_Pa, self.TAU_MAX):.2%}")
        self.assertLess(rel(f.K_m, self.K), 0.05)
        self.assertLess(rel(f.tau_max_Pa, self.TAU_MAX), 0.02)
        self.assertFalse(f.tau_max_fixed or f.at_bound)
        self.assertGreater(f.r2, 0.99)

    def test_fixed_tau_max(self):
        j, t = self.curve(seed=12)
        f = fits.fit_janosi(j, t, tau_max_Pa=self.TAU_MAX)
        report("Janosi fixed tau_max", K_err=f"{rel(f.K_m, self.K):.2%}")
        self.assertLess(rel(f.K_m, self.K), 0.05)
        self.assertEqual(f.tau_max_Pa, self.TAU_MAX)
        self.assertTrue(f.tau_max_fixed)
        # A wrong tau_max gives a different K: the value given is really used.
        g = fits.fit_janosi(j, t, tau_max_Pa=1.3 * self.TAU_MAX)
        self.assertGreater(rel(g.K_m, self.K), 0.1)

    def test_straight_line_is_at_bound(self):
        j = np.linspace(0.0, 0.01, 20)
        self.assertTrue(fits.fit_janosi(j, 1e5 * j).at_bound)

    def test_bad_input(self):
        j, t = self.curve()
        t[3] = np.nan
        with self.assertRaisesRegex(FitInputError, r"tau_Pa\[3\] is nan"):
            fits.fit_janosi(j, t)
        with self.assertRaisesRegex(FitInputError, r"j_m\[0\] is -0\.001: .* >= 0 m"):
            fits.fit_janosi([-0.001, 0.01, 0.02, 0.03], [0.0, 1.0, 2.0, 3.0])
        with self.assertRaisesRegex(FitInputError, r"tau_max_Pa must be a finite number"):
            fits.fit_janosi([0.0, 0.01, 0.02, 0.03], [0.0, 1.0, 2.0, 3.0], tau_max_Pa=np.nan)


class RelaxationTest(unittest.TestCase):
    P_INF, DROP, TAU = 8e3, 3e3, 0.1  # Pa, Pa, s

    def hold(self, tau, seed=21, noise=150.0, duration=1.0):
        rng = np.random.default_rng(seed)
        t = np.linspace(0.0, duration, 500)
        return t, self.P_INF + self.DROP * np.exp(-t / tau) + rng.normal(0.0, noise, t.size)

    def test_recovers_tau_and_the_relaxed_pressure(self):
        t, p = self.hold(self.TAU)
        f = fits.fit_relaxation(t, p)
        report("relaxation", tau_err=f"{rel(f.tau_s, self.TAU):.2%}",
               p_inf_err=f"{rel(f.p_inf_Pa, self.P_INF):.2%}")
        self.assertLess(rel(f.tau_s, self.TAU), 0.05)
        self.assertLess(rel(f.p_inf_Pa, self.P_INF), 0.01)
        self.assertLess(rel(f.p0_Pa, self.P_INF + self.DROP), 0.02)
        self.assertAlmostEqual(f.duration_s, 1.0)
        self.assertTrue(f.converged)
        self.assertFalse(f.at_bound)

    def test_a_hold_too_short_for_its_relaxation_is_not_converged(self):
        # tau 3 s in a 1 s hold: the pressure still falls at the end; p_inf is an extrapolation
        t, p = self.hold(3.0, seed=22)
        self.assertFalse(fits.fit_relaxation(t, p).converged)
        # a straight decline has no time scale within the hold at all
        f = fits.fit_relaxation(t, 1e4 - 2e3 * t)
        self.assertFalse(f.converged)

    def test_bad_input(self):
        with self.assertRaisesRegex(FitInputError, r"at least 4 points, got 3"):
            fits.fit_relaxation([0.0, 0.1, 0.2], [3.0, 2.0, 1.0])
        with self.assertRaisesRegex(FitInputError, r"t_s must start at >= 0 s and increase"):
            fits.fit_relaxation([0.0, 0.2, 0.1, 0.3], [4.0, 3.0, 2.0, 1.0])
        with self.assertRaisesRegex(FitInputError, r"p_Pa\[2\] is nan"):
            fits.fit_relaxation([0.0, 0.1, 0.2, 0.3], [4.0, 3.0, np.nan, 1.0])


class PeakResidualTest(unittest.TestCase):
    def test_peak_and_residual(self):
        # Rises to 12 kPa at j = 10 mm, softens to 9 kPa from 20 mm on, ends at 50 mm.
        j = np.linspace(0.0, 0.05, 501)
        t = np.interp(j, [0.0, 0.01, 0.02, 0.05], [0.0, 12e3, 9e3, 9e3])
        t = t + 50.0 * np.sin(2e3 * j)  # a ripple of zero mean over the window
        f = fits.peak_and_residual(j, t)
        self.assertAlmostEqual(f.j_peak_m, 0.01, delta=1e-3)
        self.assertAlmostEqual(f.tau_peak_Pa, 12e3, delta=60.0)
        self.assertAlmostEqual(f.j_residual_from_m, 0.04, places=12)
        self.assertEqual(f.n_residual_points, 101)
        self.assertAlmostEqual(f.tau_residual_Pa, 9e3, delta=15.0)
        self.assertAlmostEqual(f.tau_residual_std_Pa, 50.0 / np.sqrt(2), delta=5.0)
        g = fits.peak_and_residual(j, t, residual_fraction=0.8)  # reaches into the softening
        self.assertGreater(g.tau_residual_Pa, 9.2e3)

    def test_bad_input(self):
        with self.assertRaisesRegex(FitInputError, r"j_m\[1\] is nan"):
            fits.peak_and_residual([0.0, np.nan, 0.02], [0.0, 1.0, 2.0])
        with self.assertRaisesRegex(FitInputError, r"residual_fraction must be in \(0, 1\]"):
            fits.peak_and_residual([0.0, 0.01, 0.02], [0.0, 1.0, 2.0], residual_fraction=0.0)


if __name__ == "__main__":
    unittest.main()
