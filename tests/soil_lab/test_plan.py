"""soil-lab's test plan (soil_lab_py.plan): sizes from the grain size, and bad input named."""

import unittest

from soil_lab_py import plan
from soil_lab_py.plan import LabInputError, SoilInfo, make_plan

SAND = SoilInfo(name="sand", file="/x/sand.in", dmin_m=0.004, dmax_m=0.008, dref_m=0.006,
                density_kg_m3=2650.0, multisphere=False, dt_s=1e-5, youngs_Pa=5e7)


class Plan(unittest.TestCase):
    def test_standard_sizes_follow_the_grain_size(self):
        p = make_plan(SAND, ("bulk", "plate", "shear", "repose"))
        d = SAND.dmax_m
        plates = [r for r in p.runs if r.test == "plate"]
        self.assertEqual([r.meta["b_m"] for r in plates], [5 * d, 8 * d])
        self.assertAlmostEqual(p.beds["plate"].length_m, 24 * d)  # 3 x the larger plate
        self.assertAlmostEqual(p.beds["shear"].length_m, 12 * d)  # ASTM D3080: >= 10 d_max
        self.assertGreaterEqual(p.beds["shear"].fill_height_m, 6 * d)
        shear = [r for r in p.runs if r.test == "shear"]
        self.assertEqual([r.meta["normal_stress_Pa"] for r in shear], [5e3, 1e4, 2e4])
        # the lid fits inside the frame's hole
        lid = float(shear[0].meshes["lid_mesh"][1])
        hole = float(shear[0].meshes["frame_up_mesh"][1])
        self.assertLess(lid, hole)
        self.assertEqual(p.beds["repose"].length_m, 20 * d)
        self.assertAlmostEqual(p.beds["repose"].fill_height_m, 10 * d)

    def test_bad_input_is_named(self):
        cases = {
            "unknown test 'sheer'": dict(tests=("sheer",)),
            "unknown preset 'fast'": dict(tests=("plate",), preset="fast"),
            "needs >= 3 normal stresses": dict(tests=("shear",), normal_stresses_Pa=(1e3, 2e3)),
            "normal stress 1e+06 Pa is outside": dict(tests=("shear",),
                                                      normal_stresses_Pa=(1e3, 2e3, 1e6)),
            "normal stress -5 Pa is outside": dict(tests=("shear",),
                                                   normal_stresses_Pa=(-5, 1e3, 2e3)),
            "too wide for the plate bin": dict(tests=("plate",), plate_widths_m=(0.04, 0.1),
                                               plate_bin_m=0.2),
            "too wide for the plate bin (side 0.1 m)": dict(tests=("bulk", "plate"),
                                                            plate_bin_m=0.1),
            "narrower than 8 grains": dict(tests=("bulk",), plate_bin_m=0.06),
            "two different widths": dict(tests=("plate",), plate_widths_m=(0.05, 0.05)),
            "less than 2 grains": dict(tests=("plate",), plate_widths_m=(0.01, 0.05)),
            "--shear-travel 0.6 is outside (0, 0.5]": dict(tests=("shear",), shear_travel=0.6),
            "--shear-travel 0 is outside (0, 0.5]": dict(tests=("shear",), shear_travel=0.0),
            "--plate-speed 0 m/s is outside (0, 0.1] m/s": dict(tests=("plate",), plate_speed=0.0),
            "--shear-speed 5 m/s is outside (0, 0.1] m/s": dict(tests=("shear",), shear_speed=5.0),
            "--plate-depth 0.004 m is under one grain": dict(tests=("plate",), plate_depth=0.004),
            "--plate-depth nan m: expected a finite depth > 0 m": dict(
                tests=("plate",), plate_depth=float("nan")),
            "--plate-depth inf m: expected a finite depth": dict(tests=("plate",),
                                                                 plate_depth=float("inf")),
            "--plate-hold 0 s is outside (0, 60] s": dict(tests=("plate",), plate_hold=0.0),
            "--plate-hold 500 s is outside": dict(tests=("plate",), plate_hold=500.0),
            "--plate-hold nan s is outside": dict(tests=("plate",), plate_hold=float("nan")),
            "--plate-hold-stages 3 without --plate-hold": dict(tests=("plate",),
                                                               plate_hold_stages=3),
            "--plate-hold-stages 0 is outside 1..20": dict(tests=("plate",), plate_hold=1.0,
                                                           plate_hold_stages=0),
        }
        for message, kwargs in cases.items():
            with self.subTest(message):
                with self.assertRaises(LabInputError) as cm:
                    make_plan(SAND, **kwargs)
                self.assertIn(message, str(cm.exception))

    def test_options_that_need_no_soil_are_checked_without_one(self):
        # soil-lab run makes these checks before it creates or starts anything (in.lab_soilinfo,
        # a LIGGGHTS run, measures the soil): check_options takes no soil. make_plan refuses the
        # same options with the same message.
        cases = {
            "--plate-speed 0 m/s is outside (0, 0.1] m/s": dict(plate_speed=0.0),
            "--shear-speed 0 m/s is outside (0, 0.1] m/s": dict(shear_speed=0.0),
            "--shear-travel 0.9 is outside (0, 0.5]": dict(shear_travel=0.9),
            "--plate-widths: expected two different widths > 0 m": dict(
                plate_widths_m=(0.1, 0.1)),
            "--plate-widths: expected two different widths > 0 m (the Bekker fit separates kc "
            "from kphi by b), got [nan, 0.1]": dict(plate_widths_m=(float("nan"), 0.1)),
            "--plate-hold 100 s is outside (0, 60] s": dict(plate_hold=100.0),
            "--plate-hold-stages 2 without --plate-hold": dict(plate_hold_stages=2),
            "--plate-depth 0 m: expected a finite depth > 0 m": dict(plate_depth=0.0),
            "--plate-depth -0.01 m: expected a finite depth > 0 m": dict(plate_depth=-0.01),
            "--plate-bin nan m: expected a finite side > 0 m": dict(plate_bin_m=float("nan")),
            "--normal-stresses: the shear test needs >= 3 normal stresses for the Mohr-Coulomb "
            "fit, got 2": dict(normal_stresses_Pa=(5e3, 1e4)),
            "--normal-stresses: normal stress inf Pa is outside what the shear box can hold": dict(
                normal_stresses_Pa=(5e3, 1e4, float("inf"))),
            "--tests: expected at least one test of bulk, plate, shear, repose": dict(tests=()),
            "--tests: unknown test 'sheer' (did you mean 'shear'?)": dict(tests=("sheer",)),
        }
        for message, kwargs in cases.items():
            kwargs = {"tests": plan.TEST_NAMES, **kwargs}
            with self.subTest(message):
                with self.assertRaises(LabInputError) as cm:
                    plan.check_options(**kwargs)
                self.assertIn(message, str(cm.exception))
                with self.assertRaises(LabInputError) as again:
                    make_plan(SAND, **kwargs)
                self.assertEqual(str(again.exception), str(cm.exception))
        # Options only the soil can judge pass check_options and are refused by make_plan.
        d = SAND.dmax_m
        for message, kwargs in {
                "too wide for the plate bin": dict(tests=("plate",), plate_widths_m=(0.04, 0.1),
                                                   plate_bin_m=0.2),
                "--plate-depth 0.004 m is under one grain": dict(tests=("plate",),
                                                                 plate_depth=0.5 * d),
                "less than 2 grains": dict(tests=("plate",), plate_widths_m=(0.01, 0.05)),
                "narrower than 8 grains": dict(tests=("bulk",), plate_bin_m=0.06),
                "--normal-stresses: normal stress 1e+06 Pa is outside what the shear box can "
                "hold for this soil": dict(tests=("shear",), normal_stresses_Pa=(1e3, 2e3, 1e6)),
        }.items():
            with self.subTest(message):
                self.assertEqual(plan.check_options(**kwargs), kwargs["tests"])
                with self.assertRaises(LabInputError) as cm:
                    make_plan(SAND, **kwargs)
                self.assertIn(message, str(cm.exception))
        # Options of a test that does not run are not looked at, as make_plan never did.
        self.assertEqual(plan.check_options(("shear",), plate_hold=100.0), ("shear",))
        self.assertEqual(plan.check_options(("plate",), normal_stresses_Pa=(1.0,)), ("plate",))

    def test_bulk_alone_may_use_a_narrow_bin(self):
        # no plates: the bin only has to hold the core cell (>= 8 d_max), the depth stays the
        # plate bed's so the bed is the same recipe with or without plates
        d = SAND.dmax_m
        p = make_plan(SAND, ("bulk",), plate_bin_m=10 * d)
        self.assertAlmostEqual(p.beds["plate"].length_m, 10 * d)
        self.assertAlmostEqual(p.beds["plate"].fill_height_m,
                               make_plan(SAND, ("bulk",)).beds["plate"].fill_height_m)
        self.assertEqual(p.runs, [])

    def test_shear_travel_is_a_fraction_of_the_box(self):
        L = 12 * SAND.dmax_m
        for travel, expected in ((None, 0.12 * L), (0.2, 0.2 * L)):
            p = make_plan(SAND, ("shear",), shear_travel=travel)
            for r in p.runs:
                self.assertAlmostEqual(float(r.variables["shear_distance"]), expected)

    def test_plate_depth_default_or_as_given_with_a_bed_as_much_deeper(self):
        d = SAND.dmax_m
        default = make_plan(SAND, ("bulk", "plate"))
        deep = make_plan(SAND, ("bulk", "plate"), plate_depth=0.1)
        for p, depth2 in ((default, 3 * d), (deep, 0.1)):
            for r in (r for r in p.runs if r.test == "plate"):
                self.assertAlmostEqual(float(r.variables["depth2"]), depth2)
                self.assertAlmostEqual(float(r.variables["depth1"]), depth2 * 2 / 3, places=6)
                self.assertAlmostEqual(float(r.variables["unload"]), depth2 / 6, places=6)
        self.assertAlmostEqual(deep.beds["plate"].fill_height_m,
                               default.beds["plate"].fill_height_m + 0.1 - 3 * d)
        # a shallower plate keeps the default bed
        shallow = make_plan(SAND, ("plate",), plate_depth=1.5 * d)
        self.assertAlmostEqual(shallow.beds["plate"].fill_height_m,
                               default.beds["plate"].fill_height_m)

    def test_tool_speeds_default_or_as_given(self):
        for kwargs, plate, shear in (({}, 0.02, 0.005), (dict(preset="quick"), 0.04, 0.02),
                                     (dict(plate_speed=0.01, shear_speed=0.01), 0.01, 0.01)):
            p = make_plan(SAND, ("plate", "shear"), **kwargs)
            for r in p.runs:
                want = plate if r.test == "plate" else shear
                var = "plate_speed" if r.test == "plate" else "shear_speed"
                self.assertAlmostEqual(float(r.variables[var]), want, msg=str(kwargs))
                self.assertAlmostEqual(r.meta["speed_m_s"], want, msg=str(kwargs))
        # the quasi-static check halves the speed given
        p = make_plan(SAND, ("shear",), shear_speed=0.01, speed_check=True)
        half = [r for r in p.runs if r.name.endswith("_half")]
        self.assertAlmostEqual(float(half[0].variables["shear_speed"]), 0.005)

    def test_plate_holds_as_given_and_absent_by_default(self):
        # Without --plate-hold the plate runs carry no hold variables (the deck's default is no
        # hold), so their inputs are what they were before holds existed.
        for r in make_plan(SAND, ("plate",)).runs:
            self.assertNotIn("hold", r.variables)
            self.assertNotIn("hold_stages", r.variables)
        p = make_plan(SAND, ("plate",), plate_hold=0.5, plate_hold_stages=4, speed_check=True)
        self.assertEqual(len(p.runs), 3)
        for r in p.runs:   # the half-speed twin holds as long
            self.assertEqual((r.variables["hold"], r.variables["hold_stages"]), ("0.5", "4"))
        one = make_plan(SAND, ("plate",), plate_hold=2.0).runs[0]
        self.assertEqual(one.variables["hold_stages"], "1")

    def test_the_soil_carried_over_the_lower_frame_stays_on_it_and_in_the_domain(self):
        # The upper frame ends `distance` beyond the lower one: the lower frame's rim must be
        # wider than that (plus a grain) and the domain must reach past the upper frame's hole.
        L, d = 12 * SAND.dmax_m, SAND.dmax_m
        for travel in (0.12, 0.25, 0.5):
            for r in make_plan(SAND, ("shear",), shear_travel=travel).runs:
                distance = float(r.variables["shear_distance"])
                rim = float(r.meshes["frame_low_mesh"][3])
                self.assertGreaterEqual(rim, distance + d, f"travel {travel}")
                self.assertGreaterEqual(float(r.variables["shear_xhi"]), L + distance + 2 * d)
                self.assertLess(float(r.meshes["frame_up_mesh"][3]), d)  # the upper frame: thin

    def test_repose_on_multisphere_soils_gets_a_base_plate(self):
        # in.lab_repose freezes only the single spheres of a clump soil's base layer; its free
        # clumps rest on a plate of the base's footprint, as thick as the frame's wall
        clumps = SoilInfo(**{**SAND.__dict__, "multisphere": True})
        r = make_plan(clumps, ("repose",)).runs[0]
        B, wall = 20 * SAND.dmax_m, max(0.5 * SAND.dmax_m, 0.005)
        kind, lx, ly, t = r.meshes["base_mesh"]
        self.assertEqual(kind, "plate-rect")
        self.assertAlmostEqual(float(lx), B)
        self.assertAlmostEqual(float(ly), B)
        self.assertAlmostEqual(float(t), wall)
        self.assertEqual(r.variables["base_plate_t"], t)
        # a soil of spheres keeps its runs' inputs as they were: no plate
        r = make_plan(SAND, ("repose",)).runs[0]
        self.assertNotIn("base_mesh", r.meshes)
        self.assertNotIn("base_plate_t", r.variables)

    def test_speed_check_halves_one_run_per_test(self):
        p = make_plan(SAND, ("plate", "shear", "repose"), speed_check=True)
        half = {r.name: r for r in p.runs if r.name.endswith("_half")}
        self.assertEqual(sorted(half), ["plate_b0.064_half", "repose_half", "shear_s10000_half"])
        full = {r.name: r for r in p.runs}
        for name, r in half.items():
            var = {"plate": "plate_speed", "shear": "shear_speed", "repose": "lift_speed"}[r.test]
            self.assertAlmostEqual(float(r.variables[var]),
                                   float(full[name[:-5]].variables[var]) / 2)
            self.assertEqual(r.meshes, full[name[:-5]].meshes)
        # quick: no half-speed repose (its small heap's angle is noise at the check's tolerance)
        quick = make_plan(SAND, ("plate", "shear", "repose"), preset="quick", speed_check=True)
        self.assertEqual(sorted(r.name for r in quick.runs if r.name.endswith("_half")),
                         ["plate_b0.032_half", "shear_s6000_half"])

    def test_dt_check_repeats_the_larger_plate_and_the_middle_box_at_half_the_step(self):
        p = make_plan(SAND, ("plate", "shear", "repose"), speed_check=True, dt_check=True)
        runs = {r.name: r for r in p.runs}
        halfdt = sorted(n for n in runs if n.endswith("_halfdt"))
        # not the repose heap, not the half-speed runs: the tools' tests at the soil's speeds
        self.assertEqual(halfdt, ["plate_b0.064_halfdt", "shear_s10000_halfdt"])
        for name in halfdt:
            r, full = runs[name], runs[name[: -len("_halfdt")]]
            self.assertEqual((r.test, r.deck, r.bed, r.meshes, r.variables),
                             (full.test, full.deck, full.bed, full.meshes, full.variables))
            self.assertEqual(r.meta, {**full.meta, "dt_factor": 0.5, "half_dt_of": full.name})
            self.assertEqual(plan.run_dt_s(r, SAND.dt_s), 0.5 * SAND.dt_s)
            self.assertEqual(plan.run_dt_s(full, SAND.dt_s), SAND.dt_s)
        # the other runs are those of the lab without the check (same names, same inputs)
        self.assertEqual([(r.name, r.variables, r.meta) for r in p.runs
                          if not r.name.endswith("_halfdt")],
                         [(r.name, r.variables, r.meta) for r in
                          make_plan(SAND, ("plate", "shear", "repose"), speed_check=True).runs])
        # with replicates: every bed's middle box, on its own bed
        p = make_plan(SAND, ("shear",), shear_replicates=2, dt_check=True)
        self.assertEqual([(r.name, r.bed) for r in p.runs if r.name.endswith("_halfdt")],
                         [("shear_s10000_halfdt", "shear"), ("shear_s10000_r2_halfdt", "shear_r2")])

    def test_shear_replicates_pour_their_own_beds(self):
        p = make_plan(SAND, ("shear",), shear_replicates=3, speed_check=True)
        self.assertEqual(sorted(p.beds), ["shear", "shear_r2", "shear_r3"])
        # the first bed keeps the recipe's seed (in.soilbin's default); the others their own
        self.assertNotIn("seed", p.beds["shear"].extra_vars)
        seeds = [p.beds[b].extra_vars["seed"] for b in ("shear_r2", "shear_r3")]
        self.assertEqual(seeds, [str(x) for x in plan.REPLICATE_SEEDS[:2]])
        for b in ("shear_r2", "shear_r3"):
            self.assertEqual((p.beds[b].length_m, p.beds[b].fill_height_m),
                             (p.beds["shear"].length_m, p.beds["shear"].fill_height_m))
        names = [r.name for r in p.runs]
        self.assertEqual(names, ["shear_s5000", "shear_s10000", "shear_s20000",
                                 "shear_s5000_r2", "shear_s10000_r2", "shear_s20000_r2",
                                 "shear_s5000_r3", "shear_s10000_r3", "shear_s20000_r3",
                                 "shear_s10000_half", "shear_s10000_r2_half",
                                 "shear_s10000_r3_half"])
        runs = {r.name: r for r in p.runs}
        self.assertEqual(runs["shear_s10000_r3"].bed, "shear_r3")
        self.assertEqual(runs["shear_s10000_r3"].meta["replicate"], 3)
        self.assertEqual(runs["shear_s10000_r3"].variables, runs["shear_s10000"].variables)
        # the first bed's runs keep their records as before (no replicate key: same run key)
        self.assertEqual(runs["shear_s10000"].meta, make_plan(SAND, ("shear",)).runs[1].meta)
        self.assertEqual(runs["shear_s10000_half"].bed, "shear")
        # every bed's middle box at half speed (the paired check), on its own bed
        self.assertEqual(runs["shear_s10000_r3_half"].bed, "shear_r3")
        self.assertEqual(runs["shear_s10000_r3_half"].meta["replicate"], 3)
        self.assertEqual(runs["shear_s10000_r3_half"].variables["shear_speed"], "0.0025")
        # a user's seed for every bed stays the first bed's; a replicate's own seed is refused
        p = make_plan(SAND, ("shear",), shear_replicates=2, bed_vars={"seed": "15485863"})
        self.assertEqual(p.beds["shear"].extra_vars["seed"], "15485863")
        with self.assertRaisesRegex(LabInputError, "seed=67867967"):
            make_plan(SAND, ("shear",), shear_replicates=2, bed_vars={"seed": "67867967"})
        for bad in (0, plan.MAX_SHEAR_REPLICATES + 1, 2.5, True):
            with self.assertRaisesRegex(LabInputError, "--shear-replicates"):
                plan.check_options(("shear",), shear_replicates=bad)
        with self.assertRaisesRegex(LabInputError, "add shear to --tests"):
            plan.check_options(("plate",), shear_replicates=2)
        self.assertEqual(len(plan.REPLICATE_SEEDS), plan.MAX_SHEAR_REPLICATES - 1)

    def test_plate_replicates_press_into_their_own_beds(self):
        p = make_plan(SAND, ("plate",), plate_replicates=3, speed_check=True, dt_check=True)
        self.assertEqual(sorted(p.beds), ["plate", "plate_r2", "plate_r3"])
        self.assertNotIn("seed", p.beds["plate"].extra_vars)
        self.assertEqual([p.beds[b].extra_vars["seed"] for b in ("plate_r2", "plate_r3")],
                         [str(x) for x in plan.REPLICATE_SEEDS[:2]])
        for b in ("plate_r2", "plate_r3"):   # the same bin and depth as the first bed
            self.assertEqual((p.beds[b].length_m, p.beds[b].width_m, p.beds[b].fill_height_m),
                             (p.beds["plate"].length_m, p.beds["plate"].width_m,
                              p.beds["plate"].fill_height_m))
        self.assertEqual([(r.name, r.bed) for r in p.runs], [
            ("plate_b0.04", "plate"), ("plate_b0.064", "plate"),
            ("plate_b0.04_r2", "plate_r2"), ("plate_b0.064_r2", "plate_r2"),
            ("plate_b0.04_r3", "plate_r3"), ("plate_b0.064_r3", "plate_r3"),
            # every bed's larger plate at half speed and at half the step, on its own bed
            ("plate_b0.064_half", "plate"), ("plate_b0.064_r2_half", "plate_r2"),
            ("plate_b0.064_r3_half", "plate_r3"),
            ("plate_b0.064_halfdt", "plate"), ("plate_b0.064_r2_halfdt", "plate_r2"),
            ("plate_b0.064_r3_halfdt", "plate_r3")])
        runs = {r.name: r for r in p.runs}
        self.assertEqual(runs["plate_b0.064_r3"].meta["replicate"], 3)
        self.assertEqual(runs["plate_b0.064_r3"].variables, runs["plate_b0.064"].variables)
        self.assertEqual(runs["plate_b0.064_r2_halfdt"].meta["replicate"], 2)
        # the first bed's plates keep their records as before (no replicate key: same run key)
        self.assertEqual(runs["plate_b0.064"].meta, make_plan(SAND, ("plate",)).runs[1].meta)
        with self.assertRaisesRegex(LabInputError, "seed=86028121.*--plate-replicates"):
            make_plan(SAND, ("plate",), plate_replicates=3, bed_vars={"seed": "86028121"})
        for bad in (0, plan.MAX_PLATE_REPLICATES + 1, 2.5, True):
            with self.assertRaisesRegex(LabInputError, "--plate-replicates"):
                plan.check_options(("plate",), plate_replicates=bad)
        with self.assertRaisesRegex(LabInputError, "add plate to --tests"):
            plan.check_options(("bulk", "shear"), plate_replicates=2)


if __name__ == "__main__":
    unittest.main()
