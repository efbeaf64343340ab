"""``compare``: a simulated curve (curves CSV) against measured points (slip, quantity)."""

import math

import numpy as np

from .csvio import read_csv, to_float, write_csv
from .errors import PostError
from .plotting import panel_grid, save
from .quantities import EFFICIENCY_OF_MEANS, QUANTITIES, parse_quantities

HELP = "compare a simulated curve with measured points: error per point and mean |error| in %%"


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("compare", help=HELP, description=HELP)
    parser.add_argument("curves", metavar="CURVES.csv", help="output of 'curves --csv'")
    parser.add_argument(
        "measured",
        metavar="MEASURED.csv",
        help="measured points: header 'slip,<quantity>', SI units as in CURVES.csv, "
        "'#' comment lines allowed",
    )
    parser.add_argument(
        "--quantity",
        required=True,
        metavar="Q",
        help="one of " + ", ".join(n for n in QUANTITIES if n != "slip"),
    )
    parser.add_argument(
        "--group",
        metavar="LABEL",
        help="the series ('group' column of CURVES.csv) to compare; required if it has "
        "more than one",
    )
    parser.add_argument("--png", metavar="OUT.png", help="write the plot here")
    parser.add_argument(
        "--csv", metavar="OUT.csv", help="write the per-point table here"
    )
    parser.set_defaults(func=run)
    return parser


def simulated_curve(path, quantity, group):
    """(label, slip, mean, std) of the chosen group, sorted by slip, equal slips averaged."""
    q = QUANTITIES[quantity]
    y_column = (
        EFFICIENCY_OF_MEANS if quantity == "tractive_efficiency" else q.mean_column
    )
    _, header, rows = read_csv(path, "CURVES.csv")
    for column in ("group", "slip_mean", y_column, q.std_column):
        if column not in header:
            raise PostError(
                f"CURVES.csv: file '{path}' has no column '{column}' "
                "(expected the output of 'wheelsim-post curves --csv')"
            )
    labels = list(dict.fromkeys(r["group"] for r in rows))
    if group is None:
        if len(labels) != 1:
            raise PostError(
                f"--group: '{path}' has {len(labels)} series; choose one of: "
                + "; ".join(labels)
            )
        group = labels[0]
    elif group not in labels:
        raise PostError(
            f"--group: '{group}' is not in '{path}' (it has: {'; '.join(labels)})"
        )
    points = {}
    for number, r in enumerate(rows, start=1):
        if r["group"] != group:
            continue
        x = to_float(r["slip_mean"], "CURVES.csv", path, "slip_mean", number)
        y = to_float(r[y_column], "CURVES.csv", path, y_column, number)
        e = to_float(r[q.std_column], "CURVES.csv", path, q.std_column, number)
        if math.isfinite(x) and math.isfinite(y):
            points.setdefault(x, []).append((y, e))
    if not points:
        raise PostError(
            f"CURVES.csv: '{path}' has no finite '{y_column}' for '{group}'"
        )
    slip = np.array(sorted(points))
    mean = np.array([np.mean([p[0] for p in points[s]]) for s in slip])
    std = np.array([np.mean([p[1] for p in points[s]]) for s in slip])
    return group, slip, mean, std


def measured_points(path, quantity):
    """(slip, value) arrays of the measured CSV (columns 'slip' and ``quantity``)."""
    _, header, rows = read_csv(path, "MEASURED.csv")
    for column in ("slip", quantity):
        if column not in header:
            raise PostError(
                f"MEASURED.csv: file '{path}' has no column '{column}' "
                f"(expected header 'slip,{quantity}')"
            )
    if not rows:
        raise PostError(f"MEASURED.csv: file '{path}' has no data rows")
    slip = [
        to_float(r["slip"], "MEASURED.csv", path, "slip", i)
        for i, r in enumerate(rows, 1)
    ]
    value = [
        to_float(r[quantity], "MEASURED.csv", path, quantity, i)
        for i, r in enumerate(rows, 1)
    ]
    return np.array(slip), np.array(value)


def interpolate(sim_slip, sim_value, slip):
    """(values, in_range): linear interpolation, NaN outside [min, max] of ``sim_slip``."""
    in_range = (slip >= sim_slip[0]) & (slip <= sim_slip[-1])
    values = np.where(in_range, np.interp(slip, sim_slip, sim_value), np.nan)
    return values, in_range


def percent_errors(simulated, measured):
    """100 (simulated − measured) / |measured|; NaN where measured is 0 or simulated NaN."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(
            measured != 0.0, 100.0 * (simulated - measured) / np.abs(measured), np.nan
        )


def mean_absolute_percent_error(errors):
    """Mean of |error| over the finite errors (NaN if there are none)."""
    finite = errors[np.isfinite(errors)]
    return float(np.mean(np.abs(finite))) if finite.size else math.nan


def plot(q, label, sim, meas, errors, in_range, mape, path):
    """Curve and points (out-of-range hollow), and the error per point."""
    sim_slip, sim_mean, sim_std = sim
    slip, value = meas
    fig, (ax, ax_err) = panel_grid(2, columns=1, width=7.0, height=3.5)
    ax.errorbar(
        sim_slip,
        sim_mean * q.plot_scale,
        yerr=sim_std * q.plot_scale,
        marker="o",
        capsize=3,
        label=f"simulated ({label})",
    )
    ax.plot(slip[in_range], value[in_range] * q.plot_scale, "ks", label="measured")
    if np.any(~in_range):
        ax.plot(
            slip[~in_range],
            value[~in_range] * q.plot_scale,
            "ks",
            mfc="none",
            label="measured, outside the simulated slip range",
        )
    ax.set_xlabel("slip [-]")
    ax.set_ylabel(q.axis_label())
    ax.set_title(
        f"mean |error| = {mape:.3g} % over {int(np.sum(np.isfinite(errors)))} points",
        fontsize=9,
    )
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ok = np.isfinite(errors)
    ax_err.bar(slip[ok], errors[ok], width=0.01)
    ax_err.axhline(0.0, color="k", lw=0.8)
    ax_err.set_xlabel("slip [-]")
    ax_err.set_ylabel("error (sim − meas)/|meas| [%]")
    ax_err.set_xlim(ax.get_xlim())
    ax_err.grid(True, alpha=0.3)
    save(fig, path)


def run(args):
    """Runs the subcommand; returns the exit status."""
    quantity = parse_quantities(args.quantity)
    if len(quantity) != 1 or quantity[0] == "slip":
        raise PostError(
            f"--quantity: expected one quantity other than slip, got '{args.quantity}'"
        )
    quantity = quantity[0]
    q = QUANTITIES[quantity]
    label, sim_slip, sim_mean, sim_std = simulated_curve(
        args.curves, quantity, args.group
    )
    slip, value = measured_points(args.measured, quantity)
    simulated, in_range = interpolate(sim_slip, sim_mean, slip)
    errors = percent_errors(simulated, value)
    mape = mean_absolute_percent_error(errors)
    print(f"series: {label}; simulated slip range {sim_slip[0]:g} .. {sim_slip[-1]:g}")
    print(f"{'slip':>8} {'measured':>12} {'simulated':>12} {'error %':>9}")
    for s, m, v, e, r in zip(slip, value, simulated, errors, in_range):
        note = "" if r else "  outside the simulated slip range"
        print(f"{s:8.4g} {m:12.5g} {v:12.5g} {e:9.3g}{note}")
    print(
        f"mean absolute error: {mape:.4g} % over {int(np.sum(np.isfinite(errors)))} points"
    )
    if args.csv:
        header = [
            "slip",
            f"measured_{quantity}{q.suffix}",
            f"simulated_{quantity}{q.suffix}",
            "error_percent",
            "in_range",
        ]
        rows = [
            [float(s), float(m), float(v), float(e), int(r)]
            for s, m, v, e, r in zip(slip, value, simulated, errors, in_range)
        ]
        comments = [
            f"wheelsim-post compare: {args.curves} ({label}) vs {args.measured}",
            "simulated: linear interpolation in measured slip, no extrapolation "
            "(in_range 0: nan)",
            "error_percent = 100*(simulated-measured)/|measured|",
            f"mean_absolute_error_percent = {mape:.10g}",
        ]
        write_csv(args.csv, comments, header, rows)
        print(f"wrote {args.csv}")
    if args.png:
        plot(
            q,
            label,
            (sim_slip, sim_mean, sim_std),
            (slip, value),
            errors,
            in_range,
            mape,
            args.png,
        )
        print(f"wrote {args.png}")
    return 0
