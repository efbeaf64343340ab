"""``wheelsim-post curves --results``: the validation-case results.csv on synthetic runs with known
values (slip conventions, means, batch-means SEMs, normal load, cost columns, header)."""

import csv
import math
import os
import subprocess
import unittest

import h5py
import numpy as np

import synthetic as syn
from helpers import TempDirTestCase, run_cli
from test_slip import locked_run
from wheelsim_post.results_table import COLUMNS

#: The columns issue 11 asks for.
REQUIRED = (
    "slip",
    "slip_driving",
    "slip_skid",
    "drawbar_pull_N",
    "drawbar_pull_sem_N",
    "driving_torque_Nm",
    "driving_torque_sem_Nm",
    "sinkage_m",
    "normal_load_N",
    "wall_s",
    "particles",
    "np",
)


def read(path):
    with open(path) as f:
        lines = f.read().splitlines()
    header_at = next(i for i, line in enumerate(lines) if not line.startswith("#"))
    comments = lines[:header_at]
    body = [line for line in lines[header_at:] if not line.startswith("#")]
    return comments, list(csv.DictReader(body))


def window_dp(dp_mean):
    """The drawbar pull samples of the standard run's default window (steps 800-1300)."""
    step = np.arange(syn.WINDOW_STEPS[0], syn.WINDOW_STEPS[1] + 1)
    u = np.sin(2.0 * math.pi * (step - syn.WINDOW_STEPS[0]) * syn.DT / syn.PERIOD)
    return dp_mean + syn.DP_AMPLITUDE * u


def batch_means_sem(x, batches=20):
    """SEM of the mean by batch means, written out: 20 batches of len // 20 samples, the
    earliest len % 20 left out, std (ddof 1) of the batch means / sqrt(20)."""
    m = len(x) // batches
    means = [float(np.mean(x[len(x) - batches * m + b * m:][:m])) for b in range(batches)]
    return float(np.std(means, ddof=1) / math.sqrt(batches))


class ResultsTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.dem = self.path("dem_drive.h5")
        self.skid = self.path("dem_skid.h5")
        self.scm = self.path("scm.h5")
        self.locked = self.path("flat_locked.h5")
        syn.write_rig_run(
            self.dem,
            slip=0.2,
            dp_mean=100.0,
            torque=60.0,
            parameters={"liggghts/np": "2", "liggghts/atoms": 80000, "run/wall_time": 3600.5},
        )
        # driving slip -1 = skid -0.5
        syn.write_rig_run(
            self.skid,
            slip=-1.0,
            dp_mean=-40.0,
            torque=-20.0,
            parameters={"liggghts/np": "4", "liggghts/atoms": 12345, "run/wall_time": 60.0},
        )
        syn.write_rig_run(self.scm, slip=0.5, dp_mean=70.0, parameters={"run/wall_time": 2.5})
        with h5py.File(self.scm, "r+") as f:
            del f["parameters/rig_config"]
            syn.write_parameter(f, "rig_config", syn.rig_config(0.5, terrain="scm"))
        locked_run(self.locked)

    def results(self, *extra):
        out = self.path("results.csv")
        result = run_cli("curves", self.dem, self.skid, self.scm, self.locked, "--results", out,
                         *extra)
        self.assertEqual(result.returncode, 0, result.stderr)
        return read(out), result

    def test_columns_and_rows_in_order_of_signed_slip(self):
        (comments, rows), _ = self.results()
        for column in REQUIRED:
            self.assertIn(column, rows[0])
        self.assertEqual(list(rows[0]), list(COLUMNS))
        self.assertEqual(  # relative to the table's folder (here the runs' own)
            [r["run_file"] for r in rows],
            ["flat_locked.h5", "dem_skid.h5", "dem_drive.h5", "scm.h5"],
        )
        locked, skid, dem, scm = rows
        self.assertEqual(float(locked["slip"]), -1.0)
        self.assertEqual(float(locked["slip_skid"]), -1.0)
        self.assertEqual(locked["slip_driving"], "nan")
        self.assertAlmostEqual(float(skid["slip"]), -0.5, places=9)
        self.assertAlmostEqual(float(skid["slip_driving"]), -1.0, places=9)
        self.assertAlmostEqual(float(skid["slip_skid"]), -0.5, places=9)
        self.assertAlmostEqual(float(dem["slip"]), 0.2, places=9)
        self.assertAlmostEqual(float(dem["slip_driving"]), 0.2, places=9)
        self.assertAlmostEqual(float(dem["slip_skid"]), 0.25, places=9)
        self.assertAlmostEqual(float(scm["slip"]), 0.5, places=9)

    def test_run_files_are_named_relative_to_the_table_folder(self):
        table = self.path(os.path.join("tables", "results.csv"))
        os.makedirs(os.path.dirname(table))
        result = run_cli("curves", self.dem, "--results", table)
        self.assertEqual(result.returncode, 0, result.stderr)
        _, rows = read(table)
        self.assertEqual(rows[0]["run_file"], os.path.join("..", "dem_drive.h5"))

    def test_means_and_batch_means_sems(self):
        (_, rows), _ = self.results()
        _, skid, dem, _ = rows
        self.assertAlmostEqual(float(dem["drawbar_pull_N"]), 100.0, places=6)
        self.assertAlmostEqual(float(skid["drawbar_pull_N"]), -40.0, places=6)
        self.assertAlmostEqual(float(dem["driving_torque_Nm"]), 60.0, places=9)
        self.assertAlmostEqual(float(skid["driving_torque_Nm"]), -20.0, places=9)
        self.assertAlmostEqual(float(dem["traction_force_N"]), 600.0, places=6)
        self.assertAlmostEqual(float(dem["sinkage_m"]), syn.SINKAGE, places=9)
        # the SEM of the batch means of the sine, not its std 20 sqrt(250/501) = 14.1 N
        expected = batch_means_sem(window_dp(100.0))
        sem = float(dem["drawbar_pull_sem_N"])
        print(f"\ndrawbar_pull_sem_N {sem:.6g} (batch means of the window {expected:.6g}); "
              f"std {syn.DP_AMPLITUDE * math.sqrt(syn.SIN2_MEAN):.6g}")
        self.assertAlmostEqual(sem, expected, places=8)
        std = syn.DP_AMPLITUDE * math.sqrt(syn.SIN2_MEAN)
        self.assertLess(sem, 0.25 * std)  # not the signal's std
        self.assertGreater(sem, 2.0 * std / math.sqrt(501))  # nor std/sqrt(N) (correlated)
        self.assertEqual(float(dem["driving_torque_sem_Nm"]), 0.0)  # a constant torque

    def test_normal_load_and_cost_columns(self):
        (_, rows), _ = self.results()
        locked, skid, dem, scm = rows
        self.assertEqual(float(locked["normal_load_N"]), 50.0)
        # DEM runs: wall time, atoms and ranks as recorded
        self.assertEqual((dem["wall_s"], dem["particles"], dem["np"]), ("3600.5", "80000", "2"))
        self.assertEqual((skid["wall_s"], skid["particles"], skid["np"]), ("60", "12345", "4"))
        # SCM: no particles, one process; a run without a wall time: blank
        self.assertEqual((scm["wall_s"], scm["particles"], scm["np"]), ("2.5", "", "1"))
        self.assertEqual(locked["wall_s"], "")
        self.assertEqual(locked["terrain"], "dem")  # write_run's default config: np unknown
        self.assertEqual(locked["np"], "")

    def test_run_git_revision_names_every_writer_in_order(self):
        # a run resumed three times: twice at one revision, once at another
        resumes = {"resume/1/git_revision": "abc", "resume/2/git_revision": "abc",
                   "resume/3/git_revision": "def+dirty"}
        resumes.update({f"resume/{k}/step": 100 * k for k in (1, 2, 3)})
        syn.write_rig_run(self.dem, slip=0.2, dp_mean=100.0, torque=60.0, parameters=resumes)
        (_, rows), _ = self.results()
        revisions = {r["run_file"]: r["run_git_revision"] for r in rows}
        self.assertEqual(revisions["dem_drive.h5"], "none > abc > def+dirty")
        self.assertEqual(revisions["dem_skid.h5"], "none")  # never resumed: the creator's

    def test_header_names_the_git_revision_and_the_command(self):
        (comments, _), result = self.results("--window-fraction", "0.5", "1")
        git = next(c for c in comments if c.startswith("# git: "))
        root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        head = subprocess.run(["git", "-C", root, "rev-parse", "HEAD"], capture_output=True,
                              text=True)
        if head.returncode == 0:
            self.assertTrue(git.startswith("# git: " + head.stdout.strip()), git)
        command = next(c for c in comments if c.startswith("# command: "))
        self.assertIn(f"wheelsim-post curves {self.dem} ", command)
        self.assertIn(f"--results {self.path('results.csv')}", command)
        self.assertIn("--window-fraction 0.5 1", command)
        self.assertTrue(any("from 0.5 to 1 of its duration" in c for c in comments))

    def test_bad_cost_parameter_is_an_error_naming_it(self):
        syn.write_rig_run(self.dem, parameters={"liggghts/np": "two"})
        result = run_cli("curves", self.dem, "--results", self.path("r.csv"))
        self.assertEqual(result.returncode, 2)
        self.assertIn("/parameters/liggghts/np is 'two', expected the number of MPI ranks",
                      result.stderr)
        self.assertFalse(os.path.exists(self.path("r.csv")))


if __name__ == "__main__":
    unittest.main()
