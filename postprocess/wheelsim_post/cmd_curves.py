"""``curves``: steady-state quantities of many runs against slip (CSV and PNG)."""

import math
import textwrap

import numpy as np
from matplotlib.ticker import MaxNLocator

from .analysis import analyse_runs, group_label
from .csvio import write_csv
from .metadata import parse_group_by
from .options import add_window_options, window_from_args
from .plotting import panel_grid, save
from .quantities import CURVE_QUANTITIES, EFFICIENCY_OF_MEANS, QUANTITIES, SLIP_OF_MEANS

HELP = "steady-state drawbar pull, torque, sinkage, efficiency, ... against slip"

#: Columns before the quantities in the curves CSV.
LEAD_COLUMNS = (
    "group",
    "wheel",
    "soil",
    "terrain",
    "target_slip",
    "run_file",
    "test_start_s",
    "window_start_s",
    "window_end_s",
    "n_samples",
    "r_eff_m",
)


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("curves", help=HELP, description=HELP)
    parser.add_argument("runs", nargs="+", metavar="RUN.h5", help="run files")
    add_window_options(parser)
    parser.add_argument(
        "--group-by",
        default="wheel,soil,terrain",
        metavar="KEYS",
        help="comma-separated keys from wheel, soil, terrain that separate the series "
        "(default: wheel,soil,terrain)",
    )
    parser.add_argument("--csv", metavar="OUT.csv", help="write the table here")
    parser.add_argument("--png", metavar="OUT.png", help="write the plot here")
    parser.set_defaults(func=run)
    return parser


def csv_header():
    """Column names of the curves CSV (units in the names; see docs/postprocess.md)."""
    columns = list(LEAD_COLUMNS)
    columns += ["slip_mean", "slip_std", SLIP_OF_MEANS]
    for name in CURVE_QUANTITIES:
        q = QUANTITIES[name]
        columns += [q.mean_column, q.std_column]
        if name == "tractive_efficiency":
            columns.append(EFFICIENCY_OF_MEANS)
    return columns


def csv_row(result, group):
    """One CSV row of a RunResult, in the order of csv_header()."""
    m, s = result.metadata, result.stats
    span = s["span"]
    row = [group, m.wheel, m.soil, m.terrain, m.target_slip, result.path]
    row += [span.test_start, span.start, span.end, s["n_samples"], s["r_eff"]]
    row += [s["slip"][0], s["slip"][1], s[SLIP_OF_MEANS]]
    for name in CURVE_QUANTITIES:
        row += list(s[name])
        if name == "tractive_efficiency":
            row.append(s[EFFICIENCY_OF_MEANS])
    return row


def sorted_groups(results, group_by):
    """{label: [RunResult sorted by measured slip]} in order of first appearance."""
    groups = {}
    for result in results:
        groups.setdefault(group_label(result.metadata, group_by), []).append(result)
    for members in groups.values():
        members.sort(key=lambda r: (math.isnan(r.mean("slip")), r.mean("slip")))
    return groups


EFFICIENCY_AXIS = (-0.5, 1.0)


def clip_efficiency_axis(ax, values):
    """Limits the η axis to EFFICIENCY_AXIS when a point lies outside it (near zero torque η
    diverges and would flatten the curve); says how many points are not shown."""
    lo, hi = EFFICIENCY_AXIS
    outside = [v for v in values if v < lo or v > hi]
    if not outside:
        return
    ax.set_ylim(lo, hi)
    ax.text(
        0.02,
        0.02,
        f"{len(outside)} point(s) outside [{lo}, {hi}] not shown (T·ω near 0)",
        transform=ax.transAxes,
        fontsize=7,
    )


def plot_curves(groups, path, window_text):
    """One panel per quantity of CURVE_QUANTITIES against measured slip, with error bars."""
    fig, axes = panel_grid(len(CURVE_QUANTITIES), columns=2)
    efficiency_values = []
    slip_q = QUANTITIES["slip"]
    for ax, name in zip(axes, CURVE_QUANTITIES):
        q = QUANTITIES[name]
        for label, members in groups.items():
            x = np.array([r.mean("slip") for r in members])
            xerr = np.array([r.std("slip") for r in members])
            if name == "tractive_efficiency":
                y = np.array([r.stats[EFFICIENCY_OF_MEANS] for r in members])
            else:
                y = np.array([r.mean(name) for r in members])
            yerr = np.array([r.std(name) for r in members])
            if name == "tractive_efficiency":
                # The std of the per-step η is meaningless where T·ω crosses 0: no error bars.
                yerr = None
                efficiency_values.extend(v for v in y if np.isfinite(v))
            ax.errorbar(
                x,
                y * q.plot_scale,
                yerr=None if yerr is None else yerr * q.plot_scale,
                xerr=xerr,
                marker="o",
                capsize=3,
                label=label,
            )
        ax.set_xlabel(f"measured {slip_q.axis_label()}")
        ax.set_ylabel(q.axis_label())
        if name == "tractive_efficiency":
            ax.set_title("η = mean DP·mean v / (mean T·mean ω)", fontsize=9)
            clip_efficiency_axis(ax, efficiency_values)
        ax.xaxis.set_major_locator(MaxNLocator(5))
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(textwrap.fill(f"mean ± std; {window_text}", 110), fontsize=8)
    save(fig, path)


def run(args):
    """Runs the subcommand; returns the exit status."""
    window = window_from_args(args)
    group_by = parse_group_by(args.group_by)
    print(window.describe())
    results = analyse_runs(args.runs, window)
    groups = sorted_groups(results, group_by)
    rows = []
    for label, members in groups.items():
        for r in members:
            rows.append(csv_row(r, label))
            print(
                f"{label}: target slip {r.metadata.target_slip:g}, "
                f"slip {r.mean('slip'):.4g} ± {r.std('slip'):.2g}, "
                f"DP {r.mean('drawbar_pull'):.4g} ± {r.std('drawbar_pull'):.2g} N, "
                f"T {r.mean('driving_torque'):.4g} ± {r.std('driving_torque'):.2g} N m, "
                f"η {r.stats[EFFICIENCY_OF_MEANS]:.3g}  ({r.path})"
            )
    if args.csv:
        comments = [
            "wheelsim-post curves: steady-state mean and std (ddof 0) per run",
            window.describe(),
            "units: see column suffixes (_N, _Nm, _m, _s; none = dimensionless); "
            "tractive_efficiency_of_means = DP_mean*v_mean/(T_mean*omega_mean) is plotted",
        ]
        write_csv(args.csv, comments, csv_header(), rows)
        print(f"wrote {args.csv}")
    if args.png:
        plot_curves(groups, args.png, window.describe())
        print(f"wrote {args.png}")
    return 0
