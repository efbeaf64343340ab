"""soil_lab_py.scm_file: the written file has the format of inputs/scm_soils/*.toml (same tables
and keys as dry_sand.toml, a source for every value), holds exactly the values given, and values
outside the SCM loader's ranges raise a SoilValueError naming them before anything is written.
(The C++ loader itself reads the file in test_scm_file_loader.py.)"""

import os
import tempfile
import tomllib
import unittest

from soil_lab_py import fits, scm_file
from soil_lab_py.scm_file import SoilValueError, dem_source, write_scm_soil

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DRY_SAND = os.path.join(ROOT, "inputs", "scm_soils", "dry_sand.toml")

VALUES = dict(n=0.83, kc=12345.6, kphi=2.5e6, cohesion_Pa=850.0, friction_deg=33.25,
              janosi_K_m=0.0071)
SOURCES = {
    "bekker": "fitted from the DEM soil 'loose_sand': plate sinkage",
    "mohr_coulomb.cohesion": "shear box, peak",
    "mohr_coulomb.friction_angle": "shear box, peak (phi)",
    "janosi": "shear box, sigma_n = 10 kPa",
}


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def structure(doc):
    return {k: sorted(v) if isinstance(v, dict) else None for k, v in doc.items()} | {
        "source." + k: sorted(v) for k, v in doc.get("source", {}).items()
    }


class WriteTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.tmp.name, "fitted.toml")

    def tearDown(self):
        self.tmp.cleanup()

    def write(self, **over):
        args = dict(name="DEM loose sand", description="fitted by the soil lab", **VALUES,
                    sources=SOURCES)
        args.update(over)
        return write_scm_soil(self.path, **args)

    def load(self):
        with open(self.path, "rb") as f:
            return tomllib.load(f)

    def test_values_and_format_of_the_shipped_files(self):
        self.assertEqual(self.write(), self.path)
        doc = self.load()
        with open(DRY_SAND, "rb") as f:
            shipped = tomllib.load(f)
        self.assertEqual(structure(doc), structure(shipped))  # same tables, keys, source keys
        self.assertEqual(doc["name"], "DEM loose sand")
        self.assertEqual(doc["bekker"], {"n": 0.83, "kc": 12345.6, "kphi": 2.5e6})
        self.assertEqual(doc["mohr_coulomb"], {"cohesion": 850.0, "friction_angle": 33.25})
        self.assertEqual(doc["janosi"], {"shear_modulus": 0.0071})
        self.assertEqual(doc["source"]["bekker"]["kphi"], SOURCES["bekker"])
        self.assertEqual(doc["source"]["mohr_coulomb"]["friction_angle"], "shear box, peak (phi)")
        text = read(self.path)
        self.assertIn("# [scm] is omitted", text)
        self.assertIn("docs/scm-soils.md", text)

    def test_elastic_stiffness_and_its_source(self):
        self.write(elastic_K_Pa_m=3.5e7, sources=dict(SOURCES, scm="plate unloading"))
        doc = self.load()
        self.assertEqual(doc["scm"], {"elastic_stiffness": 3.5e7})
        self.assertEqual(doc["source"]["scm"], {"elastic_stiffness": "plate unloading"})
        self.assertEqual(sorted(doc), sorted(["name", "description", "bekker", "mohr_coulomb",
                                              "janosi", "scm", "source"]))

    def test_awkward_strings_and_no_description(self):
        name = 'sand "B" \\ 2 – φ\ttab'
        self.write(name=name, description=None, sources=dict(SOURCES, janosi="line1\nline2\x7f"))
        doc = self.load()
        self.assertEqual(doc["name"], name)
        self.assertNotIn("description", doc)
        self.assertEqual(doc["source"]["janosi"]["shear_modulus"], "line1\nline2\x7f")

    def test_integers_and_numpy_values(self):
        import numpy as np
        self.write(n=np.float64(1.0), kc=0, kphi=np.int64(800000))
        doc = self.load()
        self.assertEqual(doc["bekker"], {"n": 1.0, "kc": 0.0, "kphi": 800000.0})
        self.assertIsInstance(doc["bekker"]["kc"], float)

    def test_fitted_values_are_written_to_six_significant_digits(self):
        # A fit's 17 digits are rounded: 6 are written (and the value checked is the one written).
        self.write(n=0.7235747329522896, kphi=144358.6220689771, friction_deg=31.189745480858136,
                   janosi_K_m=0.0009041611221224426, elastic_K_Pa_m=10676583.44517838,
                   sources=dict(SOURCES, scm="plate unloading"))
        doc = self.load()
        self.assertEqual(doc["bekker"]["n"], 0.723575)
        self.assertEqual(doc["bekker"]["kphi"], 144359.0)
        self.assertEqual(doc["mohr_coulomb"]["friction_angle"], 31.1897)
        self.assertEqual(doc["janosi"]["shear_modulus"], 0.000904161)
        self.assertEqual(doc["scm"]["elastic_stiffness"], 10676600.0)
        with self.assertRaisesRegex(SoilValueError, r"friction_angle must be in \[0, 90\) deg, "
                                                    r"got 90\.0$"):
            self.write(friction_deg=89.9999999)

    def test_out_of_range_values_are_errors_before_writing(self):
        cases = [
            (dict(n=2.5), r"^bekker\.n must be in \(0, 2\], got 2\.5$"),
            (dict(n=0.0), r"^bekker\.n must be in \(0, 2\], got 0\.0$"),
            (dict(kc=-1.0), r"^bekker\.kc must be >= 0 N/m\^\(n\+1\), got -1\.0$"),
            (dict(kc=0.0, kphi=0.0), r"^bekker\.kc \+ bekker\.kphi must be > 0"),
            (dict(cohesion_Pa=-3.0), r"^mohr_coulomb\.cohesion must be >= 0 Pa, got -3\.0$"),
            (dict(friction_deg=90.0), r"friction_angle must be in \[0, 90\) deg, got 90\.0$"),
            (dict(janosi_K_m=0.0), r"^janosi\.shear_modulus must be > 0 m, got 0\.0$"),
            (dict(elastic_K_Pa_m=-1.0), r"^scm\.elastic_stiffness must be > 0 Pa/m, got -1\.0$"),
            (dict(kphi=float("nan")), r"^bekker\.kphi must be a finite number in N/m\^\(n\+2\)"),
            (dict(n="1.1"), r"^bekker\.n must be a number, got '1\.1'$"),
            (dict(friction_deg=True), r"^mohr_coulomb\.friction_angle must be a number in deg"),
            (dict(janosi_K_m="big"), r"^janosi\.shear_modulus must be a number in m, got 'big'"),
            (dict(name=""), r"^name must be a non-empty string"),
            (dict(sources={k: v for k, v in SOURCES.items() if k != "janosi"}),
             r"^missing source for janosi\.shear_modulus"),
            (dict(sources=dict(SOURCES, bekkr="x")), r"^unknown source key 'bekkr'"),
            (dict(sources=dict(SOURCES, scm="x")), None),  # a table-wide source for [scm] unused
            (dict(sources=dict(SOURCES, **{"scm.elastic_stiffness": "x"})),
             r"^sources given for values not written: scm\.elastic_stiffness"),
        ]
        with open(self.path, "w") as f:
            f.write("previous contents\n")
        for over, pattern in cases:
            with self.subTest(over=over):
                if pattern is None:
                    self.write(**over)
                    with open(self.path, "w") as f:
                        f.write("previous contents\n")
                    continue
                with self.assertRaisesRegex(SoilValueError, pattern):
                    self.write(**over)
                self.assertEqual(read(self.path), "previous contents\n")
        self.assertEqual(os.listdir(self.tmp.name), ["fitted.toml"])  # no temporary left

    def test_dem_source_quotes_the_fit(self):
        fit = fits.fit_mohr_coulomb([1e4, 2e4, 3e4, 4e4], [7e3, 13.1e3, 18.9e3, 25e3])
        text = dem_source("loose_sand", "direct shear box, peak", fit, "4 normal stresses")
        self.assertTrue(text.startswith("fitted from the DEM soil 'loose_sand'"), text)
        self.assertIn("direct shear box, peak, 4 normal stresses", text)
        self.assertIn(f"RMS {fit.rms_Pa:.3g} Pa", text)
        self.assertIn(f"R² {fit.r2:.4f}", text)
        self.assertIn("4 points", text)
        self.assertEqual(scm_file.SOURCE_KEYS[0], "bekker.n")


if __name__ == "__main__":
    unittest.main()
