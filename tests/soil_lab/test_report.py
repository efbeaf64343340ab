"""soil_lab_py.report: each plot is written as a PNG, its title names the soil and the units, and
it shows the fits it was given (Bekker parameters, Janosi K, Mohr-Coulomb c and phi in the
legend, the repose angle)."""

import os
import tempfile
import unittest

import numpy as np

import synthetic as syn
from soil_lab_py import fits, report, repose

SOIL = "DEM loose sand"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def legend_texts(fig):
    return [t.get_text() for t in fig.axes[0].get_legend().get_texts()]


class ReportTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def png(self, name):
        return os.path.join(self.tmp.name, name)

    def assertPlot(self, fig, path, *units):
        with open(path, "rb") as f:
            self.assertEqual(f.read(8), PNG_MAGIC)
        self.assertGreater(os.path.getsize(path), 10_000)
        ax = fig.axes[0]
        self.assertIn(SOIL, ax.get_title())
        for unit in units:
            self.assertIn(unit, ax.get_title())
            self.assertIn(unit, ax.get_xlabel() + ax.get_ylabel())

    def test_pressure_sinkage(self):
        plates = syn.bekker_plates(0.79, 102e3, 5301e3, (0.05, 0.10))
        fit = fits.fit_bekker(plates)
        fig = report.plot_pressure_sinkage(self.png("ps.png"), SOIL, plates, fit)
        self.assertPlot(fig, self.png("ps.png"), "[kPa]", "[mm]")
        texts = legend_texts(fig)
        self.assertTrue(any(f"n = {fit.n:.3f}" in t and "kc =" in t and "kφ =" in t
                            for t in texts), texts)
        self.assertEqual(len(fig.axes[0].get_lines()), 5)  # 2 plates x (data, fit) + the text
        # The fit line of the 50 mm plate ends at the Bekker pressure (kPa) at 30 mm.
        line, = [x for x in fig.axes[0].get_lines() if x.get_label() == "Bekker fit, b = 50 mm"]
        self.assertAlmostEqual(line.get_ydata()[-1],
                               (fit.kc / 0.05 + fit.kphi) * 0.03**fit.n / 1e3, places=6)
        # replicate beds (--plate-replicates): a marker set per plate and bed, one fit line per
        # width, the bed named in the legend
        beds = [(b, z, p, bed) for bed, seed in ((1, 1), (2, 7))
                for b, z, p in syn.bekker_plates(0.79, 102e3, 5301e3, (0.05, 0.10), seed=seed)]
        fig = report.plot_pressure_sinkage(self.png("ps_beds.png"), SOIL, beds, fit)
        labels = [x.get_label() for x in fig.axes[0].get_lines()]
        self.assertEqual(len(labels), 7)   # 4 plates + 2 fit lines + the text
        self.assertIn("plate b = 100 mm (DEM, bed 2)", labels)
        self.assertEqual(sum(x.startswith("Bekker fit, b =") for x in labels), 2)

    def test_shear_curves_and_mohr_coulomb(self):
        j = np.linspace(0.0, 0.05, 80)
        sigma = [5e3, 10e3, 20e3]
        curves = [(s, j, (1e3 + s * np.tan(np.radians(30))) * -np.expm1(-j / 0.006))
                  for s in sigma]
        jf = [fits.fit_janosi(jj, t) for _, jj, t in curves]
        fig = report.plot_shear_curves(self.png("shear.png"), SOIL, curves, jf)
        self.assertPlot(fig, self.png("shear.png"), "[kPa]", "[mm]")
        texts = legend_texts(fig)
        self.assertEqual(sum("K = 6 mm" in t for t in texts), 3, texts)
        self.assertIn("σn = 10 kPa", texts)
        # With the lid's record: a second panel, the vertical displacement in mm.
        dz = [-0.002 * (1 - np.exp(-j / 0.01)) for _ in sigma]
        fig = report.plot_shear_curves(self.png("shear_v.png"), SOIL, curves, jf, dz)
        self.assertPlot(fig, self.png("shear_v.png"), "[kPa]", "[mm]")
        self.assertEqual(len(fig.axes), 2)
        self.assertIn("vertical displacement [mm]", fig.axes[1].get_ylabel())
        self.assertAlmostEqual(fig.axes[1].get_lines()[0].get_ydata()[-1], 1e3 * dz[0][-1])
        with self.assertRaisesRegex(ValueError, "3 curves but 2 lid records"):
            report.plot_shear_curves(self.png("bad.png"), SOIL, curves, jf, dz[:2])

        peak = [fits.peak_and_residual(jj, t) for _, jj, t in curves]
        tp = [p.tau_peak_Pa for p in peak]
        tr = [0.9 * p.tau_residual_Pa for p in peak]
        fp, fr = fits.fit_mohr_coulomb(sigma, tp), fits.fit_mohr_coulomb(sigma, tr)
        fig = report.plot_mohr_coulomb(self.png("mc.png"), SOIL, sigma, tp, fp, sigma, tr, fr)
        self.assertPlot(fig, self.png("mc.png"), "[kPa]")
        texts = legend_texts(fig)
        self.assertTrue(any(t.startswith(f"peak: c = {fp.cohesion_Pa / 1e3:.3g} kPa, "
                                         f"φ = {fp.friction_deg:.1f}°") for t in texts), texts)
        self.assertTrue(any(t.startswith("residual: c = ") for t in texts), texts)
        self.assertAlmostEqual(fp.friction_deg, 30.0, delta=0.1)

    def test_repose(self):
        x, _, z = syn.heap_particles(0.1, 25.0, 35.0, 0.002, depth_m=0.02, n_surface=8000,
                                     n_fill=0)
        xc, h = repose.surface_profile(x, z, 0.002, bins=80)
        fit = repose.repose_angle(xc, h)
        fig = report.plot_repose(self.png("repose.png"), SOIL, xc, h, fit)
        self.assertPlot(fig, self.png("repose.png"), "[mm]")
        self.assertIn(f"angle of repose {fit.angle_deg:.1f}°", fig.axes[0].get_title())
        texts = legend_texts(fig)
        self.assertTrue(any(t.startswith(f"left flank: {fit.left.angle_deg:.1f}°") for t in texts))
        self.assertTrue(any(t.startswith(f"right flank: {fit.right.angle_deg:.1f}°")
                            for t in texts))


if __name__ == "__main__":
    unittest.main()
