"""soil-lab's analysis of a lab directory (soil_lab_py.analysis) on synthetic plate runs:
the unloading stiffness is taken from the turning point on, whatever the loading's noise; the
SCM file of a soil whose Mohr-Coulomb intercept is negative gets c = 0 and phi through the
origin, and says so; a bed's bed-hold check is reported only for the bed as it is."""

import json
import tempfile
import tomllib
import unittest
from pathlib import Path
from types import SimpleNamespace

import numpy as np

import synthetic as syn
from synthetic import KE_Pa_m, plate_run
from soil_lab_py import analysis, fits, plan

RELAXED = 0.8  # the held synthetic soil relaxes to this fraction of its pressure at speed


def held_plate_run(directory, b_m, tau_s, stages=3, hold_s=0.5, speed=0.02, depth1=0.02,
                   creep=0.0):
    """in.lab_plate with `stages` holds: the loading at `speed` (Bekker, n 1.1) stops at
    k depth1 / stages for hold_s, where the pressure relaxes exponentially (tau_s) towards RELAXED
    of its value at speed (with `creep`, a further share of it goes with tau 0.5 s: a slow tail),
    then goes on from there; after the last hold an unload by 2 mm with slope KE_Pa_m. Samples
    every 1 ms."""
    dt = 1e-3
    t, z, p, phase = [], [], [], []
    time, p_now = 0.0, 0.0
    for k in range(stages):
        z_a, z_b = k * depth1 / stages, (k + 1) * depth1 / stages
        for zz in np.arange(z_a, z_b, speed * dt):
            p_now = (1e4 / b_m + 5e5) * zz ** 1.1
            t.append(time); z.append(zz); p.append(p_now); phase.append(1)
            time += dt
        p_speed = (1e4 / b_m + 5e5) * z_b ** 1.1
        for th in np.arange(0.0, hold_s, dt):
            p_now = p_speed * (RELAXED + (1 - RELAXED - creep) * np.exp(-th / tau_s)
                               + creep * np.exp(-th / 0.5))
            t.append(time); z.append(z_b); p.append(p_now); phase.append(4)
            time += dt
    for zz in np.linspace(depth1, depth1 - 0.002, 40):
        t.append(time); z.append(zz); p.append(p_now - KE_Pa_m * (depth1 - zz)); phase.append(2)
        time += dt
    run = Path(directory) / f"plate_b{b_m:g}"
    run.mkdir(parents=True)
    t, z, p = np.array(t), np.array(z), np.array(p)
    np.savetxt(run / "plate.csv", np.column_stack([t, z, p * b_m * b_m, p, 10 + 0 * z, phase]),
               header="time_s sinkage_m force_N pressure_Pa contacts phase")
    (run / "done.json").write_text(json.dumps({"meta": {"b_m": b_m}, "wall_s": 1.0}))


def plate_twin(directory, name, scale, record):
    """A check's run of the plate b 0.032 m (`name`, e.g. plate_b0.032_half): its CSV with every
    force and pressure times `scale`, and the done.json `record`."""
    full, twin = Path(directory) / "plate_b0.032", Path(directory) / name
    twin.mkdir()
    t = np.loadtxt(full / "plate.csv", ndmin=2)
    t[:, 2:4] *= scale
    np.savetxt(twin / "plate.csv", t, header="time_s sinkage_m force_N pressure_Pa contacts phase")
    (twin / "done.json").write_text(json.dumps(record))


class Analysis(unittest.TestCase):
    def lab(self, noisy):
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\ndmax_m = 0.004\n')
        plate_run(d, 0.02, noisy)
        plate_run(d, 0.032, noisy)
        return analysis.analyse(d)

    def test_unloading_stiffness_from_the_turning_point(self):
        for noisy in (False, True):
            r = self.lab(noisy)
            self.assertEqual(r.unload_errors, {})
            self.assertEqual(sorted(r.unload), [0.02, 0.032])   # both plates fitted
            for b, fit in r.unload.items():
                # a spike in the loading before the turning point must not enter the fit
                self.assertAlmostEqual(fit.Ke_Pa_m / KE_Pa_m, 1.0, delta=0.02, msg=f"b {b}")

    def test_a_plate_without_an_unloading_branch_is_reported_not_fatal(self):
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\ndmax_m = 0.004\n')
        plate_run(d, 0.032, False)
        run = d / "plate_b0.02"
        run.mkdir()
        z = np.linspace(0, 0.02, 50)
        np.savetxt(run / "plate.csv", np.column_stack([z, z, z, 1e6 * z, z, 1 + 0 * z]))
        (run / "done.json").write_text(json.dumps({"meta": {"b_m": 0.02}}))
        r = analysis.analyse(d)
        self.assertIn(0.02, r.unload_errors)
        self.assertIn(0.032, r.unload)

    def test_plate_speed_check_compares_the_whole_loading_by_depth(self):
        # The half-speed twin of the larger plate carries 20 % less pressure at every depth: the
        # check reads -20 % at the end of loading and in each of the depth bands.
        r = self.lab(False)
        full = r.directory / "plate_b0.032"
        plate_twin(r.directory, "plate_b0.032_half", 0.8,
                   {"meta": {"b_m": 0.032, "half_of": "plate_b0.032"}, "wall_s": 2.0})
        q, = analysis.analyse(r.directory).quasi_static
        self.assertAlmostEqual(q["difference"], -0.2, places=9)
        self.assertFalse(q["passed"])
        self.assertEqual(len(q["profile_depth_m"]), analysis.PLATE_PROFILE_BANDS)
        np.testing.assert_allclose(q["profile_depth_m"], [0.002, 0.006, 0.01, 0.014, 0.018])
        np.testing.assert_allclose(q["profile_difference"], -0.2, atol=1e-9)
        # the last band is the end-of-loading pressure: the mean over the last 20 % of the depth
        plate = analysis.read_plate(full, {"meta": {"b_m": 0.032}})
        z1 = np.linspace(0.0, 0.02, 200)
        p1 = (1e4 / 0.032 + 5e5) * z1 ** 1.1
        self.assertAlmostEqual(analysis.plate_end_pressure(plate) / p1[z1 >= 0.016].mean(), 1.0,
                               places=9)

    def test_the_scm_file_states_the_plates_speed_check(self):
        # No check: said. A half-speed twin 2 % softer: quasi-static, said. 20 % softer: refused
        # without --rate-dependent, written and said with it.
        shear = analysis.shear_strength_from(self.shear_summary(), "synthetic")

        def scm(scale, **kw):
            r = self.lab(False)
            if scale is not None:
                plate_twin(r.directory, "plate_b0.032_half", scale,
                           {"meta": {"b_m": 0.032, "half_of": "plate_b0.032"}, "wall_s": 2.0})
                r = analysis.analyse(r.directory)
            out = Path(tempfile.mkdtemp()) / "scm.toml"
            analysis.write_scm(r, out, shear=shear, **kw)
            return tomllib.loads(out.read_text())["source"]["bekker"]["n"]
        self.assertIn("plate speed not checked (no --speed-check half-speed plate in the lab)",
                      scm(None))
        # nor its time step: said, with the step the plates ran at (their records' dt_s)
        self.assertIn("; time step not checked (no --dt-check half-step plate in the lab, fitted "
                      "at dt 1e-05 s)", scm(None))
        self.assertIn("speed check: plate_b0.032 at half speed: -2.0 % at the end of loading "
                      "(tolerance 5 %): quasi-static", scm(0.98))
        with self.assertRaisesRegex(analysis.LabResultError,
                                    r"speed check failed \(plate_b0.032 at half speed: -20.0 % .*"
                                    r"NOT quasi-static\).*with --rate-dependent"):
            scm(0.8)
        self.assertIn("-20.0 % at the end of loading (tolerance 5 %): NOT quasi-static",
                      scm(0.8, rate_dependent_ok=True))

    def test_plate_time_step_check_compares_the_loading_and_is_stated_in_the_scm_file(self):
        # The larger plate at half the step carries 12 % more pressure at every depth: the check
        # reads +12 % at the end of loading and in each band, fails its 5 %, is not a point of the
        # Bekker fit, and the SCM file's [source] states it (without refusing the fit).
        r = self.lab(False)
        bekker = r.bekker
        plate_twin(r.directory, "plate_b0.032_halfdt", 1.12,
                   {"meta": {"b_m": 0.032, "dt_factor": 0.5, "half_dt_of": "plate_b0.032"},
                    "wall_s": 4.0, "dt_s": 5e-6})
        r = analysis.analyse(r.directory)
        self.assertEqual(r.quasi_static, [])
        q, = r.time_step
        self.assertEqual((q["run"], q["half_dt_s"], q["unit"]), ("plate_b0.032", 5e-6, "Pa"))
        self.assertAlmostEqual(q["difference"], 0.12, places=9)
        self.assertFalse(q["passed"])
        np.testing.assert_allclose(q["profile_difference"], 0.12, atol=1e-9)
        self.assertEqual(len(r.plates), 2)   # the half-step plate is not a third plate
        self.assertEqual((r.bekker.n, r.bekker.kc, r.bekker.kphi),
                         (bekker.n, bekker.kc, bekker.kphi))
        self.assertAlmostEqual(analysis.summary(r)["time_step"]["plate_b0.032"]["difference"],
                               0.12, places=9)
        out = Path(tempfile.mkdtemp()) / "scm.toml"
        analysis.write_scm(r, out, shear=analysis.shear_strength_from(self.shear_summary(),
                                                                      "synthetic"))
        self.assertIn("time-step check: plate_b0.032 at half the step (5e-06 s): +12.0 % at the "
                      "end of loading (tolerance 5 %): step-dependent",
                      tomllib.loads(out.read_text())["source"]["bekker"]["n"])

    def test_replicate_plates_give_each_beds_fit_and_pair_the_step_check_on_its_bed(self):
        # Three plate beds 0 / +10 / -10 % stiff (kc and kphi scaled, n 1.1), each with its larger
        # plate at half the step +1 / 0 / -1 % against its own: every plate enters one Bekker fit
        # (the mean soil: kc 1e4, kphi 5e5); each bed's own fit recovers its scale; the pressure
        # at the end of loading scatters 10 % (sd) and 20 % (spread) per width; the step check
        # paired over the beds: mean 0, sd 1 %, 95 % interval +-4.303 x 1 / sqrt 3 = +-2.48 %,
        # within 5 %: "step-converged", said so in the SCM file's [source].
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\ndmax_m = 0.004\n')
        for k, scale, step in ((1, 1.0, 1.01), (2, 1.1, 1.0), (3, 0.9, 0.99)):
            suffix, rep = ("", {}) if k == 1 else (f"_r{k}", {"replicate": k})
            for b in (0.02, 0.032):
                plate_run(d, b, scale=scale, name=f"plate_b{b:g}{suffix}", meta=rep)
            plate_run(d, 0.032, scale=scale * step, name=f"plate_b0.032{suffix}_halfdt",
                      meta={**rep, "dt_factor": 0.5, "half_dt_of": f"plate_b0.032{suffix}"},
                      dt_s=5e-6)
            bed = d / "beds" / plan.plate_bed_name(k)
            bed.mkdir(parents=True)
            (bed / "done.json").write_text(json.dumps({"result": {
                "bulk_density": "700", "porosity": "0.5", "bed_depth": "0.1",
                "core_bulk_density": f"{750 + k}"}}))
        r = analysis.analyse(d)
        self.assertEqual([(p["run"], p["replicate"]) for p in r.plates],
                         [("plate_b0.02", 1), ("plate_b0.032", 1), ("plate_b0.02_r2", 2),
                          ("plate_b0.032_r2", 2), ("plate_b0.02_r3", 3), ("plate_b0.032_r3", 3)])
        self.assertAlmostEqual(r.bekker.n, 1.1, delta=1e-3)
        self.assertAlmostEqual(r.bekker.kc / 1e4, 1.0, delta=0.01)
        self.assertAlmostEqual(r.bekker.kphi / 5e5, 1.0, delta=0.01)
        self.assertEqual(sorted(r.unload), [0.02, 0.032])   # the first bed's plates
        rep = r.plate_replicates
        self.assertEqual((rep["replicates"], rep["fitted_replicates"]), ([1, 2, 3], [1, 2, 3]))
        for i, scale in enumerate((1.0, 1.1, 0.9)):
            self.assertAlmostEqual(rep["n"][i], 1.1, delta=1e-3)
            self.assertAlmostEqual(rep["kc_N_m_n1"][i] / (scale * 1e4), 1.0, delta=0.01)
            self.assertAlmostEqual(rep["kphi_N_m_n2"][i] / (scale * 5e5), 1.0, delta=0.01)
        self.assertAlmostEqual(rep["kphi_N_m_n2_sd"] / 5e5, 0.1, delta=0.002)
        self.assertEqual(rep["bed_bulk_density_kg_m3"], {"bed1": 751.0, "bed2": 752.0,
                                                         "bed3": 753.0})
        for b in rep["by_width"]:
            self.assertEqual(b["plates"], 3)
            self.assertAlmostEqual(b["p_end_sd_Pa"] / b["p_end_mean_Pa"], 0.1, delta=1e-6)
            self.assertAlmostEqual(b["p_end_spread"], 0.2, delta=1e-6)
        # each bed's half-step plate against its own bed's plate, not the first bed's
        self.assertEqual([(q["run"], q["replicate"]) for q in r.time_step],
                         [("plate_b0.032", 1), ("plate_b0.032_r2", 2), ("plate_b0.032_r3", 3)])
        np.testing.assert_allclose([q["difference"] for q in r.time_step], [0.01, 0.0, -0.01],
                                   atol=1e-9)
        c, = r.paired_step_checks
        self.assertEqual((c["test"], c["b_m"], c["beds"]), ("plate", 0.032, 3))
        self.assertAlmostEqual(c["interval_high"], 4.303 * 0.01 / np.sqrt(3), places=4)
        self.assertEqual(c["verdict"], "step-converged")
        s = analysis.summary(r)
        self.assertEqual(s["time_step_paired"]["plate_b0.032"]["verdict"], "step-converged")
        self.assertEqual(s["plate"]["replicates"]["fitted_replicates"], [1, 2, 3])
        analysis.write_report(r)
        rows = {(t, q): float(v) for t, q, v in
                (line.split(",") for line in (d / "results.csv").read_text().splitlines()[1:])}
        self.assertAlmostEqual(rows["plate", "bed2_kphi_N_m_n2"] / 5.5e5, 1.0, delta=0.01)
        self.assertAlmostEqual(rows["plate", "replicates_b0.032_p_end_spread"], 0.2, delta=1e-5)
        self.assertAlmostEqual(rows["time_step_paired", "plate_b0.032_mean_difference"], 0.0,
                               delta=1e-6)
        out = Path(tempfile.mkdtemp()) / "scm.toml"
        analysis.write_scm(r, out, shear=analysis.shear_strength_from(self.shear_summary(),
                                                                      "synthetic"))
        source = tomllib.loads(out.read_text())["source"]["bekker"]["n"]
        self.assertIn("; time-step check over 3 beds (plate b 0.032 m, each paired on its bed): "
                      "mean +0.0 %, 95 % interval -2.5 to +2.5 % (tolerance 5 %): step-converged",
                      source)
        self.assertNotIn("step-dependent", source)
        self.assertIn("square plates b = 0.02, 0.032 m on 3 beds of the recipe (each bed's own "
                      "fit: n sd ", source)
        self.assertRegex(source, r"kphi sd 10(\.0)? %\), loading branches")
        # one bed of three without its larger plate: two beds fitted, no pairs to pool
        for run in ("plate_b0.032_r3", "plate_b0.032_r3_halfdt"):
            for f in (d / run).iterdir():
                f.unlink()
            (d / run).rmdir()
        r = analysis.analyse(d)
        self.assertEqual(r.plate_replicates["fitted_replicates"], [1, 2])
        self.assertEqual([b["plates"] for b in r.plate_replicates["by_width"]], [3, 2])
        self.assertEqual(r.paired_step_checks[0]["beds"], 2)

    def test_shear_speed_check_compares_the_peaks(self):
        # Three boxes; the one at 10 kPa again at half speed with a 10 % lower, then a 3 % lower
        # plateau: the check reads -10 % (outside its 5 %) and -3 % (inside), relative.
        for scale, passed in ((0.9, False), (0.97, True)):
            d = Path(tempfile.mkdtemp())
            (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\n'
                                         'dmax_m = 0.004\n')
            for sigma in (5e3, 1e4, 2e4):
                syn.shear_run(d, sigma)
            syn.shear_run(d, 1e4, name="shear_s10000_half", tau_scale=scale)
            r = analysis.analyse(d)
            q, = r.quasi_static
            self.assertEqual((q["run"], q["quantity"], q["unit"]),
                             ("shear_s10000", "peak shear stress", "Pa"))
            self.assertAlmostEqual(q["difference"], scale - 1.0, places=6)
            self.assertAlmostEqual(q["half_speed"] / q["full_speed"], scale, places=6)
            self.assertTrue(q["relative"])
            self.assertEqual(q["tolerance"], 0.05)
            self.assertIs(q["passed"], passed)
            self.assertEqual(len(r.shears), 3)  # the half-speed box is not a Mohr-Coulomb point
            # a uniformly weaker box is weaker in every quarter of the travel: no sign change
            np.testing.assert_allclose(q["profile_displacement_m"],
                                       [0.00125, 0.00375, 0.00625, 0.00875])
            np.testing.assert_allclose(q["profile_difference"], scale - 1.0, atol=1e-9)
            self.assertIs(q["profile_changes_sign"], False)

    def test_shear_speed_check_reports_a_difference_that_changes_sign(self):
        # The half-speed box 5 % weaker over the first half of the travel and 10 % stronger over
        # the second: the peaks differ by +10 % (NOT quasi-static by the rule), and the quarters
        # read -5, -5, +10, +10 %, which the check flags as a sign change (the box's fluctuation,
        # not shown to be a rate effect); results.toml keeps the bands and the flag.
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\n'
                                     'dmax_m = 0.004\n')
        for sigma in (5e3, 1e4, 2e4):
            syn.shear_run(d, sigma)
        half = d / "shear_s10000_half"
        half.mkdir()
        t = np.loadtxt(d / "shear_s10000" / "shear.csv")
        t[:, 3] *= np.where(t[:, 1] < 0.005, 0.95, 1.10)
        np.savetxt(half / "shear.csv", t, header="time_s displacement_m shear_force_N tau_Pa "
                   "sigma_Pa lid_z_m phase")
        (half / "done.json").write_text((d / "shear_s10000" / "done.json").read_text())
        r = analysis.analyse(d)
        q, = r.quasi_static
        self.assertAlmostEqual(q["difference"], 0.10, places=2)
        self.assertFalse(q["passed"])
        np.testing.assert_allclose(q["profile_difference"], [-0.05, -0.05, 0.10, 0.10],
                                   atol=1e-9)
        self.assertIs(q["profile_changes_sign"], True)
        written = analysis.summary(r)["quasi_static"]["shear_s10000"]
        self.assertEqual(written["profile_difference"], q["profile_difference"])
        self.assertIs(written["profile_changes_sign"], True)
        self.assertEqual((written["lid_full_m"], written["lid_half_m"]), (0.0, 0.0))
        # within +-1 % both ways is no sign change worth naming
        self.assertIs(analysis.profile_changes_sign([-0.005, 0.004, 0.2]), False)
        self.assertIs(analysis.profile_changes_sign([float("nan"), -0.02, 0.02]), True)

    def test_repose_speed_check_compares_the_angles_in_degrees(self):
        # A 30 deg heap against one of 33 deg (fails the 1.5 deg tolerance), then against another
        # 30 deg heap (another random packing: passes); the difference is absolute, in degrees.
        for half_deg, passed in ((33.0, False), (30.0, True)):
            d = Path(tempfile.mkdtemp())
            (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\n'
                                         'dmax_m = 0.004\n')
            syn.repose_run(d, 30.0)
            syn.repose_run(d, half_deg, name="repose_half", seed=5)
            r = analysis.analyse(d)
            self.assertIsNone(r.repose_error)
            q, = r.quasi_static
            self.assertEqual((q["run"], q["quantity"], q["unit"]),
                             ("repose", "angle of repose", "deg"))
            self.assertAlmostEqual(q["full_speed"], 30.0, delta=0.5)
            self.assertAlmostEqual(q["difference"], half_deg - 30.0, delta=0.7)
            self.assertFalse(q["relative"])
            self.assertEqual(q["tolerance"], 1.5)
            self.assertIs(q["passed"], passed)

    def held_lab(self, tau_s, creep=0.0):
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\ndmax_m = 0.004\n')
        for b in (0.02, 0.032):
            held_plate_run(d, b, tau_s, creep=creep)
        return analysis.analyse(d)

    @staticmethod
    def with_shear_boxes(r):
        """`r` with three shear boxes (c 500 Pa, tan phi 0.6), enough for write_scm."""
        sigma = np.array([5e3, 1e4, 2e4])
        r.shears = [{"sigma_Pa": s, "peak": SimpleNamespace(tau_peak_Pa=500 + 0.6 * s),
                     "janosi": SimpleNamespace(K_m=1e-3)} for s in sigma]
        r.mc_peak = fits.fit_mohr_coulomb(sigma, [500 + 0.6 * s for s in sigma])
        return r

    def test_held_plates_relaxation_and_the_relaxed_bekker_fit(self):
        # Three holds per plate, relaxing to 80 % with tau 0.05 s in 0.5 s: each hold's stop depth,
        # relaxation and tau; the relaxed fit on the hold ends is the loading's Bekker curve x 0.8
        # (same n, kc and kphi x 0.8); the loading fit itself ignores the holds; the unloading
        # stiffness is taken from the end of the last hold.
        r = self.held_lab(0.05)
        self.assertEqual(sorted(r.holds), [0.02, 0.032])
        for b, hs in r.holds.items():
            self.assertEqual(len(hs), 3)
            np.testing.assert_allclose([h["z_m"] for h in hs], [0.02 / 3, 0.04 / 3, 0.02],
                                       rtol=1e-9)
            for h in hs:
                self.assertAlmostEqual(h["relaxation"], 1 - RELAXED, delta=0.01)
                self.assertAlmostEqual(h["fit"].tau_s, 0.05, delta=0.0025)
                self.assertTrue(h["fit"].converged)
                self.assertTrue(h["converged"])
                self.assertLess(abs(h["late_drop"]), 0.005)  # 0.2 e^-5 = 0.13 %
                self.assertAlmostEqual(h["hold_s"], 0.499, places=9)
        self.assertAlmostEqual(r.bekker.n, 1.1, places=3)
        rb = r.bekker_relaxed
        self.assertAlmostEqual(rb.n, 1.1, places=3)
        self.assertAlmostEqual(rb.kc / (RELAXED * 1e4), 1.0, delta=0.01)
        self.assertAlmostEqual(rb.kphi / (RELAXED * 5e5), 1.0, delta=0.01)
        for b, fit in r.unload.items():
            self.assertAlmostEqual(fit.Ke_Pa_m / KE_Pa_m, 1.0, delta=0.02, msg=f"b {b}")
        s = analysis.summary(r)["plate"]
        self.assertEqual(len(s["holds"]["b0.032"]), 3)
        for h in s["holds"]["b0.032"]:   # the synthetic pressure has no step at the stop
            self.assertLess(abs(h["step_at_stop"]), 0.01)
        self.assertTrue(s["relaxed"]["converged"])
        self.assertAlmostEqual(s["relaxed"]["n"], 1.1, places=3)
        self.assertIn(Path(r.directory) / "plate_holds.png", analysis.write_report(r))
        out = Path(tempfile.mkdtemp()) / "scm.toml"
        analysis.write_scm(self.with_shear_boxes(r), out, relaxed=True)
        data = tomllib.loads(out.read_text())
        self.assertAlmostEqual(data["bekker"]["kphi"] / (RELAXED * 5e5), 1.0, delta=0.01)
        self.assertIn("ends of holds of 0.499 s at 6 depths", data["source"]["bekker"]["n"])
        analysis.write_scm(r, out)   # the loading fit, as without holds
        self.assertAlmostEqual(tomllib.loads(out.read_text())["bekker"]["kphi"] / 5e5, 1.0,
                               delta=0.01)

    def test_relaxed_scm_file_refused_while_still_relaxing_or_without_holds(self):
        # A slow tail under a fast relaxation (15 % with tau 0.5 s in 0.5 s holds): one
        # exponential may fit it as done, but the pressure still falls by > 2 % of the moving
        # pressure over the hold's second half.
        r = self.held_lab(0.02, creep=0.15)
        self.assertTrue(any(r.holds.values()), "no hold analysed")
        for h in (h for hs in r.holds.values() for h in hs):
            self.assertGreater(h["late_drop"], analysis.HOLD_LATE_DROP_TOLERANCE)
            self.assertFalse(h["converged"])
        r = self.held_lab(2.0)   # tau 2 s in 0.5 s holds
        self.assertFalse(analysis.summary(r)["plate"]["relaxed"]["converged"])
        self.with_shear_boxes(r)
        out = Path(tempfile.mkdtemp()) / "scm.toml"
        with self.assertRaisesRegex(analysis.LabResultError, r"still relaxing at the end of their "
                                    r"holds \(b = 0.02 m at z = 6.67 mm;.*hold longer"):
            analysis.write_scm(r, out, relaxed=True)
        r = self.lab(False)
        r.mc_peak = True
        with self.assertRaisesRegex(analysis.LabResultError, r"no relaxed pressure-sinkage curve"):
            analysis.write_scm(r, out, relaxed=True)
        self.assertFalse(out.exists())

    def test_negative_cohesion_gives_c0_and_phi_through_the_origin(self):
        r = self.lab(False)
        sigma = np.array([5e3, 1e4, 2e4])
        tau = -300.0 + sigma * np.tan(np.radians(32.0))  # a non-cohesive soil's scatter
        r.shears = [{"sigma_Pa": s, "peak": SimpleNamespace(tau_peak_Pa=t),
                     "janosi": SimpleNamespace(K_m=1e-3)} for s, t in zip(sigma, tau)]
        r.mc_peak = fits.fit_mohr_coulomb(sigma, tau)
        self.assertAlmostEqual(r.mc_peak.friction_deg, 32.0, places=6)
        out = Path(tempfile.mkdtemp()) / "scm.toml"
        analysis.write_scm(r, out)
        data = tomllib.loads(out.read_text())
        phi_origin = np.degrees(np.arctan((sigma @ tau) / (sigma @ sigma)))
        self.assertEqual(data["mohr_coulomb"]["cohesion"], 0.0)
        # Written to scm_file.SIGNIFICANT_DIGITS (6) significant digits.
        self.assertEqual(data["mohr_coulomb"]["friction_angle"], float(f"{phi_origin:.6g}"))
        self.assertLess(phi_origin, 32.0)
        src = data["source"]["mohr_coulomb"]["cohesion"]
        self.assertIn("intercept was -300 Pa (< 0: no cohesion), so c = 0", src)

    def shear_summary(self, soil="synthetic", boxes=3, extra=("", "", "")):
        """A results.toml as `soil-lab report` writes it: c 1 kPa, phi 30 deg, K 10/20/30 mm;
        `extra`: more lines for each box."""
        d = Path(tempfile.mkdtemp())
        lines = [f'[soil]\nname = "{soil}"\n']
        for sigma, K, more in list(zip((5e3, 1e4, 2e4), (0.01, 0.02, 0.03), extra))[:boxes]:
            tau = 1e3 + sigma * np.tan(np.radians(30.0))
            lines.append(f"[[shear.stresses]]\nsigma_n_Pa = {sigma!r}\ntau_peak_Pa = {tau!r}\n"
                         f"janosi_K_m = {K!r}\n{more}")
        (d / "results.toml").write_text("\n".join(lines))
        return d

    def test_shear_boxes_from_another_lab_of_the_same_soil(self):
        # Plates pressed in a lab of their own (--plate-depth), shear boxes from the standard lab.
        r = self.lab(False)
        other = self.shear_summary()
        for where in (other, other / "results.toml"):
            shear = analysis.shear_strength_from(where, "synthetic")
            out = Path(tempfile.mkdtemp()) / "scm.toml"
            analysis.write_scm(r, out, shear=shear)
            data = tomllib.loads(out.read_text())
            self.assertAlmostEqual(data["mohr_coulomb"]["cohesion"], 1000.0, places=2)
            self.assertAlmostEqual(data["mohr_coulomb"]["friction_angle"], 30.0, places=4)
            self.assertAlmostEqual(data["janosi"]["shear_modulus"], 0.02, places=9)
            self.assertAlmostEqual(data["bekker"]["n"], r.bekker.n, places=5)
            for key in ("cohesion", "friction_angle"):
                self.assertIn(f"(the lab {where})", data["source"]["mohr_coulomb"][key])
            self.assertIn(f"(the lab {where})", data["source"]["janosi"]["shear_modulus"])

    def test_shear_from_is_refused_when_it_cannot_be_the_soils(self):
        r = self.lab(False)
        with self.assertRaisesRegex(analysis.LabResultError,
                                    "its soil is 'other', this lab's is 'synthetic'"):
            analysis.shear_strength_from(self.shear_summary("other"), "synthetic")
        with self.assertRaisesRegex(analysis.LabResultError, r"2 shear box\(es\).*need 3"):
            analysis.shear_strength_from(self.shear_summary(boxes=2), "synthetic")
        # Unstable boxes: the summary's verdict, or (older summaries) a Janosi tau_max <= 0.
        for extra in (("stable = true\n", "stable = false\n", "stable = true\n"),
                      ("", "janosi_tau_max_Pa = -50.0\n", "")):
            with self.assertRaisesRegex(analysis.LabResultError,
                                        r"unstable shear box\(es\) at 10 kPa"):
                analysis.shear_strength_from(self.shear_summary(extra=extra), "synthetic")
        with self.assertRaisesRegex(analysis.LabResultError, "neither shear box runs nor"):
            analysis.shear_strength_from(Path(tempfile.mkdtemp()), "synthetic")
        # Without shear boxes of its own or from another lab: named, with the way out.
        with self.assertRaisesRegex(analysis.LabResultError, "no shear box results.*--shear-from"):
            analysis.write_scm(r, Path(tempfile.mkdtemp()) / "scm.toml")
        # A lab with shear boxes of its own: the other lab's would silently replace them.
        r.mc_peak = fits.fit_mohr_coulomb([5e3, 1e4, 2e4], [4e3, 7e3, 12e3])
        shear = analysis.shear_strength_from(self.shear_summary(), "synthetic")
        with self.assertRaisesRegex(analysis.LabResultError, "has shear boxes of its own"):
            analysis.write_scm(r, Path(tempfile.mkdtemp()) / "scm.toml", shear=shear)

    def test_shear_boxes_run_under_another_name_are_taken_when_declared(self):
        # A trial later shipped under the soil's own name: its boxes were run as 'trial'.
        r = self.lab(False)
        summary = self.shear_summary("trial")
        with self.assertRaisesRegex(analysis.LabResultError,
                                    "its soil is 'trial', this lab's is 'synthetic'.*"
                                    "--shear-soil trial"):
            analysis.shear_strength_from(summary, "synthetic")
        with self.assertRaisesRegex(analysis.LabResultError,
                                    "its soil is 'trial', not the --shear-soil 'other'"):
            analysis.shear_strength_from(summary, "synthetic", "other")
        # an archive folder of boxes (--archive's: shear_s*/ with shear.csv and done.json, no
        # soil.toml) records no name: refused without --shear-soil, taken with it
        boxes = Path(tempfile.mkdtemp())
        for sigma in (5e3, 1e4, 2e4):
            syn.shear_run(boxes, sigma, c=1e3, phi_deg=30.0)
        with self.assertRaisesRegex(analysis.LabResultError, "records no soil name: give "
                                    "--shear-soil NAME.*'synthetic'"):
            analysis.shear_strength_from(boxes, "synthetic")
        for where in (summary, boxes):
            shear = analysis.shear_strength_from(where, "synthetic", "trial")
            self.assertEqual(shear.declared_soil, "trial")
            out = Path(tempfile.mkdtemp()) / "scm.toml"
            analysis.write_scm(r, out, shear=shear)
            data = tomllib.loads(out.read_text())
            # the synthetic boxes' peaks: 5 % running means of Janosi curves at 1 - exp(-10)
            self.assertAlmostEqual(data["mohr_coulomb"]["friction_angle"], 30.0, delta=0.05)
            self.assertAlmostEqual(data["mohr_coulomb"]["cohesion"], 1000.0, delta=20.0)
            self.assertIn(f"(the lab {where}: its soil 'trial', the same recipe under another "
                          "name as declared with --shear-soil)",
                          data["source"]["mohr_coulomb"]["friction_angle"])
        # declaring the soil's own name changes nothing
        self.assertEqual(analysis.shear_strength_from(self.shear_summary(), "synthetic",
                                                      "synthetic").declared_soil, "")
        # a folder with fewer than 3 stresses
        two = Path(tempfile.mkdtemp())
        for sigma in (5e3, 1e4):
            syn.shear_run(two, sigma)
        with self.assertRaisesRegex(analysis.LabResultError, "fewer than 3 finished shear boxes"):
            analysis.shear_strength_from(two, "synthetic", "trial")

    def test_particles_lost_from_the_shear_box_are_counted_and_reported(self):
        # A log as in.lab_shear writes it: an earlier thermo block (the consolidation's settle),
        # then the shear's, then LIGGGHTS' loop summary.
        rows = "\n".join(f"{100 * i:8d} {n:8d} {j:12.6g} 1000 5000 0.3"
                          for i, (n, j) in enumerate(zip([1000] * 6 + [995, 990, 960, 900],
                                                         np.linspace(0.0, 0.09, 10))))
        log = ("    Step    Atoms        soil_ke       ke_ratio\n       0     1000  1e-3  0.5\n"
               "Loop time of 1.0 on 1 procs for 0 steps with 1000 atoms\n"
               "    Step    Atoms              j            tau          sigma          lid_z \n"
               f"{rows}\nLoop time of 2.0 on 1 procs for 900 steps with 900 atoms\n")
        counts = analysis.shear_particle_counts(log)
        self.assertEqual(len(counts[0]), 10)
        early = analysis.shear_particle_loss(counts, 0.04)  # the peak before any loss
        self.assertEqual((early["particles"], early["lost_by_peak"]), (1000, 0.0))
        self.assertAlmostEqual(early["lost_at_end"], 0.1)
        late = analysis.shear_particle_loss(counts, 0.07)  # the row at j = 0.07: 990 left
        self.assertAlmostEqual(late["lost_by_peak"], 0.01)
        self.assertIsNone(analysis.shear_particle_counts("no thermo here\n"))

        def box(loss, j_peak=0.05):
            return {"sigma_Pa": 1e4, "loss": loss, "peak": SimpleNamespace(j_peak_m=j_peak)}
        warn = analysis.shear_loss_warnings([box(early), box(None),
                                             box({**late, "lost_by_peak": 0.02}, 0.07)])
        self.assertEqual(len(warn), 2)
        self.assertIn("10.0 % of its 1000 particles had left the box by the end", warn[0])
        self.assertIn("2.0 % of its 1000 particles had left the box by the peak (j 0.07 m", warn[1])
        self.assertEqual(analysis.shear_loss_warnings([box({**early, "lost_at_end": 0.005})]), [])

    def test_a_box_sheared_before_it_consolidated_is_named(self):
        # 100 consolidation rows, then 1000 shear rows; the lid sinks 2 mm over the shear.
        t = np.arange(1100) * 1e-3
        phase = np.where(np.arange(1100) < 100, 1, 2)
        lid = 0.2 - 0.002 * np.clip(t - 0.1, 0, None) / 0.999
        loaded = np.full(1100, 1e4)
        late = np.where(t < 0.2, 1.5e3, 1e4)  # the lid loads the sample 0.1 s into the shear
        good = analysis.shear_consolidation(t, loaded, lid, phase)
        self.assertAlmostEqual(good["consolidation_s"], 0.1)
        self.assertAlmostEqual(good["sigma_start_ratio"], 1.0)
        self.assertAlmostEqual(good["lid_z_start_m"], 0.2)
        self.assertAlmostEqual(good["lid_travel_m"], -0.002, places=6)
        self.assertFalse(good["not_consolidated"])
        bad = analysis.shear_consolidation(t, late, lid, phase)
        self.assertAlmostEqual(bad["sigma_start_ratio"], 1.5e3 / np.mean(late[100:]))
        creeping = analysis.shear_consolidation(
            t, loaded, lid, phase, "soil-lab: shear: WARNING: not consolidated after 3.0 s")
        self.assertTrue(creeping["not_consolidated"])

        def box(c):
            return {"sigma_Pa": 1e4, "consolidation": c}
        warn = analysis.shear_consolidation_warnings([box(good), box(bad), box(creeping), {}])
        self.assertEqual(len(warn), 2)
        self.assertIn("the shear began at 16 % of the normal stress (after 0.1 s", warn[0])
        self.assertIn("still settled when the shear began", warn[1])
        self.assertIn("its lid moved -2 mm over the shear (sample 200 mm high)", warn[1])

    def test_the_samples_density_under_the_lid(self):
        # Two synthetic boxes (box 0.1 m, lid 0.05 m above the floor throughout) on a bed of
        # 0.4 kg in a 0.1 x 0.1 m bin: 0.4 / (0.01 * 0.05) = 800 kg/m3; a lab without the bed's
        # record, and a box of another side, get none.
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\ndmax_m = 0.004\n')
        for sigma in (5e3, 1e4, 2e4):
            syn.shear_run(d, sigma)
        r = analysis.analyse(d)
        self.assertIsNone(r.shear_bed_bulk_density)
        self.assertNotIn("sample_bulk_density_kg_m3", r.shears[0]["consolidation"])
        bed = d / "beds" / "shear"
        bed.mkdir(parents=True)
        (bed / "done.json").write_text(json.dumps({"result": {
            "particle_mass": "0.4", "bin_length": "0.1", "bin_width": "0.1", "spheres": "500",
            "bulk_density": "760.5"}}))
        r = analysis.analyse(d)
        self.assertEqual(r.shear_bed_bulk_density, 760.5)
        for s in r.shears:
            self.assertAlmostEqual(s["consolidation"]["sample_bulk_density_kg_m3"], 800.0)
            self.assertAlmostEqual(s["consolidation"]["sample_bulk_density_end_kg_m3"], 800.0)
        s = analysis.summary(r)["shear"]
        self.assertEqual(s["bed_bulk_density_kg_m3"], 760.5)
        self.assertAlmostEqual(s["stresses"][1]["sample_bulk_density_kg_m3"], 800.0)
        # the lid rises 5 mm over the shear and 10 % of 500 particles (450 at the start) leave
        c = {"lid_z_start_m": 0.05, "lid_travel_m": 0.005}
        box = {"consolidation": c, "done": {"meta": {"box_m": 0.1}},
               "loss": {"particles": 450, "lost_by_peak": 0.0, "lost_at_end": 0.1}}
        other = {"consolidation": c, "done": {"meta": {"box_m": 0.2}}}
        rho, boxes = analysis.shear_sample_density([box, other], bed)
        self.assertAlmostEqual(boxes[0][0], 0.4 * 0.9 / (0.01 * 0.05))
        self.assertAlmostEqual(boxes[0][1], 0.4 * 0.9 * 0.9 / (0.01 * 0.055))
        self.assertIsNone(boxes[1])

    def test_shear_thermo_blocks_of_the_consolidation_checks_are_all_read(self):
        # in.lab_shear runs its consolidation in checks: one thermo block per LIGGGHTS run.
        head = "    Step    Atoms              j            tau          sigma          lid_z \n"
        log = (head + "       0     1000 0 0 0 0.2\n     100     1000 0 0 0 0.2\n"
               "Loop time of 1.0 on 1 procs for 100 steps with 1000 atoms\n"
               + head + "     100     1000 0 0 0 0.2\n     200      990 0.01 0 0 0.2\n"
               "Loop time of 1.0 on 1 procs for 100 steps with 990 atoms\n")
        j, n = analysis.shear_particle_counts(log)
        self.assertEqual(list(n), [1000, 1000, 1000, 990])
        self.assertAlmostEqual(j[-1], 0.01)

    def test_too_few_shear_boxes_for_mohr_coulomb_are_named(self):
        def boxes(*targets):
            return [{"sigma_target_Pa": t} for t in targets]
        self.assertEqual(analysis.shear_count_warnings([]), [])
        self.assertEqual(analysis.shear_count_warnings(boxes(5e3, 1e4, 2e4)), [])
        warn = analysis.shear_count_warnings(boxes(5e3, 1e4))
        self.assertEqual(len(warn), 1)
        self.assertIn("only 2 shear box(es) finished", warn[0])
        self.assertIn("c and phi are not fitted", warn[0])
        # replicates of a stress count once: four boxes at two stresses are not enough
        warn = analysis.shear_count_warnings(boxes(5e3, 1e4, 5e3, 1e4))
        self.assertIn("only 4 shear box(es) finished, at 2 normal stress(es)", warn[0])

    def test_replicate_boxes_give_the_scatter_per_stress_and_of_each_beds_fit(self):
        # Three beds (--shear-replicates 3): the second bed's boxes 10 % stronger, the third's
        # 10 % weaker, on a soil of c 1 kPa, phi 30 deg. Each bed's own fit: phi and c scaled by
        # 1.1 / 0.9 (tan phi 10 % up / down: 32.42 / 27.46 deg); per stress the peaks' sd is
        # 10 % of the middle one and the spread 20 %. The pooled fit over all nine points is the
        # soil's, with a standard error from the beds' scatter; the half-speed box of the first
        # bed, 4 % weaker, lies 0.4 sd from the mean of the three same-speed boxes.
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\n'
                                     'dmax_m = 0.004\n')
        for k, scale in ((1, 1.0), (2, 1.1), (3, 0.9)):
            for sigma in (5e3, 1e4, 2e4):
                syn.shear_run(d, sigma, tau_scale=scale, replicate=k)
        syn.shear_run(d, 1e4, name="shear_s10000_half", tau_scale=0.96)
        r = analysis.analyse(d)
        self.assertEqual(len(r.shears), 9)
        self.assertEqual([s["replicate"] for s in r.shears[:3]], [1, 2, 3])
        self.assertAlmostEqual(r.mc_peak.friction_deg, 30.0, delta=0.05)
        self.assertAlmostEqual(r.mc_peak.cohesion_Pa, 1e3, delta=20)
        self.assertGreater(r.mc_peak.friction_se_deg, 0.5)
        rep = r.replicates
        self.assertEqual(rep["replicates"], [1, 2, 3])
        self.assertEqual(rep["fitted_replicates"], [1, 2, 3])
        for got, scale in zip(rep["friction_deg"], (1.0, 1.1, 0.9)):
            self.assertAlmostEqual(got, np.degrees(np.arctan(scale * np.tan(np.radians(30)))),
                                   delta=0.05)
        for got, scale in zip(rep["cohesion_Pa"], (1.0, 1.1, 0.9)):
            self.assertAlmostEqual(got, scale * 1e3, delta=20)
        self.assertAlmostEqual(rep["friction_sd_deg"], np.std(rep["friction_deg"], ddof=1))
        for b in rep["by_stress"]:
            self.assertEqual(b["boxes"], 3)
            self.assertAlmostEqual(b["tau_peak_sd_Pa"] / b["tau_peak_mean_Pa"], 0.1, delta=0.002)
            self.assertAlmostEqual(b["tau_peak_spread"], 0.2, delta=0.004)
        # a warning about a replicate's box names its bed: the second bed's 10 kPa box still
        # rising at the end of its travel
        rising = dict(r.shears[4], j=np.linspace(0, 0.01, 100), tau=np.linspace(1e3, 8e3, 100))
        self.assertEqual(rising["replicate"], 2)
        warn, = analysis.shear_peak_warnings([rising])
        self.assertTrue(warn.startswith("shear box at 10 kPa (bed 2): the shear stress still "
                                        "rises"), warn)
        q, = r.quasi_static
        self.assertEqual(r.paired_speed_checks, [])   # one bed's half-speed box: no pairs to pool
        np.testing.assert_allclose(q["replicate_differences"], [0.1, -0.1], atol=2e-3)
        # against the three same-speed boxes (mean 1.0, sd 0.1 of the first): -4 %, -0.4 sd
        self.assertAlmostEqual(q["half_speed_from_mean"], -0.04, delta=1e-3)
        self.assertAlmostEqual(q["half_speed_sds_from_mean"], -0.4, delta=0.01)
        self.assertAlmostEqual(q["replicate_peak_sd_Pa"] / q["replicate_peak_mean_Pa"], 0.1,
                               delta=1e-3)
        s = analysis.summary(r)
        self.assertEqual(s["shear"]["replicates"]["fitted_replicates"], [1, 2, 3])
        self.assertEqual([b.get("replicate", 1) for b in s["shear"]["stresses"][:3]], [1, 2, 3])
        self.assertEqual(s["quasi_static"]["shear_s10000"]["replicate_differences"],
                         q["replicate_differences"])
        self.assertIn("friction_se_deg", s["shear"])
        # results.csv flattens the replicate table
        analysis.write_report(r)
        rows = {(t, q): float(v) for t, q, v in
                (line.split(",") for line in (d / "results.csv").read_text().splitlines()[1:])}
        self.assertAlmostEqual(rows["shear", "bed2_friction_deg"], rep["friction_deg"][1], places=3)
        self.assertAlmostEqual(rows["shear", "replicates_friction_sd_deg"],
                               rep["friction_sd_deg"], places=3)
        self.assertAlmostEqual(rows["shear", "replicates_s10000_tau_peak_spread"], 0.2, delta=0.004)
        # each bed's sample density from its own bed's record
        for k, mass in ((1, "0.4"), (2, "0.44")):
            bed = d / "beds" / plan.shear_bed_name(k)
            bed.mkdir(parents=True)
            (bed / "done.json").write_text(json.dumps({"result": {
                "particle_mass": mass, "bin_length": "0.1", "bin_width": "0.1",
                "spheres": "500", "bulk_density": "760.5"}}))
        r = analysis.analyse(d)
        rho = {s["replicate"]: s["consolidation"].get("sample_bulk_density_kg_m3")
               for s in r.shears}
        self.assertAlmostEqual(rho[1], 800.0)
        self.assertAlmostEqual(rho[2], 880.0)
        self.assertIsNone(rho[3])   # no record of the third bed
        # a lab without replicates has no replicate summary
        self.assertIsNone(analysis.shear_replicates([s for s in r.shears if s["replicate"] == 1]))

    def test_the_speed_check_over_beds_pairs_each_beds_boxes(self):
        # Three beds 0 / +10 / -10 % strong, each with its middle box at half speed -4 / -2 / -6 %
        # weaker than its own bed's: the bed-to-bed scatter (10 %) leaves the pairs; mean -4 %,
        # sd 2 %, standard error 2 / sqrt 3 = 1.155 %, 95 % interval -4 +- 4.303 x 1.155 =
        # -8.97 .. +0.97 %: it straddles -5 %, so "cannot tell" (the mean alone passes 5 %).
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\n'
                                     'dmax_m = 0.004\n')
        for k, scale, half in ((1, 1.0, 0.96), (2, 1.1, 0.98), (3, 0.9, 0.94)):
            for sigma in (5e3, 1e4, 2e4):
                syn.shear_run(d, sigma, tau_scale=scale, replicate=k)
            name = "shear_s10000" + ("" if k == 1 else f"_r{k}") + "_half"
            syn.shear_run(d, 1e4, name=name, tau_scale=scale * half, replicate=k)
        r = analysis.analyse(d)
        self.assertEqual([q["run"] for q in r.quasi_static],
                         ["shear_s10000", "shear_s10000_r2", "shear_s10000_r3"])
        c, = r.paired_speed_checks
        self.assertEqual((c["beds"], c["replicates"], c["sigma_target_Pa"]), (3, [1, 2, 3], 1e4))
        np.testing.assert_allclose(c["differences"], [-0.04, -0.02, -0.06], atol=1e-3)
        self.assertAlmostEqual(c["mean_difference"], -0.04, delta=1e-3)
        self.assertAlmostEqual(c["sem_difference"], 0.02 / np.sqrt(3), delta=1e-3)
        self.assertAlmostEqual(c["interval_low"], -0.0897, delta=2e-3)
        self.assertAlmostEqual(c["interval_high"], 0.0097, delta=2e-3)
        self.assertEqual((c["verdict"], c["passed"]), ("cannot tell", True))
        s = analysis.summary(r)
        self.assertEqual(s["quasi_static_paired"]["shear_s10000"]["verdict"], "cannot tell")
        self.assertEqual(s["quasi_static_paired"]["shear_s10000"]["runs"],
                         ["shear_s10000", "shear_s10000_r2", "shear_s10000_r3"])
        analysis.write_report(r)
        rows = {(t, q): float(v) for t, q, v in
                (line.split(",") for line in (d / "results.csv").read_text().splitlines()[1:])}
        self.assertAlmostEqual(rows["quasi_static_paired", "shear_s10000_mean_difference"],
                               c["mean_difference"], places=5)
        # the verdicts: an interval within +-5 %, one wholly outside it; a single bed is refused
        ok = analysis.paired_check([-0.01, 0.0, 0.01], 0.05)
        self.assertEqual(ok["verdict"], "quasi-static")
        self.assertAlmostEqual(ok["interval_high"], 4.303 * 0.01 / np.sqrt(3), places=6)
        rate = analysis.paired_check([-0.12, -0.10, -0.14], 0.05)
        self.assertEqual((rate["verdict"], rate["passed"]), ("rate effect", False))
        self.assertEqual(analysis.paired_check([0.20, 0.08], 0.05)["verdict"],
                         "cannot tell")   # two beds: t 12.7, a wide interval
        with self.assertRaisesRegex(ValueError, "2..5 beds, got 1"):
            analysis.paired_check([0.01], 0.05)

    def test_the_time_step_check_over_beds_pairs_each_beds_boxes(self):
        # Three beds 0 / +10 / -10 % strong, each with its middle box at half the step +12 / +10
        # / +14 % stronger than its own bed's: mean +12 %, sd 2 %, 95 % interval 12 +- 4.303 x
        # 1.155 = +7.03 .. +16.97 %, wholly outside +-5 %: "step effect". The same beds at
        # +1 / 0 / -1 %: "step-converged". The speed check's verdict words are not used.
        for steps, verdict, low in (((1.12, 1.10, 1.14), "step effect", 0.0703),
                                    ((1.01, 1.00, 0.99), "step-converged", -0.0248)):
            d = Path(tempfile.mkdtemp())
            (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\n'
                                         'dmax_m = 0.004\n')
            for k, scale, step in zip((1, 2, 3), (1.0, 1.1, 0.9), steps):
                for sigma in (5e3, 1e4, 2e4):
                    syn.shear_run(d, sigma, tau_scale=scale, replicate=k)
                name = "shear_s10000" + ("" if k == 1 else f"_r{k}") + "_halfdt"
                syn.shear_run(d, 1e4, name=name, tau_scale=scale * step, replicate=k)
                record = json.loads((d / name / "done.json").read_text())
                record.update(dt_s=5e-6, meta={**record["meta"], "dt_factor": 0.5})
                (d / name / "done.json").write_text(json.dumps(record))
            r = analysis.analyse(d)
            self.assertEqual((r.quasi_static, r.paired_speed_checks), ([], []))
            self.assertEqual([(q["run"], q["replicate"], q["half_dt_s"]) for q in r.time_step],
                             [("shear_s10000", 1, 5e-6), ("shear_s10000_r2", 2, 5e-6),
                              ("shear_s10000_r3", 3, 5e-6)])
            c, = r.paired_step_checks
            self.assertEqual((c["beds"], c["replicates"], c["sigma_target_Pa"]), (3, [1, 2, 3], 1e4))
            np.testing.assert_allclose(c["differences"], np.array(steps) - 1, atol=1e-3)
            self.assertAlmostEqual(c["interval_low"], low, delta=2e-3)
            self.assertEqual(c["verdict"], verdict)
            s = analysis.summary(r)
            self.assertEqual(s["time_step_paired"]["shear_s10000"]["verdict"], verdict)
            self.assertNotIn("quasi_static_paired", s)
            analysis.write_report(r)
            rows = {(t, q): float(v) for t, q, v in
                    (line.split(",") for line in (d / "results.csv").read_text().splitlines()[1:])}
            self.assertAlmostEqual(rows["time_step_paired", "shear_s10000_interval_low"],
                                   c["interval_low"], places=5)

    def test_an_unstable_shear_box_is_named(self):
        j = np.linspace(0.0, 0.008, 400)
        good = 1000.0 * (1.0 - np.exp(-j / 0.002))
        bad = good - 2400.0 * np.sin(j / 0.008 * 3 * np.pi) ** 2  # swings to -1.4 kPa

        def box(tau, tau_max):
            return {"sigma_Pa": 2.5e3, "tau": tau,
                    "peak": SimpleNamespace(tau_peak_Pa=float(np.max(tau))),
                    "janosi": SimpleNamespace(tau_max_Pa=tau_max)}
        self.assertEqual(analysis.shear_stability_errors([box(good, 1000.0)]), [])
        err = analysis.shear_stability_errors([box(good, 1000.0), box(bad, 800.0),
                                               box(good, -400.0)])
        self.assertEqual(len(err), 2)
        self.assertIn("shear box at 2.5 kPa: unstable: the shear stress reached -1", err[0])
        self.assertIn("Janosi tau_max -400 Pa", err[1])

    def test_a_shear_box_still_rising_at_the_end_is_named(self):
        # Box side 0.24 m, travel 0.06 m (0.25 L), 3000 samples.
        j = np.linspace(0.0, 0.06, 3000)
        # Straight line: last quarter's mean 0.875, the quarter before 0.625 of the peak: +25 %.
        self.assertAlmostEqual(analysis.shear_rise_at_end(j, 8000.0 * j / 0.06), 0.25, places=3)
        # Levelled off (Janosi, K 4 mm) with stick-slip waves of 12 % and a grain's length (10 mm):
        # the quarters differ by the waves' share only, under the 8 % threshold.
        level = 4000.0 * (1.0 - np.exp(-j / 0.004)) * (1.0 + 0.12 * np.sin(2 * np.pi * j / 0.01))
        # A peak at 0.02 m, then softening to 70 %: falling at the end.
        soft = np.interp(j, [0.0, 0.02, 0.04, 0.06], [0.0, 5000.0, 3500.0, 3500.0])

        def box(tau, sigma=1e4):
            return {"sigma_Pa": sigma, "j": j, "tau": tau, "done": {"meta": {"box_m": 0.24}}}
        self.assertLess(abs(analysis.shear_rise_at_end(j, level)), 0.08)
        self.assertLess(analysis.shear_rise_at_end(j, soft), 0.0)
        warn = analysis.shear_peak_warnings([box(level), box(8000.0 * j / 0.06, 2e4), box(soft)])
        self.assertEqual(len(warn), 1)
        self.assertIn("shear box at 20 kPa: the shear stress still rises at the end of the travel "
                      "(its last quarter, to j 0.06 m, 25.0 % of the peak", warn[0])
        self.assertIn("longer travel than 0.25 of the box side", warn[0])
        self.assertEqual(analysis.shear_peak_warnings([{"sigma_Pa": 1e4, "j": None, "tau": None}]),
                         [])

    def test_shear_peak_is_smoothed_and_the_residual_is_the_raw_curves(self):
        # A curve that levels off at 10 kPa well before the end, with +-1 kPa of fast noise: the
        # residual (last 20 %) is the plateau's raw mean; the peak, a running mean over 5 % of the
        # points, is near the plateau (not the noise's maximum, 11 kPa). A running mean
        # zero-padded at the ends (the lab until 2026-11-27) read the residual ~3 % low.
        j = np.linspace(0.0, 0.06, 4000)
        noise = 1000.0 * np.sin(2 * np.pi * np.arange(j.size) / 7.0)
        tau = 10000.0 * (1.0 - np.exp(-j / 0.004)) + noise
        r = analysis.shear_peak_and_residual(j, tau)
        plateau = tau[j >= 0.048]
        self.assertAlmostEqual(r.tau_residual_Pa, plateau.mean(), delta=1e-9 * 1e4)
        self.assertAlmostEqual(r.tau_residual_Pa, 10000.0, delta=30.0)
        self.assertGreater(r.tau_peak_Pa, 9950.0)
        self.assertLess(r.tau_peak_Pa, 10150.0)
        # still rising at the end: the peak is the last full window's mean, centred inside it
        rising = 8000.0 * j / 0.06
        r = analysis.shear_peak_and_residual(j, rising)
        w = int(j.size * 0.05)
        self.assertAlmostEqual(r.tau_peak_Pa, rising[-w:].mean(), delta=1e-6)
        self.assertAlmostEqual(r.j_peak_m, j[-w + w // 2], delta=1e-12)

    def test_only_the_bed_hold_record_of_the_bed_as_it_is_is_reported(self):
        d = Path(tempfile.mkdtemp())
        (d / "soil.toml").write_text('name = "synthetic"\npreset = "standard"\ndmax_m = 0.004\n')
        bed = d / "beds" / "plate"
        (bed / "hold").mkdir(parents=True)
        (bed / "done.json").write_text(json.dumps(
            {"inputs": "bed-A", "wall_s": 10.0,
             "result": {"bulk_density": "1000", "porosity": "0.5", "bed_depth": "0.1"}}))
        hold = {"hold_s": 0.2, "zcm_start_m": 0.05, "zcm_end_m": 0.04998, "settlement": 0.0004,
                "settlement_last_quarter": 1e-4, "sink_rate_m_s": 1e-4}

        def record(bed_inputs):
            (bed / "hold" / "done.json").write_text(json.dumps(
                {"inputs": "k", "bed_inputs": bed_inputs, "wall_s": 4.0, "result": hold}))
            return analysis.analyse(d)
        r = record("bed-A")
        self.assertEqual(r.bed_holds, {"plate": hold})
        self.assertEqual(r.bed_costs, {"plate": 10.0, "plate/hold": 4.0})
        self.assertEqual(analysis.summary(r)["bed_hold"], {"plate": hold})
        r = record("bed-B")  # the check of an earlier preparation of this bed: not this bed's
        self.assertEqual((r.bed_holds, r.bed_costs), ({}, {"plate": 10.0}))
        self.assertNotIn("bed_hold", analysis.summary(r))


if __name__ == "__main__":
    unittest.main()
