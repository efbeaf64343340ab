"""wheelsim_post.bed_hold: in.bedhold's printed lines read into the check's result (known
settlements), and its verdicts at and around the limits (docs/soil-bins.md "The bed-hold check")."""
import unittest

from wheelsim_post import bed_hold


def screen(zcm, t_end=0.2, ztop=0.05):
    """in.bedhold's output with the centre of mass heights `zcm` (5 values) at quarters 0..4."""
    lines = ["    Step    Atoms       bedhold_", "Loop time of 0.1 on 1 procs for 0 steps"]
    for q, z in enumerate(zcm):
        lines.append(f"bedhold: quarter={q} t={t_end * q / 4!r} zcm={z!r} ztop={ztop!r}")
    return "\n".join(lines) + "\n"


class Parse(unittest.TestCase):
    def test_settlements_over_the_hold_and_its_last_quarter(self):
        r = bed_hold.parse(screen([0.100, 0.099, 0.098, 0.097, 0.095]))
        self.assertAlmostEqual(r["settlement"], 0.05, places=12)
        self.assertAlmostEqual(r["settlement_last_quarter"], 1 - 0.095 / 0.097, places=12)
        self.assertEqual((r["zcm_start_m"], r["zcm_end_m"], r["hold_s"]), (0.100, 0.095, 0.2))
        self.assertEqual((r["ztop_start_m"], r["ztop_end_m"]), (0.05, 0.05))
        self.assertAlmostEqual(r["sink_rate_m_s"], 0.002 / 0.05, places=12)  # last quarter
        self.assertIn("(sinking 40 mm/s)", bed_hold.describe(r))

    def test_a_bed_that_rises_settles_negatively(self):
        r = bed_hold.parse(screen([0.1, 0.1, 0.1, 0.1, 0.101]))
        self.assertAlmostEqual(r["settlement"], -0.01, places=12)
        self.assertIsNone(bed_hold.failure(r, "b", "log"))

    def test_a_garbled_line_is_an_error_naming_the_log(self):
        text = screen([0.1] * 5).replace("zcm=0.1 ztop", "zcm ztop", 1)
        with self.assertRaisesRegex(bed_hold.BedHoldError, r"not of the form.*x\.log"):
            bed_hold.parse(text, "x.log")
        with self.assertRaisesRegex(bed_hold.BedHoldError, r"not of the form"):
            bed_hold.parse(screen([0.1] * 5).replace("ztop=", "top=", 1))

    def test_a_cut_output_names_the_count_and_the_log(self):
        text = "".join(screen([0.1] * 5).splitlines(keepends=True)[:5])
        with self.assertRaisesRegex(bed_hold.BedHoldError, r"printed 3 of its 5 lines.*x\.log"):
            bed_hold.parse(text, "x.log")

    def test_times_that_do_not_increase_are_an_error(self):
        with self.assertRaisesRegex(bed_hold.BedHoldError, "do not increase"):
            bed_hold.parse(screen([0.1] * 5, t_end=0.0))

    def test_a_centre_of_mass_under_the_floor_is_an_error(self):
        with self.assertRaisesRegex(bed_hold.BedHoldError, "at or below the floor"):
            bed_hold.parse(screen([0.1, 0.05, 0.0, -0.01, -0.02]))


class Verdict(unittest.TestCase):
    def result(self, settlement):
        return bed_hold.parse(screen([0.1, 0.1, 0.1, 0.1, 0.1 * (1 - settlement)]))

    def test_limits(self):
        self.assertEqual(bed_hold.verdict(self.result(0.005)), "holds")
        self.assertEqual(bed_hold.verdict(self.result(0.02)), "settles, within the limit")
        self.assertIsNone(bed_hold.failure(self.result(0.0299), "b", "log"))
        msg = bed_hold.failure(self.result(0.11), "plate", "beds/plate/hold/liggghts.log")
        self.assertRegex(msg, r"^bed 'plate' does not hold under the soil's test settings: "
                              r"centre of mass 0\.1 -> 0\.089 m \(-11\.00 %\)")
        self.assertIn("Preparing the bed with other contact settings", msg)
        self.assertIn("beds/plate/hold/liggghts.log", msg)

    def test_a_bed_that_rises_beyond_the_limit_fails_too(self):
        self.assertEqual(bed_hold.verdict(self.result(-0.02)), "rises, within the limit")
        msg = bed_hold.failure(self.result(-0.05), "shear", "log")
        self.assertRegex(msg, r"^bed 'shear' does not hold under the soil's test settings: it "
                              r"rises, centre of mass 0\.1 -> 0\.105 m \(\+5\.00 %\)")

    def test_an_unsettled_bed_is_told_so(self):
        msg = bed_hold.failure(self.result(0.4), "my_sand", "bedhold.log", settled=False)
        self.assertRegex(msg, r"^bed 'my_sand' had not settled when it was prepared")
        self.assertIn("--bed-hold 0", msg)
        self.assertIsNone(bed_hold.failure(self.result(0.01), "my_sand", "log", settled=False))


if __name__ == "__main__":
    unittest.main()
