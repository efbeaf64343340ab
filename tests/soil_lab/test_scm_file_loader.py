"""The SCM soil file written by soil_lab_py loads unchanged in the C++ loader (a script: exit 77 =
skip when wheel-rig or the test wheel mesh is not built; usage:
test_scm_file_loader.py [--build-dir DIR]).

1. Synthetic plate, shear and unloading data are fitted and written with write_scm_soil (with
   [scm] elastic_stiffness); a rig config made from wheel_dynamics/examples/rig_scm.toml with its
   [terrain] soil pointing at the file passes `wheel-rig --check` (exit 0). The same file with
   n = 2.5 fails it (exit 2, naming bekker.n): the check really loads the soil.
2. When wong-reece is built: LETE sand's values written by write_scm_soil give exactly the same
   wong-reece table as inputs/scm_soils/lete_sand.toml (the loader reads every value unchanged).
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
import tomllib
import unittest

import numpy as np

import synthetic as syn
from soil_lab_py import fits
from soil_lab_py.scm_file import dem_source, write_scm_soil

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLE = os.path.join(ROOT, "wheel_dynamics", "examples", "rig_scm.toml")
BUILD_DIR = os.path.join(ROOT, "build")
SKIP = 77


def binary(name):
    path = os.path.join(BUILD_DIR, "bin", name)
    return path if os.access(path, os.X_OK) else None


def mesh():
    path = os.path.join(BUILD_DIR, "meshes", "test_small.obj")
    return path if os.path.isfile(path) else None


def rig_config(path, soil):
    """The SCM rig example with its wheel mesh and soil replaced by absolute paths."""
    with open(EXAMPLE, encoding="utf-8") as f:
        text = f.read()
    text, n_mesh = re.subn(r'(?m)^mesh = "[^"]*"', f'mesh = "{mesh()}"', text)
    text, n_soil = re.subn(r'(?m)^soil = "[^"]*"', f'soil = "{soil}"', text)
    assert (n_mesh, n_soil) == (1, 1), f"{EXAMPLE}: mesh/soil lines not found ({n_mesh}, {n_soil})"
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def fitted_soil_file(path):
    """Fits of synthetic lab data written as a soil file; returns the fitted values."""
    plates = syn.bekker_plates(0.9, 30e3, 1.2e6, (0.05, 0.1), seed=21)
    bekker = fits.fit_bekker(plates)
    rng = np.random.default_rng(22)
    sigma = np.array([5e3, 10e3, 20e3])
    j = np.linspace(0.0, 0.05, 100)
    curves = [(s, j, (800 + s * np.tan(np.radians(32))) * -np.expm1(-j / 0.008)
               + rng.normal(0, 30, j.size)) for s in sigma]
    janosi = [fits.fit_janosi(jj, t) for _, jj, t in curves]
    mc = fits.fit_mohr_coulomb(sigma, [f.tau_max_Pa for f in janosi])
    z = np.linspace(0.030, 0.0295, 30)
    unload = fits.fit_unload_stiffness(z, 3e5 + 1e8 * (z - 0.030))
    soil = "synthetic_dem_soil"
    write_scm_soil(
        path, "DEM soil (synthetic)", "soil_lab_py round trip test", bekker.n, bekker.kc,
        bekker.kphi, mc.cohesion_Pa, mc.friction_deg, float(np.mean([f.K_m for f in janosi])),
        elastic_K_Pa_m=unload.Ke_Pa_m,
        sources={
            "bekker": dem_source(soil, "plate sinkage, plates b 50 and 100 mm", bekker),
            "mohr_coulomb": dem_source(soil, "direct shear, Janosi tau_max at 3 stresses", mc),
            "janosi": dem_source(soil, "direct shear, mean K of 3 curves", janosi[0]),
            "scm": dem_source(soil, "plate unloading, upper half", unload),
        },
    )
    return bekker, mc


class LoaderRoundTripTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.tmp.name, name)

    def check(self, config):
        return subprocess.run([binary("wheel-rig"), "--config", config, "--check"],
                              capture_output=True, text=True, timeout=60)

    def test_wheel_rig_check_loads_the_file(self):
        soil = self.path("fitted.toml")
        bekker, _ = fitted_soil_file(soil)
        self.assertLess(abs(bekker.n - 0.9), 0.02)  # the fit behind the file is sane
        r = self.check(rig_config(self.path("rig.toml"), soil))
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("ok", r.stdout)
        # The same file made invalid: the check must fail on the soil, naming the key.
        with open(soil, encoding="utf-8") as f:
            text = f.read()
        bad, count = re.subn(r'(?m)^n = (?!")\S+', "n = 2.5", text)
        self.assertEqual(count, 1)
        with open(soil, "w", encoding="utf-8") as f:
            f.write(bad)
        r = self.check(self.path("rig.toml"))
        self.assertEqual(r.returncode, 2, r.stdout + r.stderr)
        self.assertIn("bekker.n must be in (0, 2], got 2.5", r.stderr)

    def test_values_reach_the_loader_unchanged(self):
        wong_reece = binary("wong-reece")
        if wong_reece is None:
            self.skipTest("wong-reece is not built")
        lete = os.path.join(ROOT, "inputs", "scm_soils", "lete_sand.toml")
        with open(lete, "rb") as f:
            d = tomllib.load(f)
        ours = self.path("lete_from_python.toml")
        write_scm_soil(
            ours, d["name"], None, d["bekker"]["n"], d["bekker"]["kc"], d["bekker"]["kphi"],
            d["mohr_coulomb"]["cohesion"], d["mohr_coulomb"]["friction_angle"],
            d["janosi"]["shear_modulus"],
            sources={t: "copied from lete_sand.toml" for t in ("bekker", "mohr_coulomb", "janosi")},
        )
        tables = []
        for soil, csv in ((lete, self.path("shipped.csv")), (ours, self.path("ours.csv"))):
            r = subprocess.run(
                [wong_reece, "--soil", soil, "--radius", "0.617", "--width", "0.479", "--load",
                 "13200", "--slips", "0.05,0.2,0.4", "--csv", csv],
                capture_output=True, text=True, timeout=60)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(csv, encoding="utf-8") as f:
                tables.append(f.read())
        self.assertEqual(tables[0], tables[1])
        self.assertEqual(len(tables[0].splitlines()), 4)


def main():
    global BUILD_DIR
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build-dir", default=BUILD_DIR, help="the CMake build directory")
    args, rest = parser.parse_known_args()
    BUILD_DIR = os.path.abspath(args.build_dir)
    if binary("wheel-rig") is None:
        print(f"SKIP: {os.path.join(BUILD_DIR, 'bin', 'wheel-rig')} is not built")
        return SKIP
    if mesh() is None:
        print(f"SKIP: the test wheel mesh {os.path.join(BUILD_DIR, 'meshes', 'test_small.obj')} "
              "is not built")
        return SKIP
    result = unittest.main(argv=[sys.argv[0], "-v"] + rest, exit=False).result
    return 0 if result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
