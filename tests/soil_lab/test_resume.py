"""soil-lab's resume records (soil_lab_py.runner.Lab): a finished step is skipped only while its
inputs are unchanged, including the files its decks and soil file include in turn (a soil file
that includes a base soil, as dry_sand_coarse.in includes dry_sand.in); and the command each
invocation records for a later resume can be pasted back."""

import json
import shlex
import sys
import tempfile
import unittest
from pathlib import Path
from unittest import mock

from soil_lab_py import cli
from soil_lab_py.runner import Lab


class Resume(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        root = Path(self.tmp.name)
        (root / "build" / "bin").mkdir(parents=True)
        for exe in ("liggghts-wheel", "wheel-mesh"):  # the Lab checks they exist; nothing runs
            (root / "build" / "bin" / exe).write_text("")
        soils = root / "repo" / "inputs" / "soils"
        soils.mkdir(parents=True)
        self.base = soils / "base_sand.in"
        self.base.write_text("variable soil_mur index 0.3\n")
        self.variant = root / "my_sand.in"
        self.variant.write_text("variable soil_size_scale index 2.0\n"
                                "include ${inputs_dir}/soils/base_sand.in\n")
        self.lab = Lab(root / "repo", root / "build", root / "out", quiet=True)
        self.step = root / "out" / "beds" / "plate"
        self.step.mkdir(parents=True)

    def tearDown(self):
        self.tmp.cleanup()

    def key(self):
        return self.lab._key({"bin_length": "0.2"}, files=(self.variant,))

    def test_a_changed_included_file_redoes_the_step(self):
        self.lab._finish(self.step, self.key(), wall_s=1.0)
        self.assertIsNotNone(self.lab._done(self.step, self.key()), "unchanged inputs: skipped")
        done = json.loads((self.step / "done.json").read_text())
        self.assertEqual(list(done["included_sha256"]), [str(self.base)])
        self.base.write_text("variable soil_mur index 0.2\n")  # the variant file is unchanged
        self.assertIsNone(self.lab._done(self.step, self.key()),
                          "the base soil changed: the step must be done again")

    def test_a_changed_step_input_redoes_the_step(self):
        self.lab._finish(self.step, self.key(), wall_s=1.0)
        other = self.lab._key({"bin_length": "0.3"}, files=(self.variant,))
        self.assertIsNone(self.lab._done(self.step, other))

    def test_archive_keeps_and_restores_a_finished_step(self):
        root = Path(self.tmp.name)
        lab = Lab(root / "repo", root / "build", root / "out", quiet=True, archive=root / "arch")
        step = root / "out" / "shear_s5000"
        step.mkdir()
        (step / "shear.csv").write_text("# t tau\n0 1\n")
        lab._finish(step, self.key(), wall_s=1.0)
        lab._keep_step(step, "shear_s5000")
        kept = sorted(f.name for f in (root / "arch" / "shear_s5000").iterdir())
        self.assertEqual(kept, ["done.json", "shear.csv"])
        for f in step.iterdir():  # a new session: the output directory is gone
            f.unlink()
        self.assertIsNone(lab._done(step, self.key()))
        lab._restore_step(step, "shear_s5000")
        self.assertIsNotNone(lab._done(step, self.key()), "the restored step is not finished")
        self.assertEqual((step / "shear.csv").read_text(), "# t tau\n0 1\n")
        # a step of this output directory is not overwritten by the archive
        (step / "done.json").write_text("{}")
        lab._restore_step(step, "shear_s5000")
        self.assertEqual((step / "done.json").read_text(), "{}")
        # with other inputs the restored record does not count
        other = lab._key({"bin_length": "0.3"}, files=(self.variant,))
        (step / "done.json").unlink()
        lab._restore_step(step, "shear_s5000")
        self.assertIsNone(lab._done(step, other))

    def test_a_record_from_before_included_files_is_kept(self):
        inputs, _ = self.key()
        (self.step / "done.json").write_text(json.dumps({"inputs": inputs, "wall_s": 1.0}))
        self.assertIsNotNone(self.lab._done(self.step, self.key()))


class Provenance(unittest.TestCase):
    def test_the_recorded_command_can_be_pasted_back(self):
        # an argument with a space (a bed variable holding two words) must stay one argument
        argv = ["soil-lab", "run", "my soil.in", "--bed-var", "soil_pair_settings=tangential_reduce off"]
        with mock.patch.object(sys, "argv", argv):
            command = cli._provenance(1)["command"]
        self.assertEqual(shlex.split(command), argv)


if __name__ == "__main__":
    unittest.main()
