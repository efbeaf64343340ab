"""``wheelsim-post series``: the step-joined CSV and the PNG."""

import csv
import unittest

import h5py

import synthetic
from helpers import TempDirTestCase, is_png, run_cli


class SeriesTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.run_path = self.path("run.h5")
        with h5py.File(self.run_path, "w") as f:
            synthetic.write_header(f)
            synthetic.write_observable(
                f, "phase", [0, 1, 2, 3], [0, 0.1, 0.2, 0.3], [0, 1, 2, 3], "1"
            )
            synthetic.write_observable(
                f, "drawbar_pull", [0, 1, 2, 3], [0, 0.1, 0.2, 0.3], [1, 2, 3, 4], "N"
            )
            # half the cadence, plus a torn row
            synthetic.write_observable(
                f,
                "sinkage",
                [0, 2],
                [0, 0.2],
                [0.01, 0.03],
                "m",
                crashed_rows=([0.3], [9.0]),
            )
            synthetic.write_observable(
                f, "wheel/position", [1, 3], [0.1, 0.3], [[1, 2, 3], [4, 5, 6]], "m"
            )

    def test_csv_outer_join_on_step(self):
        out = self.path("series.csv")
        result = run_cli(
            "series",
            self.run_path,
            "--observables",
            "drawbar_pull,sinkage,wheel/position",
            "--csv",
            out,
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(out) as f:
            rows = list(csv.reader(line for line in f if not line.startswith("#")))
        self.assertEqual(
            rows[0],
            [
                "step",
                "time_s",
                "drawbar_pull [N]",
                "sinkage [m]",
                "wheel/position_x [m]",
                "wheel/position_y [m]",
                "wheel/position_z [m]",
                "phase [1]",
            ],
        )
        self.assertEqual(len(rows), 5)  # steps 0..3; the step -1 row is dropped
        self.assertEqual(rows[2], ["1", "0.1", "2", "", "1", "2", "3", "1"])
        self.assertEqual(rows[3], ["2", "0.2", "3", "0.03", "", "", "", "2"])

    def test_png_with_default_observables(self):
        png = self.path("series.png")
        result = run_cli("series", self.run_path, "--png", png)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(is_png(png))

    def test_unknown_observable_is_named(self):
        result = run_cli(
            "series",
            self.run_path,
            "--observables",
            "torque",
            "--png",
            self.path("x.png"),
        )
        self.assertEqual(result.returncode, 2)
        self.assertIn("has no observable 'torque'", result.stderr)
        self.assertIn("drawbar_pull", result.stderr)  # lists what is available

    def test_an_observable_of_strings_is_a_one_line_error(self):
        with h5py.File(self.run_path, "a") as f:
            group = f["observables/drawbar_pull"]
            del group["value"]
            group.create_dataset("value", data=["a", "b", "c", "d"], dtype=synthetic.STRING)
        result = run_cli("series", self.run_path, "--csv", self.path("x.csv"))
        self.assertOneLineError(
            result, "run.h5': observable 'drawbar_pull'", "holds strings, expected numbers"
        )


if __name__ == "__main__":
    unittest.main()
