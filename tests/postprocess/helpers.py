"""Shared test helpers: a temporary directory per test and running the wheelsim-post script."""

import contextlib
import io
import os
import subprocess
import sys
import tempfile
import unittest

import wheelsim_post

#: The entry script next to the package (found from the package, no fixed path).
SCRIPT = os.path.join(
    os.path.dirname(os.path.dirname(os.path.abspath(wheelsim_post.__file__))),
    "wheelsim-post",
)


class TempDirTestCase(unittest.TestCase):
    """A TestCase with ``self.dir``, a fresh temporary directory removed after the test."""

    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="wheelsim_post_test_")
        self.dir = self._tmp.name

    def tearDown(self):
        self._tmp.cleanup()

    def path(self, name):
        """A path inside the temporary directory."""
        return os.path.join(self.dir, name)

    def assertOneLineError(self, result, *fragments):
        """``result`` (run_cli's) failed as the tool's input errors do: exit status 2 and one
        line on stderr, 'wheelsim-post ...: error: ...', holding every one of ``fragments``."""
        self.assertEqual(result.returncode, 2, (result.stdout, result.stderr))
        lines = result.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, result.stderr)
        self.assertTrue(lines[0].startswith("wheelsim-post"), lines[0])
        self.assertIn("error:", lines[0])
        for fragment in fragments:
            self.assertIn(fragment, lines[0])


def run_cli(*args):
    """Runs wheelsim-post with this interpreter; returns the CompletedProcess (text)."""
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run(
        [sys.executable, SCRIPT, *[str(a) for a in args]],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )


def run_cli_here(*args):
    """Runs wheelsim-post's main() in this process and returns what run_cli returns: for a test
    of many short cases, where starting an interpreter (numpy, h5py, matplotlib) per case costs
    more than the case."""
    from wheelsim_post import cli

    os.environ.setdefault("MPLBACKEND", "Agg")
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            rc = cli.main([str(a) for a in args])
        except SystemExit as exc:  # argparse's usage errors
            rc = exc.code if isinstance(exc.code, int) else 1
    return subprocess.CompletedProcess(list(args), rc, out.getvalue(), err.getvalue())


def is_png(path):
    """True if ``path`` exists and starts with the PNG signature."""
    if not os.path.isfile(path) or os.path.getsize(path) < 100:
        return False
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n"
