"""How far a soil-lab run has come (soil_lab_py.progress): what --park says of each run it parks
(a plate's share of its schedule, plan.plate_test_time_s; a shear box's displacement over its
travel read off its CSV at the checkpoint, a later row not taken), and the line every 10 min of
wall time while a run goes (RunProgress, with a fake clock: nothing before, then the progress and
the wall time left at its pace); and what is left (soil_lab_py.estimate, `run --estimate`): a
parked run's steps left at its own last attempt's pace, a run on the same bed at that pace, a
finished run named, a bed to prepare named."""

import json
import lzma
import shutil
import tempfile
import unittest
from pathlib import Path
from types import SimpleNamespace

import numpy as np

import synthetic as syn
from soil_lab_py import estimate, plan, progress


class Progress(unittest.TestCase):
    def test_plate_share_of_its_schedule(self):
        variables = {"plate_speed": "0.02", "gap": "0.005", "depth1": "0.04", "unload": "0.01",
                     "depth2": "0.06"}
        # 5 mm of gap + 40 mm down, 10 mm up, 30 mm down again, at 20 mm/s
        self.assertAlmostEqual(plan.plate_test_time_s(variables), 4.25)
        self.assertAlmostEqual(plan.plate_test_time_s({**variables, "hold": "0.5",
                                                       "hold_stages": "3"}), 5.75)
        run = plan.Run("plate_b0.1", "plate", "in.lab_plate", "plate", {}, variables, {})
        self.assertEqual(progress.run_length(run, 1e-4), "4.25 s simulated = 42 500 steps")
        box = plan.Run("shear_s5000", "shear", "in.lab_shear", "shear", {},
                       {"shear_distance": "0.06", "shear_speed": "0.005", "consolidate_max": "3.0"},
                       {})
        self.assertEqual(progress.run_length(box, 1e-4),
                         "consolidation <= 3 s + shear 12 s simulated = <= 150 000 steps")
        self.assertEqual(progress.run_progress(run, None, 3.405),
                         "t 3.40 of 4.25 s simulated, 80 %")

    def test_shear_displacement_at_the_checkpoint(self):
        with tempfile.TemporaryDirectory() as tmp:
            syn.shear_run(tmp, 5e3)  # 50 rows consolidating, then j 0 -> 10 mm over 400 rows, 1 ms each
            run = plan.Run("shear_s5000", "shear", "in.lab_shear", "shear", {},
                           {"shear_distance": "0.012"}, {})
            d = Path(tmp) / "shear_s5000"
            self.assertEqual(progress.run_progress(run, d, 0.030), "consolidating under its lid")
            # row 249 (t 0.249 s) is j = 199/399 x 10 mm = 4.99 mm; a later row is not taken
            self.assertEqual(progress.run_progress(run, d, 0.2495),
                             "shear j 5.0 of 12.0 mm, 42 %")

    def test_progress_lines_while_a_run_goes(self):
        # RunProgress (Lab.run's while_running): nothing before every_s of wall time; then the
        # run's progress and, from its pace since the start, the wall time left
        variables = {"plate_speed": "0.02", "gap": "0.005", "depth1": "0.04", "unload": "0.01",
                     "depth2": "0.06"}   # 4.25 s simulated
        run = plan.Run("plate_b0.1", "plate", "in.lab_plate", "plate", {}, variables, {})
        with tempfile.TemporaryDirectory() as tmp:
            d = Path(tmp)
            csv = d / "plate.csv"
            csv.write_text("# time_s sinkage_m force_N pressure_Pa contacts phase\n"
                           "1.0 0.015 1 100 3 1\n")   # resumed at t 1.0 s
            now, said = [0.0], []
            report = progress.RunProgress(run, d, said.append, "[1/3] plate_b0.1", every_s=600.0,
                                        clock=lambda: now[0])
            report()
            now[0] = 300.0
            with open(csv, "a") as f:
                f.write("1.5 0.02 1 100 3 1\n2.0 0.0")   # a partial last line is not read
            report()
            self.assertEqual(said, [])
            now[0] = 600.0
            report()
            # 1.0 -> 1.5 s simulated in 600 s of wall: the 2.75 s left take 3300 s
            self.assertEqual(said, ["[1/3] plate_b0.1: t 1.50 of 4.25 s simulated, 35 %, "
                                    "~55 min left at this pace"])
            # a run whose progress cannot be read (here: a schedule variable that is no number)
            # is not stopped by its report
            bad = plan.Run("plate_b0.1", "plate", "in.lab_plate", "plate", {},
                           {**variables, "gap": "x"}, {})
            quiet = progress.RunProgress(bad, d, said.append, "x", clock=lambda: now[0])
            quiet()
            now[0] = 1300.0
            quiet()
            self.assertEqual(len(said), 1)

    def test_shear_progress_waits_for_the_shear(self):
        with tempfile.TemporaryDirectory() as tmp:
            run = plan.Run("shear_s5000", "shear", "in.lab_shear", "shear", {},
                           {"shear_distance": "0.012"}, {})
            d = Path(tmp) / "shear_s5000"
            d.mkdir()
            self.assertEqual(progress.run_progress(run, d), "consolidating under its lid")  # no CSV
            d.rmdir()
            syn.shear_run(tmp, 5e3)   # its last row: j 10 mm
            self.assertEqual(progress.run_progress(run, d), "shear j 10.0 of 12.0 mm, 83 %")


class Estimate(unittest.TestCase):
    def test_what_is_left_at_the_measured_pace(self):
        plate = {"plate_speed": "0.02", "gap": "0.005", "depth1": "0.04", "unload": "0.01",
                 "depth2": "0.06"}   # 4.25 s: 42 500 steps at 1e-4 s
        runs = [plan.Run("plate_b0.1", "plate", "in.lab_plate", "plate", {}, plate, {}),
                plan.Run("plate_b0.16", "plate", "in.lab_plate", "plate", {}, plate, {}),
                plan.Run("shear_s5000", "shear", "in.lab_shear", "shear", {},
                         {"shear_distance": "0.06", "shear_speed": "0.005"}, {})]
        lab = SimpleNamespace(runs=runs, beds={"plate": None, "shear": None},
                              soil=SimpleNamespace(dt_s=1e-4))
        with tempfile.TemporaryDirectory() as tmp:
            out, arch = Path(tmp) / "out", Path(tmp) / "archive"
            (out / "beds" / "plate").mkdir(parents=True)
            (out / "beds" / "plate" / "done.json").write_text("{}")
            # plate_b0.1 parked at step 30 000 of a run that started at 10 000; its last attempt
            # began at t 1000 s (from the start) and wrote that checkpoint at 2000 s: 20 steps/s
            kept = arch / "plate_b0.1" / "parked"
            (kept / "checkpoints").mkdir(parents=True)
            (kept / "parked.json").write_text(json.dumps({
                "step": 30000, "start_step": 10000, "time_s": 2.0, "files": [
                    {"path": "checkpoints/lab-10000-30000.restart", "mtime_unix": 2000.0}]}))
            (kept / "checkpoints" / "state.json.xz").write_bytes(lzma.compress(json.dumps(
                {"attempts": [{"start_unix": 1000.0, "wall_before_s": 0.0}]}).encode()))
            (arch / "shear_s5000").mkdir()
            (arch / "shear_s5000" / "done.json").write_text('{"steps": 5, "wall_s": 1.0}')
            lines = estimate.lab_estimate(lab, out, arch)
            # an attempt without its ranks (before 2026-12-07) is not rescaled on two ranks
            self.assertEqual(estimate.lab_estimate(lab, out, arch, np_=2), lines)
            # measured on one rank, priced on two: x 2 x 0.85 (the default 2-rank efficiency)
            (kept / "checkpoints" / "state.json.xz").write_bytes(lzma.compress(json.dumps(
                {"attempts": [{"start_unix": 1000.0, "wall_before_s": 0.0, "np": 1}]}).encode()))
            two = estimate.lab_estimate(lab, out, arch, np_=2)
            self.assertEqual(two[1], "estimate: [1/3] plate_b0.1: 22 500 steps to run (parked "
                             "with 20 000 of 42 500 steps done), ~11 min at 34 steps/s (measured "
                             "on 1 rank(s), x 1.70 for 2)")
            self.assertEqual(two[2], "estimate: [2/3] plate_b0.16: 42 500 steps to run, ~21 min "
                             "at 34 steps/s (measured on 1 rank(s), x 1.70 for 2)")
            # a finished run's done.json names its ranks: 2 ranks priced on one
            (arch / "plate_b0.1" / "done.json").write_text('{"steps": 340, "wall_s": 10.0, '
                                                             '"np": 2}')
            one = estimate.lab_estimate(lab, out, arch, np_=1)
            self.assertEqual(one[2], "estimate: [2/3] plate_b0.16: 42 500 steps to run, ~35 min "
                             "at 20 steps/s (measured on 2 rank(s), x 0.59 for 1)")
            (arch / "plate_b0.1" / "done.json").unlink()
            # the shear bed's record in the archive, its one box finished: it is not poured
            (arch / "beds" / "shear").mkdir(parents=True)
            (arch / "beds" / "shear" / "done.json").write_text('{"result": {"spheres": "10"}}')
            self.assertEqual(estimate.lab_estimate(lab, out, arch)[0],
                             "estimate: bed 'shear': not poured (its record in the archive, "
                             "every run on it finished or parked)")
            shutil.rmtree(arch / "beds")
        self.assertEqual(lines, [
            "estimate: bed 'shear': to prepare here (its cost is not estimated)",
            "estimate: [1/3] plate_b0.1: 22 500 steps to run (parked with 20 000 of 42 500 steps "
            "done), ~19 min at 20 steps/s",
            "estimate: [2/3] plate_b0.16: 42 500 steps to run, ~35 min at 20 steps/s",
            "estimate: [3/3] shear_s5000: finished before (archive; the lab compares its inputs)",
            "estimate: 65 000 steps to run, ~0.9 h of wall time at the measured paces; nothing "
            "was run"])
        # without the archive nothing is known of the plates' pace
        with tempfile.TemporaryDirectory() as tmp:
            lines = estimate.lab_estimate(lab, Path(tmp), None)
        self.assertIn("pace unknown", lines[2])
        self.assertTrue(lines[-1].endswith("+ 3 run(s) of unknown length or pace; nothing was "
                                           "run"), lines[-1])

    def test_a_lab_not_started_is_priced_at_the_machine_rate(self):
        # one sieve class of 10 mm spheres at 2000 kg/m^3, dt 1e-4 s; a 0.2 x 0.2 m bin filled
        # 0.1 m at solid fraction 0.6 / (pi/6 1e-6 m^3) = 4584 spheres; the bed settles for at
        # most 0.3 s (3 checks of 0.1 s): 3000 steps
        sv = {"soil_d1": 0.01, "soil_w1": 1.0, "soil_density": 2000.0, "soil_dt": 1e-4,
              "soil_dref": 0.01}
        defaults = {"fill_solid_fraction": "0.6", "check_time": "0.1", "max_settle_time": "0.3",
                    "compaction": "none"}
        rate = SimpleNamespace(rate_per_rank=1e6, bed_rate_per_rank=5e5, efficiency_np2=0.8,
                               source="test rate")
        bed = plan.Bed("plate", 0.2, 0.2, 0.1)
        plate = {"plate_speed": "0.02", "gap": "0.005", "depth1": "0.04", "unload": "0.01",
                 "depth2": "0.06"}   # 4.25 s: 42 500 steps at 1e-4 s
        lab = SimpleNamespace(runs=[plan.Run("plate_b0.1", "plate", "in.lab_plate", "plate", {},
                                             plate, {})],
                              beds={"plate": bed}, soil=SimpleNamespace(dt_s=1e-4))
        with tempfile.TemporaryDirectory() as tmp:
            # two ranks: 1e6 x 2 x 0.8 / 4584 spheres = 349 steps/s; the bed 5e5 x 1.6 / 4584
            machine = estimate.MachineRate(rate, 2, sv, defaults)
            lines = estimate.lab_estimate(lab, Path(tmp), None, machine)
            self.assertEqual(lines[0], "estimate: bed 'plate': to prepare here, ~4 600 spheres "
                             "(bin x fill solid fraction 0.6 / mean grain, 1 sieve classes by mass "
                             "fraction), <= 3 000 steps, <= 17.2 s at this machine's rate (+ its "
                             "bed-hold check)")
            self.assertEqual(lines[1], "estimate: [1/1] plate_b0.1: 42 500 steps to run, ~2 min "
                             "at 349 steps/s (this machine's rate, ~4 600 spheres estimated)")
            self.assertIn("1e+06 particle-steps/s per rank (beds 5e+05), 2 rank(s)", lines[2])
            self.assertIn("test rate", lines[2])
            self.assertTrue(lines[3].endswith("at the measured paces and this machine's rate; "
                                              "nothing was run"), lines[3])
            # --bed-np 1: the bed on one rank (5e5 / 4584 spheres: 27.5 s), the run on two
            one_rank_beds = estimate.MachineRate(rate, 2, sv, defaults, bed_np=1)
            lines = estimate.lab_estimate(lab, Path(tmp), None, one_rank_beds)
            self.assertIn("<= 3 000 steps, <= 27.5 s at this machine's rate", lines[0])
            self.assertIn("~2 min at 349 steps/s", lines[1])
            self.assertIn("2 rank(s) (beds 1), np-2 efficiency 0.80", lines[2])
            # once the bed is prepared its own sphere count prices the run
            (Path(tmp) / "beds" / "plate").mkdir(parents=True)
            (Path(tmp) / "beds" / "plate" / "done.json").write_text(
                json.dumps({"result": {"spheres": "8000"}}))
            lines = estimate.lab_estimate(lab, Path(tmp), None, machine)
            self.assertEqual(lines[0], "estimate: [1/1] plate_b0.1: 42 500 steps to run, ~4 min "
                             "at 200 steps/s (this machine's rate, its bed's 8 000 spheres)")

    def test_a_multisphere_soil_is_priced_by_its_spheres(self):
        # the same bed of a multisphere soil: 4584 particles x 2.1 spheres each (the
        # distribution's, wheel-sweep's spheres_per_particle) = 9626 spheres; without the ratio
        # the particles are priced and the line says it is low
        sv = {"soil_d1": 0.01, "soil_w1": 1.0, "soil_density": 2000.0, "soil_dt": 1e-4,
              "soil_dref": 0.01, "soil_multisphere": 1.0}
        defaults = {"fill_solid_fraction": "0.6"}
        rate = SimpleNamespace(rate_per_rank=1e6, bed_rate_per_rank=5e5, efficiency_np2=0.8,
                               source="test rate")
        bed = plan.Bed("plate", 0.2, 0.2, 0.1)
        known = estimate.MachineRate(rate, 1, sv, defaults, (2.1, "2.1 spheres per particle"))
        n, how = known.bed_spheres(bed)
        self.assertAlmostEqual(n, 2.1 * 0.2 * 0.2 * 0.1 * 0.6 / (np.pi / 6 * 1e-6), places=6)
        self.assertIn("multisphere: x 2.1 spheres per particle", how)
        self.assertFalse(known.clumps_uncounted)
        unknown = estimate.MachineRate(rate, 1, sv, defaults, (None, "a mass-based mix"))
        n, how = unknown.bed_spheres(bed)
        self.assertAlmostEqual(n, 0.2 * 0.2 * 0.1 * 0.6 / (np.pi / 6 * 1e-6), places=6)
        self.assertIn("clumps counted once, so low by their extra spheres (a mass-based mix)", how)
        self.assertTrue(unknown.clumps_uncounted)


if __name__ == "__main__":
    unittest.main()
