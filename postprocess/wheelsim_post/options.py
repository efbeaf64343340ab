"""argparse options shared by several subcommands, and their conversion."""

from .steady import make_window


def add_window_options(parser):
    """Adds --window-start/--window-end [s] and --window-fraction A B."""
    group = parser.add_argument_group(
        "steady-state window (default: --window-fraction 0.5 1, the test phase's second half)"
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


def window_from_args(args):
    """The steady.Window of parsed window options."""
    return make_window(args.window_start, args.window_end, args.window_fraction)
