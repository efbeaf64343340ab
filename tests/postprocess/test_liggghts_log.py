"""wheelsim_post.liggghts_log: the run summaries of a LIGGGHTS screen output, as LIGGGHTS 3.8
prints them (a bed's settle runs then a wheel run), in order, with their numbers."""
import unittest

from wheelsim_post.liggghts_log import Loop, loops

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


if __name__ == "__main__":
    unittest.main()
