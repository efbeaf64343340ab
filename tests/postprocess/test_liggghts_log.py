"""wheelsim_post.liggghts_log: the run summaries and the thermo tables of a LIGGGHTS screen output,
as LIGGGHTS 3.8 prints them (a bed's settle runs then a wheel run), in order, with their numbers."""
import unittest

from wheelsim_post.liggghts_log import Loop, Thermo, loops, merged, thermo

SCREEN = """\
Setting up run ...
    Step    Atoms         KinEng
       0    11624              0
Loop time of 1.23456 on 2 procs for 500 steps with 11624 atoms

Pair  time (%) = 0.8 (64.8)
Loop time of 0.5 on 2 procs for 0 steps with 11624 atoms
soilbin: particles = 11624
Loop time of 7.5e+01 on 1 procs for 2000 steps with 11580 atoms
"""


class Loops(unittest.TestCase):
    def test_every_run_in_order_with_its_numbers(self):
        self.assertEqual(loops(SCREEN), [Loop(1.23456, 2, 500, 11624), Loop(0.5, 2, 0, 11624),
                                         Loop(75.0, 1, 2000, 11580)])

    def test_fields_by_name(self):
        last = loops(SCREEN)[-1]
        self.assertEqual((last.seconds, last.procs, last.steps, last.atoms), (75.0, 1, 2000, 11580))

    def test_no_run_gives_an_empty_list(self):
        self.assertEqual(loops("ERROR: Unknown command\n"), [])


# As LIGGGHTS 3.8 prints them (tests/active_domain's restart run, shortened): a settle check's
# table, a warning, the wheel run's table with a warning inside it, the next run's "Loop time".
TABLES = """\
    Step    Atoms        soil_ke       ke_ratio       rot_rati 
    6545     3844  4.0175074e-07  9.0999104e-06   4.413405e-05 
Loop time of 8.11e-07 on 2 procs for 0 steps with 3844 atoms, finish time Sat Nov 28 05:01:37 2026
WARNING: New thermo_style command, previous thermo_modify settings will be lost (./src/output.cpp:725)
    Step    Atoms             fx             fz       wheel[10 
    6545     3844 0 0 0.133375784111655 
    6546     3844 -1.5e-3 2.25 0.133365993247265 
WARNING: Less insertions than requested (../fix_insert.cpp:790)
    6547     3844 -2 4 0.13 
Loop time of 1.04224 on 2 procs for 2 steps with 3844 atoms, finish time Sat Nov 28 05:01:38 2026
    1 2 3 4 5
"""


class ThermoTables(unittest.TestCase):
    def test_every_table_in_order_with_its_columns(self):
        tables = thermo(TABLES)
        self.assertEqual([t.columns for t in tables],
                         [["Step", "Atoms", "soil_ke", "ke_ratio", "rot_rati"],
                          ["Step", "Atoms", "fx", "fz", "wheel[10"]])
        self.assertEqual(tables[0].rows, [[6545, 3844, 4.0175074e-07, 9.0999104e-06, 4.413405e-05]])

    def test_a_warning_inside_a_table_is_skipped_and_loop_time_ends_it(self):
        wheel = thermo(TABLES)[1]
        self.assertEqual([r[0] for r in wheel.rows], [6545, 6546, 6547])  # not the "1 2 3 4 5" after it
        self.assertEqual(wheel.rows[1], [6546, 3844, -1.5e-3, 2.25, 0.133365993247265])

    def test_a_column_by_name_and_a_clear_error_for_a_missing_one(self):
        wheel = thermo(TABLES)[1]
        self.assertEqual(wheel.column("fz"), {6545: 0.0, 6546: 2.25, 6547: 4.0})
        with self.assertRaisesRegex(KeyError, "thermo column 'ty' not in"):
            wheel.column("ty")

    def test_a_line_of_words_as_wide_as_the_header_ends_the_table(self):
        t = thermo("Step Atoms fx\n1 10 0.5\nsoilbin: particles = 10\nx y z\n2 10 0.7\n")
        self.assertEqual(t, [Thermo(["Step", "Atoms", "fx"], [[1, 10, 0.5]])])

    def test_no_table_gives_an_empty_list(self):
        self.assertEqual(thermo(SCREEN.replace("Step", "step")), [])


class Merged(unittest.TestCase):
    TWO_RUNS = TABLES + TABLES.split("WARNING: New thermo_style")[1].replace("6545", "6548") \
        .replace("6546", "6549").replace("6547", "6550")

    def test_the_rows_of_every_run_with_the_column_under_one_header(self):
        t = merged(self.TWO_RUNS, "fx")
        self.assertEqual(t.columns, ["Step", "Atoms", "fx", "fz", "wheel[10"])
        self.assertEqual([r[0] for r in t.rows], [6545, 6546, 6547, 6548, 6549, 6550])
        self.assertEqual(t.values("fz"), [0.0, 2.25, 4.0, 0.0, 2.25, 4.0])

    def test_a_clear_error_for_a_column_no_table_has(self):
        with self.assertRaisesRegex(ValueError, "no thermo table with a 'ty' column"):
            merged(TABLES, "ty")

    def test_tables_that_differ_in_their_columns_are_an_error(self):
        with self.assertRaisesRegex(ValueError, "differ"):
            merged("Step Atoms fx\n1 10 0.5\nLoop time of\nStep fx\n2 0.7\n", "fx")


if __name__ == "__main__":
    unittest.main()
