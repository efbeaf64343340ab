"""``series``: time histories of observables of one run, phases shaded (PNG) and as CSV."""

import numpy as np

from .csvio import write_csv
from .errors import PostError
from .choices import split_list
from .plotting import panel_grid, save, shade_phases
from .runfile import RunFile

HELP = "time histories of observables of one run (phases shaded)"

DEFAULT_OBSERVABLES = (
    "drawbar_pull",
    "driving_torque",
    "sinkage",
    "slip",
    "carriage/velocity",
    "wheel/omega",
)


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("series", help=HELP, description=HELP)
    parser.add_argument("run", metavar="RUN.h5", help="run file")
    parser.add_argument(
        "--observables",
        metavar="A,B,...",
        help="comma-separated observable names as in the run file, e.g. "
        "drawbar_pull,wheel/position (default: those of "
        + ",".join(DEFAULT_OBSERVABLES)
        + " that the file has)",
    )
    parser.add_argument("--png", metavar="OUT.png", help="write the plot here")
    parser.add_argument(
        "--csv", metavar="OUT.csv", help="write the series here (one row per step)"
    )
    parser.set_defaults(func=run)
    return parser


def component_names(series):
    """Column suffixes of a series' components ('' for one component)."""
    if series.value.ndim == 1:
        return [""]
    count = series.value.shape[1]
    if count == 4 and series.name.endswith("orientation"):
        return ["_w", "_x", "_y", "_z"]
    if count == 3:
        return ["_x", "_y", "_z"]
    return [f"_{i}" for i in range(count)]


def _columns(series):
    """The series' values as [n][c] (2-D even for one component)."""
    return series.value.reshape(len(series), -1)


def table(series_list):
    """(header, rows) of an outer join of the series on step; '' where a series has no row."""
    steps = np.unique(np.concatenate([s.step for s in series_list]))
    index = {int(s): i for i, s in enumerate(steps)}
    time = np.full(len(steps), np.nan)
    header = ["step", "time_s"]
    blocks = []
    for s in series_list:
        rows = [index[int(k)] for k in s.step]
        missing = np.isnan(time[rows])
        time[np.array(rows)[missing]] = s.time[missing]
        values = _columns(s)
        block = np.full((len(steps), values.shape[1]), np.nan)
        block[rows] = values
        blocks.append(block)
        header += [f"{s.name}{suffix} [{s.unit}]" for suffix in component_names(s)]
    data = np.hstack(blocks)
    out = []
    for i, step in enumerate(steps):
        cells = ["" if np.isnan(v) else float(v) for v in data[i]]
        out.append([int(step), float(time[i])] + cells)
    return header, out


def plot(series_list, phase, path, title):
    """One panel per series against time, phases shaded if ``phase`` is given."""
    fig, axes = panel_grid(
        len(series_list), columns=1, width=9.0, height=2.4, sharex=True
    )
    for number, (ax, s) in enumerate(zip(axes, series_list)):
        if phase is not None:
            shade_phases(ax, phase.time, np.ravel(phase.value), label=number == 0)
        values = _columns(s)
        for c, suffix in enumerate(component_names(s)):
            ax.plot(s.time, values[:, c], lw=0.8, label=suffix.lstrip("_") or None)
        unit = "-" if s.unit == "1" else s.unit
        ax.set_ylabel(f"{s.name} [{unit}]", fontsize=8)
        ax.grid(True, alpha=0.3)
        if values.shape[1] > 1 or (phase is not None and number == 0):
            ax.legend(fontsize=7, loc="best", ncol=4)
    axes[-1].set_xlabel("time [s]")
    axes[0].set_title(title, fontsize=9)
    save(fig, path)


def run(args):
    """Runs the subcommand; returns the exit status."""
    if not args.png and not args.csv:
        raise PostError("give --png OUT.png and/or --csv OUT.csv")
    with RunFile(args.run) as run_file:
        if args.observables is not None:
            names = split_list(args.observables)
            if not names:
                raise PostError(
                    "--observables: expected a comma-separated list of names"
                )
        else:
            names = [n for n in DEFAULT_OBSERVABLES if run_file.has_observable(n)]
            if not names:
                raise PostError(
                    f"run file '{args.run}' has none of the default observables "
                    f"{','.join(DEFAULT_OBSERVABLES)}; choose some with --observables"
                )
        series_list = [run_file.observable(n) for n in names]
        empty = [s.name for s in series_list if len(s) == 0]
        if empty:
            raise PostError(
                f"run file '{args.run}': observable '{empty[0]}' has no rows"
            )
        phase = (
            run_file.observable("phase") if run_file.has_observable("phase") else None
        )
        if args.csv:
            header, rows = table(series_list + ([phase] if phase is not None else []))
            comments = [
                f"wheelsim-post series of {args.run}; units in the column names"
            ]
            write_csv(args.csv, comments, header, rows)
            print(f"wrote {args.csv}")
        if args.png:
            plot(series_list, phase, args.png, run_file.name)
            print(f"wrote {args.png}")
    return 0
