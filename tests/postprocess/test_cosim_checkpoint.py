"""cosim_checkpoint: which step a coupled run resumes from (scripts/wheel-cosim --resume and
wheel-sweep --park share it). Known directories: complete pairs, a later half without its partner
(named, the older pair taken), a LIGGGHTS half missing its .wheel or .info, halves that disagree
on the step or the inputs hash, another run's hash, no checkpoint at all; and the command line
wheel-cosim calls."""

import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

from wheelsim_post import cosim_checkpoint as cc

HASH = "a" * 64


def rig_half(d, step, inputs_hash=HASH):
    (d / f"rig-{step}.ckpt").write_text(f"t step {step}\nt inputs_hash {inputs_hash}\n")


def liggghts_half(d, step, inputs_hash=HASH, info_step=None, parts=("", ".wheel", ".info")):
    for p in parts:
        body = (f"step {step if info_step is None else info_step}\ntime 0.25\n"
                f"inputs_hash {inputs_hash}\nranks 2\n") if p == ".info" else "x"
        (d / f"liggghts-{step}.restart{p}").write_text(body)


class Resume(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.d = Path(self.tmp.name) / "checkpoints"
        self.d.mkdir()
        self.warnings = []

    def tearDown(self):
        self.tmp.cleanup()

    def resume(self, inputs_hash=HASH):
        return cc.resume_step(self.d, inputs_hash, warn=self.warnings.append)

    def pair(self, step, **kw):
        rig_half(self.d, step, **{k: v for k, v in kw.items() if k == "inputs_hash"})
        liggghts_half(self.d, step, **kw)

    def test_no_directory_and_empty_directory_mean_no_checkpoint(self):
        self.assertIsNone(cc.resume_step(self.d / "absent", HASH))
        self.assertIsNone(cc.newest(self.d / "absent"))
        self.assertIsNone(self.resume())

    def test_the_newest_complete_pair(self):
        self.pair(300)
        self.pair(600)
        self.assertEqual(self.resume(), 600)
        self.assertEqual(cc.newest(self.d), 600)
        self.assertEqual(self.warnings, [])
        self.assertEqual(cc.info(self.d, 600), {"step": "600", "time": "0.25",
                                                "inputs_hash": HASH, "ranks": "2"})

    def test_a_later_half_without_partner_is_named_and_skipped(self):
        self.pair(300)
        rig_half(self.d, 600)
        self.assertEqual(self.resume(), 300)
        self.assertEqual(len(self.warnings), 1)
        self.assertIn("rig half at step 600 has no partner", self.warnings[0])
        liggghts_half(self.d, 900)
        self.warnings.clear()
        self.assertEqual(self.resume(), 300)
        self.assertTrue(any("LIGGGHTS half at step 900" in w for w in self.warnings))

    def test_a_liggghts_half_needs_its_wheel_and_info_files(self):
        self.pair(300)
        rig_half(self.d, 600)
        liggghts_half(self.d, 600, parts=("", ".wheel"))   # killed before .info
        self.assertEqual(cc.halves(self.d), ({300, 600}, {300}))
        self.assertEqual(cc.newest(self.d), 300)
        self.assertEqual(self.resume(), 300)

    def test_halves_that_never_meet_are_refused(self):
        rig_half(self.d, 300)
        liggghts_half(self.d, 600)
        with self.assertRaisesRegex(cc.CheckpointError, r"rig halves at steps \[300\].*\[600\].*no step has both"):
            self.resume()

    def test_disagreeing_halves_are_refused(self):
        rig_half(self.d, 300)
        liggghts_half(self.d, 300, inputs_hash="b" * 64)
        with self.assertRaisesRegex(cc.CheckpointError, "halves differ in their inputs hash"):
            self.resume()

    def test_an_info_naming_another_step_is_refused(self):
        self.pair(300, info_step=299)
        with self.assertRaisesRegex(cc.CheckpointError, "says step 299"):
            self.resume()

    def test_another_runs_inputs_are_refused(self):
        self.pair(300)
        with self.assertRaisesRegex(cc.CheckpointError, "an input changed"):
            self.resume("c" * 64)

    def test_the_rig_halfs_progress(self):
        # the lines RigSimulation::save_checkpoint writes (wheel_dynamics/src/rig_simulation.cpp)
        body = ("wheelsim-rig-checkpoint 1\nn sim/time 1 1.25\nn sim/test_start 1 {t0}\n"
                "i sim/phase {k}\nt sim/phase_name {name}\nt inputs_hash " + HASH + "\nend\n")
        (self.d / "rig-100.ckpt").write_text(body.format(t0="0.75", k=3, name="test"))
        self.assertEqual(cc.rig_progress(self.d, 100), ("test", 1.25, 0.75))
        (self.d / "rig-100.ckpt").write_text(body.format(t0="nan", k=1, name="settle"))
        self.assertEqual(cc.rig_progress(self.d, 100), ("settle", 1.25, None))
        (self.d / "rig-100.ckpt").write_text("t inputs_hash " + HASH + "\n")
        with self.assertRaisesRegex(KeyError, "rig-100.ckpt: no 'n sim/test_start' line"):
            cc.rig_progress(self.d, 100)

    def test_the_command_wheel_cosim_calls(self):
        def run(*args):
            return subprocess.run([sys.executable, "-m", "wheelsim_post.cosim_checkpoint", *args],
                                  capture_output=True, text=True, timeout=60)
        r = run("resume", str(self.d), HASH)
        self.assertEqual((r.returncode, r.stdout), (0, "\n"))
        self.pair(300)
        rig_half(self.d, 600)
        r = run("resume", str(self.d), HASH)
        self.assertEqual((r.returncode, r.stdout), (0, "300\n"))
        self.assertIn("has no partner", r.stderr)
        r = run("resume", str(self.d), "c" * 64)
        self.assertEqual(r.returncode, 1)
        self.assertIn("an input changed", r.stderr)
        self.assertEqual(r.stdout, "")
        r = run("resume", str(self.d))
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("usage", r.stderr)


if __name__ == "__main__":
    unittest.main()
