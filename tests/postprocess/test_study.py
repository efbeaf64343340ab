"""``wheelsim-post study``: tables per soil and quantity, rows wheels, columns target slips."""

import csv
import os
import unittest

import synthetic as syn
from helpers import TempDirTestCase, run_cli


def read(path):
    with open(path) as f:
        return list(csv.reader(line for line in f if not line.startswith("#")))


class StudyTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.runs = syn.write_sweep_runs(
            lambda wheel, soil, slip, i: self.path(f"{wheel}_{i}.h5"),
            (
                ("W2", "S1", 0.3, 130.0),
                ("W1", "S1", 0.3, 120.0),
                ("W1", "S1", 0.1, 80.0),
                ("W1", "S/2", 0.1, 60.0),
            ),
        )
        self.out = self.path("study")

    def test_table_layout(self):
        result = run_cli(
            "study",
            *self.runs,
            "--quantity",
            "drawbar_pull,sinkage",
            "--out-dir",
            self.out,
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(
            sorted(os.listdir(self.out)),
            sorted(
                f"{soil}_{q}{kind}.csv"
                for soil in ("S1", "S_2")
                for q in ("drawbar_pull", "sinkage")
                for kind in ("", "_std", "_sem")
            )
            + ["runs.csv", "study.md"],
        )
        table = read(os.path.join(self.out, "S1_drawbar_pull.csv"))
        self.assertEqual(table[0], ["wheel", "0.1", "0.3"])
        self.assertEqual(table[1][0], "W1")
        self.assertAlmostEqual(float(table[1][1]), 80.0, places=6)
        self.assertAlmostEqual(float(table[1][2]), 120.0, places=6)
        self.assertEqual(table[2][:2], ["W2", ""])  # no run of W2 at 0.1
        self.assertAlmostEqual(float(table[2][2]), 130.0, places=6)
        sinkage = read(os.path.join(self.out, "S1_sinkage.csv"))
        self.assertAlmostEqual(float(sinkage[1][1]), syn.SINKAGE, places=9)
        self.assertIn("### soil S1: drawbar pull [N]", result.stdout)
        self.assertIn("| wheel | s = 0.1 | s = 0.3 |", result.stdout)
        # cells: mean ± SEM (batch means); unchecked runs (no /health) are not marked
        self.assertRegex(result.stdout, r"\| W2 \| – \| 130 ± [0-9.]+ \|\n")
        self.assertIn("4 run(s) have no /health group (unchecked", result.stdout)

    def test_two_runs_in_one_cell_are_an_error(self):
        twin = self.path("twin.h5")
        syn.write_rig_run(
            twin, slip=0.3, sweep={"wheel": "W2", "soil": "S1", "slip": "0.3"}
        )
        result = run_cli(
            "study",
            *self.runs,
            twin,
            "--quantity",
            "drawbar_pull",
            "--out-dir",
            self.out,
        )
        self.assertEqual(result.returncode, 2)
        self.assertIn("W2_0.h5' and '", result.stderr)
        self.assertIn(
            "twin.h5' both have soil S1, wheel W2, target slip 0.3", result.stderr
        )


if __name__ == "__main__":
    unittest.main()
