"""The command line: one error line naming the option or file, exit status 2; option help."""

import argparse
import os
import subprocess
import sys
import unittest

import synthetic
from helpers import SCRIPT, TempDirTestCase, run_cli
from wheelsim_post.cli import build_parser


class CliErrorTest(TempDirTestCase):
    def setUp(self):
        super().setUp()
        self.run_path = self.path("run.h5")
        synthetic.write_rig_run(self.run_path)

    def check(self, args, *fragments):
        result = run_cli(*args)
        self.assertEqual(result.returncode, 2, (args, result.stdout, result.stderr))
        lines = result.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, (args, result.stderr))
        self.assertTrue(lines[0].startswith("wheelsim-post"), lines[0])
        for fragment in fragments:
            self.assertIn(fragment, lines[0], args)

    def test_errors(self):
        run, out = self.run_path, self.path("out")
        folder = self.path("adir.h5")
        os.mkdir(folder)
        cases = [
            (["curves", folder], "run file", "adir.h5' is a directory, expected an HDF5 file"),
            (
                ["compare", folder, "m.csv", "--quantity", "sinkage"],
                "SIM.csv: ",
                "adir.h5' is a directory, expected a CSV file",
            ),
            (["bogus"], "invalid choice: 'bogus'"),
            (["curves"], "required: RUN.h5"),
            (
                ["curves", run, "--window-fraction", "0.8", "0.2"],
                "--window-fraction",
                "A < B",
            ),
            (
                ["curves", run, "--window-start", "abc", "--window-end", "1"],
                "--window-start",
            ),
            (
                ["curves", run, "--window-start", "0.1"],
                "--window-start and --window-end",
            ),
            (["curves", self.path("missing.h5")], "missing.h5' does not exist"),
            (["curves", run, "--group-by", "colour"], "--group-by: 'colour'"),
            (
                ["curves", run, "--csv", self.path("no/dir/c.csv")],
                "directory",
                "does not exist",
            ),
            (["series", run], "--png OUT.png and/or --csv OUT.csv"),
            (["maps", run, "--png-dir", out], "has no /terrain snapshots"),
            (
                ["maps", run, "--vtk", "a.vtk", "--png-dir", out],
                "either RUN.h5 or --vtk",
            ),
            (
                ["maps", "--vtk", self.path("none.vtk"), "--png-dir", out],
                "--vtk",
                "none.vtk",
            ),
            (["maps", run], "--png-dir"),
            (
                ["compare", "c.csv", "m.csv", "--quantity", "speed"],
                "--quantity: 'speed'",
            ),
            (
                ["compare", self.path("c.csv"), "m.csv", "--quantity", "sinkage"],
                "SIM.csv",
                "c.csv' does not exist",
            ),
            (["study", run, "--quantity", "dp", "--out-dir", out], "--quantity: 'dp'"),
            (["curves", run, "--lugs", "-1"], "--lugs: expected a lug count >= 0"),
            (
                ["compare", "a.csv", "b.csv", "--quantity", "sinkage", "--columns", "slip"],
                "--columns: 'slip' is not NAME=COLUMN",
            ),
        ]
        for args, *fragments in cases:
            with self.subTest(args=args):
                self.check(args, *fragments)


class UsageTest(TempDirTestCase):
    """usage.py: misspelt options and commands name the nearest valid one; --version;
    --help; the exit codes of docs/postprocess.md (0 success, 2 usage or input error)."""

    def check_usage(self, args, expected):
        result = run_cli(*args)
        self.assertEqual(result.returncode, 2, (args, result.stderr))
        self.assertEqual(result.stderr.strip(), expected)
        self.assertEqual(result.stdout, "")

    def test_misspelt_options_name_the_nearest(self):
        cases = [
            (
                ["compare", "a.csv", "b.csv", "--quantitiy", "drawbar_pull"],
                "wheelsim-post compare: error: unknown option '--quantitiy' "
                "(did you mean '--quantity'?)",
            ),
            (
                ["study", "run.h5", "--quantitiy", "sinkage", "--out-dir", "x"],
                "wheelsim-post study: error: unknown option '--quantitiy' "
                "(did you mean '--quantity'?)",
            ),
            (
                ["curves", "run.h5", "--normalized"],
                "wheelsim-post curves: error: unknown option '--normalized' "
                "(did you mean '--normalised'?)",
            ),
            (
                ["curves", "--grup-by=wheel"],  # before the missing RUN.h5 is reported
                "wheelsim-post curves: error: unknown option '--grup-by' "
                "(did you mean '--group-by'?)",
            ),
            (
                ["--verison"],
                "wheelsim-post: error: unknown option '--verison' (did you mean '--version'?)",
            ),
            (
                ["curvs", "run.h5"],
                "wheelsim-post: error: argument COMMAND: invalid choice: 'curvs' (choose "
                "from 'curves', 'series', 'approach', 'maps', 'compare', 'study', 'vtk', 'pvd', 'surface')"
                " (did you mean 'curves'?)",
            ),
            (
                ["curves", "run.h5", "--zzz"],
                "wheelsim-post curves: error: unknown option '--zzz'",
            ),
        ]
        for args, expected in cases:
            with self.subTest(args=args):
                self.check_usage(args, expected)

    def test_version(self):
        result = run_cli("--version")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertRegex(result.stdout, r"^wheelsim-post 0\.1\.0( \(git [0-9a-f]+\))?\n$")

    def test_help_exits_0(self):
        for args in (["--help"], ["curves", "--help"], ["compare", "-h"]):
            with self.subTest(args=args):
                result = run_cli(*args)
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertIn("usage: wheelsim-post", result.stdout)

    def test_start_up_leaves_matplotlib_out(self):
        # pyplot is ~0.5 s of every command's start-up; only a command that draws imports it
        # (plotting.pyplot). A run that writes a CSV and no PNG must not load it either.
        code = (
            "import sys\nfrom wheelsim_post import cli\ntry:\n    cli.main(sys.argv[1:])\n"
            "except SystemExit:\n    pass\nprint(sorted(m for m in sys.modules\n"
            "             if m.split('.')[0] == 'matplotlib' or m.startswith('mpl_toolkits.')))"
        )  # (Debian's matplotlib registers the bare mpl_toolkits namespace at start-up: a .pth)
        run = self.path("run.h5")
        synthetic.write_rig_run(run)
        for args in (["--version"], ["curves", run, "--csv", self.path("c.csv")]):
            with self.subTest(args=args):
                result = subprocess.run(
                    [sys.executable, "-c", code, *args], capture_output=True, text=True,
                    env=dict(os.environ, PYTHONPATH=os.path.dirname(SCRIPT)), timeout=120,
                )
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertTrue(result.stdout.rstrip().endswith("[]"), result.stdout)

    def test_project_version_comes_from_cmakelists(self):
        from wheelsim_post import usage

        root = usage.find_project_root()
        self.assertIsNotNone(root)
        with open(f"{root}/CMakeLists.txt") as f:
            self.assertIn(f"project(wheelsim VERSION {usage.project_version(root)}", f.read())
        cmake = self.path("CMakeLists.txt")
        with open(cmake, "w") as f:
            f.write(
                "cmake_minimum_required(VERSION 3.20)\n"
                "project(wheelsim VERSION 2.3.4 LANGUAGES C)\n"
            )
        self.assertEqual(usage.project_version(self.dir), "2.3.4")
        self.assertEqual(usage.find_project_root(cmake), self.dir)


class HelpTest(unittest.TestCase):
    def test_every_option_has_help(self):
        parser = build_parser()
        subparsers = next(
            a for a in parser._actions if isinstance(a, argparse._SubParsersAction)
        )
        self.assertEqual(
            sorted(subparsers.choices),
            ["approach", "compare", "curves", "maps", "pvd", "series", "study", "surface", "vtk"],
        )
        for name, sub in subparsers.choices.items():
            for action in sub._actions:
                if isinstance(action, argparse._HelpAction):
                    continue
                with self.subTest(command=name, option=action.dest):
                    self.assertTrue(action.help, f"{name} {action.dest} has no help")

    def test_time_options_state_their_unit(self):
        sub = build_parser()._subparsers._group_actions[0].choices["curves"]
        helps = {a.dest: a.help for a in sub._actions}
        self.assertIn("[s]", helps["window_start"])
        self.assertIn("[s]", helps["window_end"])


if __name__ == "__main__":
    unittest.main()
