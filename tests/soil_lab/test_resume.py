"""soil-lab's resume records (soil_lab_py.runner.Lab): a finished step is skipped only while its
inputs are unchanged, including the files its decks and soil file include in turn (a soil file
that includes a base soil, as dry_sand_coarse.in includes dry_sand.in); and the command each
invocation records for a later resume can be pasted back."""

import json
import shlex
import shutil
import sys
import tempfile
import unittest
from pathlib import Path
from unittest import mock

from soil_lab_py import cli, runner
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
        self.lab = Lab(root / "repo", root / "build", root / "out", quiet=True, bed_hold_s=0)
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
        lab = Lab(root / "repo", root / "build", root / "out", quiet=True, archive=root / "arch",
                  bed_hold_s=0)
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
        (self.step / "done.json").write_text(json.dumps({"inputs": self.key().inputs,
                                                         "wall_s": 1.0}))
        self.assertIsNotNone(self.lab._done(self.step, self.key()))


    def test_the_record_says_what_changed(self):
        self.lab._finish(self.step, self.key(), wall_s=1.0)
        self.assertEqual(Lab.changed_inputs(self.step, self.key()), [])
        other = self.lab._key({"bin_length": "0.3"}, files=(self.variant,))
        self.assertEqual(Lab.changed_inputs(self.step, other), ["settings"])
        self.base.write_text("variable soil_mur index 0.2\n")
        self.assertEqual(Lab.changed_inputs(self.step, self.key()), [str(self.base)])
        self.variant.write_text("variable soil_size_scale index 3.0\n"
                                "include ${inputs_dir}/soils/base_sand.in\n")
        self.assertEqual(Lab.changed_inputs(self.step, self.key()),
                         [str(self.variant), str(self.base)])


class LabWithBed(unittest.TestCase):
    """A Lab whose LIGGGHTS runs (a bed, a repose-like test run) are faked."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name)
        (self.root / "build" / "bin").mkdir(parents=True)
        for exe in ("liggghts-wheel", "wheel-mesh"):
            (self.root / "build" / "bin" / exe).write_text("")
        (self.root / "repo" / "inputs").mkdir(parents=True)
        (self.root / "repo" / "inputs" / "in.soilbin").write_text("# the bed deck\n")
        self.soil = self.root / "sand.in"
        self.soil.write_text("variable soil_mur index 0.3\n")
        self.lab = Lab(self.root / "repo", self.root / "build", self.root / "out", quiet=True,
                       archive=self.root / "arch", bed_hold_s=0)  # no bed-hold run to fake

        self.messages = []
        self.lab.say = self.messages.append

    def tearDown(self):
        self.tmp.cleanup()

    def prepare_bed(self, restart_bytes, how="bed"):
        """A bed 'prepared' by a fake LIGGGHTS that writes `restart_bytes` (the same recipe) and
        its .vars, through Lab.bed (or Lab.plan_bed: how="plan_bed"); self.pours counts the
        preparations."""
        beds = self.root / "out" / "beds" / "b"
        for f in beds.glob("*"):
            if f.is_file():
                f.unlink()
        restart = beds / "bed.restart"

        def fake_liggghts(deck, variables, log, cwd, while_running=None, np=None):
            self.bed_ranks = np or self.lab.np  # the ranks the bed was poured on
            self.pours = getattr(self, "pours", 0) + 1
            restart.write_bytes(restart_bytes)
            Path(f"{restart}.vars").write_text("variable bed_depth equal 0.1\n")
            return f"soilbin: restart = {restart}\nsoilbin: spheres = 10\n"
        self.bed_spec = mock.Mock(length_m=0.2, width_m=0.2, fill_height_m=0.1, extra_vars={})
        self.bed_spec.name = "b"
        self.fake_bed_liggghts = fake_liggghts
        with mock.patch.object(self.lab, "_liggghts", side_effect=fake_liggghts):
            return getattr(self.lab, how)(mock.Mock(file=str(self.soil)), self.bed_spec)

    def run_on(self, bed, name="repose"):
        """Lab.run of a repose-like run with the LIGGGHTS call faked (a bed poured meanwhile by
        the bed's fake); True if it ran."""
        ran = []

        def fake_liggghts(deck, variables, log, cwd, while_running=None, np=None):
            if Path(deck).name == "in.soilbin":
                return self.fake_bed_liggghts(deck, variables, log, cwd, while_running, np)
            self.run_ranks = np or self.lab.np  # the ranks the test ran on
            ran.append(deck)
            return "Loop time of 1.0 on 1 procs for 100 steps with 10 atoms\n"
        run = mock.Mock(test="repose", deck="in.lab_repose", meshes={}, variables={"x": "1"},
                        meta={})
        run.name = name
        soil = mock.Mock(file=str(self.soil), dt_s=1e-5)
        with mock.patch.object(self.lab, "_liggghts", side_effect=fake_liggghts):
            self.lab.run(soil, run, bed)
        return bool(ran)


class BedIdentity(LabWithBed):
    """A test run names its bed by the bed's recipe, not by the restart's bytes: a multisphere
    bed's restart holds memory addresses (fix multisphere), so preparing the same recipe again
    writes another file, and an archived run must still count (docs/soil-lab.md)."""

    def test_an_archived_run_counts_on_a_bed_of_the_same_recipe(self):
        first = self.prepare_bed(b"bodies at 0x7f5ddb5f1ce0")
        self.assertTrue(self.run_on(first))
        done = json.loads((self.root / "out" / "repose" / "done.json").read_text())
        self.assertEqual(done["bed_restart_sha256"], runner._sha256(first.restart))
        shutil.rmtree(self.root / "out")  # a new machine: only the archive is left
        again = self.prepare_bed(b"bodies at 0x7f0a01234560")  # same recipe, other bytes
        self.assertEqual(again.recipe, first.recipe)
        self.assertFalse(self.run_on(again), "the archived run was run again")
        self.assertTrue(any("another preparation of the same bed recipe" in m
                            for m in self.messages), self.messages)

    def test_a_bed_of_another_recipe_runs_again_and_says_why(self):
        first = self.prepare_bed(b"bed")
        self.assertTrue(self.run_on(first))
        shutil.rmtree(self.root / "out")
        self.soil.write_text("variable soil_mur index 0.2\n")  # another recipe
        other = self.prepare_bed(b"bed")
        self.assertNotEqual(other.recipe, first.recipe)
        self.assertTrue(self.run_on(other))
        self.assertTrue(any("does not match" in m and f"changed: {self.soil}, bed recipe" in m
                            for m in self.messages), self.messages)


    def test_a_lab_resumed_on_more_ranks_keeps_its_runs_with_bed_np(self):
        # --np 2 --bed-np 1 pours the bed as before and the archived run is kept; --np 2 alone
        # pours it on two ranks: another recipe, the run goes again (docs/soil-lab.md "Resuming
        # on more ranks")
        first = self.prepare_bed(b"bed")
        self.assertEqual(self.bed_ranks, 1)
        self.assertTrue(self.run_on(first))
        for bed_np, kept in ((1, True), (None, False)):  # (the second re-archives the run)
            shutil.rmtree(self.root / "out")  # a new machine
            self.lab.np, self.lab.bed_np = 2, bed_np or 2
            self.messages.clear()
            again = self.prepare_bed(b"bed")
            self.assertEqual(self.bed_ranks, bed_np or 2)
            self.assertEqual(again.recipe == first.recipe, kept)
            self.assertEqual(self.run_on(again), not kept, f"--bed-np {bed_np}")
            if not kept:
                self.assertEqual(self.run_ranks, 2)
                self.assertTrue(any("changed: bed recipe" in m for m in self.messages),
                                self.messages)


class LazyBeds(LabWithBed):
    """A lab on a new machine pours a bed only when a run must start from it: the archive keeps
    each bed's record (done.json, the hold record, the restart's .vars), which the runs' keys and
    the report need (docs/soil-lab.md "Beds poured only when a run needs them")."""

    def new_machine(self):
        shutil.rmtree(self.root / "out")
        self.pours = 0
        return self.prepare_bed(b"bed again", how="plan_bed")

    def test_finished_runs_need_no_bed(self):
        first = self.prepare_bed(b"bed")
        kept = self.root / "arch" / "beds" / "b"
        self.assertEqual(sorted(f.name for f in kept.iterdir()), ["done.json", "restart.vars"])
        self.assertEqual(json.loads((kept / "done.json").read_text())["restart_sha256"],
                         first.restart_sha256)
        self.assertTrue(self.run_on(first))
        lazy = self.new_machine()
        self.assertIsInstance(lazy, runner.LazyBed)
        self.assertEqual((self.pours, lazy.recipe, lazy.restart, lazy.restart_sha256),
                         (0, first.recipe, first.restart, first.restart_sha256))
        self.assertFalse(self.run_on(lazy), "the archived run ran again")
        self.assertEqual(self.pours, 0, "the bed was poured for a finished run")
        # its record is here for the report, the restart is not
        self.assertTrue((self.root / "out" / "beds" / "b" / "done.json").is_file())
        self.assertFalse(Path(first.restart).exists())
        self.assertTrue(any("poured only if a run must start from it" in m
                            for m in self.messages), self.messages)

    def test_a_run_that_must_start_pours_it_once(self):
        first = self.prepare_bed(b"bed")
        self.assertTrue(self.run_on(first))
        lazy = self.new_machine()
        self.assertTrue(self.run_on(lazy, name="repose_2"), "a new run did not run")
        self.assertEqual(self.pours, 1)
        self.assertEqual(Path(first.restart).read_bytes(), b"bed again")
        self.assertTrue(self.run_on(lazy, name="repose_3"))
        self.assertEqual(self.pours, 1, "poured twice")
        # the record of the new preparation replaced the restored one (and is archived)
        done = json.loads((self.root / "arch" / "beds" / "b" / "done.json").read_text())
        self.assertEqual(done["restart_sha256"], runner._sha256(first.restart))
        # the next invocation finds the bed prepared here
        with mock.patch.object(self.lab, "_liggghts", side_effect=AssertionError("LIGGGHTS")):
            again = self.lab.plan_bed(mock.Mock(file=str(self.soil)), self.bed_spec)
        self.assertIsInstance(again, runner.Bed)

    def test_a_stale_archived_record_is_not_taken(self):
        self.prepare_bed(b"bed")
        shutil.rmtree(self.root / "out")
        self.soil.write_text("variable soil_mur index 0.2\n")  # another recipe
        self.pours = 0
        bed = self.prepare_bed(b"other", how="plan_bed")
        self.assertIsInstance(bed, runner.Bed)
        self.assertEqual(self.pours, 1)
        self.assertTrue(any("archived record does not match" in m for m in self.messages))

    def test_a_resuming_run_needs_only_the_vars(self):
        first = self.prepare_bed(b"bed")
        lazy = self.new_machine()
        self.assertTrue(Path(f"{first.restart}.vars").is_file(), "the .vars restored")
        # a plate with a checkpoint of these inputs resumes: no bed; without one it pours it
        run = mock.Mock(test="plate", deck="in.lab_plate", meshes={}, variables={}, meta={})
        run.name = "plate_b0.1"
        soil = mock.Mock(file=str(self.soil), dt_s=1e-5)
        for resumable, pours in ((True, 0), (False, 1)):
            def prepare(ckpt, restart, np=None):
                self.prepared_from = restart
                return {}
            with mock.patch.object(runner.Checkpoints, "resumable", return_value=resumable), \
                    mock.patch.object(runner.Checkpoints, "prepare", prepare), \
                    mock.patch.object(self.lab, "_liggghts", side_effect=(
                        lambda deck, *a, **k: self.fake_bed_liggghts(deck, *a, **k)
                        if Path(deck).name == "in.soilbin" else "")), \
                    mock.patch.object(runner, "run_length", return_value=""), \
                    mock.patch.object(runner, "RunProgress"):
                self.lab.run(soil, run, lazy)
            self.assertEqual((self.pours, self.prepared_from), (pours, first.restart))
            shutil.rmtree(self.root / "out" / "plate_b0.1")
            shutil.rmtree(self.root / "arch" / "plate_b0.1", ignore_errors=True)


class ResumedEta(LabWithBed):
    """The lab's ETA counts a resumed run less the share its checkpoint holds (until 2026-12-07
    a plate resumed with 42 % of its steps done was announced at a whole run's cost: "~104 min
    left", where the same pace gives ~60)."""

    def test_lab_eta(self):
        self.assertEqual(runner.lab_eta([], 3), "")
        self.assertEqual(runner.lab_eta([600.0, 1200.0], 2.25), ", ~33.8 min left")

    def test_a_resumed_run_announces_what_is_left_of_it(self):
        first = self.prepare_bed(b"bed")
        variables = {"plate_speed": "0.02", "gap": "0.005", "depth1": "0.04", "unload": "0.01",
                     "depth2": "0.06"}   # 4.25 s: 425 000 steps at 1e-5 s
        run = mock.Mock(test="plate", deck="in.lab_plate", meshes={}, variables=variables,
                        meta={})
        run.name = "plate_b0.1"
        soil = mock.Mock(file=str(self.soil), dt_s=1e-5)

        def prepare(ckpt, restart, np=None):
            ckpt.start_step, ckpt.resumed_step = 1000, 1000 + 318750   # 75 % done
            return {}
        shares = []

        def prefix(done=0.0):
            shares.append(done)
            return f"[2/2{runner.lab_eta([600.0], 1 - done)}] "
        with mock.patch.object(runner.Checkpoints, "resumable", return_value=True), \
                mock.patch.object(runner.Checkpoints, "prepare", prepare), \
                mock.patch.object(self.lab, "_liggghts", return_value=""), \
                mock.patch.object(runner, "RunProgress"):
            self.lab.run(soil, run, first, progress=prefix)
        self.assertAlmostEqual(shares[-1], 0.75)
        self.assertIn("[2/2, ~2.5 min left] plate_b0.1: resuming from its checkpoint at step "
                      "319750 (318750 of 425000 steps done, 75 %)", self.messages)


class AcceptChange(LabWithBed):
    """soil-lab run --accept-change FILE --reason TEXT: a finished bed and test run whose records
    differ from the lab's inputs only by an included file (the variant's base soil) are kept, their
    records updated and annotated, the archive's too; another change still re-runs them."""

    def setUp(self):
        super().setUp()
        soils = self.root / "repo" / "inputs" / "soils"
        soils.mkdir()
        self.base = soils / "base_sand.in"
        self.base.write_text("variable soil_rho equal 2147.0\n")
        self.soil.write_text("variable soil_rho index 1836.0\n"
                             "include ${inputs_dir}/soils/base_sand.in\n")

    def accepting(self, *files):
        self.lab.accept_files = {str(Path(f).resolve()) for f in files}
        self.lab.accept_reason = "equal -> index, same value"

    def test_an_accepted_edit_keeps_the_bed_and_the_run(self):
        first = self.prepare_bed(b"bed")
        self.assertTrue(self.run_on(first))
        old = runner._sha256(self.base)
        self.base.write_text("variable soil_rho index 2147.0\n")  # the value unchanged
        self.accepting(self.base)
        again = self.prepare_bed_if_needed()
        self.assertIsNone(again["prepared"], "the bed was prepared again")
        self.assertFalse(self.run_on(again["bed"]), "the test run was run again")
        for record in (self.root / "out" / "beds" / "b" / "done.json",
                       self.root / "out" / "repose" / "done.json",
                       self.root / "arch" / "repose" / "done.json"):
            done = json.loads(record.read_text())
            self.assertEqual(done["included_sha256"][str(self.base)], runner._sha256(self.base))
            entry, = done["accepted_changes"]
            self.assertEqual((entry["file"], entry["old_sha256"], entry["new_sha256"],
                              entry["reason"]),
                             (str(self.base), old, runner._sha256(self.base),
                              "equal -> index, same value"))
        self.assertEqual(len(self.lab.accepted), 2, self.lab.accepted)
        # kept once: the next lab finds the records valid as they are
        self.lab.accepted.clear()
        self.assertFalse(self.run_on(self.prepare_bed_if_needed()["bed"]))
        self.assertEqual(self.lab.accepted, {})

    def test_without_accepting_or_with_another_change_they_run_again(self):
        first = self.prepare_bed(b"bed")
        self.assertTrue(self.run_on(first))
        self.base.write_text("variable soil_rho index 2147.0\n")
        self.assertIsNotNone(self.prepare_bed_if_needed()["prepared"], "nothing accepted")
        self.setUp_records_again()
        # the soil file changed too: not only the accepted file, so the bed is prepared again
        self.soil.write_text("variable soil_rho index 1800.0\n"
                             "include ${inputs_dir}/soils/base_sand.in\n")
        self.accepting(self.base)
        self.assertIsNotNone(self.prepare_bed_if_needed()["prepared"])
        # and a file that was not edited accepts nothing
        self.assertEqual(self.lab.accepted, {})

    def setUp_records_again(self):
        """Fresh records made with the base soil as it is now."""
        shutil.rmtree(self.root / "out")
        shutil.rmtree(self.root / "arch")
        self.base.write_text("variable soil_rho equal 2147.0\n")
        self.assertTrue(self.run_on(self.prepare_bed(b"bed")))
        self.base.write_text("variable soil_rho index 2147.0\n")

    def prepare_bed_if_needed(self):
        """Lab.bed with a fake LIGGGHTS that records whether it prepared the bed."""
        restart = self.root / "out" / "beds" / "b" / "bed.restart"
        prepared = []

        def fake_liggghts(deck, variables, log, cwd, while_running=None, np=None):
            prepared.append(deck)
            restart.write_bytes(b"bed")
            return f"soilbin: restart = {restart}\nsoilbin: spheres = 10\n"
        spec = mock.Mock(length_m=0.2, width_m=0.2, fill_height_m=0.1, extra_vars={})
        spec.name = "b"
        with mock.patch.object(self.lab, "_liggghts", side_effect=fake_liggghts):
            bed = self.lab.bed(mock.Mock(file=str(self.soil)), spec)
        return {"bed": bed, "prepared": prepared[0] if prepared else None}


class Provenance(unittest.TestCase):
    def test_the_recorded_command_can_be_pasted_back(self):
        # an argument with a space (a bed variable holding two words) must stay one argument
        argv = ["soil-lab", "run", "my soil.in", "--bed-var", "soil_pair_settings=tangential_reduce off"]
        with mock.patch.object(sys, "argv", argv):
            command = cli._provenance(1)["command"]
        self.assertEqual(shlex.split(command), argv)


if __name__ == "__main__":
    unittest.main()
