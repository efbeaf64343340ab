"""Run health in curves and study: the rig's /health group (status and entries), runs
without it ("unchecked"), and post-processing's own findings over the window
(efficiency_bound, steady_state_trend, active_domain_sinkage, floor_clearance,
end_wall_clearance, particles_lost, scm_rim_skid)."""

import csv
import os
import unittest

import numpy as np

import synthetic as syn
from helpers import TempDirTestCase, is_png, run_cli
from wheelsim_post.analysis import analyse_run
from wheelsim_post.steady import make_window

N_TEST = 4000
HALF = make_window(None, None, (0.5, 1.0))


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


class HealthTest(TempDirTestCase):
    def write(self, name, dp=100.0, torque=60.0, health=None, slip=0.2, parameters=None,
              x_end=None):
        time, phase, series = syn.steady_run_series(
            N_TEST, 1e-3, 2.0, slip, dp, torque, load=1000.0
        )
        if x_end is not None:  # the wheel centre moving from x = 0 to x_end
            x = np.linspace(0.0, x_end, len(time))
            series["wheel/position"] = (np.column_stack([x, 0 * x, 0.1 + 0 * x]), "m")
        path = self.path(name)
        syn.write_run(
            path,
            time,
            phase,
            series,
            parameters={
                "sweep/wheel": "W",
                "sweep/soil": "S",
                "sweep/slip": str(slip),
                **(parameters or {}),
            },
            health=health,
        )
        return path

    def test_sinkage_beyond_the_active_domains_allowance(self):
        # The synthetic wheel sinks syn.SINKAGE = 0.02 m on average (+-1 mm).
        name = "liggghts/active_sinkage_allowance"
        deeper = self.write("deep.h5", parameters={name: (0.015, "m")}, health=("healthy", []))
        self.assertEqual(self.verdict(deeper), ("warning", "active_domain_sinkage"))
        message = analyse_run(deeper, HALF).health.findings[0].message
        self.assertIn("the wheel sank 0.02 m, deeper than the active domain's sinkage "
                      "allowance 0.015 m", message)
        within = self.write("within.h5", parameters={name: (0.025, "m")}, health=("healthy", []))
        self.assertEqual(self.verdict(within), ("ok", ""))
        # no active domain (no parameter): no finding
        self.assertEqual(self.verdict(self.write("full.h5", health=("healthy", []))), ("ok", ""))

    def test_scm_rim_skid(self):
        # a lugged wheel on SCM below s* = h/R_eff (0.1 here) warns; above, on DEM, or
        # smooth, it does not
        lugged = {"sweep/terrain": "scm", "wheel/lug_height": (syn.R_EFF / 10.0, "m")}
        low = self.write("low.h5", slip=0.05, parameters=lugged, health=("healthy", []))
        self.assertEqual(self.verdict(low), ("warning", "scm_rim_skid"))
        message = analyse_run(low, HALF).health.findings[0].message
        self.assertIn(f"SCM with a lugged wheel at slip 0.05, below lug height / effective "
                      f"radius = {syn.R_EFF / 10:.4g} / {syn.R_EFF:.4g} m = 0.1:", message)
        high = self.write("high.h5", slip=0.12, parameters=lugged, health=("healthy", []))
        self.assertEqual(self.verdict(high), ("ok", ""))
        dem = self.write("dem.h5", slip=0.05, parameters={**lugged, "sweep/terrain": "dem"},
                         health=("healthy", []))
        self.assertEqual(self.verdict(dem), ("ok", ""))
        smooth = self.write("smooth.h5", slip=0.05,
                            parameters={**lugged, "wheel/lug_height": (0.0, "m")},
                            health=("healthy", []))
        self.assertEqual(self.verdict(smooth), ("ok", ""))
        tips = self.write("tips.h5", slip=0.05,
                          parameters={**lugged, "terrain/shear_surface": "lug_tips"},
                          health=("healthy", []))
        self.assertEqual(self.verdict(tips), ("ok", ""))
        skid = self.write("skid.h5", slip=-0.2, parameters=lugged, health=("healthy", []))
        self.assertNotIn("scm_rim_skid", self.verdict(skid)[1])

    def test_floor_clearance(self):
        # sinkage 0.02 m: a 0.05 m bed leaves 0.03 m below the wheel, less than its 0.04 m width
        bed, width = "bed/bed_depth_m", "wheel/width"
        shallow = self.write("shallow.h5", parameters={bed: ("0.05", "m"), width: (0.04, "m")},
                             health=("healthy", []))
        self.assertEqual(self.verdict(shallow), ("warning", "floor_clearance"))
        message = analyse_run(shallow, HALF).health.findings[0].message
        self.assertIn("the wheel's bottom ran 0.03 m above the bin's rigid floor (bed depth "
                      "0.05 m, sinkage 0.02 m), less than 1 x its width 0.04 m", message)
        deep = self.write("deep.h5", parameters={bed: ("0.07", "m"), width: (0.04, "m")},
                          health=("healthy", []))
        self.assertEqual(self.verdict(deep), ("ok", ""))
        # SCM or flat (no bed depth), a wheel without a mesh (no width): no finding
        for name, params in (("scm.h5", {width: (0.04, "m")}), ("nomesh.h5", {bed: ("0.05", "m")})):
            self.assertEqual(self.verdict(self.write(name, parameters=params,
                                                     health=("healthy", []))), ("ok", ""))

    def test_end_wall_clearance(self):
        # sinkage 0.02 m; the centre ends at x = 0.5 m, the rim (radius 0.1 m) at 0.6 m
        params = {"wheel/rim_radius": (0.1, "m")}
        near = self.write("near.h5", parameters={**params, "bed/bin_length_m": ("0.63", "m")},
                          health=("healthy", []), x_end=0.5)
        self.assertEqual(self.verdict(near), ("warning", "end_wall_clearance"))
        message = analyse_run(near, HALF).health.findings[0].message
        self.assertIn("the rim's front came to 0.03 m from the bin's far wall (bin length 0.63 m, "
                      "wheel centre at x = 0.5 m, rim radius 0.1 m), less than 2 x the sinkage "
                      "0.02 m", message)
        far = self.write("far.h5", parameters={**params, "bed/bin_length_m": ("0.7", "m")},
                         health=("healthy", []), x_end=0.5)
        self.assertEqual(self.verdict(far), ("ok", ""))
        # no bin length (SCM, flat, older runs) or no position: no finding
        for name, kw in (("scm.h5", {"parameters": params, "x_end": 0.5}),
                         ("nopos.h5", {"parameters": {**params, "bed/bin_length_m": ("0.63", "m")}})):
            self.assertEqual(self.verdict(self.write(name, health=("healthy", []), **kw)), ("ok", ""))

    def test_end_wall_clearance_places_a_coupled_run_s_wheel_in_the_box(self):
        # A coupled run records x from the wheel's start (box_frame.py): a centre recorded at
        # 0.5 m that started at x0 = 0.1 m is at 0.6 m in the bin; its rim (0.1 m) ends 0.03 m
        # from the far wall of a 0.73 m bin (< 2 x 0.02 m sinkage). Without the origin, 0.13 m.
        params = {"wheel/rim_radius": (0.1, "m"), "bed/bin_length_m": ("0.73", "m"),
                  "coupling/start_step": (100, "1")}
        message = ("the rim's front came to 0.03 m from the bin's far wall (bin length 0.73 m, "
                   "wheel centre at x = 0.6 m")
        deck = self.path("in.deck")
        with open(deck, "w") as f:
            f.write("variable x  index 9\nvariable x0 index 0.10   # [m]\n")
        for name, extra in (
                ("recorded.h5", {"coupling/origin_x": (0.1, "m")}),
                ("extra_args.h5", {"liggghts/extra_args": "-var max_steps 9 -var x0 0.1"}),
                ("deck.h5", {"liggghts/extra_args": "-var max_steps 9", "liggghts/deck": deck})):
            run = self.write(name, parameters={**params, **extra}, health=("healthy", []),
                             x_end=0.5)
            self.assertEqual(self.verdict(run), ("warning", "end_wall_clearance"), name)
            self.assertIn(message, analyse_run(run, HALF).health.findings[0].message, name)
        # the origin unknown (no record, no x0, the deck gone): no finding rather than a wrong one
        lost = self.write("lost.h5", parameters={**params, "liggghts/deck": self.path("gone")},
                          health=("healthy", []), x_end=0.5)
        self.assertEqual(self.verdict(lost), ("ok", ""))

    def test_particles_lost(self):
        # 78 577 at the start (case 1's bed), 77 928 at the end: 649 lost, 0.83 % > 0.1 %
        start, end = "liggghts/atoms_start", "liggghts/atoms"
        lost = self.write("lost.h5", parameters={start: (78577, "1"), end: (77928, "1")},
                          health=("healthy", []))
        self.assertEqual(self.verdict(lost), ("warning", "particles_lost"))
        message = analyse_run(lost, HALF).health.findings[0].message
        self.assertIn("649 of 78577 particles (0.83 %) left the simulation box", message)
        # 78 of 78 577 (0.099 %): within the tolerance
        few = self.write("few.h5", parameters={start: (78577, "1"), end: (78499, "1")},
                         health=("healthy", []))
        self.assertEqual(self.verdict(few), ("ok", ""))
        # SCM, flat, runs before the start count was recorded: no finding
        older = self.write("older.h5", parameters={end: (77928, "1")}, health=("healthy", []))
        self.assertEqual(self.verdict(older), ("ok", ""))

    def verdict(self, path):
        r = analyse_run(path, HALF)
        return r.health.verdict, r.health.codes

    def test_rig_status_and_codes(self):
        cases = {
            "healthy.h5": (("healthy", []), ("ok", "")),
            "warnings.h5": (
                (
                    "warnings",
                    [
                        (10, 0.01, "grid_coarse", "warning", "grid 4 cm > 2 cm"),
                        (900, 0.9, "slip_not_held", "warning", "slip 0.26, target 0.2"),
                        (950, 0.95, "grid_coarse", "warning", "again"),
                    ],
                ),
                ("warning", "grid_coarse;slip_not_held"),
            ),
            "running.h5": (("running", []), ("incomplete", "")),
            "unhealthy.h5": (
                (
                    "unhealthy",
                    [(500, 0.5, "nonfinite_state", "error", "wheel z is nan")],
                ),
                ("unhealthy", "nonfinite_state"),
            ),
            "old.h5": (None, ("unchecked", "")),
        }
        for name, (health, expected) in cases.items():
            with self.subTest(name):
                self.assertEqual(self.verdict(self.write(name, health=health)), expected)

    def test_efficiency_above_one_minus_slip(self):
        # η = DP v/(T ω) = 1000·0.16/(60·2) = 1.33 > 1 − s = 0.8
        path = self.write("eta.h5", dp=1000.0, health=("healthy", []))
        self.assertEqual(self.verdict(path), ("warning", "efficiency_bound"))
        # within the bound: no finding
        self.assertEqual(self.verdict(self.write("fine.h5")), ("unchecked", ""))

    def test_drawbar_pull_trend(self):
        rng = np.random.default_rng(3)
        noise = 5.0 * syn.ar1(0.9, N_TEST, rng)
        ramp = 100.0 + 40.0 * np.arange(N_TEST) / N_TEST  # +20 N over the window
        trending = self.write("trend.h5", dp=ramp + noise, health=("healthy", []))
        verdict, codes = self.verdict(trending)
        self.assertEqual((verdict, codes), ("warning", "steady_state_trend"))
        steady = self.write("steady.h5", dp=100.0 + noise, health=("healthy", []))
        self.assertEqual(self.verdict(steady), ("ok", ""))

    def test_false_alarm_rate_of_the_trend_check(self):
        # stationary AR(1) noise: the trend check (3 standard errors of the fitted change)
        # must stay quiet in nearly all of 40 runs
        alarms = 0
        for seed in range(40):
            noise = 5.0 * syn.ar1(0.95, N_TEST, np.random.default_rng(100 + seed))
            path = self.write(f"s{seed}.h5", dp=100.0 + noise, health=("healthy", []))
            alarms += "steady_state_trend" in self.verdict(path)[1]
        self.assertLessEqual(alarms, 3)

    def test_curves_and_study_columns(self):
        paths = [
            self.write("a.h5", slip=0.1, health=("healthy", [])),
            self.write(
                "b.h5",
                slip=0.3,
                health=("warnings", [(5, 0.005, "lost_contact", "warning", "no contact")]),
            ),
            self.write("c.h5", slip=0.5),
        ]
        out, png = self.path("curves.csv"), self.path("curves.png")
        result = run_cli(
            "curves", *paths, "--window-fraction", "0.5", "1", "--csv", out, "--png", png
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = read_rows(out)
        self.assertEqual(
            [(r["health"], r["health_codes"]) for r in rows],
            [("ok", ""), ("warning", "lost_contact"), ("unchecked", "")],
        )
        with open(out) as f:
            text = f.read()
        self.assertIn("# notes:", text)
        self.assertIn("b.h5: health warning (lost_contact)", text)
        self.assertIn("health warning (lost_contact)", result.stdout)
        self.assertTrue(is_png(png))
        norm_png = self.path("normalised.png")
        result = run_cli("curves", *paths, "--normalised", "--png", norm_png)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(is_png(norm_png))

        study = self.path("study")
        result = run_cli("study", *paths, "--quantity", "drawbar_pull", "--out-dir", study)
        self.assertEqual(result.returncode, 0, result.stderr)
        runs = read_rows(os.path.join(study, "runs.csv"))
        self.assertEqual(
            [(r["health"], r["health_codes"]) for r in runs],
            [("ok", ""), ("warning", "lost_contact"), ("unchecked", "")],
        )
        self.assertIn("(warning)", result.stdout)
        self.assertIn("W, soil S, s = 0.3: warning (lost_contact)", result.stdout)


if __name__ == "__main__":
    unittest.main()
