"""``compare``: a simulated curve against a reference curve or points (wheelsim-post curves
CSVs, ``wong-reece --csv`` tables, measured CSVs with a column mapping)."""

import dataclasses
import math
import os

import numpy as np

from .choices import split_list
from .csvio import read_csv, to_float, write_csv
from .errors import PostError
from .plotting import panel_grid, save
from .quantities import EFFICIENCY_OF_MEANS, QUANTITIES, parse_quantities

HELP = (
    "compare a simulated curve with a reference (another simulation, wong-reece, or "
    "measurements): error per point and mean errors"
)

#: Relative errors (%) are reported only where |reference| >= this fraction of the
#: quantity's scale (W for forces, W*R_eff for torques, 1 for dimensionless quantities).
RELATIVE_MIN_FRACTION = 0.1

#: Other column names our own tables use for a quantity (wong-reece --csv: torque_Nm).
ALIASES = {"driving_torque": ("torque_Nm", "torque")}


@dataclasses.dataclass
class Curve:
    """Points of one curve: slip, value, its SEM (None if unknown), and the wheel load W [N]
    and effective radius [m] when the file gives them (NaN otherwise)."""

    label: str
    slip: np.ndarray
    value: np.ndarray
    sem: object
    load: float = math.nan
    r_eff: float = math.nan
    kind: str = "points"


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("compare", help=HELP, description=HELP)
    parser.add_argument(
        "simulated",
        metavar="SIM.csv",
        help="the curve to judge: output of 'wheelsim-post curves --csv' or "
        "'wong-reece --csv' (or any CSV with columns slip and <quantity><unit suffix>)",
    )
    parser.add_argument(
        "reference",
        metavar="REFERENCE.csv",
        help="the reference: the same formats, or measurements read with --columns; "
        "SI units; '#' comment lines allowed",
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
        help="the series ('group' column) of a curves CSV to compare; required if it has "
        "more than one",
    )
    parser.add_argument(
        "--columns",
        metavar="NAME=COLUMN,...",
        help="REFERENCE.csv's column for slip and the quantity, e.g. "
        "'slip=Slip,drawbar_pull=DP_N' (values in SI units)",
    )
    parser.add_argument(
        "--reference-label",
        metavar="TEXT",
        help="name of the reference in the table and plot (default: REFERENCE.csv's "
        "file name without extension)",
    )
    parser.add_argument(
        "--load",
        type=float,
        metavar="W",
        help="vertical wheel load W [N] for the normalised errors (default: the "
        "vertical_load_N column of a curves CSV)",
    )
    parser.add_argument(
        "--r-eff",
        type=float,
        metavar="R",
        help="effective radius [m] for torque errors normalised by W*R_eff (default: the "
        "r_eff_m column of a curves CSV)",
    )
    parser.add_argument("--png", metavar="OUT.png", help="write the plot here")
    parser.add_argument(
        "--csv", metavar="OUT.csv", help="write the per-point table here"
    )
    parser.set_defaults(func=run)
    return parser


def parse_columns(text):
    """'slip=Slip,drawbar_pull=DP_N' -> {'slip': 'Slip', 'drawbar_pull': 'DP_N'}."""
    mapping = {}
    for item in split_list(text or ""):
        name, sep, column = item.partition("=")
        name, column = name.strip(), column.strip()
        if not sep or not name or not column:
            raise PostError(
                f"--columns: '{item}' is not NAME=COLUMN (e.g. slip=Slip,drawbar_pull=DP_N)"
            )
        if name not in QUANTITIES:
            raise PostError(
                f"--columns: '{name}' is not one of {', '.join(QUANTITIES)}"
            )
        mapping[name] = column
    return mapping


def _group_rows(path, rows, group, option):
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
    return group, [(n, r) for n, r in enumerate(rows, start=1) if r["group"] == group]


def _mean_of_column(path, rows, column, option):
    values = [
        to_float(r[column], option, path, column, n) for n, r in rows if column in r
    ]
    values = [v for v in values if math.isfinite(v)]
    return float(np.mean(values)) if values else math.nan


def read_curves_csv(path, header, rows, quantity, group, option):
    """The Curve of one group of a 'wheelsim-post curves' CSV (equal slips averaged)."""
    q = QUANTITIES[quantity]
    y_column = (
        EFFICIENCY_OF_MEANS if quantity == "tractive_efficiency" else q.mean_column
    )
    e_column = (
        EFFICIENCY_OF_MEANS + "_sem"
        if quantity == "tractive_efficiency"
        else q.sem_column
    )
    if e_column not in header:  # a curves CSV of wheelsim-post before the SEM columns
        e_column = q.std_column if q.std_column in header else None
    for column in ("slip_mean", y_column):
        if column not in header:
            raise PostError(
                f"{option}: file '{path}' has no column '{column}' "
                "(expected the output of 'wheelsim-post curves --csv')"
            )
    label, members = _group_rows(path, rows, group, option)
    points = {}
    for number, r in members:
        x = to_float(r["slip_mean"], option, path, "slip_mean", number)
        y = to_float(r[y_column], option, path, y_column, number)
        e = to_float(r[e_column], option, path, e_column, number) if e_column else 0.0
        if math.isfinite(x) and math.isfinite(y):
            points.setdefault(x, []).append((y, e))
    if not points:
        raise PostError(f"{option}: '{path}' has no finite '{y_column}' for '{label}'")
    slip = np.array(sorted(points))
    value = np.array([np.mean([p[0] for p in points[s]]) for s in slip])
    # runs at one slip averaged: SEM of the mean of k independent means
    sem = np.array(
        [math.sqrt(sum(p[1] ** 2 for p in points[s])) / len(points[s]) for s in slip]
    )
    load = _mean_of_column(path, members, "vertical_load_N", option)
    r_eff = _mean_of_column(path, members, "r_eff_m", option)
    return Curve(label, slip, value, sem if e_column else None, load, r_eff, "curves")


def value_column(header, quantity, mapping):
    """The column holding ``quantity`` (None if there is none)."""
    if quantity in mapping:
        return mapping[quantity]
    q = QUANTITIES[quantity]
    for name in (q.name + q.suffix, q.name) + ALIASES.get(quantity, ()):
        if name in header:
            return name
    return None


def read_curve(path, quantity, group=None, mapping=None, option="REFERENCE.csv"):
    """The Curve of a CSV: a curves CSV (columns group, slip_mean), else a table of points
    with a slip column and a quantity column (our names, e.g. wong-reece --csv's, or those
    of ``mapping``), sorted by slip."""
    mapping = mapping or {}
    _, header, rows = read_csv(path, option)
    stem = os.path.splitext(os.path.basename(path))[0]
    if not mapping and "group" in header and "slip_mean" in header:
        return read_curves_csv(path, header, rows, quantity, group, option)
    slip_column = mapping.get("slip", "slip")
    y_column = value_column(header, quantity, mapping)
    q = QUANTITIES[quantity]
    for column, what in ((slip_column, "slip"), (y_column, quantity)):
        if column is None or column not in header:
            expected = column or f"{q.name + q.suffix} or {q.name}"
            raise PostError(
                f"{option}: file '{path}' has no column '{expected}' for {what} (it has: "
                f"{', '.join(header)}; map columns with --columns {what}=COLUMN)"
            )
    if not rows:
        raise PostError(f"{option}: file '{path}' has no data rows")
    slip = np.array([to_float(r[slip_column], option, path, slip_column, n)
                     for n, r in enumerate(rows, 1)])
    value = np.array([to_float(r[y_column], option, path, y_column, n)
                      for n, r in enumerate(rows, 1)])
    check_slips(slip, path, slip_column, option)
    order = np.argsort(slip, kind="stable")
    return Curve(stem, slip[order], value[order], None)


def check_slips(slip, path, column, option):
    """PostError naming the file, the row and the column if a slip of a table of points is not
    finite or appears twice (one point per slip: the interpolation and the comparison need it)."""
    first = {}
    for number, s in enumerate(slip, 1):
        if not math.isfinite(s):
            raise PostError(
                f"{option}: file '{path}', row {number}, column '{column}': slip {s:g}, "
                "expected a finite number"
            )
        if s in first:
            raise PostError(
                f"{option}: file '{path}', rows {first[s]} and {number}, column '{column}': "
                f"slip {s:g} appears twice, expected one point per slip"
            )
        first[s] = number


def interpolate(sim_slip, sim_value, slip):
    """(values, in_range): linear interpolation, NaN outside [min, max] of ``sim_slip``."""
    in_range = (slip >= sim_slip[0]) & (slip <= sim_slip[-1])
    values = np.where(in_range, np.interp(slip, sim_slip, sim_value), np.nan)
    return values, in_range


def error_scale(quantity, load, r_eff):
    """(scale, name) normalising the differences of ``quantity``: W for forces, W*R_eff for
    torques, 1 for dimensionless quantities; (NaN, reason) when unknown or not defined
    (sinkage: relative errors only)."""
    unit = QUANTITIES[quantity].unit
    if unit == "1":
        return 1.0, "1"
    if unit == "N":
        return (load, "W") if load > 0 else (math.nan, "W unknown (--load)")
    if unit == "N m":
        if load > 0 and r_eff > 0:
            return load * r_eff, "W*R_eff"
        return math.nan, "W*R_eff unknown (--load, --r-eff)"
    return math.nan, "none"


def percent_errors(simulated, reference, threshold=0.0):
    """100 (simulated − reference) / |reference| where |reference| > ``threshold`` (and not
    0), else NaN."""
    with np.errstate(divide="ignore", invalid="ignore"):
        keep = (np.abs(reference) > threshold) & (reference != 0.0)
        return np.where(keep, 100.0 * (simulated - reference) / np.abs(reference), np.nan)


def mean_absolute(errors):
    """Mean of |error| over the finite errors (NaN if there are none)."""
    finite = errors[np.isfinite(errors)]
    return float(np.mean(np.abs(finite))) if finite.size else math.nan


def plot(q, sim, ref, result, path):
    """Simulated curve (± SEM), reference points (hollow out of range), errors per point."""
    slip, simulated, normalised, errors, in_range, scale_name = result
    fig, (ax, ax_err) = panel_grid(2, columns=1, width=7.0, height=3.5)
    ax.errorbar(
        sim.slip,
        sim.value * q.plot_scale,
        yerr=None if sim.sem is None else sim.sem * q.plot_scale,
        marker="o",
        capsize=3,
        label=sim.label,
    )
    ax.plot(slip[in_range], ref.value[in_range] * q.plot_scale, "ks", label=ref.label)
    if np.any(~in_range):
        ax.plot(
            slip[~in_range],
            ref.value[~in_range] * q.plot_scale,
            "ks",
            mfc="none",
            label=f"{ref.label}, outside the simulated slip range",
        )
    ax.set_xlabel("slip [-]")
    ax.set_ylabel(q.axis_label())
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    if np.any(np.isfinite(normalised)):
        ok = np.isfinite(normalised)
        ax_err.bar(slip[ok], normalised[ok], width=0.01)
        ax_err.set_ylabel(f"(sim − ref)/{scale_name} [-]")
    else:
        ok = np.isfinite(errors)
        ax_err.bar(slip[ok], errors[ok], width=0.01)
        ax_err.set_ylabel("(sim − ref)/|ref| [%]")
    ax_err.axhline(0.0, color="k", lw=0.8)
    ax_err.set_xlabel("slip [-]")
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
    mapping = parse_columns(args.columns)
    sim = read_curve(args.simulated, quantity, args.group, None, "SIM.csv")
    ref = read_curve(args.reference, quantity, args.group, mapping, "REFERENCE.csv")
    if args.reference_label:
        ref.label = args.reference_label
    if sim.kind != "curves":
        sim.label = os.path.splitext(os.path.basename(args.simulated))[0]
    for option, value in (("--load", args.load), ("--r-eff", args.r_eff)):
        if value is not None and not (value > 0 and math.isfinite(value)):
            raise PostError(f"{option}: expected a number > 0, got {value:g}")
    load = args.load or (sim.load if sim.load > 0 else ref.load)
    r_eff = args.r_eff or (sim.r_eff if sim.r_eff > 0 else ref.r_eff)
    scale, scale_name = error_scale(quantity, load, r_eff)

    slip = ref.slip
    simulated, in_range = interpolate(sim.slip, sim.value, slip)
    if not np.any(in_range):
        raise PostError(
            f"REFERENCE.csv: no slip of '{args.reference}' ({slip[0]:g} .. {slip[-1]:g}) lies in "
            f"the simulated slip range {sim.slip[0]:g} .. {sim.slip[-1]:g} of "
            f"'{args.simulated}': nothing to compare (no extrapolation)"
        )
    difference = simulated - ref.value
    normalised = difference / scale if math.isfinite(scale) else np.full(len(slip), np.nan)
    threshold = RELATIVE_MIN_FRACTION * scale if math.isfinite(scale) else 0.0
    errors = percent_errors(simulated, ref.value, threshold)
    mean_norm, mean_pct = mean_absolute(normalised), mean_absolute(errors)
    n_norm, n_pct = int(np.sum(np.isfinite(normalised))), int(np.sum(np.isfinite(errors)))
    if n_norm == 0 and n_pct == 0:
        why = f"the simulated or reference {quantity} there is not finite"
        if not math.isfinite(scale):
            why += f", or the reference is 0 and there is no scale ({scale_name})"
        raise PostError(
            f"REFERENCE.csv: no point of '{args.reference}' in the simulated slip range has an "
            f"error ({why}): nothing to compare"
        )

    print(
        f"simulated: {sim.label} ({args.simulated}); reference: {ref.label} "
        f"({args.reference}); simulated slip range {sim.slip[0]:g} .. {sim.slip[-1]:g}"
    )
    if math.isfinite(scale):
        print(
            f"differences normalised by {scale_name} = {scale:.6g}; relative errors only "
            f"where |reference| >= {RELATIVE_MIN_FRACTION:g}*{scale_name}"
        )
    else:
        print(f"no normalised differences ({scale_name}); relative errors only")
    print(
        f"{'slip':>8} {ref.label[:12]:>12} {'simulated':>12} {'(s−r)/' + scale_name:>12} "
        f"{'error %':>9}"
    )
    for s, r, v, d, e, inside in zip(slip, ref.value, simulated, normalised, errors, in_range):
        note = "" if inside else "  outside the simulated slip range"
        print(f"{s:8.4g} {r:12.5g} {v:12.5g} {d:12.4g} {e:9.3g}{note}")
    if math.isfinite(scale):
        print(f"mean |sim − ref|/{scale_name}: {mean_norm:.4g} over {n_norm} points")
    print(f"mean absolute error: {mean_pct:.4g} % over {n_pct} points")
    if args.csv:
        header = [
            "slip",
            f"reference_{quantity}{q.suffix}",
            f"simulated_{quantity}{q.suffix}",
            f"difference_{quantity}{q.suffix}",
            "normalised_difference",
            "error_percent",
            "in_range",
        ]
        rows = [
            [float(s), float(r), float(v), float(v - r), float(d), float(e), int(i)]
            for s, r, v, d, e, i in zip(
                slip, ref.value, simulated, normalised, errors, in_range
            )
        ]
        comments = [
            f"wheelsim-post compare: simulated {sim.label} ({args.simulated}) vs reference "
            f"{ref.label} ({args.reference})",
            "simulated: linear interpolation in the reference's slip, no extrapolation "
            "(in_range 0: nan)",
            f"normalised_difference = (simulated-reference)/{scale_name}"
            + (f", {scale_name} = {scale:.10g}" if math.isfinite(scale) else ""),
            "error_percent = 100*(simulated-reference)/|reference|, only where |reference| "
            + (
                f">= {RELATIVE_MIN_FRACTION:g}*{scale_name}"
                if math.isfinite(scale)
                else "> 0"
            ),
            f"mean_absolute_normalised_difference = {mean_norm:.10g}",
            f"mean_absolute_error_percent = {mean_pct:.10g}",
        ]
        write_csv(args.csv, comments, header, rows)
        print(f"wrote {args.csv}")
    if args.png:
        result = (slip, simulated, normalised, errors, in_range, scale_name)
        plot(q, sim, ref, result, args.png)
        print(f"wrote {args.png}")
    return 0
