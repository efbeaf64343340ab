"""The checkpoints of a plate or shear run (soil_lab_py.checkpoints; docs/soil-lab.md "Stopping and
resuming"), on synthetic files: which restart is complete, what resuming does to the CSV, the
state and the wall-time record, and when a run starts afresh instead."""

import json
import os
import tempfile
import unittest
from pathlib import Path

from soil_lab_py.checkpoints import Checkpoints

DT = 2.5e-5      # [s] time step of the synthetic run
EVERY = 20       # CSV row interval [steps]
START = 1234     # the run's first step (a bed restart's step: not a multiple of EVERY)
HEADER = "# time_s displacement_m shear_force_N tau_Pa sigma_Pa lid_z_m phase\n"


def row(step):
    """The deck's row of global step `step` (time since the start, then made-up columns)."""
    t = (step - START) * DT
    return f"{t!r} {1e-3 * t} 0.5 100 5000 0.05 2\n"


class CheckpointsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.run = Path(self.tmp.name) / "shear_s5000"
        self.run.mkdir()
        self.csv = self.run / "shear.csv"
        self.bed = Path(self.tmp.name) / "soilbin.restart"
        self.bed.write_text("bed")
        Path(f"{self.bed}.vars").write_text("variable bed_depth equal 0.1\n")

    def tearDown(self):
        self.tmp.cleanup()

    def ck(self, key="k1"):
        return Checkpoints(self.run / "checkpoints", self.csv, DT, key)

    def killed_attempt(self, last_row_step, checkpoint_steps, cut_last_line=False):
        """A first attempt killed with rows up to last_row_step and these restart files."""
        c = self.ck()
        self.assertEqual(c.prepare(self.bed), {}, "no checkpoint yet: a fresh start")
        rows = [row(s) for s in range(1240, last_row_step + 1, EVERY)]
        text = HEADER + "".join(rows)
        if cut_last_line:
            text = text[:-10]  # the kill hit the print of the last row
        self.csv.write_text(text)
        for s in checkpoint_steps:
            (c.dir / f"lab-{START}-{s}.restart").write_text(f"restart {s}")
        return c

    def test_a_checkpoint_without_a_later_row_is_not_complete(self):
        c = self.killed_attempt(last_row_step=4400, checkpoint_steps=[2200, 4400])
        start, step, path = c.newest_complete()
        self.assertEqual((start, step), (START, 2200), "4400 has no row after it: maybe cut short")

    def test_a_cut_last_line_is_not_a_row(self):
        c = self.killed_attempt(last_row_step=4420, checkpoint_steps=[2200, 4400],
                                cut_last_line=True)
        self.assertEqual(c.newest_complete()[1], 2200, "the cut row of step 4420 does not count")

    def test_resuming_cuts_the_csv_back_to_the_checkpoint(self):
        self.killed_attempt(last_row_step=5000, checkpoint_steps=[2200, 4400])
        c = self.ck()
        variables = c.prepare(self.bed, np=2)
        path = c.dir / f"lab-{START}-4400.restart"
        # the attempt's ranks are kept with it (the estimate rescales its pace by them)
        last = json.loads((c.dir / "state.json").read_text())["attempts"][-1]
        self.assertEqual((last["resumed_at_step"], last["np"]), (4400, 2))
        self.assertEqual(variables, {"restart_file": str(path), "start_step": START,
                                     "resume_setup_run": 0})
        self.assertTrue(c.resuming)
        self.assertEqual((c.start_step, c.resumed_step), (START, 4400))
        lines = self.csv.read_text().splitlines(True)
        self.assertEqual(lines[0], HEADER)
        self.assertEqual(lines[1:], [row(s) for s in range(1240, 4401, EVERY)],
                         "rows up to the checkpoint's step, unchanged, and none after it")
        self.assertFalse((c.dir / f"lab-{START}-2200.restart").exists(), "older one removed")
        self.assertEqual(Path(f"{path}.vars").read_text(), "variable bed_depth equal 0.1\n",
                         "resume.in reads the bed's variables beside the restart")

    def test_wall_time_before_the_checkpoint_is_counted(self):
        self.killed_attempt(last_row_step=5000, checkpoint_steps=[4400])
        c = self.ck()
        # the first attempt started 1000 s ago and wrote the checkpoint 125 s later
        state = json.loads((c.dir / "state.json").read_text())
        started = state["attempts"][0]["start_unix"] - 1000.0
        state["attempts"][0]["start_unix"] = started
        (c.dir / "state.json").write_text(json.dumps(state))
        os.utime(c.dir / f"lab-{START}-4400.restart", (started + 125.0, started + 125.0))
        c.prepare(self.bed)
        self.assertAlmostEqual(c.wall_before_s, 125.0, places=3)
        # killed again before its first checkpoint and before its first row: the next attempt
        # resumes from the same file (complete: resumed from already, though the CSV now ends at
        # its step), written by the first attempt, so the wall time before it is the first one's
        c2 = self.ck()
        c2.prepare(self.bed)
        self.assertEqual(c2.resumed_step, 4400)
        self.assertAlmostEqual(c2.wall_before_s, 125.0, places=3)

    def test_other_inputs_start_afresh(self):
        self.killed_attempt(last_row_step=5000, checkpoint_steps=[2200, 4400])
        c = self.ck(key="another")
        self.assertEqual(c.prepare(self.bed), {}, "a checkpoint of other inputs is not taken")
        self.assertFalse(c.resuming)
        self.assertEqual(c.files(), [])
        self.assertFalse(self.csv.exists(), "the old rows are gone")

    def test_no_complete_checkpoint_starts_afresh(self):
        self.killed_attempt(last_row_step=2200, checkpoint_steps=[2200])
        c = self.ck()
        self.assertEqual(c.prepare(self.bed), {})
        self.assertEqual(c.files(), [])

    def test_prune_keeps_the_newest_complete_and_later_ones(self):
        c = self.killed_attempt(last_row_step=6700, checkpoint_steps=[2200, 4400, 6600])
        c.prune()
        self.assertEqual([s for _, s, _ in c.files()], [6600])
        c.clear()
        c = self.killed_attempt(last_row_step=5000, checkpoint_steps=[2200, 4400, 6600])
        c.prune()
        self.assertEqual([s for _, s, _ in c.files()], [4400, 6600],
                         "6600 may still be being written: kept, and 4400 with it")

    def test_clear(self):
        c = self.killed_attempt(last_row_step=5000, checkpoint_steps=[4400])
        c.clear()
        self.assertFalse(c.dir.exists())


if __name__ == "__main__":
    unittest.main()
