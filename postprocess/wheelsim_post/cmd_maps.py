"""``maps``: SCM terrain snapshots of a run, or unrolled contact pressure of VTK wheel surfaces.

Every input is checked (the options, the run file and each snapshot to draw, or every VTK file)
before the PNG directory is created: bad input leaves nothing behind.
"""

import math
import os

import numpy as np

from .errors import PostError
from .choices import split_list
from .plotting import panel_grid, save
from .runfile import RunFile
from .vtk import (
    bounding_box_centre,
    read_wheel_surface,
    unrolled_pressure,
    unrolled_triangles,
)

HELP = "maps of SCM terrain snapshots (RUN.h5) or of wheel-surface contact pressure (--vtk)"


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("maps", help=HELP, description=HELP)
    parser.add_argument(
        "run", nargs="?", metavar="RUN.h5", help="run file with /terrain snapshots"
    )
    parser.add_argument(
        "--vtk",
        nargs="+",
        metavar="FILE.vtk",
        help="wheel-surface files of fix wheel/cosim (instead of RUN.h5)",
    )
    parser.add_argument(
        "--png-dir",
        required=True,
        metavar="DIR",
        help="directory for the PNG files (created if missing)",
    )
    snap = parser.add_argument_group("SCM snapshots (with RUN.h5)")
    snap.add_argument(
        "--field",
        metavar="F,...",
        help="comma-separated fields, e.g. height, sinkage, plastic_sinkage, pressure, "
        "shear_stress, shear_displacement (default: all the file has)",
    )
    which = snap.add_mutually_exclusive_group()
    which.add_argument("--step", type=int, metavar="N", help="the snapshot of step N")
    which.add_argument(
        "--time", type=float, metavar="T", help="the snapshot nearest to time T [s]"
    )
    which.add_argument(
        "--all", action="store_true", help="every snapshot (default: the last one)"
    )
    wheel = parser.add_argument_group("wheel surface (with --vtk)")
    wheel.add_argument(
        "--centre",
        type=float,
        nargs=3,
        metavar=("X", "Y", "Z"),
        help="wheel centre [m] in the file's (world) frame, e.g. f_ID[8..10] of the fix "
        "(default: centre of the points' bounding box)",
    )
    wheel.add_argument(
        "--binned",
        action="store_true",
        help="draw the area-weighted mean pressure on an (angle, y) grid instead of "
        "the triangles themselves",
    )
    wheel.add_argument(
        "--angle-bin",
        type=float,
        default=2.0,
        metavar="DEG",
        help="with --binned: angular bin width [deg] (default 2)",
    )
    wheel.add_argument(
        "--axial-bins",
        type=int,
        default=30,
        metavar="N",
        help="with --binned: number of bins across the wheel width along y (default 30)",
    )
    wheel.add_argument(
        "--angle-range",
        type=float,
        nargs=2,
        default=(-180.0, 180.0),
        metavar=("MIN", "MAX"),
        help="angle range [deg] shown; 0 is below the axle, + towards +x "
        "(default -180 180)",
    )
    parser.set_defaults(func=run)
    return parser


def _output_dir(path):
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as exc:
        raise PostError(f"--png-dir: cannot create '{path}': {exc.strerror}") from None
    return path


def select_steps(steps, step, time, every, times_of):
    """Steps to draw from ``steps`` (sorted) for --step/--time/--all (default: the last)."""
    if every:
        return list(steps)
    if step is not None:
        if step not in steps:
            raise PostError(
                f"--step: no snapshot at step {step} (steps: "
                f"{', '.join(str(s) for s in steps)})"
            )
        return [step]
    if time is not None:
        times = np.array([times_of(s) for s in steps])
        return [steps[int(np.argmin(np.abs(times - time)))]]
    return [steps[-1]]


def plot_snapshot(snap, path):
    """An image of a snapshot with x/y [m] axes and a colour bar with its unit."""
    left, right, bottom, top = snap.extent()
    ratio = (top - bottom) / (right - left)
    fig, (ax,) = panel_grid(1, width=8.0, height=min(max(6.5 * ratio + 1.2, 2.5), 9.0))
    image = ax.imshow(
        snap.value,
        origin="lower",
        extent=snap.extent(),
        aspect="equal",
        interpolation="nearest",
        cmap="viridis",
    )
    from mpl_toolkits.axes_grid1 import make_axes_locatable  # matplotlib on first plot

    bar_axes = make_axes_locatable(ax).append_axes("right", size="3%", pad=0.1)
    bar = fig.colorbar(image, cax=bar_axes)
    unit = "-" if snap.unit == "1" else snap.unit
    bar.set_label(f"{snap.field} [{unit}]")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{snap.field}, step {snap.step}, t = {snap.time:g} s")
    save(fig, path)


def snapshot_plan(args, run_file):
    """The (field, step) of each SCM snapshot of ``run_file`` to draw for --field and
    --step/--time/--all, every one checked (RunFile.snapshot_grid) before anything is written."""
    present = run_file.snapshot_fields()
    if not present:
        raise PostError(f"run file '{args.run}' has no /terrain snapshots")
    fields = split_list(args.field) if args.field is not None else present
    for field in fields:
        if field not in present:
            raise PostError(
                f"--field: run file '{args.run}' has no snapshots of '{field}' "
                f"(it has: {', '.join(present)})"
            )
    plan = []
    for field in fields:
        steps = run_file.snapshot_steps(field)
        chosen = select_steps(
            steps,
            args.step,
            args.time,
            args.all,
            lambda s, f=field: run_file.snapshot_time(f, s),
        )
        plan += [(field, step) for step in chosen]
    for field, step in plan:
        run_file.snapshot_grid(field, step)
    return plan


def run_snapshots(run_file, plan, out_dir):
    """Maps of the SCM snapshots ``plan`` (snapshot_plan) of ``run_file``; returns the PNG
    paths."""
    written = []
    for field, step in plan:
        snap = run_file.snapshot(field, step)
        path = os.path.join(out_dir, f"{field}_{step:09d}.png")
        plot_snapshot(snap, path)
        written.append(path)
    return written


def _binned(ax, surface, centre, args):
    """pcolormesh of unrolled_pressure() on the --angle-bin × --axial-bins grid."""
    lo, hi = args.angle_range
    bins = max(1, int(round((hi - lo) / args.angle_bin)))
    angle_edges = np.linspace(lo, hi, bins + 1)
    y = surface.points[:, 1] - centre[1]
    pad = 1e-9 * max(1.0, float(np.ptp(y)))
    y_edges = np.linspace(y.min() - pad, y.max() + pad, args.axial_bins + 1)
    grid = unrolled_pressure(surface, centre, angle_edges, y_edges)
    return ax.pcolormesh(
        angle_edges, y_edges, np.ma.masked_invalid(grid), cmap="inferno"
    )


def _triangles(ax, surface, centre):
    """Each triangle drawn in the (θ, y) plane, coloured by its pressure (loaded on top)."""
    from matplotlib.collections import PolyCollection  # matplotlib on first plot (plotting.py)

    polygons = unrolled_triangles(surface, centre)
    pressure = surface.cell_data["contact_pressure"]
    order = np.argsort(pressure, kind="stable")
    collection = PolyCollection(
        polygons[order], array=pressure[order], cmap="inferno", edgecolors="face"
    )
    collection.set_linewidth(0.2)
    ax.add_collection(collection)
    y = polygons[..., 1]
    ax.set_ylim(y.min(), y.max())
    return collection


def plot_wheel_surface(surface, centre, args, path):
    """The unrolled contact-pressure map of one wheel surface."""
    fig, (ax,) = panel_grid(1, width=9.0, height=4.0)
    if args.binned:
        mappable = _binned(ax, surface, centre, args)
    else:
        mappable = _triangles(ax, surface, centre)
    ax.set_xlim(*args.angle_range)
    bar = fig.colorbar(mappable, ax=ax)
    bar.set_label("contact pressure [Pa]")
    ax.set_xlabel("angle about the axle θ [deg] (0 below the axle, + towards +x)")
    ax.set_ylabel("axial position y − y_centre [m]")
    when = "" if surface.step < 0 else f", step {surface.step}, t = {surface.time:g} s"
    ax.set_title(f"{os.path.basename(surface.path)}{when}", fontsize=9)
    save(fig, path)


def check_vtk_inputs(args):
    """PostError naming the first bad wheel-surface option or --vtk file (each file read)."""
    lo, hi = args.angle_range
    if not (-360.0 <= lo < hi <= 360.0):
        raise PostError(f"--angle-range: expected MIN < MAX [deg], got {lo:g} {hi:g}")
    if not (args.angle_bin > 0.0 and math.isfinite(args.angle_bin)):
        raise PostError(f"--angle-bin: expected > 0 deg, got {args.angle_bin:g}")
    if args.axial_bins < 1:
        raise PostError(f"--axial-bins: expected >= 1, got {args.axial_bins}")
    if args.centre is not None and not all(math.isfinite(c) for c in args.centre):
        raise PostError(
            "--centre: expected a finite point X Y Z [m], got "
            + " ".join(f"{c:g}" for c in args.centre)
        )
    for vtk_path in args.vtk:
        read_wheel_surface(vtk_path)  # parsed again when drawn: one surface in memory at a time


def run_vtk(args, out_dir):
    """Unrolled pressure maps of args.vtk (checked by check_vtk_inputs); returns the PNG
    paths."""
    written = []
    for vtk_path in args.vtk:
        surface = read_wheel_surface(vtk_path)
        centre = np.array(args.centre) if args.centre else bounding_box_centre(surface)
        stem = os.path.splitext(os.path.basename(vtk_path))[0]
        path = os.path.join(out_dir, f"{stem}_pressure.png")
        plot_wheel_surface(surface, centre, args, path)
        written.append(path)
    return written


def run(args):
    """Runs the subcommand; returns the exit status."""
    if (args.run is None) == (args.vtk is None):
        raise PostError("give either RUN.h5 or --vtk FILE.vtk ..., not both or neither")
    if args.vtk is not None and (
        args.field or args.step is not None or args.time is not None or args.all
    ):
        raise PostError(
            "--field/--step/--time/--all apply to RUN.h5 snapshots, not --vtk"
        )
    if args.time is not None and not (math.isfinite(args.time) and args.time >= 0.0):
        raise PostError(f"--time: expected a time >= 0 s, got {args.time:g}")
    if args.vtk is not None:
        check_vtk_inputs(args)
        written = run_vtk(args, _output_dir(args.png_dir))
    else:
        with RunFile(args.run) as run_file:
            plan = snapshot_plan(args, run_file)
            written = run_snapshots(run_file, plan, _output_dir(args.png_dir))
    for path in written:
        print(f"wrote {path}")
    return 0
