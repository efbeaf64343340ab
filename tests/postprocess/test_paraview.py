"""``wheelsim-post pvd`` and ``wheelsim-post vtk``: ParaView collections with physical times and
SCM snapshots as VTK image data. The files are read back with the standard library's XML parser
and numpy (no VTK needed) and compared with what was written into the synthetic run file."""

import base64
import os
import unittest
import xml.etree.ElementTree as ET

import h5py
import numpy as np

import synthetic
from helpers import TempDirTestCase, run_cli
from wheelsim_post.errors import PostError
from wheelsim_post.paraview import read_pvd, write_pvd


def pvd_entries(path):
    """(time, file) of a .pvd, parsed here independently of wheelsim_post."""
    root = ET.parse(path).getroot()
    assert root.get("type") == "Collection"
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def decode(element, dtype="<f8"):
    """Values of a VTK XML binary DataArray (base64, UInt32 byte count first)."""
    raw = base64.b64decode(element.text.strip())
    count = int(np.frombuffer(raw[:4], dtype="<u4")[0])
    return np.frombuffer(raw[4 : 4 + count], dtype=dtype)


def read_vti(path):
    """(ImageData attributes, {point array: values}, {field array: values}) of a .vti."""
    root = ET.parse(path).getroot()
    image = root.find("ImageData")
    points = {a.get("Name"): decode(a) for a in image.find("Piece/PointData")}
    fields = {}
    for a in image.findall("FieldData/DataArray"):
        fields[a.get("Name")] = decode(a, "<i8" if a.get("type") == "Int64" else "<f8")
    return image.attrib, points, fields


class PvdCommandTest(TempDirTestCase):
    DT = 1e-5  # [s]

    def make_series(self, steps, name="particles_{}.vtk"):
        os.makedirs(self.path("post"), exist_ok=True)
        for step in steps:
            with open(self.path(os.path.join("post", name.format(step))), "w") as out:
                out.write("# vtk DataFile Version 2.0\n")

    def test_lists_every_file_with_step_times_dt(self):
        steps = [0, 500, 1000, 1500, 12000]
        self.make_series(steps)
        self.make_series([500], name="particles_boundingBox_{}.vtk")  # not a step: skipped
        out = self.path("particles.pvd")
        result = run_cli("pvd", self.path("post/particles_*.vtk"), "--dt", self.DT, "--out", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        entries = pvd_entries(out)
        self.assertEqual([f for _, f in entries], [f"post/particles_{s}.vtk" for s in steps])
        for (time, _), step in zip(entries, steps):
            self.assertLessEqual(abs(time - step * self.DT), 1e-12 * max(step * self.DT, 1e-300))
        for (_, name) in entries:  # relative to the .pvd's folder
            self.assertTrue(os.path.exists(os.path.join(self.dir, name)))
        self.assertEqual([f for f in os.listdir(self.dir) if f.endswith(".tmp")], [])

    def test_like_takes_the_time_origin_of_another_collection(self):
        self.make_series([6600, 6700])
        wheel = self.path("post/wheel_surface.pvd")
        write_pvd(wheel, [(0.0026924877073790962, self.path("post/wheel_surface_6600.vtk"))])
        out = self.path("post/particles.pvd")
        dt = 4.89543219523472e-05
        result = run_cli(
            "pvd", self.path("post/particles_*.vtk"), "--dt", dt, "--out", out, "--like", wheel
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        (t0, f0), (t1, f1) = pvd_entries(out)
        self.assertEqual((f0, f1), ("particles_6600.vtk", "particles_6700.vtk"))
        self.assertEqual(t0, 0.0026924877073790962)
        self.assertAlmostEqual(t1, t0 + 100 * dt, delta=1e-12 * t1)

    def test_rewrite_is_atomic_and_replaces_the_old_collection(self):
        out = self.path("c.pvd")
        write_pvd(out, [(0.0, self.path("a_0.vtk")), (1.0, self.path("a_1.vtk"))])
        write_pvd(out, [(2.0, self.path("a_2.vtk"))])
        self.assertEqual(read_pvd(out), [(2.0, "a_2.vtk")])
        self.assertEqual(os.listdir(self.dir), ["c.pvd"])
        with self.assertRaises(PostError):
            write_pvd(self.path("missing/c.pvd"), [(0.0, "a_0.vtk")])
        self.assertEqual(os.listdir(self.dir), ["c.pvd"])

    def test_errors_name_the_problem(self):
        result = run_cli("pvd", self.path("none_*.vtk"), "--dt", "1e-5", "--out", "x.pvd")
        self.assertEqual(result.returncode, 2)
        self.assertIn("no file matches", result.stderr)
        result = run_cli("pvd", self.path("p.vtk"), "--dt", "1e-5", "--out", "x.pvd")
        self.assertIn("exactly one '*'", result.stderr)
        self.make_series([0])
        result = run_cli("pvd", self.path("post/particles_*.vtk"), "--dt", "0", "--out", "x.pvd")
        self.assertIn("--dt: expected a time step > 0 s", result.stderr)


class TerrainVtkTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.run_path = self.path("scm.h5")
        rng = np.random.default_rng(7)
        self.grids = {}
        with h5py.File(self.run_path, "w") as f:
            synthetic.write_header(f)
            # the window grows between snapshots (docs/hdf5-layout.md)
            for step, shape, x0 in ((4000, (3, 5), 0.10), (8000, (4, 7), 0.08)):
                time = step * 2.5e-4
                for field, unit in (("height", "m"), ("sinkage", "m"), ("pressure", "Pa")):
                    value = rng.normal(size=shape)
                    self.grids[field, step] = (value, time)
                    synthetic.write_snapshot(f, field, step, time, value, unit, x0, -0.06, 0.01)
        self.out = self.path("vtk")

    def test_one_vti_per_step_with_every_field_and_a_pvd(self):
        result = run_cli("vtk", self.run_path, "--out", self.out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(
            sorted(os.listdir(self.out)),
            ["terrain.pvd", "terrain_000004000.vti", "terrain_000008000.vti"],
        )
        entries = pvd_entries(os.path.join(self.out, "terrain.pvd"))
        self.assertEqual(
            entries, [(1.0, "terrain_000004000.vti"), (2.0, "terrain_000008000.vti")]
        )
        attrs, points, fields = read_vti(os.path.join(self.out, "terrain_000008000.vti"))
        self.assertEqual(attrs["WholeExtent"].split(), ["0", "6", "0", "3", "0", "0"])
        origin = [float(v) for v in attrs["Origin"].split()]
        spacing = [float(v) for v in attrs["Spacing"].split()]
        self.assertEqual(origin, [0.08, -0.06, 0.0])
        self.assertEqual(spacing[:2], [0.01, 0.01])
        self.assertEqual(sorted(points), ["height", "pressure", "sinkage"])
        with h5py.File(self.run_path, "r") as f:
            stored = f["terrain/sinkage/000008000/value"][()]
        # VTK point order: x (column j) fastest, then y (row i)
        np.testing.assert_array_equal(points["sinkage"].reshape(4, 7), stored)
        np.testing.assert_array_equal(points["sinkage"][7 * 2 + 3], stored[2, 3])
        self.assertEqual(float(fields["TimeValue"][0]), 2.0)
        self.assertEqual(int(fields["step"][0]), 8000)
        attrs, points, _ = read_vti(os.path.join(self.out, "terrain_000004000.vti"))
        self.assertEqual(attrs["WholeExtent"].split(), ["0", "4", "0", "2", "0", "0"])
        np.testing.assert_array_equal(
            points["height"].reshape(3, 5), self.grids["height", 4000][0]
        )
        self.assertEqual([f for f in os.listdir(self.out) if f.endswith(".tmp")], [])

    def test_a_file_without_snapshots_is_an_error(self):
        empty = self.path("empty.h5")
        with h5py.File(empty, "w") as f:
            synthetic.write_header(f)
        result = run_cli("vtk", empty, "--out", self.out)
        self.assertEqual(result.returncode, 2)
        self.assertIn("has no /terrain snapshots", result.stderr)

    def test_a_grid_spacing_of_0_is_an_error_and_writes_nothing(self):
        with h5py.File(self.run_path, "a") as f:
            f["terrain/height/000004000/spacing"][()] = 0.0
        result = run_cli("vtk", self.run_path, "--out", self.out)
        self.assertOneLineError(
            result, "snapshot '/terrain/height/000004000' has spacing 0 m",
            "expected a finite grid spacing > 0 m",
        )
        self.assertFalse(os.path.exists(self.out))  # checked before the directory is made


if __name__ == "__main__":
    unittest.main()
