"""``vtk``: SCM terrain snapshots of a run file as a ParaView series of VTK image data.

One ``PREFIX_<step>.vti`` per snapshot step (ImageData, binary base64 Float64 point data: every
field the run file has at that step, e.g. height, sinkage, pressure, shear_stress; grid point
(i, j) at x = x0 + j*spacing, y = y0 + i*spacing, z = 0) and ``PREFIX.pvd`` listing them with the
snapshots' simulated times [s]. In ParaView, "Warp By Scalar" with ``height`` lifts the flat
image to the soil surface (docs/paraview.md).
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


def write_step(run_file, step, fields, path):
    """Writes the .vti of one snapshot step; returns its time [s]."""
    snaps = [run_file.snapshot(field, step) for field in fields]
    first = snaps[0]
    for snap in snaps[1:]:
        grid = (snap.value.shape, snap.x0, snap.y0, snap.spacing)
        if grid != (first.value.shape, first.x0, first.y0, first.spacing):
            raise PostError(
                f"run file '{run_file.path}': at step {step} the snapshot of '{snap.field}' "
                f"(shape {snap.value.shape}, x0 {snap.x0}, y0 {snap.y0}, spacing "
                f"{snap.spacing}) is not on the grid of '{first.field}' (shape "
                f"{first.value.shape}, x0 {first.x0}, y0 {first.y0}, spacing {first.spacing})"
            )
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
    try:
        os.makedirs(args.out, exist_ok=True)
    except OSError as exc:
        raise PostError(f"--out: cannot create '{args.out}': {exc.strerror}") from None
    with RunFile(args.run) as run_file:
        steps = step_fields(run_file)
        if not steps:
            raise PostError(f"run file '{args.run}' has no /terrain snapshots")
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
