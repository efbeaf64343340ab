"""``wheelsim-post maps``: SCM snapshots from /terrain, unrolled pressure from VTK files."""

import os
import unittest

import h5py
import numpy as np

import synthetic
from helpers import TempDirTestCase, is_png, run_cli
from wheelsim_post.errors import PostError
from wheelsim_post.vtk import (
    bounding_box_centre,
    read_wheel_surface,
    unrolled_pressure,
    unrolled_triangles,
)

CENTRE = (0.5, 0.01, 0.2)


class SnapshotMapsTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.run_path = self.path("scm.h5")
        grid = np.add.outer(np.arange(4.0), np.arange(6.0)) * 1e-3
        with h5py.File(self.run_path, "w") as f:
            synthetic.write_header(f)
            for step in (100, 200):
                synthetic.write_snapshot(
                    f, "sinkage", step, step * 1e-3, grid, "m", 0.0, -0.1, 0.02
                )
            synthetic.write_snapshot(
                f, "pressure", 200, 0.2, grid * 1e6, "Pa", 0.0, -0.1, 0.02
            )
        self.out = self.path("maps")

    def maps(self, *args):
        result = run_cli("maps", self.run_path, "--png-dir", self.out, *args)
        return result, sorted(os.listdir(self.out)) if os.path.isdir(self.out) else []

    def test_default_is_the_last_snapshot_of_every_field(self):
        result, files = self.maps()
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(files, ["pressure_000000200.png", "sinkage_000000200.png"])
        self.assertTrue(is_png(os.path.join(self.out, files[0])))

    def test_step_time_and_all(self):
        self.assertEqual(
            self.maps("--field", "sinkage", "--step", "100")[1],
            ["sinkage_000000100.png"],
        )
        self.tearDown()
        self.setUp()
        self.assertEqual(
            self.maps("--field", "sinkage", "--time", "0.09")[1],
            ["sinkage_000000100.png"],
        )
        self.tearDown()
        self.setUp()
        self.assertEqual(
            self.maps("--field", "sinkage", "--all")[1],
            ["sinkage_000000100.png", "sinkage_000000200.png"],
        )

    def test_missing_step_and_field_are_errors(self):
        result, _ = self.maps("--step", "300")
        self.assertEqual(result.returncode, 2)
        self.assertIn("--step: no snapshot at step 300", result.stderr)
        result, _ = self.maps("--field", "height")
        self.assertEqual(result.returncode, 2)
        self.assertIn("--field: run file", result.stderr)
        self.assertIn("no snapshots of 'height'", result.stderr)

    def test_time_must_be_finite_and_not_negative(self):
        for value in ("nan", "-1", "inf"):
            with self.subTest(time=value):
                result, _ = self.maps("--time", value)
                self.assertOneLineError(result, f"--time: expected a time >= 0 s, got {value}")

    def test_a_grid_spacing_of_0_names_the_snapshot_and_the_value(self):
        with h5py.File(self.run_path, "a") as f:
            f["terrain/sinkage/000000200/spacing"][()] = 0.0
        result, files = self.maps("--field", "sinkage")
        self.assertOneLineError(
            result,
            "scm.h5': snapshot '/terrain/sinkage/000000200' has spacing 0 m",
            "expected a finite grid spacing > 0 m",
        )
        self.assertEqual(files, [])


class VtkMapsTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        # 36 segments of 10°: pressure 1000 Pa on the first triangle (centroid at y < 0) of
        # segments 0..2 (θ = 0..30°, below the axle, towards +x), 0 elsewhere.
        points, triangles = synthetic.cylinder_mesh(centre=CENTRE)
        pressure = np.zeros(len(triangles))
        pressure[[0, 2, 4]] = 1000.0
        self.vtk_path = self.path("wheel_surface_2000.vtk")
        synthetic.write_vtk(
            self.vtk_path, points, triangles, pressure, step=2000, time=0.25
        )

    def test_reader(self):
        surface = read_wheel_surface(self.vtk_path)
        self.assertEqual((surface.step, surface.time), (2000, 0.25))
        self.assertEqual(surface.points.shape, (72, 3))
        self.assertEqual(surface.triangles.shape, (72, 3))
        self.assertEqual(
            sorted(surface.cell_data), ["contact_count", "contact_pressure"]
        )
        np.testing.assert_allclose(bounding_box_centre(surface), CENTRE, atol=1e-9)

    def test_unrolled_pressure_lies_below_the_axle(self):
        surface = read_wheel_surface(self.vtk_path)
        angle_edges = np.linspace(-180, 180, 37)
        y_edges = np.array([-0.025, 0.0, 0.025])
        grid = unrolled_pressure(surface, np.array(CENTRE), angle_edges, y_edges)
        self.assertEqual(grid.shape, (2, 36))
        expected = np.zeros((2, 36))
        expected[0, 18:21] = 1000.0  # y < 0; bins 0..10°, 10..20°, 20..30°
        np.testing.assert_allclose(grid, expected)
        # one axial bin: two triangles of equal area per bin, one loaded → area mean 500 Pa
        one = unrolled_pressure(
            surface, np.array(CENTRE), angle_edges, np.array([-0.03, 0.03])
        )
        np.testing.assert_allclose(one[0, 18:21], 500.0)
        # a bin without triangles is NaN, not 0
        fine = unrolled_pressure(
            surface, np.array(CENTRE), np.linspace(-180, 180, 721), y_edges
        )
        self.assertTrue(np.isnan(fine).any())

    def test_unrolled_triangles_keep_their_width_across_the_seam(self):
        surface = read_wheel_surface(self.vtk_path)
        polygons = unrolled_triangles(surface, np.array(CENTRE))
        self.assertEqual(polygons.shape, (72, 3, 2))
        width = np.ptp(polygons[..., 0], axis=1)
        # every triangle spans one 10° segment, also 170..190° (segment 17, across ±180°)
        np.testing.assert_allclose(width, 10.0, atol=1e-6)
        np.testing.assert_allclose(
            sorted(polygons[0, :, 0]), [0.0, 0.0, 10.0], atol=1e-6
        )
        np.testing.assert_allclose(np.ptp(polygons[..., 1], axis=1), 0.05, atol=1e-9)

    def test_cli_writes_one_png_per_file(self):
        second = self.path("wheel_surface_3000.vtk")
        points, triangles = synthetic.cylinder_mesh(centre=CENTRE)
        synthetic.write_vtk(second, points, triangles, np.ones(len(triangles)))
        out = self.path("png")
        result = run_cli("maps", "--vtk", self.vtk_path, second, "--png-dir", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(
            sorted(os.listdir(out)),
            ["wheel_surface_2000_pressure.png", "wheel_surface_3000_pressure.png"],
        )
        self.assertTrue(is_png(os.path.join(out, "wheel_surface_2000_pressure.png")))
        binned = self.path("binned")
        result = run_cli(
            "maps",
            "--vtk",
            self.vtk_path,
            "--png-dir",
            binned,
            "--binned",
            "--angle-bin",
            "5",
            "--axial-bins",
            "4",
        )
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(is_png(os.path.join(binned, "wheel_surface_2000_pressure.png")))

    def test_malformed_vtk_names_the_file(self):
        bad = self.path("bad.vtk")
        with open(self.vtk_path) as src, open(bad, "w") as dst:
            dst.write(src.read().replace("SCALARS contact_pressure", "SCALARS other"))
        with self.assertRaisesRegex(
            PostError, "bad.vtk.*no cell data 'contact_pressure'"
        ):
            read_wheel_surface(bad)
        result = run_cli("maps", "--vtk", bad, "--png-dir", self.path("png"))
        self.assertEqual(result.returncode, 2)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1)

    def test_a_binary_file_names_the_file(self):
        garbage = self.path("garbage.h5")
        with open(garbage, "wb") as f:
            f.write(b"\x89HDF\r\n\x1a\n" + bytes(range(256)))
        with self.assertRaisesRegex(PostError, "garbage.h5'.*not a text file"):
            read_wheel_surface(garbage)
        result = run_cli("maps", "--vtk", garbage, "--png-dir", self.path("png"))
        self.assertOneLineError(result, "VTK file", "garbage.h5': not a text file",
                                "expected a legacy ASCII VTK file")


if __name__ == "__main__":
    unittest.main()
