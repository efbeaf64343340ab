"""soil-lab's analysis of a lab directory (soil_lab_py.analysis) on synthetic plate runs:
the unloading stiffness is taken from the turning point on, whatever the loading's noise; the
SCM file of a soil whose Mohr-Coulomb intercept is negative gets c = 0 and phi through the
origin, and says so."""

import json
import tempfile
import tomllib
import unittest
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from soil_lab_py import analysis, fits

KE_Pa_m = 2.0e7  # the synthetic soil's unloading stiffness


def plate_run(directory, b_m, noisy_peak):
    """A load (Bekker, n = 1.1), unload by 2 mm with slope KE_Pa_m, reload; with noisy_peak a
    pressure spike at 60 % of the loading, above the pressure at the turning point."""
    z1 = np.linspace(0.0, 0.02, 200)
    p1 = (1e4 / b_m + 5e5) * z1 ** 1.1
    if noisy_peak:
        p1[120] = 1.3 * p1[-1]
    z2 = np.linspace(0.02, 0.018, 40)
    p2 = p1[-1] - KE_Pa_m * (0.02 - z2)
    z3 = np.linspace(0.018, 0.03, 100)
    p3 = p2[-1] + (z3 - 0.018) * 3e5
    z, p = np.concatenate([z1, z2, z3]), np.concatenate([p1, p2, p3])
    phase = np.repeat([1, 2, 3], [len(z1), len(z2), len(z3)])
    t = np.arange(len(z)) * 1e-3
    run = Path(directory) / f"plate_b{b_m:g}"
    run.mkdir(parents=True)
    np.savetxt(run / "plate.csv", np.column_stack([t, z, p * b_m * b_m, p, 10 + 0 * z, phase]),
               header="time_s sinkage_m force_N pressure_Pa contacts phase")
    (run / "done.json").write_text(json.dumps({"meta": {"b_m": b_m}, "wall_s": 1.0}))


class Analysis(unittest.TestCase):
    def lab(self, noisy):
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\ndmax_m = 0.004\n')
        plate_run(d, 0.02, noisy)
        plate_run(d, 0.032, noisy)
        return analysis.analyse(d)

    def test_unloading_stiffness_from_the_turning_point(self):
        for noisy in (False, True):
            r = self.lab(noisy)
            self.assertEqual(r.unload_errors, {})
            for b, fit in r.unload.items():
                # a spike in the loading before the turning point must not enter the fit
                self.assertAlmostEqual(fit.Ke_Pa_m / KE_Pa_m, 1.0, delta=0.02, msg=f"b {b}")

    def test_a_plate_without_an_unloading_branch_is_reported_not_fatal(self):
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\ndmax_m = 0.004\n')
        plate_run(d, 0.032, False)
        run = d / "plate_b0.02"
        run.mkdir()
        z = np.linspace(0, 0.02, 50)
        np.savetxt(run / "plate.csv", np.column_stack([z, z, z, 1e6 * z, z, 1 + 0 * z]))
        (run / "done.json").write_text(json.dumps({"meta": {"b_m": 0.02}}))
        r = analysis.analyse(d)
        self.assertIn(0.02, r.unload_errors)
        self.assertIn(0.032, r.unload)

    def test_negative_cohesion_gives_c0_and_phi_through_the_origin(self):
        r = self.lab(False)
        sigma = np.array([5e3, 1e4, 2e4])
        tau = -300.0 + sigma * np.tan(np.radians(32.0))  # a non-cohesive soil's scatter
        r.shears = [{"sigma_Pa": s, "peak": SimpleNamespace(tau_peak_Pa=t),
                     "janosi": SimpleNamespace(K_m=1e-3)} for s, t in zip(sigma, tau)]
        r.mc_peak = fits.fit_mohr_coulomb(sigma, tau)
        self.assertAlmostEqual(r.mc_peak.friction_deg, 32.0, places=6)
        out = Path(tempfile.mkdtemp()) / "scm.toml"
        analysis.write_scm(r, out)
        data = tomllib.loads(out.read_text())
        phi_origin = np.degrees(np.arctan((sigma @ tau) / (sigma @ sigma)))
        self.assertEqual(data["mohr_coulomb"]["cohesion"], 0.0)
        # Written to scm_file.SIGNIFICANT_DIGITS (6) significant digits.
        self.assertEqual(data["mohr_coulomb"]["friction_angle"], float(f"{phi_origin:.6g}"))
        self.assertLess(phi_origin, 32.0)
        src = data["source"]["mohr_coulomb"]["cohesion"]
        self.assertIn("intercept was -300 Pa (< 0: no cohesion), so c = 0", src)


if __name__ == "__main__":
    unittest.main()
