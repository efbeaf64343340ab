"""wheelsim_post.metadata: sweep parameters first, then the documented fallbacks."""

import math
import unittest

import h5py

import synthetic
from helpers import TempDirTestCase
from wheelsim_post.errors import PostError
from wheelsim_post.metadata import parse_group_by, read_metadata
from wheelsim_post.runfile import RunFile


def metadata(path):
    with RunFile(path) as run:
        return read_metadata(run)


class MetadataTest(TempDirTestCase):
    def write(self, name, params, slip=0.2):
        path = self.path(name)
        with h5py.File(path, "w") as f:
            synthetic.write_header(f)
            synthetic.write_parameter(
                f, "rig_config", synthetic.rig_config(slip, "scm")
            )
            for key, value in params.items():
                synthetic.write_parameter(f, key, value)
        return path

    def test_sweep_parameters_win_over_fallbacks(self):
        path = self.write(
            "a.h5",
            {
                "sweep/wheel": "W1",
                "sweep/soil": "GRC-1",
                "sweep/slip": "0.35",
                "sweep/terrain": "dem",
                "wheel/source": "mesh meshes/other.stl",
                "bed/soil": "other",
            },
            slip=0.1,
        )
        m = metadata(path)
        self.assertEqual(
            (m.wheel, m.soil, m.terrain, m.target_slip), ("W1", "GRC-1", "dem", 0.35)
        )

    def test_dem_fallbacks(self):
        path = self.write(
            "b.h5",
            {"wheel/source": "mesh ../meshes/lugged_12.stl", "bed/soil": "ci_sand"},
        )
        m = metadata(path)
        self.assertEqual(
            (m.wheel, m.soil, m.terrain, m.target_slip),
            ("lugged_12", "ci_sand", "scm", 0.2),
        )

    def test_mesh_file_and_scm_soil_fallbacks(self):
        path = self.write(
            "c.h5",
            {
                "wheel/source": "config",
                "wheel/mesh_file": "/x/y/grouser_8.obj",
                "terrain/soil_name": "LETE sand",
            },
        )
        m = metadata(path)
        self.assertEqual((m.wheel, m.soil), ("grouser_8", "LETE sand"))

    def test_no_target_slip_is_nan(self):
        path = self.path("d.h5")
        with h5py.File(path, "w") as f:
            synthetic.write_header(f)
            synthetic.write_parameter(
                f, "rig_config", '[carriage]\nmode = "constant_load"\n'
            )
        m = metadata(path)
        self.assertTrue(math.isnan(m.target_slip))
        self.assertEqual(
            (m.wheel, m.soil, m.terrain), ("unknown", "unknown", "unknown")
        )

    def test_bad_sweep_slip(self):
        path = self.write("e.h5", {"sweep/slip": "high"})
        with self.assertRaisesRegex(
            PostError, "sweep/slip is 'high', expected a number"
        ):
            metadata(path)

    def test_group_by(self):
        self.assertEqual(parse_group_by("wheel, soil"), ("wheel", "soil"))
        with self.assertRaisesRegex(PostError, "--group-by: 'wheel,colour'"):
            parse_group_by("wheel,colour")


if __name__ == "__main__":
    unittest.main()
