"""``wheelsim-post compare``: interpolation, out-of-range points, errors in %."""

import csv
import unittest

import numpy as np

from helpers import TempDirTestCase, is_png, run_cli
from wheelsim_post.cmd_compare import interpolate, percent_errors

CURVES = """# a hand-written curves table
group,slip_mean,drawbar_pull_mean_N,drawbar_pull_std_N
A,0.3,200,5
A,0.1,100,4
A,0.5,220,6
B,0.1,1,1
B,0.5,2,1
"""

# measured: 0.2 -> sim 150 vs 120 (+25 %), 0.4 -> 210 vs 210 (0 %), 0.5 -> 220 vs 200 (+10 %,
# the curve's end is in range), 0.05 and 0.6 outside the simulated range
MEASURED = """# slip [-], drawbar pull [N]
slip,drawbar_pull
0.05,50
0.2,120
0.4,210
0.5,200
0.6,300
"""


class CompareTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.curves, self.measured = self.path("curves.csv"), self.path("measured.csv")
        with open(self.curves, "w") as f:
            f.write(CURVES)
        with open(self.measured, "w") as f:
            f.write(MEASURED)

    def test_errors_per_point_and_mean(self):
        out, png = self.path("cmp.csv"), self.path("cmp.png")
        result = run_cli(
            "compare",
            self.curves,
            self.measured,
            "--quantity",
            "drawbar_pull",
            "--group",
            "A",
            "--csv",
            out,
            "--png",
            png,
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(out) as f:
            lines = f.read().splitlines()
        comments = [line for line in lines if line.startswith("#")]
        rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
        self.assertEqual(
            list(rows[0]),
            [
                "slip",
                "reference_drawbar_pull_N",
                "simulated_drawbar_pull_N",
                "difference_drawbar_pull_N",
                "normalised_difference",
                "error_percent",
                "in_range",
            ],
        )
        self.assertEqual([r["in_range"] for r in rows], ["0", "1", "1", "1", "0"])
        errors = [float(r["error_percent"]) for r in rows]
        self.assertTrue(np.isnan(errors[0]) and np.isnan(errors[4]))
        np.testing.assert_allclose(errors[1:4], [25.0, 0.0, 10.0], atol=1e-9)
        self.assertAlmostEqual(
            float(rows[1]["simulated_drawbar_pull_N"]), 150.0, places=9
        )
        self.assertIn("mean_absolute_error_percent = 11.66666667", comments[-1])
        self.assertIn("mean absolute error: 11.67 % over 3 points", result.stdout)
        self.assertTrue(is_png(png))

    def test_several_series_need_group(self):
        result = run_cli(
            "compare", self.curves, self.measured, "--quantity", "drawbar_pull"
        )
        self.assertEqual(result.returncode, 2)
        self.assertIn("--group:", result.stderr)
        self.assertIn("2 series; choose one of: A; B", result.stderr)

    def test_missing_measured_column(self):
        result = run_cli(
            "compare",
            self.curves,
            self.measured,
            "--quantity",
            "driving_torque",
            "--group",
            "A",
        )
        self.assertEqual(result.returncode, 2)
        self.assertIn("has no column 'driving_torque_mean_Nm'", result.stderr)

    def compare(self, reference_text, *extra):
        reference = self.path("ref.csv")
        with open(reference, "w") as f:
            f.write(reference_text)
        return run_cli("compare", self.curves, reference, "--quantity", "drawbar_pull",
                       "--group", "A", *extra)

    def test_a_binary_reference_names_the_file(self):
        reference = self.path("run.h5")  # an HDF5 file given as the CSV
        with open(reference, "wb") as f:
            f.write(b"\x89HDF\r\n\x1a\n" + bytes(range(256)))
        result = run_cli("compare", self.curves, reference, "--quantity", "drawbar_pull",
                         "--group", "A")
        self.assertOneLineError(result, "REFERENCE.csv: file", "run.h5' is not a UTF-8 text file")

    def test_nan_and_duplicate_reference_slips_name_the_row(self):
        result = self.compare("slip,drawbar_pull\n0.2,120\nnan,50\n")
        self.assertOneLineError(
            result, "REFERENCE.csv: file", "ref.csv', row 2, column 'slip': slip nan"
        )
        result = self.compare("# measured\nslip,drawbar_pull\n0.2,50\n0.4,60\n0.2,120\n")
        self.assertOneLineError(
            result, "ref.csv', rows 1 and 3, column 'slip': slip 0.2 appears twice"
        )
        # the same with a column mapping
        result = self.compare("S,DP\n0.2,50\n0.2,120\n", "--columns", "slip=S,drawbar_pull=DP")
        self.assertOneLineError(result, "rows 1 and 2, column 'S': slip 0.2 appears twice")

    def test_nothing_to_compare_is_an_error(self):
        result = self.compare("slip,drawbar_pull\n0.6,50\n0.7,60\n")
        self.assertOneLineError(
            result, "no slip of", "(0.6 .. 0.7) lies in the simulated slip range 0.1 .. 0.5"
        )
        self.assertNotIn("over 0 points", result.stdout)
        result = self.compare("slip,drawbar_pull\n0.2,nan\n0.3,0\n")
        self.assertOneLineError(result, "no point of", "has an error",
                                "or the reference is 0 and there is no scale")
        # with W every point in range has a normalised difference: no error
        result = self.compare("slip,drawbar_pull\n0.2,0\n0.6,60\n", "--load", "1000")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("mean |sim − ref|/W: 0.15 over 1 points", result.stdout)

    def test_interpolate_and_percent_errors(self):
        sim_slip, sim = np.array([0.0, 1.0]), np.array([0.0, 10.0])
        values, inside = interpolate(
            sim_slip, sim, np.array([-0.1, 0.0, 0.25, 1.0, 1.1])
        )
        np.testing.assert_array_equal(inside, [False, True, True, True, False])
        np.testing.assert_allclose(values[1:4], [0.0, 2.5, 10.0])
        e = percent_errors(np.array([2.0, 3.0, 1.0]), np.array([-4.0, 0.0, 1.0]))
        self.assertAlmostEqual(e[0], 150.0)  # relative to |measured|
        self.assertTrue(np.isnan(e[1]))
        self.assertEqual(e[2], 0.0)


if __name__ == "__main__":
    unittest.main()
