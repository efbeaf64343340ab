"""The ``wheelsim-post`` command line: argparse set-up and error reporting.

Every input error ends the program with one line ``wheelsim-post <command>: error: ...`` on
stderr and exit status 2; a misspelt option or command names the nearest valid one (usage.py).
"""

import sys

from . import (cmd_approach, cmd_compare, cmd_curves, cmd_maps, cmd_pvd, cmd_series, cmd_study,
               cmd_surface, cmd_vtk)
from .errors import PostError
from .usage import EXIT_USAGE, UsageParser, add_version

COMMANDS = (cmd_curves, cmd_series, cmd_approach, cmd_maps, cmd_compare, cmd_study, cmd_vtk,
            cmd_pvd, cmd_surface)


def build_parser():
    """The top-level parser with one subparser per command."""
    parser = UsageParser(
        prog="wheelsim-post",
        description="Post-processing of wheelsim run files (docs/postprocess.md). "
        "Exit status: 0 success, 2 usage or input error.",
    )
    add_version(parser, "wheelsim-post")
    subparsers = parser.add_subparsers(
        dest="command", metavar="COMMAND", parser_class=UsageParser
    )
    subparsers.required = True
    for command in COMMANDS:
        command.add_parser(subparsers)
    return parser


def main(argv=None):
    """Parses ``argv`` and runs the command; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)  # for files that record it
    try:
        return args.func(args)
    except PostError as exc:
        print(f"wheelsim-post {args.command}: error: {exc}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
