"""``wheelsim-post vtk`` and ``maps``: bad input is refused before the output directory is made.
Each case runs the command on one bad input (a missing, unreadable or non-HDF5 run file, a run file
without snapshots or with a malformed one, a misnamed field or step, a bad option value, a missing
or malformed VTK file among good ones) and checks: exit status 2, one error line naming the input,
and no output directory left behind (before 2026-12-02 both made it first and left it empty).
The cases run in this process (run_cli_here): 24 interpreter starts took ~45 s on a slow machine."""

import os
import unittest

import h5py
import numpy as np

import synthetic
from helpers import TempDirTestCase, run_cli_here as run_cli

GRID = np.add.outer(np.arange(3.0), np.arange(4.0)) * 1e-3  # [m]


class BadInputLeavesNoOutputTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.run_path = self.path("scm.h5")
        with h5py.File(self.run_path, "w") as f:
            synthetic.write_header(f)
            for step in (100, 200):
                synthetic.write_snapshot(f, "sinkage", step, step * 1e-3, GRID, "m", 0.0, -0.1,
                                         0.02)
        self.empty = self.path("empty.h5")  # a run file without /terrain snapshots
        with h5py.File(self.empty, "w") as f:
            synthetic.write_header(f)
        self.not_hdf5 = self.path("notes.h5")
        with open(self.not_hdf5, "w") as f:
            f.write("not an HDF5 file\n")
        self.bad_grid = self.path("bad_grid.h5")  # the second step's spacing is 0 m
        with h5py.File(self.bad_grid, "w") as f:
            synthetic.write_header(f)
            synthetic.write_snapshot(f, "sinkage", 100, 0.1, GRID, "m", 0.0, -0.1, 0.02)
            synthetic.write_snapshot(f, "sinkage", 200, 0.2, GRID, "m", 0.0, -0.1, 0.0)
        self.two_grids = self.path("two_grids.h5")  # two fields of one step on other grids
        with h5py.File(self.two_grids, "w") as f:
            synthetic.write_header(f)
            synthetic.write_snapshot(f, "sinkage", 100, 0.1, GRID, "m", 0.0, -0.1, 0.02)
            synthetic.write_snapshot(f, "pressure", 100, 0.1, GRID, "Pa", 0.0, -0.1, 0.01)
        points, triangles = synthetic.cylinder_mesh()
        self.vtk = self.path("wheel_surface_1000.vtk")
        synthetic.write_vtk(self.vtk, points, triangles, np.ones(len(triangles)))
        self.bad_vtk = self.path("wheel_surface_2000.vtk")
        with open(self.bad_vtk, "w") as f:
            f.write("# vtk DataFile Version 3.0\ntruncated\n")
        self.out = self.path("out")

    def refused(self, args, *fragments):
        """The command fails as input errors do, naming fragments, and leaves no self.out."""
        result = run_cli(*args)
        self.assertOneLineError(result, *fragments)
        self.assertFalse(os.path.exists(self.out), f"{args}: left {self.out} behind")

    def test_vtk(self):
        missing = self.path("missing.h5")
        cases = [
            ([missing], f"run file '{missing}' does not exist"),
            ([self.path("")], "is a directory"),
            ([self.not_hdf5], f"cannot open run file '{self.not_hdf5}' as HDF5"),
            ([self.empty], f"run file '{self.empty}' has no /terrain snapshots"),
            ([self.bad_grid], "bad_grid.h5': snapshot '/terrain/sinkage/000000200' has "
             "spacing 0 m"),
            ([self.two_grids], "at step 100 the snapshot of 'pressure'", "spacing 0.01",
             "not on the grid of 'sinkage'"),
            ([self.run_path, "--prefix", "sub/terrain"],
             "--prefix: expected a file name prefix (no '/'), got 'sub/terrain'"),
            ([self.run_path, "--prefix", ""], "--prefix: expected a file name prefix"),
        ]
        for extra, *fragments in cases:
            with self.subTest(args=extra):
                self.refused(["vtk", extra[0], "--out", self.out, *extra[1:]], "vtk: error:",
                             *fragments)
        self.assertEqual(run_cli("vtk", self.run_path, "--out", self.out).returncode, 0)
        self.assertEqual(len(os.listdir(self.out)), 3)  # 2 .vti and the .pvd: the good case

    def test_maps_of_snapshots(self):
        missing = self.path("missing.h5")
        cases = [
            ([missing], f"run file '{missing}' does not exist"),
            ([self.not_hdf5], f"cannot open run file '{self.not_hdf5}' as HDF5"),
            ([self.empty], f"run file '{self.empty}' has no /terrain snapshots"),
            ([self.run_path, "--field", "height"], "--field: run file", "no snapshots of "
             "'height' (it has: sinkage)"),
            ([self.run_path, "--step", "300"], "--step: no snapshot at step 300"),
            ([self.run_path, "--time", "-1"], "--time: expected a time >= 0 s, got -1"),
            ([self.bad_grid, "--all"], "snapshot '/terrain/sinkage/000000200' has spacing 0 m"),
        ]
        for extra, *fragments in cases:
            with self.subTest(args=extra):
                self.refused(["maps", *extra, "--png-dir", self.out], "maps: error:", *fragments)
        self.assertEqual(run_cli("maps", self.run_path, "--png-dir", self.out).returncode, 0)
        self.assertEqual(os.listdir(self.out), ["sinkage_000000200.png"])  # the good case

    def test_maps_of_wheel_surfaces(self):
        missing = self.path("missing.vtk")
        cases = [
            ([self.vtk, missing], f"--vtk: cannot read '{missing}'"),
            ([self.vtk, self.bad_vtk], "wheel_surface_2000.vtk"),
            ([self.vtk, "--angle-bin", "0"], "--angle-bin: expected > 0 deg, got 0"),
            ([self.vtk, "--angle-range", "10", "-10"], "--angle-range: expected MIN < MAX"),
            ([self.vtk, "--axial-bins", "0"], "--axial-bins: expected >= 1, got 0"),
            ([self.vtk, "--centre", "0", "nan", "0"], "--centre: expected a finite point"),
        ]
        for files, *fragments in cases:
            with self.subTest(args=files):
                self.refused(["maps", "--vtk", *files, "--png-dir", self.out], "maps: error:",
                             *fragments)
        self.assertEqual(run_cli("maps", "--vtk", self.vtk, "--png-dir", self.out).returncode, 0)
        self.assertEqual(os.listdir(self.out), ["wheel_surface_1000_pressure.png"])


if __name__ == "__main__":
    unittest.main()
