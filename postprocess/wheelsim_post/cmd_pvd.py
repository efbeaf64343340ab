"""``pvd``: a ParaView collection (.pvd) with physical times for a series of per-step files.

For LIGGGHTS dumps such as ``dump custom/vtk N particles_*.vtk ...``: the step of each file is
the number that ``*`` stands for; its time is ``t0 + (step - step0) * dt`` (default t0 = 0,
step0 = 0, so ``step * dt``). ``--like`` takes (step0, t0) from another collection, e.g. the
wheel_surface.pvd that fix wheel/cosim writes with LIGGGHTS' own time, so that both series share
one time axis in ParaView (docs/paraview.md).
"""

import glob
import math
import os
import re

from .errors import PostError
from .paraview import read_pvd, step_of_name, write_pvd

HELP = "ParaView collection (.pvd) with physical times for per-step files, e.g. particle dumps"


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("pvd", help=HELP, description=HELP)
    parser.add_argument(
        "pattern",
        metavar="PATTERN",
        help="quoted file pattern with one '*' in the file name standing for the step, e.g. "
        "'post/particles_*.vtk' (files where '*' is not a whole number are skipped)",
    )
    parser.add_argument("--dt", type=float, required=True, metavar="S", help="time step [s]")
    parser.add_argument(
        "--out", required=True, metavar="FILE.pvd", help="collection to write (atomically)"
    )
    origin = parser.add_mutually_exclusive_group()
    origin.add_argument(
        "--origin",
        nargs=2,
        metavar=("STEP0", "T0"),
        help="time T0 [s] of step STEP0 (default: 0 0, time = step * dt)",
    )
    origin.add_argument(
        "--like",
        metavar="OTHER.pvd",
        help="take STEP0 and T0 from the first data set of another collection whose file "
        "names end in the step, e.g. fix wheel/cosim's wheel_surface.pvd",
    )
    parser.set_defaults(func=run)
    return parser


def _origin(args):
    if args.like is not None:
        entries = read_pvd(args.like)
        if not entries:
            raise PostError(f"--like: the collection '{args.like}' lists no data set")
        time, name = entries[0]
        step = step_of_name(name)
        if step is None:
            raise PostError(f"--like: the file name '{name}' in '{args.like}' ends in no step")
        return step, time
    if args.origin is not None:
        try:
            return int(args.origin[0]), float(args.origin[1])
        except ValueError:
            raise PostError(
                f"--origin: expected a step and a time [s], got {' '.join(args.origin)}"
            ) from None
    return 0, 0.0


def matching_files(pattern):
    """(step, path) of the files matching ``pattern`` (one '*' in the file name), by step."""
    name = os.path.basename(pattern)
    if name.count("*") != 1 or "*" in os.path.dirname(pattern) or "?" in pattern:
        raise PostError(
            f"pattern '{pattern}': expected exactly one '*' (the step) in the file name, "
            "e.g. 'particles_*.vtk'"
        )
    head, tail = name.split("*")
    exact = re.compile(re.escape(head) + r"(\d+)" + re.escape(tail) + "$")
    found = []
    for path in glob.glob(os.path.join(glob.escape(os.path.dirname(pattern)), name)):
        match = exact.match(os.path.basename(path))
        if match:
            found.append((int(match.group(1)), path))
    return sorted(found)


def run(args):
    """Writes the collection; prints how many files it lists and their time range."""
    if not (math.isfinite(args.dt) and args.dt > 0):
        raise PostError(f"--dt: expected a time step > 0 s, got {args.dt}")
    step0, t0 = _origin(args)
    files = matching_files(args.pattern)
    if not files:
        raise PostError(f"pattern '{args.pattern}': no file matches with a step for '*'")
    entries = [(t0 + (step - step0) * args.dt, path) for step, path in files]
    write_pvd(args.out, entries)
    print(
        f"wrote {args.out}: {len(entries)} files, steps {files[0][0]}..{files[-1][0]}, "
        f"t = {entries[0][0]:.9g}..{entries[-1][0]:.9g} s"
    )
    return 0
