"""soil-lab compare (soil_lab_py.compare): two synthetic labs of Janosi boxes with known answers,
and synthetic Bekker plates (a lab's, an archive's, one run's folder).
τ at a displacement is the curve's value there (mean over ±0.25 mm), '–' past the box's travel;
boxes are matched by target normal stress, a box one lab lacks gives no row; the sample density
appears only where the lab's shear-bed record is, its solid fraction where soil.toml is too; peaks
against a target line c + σ tan φ (--target); the Mohr–Coulomb fit through each source's peaks
against an independent least-squares formula, and φ judged against the tolerance (inside, outside,
undecided within one SE); bad sources, --at, --target and --tolerance values are named; the
command writes its Markdown and PNG."""

import contextlib
import io
import json
import re
import tempfile
import unittest
from pathlib import Path

import numpy as np

import synthetic as syn
from soil_lab_py import cli, compare, plan

K_M = 1e-3  # synthetic.shear_run's Janosi K


def janosi(sigma, c, phi_deg, j_m, scale=1.0):
    return scale * (c + sigma * np.tan(np.radians(phi_deg))) * -np.expm1(-j_m / K_M)


class Compare(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        root = Path(self.tmp.name)
        self.a, self.b = root / "lab_a", root / "boxes_b"
        for sigma in (5e3, 1e4, 2e4):
            syn.shear_run(self.a, sigma, c=1e3, phi_deg=30.0)
        for sigma in (5e3, 1e4):  # an archive-like folder: boxes only, no 20 kPa box
            syn.shear_run(self.b, sigma, c=2e3, phi_deg=25.0)
        bed = self.a / "beds" / "shear"
        bed.mkdir(parents=True)
        # box 0.1 m, lid 0.05 m above the floor: 0.4 kg / (0.01 x 0.05 m^3) = 800 kg/m3
        (bed / "done.json").write_text(json.dumps({"result": {
            "particle_mass": "0.4", "bin_length": "0.1", "bin_width": "0.1", "spheres": "500",
            "bulk_density": "760"}}))
        (self.a / "soil.toml").write_text('name = "a"\ndmax_m = 0.01\ndensity_kg_m3 = 2000.0\n')
        self.sources = [("A", self.a), ("B", self.b)]

    def tearDown(self):
        self.tmp.cleanup()

    def rows(self, text, heading):
        """{source: cells} of the table under `heading` (a box's stress [kPa], or a title)."""
        if not isinstance(heading, str):
            heading = f"Box at {heading:g} kPa"
        block = text.split(f"### {heading}")[1].split("###")[0]
        return {cells[0]: cells[1:] for line in block.splitlines() if line.startswith("| ")
                and not line.startswith("| source")
                for cells in [[c.strip() for c in line.strip("|").split("|")]]}

    def test_tau_at_displacements_and_matching_by_stress(self):
        text = compare.table(compare.load(self.sources), at_mm=(2, 5, 20))
        self.assertEqual(re.findall(r"### Box at (\S+) kPa", text), ["5", "10", "20"])
        at5 = self.rows(text, 5)
        self.assertEqual(set(at5), {"A", "B"})
        self.assertEqual(set(self.rows(text, 20)), {"A"})
        for label, c, phi in (("A", 1e3, 30.0), ("B", 2e3, 25.0)):
            row = at5[label]
            self.assertEqual(float(row[0]), 5.0)  # sigma on the plane [kPa]
            for cell, j_mm in zip(row[1:3], (2, 5)):
                self.assertAlmostEqual(float(cell), janosi(5e3, c, phi, j_mm * 1e-3) / 1e3,
                                       delta=0.01 * janosi(5e3, c, phi, j_mm * 1e-3) / 1e3 + 0.005)
            self.assertEqual(row[3], "–")  # the synthetic boxes travel 10 mm
        self.assertEqual(at5["A"][-2:], ["800", "0.400"])  # 800 / 2000 kg/m3
        self.assertEqual(at5["B"][-2:], ["–", "–"])
        box = compare.boxes(self.a)[5e3]
        self.assertIsNone(compare.tau_at(box, 0.02))
        self.assertAlmostEqual(compare.tau_at(box, 0.005),
                               np.mean(box["tau"][np.abs(box["j"] - 0.005) <= 0.25e-3]))

    def test_peaks_against_a_target_line(self):
        # A's boxes are Janosi curves saturating at 1 kPa + sigma tan 30 deg: on A's own line
        # their peaks lie on it; B's (2 kPa, 25 deg) lie 11.4 % above it at 5 kPa, 1.6 % below at 10
        text = compare.table(compare.load(self.sources), at_mm=(5,), target=(1e3, 30.0))
        self.assertIn("| target line [kPa] (peak against it) |", text)
        for sigma, expected in ((5e3, {"A": 0.0, "B": 11.4}), (1e4, {"A": 0.0, "B": -1.6}),
                                (2e4, {"A": 0.0})):
            rows = self.rows(text, sigma / 1e3)
            self.assertEqual(set(rows), set(expected))
            for label, excess in expected.items():
                line, against = re.fullmatch(r"(\S+) \((\S+) %\)", rows[label][-1]).groups()
                self.assertAlmostEqual(float(line), (1e3 + sigma * np.tan(np.radians(30))) / 1e3,
                                       delta=0.006)
                self.assertAlmostEqual(float(against), excess, delta=0.15, msg=(sigma, label))
        self.assertIn("c 1 kPa, φ 30°", text)
        self.assertNotIn("target line", compare.table(compare.load(self.sources), at_mm=(5,)))
        for bad in ((1e3,), (-1.0, 30.0), (1e3, 0.0), (1e3, 90.0), (float("nan"), 30.0)):
            with self.assertRaisesRegex(plan.LabInputError, "--target: expected C_PA,PHI_DEG"):
                compare.check_target(bad)

    def test_mohr_coulomb_fit_through_the_peaks(self):
        # C: boxes whose plateaus lie off one line (10 kPa box 8 % low), a known least-squares answer
        c_dir = Path(self.tmp.name) / "lab_c"
        for sigma, scale in ((5e3, 1.0), (1e4, 0.92), (2e4, 1.0)):
            syn.shear_run(c_dir, sigma, c=1e3, phi_deg=30.0, tau_scale=scale)
        labs = compare.load(self.sources + [("C", c_dir)])
        rows = self.rows(compare.table(labs, at_mm=(5,), target=(1e3, 31.0)),
                         "Mohr–Coulomb through the peaks")
        self.assertEqual(rows["B"][:2], ["2", "– (needs boxes at 3 stresses)"])
        # A: on its own line, 30 deg and 1 kPa (peaks are the 5 % running mean of a curve at
        # 1 - exp(-10) of its plateau), SE ~0; within 2 deg of a 31 deg target, decided
        phi, se = map(float, re.fullmatch(r"(\S+) \(± (\S+)\)", rows["A"][1]).groups())
        self.assertAlmostEqual(phi, 30.0, delta=0.05)
        self.assertLess(se, 0.05)
        self.assertAlmostEqual(float(rows["A"][2].split()[0]), 1.0, delta=0.02)
        self.assertEqual(rows["A"][-1], "yes")
        # C against the textbook formulas: slope = Sxy/Sxx, SE(slope) = sqrt(SSR/(n-2)/Sxx)
        x = np.array([b["sigma_Pa"] for _, b in sorted(labs[2][1].items())])
        y = np.array([b["peak"].tau_peak_Pa for _, b in sorted(labs[2][1].items())])
        sxx = ((x - x.mean()) ** 2).sum()
        slope = ((x - x.mean()) * (y - y.mean())).sum() / sxx
        ssr = ((y - y.mean() - slope * (x - x.mean())) ** 2).sum()
        se_slope = np.sqrt(ssr / (len(x) - 2) / sxx)
        phi, se = map(float, re.fullmatch(r"(\S+) \(± (\S+)\)", rows["C"][1]).groups())
        self.assertAlmostEqual(phi, np.degrees(np.arctan(slope)), delta=0.006)
        self.assertAlmostEqual(se, np.degrees(se_slope / (1 + slope**2)), delta=0.006)
        self.assertAlmostEqual(float(rows["C"][4].rstrip("°")), phi - 31.0, delta=0.006)
        self.assertNotIn("φ within the tolerance", compare.table(labs, at_mm=(5,)))

    def test_the_fit_takes_every_beds_peaks(self):
        # D: a second bed (--shear-replicates) 10 % stronger at every stress: the per-stress
        # tables show the first bed's boxes, the fit all six peaks (its SE their scatter)
        d_dir = Path(self.tmp.name) / "lab_d"
        for sigma in (5e3, 1e4, 2e4):
            syn.shear_run(d_dir, sigma, c=1e3, phi_deg=30.0)
            syn.shear_run(d_dir, sigma, c=1e3, phi_deg=30.0, tau_scale=1.1, replicate=2)
        labs = compare.load([("D", d_dir)])
        text = compare.table(labs, at_mm=(5,), target=(1e3, 30.0))
        first = self.rows(text, 5)["D"]
        self.assertAlmostEqual(float(first[1]), janosi(5e3, 1e3, 30.0, 0.005) / 1e3, delta=0.01)
        row = self.rows(text, "Mohr–Coulomb through the peaks")["D"]
        self.assertEqual(row[0], "6 (2 beds)")
        pts = [p for _, b in sorted(labs[0][1].items()) for p in b["bed_peaks"]]
        self.assertEqual(sorted(bed for bed, _, _ in pts), [1, 1, 1, 2, 2, 2])
        x, y = np.array([p[1] for p in pts]), np.array([p[2] for p in pts])
        sxx = ((x - x.mean()) ** 2).sum()
        slope = ((x - x.mean()) * (y - y.mean())).sum() / sxx
        se = np.sqrt(((y - y.mean() - slope * (x - x.mean())) ** 2).sum() / (len(x) - 2) / sxx)
        phi, phi_se = map(float, re.fullmatch(r"(\S+) \(± (\S+)\)", row[1]).groups())
        self.assertAlmostEqual(phi, np.degrees(np.arctan(slope)), delta=0.006)
        self.assertAlmostEqual(phi_se, np.degrees(se / (1 + slope**2)), delta=0.006)
        self.assertGreater(phi_se, 0.5)  # the beds' 10 % difference, not one bed's ~0

    def test_verdict_against_the_tolerance(self):
        for dphi, se, expected in ((1.0, 0.5, "yes"), (-1.8, 0.5, "yes (undecided"),
                                   (3.0, 0.5, "no"), (2.85, 4.04, "no (undecided"),
                                   (-2.3, 0.5, "no (undecided"), (3.0, float("nan"), "no")):
            text = compare.verdict(dphi, se, 2.0)
            self.assertTrue(text.startswith(expected), (dphi, se, text))
            if "(" not in expected:
                self.assertNotIn("undecided", text)
        self.assertEqual(compare.verdict(2.5, 0.1, 3.0), "yes")

    def test_bad_sources_are_named(self):
        for text, msg in (("lab_a", "expected LABEL=DIR"), ("=x", "expected LABEL=DIR"),
                          (f"A={self.a}/absent", "is not a directory")):
            with self.assertRaisesRegex(plan.LabInputError, msg):
                compare.parse_source(text)
        empty = Path(self.tmp.name) / "empty"
        empty.mkdir()
        with self.assertRaisesRegex(plan.LabInputError, "no finished shear box"):
            compare.boxes(empty)

    def test_plates_by_width_and_depth_band(self):
        # Lab A's two plates (Bekker n 1.1, kc 1e4, kphi 5e5); an archive folder B with only the
        # 32 mm plate, 20 % stiffer; A's 32 mm plate at half the step as one run's folder, 10 %
        # stiffer. Matched by width; the pressure in A's five depth bands; the end of loading
        # against A: +20 % and +10 %; the run's step; A's Bekker fit recovered, B none (one width).
        root = Path(self.tmp.name)
        for b in (0.02, 0.032):
            syn.plate_run(self.a, b)
        syn.plate_run(root / "plates_b", 0.032, scale=1.2)
        syn.plate_run(self.a, 0.032, scale=1.1, name="plate_b0.032_halfdt", dt_s=5e-6,
                      meta={"dt_factor": 0.5, "half_dt_of": "plate_b0.032"})
        sources = [("A", self.a), ("B", root / "plates_b"),
                   ("A_halfdt", self.a / "plate_b0.032_halfdt")]
        box_labs, plate_labs = compare.load_all(sources)
        self.assertEqual([sorted(ps) for _, ps in plate_labs], [[0.02, 0.032], [0.032], [0.032]])
        self.assertEqual([sorted(bs) for _, bs in box_labs], [[5e3, 1e4, 2e4], [], []])
        text = compare.plate_table(plate_labs)
        rows = self.rows(text, "Plate b 32 mm")
        self.assertEqual(sorted(rows), ["A", "A_halfdt", "B"])
        # the last band: z in [16, 20] mm of the 20 mm loading; the mean of the loading samples
        z = np.linspace(0.0, 0.02, 200)
        last = (1e4 / 0.032 + 5e5) * z[z >= 0.016] ** 1.1
        self.assertAlmostEqual(float(rows["A"][4]), last.mean() / 1e3, places=2)
        self.assertAlmostEqual(float(rows["B"][4]), 1.2 * last.mean() / 1e3, places=2)
        self.assertEqual([rows[k][5] for k in ("A", "B", "A_halfdt")],
                         ["+0.0 %", "+20.0 %", "+10.0 %"])
        self.assertEqual((rows["A"][6], rows["A_halfdt"][6]), ("1e-05", "5e-06"))
        self.assertIn("| p at 2 mm [kPa] | p at 6 mm [kPa] |", text)
        fits_rows = self.rows(text, "Bekker fits")
        n, kc, kphi = (float(x) for x in fits_rows["A"][:3])
        self.assertAlmostEqual(n, 1.1, places=3)
        self.assertAlmostEqual(kc, 10.0, delta=0.1)
        self.assertAlmostEqual(kphi, 500.0, delta=5)
        self.assertEqual(fits_rows["B"][0], "– (needs plates of 2 widths)")
        # a source with neither a box nor a plate, and a run's folder without its record
        empty = root / "empty"
        empty.mkdir()
        with self.assertRaisesRegex(plan.LabInputError, r"E=.*empty: no finished shear box .*nor "
                                                        r"plate"):
            compare.load_all([("E", empty)])
        (self.a / "plate_b0.032_halfdt" / "done.json").unlink()
        with self.assertRaisesRegex(plan.LabInputError, "a plate's folder without its done.json"):
            compare.plates(self.a / "plate_b0.032_halfdt")
        # the command: a plates-only source beside a lab; the PNG has a panel per stress and
        # per plate width
        png = root / "plates.png"
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            rc = cli.main(["compare", f"A={self.a}", f"B={root / 'plates_b'}", "--png", str(png)])
        self.assertEqual(rc, 0)
        self.assertIn("### Box at 10 kPa", out.getvalue())
        self.assertIn("### Plate b 20 mm", out.getvalue())
        self.assertIn("B", self.rows(out.getvalue(), "Plate b 32 mm"))
        self.assertNotIn("B", self.rows(out.getvalue(), "Box at 10 kPa"))
        self.assertGreater(png.stat().st_size, 10000)

    def test_the_command(self):
        md, png = Path(self.tmp.name) / "cmp.md", Path(self.tmp.name) / "cmp.png"
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            rc = cli.main(["compare", f"A={self.a}", f"B={self.b}", "--at", "5,8",
                           "--target", "1000,30", "--md", str(md), "--png", str(png)])
        self.assertEqual(rc, 0)
        self.assertIn("| τ at 5 mm | τ at 8 mm |", md.read_text())
        self.assertIn("c 1 kPa, φ 30°", md.read_text())
        self.assertIn("Tolerance ±2° on φ", md.read_text())
        self.assertTrue(out.getvalue().startswith(md.read_text()))
        self.assertGreater(png.stat().st_size, 10000)
        for args, msg in ((["--at", "0,5"], "--at: expected shear displacements > 0"),
                          (["--at", "x"], "--at: expected"),
                          (["--target", "3300"], "--target: expected C_PA,PHI_DEG"),
                          (["--target", "a,b"], "--target: expected C_PA,PHI_DEG"),
                          (["--target", "1000,30", "--tolerance", "0"],
                           "--tolerance: expected a friction angle tolerance in"),
                          (["--md", str(Path(self.tmp.name) / "no" / "x.md")], "--md .*cannot write")):
            err = io.StringIO()
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                rc = cli.main(["compare", f"A={self.a}", *args])
            self.assertEqual(rc, 2, args)
            self.assertRegex(err.getvalue(), msg)
            self.assertEqual(len(err.getvalue().strip().splitlines()), 1)


if __name__ == "__main__":
    unittest.main()
