"""argparse options shared by several subcommands, and their conversion."""

from .errors import PostError
from .steady import make_window


def add_window_options(parser):
    """Adds --window-start/--window-end [s], --window-fraction A B and --lugs N."""
    group = parser.add_argument_group(
        "steady-state window (default: the most whole lug passes, or wheel revolutions, that "
        "fit in the second half of the test phase, ending at its end)"
    )
    group.add_argument(
        "--window-start",
        type=float,
        metavar="S",
        help="window start [s] after the first test-phase (phase == 3) sample",
    )
    group.add_argument(
        "--window-end",
        type=float,
        metavar="S",
        help="window end [s] after the first test-phase sample (included)",
    )
    group.add_argument(
        "--window-fraction",
        type=float,
        nargs=2,
        metavar=("A", "B"),
        help="window from A to B (fractions in [0, 1]) of the test-phase duration",
    )
    group.add_argument(
        "--lugs",
        type=int,
        metavar="N",
        help="lug count of the wheel for the default window (0: whole revolutions; "
        "default: from the run's mesh properties or meshes/catalog.toml)",
    )


def window_from_args(args):
    """The steady.Window of parsed window options."""
    if args.lugs is not None and args.lugs < 0:
        raise PostError(f"--lugs: expected a lug count >= 0, got {args.lugs}")
    return make_window(args.window_start, args.window_end, args.window_fraction)
