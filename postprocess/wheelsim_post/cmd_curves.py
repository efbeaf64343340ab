"""``curves``: steady-state quantities of many runs against slip (CSV and PNG)."""

import math
import textwrap

import numpy as np

from .analysis import (analyse_runs, group_label, offset_sinkage, sinkage_offset_comment,
                       window_lines)
from .csvio import write_csv
from .errors import PostError
from .metadata import parse_group_by
from .options import add_window_options, window_from_args
from .plotting import panel_grid, save
from .results_table import HELP as RESULTS_HELP
from .results_table import write_results
from .quantities import (
    CURVE_QUANTITIES,
    EFFICIENCY_OF_MEANS,
    NORMALISED_CURVE_QUANTITIES,
    NORMALISED_QUANTITIES,
    QUANTITIES,
    SLIP_QUANTITIES,
    of_means,
)

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
    "lug_count",
    "window_passes",
    "r_eff_m",
    "vertical_load_N",
)

#: Columns after the quantities.
TAIL_COLUMNS = ("health", "health_codes", "window_notes")


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
    parser.add_argument("--results", metavar="OUT.csv", help=RESULTS_HELP)
    parser.add_argument(
        "--sinkage-offset",
        type=float,
        default=0.0,
        metavar="M",
        help="read sinkage against a surface M metres below the one each run recorded, e.g. a "
        "DEM bed's equivalent surface (wheelsim-post surface): every sinkage is M less "
        "(default 0)",
    )
    parser.add_argument(
        "--normalised",
        action="store_true",
        help="plot DP/W and T/(W R_eff) (W = vertical load) instead of DP, T and T/R_eff",
    )
    parser.set_defaults(func=run)
    return parser


def _stat_columns(name):
    q = QUANTITIES[name]
    return [q.mean_column, q.std_column, q.sem_column]


def csv_header():
    """Column names of the curves CSV (units in the names; see docs/postprocess.md)."""
    columns = list(LEAD_COLUMNS)
    for name in SLIP_QUANTITIES:
        columns += _stat_columns(name) + [of_means(name), of_means(name) + "_sem"]
    for name in CURVE_QUANTITIES + NORMALISED_QUANTITIES:
        columns += _stat_columns(name)
        if name == "tractive_efficiency":
            columns += [EFFICIENCY_OF_MEANS, EFFICIENCY_OF_MEANS + "_sem"]
    return columns + list(TAIL_COLUMNS)


def csv_row(result, group):
    """One CSV row of a RunResult, in the order of csv_header()."""
    m, s = result.metadata, result.stats
    span = s["span"]
    lugs = "unknown" if span.lug_count is None else span.lug_count
    row = [group, m.wheel, m.soil, m.terrain, m.target_slip, result.path]
    row += [span.test_start, span.start, span.end, s["n_samples"], lugs, span.passes]
    row += [s["r_eff"], s["vertical_load"]]
    for name in SLIP_QUANTITIES:
        row += list(s[name]) + [s[of_means(name)].mean, s[of_means(name)].sem]
    for name in CURVE_QUANTITIES + NORMALISED_QUANTITIES:
        row += list(s[name])
        if name == "tractive_efficiency":
            row += [s[EFFICIENCY_OF_MEANS].mean, s[EFFICIENCY_OF_MEANS].sem]
    row += [result.health.verdict, result.health.codes, "; ".join(span.notes)]
    return row


def sorted_groups(results, group_by):
    """{label: [RunResult sorted by measured slip (signed convention)]} in order of first
    appearance."""
    groups = {}
    for result in results:
        groups.setdefault(group_label(result.metadata, group_by), []).append(result)
    for members in groups.values():
        members.sort(key=lambda r: (math.isnan(r.mean("slip_signed")), r.mean("slip_signed")))
    return groups


def footnotes(results):
    """Lines for the CSV footer and the plot: runs whose health is not ok, window notes."""
    lines = []
    for r in results:
        if r.health.verdict != "ok":
            codes = f" ({r.health.codes})" if r.health.codes else ""
            lines.append(f"{r.path}: health {r.health.verdict}{codes}")
        lines += [f"{r.path}: {note}" for note in r.span.notes]
    return lines


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


def plot_curves(groups, path, window_text, normalised=False, notes=()):
    """One panel per quantity against measured slip (signed convention: driving for s ≥ 0,
    skid for s < 0), error bars ± SEM; points whose health
    is not ok hollow, listed with the window notes in a footnote."""
    from matplotlib.ticker import MaxNLocator  # matplotlib on first plot (plotting.py)

    names = NORMALISED_CURVE_QUANTITIES if normalised else CURVE_QUANTITIES
    fig, axes = panel_grid(len(names), columns=2)
    efficiency_values = []
    slip_q = QUANTITIES["slip_signed"]
    for ax, name in zip(axes, names):
        q = QUANTITIES[name]
        for index, (label, members) in enumerate(groups.items()):
            colour = f"C{index % 10}"
            x = np.array([r.mean("slip_signed") for r in members])
            xerr = np.array([r.sem("slip_signed") for r in members])
            if name == "tractive_efficiency":
                y = np.array([r.stats[EFFICIENCY_OF_MEANS].mean for r in members])
                yerr = np.array([r.stats[EFFICIENCY_OF_MEANS].sem for r in members])
                efficiency_values.extend(v for v in y if np.isfinite(v))
            else:
                y = np.array([r.mean(name) for r in members])
                yerr = np.array([r.sem(name) for r in members])
            ok = np.array([r.health.verdict == "ok" for r in members], dtype=bool)
            ax.errorbar(
                x,
                y * q.plot_scale,
                yerr=yerr * q.plot_scale,
                xerr=xerr,
                color=colour,
                capsize=3,
                label=label,
            )
            ax.plot(x[ok], y[ok] * q.plot_scale, "o", color=colour)
            ax.plot(
                x[~ok], y[~ok] * q.plot_scale, "o", color=colour, mfc="white", zorder=3
            )
        ax.set_xlabel(f"measured {slip_q.axis_label()}")
        ax.set_ylabel(q.axis_label())
        if name == "tractive_efficiency":
            ax.set_title("η = mean DP·mean v / (mean T·mean ω)", fontsize=9)
            clip_efficiency_axis(ax, efficiency_values)
        ax.xaxis.set_major_locator(MaxNLocator(5))
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(
        textwrap.fill(f"mean ± standard error of the mean (batch means); {window_text}", 110),
        fontsize=8,
    )
    if notes:
        text = ["hollow markers: health not ok; notes:"] + [f"  {n}" for n in notes]
        if len(text) > 12:
            text = text[:11] + [f"  ... and {len(text) - 11} more (see the CSV)"]
        fig.tight_layout(rect=(0, 0.02 + 0.018 * len(text), 1, 1))
        fig.text(0.01, 0.01, "\n".join(text), fontsize=6, va="bottom", family="monospace")
    save(fig, path, tight=not notes)


def run(args):
    """Runs the subcommand; returns the exit status."""
    window = window_from_args(args)
    group_by = parse_group_by(args.group_by)
    if not math.isfinite(args.sinkage_offset):
        raise PostError(f"--sinkage-offset: expected a finite length [m], got "
                        f"{args.sinkage_offset:g}")
    print(window.describe())
    results = analyse_runs(args.runs, window, args.lugs)
    if args.sinkage_offset:
        offset_sinkage(results, args.sinkage_offset)
        print(*sinkage_offset_comment(args.sinkage_offset))
    groups = sorted_groups(results, group_by)
    rows = []
    for label, members in groups.items():
        for r in members:
            rows.append(csv_row(r, label))
            for line in window_lines(r):
                print(line)
            codes = f" ({r.health.codes})" if r.health.codes else ""
            print(
                f"{label}: target slip {r.metadata.target_slip:g}, "
                f"slip {r.mean('slip'):.4g} ± {r.sem('slip'):.2g} "
                f"(signed {r.mean('slip_signed'):.4g}), "
                f"DP {r.mean('drawbar_pull'):.4g} ± {r.sem('drawbar_pull'):.2g} N, "
                f"T {r.mean('driving_torque'):.4g} ± {r.sem('driving_torque'):.2g} N m, "
                f"DP/W {r.mean('dp_over_w'):.4g} ± {r.sem('dp_over_w'):.2g}, "
                f"η {r.stats[EFFICIENCY_OF_MEANS].mean:.3g}, "
                f"health {r.health.verdict}{codes}  ({r.path})"
            )
    notes = footnotes(results)
    if args.csv:
        comments = [
            "wheelsim-post curves: steady-state mean, std (ddof 0) and standard error of the "
            "mean (_sem: batch means, 20 batches) per run",
            window.describe(),
            "slip: driving 1 - v/(omega*R_eff); slip_skid: (omega*R_eff - v)/v; slip_signed: "
            "driving for s >= 0, skid for s < 0 (docs/postprocess.md, 'Slip conventions')",
            "units: see column suffixes (_N, _Nm, _m, _s; none = dimensionless); "
            "tractive_efficiency_of_means = DP_mean*v_mean/(T_mean*omega_mean) is plotted; "
            "dp_over_w = DP/W, torque_over_w_reff = T/(W*R_eff), W = vertical_load_N",
        ] + sinkage_offset_comment(args.sinkage_offset)
        footer = ["notes:"] + notes if notes else []
        write_csv(args.csv, comments, csv_header(), rows, footer)
        print(f"wrote {args.csv}")
    if args.png:
        plot_curves(groups, args.png, window.describe(), args.normalised, notes)
        print(f"wrote {args.png}")
    if args.results:
        write_results(args.results, results, window, args)
        print(f"wrote {args.results}")
    return 0
