"""wheelsim_post.bed_surface: column tops and profiles of known particle sets, in.soilbin's grid
(inputs/soilbin/measure.in), the dump and deck-line readers and their errors (docs/postprocess.md
"surface"). The command on real LIGGGHTS beds: tests/postprocess/check_surface.py."""
import os
import tempfile
import unittest

import numpy as np

from helpers import TempDirTestCase
from synthetic import write_run
from wheelsim_post import bed_surface, cmd_surface
from wheelsim_post.errors import PostError


def spheres(x, y, z, r=0.01, step=0):
    n = len(x)
    return bed_surface.Particles(step, np.asarray(x, float), np.asarray(y, float),
                                 np.asarray(z, float), np.full(n, r))


class Grids(unittest.TestCase):
    def test_bed_grid_is_measure_in_s(self):
        # floor(L / 2 dmax) clamped to [1, 20] along x, [1, 10] across (measure.in)
        x, y = bed_surface.bed_grid(0.12, 0.08, 0.008)
        self.assertEqual((len(x) - 1, len(y) - 1), (7, 5))
        x, y = bed_surface.bed_grid(5.3, 1.0, 0.04)
        self.assertEqual((len(x) - 1, len(y) - 1), (20, 10))
        x, y = bed_surface.bed_grid(0.05, 0.05, 0.04)
        self.assertEqual((len(x) - 1, len(y) - 1), (1, 1))
        self.assertAlmostEqual(y[0], -0.025, places=15)
        self.assertAlmostEqual(x[-1], 0.05, places=15)

    def test_column_grid_is_as_close_to_the_width_as_the_bin_allows(self):
        x, y = bed_surface.column_grid(5.3, 1.0, 0.08)
        self.assertEqual((len(x) - 1, len(y) - 1), (66, 12))
        self.assertAlmostEqual(x[1] - x[0], 5.3 / 66, places=14)
        with self.assertRaisesRegex(PostError, r"--column: expected a width > 0 m, got 0"):
            bed_surface.column_grid(1.0, 1.0, 0.0)


class Tops(unittest.TestCase):
    def test_each_column_holds_its_highest_top_and_empty_columns_are_nan(self):
        x_edges, y_edges = np.array([0.0, 1.0, 2.0]), np.array([-0.5, 0.0, 0.5])
        p = spheres([0.5, 0.5, 1.5, 1.5, 0.2], [-0.2, -0.3, 0.2, -0.2, 0.3],
                    [0.10, 0.30, 0.20, 0.05, 0.40], r=0.01)
        tops = bed_surface.column_tops(p, x_edges, y_edges)
        np.testing.assert_allclose(tops, [[0.31, 0.41], [0.06, 0.21]], rtol=0, atol=1e-15)
        p = spheres([0.5, 5.0], [0.2, 0.2], [0.1, 9.0])  # the second lies outside the grid
        tops = bed_surface.column_tops(p, x_edges, y_edges)
        self.assertTrue(np.isnan(tops[0, 0]) and np.isnan(tops[1, 0]) and np.isnan(tops[1, 1]))
        self.assertAlmostEqual(tops[0, 1], 0.11, places=15)

    def test_a_centre_on_an_inner_edge_counts_above_it_and_the_last_edge_closes_the_grid(self):
        x_edges, y_edges = np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0])
        tops = bed_surface.column_tops(spheres([1.0, 2.0], [0.5, 1.0], [0.2, 0.3], r=0.0),
                                       x_edges, y_edges)
        np.testing.assert_allclose(tops[:, 0], [np.nan, 0.3])

    def test_a_tilted_surface_of_known_slope_gives_its_profile(self):
        # one sphere top per column on h(x) = 0.5 + 0.1 x: each row's mean is h at its centre
        rng = np.random.default_rng(7)
        x_edges, y_edges = bed_surface.column_grid(2.0, 0.4, 0.1)
        xc = 0.5 * (x_edges[:-1] + x_edges[1:])
        yc = 0.5 * (y_edges[:-1] + y_edges[1:])
        gx, gy = np.meshgrid(xc, yc, indexing="ij")
        top = 0.5 + 0.1 * gx
        # below each top, buried spheres that must not count
        bx = np.repeat(gx.ravel(), 5) + rng.uniform(-0.04, 0.04, gx.size * 5)
        by = np.repeat(gy.ravel(), 5) + rng.uniform(-0.04, 0.04, gx.size * 5)
        bz = rng.uniform(0.0, 0.3, gx.size * 5)
        p = spheres(np.r_[gx.ravel(), bx], np.r_[gy.ravel(), by], np.r_[top.ravel() - 0.01, bz])
        tops = bed_surface.column_tops(p, x_edges, y_edges)
        mean, used = bed_surface.profile_x(tops, y_edges)
        np.testing.assert_allclose(mean, 0.5 + 0.1 * xc, rtol=0, atol=1e-12)
        self.assertTrue(np.all(used == 4))


class Profile(unittest.TestCase):
    def test_the_band_picks_the_columns_by_centre_and_empty_ones_are_left_out(self):
        y_edges = np.array([-0.3, -0.1, 0.1, 0.3])
        tops = np.array([[1.0, 2.0, 3.0], [np.nan, 4.0, np.nan], [np.nan] * 3])
        mean, used = bed_surface.profile_x(tops, y_edges)
        np.testing.assert_allclose(mean[:2], [2.0, 4.0])
        self.assertTrue(np.isnan(mean[2]))
        self.assertEqual(list(used), [3, 1, 0])
        mean, used = bed_surface.profile_x(tops, y_edges, (0.05, 0.3))
        self.assertEqual(mean[0], 3.0)
        self.assertEqual(list(used), [1, 0, 0])
        with self.assertRaisesRegex(PostError, r"--y-band 0\.35,0\.4: no column centre lies in it"):
            bed_surface.profile_x(tops, y_edges, (0.35, 0.4))


def lattice(nx, ny, nz, r, top_fill=0.0):
    """A simple cubic packing of spheres of radius r touching their neighbours (solid fraction
    pi/6) filling a bin nx 2r long and ny 2r wide to nz layers, floor at z = 0, centred on y = 0;
    with ``top_fill`` = 0.5 a layer nz + 1 on every other site (a checkerboard)."""
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz + 1), indexing="ij")
    keep = k < nz
    if top_fill == 0.5:
        keep |= (k == nz) & ((i + j) % 2 == 0)
    x, y, z = ((2 * i + 1) * r)[keep], ((2 * j + 1) * r - ny * r)[keep], ((2 * k + 1) * r)[keep]
    return spheres(x, y, z, r=r)


class Equivalent(unittest.TestCase):
    R = 0.005

    def test_cap_volumes_are_exact(self):
        r = 0.01
        p = spheres([0.0] * 4, [0.0] * 4, [0.0, 0.0, 0.0, 0.0], r=r)
        full = 4.0 / 3.0 * np.pi * r ** 3
        np.testing.assert_allclose(bed_surface.volume_above(p, -1.0), full, rtol=1e-14)
        np.testing.assert_allclose(bed_surface.volume_above(p, 1.0), 0.0, atol=0)
        np.testing.assert_allclose(bed_surface.volume_above(p, 0.0), full / 2, rtol=1e-14)
        # against the integral of the slices' areas pi (r^2 - t^2) above t = 0.3 r
        t = np.linspace(0.3 * r, r, 200001)
        numeric = np.trapz(np.pi * (r * r - t * t), t)
        self.assertAlmostEqual(bed_surface.volume_above(p, 0.3 * r)[0] / numeric, 1.0, places=9)

    def test_a_lattice_s_equivalent_surface_is_its_top_plane(self):
        r, n = self.R, 10
        eq = bed_surface.equivalent_surface(lattice(n, n, 12, r), n * 2 * r, n * 2 * r, 2 * r,
                                            12 * 2 * r)
        self.assertAlmostEqual(eq.level_m, 12 * 2 * r, places=12)
        self.assertAlmostEqual(eq.core_solid_fraction, np.pi / 6, places=12)
        self.assertEqual(eq.spheres, (n - 2) ** 2 * 12)      # centres d_max from the walls
        self.assertAlmostEqual(eq.area_m2, ((n - 2) * 2 * r) ** 2, places=15)

    def test_a_half_filled_top_layer_raises_it_by_half_a_layer(self):
        # the column tops of such a bed lie a whole layer up wherever a top sphere is; the
        # equivalent surface counts the volume: half a layer
        r, n = self.R, 10
        eq = bed_surface.equivalent_surface(lattice(n, n, 12, r, top_fill=0.5), n * 2 * r,
                                            n * 2 * r, 2 * r, 13 * 2 * r)
        self.assertAlmostEqual(eq.level_m, 12 * 2 * r + r, places=12)
        self.assertAlmostEqual(eq.core_solid_fraction, np.pi / 6, places=12)

    def test_a_bed_too_small_for_a_core_is_an_error(self):
        r = self.R
        with self.assertRaisesRegex(PostError, r"too small for a core .* at least 4 d_max"):
            bed_surface.equivalent_surface(lattice(10, 10, 3, r), 0.1, 0.1, 2 * r, 6 * r)
        with self.assertRaisesRegex(PostError, r"too small for a core"):
            bed_surface.equivalent_surface(lattice(2, 2, 12, r), 4 * r, 4 * r, 2 * r, 24 * r)
        line = cmd_surface.equivalent_line(lattice(10, 10, 3, r), {
            "bed_depth": 6 * r, "bin_length": 0.1, "bin_width": 0.1, "soil_dmax": 2 * r})
        self.assertIn("equivalent surface: none (bed 0.1 x 0.1 m", line)


DUMP = """ITEM: TIMESTEP
120
ITEM: NUMBER OF ATOMS
2
ITEM: BOX BOUNDS ff ff ff
0 1
-1 1
0 1
ITEM: ATOMS id x y z radius
1 0.1 0.2 0.3 0.01
2 0.4 -0.5 0.6 0.02
"""


class Readers(unittest.TestCase):
    def write(self, text):
        fd, path = tempfile.mkstemp(suffix=".dump")
        with os.fdopen(fd, "w") as f:
            f.write(text)
        self.addCleanup(os.remove, path)
        return path

    def test_a_dump_is_read_by_its_column_names(self):
        p = bed_surface.read_dump(self.write(DUMP))
        self.assertEqual(p.step, 120)
        np.testing.assert_array_equal(p.y, [0.2, -0.5])
        np.testing.assert_array_equal(p.radius, [0.01, 0.02])
        swapped = DUMP.replace("id x y z radius", "id radius z y x").replace(
            "1 0.1 0.2 0.3 0.01", "1 0.01 0.3 0.2 0.1")
        self.assertEqual(bed_surface.read_dump(self.write(swapped)).x[0], 0.1)

    def test_bad_dumps_name_the_file_and_the_fault(self):
        with self.assertRaisesRegex(PostError, r"cannot read the particle dump '/no/such'"):
            bed_surface.read_dump("/no/such")
        cut = self.write(DUMP.rsplit("\n", 2)[0] + "\n")
        with self.assertRaisesRegex(PostError, r"announces 2 atoms but holds 1.*cut file"):
            bed_surface.read_dump(cut)
        with self.assertRaisesRegex(PostError, r"columns are id x y z; expected x y z radius"):
            bed_surface.read_dump(self.write(DUMP.replace("z radius", "z")))
        with self.assertRaisesRegex(PostError, r"is not a LIGGGHTS text dump"):
            bed_surface.read_dump(self.write("hello\n"))
        with self.assertRaisesRegex(PostError, r"non-finite"):
            bed_surface.read_dump(self.write(DUMP.replace("0.6 0.02", "nan 0.02")))
        binary = self.write("")
        with open(binary, "wb") as f:
            f.write(b"\x89HDF\r\n\x1a\n" + bytes(range(256)))
        with self.assertRaisesRegex(PostError, r"is not a LIGGGHTS text dump \(byte 0x89"):
            bed_surface.read_dump(binary)

    def test_the_deck_line_is_parsed_and_its_absence_is_an_error(self):
        text = ("x\nbedsurface: step=7 soil_dmax=0.008 bed_depth=0.0457 bin_length=0.12 "
                "bin_width=0.08\n")
        v = bed_surface.parse_deck_line(text, "here")
        self.assertEqual((v["step"], v["soil_dmax"], v["bin_width"]), (7, 0.008, 0.08))
        with self.assertRaisesRegex(PostError, r"^here: no 'bedsurface:' line"):
            bed_surface.parse_deck_line("ERROR: x\n", "here")
        with self.assertRaisesRegex(PostError, r"lacks one of step, soil_dmax"):
            bed_surface.parse_deck_line("bedsurface: step=7\n", "here")


class WheelPosition(TempDirTestCase):
    def test_the_wheel_centre_at_a_step_is_that_sample_or_the_last_before_it(self):
        n = 10
        x = np.stack([0.5 + 0.1 * np.arange(n), np.zeros(n), np.full(n, 0.3)], axis=1)
        run = self.path("run.h5")
        write_run(run, 0.01 * np.arange(n), np.full(n, 3), {"wheel/position": (x, "m")})
        self.assertEqual(cmd_surface.wheel_x_at(run, 4), (0.9, 4))
        self.assertEqual(cmd_surface.wheel_x_at(run, 11)[1], 9)  # within 2 samples: the last
        # far past the run file's last sample: a run file that did not write this checkpoint
        with self.assertRaisesRegex(PostError, r"no sample near step 400: its samples end at "
                                               r"step 9 \(every 1 steps\)"):
            cmd_surface.wheel_x_at(run, 400)
        with self.assertRaisesRegex(PostError, r"no sample at or before step -1"):
            cmd_surface.wheel_x_at(run, -1)
        # a coupled run records x from the wheel's start: the box x adds it (box_frame.py)
        coupled = self.path("coupled.h5")
        write_run(coupled, 0.01 * np.arange(n), np.full(n, 3), {"wheel/position": (x, "m")},
                  parameters={"coupling/start_step": (0, "1"), "coupling/origin_x": (0.67, "m")})
        self.assertAlmostEqual(cmd_surface.wheel_x_at(coupled, 4)[0], 0.9 + 0.67, places=12)
        lost = self.path("lost.h5")
        write_run(lost, 0.01 * np.arange(n), np.full(n, 3), {"wheel/position": (x, "m")},
                  parameters={"coupling/start_step": (0, "1")})
        with self.assertRaisesRegex(PostError, r"started the wheel in the box is unknown"):
            cmd_surface.wheel_x_at(lost, 4)
        bare = self.path("bare.h5")
        write_run(bare, [0.0], [3], {})
        with self.assertRaisesRegex(PostError, r"has no observable wheel/position"):
            cmd_surface.wheel_x_at(bare, 0)

    def test_stretches_ahead_and_behind_average_their_rows(self):
        xc = np.arange(0.05, 3.0, 0.1)  # rows 0.1 m apart
        values = np.where(xc > 1.0, 2.0, -1.0)
        values[-1] = np.nan
        out = cmd_surface.stretches(xc, values, 1.0, 0.5)
        self.assertEqual([a for a, _, _ in out], [-1.0, -0.5, 0.0, 0.5, 1.0, 1.5])
        self.assertEqual(out[1][2], -1.0)
        self.assertEqual(out[2][2], 2.0)


if __name__ == "__main__":
    unittest.main()
