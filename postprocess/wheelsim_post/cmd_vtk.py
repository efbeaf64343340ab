"""``vtk``: SCM terrain snapshots of a run file as a ParaView series of VTK image data.

One ``PREFIX_<step>.vti`` per snapshot step (ImageData, binary base64 Float64 point data: every
field the run file has at that step, e.g. height, sinkage, pressure, shear_stress; grid point
(i, j) at x = x0 + j*spacing, y = y0 + i*spacing, z = 0) and ``PREFIX.pvd`` listing them with the
snapshots' simulated times [s]. In ParaView, "Warp By Scalar" with ``height`` lifts the flat
image to the soil surface (docs/paraview.md). Every input is checked (the options, the run file,
every snapshot's grid) before the output directory is created: bad input leaves nothing behind.
"""

import os

from .errors import PostError
from .paraview import vti_text, write_atomically, write_pvd
from .runfile import RunFile

HELP = "SCM terrain snapshots of RUN.h5 as VTK image data (.vti) plus a .pvd for ParaView"


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("vtk", help=HELP, description=HELP)
    parser.add_argument("run", metavar="RUN.h5", help="run file with /terrain snapshots")
    parser.add_argument(
        "--out", required=True, metavar="DIR", help="directory for the files (created if missing)"
    )
    parser.add_argument(
        "--prefix",
        default="terrain",
        metavar="NAME",
        help="file names NAME_<step>.vti and NAME.pvd (default: terrain)",
    )
    parser.set_defaults(func=run)
    return parser


def step_fields(run_file):
    """{step: [fields with a snapshot at that step]} (fields in display order)."""
    by_step = {}
    for field in run_file.snapshot_fields():
        for step in run_file.snapshot_steps(field):
            by_step.setdefault(step, []).append(field)
    return dict(sorted(by_step.items()))


def check_grids(run_file, steps):
    """Checks every snapshot of ``steps`` ({step: fields}) without reading its values: well
    formed, and the fields of a step on one grid (one image per step); PostError naming the
    first that is not."""
    for step, fields in steps.items():
        first = run_file.snapshot_grid(fields[0], step)
        for field in fields[1:]:
            grid = run_file.snapshot_grid(field, step)
            if grid != first:
                raise PostError(
                    f"run file '{run_file.path}': at step {step} the snapshot of '{field}' "
                    f"(shape {grid[0]}, x0 {grid[1]}, y0 {grid[2]}, spacing {grid[3]}) is not "
                    f"on the grid of '{fields[0]}' (shape {first[0]}, x0 {first[1]}, y0 "
                    f"{first[2]}, spacing {first[3]})"
                )


def write_step(run_file, step, fields, path):
    """Writes the .vti of one snapshot step (its grids checked by check_grids); returns its
    time [s]."""
    snaps = [run_file.snapshot(field, step) for field in fields]
    first = snaps[0]
    text = vti_text(
        first.value.shape,
        (first.x0, first.y0, 0.0),
        first.spacing,
        {snap.field: snap.value for snap in snaps},
        time=first.time,
        step=step,
    )
    write_atomically(path, text)
    return first.time


def run(args):
    """Writes the series; prints the file count, the fields and the time range."""
    if not args.prefix or os.sep in args.prefix:
        raise PostError(
            f"--prefix: expected a file name prefix (no '{os.sep}'), got '{args.prefix}'"
        )
    with RunFile(args.run) as run_file:
        steps = step_fields(run_file)
        if not steps:
            raise PostError(f"run file '{args.run}' has no /terrain snapshots")
        check_grids(run_file, steps)
        try:
            os.makedirs(args.out, exist_ok=True)
        except OSError as exc:
            raise PostError(f"--out: cannot create '{args.out}': {exc.strerror}") from None
        entries = []
        for step, fields in steps.items():
            path = os.path.join(args.out, f"{args.prefix}_{step:09d}.vti")
            entries.append((write_step(run_file, step, fields, path), path))
    names = sorted({f for fields in steps.values() for f in fields})
    pvd = os.path.join(args.out, f"{args.prefix}.pvd")
    write_pvd(pvd, entries)
    print(
        f"wrote {pvd}: {len(entries)} snapshots ({', '.join(names)}), "
        f"t = {entries[0][0]:.9g}..{entries[-1][0]:.9g} s"
    )
    return 0
