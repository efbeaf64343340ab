"""mpi_launch's scheduler autogroups (docs/dem-performance.md "Sharing the cores"): the
autogroup file parsed (known text, missing, damaged), and a child started in a session of its own
(die_with_parent(new_session=True), as wheel-sweep starts its points) runs in a new autogroup
niced as its parent: the parent's own nice 7 becomes the new group's nice 7; without a new
session the child stays in its parent's group. The real-kernel cases skip where the kernel has no
autogroups."""

import os
import subprocess
import sys
import tempfile
import unittest

from wheelsim_post import mpi_launch

# A parent that nices itself, then starts a child the way wheel-sweep does and prints the child's
# autogroup line and its own.
PARENT = r"""
import os, subprocess, sys
from wheelsim_post import mpi_launch
os.nice(int(sys.argv[1]))
new = sys.argv[2] == "1"
line = subprocess.run(["cat", "/proc/self/autogroup"], capture_output=True, text=True,
                      preexec_fn=mpi_launch.die_with_parent(os.getpid(), new_session=new)).stdout
print(line.strip())
print(open("/proc/self/autogroup").read().strip())
print(os.getpriority(os.PRIO_PROCESS, 0))
"""


def run_parent(nice, new_session):
    """(child's autogroup line, parent's autogroup line, parent's own nice) of PARENT (its nice is
    `nice` more than this test's: a suite run with `nice -n N` starts it at N)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    out = subprocess.run([sys.executable, "-c", PARENT, str(nice), "1" if new_session else "0"],
                         capture_output=True, text=True, env=env, check=True, timeout=60)
    child, parent, own = out.stdout.splitlines()
    return child, parent, int(own)


class AutogroupFileTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)

    def write(self, text):
        path = os.path.join(self.dir.name, "autogroup")
        with open(path, "w") as f:
            f.write(text)
        return path

    def test_parses_the_kernels_line(self):
        self.assertEqual(mpi_launch.autogroup_nice(self.write("/autogroup-1896 nice 7\n")), 7)
        self.assertEqual(mpi_launch.autogroup_nice(self.write("/autogroup-3 nice -2\n")), -2)

    def test_none_without_a_readable_number(self):
        self.assertIsNone(mpi_launch.autogroup_nice(os.path.join(self.dir.name, "missing")))
        self.assertIsNone(mpi_launch.autogroup_nice(self.write("")))
        self.assertIsNone(mpi_launch.autogroup_nice(self.write("/autogroup-3 nice x\n")))


@unittest.skipIf(mpi_launch.autogroup_nice() is None, "this kernel has no scheduler autogroups")
class NewSessionTest(unittest.TestCase):
    def test_a_new_session_carries_the_parents_nice(self):
        child, parent, own = run_parent(7, new_session=True)
        self.assertNotEqual(child.split()[0], parent.split()[0], "a new session is a new group")
        self.assertGreaterEqual(own, 7)
        self.assertEqual(child.split()[-1], str(max(own, int(parent.split()[-1]))), child)

    def test_without_a_new_session_the_child_stays_in_the_group(self):
        child, parent, _ = run_parent(7, new_session=False)
        self.assertEqual(child, parent)

    def test_nothing_to_carry_at_nice_0(self):
        if mpi_launch.autogroup_nice() != 0 or os.getpriority(os.PRIO_PROCESS, 0) != 0:
            self.skipTest("this test runs niced (its process or its autogroup)")
        child, _, _ = run_parent(0, new_session=True)
        self.assertEqual(child.split()[-1], "0")


if __name__ == "__main__":
    unittest.main()
