"""Command-line usage shared by wheelsim's Python tools (wheelsim-post, wheel-sweep).

``UsageParser`` is an ``argparse.ArgumentParser`` whose errors are one line on stderr with exit
status 2 (``EXIT_USAGE``), and which names the nearest valid spelling of a misspelt option or
subcommand::

    wheelsim-post curves: error: unknown option '--quantitiy' (did you mean '--quantity'?)

Use it for the top-level parser and pass ``parser_class=UsageParser`` to ``add_subparsers`` so
subcommands behave the same; an unknown option after a subcommand is reported by that
subcommand's parser with its own options as candidates (this needs ``dest`` set on
``add_subparsers``).

``add_version(parser, prog)`` adds ``--version``, printing ``<prog> <version>`` with the version
of the top-level CMakeLists.txt (``project(wheelsim VERSION x.y.z ...)``) read at run time, and
the git revision of the checkout when it is cheaply available (``<prog> 0.1.0 (git 4f0ee74)``).

Exit codes of tools built on this module: 0 success (also ``--help``, ``--version``), 2 usage
or input error.
"""

import argparse
import difflib
import os
import re
import subprocess
import sys

EXIT_USAGE = 2

# Used when neither a CMakeLists.txt above this file nor an installed VERSION file is found.
FALLBACK_VERSION = "0.1.0"
# An installed copy (cmake --install): <prefix>/share/wheelsim/VERSION holds "<version> <git rev>",
# written by the build (cmake/WheelsimInstall.cmake); this module is share/wheelsim/postprocess/
# wheelsim_post/usage.py there.
_INSTALLED_VERSION_FILE = os.path.join(
    os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__)))), "VERSION")

_PROJECT_VERSION = re.compile(r"project\s*\(\s*wheelsim\s+VERSION\s+([0-9][0-9A-Za-z.\-]*)")
_INVALID_CHOICE = re.compile(r"invalid choice: '([^']*)' \(choose from (.*)\)")


def nearest(word, candidates):
    """The candidate closest to ``word`` (difflib ratio >= 0.6), or None."""
    matches = difflib.get_close_matches(word, list(candidates), n=1, cutoff=0.6)
    return matches[0] if matches else None


def _did_you_mean(word, candidates):
    guess = nearest(word, candidates)
    return f" (did you mean '{guess}'?)" if guess else ""


class UsageParser(argparse.ArgumentParser):
    """An ArgumentParser with one-line errors, exit status 2 and did-you-mean suggestions."""

    def error(self, message):
        match = _INVALID_CHOICE.search(message)
        if match:
            choices = [c.strip().strip("'\"") for c in match.group(2).split(",")]
            message = message + _did_you_mean(match.group(1), choices)
        elif message.startswith("the following arguments are required"):
            # 'cmd --verison' fails on the missing positional first: name the misspelling.
            bad = self.first_unknown_option(getattr(self, "_last_args", None) or [])
            if bad:
                message = f"unknown option '{bad}'" + _did_you_mean(
                    bad, self.option_strings()
                )
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")

    def is_known_option(self, name):
        """True if ``name`` is an option of this parser or (with allow_abbrev) a unique
        prefix of one."""
        options = self.option_strings()
        if name in options:
            return True
        prefixed = [o for o in options if o.startswith(name)] if self.allow_abbrev else []
        return len(prefixed) == 1

    def first_unknown_option(self, args):
        """The first option-like token of ``args`` this parser does not know (None if none)."""
        for token in args:
            if token == "--":
                return None
            if not token.startswith("-") or len(token) < 2:
                continue
            try:
                float(token)
                continue
            except ValueError:
                pass
            name = token.split("=", 1)[0]
            if not self.is_known_option(name):
                return name
        return None

    def parse_known_args(self, args=None, namespace=None):
        self._last_args = list(sys.argv[1:] if args is None else args)
        return super().parse_known_args(args, namespace)

    def option_strings(self):
        """All option strings of this parser ('--quantity', '-h', ...)."""
        return [s for action in self._actions for s in action.option_strings]

    def unknown_arguments(self, extras):
        """Reports the first of ``extras`` (arguments nobody parsed) as a usage error."""
        token = extras[0]
        if token.startswith("-") and len(token) > 1:
            name = token.split("=", 1)[0]
            self.error(
                f"unknown option '{name}'" + _did_you_mean(name, self.option_strings())
            )
        self.error(f"unexpected argument '{token}'")

    def chosen_subparser(self, namespace):
        """The innermost subcommand parser selected in ``namespace`` (self if none)."""
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                if action.dest in (None, argparse.SUPPRESS):
                    continue
                sub = action.choices.get(getattr(namespace, action.dest, None))
                if isinstance(sub, UsageParser):
                    return sub.chosen_subparser(namespace)
                if sub is not None:
                    return sub
        return self

    def parse_args(self, args=None, namespace=None):
        namespace, extras = self.parse_known_args(args, namespace)
        if extras:
            parser = self.chosen_subparser(namespace)
            if isinstance(parser, UsageParser):
                parser.unknown_arguments(extras)
            self.unknown_arguments(extras)
        return namespace


def find_project_root(start=None):
    """The nearest directory at or above ``start`` (default: this file's) holding the
    top-level CMakeLists.txt of wheelsim, or None."""
    directory = os.path.dirname(os.path.realpath(start or __file__))
    while True:
        path = os.path.join(directory, "CMakeLists.txt")
        if os.path.isfile(path):
            try:
                with open(path, encoding="utf-8") as stream:
                    if _PROJECT_VERSION.search(stream.read()):
                        return directory
            except OSError:
                pass
        parent = os.path.dirname(directory)
        if parent == directory:
            return None
        directory = parent


def project_version(root=None):
    """The version x.y.z in ``project(wheelsim VERSION x.y.z`` of the top-level CMakeLists.txt
    (FALLBACK_VERSION if there is none)."""
    root = root or find_project_root()
    if root:
        try:
            with open(os.path.join(root, "CMakeLists.txt"), encoding="utf-8") as stream:
                match = _PROJECT_VERSION.search(stream.read())
            if match:
                return match.group(1)
        except OSError:
            pass
    return FALLBACK_VERSION


def git_revision(root):
    """The short git revision of the checkout at ``root`` ('+dirty' appended if the working
    tree differs), or None when git or the checkout is not there (2 s time limit)."""
    if not root or not os.path.exists(os.path.join(root, ".git")):
        return None
    try:
        rev = subprocess.run(
            ["git", "-C", root, "rev-parse", "--short", "HEAD"],
            capture_output=True,
            text=True,
            timeout=2,
        )
    except (OSError, subprocess.SubprocessError):
        return None
    if rev.returncode != 0 or not rev.stdout.strip():
        return None
    return rev.stdout.strip()


def installed_version():
    """(version, git revision) from an installed copy's VERSION file, or None."""
    try:
        with open(_INSTALLED_VERSION_FILE, encoding="utf-8") as stream:
            fields = stream.read().split()
    except OSError:
        return None
    return (fields[0], fields[1] if len(fields) > 1 else None) if fields else None


def version_text(prog, start=None):
    """'<prog> <version>' plus ' (git <rev>)' when available."""
    root = find_project_root(start)
    installed = None if root else installed_version()
    if installed:
        version, rev = installed
        return f"{prog} {version} (git {rev})" if rev else f"{prog} {version}"
    text = f"{prog} {project_version(root)}"
    rev = git_revision(root)
    return f"{text} (git {rev})" if rev else text


class _VersionAction(argparse.Action):
    """--version: computed when asked (so --help does not run git), printed on stdout."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, prog=None, start=None, **kw):
        super().__init__(option_strings, dest=dest, nargs=0, default=argparse.SUPPRESS, **kw)
        self.prog_name = prog
        self.start = start

    def __call__(self, parser, namespace, values, option_string=None):
        sys.stdout.write(version_text(self.prog_name or parser.prog, self.start) + "\n")
        parser.exit(0)


def add_version(parser, prog=None, start=None):
    """Adds --version to ``parser``: prints '<prog> <version> (git <rev>)' and exits 0.
    ``start`` is a file inside the checkout (default: this module) used to find the
    top-level CMakeLists.txt."""
    parser.add_argument(
        "--version",
        action=_VersionAction,
        prog=prog,
        start=start,
        help="print the program's version (and git revision) and exit",
    )
