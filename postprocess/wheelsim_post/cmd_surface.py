"""``surface``: the free-surface profile of a DEM bed or of a coupled run's checkpoint, along the
bin, against the bed depth that the run reads sinkage from and, with ``--reference``, against the
bed as prepared (docs/postprocess.md, "surface"). The particles are read by LIGGGHTS itself
(inputs/in.bed_surface, one set-up run of 0 steps), the profile by bed_surface.py."""

import os
import shutil
import subprocess
import tempfile

import numpy as np

from . import bed_surface, box_frame, mpi_launch
from .choices import split_list
from .csvio import write_csv
from .errors import PostError
from .runfile import RunFile

HELP = ("free-surface profile of a bed restart or a run's LIGGGHTS checkpoint along the bin, "
        "against the bed depth and, with --reference, against the bed as prepared")
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_STRETCH_M = 0.5
WHEEL_POSITION = "wheel/position"
READ_TIMEOUT_S = 1800  # [s] for LIGGGHTS to read a restart and dump it (nothing hangs)


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("surface", help=HELP, description=HELP)
    parser.add_argument("restart", metavar="RESTART",
                        help="a bed restart of inputs/in.soilbin (its .vars beside it) or a "
                             "coupled run's checkpoints/liggghts-<step>.restart (with --bed-vars)")
    parser.add_argument("--bed-vars", metavar="FILE.vars",
                        help="the .vars of the bed RESTART was resumed from (needed for a "
                             "checkpoint; default: RESTART.vars)")
    parser.add_argument("--reference", metavar="BED.restart",
                        help="the bed as prepared: the change of every column's top from it is "
                             "reported too")
    parser.add_argument("--run", metavar="RUN.h5",
                        help="the run file of the run that wrote RESTART: positions are also "
                             "given from the wheel centre at RESTART's step")
    grid = parser.add_mutually_exclusive_group()
    grid.add_argument("--column", type=float, metavar="M",
                      help="column width [m] (default: 2 d_max of the soil)")
    grid.add_argument("--bed-grid", action="store_true",
                      help="in.soilbin's own grid (at most 20 x 10 columns): the mean is its "
                           "bed depth, measured now")
    parser.add_argument("--y-band", metavar="LO,HI",
                        help="only the columns whose centre y [m] lies in [LO, HI] (default: "
                             "the whole width; y = 0 is the bin's axis; a negative LO as --y-band=-0.2,0.2)")
    parser.add_argument("--stretch", type=float, default=DEFAULT_STRETCH_M, metavar="M",
                        help="with --run: the means printed over stretches of this length [m] "
                             f"ahead of and behind the wheel centre (default {DEFAULT_STRETCH_M})")
    parser.add_argument("--csv", metavar="OUT.csv", help="the profile, one row per column row")
    parser.add_argument("--png", metavar="OUT.png", help="the profile plotted")
    parser.add_argument("--np", type=int, default=1, metavar="N",
                        help="LIGGGHTS ranks for reading the restart (default 1)")
    parser.add_argument("--build-dir", default=os.path.join(REPO, "build"), metavar="DIR",
                        help="wheelsim's build directory (bin/liggghts-wheel; default: build/ "
                             "of this checkout)")
    parser.set_defaults(func=run)
    return parser


def read_bed(restart, vars_file, args, label):
    """(Particles, deck values) of one restart, read by in.bed_surface in a scratch directory."""
    if not os.path.isfile(restart):
        raise PostError(f"{label}: restart file '{restart}' does not exist")
    vars_file = vars_file or restart + ".vars"
    if not os.path.isfile(vars_file):
        raise PostError(f"{label}: '{vars_file}' does not exist: a checkpoint needs --bed-vars "
                        "naming the .vars of the bed its run was resumed from")
    exe = os.path.join(args.build_dir, "bin", "liggghts-wheel")
    if not os.path.isfile(exe):
        raise PostError(f"--build-dir: '{exe}' not found: build wheelsim first (scripts/build.sh)")
    with tempfile.TemporaryDirectory(prefix="wheelsim-surface-") as work:
        # resume.in reads ${restart_file}.vars: a link to the restart with the .vars beside it
        bed = os.path.join(work, "bed.restart")
        os.symlink(os.path.abspath(restart), bed)
        shutil.copyfile(vars_file, bed + ".vars")
        dump = os.path.join(work, "particles.dump")
        cmd = mpi_launch.mpirun(args.np) + [
            exe, "-in", os.path.join(REPO, "inputs", "in.bed_surface"),
            "-var", "inputs_dir", os.path.join(REPO, "inputs"), "-var", "restart_file", bed,
            "-var", "dump_file", dump]
        try:
            proc = subprocess.run(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  text=True, check=False, timeout=READ_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            raise PostError(f"{label}: LIGGGHTS did not finish reading '{restart}' within "
                            f"{READ_TIMEOUT_S} s (a 221 000-sphere bed takes ~6 s)") from None
        tail = "\n".join(proc.stdout.splitlines()[-8:])
        if proc.returncode != 0 or not os.path.isfile(dump):
            raise PostError(f"{label}: LIGGGHTS could not read '{restart}' (exit "
                            f"{proc.returncode}); the end of its output:\n{tail}")
        values = bed_surface.parse_deck_line(proc.stdout, f"{label} '{restart}'")
        return bed_surface.read_dump(dump), values


def wheel_x_at(run_path, step):
    """(x [m] in LIGGGHTS' box, the step of the sample) of the wheel centre in the run file at
    LIGGGHTS step `step`: the sample at that step, else the last one before it."""
    with RunFile(run_path) as run_file:
        if not run_file.has_observable(WHEEL_POSITION):
            raise PostError(f"--run: '{run_path}' has no observable {WHEEL_POSITION}")
        series = run_file.observable(WHEEL_POSITION)
        origin, source = box_frame.origin_x(run_file)
    if origin is None:
        raise PostError(f"--run: where '{run_path}' started the wheel in the box is {source}")
    before = np.flatnonzero(series.step <= step)
    if before.size == 0:
        raise PostError(f"--run: '{run_path}' has no sample at or before step {step} (its first "
                        f"is step {int(series.step[0]) if len(series) else 'none'}): not the run "
                        "that wrote this checkpoint?")
    i = before[-1]
    spacing = float(np.median(np.diff(series.step))) if len(series) > 1 else 0.0
    if step - int(series.step[i]) > 2 * spacing:
        raise PostError(f"--run: '{run_path}' has no sample near step {step}: its samples "
                        f"{'end' if i == len(series) - 1 else 'pause'} at step "
                        f"{int(series.step[i])} (every {spacing:g} steps); not the run that wrote "
                        "this checkpoint, or a copy made before it?")
    return float(series.value.reshape(len(series), -1)[i, 0]) + origin, int(series.step[i])


def parse_band(text):
    if text is None:
        return None
    parts = split_list(text)
    try:
        lo, hi = (float(p) for p in parts)
    except ValueError:
        raise PostError(f"--y-band: expected LO,HI in m, got '{text}'") from None
    if not hi > lo:
        raise PostError(f"--y-band: expected LO < HI, got '{text}'")
    return lo, hi


def stretches(x_centre, values, x_wheel, length):
    """[(from, to, mean)] of `values` over successive stretches of `length` ahead of (from > 0)
    and behind the wheel centre, positions from the wheel centre [m]; stretches with no finite
    value are left out."""
    rel = x_centre - x_wheel
    out = []
    lo_k = int(np.floor(np.nanmin(rel) / length))
    hi_k = int(np.ceil(np.nanmax(rel) / length))
    for k in range(lo_k, hi_k):
        a, b = k * length, (k + 1) * length
        pick = (rel >= a) & (rel < b) & np.isfinite(values)
        if pick.any():
            out.append((a, b, float(np.mean(values[pick]))))
    return out


def equivalent_line(particles, deck):
    """The summary's line on the bed's equivalent surface (bed_surface.equivalent_surface), or
    why it has none."""
    depth = deck["bed_depth"]
    try:
        eq = bed_surface.equivalent_surface(particles, deck["bin_length"], deck["bin_width"],
                                            deck["soil_dmax"], depth)
    except PostError as exc:
        return f"  equivalent surface: none ({exc})"
    return (f"  equivalent surface {eq.level_m:.6f} m ({(eq.level_m - depth) * 1e3:+.2f} mm from "
            f"the bed depth): the level of a bed packed as its core (solid fraction "
            f"{eq.core_solid_fraction:.4f} over z {eq.core_bottom_m:.4f}-{eq.core_top_m:.4f} m, "
            f"{eq.spheres} spheres in the interior) that holds the same solid volume")


def run(args):
    """Reads the restart(s), prints the summary, writes the CSV and PNG; returns 0."""
    if args.np < 1:
        raise PostError(f"--np: expected a number of ranks >= 1, got {args.np}")
    if not args.stretch > 0:
        raise PostError(f"--stretch: expected a length > 0 m, got {args.stretch:g}")
    band = parse_band(args.y_band)
    particles, deck = read_bed(args.restart, args.bed_vars, args, "RESTART")
    length, width, depth = deck["bin_length"], deck["bin_width"], deck["bed_depth"]
    if args.bed_grid:
        x_edges, y_edges = bed_surface.bed_grid(length, width, deck["soil_dmax"])
    else:
        x_edges, y_edges = bed_surface.column_grid(
            length, width, args.column if args.column is not None else 2 * deck["soil_dmax"])
    tops = bed_surface.column_tops(particles, x_edges, y_edges)
    surface, used = bed_surface.profile_x(tops, y_edges, band)
    change = None
    if args.reference:
        ref_particles, ref_deck = read_bed(args.reference, None, args, "--reference")
        if (ref_deck["bin_length"], ref_deck["bin_width"]) != (length, width):
            raise PostError(f"--reference: its bin is {ref_deck['bin_length']:g} x "
                            f"{ref_deck['bin_width']:g} m, RESTART's {length:g} x {width:g} m: "
                            "not the same bed")
        diff = tops - bed_surface.column_tops(ref_particles, x_edges, y_edges)
        change, _ = bed_surface.profile_x(diff, y_edges, band)
    x_wheel = None
    if args.run:
        x_wheel, wheel_step = wheel_x_at(args.run, deck["step"])
    x_centre = 0.5 * (x_edges[:-1] + x_edges[1:])

    print(f"{args.restart}: step {deck['step']}, {particles.x.size} spheres; bin {length:g} x "
          f"{width:g} m; {len(x_edges) - 1} x {len(y_edges) - 1} columns of "
          f"{(x_edges[1] - x_edges[0]) * 1e3:.1f} x {(y_edges[1] - y_edges[0]) * 1e3:.1f} mm"
          + (f", y in [{band[0]:g}, {band[1]:g}] m" if band else ""))
    print(f"  mean surface {np.nanmean(surface):.6f} m; the bed depth recorded at preparation "
          f"(the runs' sinkage reference) {depth:.6f} m")
    equivalent = equivalent_line(particles, deck)
    print(equivalent)
    if change is not None:
        print(f"  mean change from the bed as prepared ({args.reference}): "
              f"{np.nanmean(change) * 1e3:+.2f} mm over the same columns")
    if x_wheel is not None:
        print(f"  wheel centre at x = {x_wheel:.4f} m (run file sample of step {wheel_step})")
        print(f"  means over {args.stretch:g} m stretches, from the wheel centre "
              "(surface − bed depth" + (", change from the bed as prepared" if change is not None
                                         else "") + ") [mm]:")
        rel = stretches(x_centre, surface - depth, x_wheel, args.stretch)
        rel_change = ({a: m for a, _, m in stretches(x_centre, change, x_wheel, args.stretch)}
                      if change is not None else {})
        for a, b, m in rel:
            extra = f"   {rel_change[a] * 1e3:+8.2f}" if a in rel_change else ""
            print(f"    {a:+7.2f} … {b:+7.2f} m   {m * 1e3:+8.2f}{extra}")
    if args.csv:
        header = ["x_from_m", "x_to_m", "x_centre_m"]
        if x_wheel is not None:
            header.append("x_from_wheel_centre_m")
        header += ["surface_m", "surface_minus_bed_depth_m"]
        if change is not None:
            header.append("change_from_reference_m")
        header.append("columns")
        rows = []
        for i, xc in enumerate(x_centre):
            row = [float(x_edges[i]), float(x_edges[i + 1]), float(xc)]
            if x_wheel is not None:
                row.append(float(xc - x_wheel))
            row += [float(surface[i]), float(surface[i] - depth)]
            if change is not None:
                row.append(float(change[i]))
            row.append(int(used[i]))
            rows.append(row)
        comments = [f"wheelsim-post {' '.join(args.argv)}",
                    f"restart {args.restart} at step {deck['step']}; bed depth {depth!r} m",
                    equivalent.strip()]
        write_csv(args.csv, comments, header, rows)
    if args.png:
        plot(args.png, x_centre, surface - depth, change, x_wheel, args.restart)
    return 0


def plot(path, x_centre, relative, change, x_wheel, title):
    """The profile [mm] against x, the change from the bed as prepared beside it."""
    from . import plotting

    fig, (ax,) = plotting.panel_grid(1, width=9.0, height=4.0)
    ax.plot(x_centre, relative * 1e3, "-", color="tab:brown", label="surface − bed depth")
    if change is not None:
        ax.plot(x_centre, change * 1e3, "-", color="tab:blue", label="change from the bed as prepared")
    ax.axhline(0.0, color="k", lw=0.6)
    if x_wheel is not None:
        ax.axvline(x_wheel, color="tab:red", ls="--", lw=0.8, label="wheel centre")
    ax.set_xlabel("x along the bin [m]")
    ax.set_ylabel("height [mm]")
    ax.set_title(os.path.basename(title), fontsize=9)
    ax.legend(fontsize=8)
    plotting.save(fig, path)
