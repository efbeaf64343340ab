"""``study``: tables like the reference studies (rows wheels, columns target slips)."""

import math
import os
import re

from .analysis import analyse_runs, slip_text, window_lines
from .csvio import write_csv
from .errors import PostError
from .options import add_window_options, window_from_args
from .quantities import EFFICIENCY_OF_MEANS, QUANTITIES, parse_quantities

HELP = (
    "tables per soil and quantity: rows wheels, columns target slips (CSV and Markdown)"
)


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("study", help=HELP, description=HELP)
    parser.add_argument("runs", nargs="+", metavar="RUN.h5", help="run files")
    parser.add_argument(
        "--quantity",
        required=True,
        metavar="Q,...",
        help="comma-separated quantities: " + ", ".join(QUANTITIES),
    )
    parser.add_argument(
        "--out-dir",
        required=True,
        metavar="DIR",
        help="directory for the CSV tables and study.md (created if missing)",
    )
    add_window_options(parser)
    parser.set_defaults(func=run)
    return parser


def _cell(result, quantity):
    """(mean, std, sem, health) of a quantity; the efficiency's mean and SEM are those of
    the efficiency of the means."""
    mean, std, sem = result.stats[quantity]
    if quantity == "tractive_efficiency":
        mean, _, sem = result.stats[EFFICIENCY_OF_MEANS]
    return mean, std, sem, result.health.verdict


def build_tables(results, quantities):
    """{(soil, quantity): (wheel rows, slip columns, {(row, slip): _cell()})}.

    Rows are wheel names, or 'wheel (terrain)' when the runs of a soil span several terrains.
    PostError if a run has no target slip, or two runs share soil, row and target slip.
    """
    for r in results:
        if math.isnan(r.metadata.target_slip):
            raise PostError(
                f"run file '{r.path}' has no target slip (/parameters/sweep/slip or "
                "carriage.slip in /parameters/rig_config)"
            )
    tables = {}
    for soil in sorted({r.metadata.soil for r in results}):
        members = [r for r in results if r.metadata.soil == soil]
        several = len({r.metadata.terrain for r in members}) > 1
        cells, owners = {}, {}
        for r in members:
            m = r.metadata
            row = f"{m.wheel} ({m.terrain})" if several else m.wheel
            key = (row, m.target_slip)
            if key in owners:
                raise PostError(
                    f"run files '{owners[key]}' and '{r.path}' both have soil {soil}, "
                    f"wheel {row}, target slip {m.target_slip:g}"
                )
            owners[key] = r.path
            cells[key] = r
        rows = sorted({k[0] for k in cells})
        slips = sorted({k[1] for k in cells})
        for quantity in quantities:
            values = {k: _cell(r, quantity) for k, r in cells.items()}
            tables[(soil, quantity)] = (rows, slips, values)
    return tables


def safe_name(text):
    """``text`` usable in a file name (other characters replaced by '_')."""
    return re.sub(r"[^A-Za-z0-9._-]+", "_", text) or "_"


def markdown(soil, quantity, table):
    """A Markdown table: 'mean ± SEM' per cell ('mean ± SEM (health)' unless the run's
    health is ok), '–' where there is no run."""
    rows, slips, values = table
    q = QUANTITIES[quantity]
    lines = [f"### soil {soil}: {q.axis_label()}", ""]
    lines.append("| wheel | " + " | ".join(f"s = {slip_text(s)}" for s in slips) + " |")
    lines.append("|---|" + "---:|" * len(slips))
    for row in rows:
        cells = []
        for s in slips:
            if (row, s) in values:
                mean, _, sem, health = values[(row, s)]
                mark = "" if health in ("ok", "unchecked") else f" ({health})"
                cells.append(f"{mean:.4g} ± {sem:.2g}{mark}")
            else:
                cells.append("–")
        lines.append(f"| {row} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def write_table(out_dir, soil, quantity, table, window_text):
    """Writes <soil>_<quantity>.csv (means), <soil>_<quantity>_sem.csv (standard errors of
    the means), <soil>_<quantity>_std.csv (standard deviations); returns the paths."""
    rows, slips, values = table
    q = QUANTITIES[quantity]
    header = ["wheel"] + [slip_text(s) for s in slips]
    paths = []
    for index, kind in ((0, "mean"), (2, "sem"), (1, "std")):
        suffix = "" if kind == "mean" else f"_{kind}"
        path = os.path.join(out_dir, f"{safe_name(soil)}_{quantity}{suffix}.csv")
        body = [
            [row]
            + [values[(row, s)][index] if (row, s) in values else "" for s in slips]
            for row in rows
        ]
        comments = [
            f"wheelsim-post study: soil {soil}, {quantity} {kind} [{q.unit}]",
            "rows: wheel; columns: target slip [-]",
            window_text,
        ]
        write_csv(path, comments, header, body)
        paths.append(path)
    return paths


RUNS_HEADER = (
    "soil",
    "wheel",
    "terrain",
    "target_slip",
    "run_file",
    "window_start_s",
    "window_end_s",
    "window_passes",
    "health",
    "health_codes",
    "window_notes",
)


def write_runs(out_dir, results, window_text):
    """Writes runs.csv: one row per run with its window and health; returns the path."""
    path = os.path.join(out_dir, "runs.csv")
    rows = []
    for r in results:
        m, span = r.metadata, r.span
        rows.append(
            [m.soil, m.wheel, m.terrain, m.target_slip, r.path, span.start, span.end]
            + [span.passes, r.health.verdict, r.health.codes, "; ".join(span.notes)]
        )
    comments = [
        "wheelsim-post study: the runs of the tables, their window and health "
        "(ok, unchecked, warning, incomplete, unhealthy)",
        window_text,
    ]
    write_csv(path, comments, RUNS_HEADER, rows)
    return path


def health_notes(results):
    """Markdown lines naming the runs whose health is not ok (empty if all are ok)."""
    lines = [
        f"- {r.metadata.wheel}, soil {r.metadata.soil}, s = {slip_text(r.metadata.target_slip)}"
        f": {r.health.verdict}" + (f" ({r.health.codes})" if r.health.codes else "")
        + f" — {r.path}"
        for r in results
        if r.health.verdict not in ("ok", "unchecked")
    ]
    if lines:
        lines.insert(0, "Runs whose health is not ok (marked in the tables):\n")
    unchecked = sum(r.health.verdict == "unchecked" for r in results)
    if unchecked:
        lines.append(
            f"\n{unchecked} run(s) have no /health group (unchecked; see runs.csv)."
        )
    return lines


def run(args):
    """Runs the subcommand; returns the exit status."""
    quantities = parse_quantities(args.quantity)
    window = window_from_args(args)
    print(window.describe())
    results = analyse_runs(args.runs, window, args.lugs)
    for r in results:
        for line in window_lines(r):
            print(line)
    tables = build_tables(results, quantities)
    try:
        os.makedirs(args.out_dir, exist_ok=True)
    except OSError as exc:
        raise PostError(
            f"--out-dir: cannot create '{args.out_dir}': {exc.strerror}"
        ) from None
    document = [
        f"# wheelsim-post study\n\n{window.describe()}\n\n"
        "Cells: window mean ± standard error of the mean (batch means).\n"
    ]
    for (soil, quantity), table in tables.items():
        text = markdown(soil, quantity, table)
        print(text)
        document.append(text)
        for path in write_table(args.out_dir, soil, quantity, table, window.describe()):
            print(f"wrote {path}")
    notes = health_notes(results)
    if notes:
        print("\n".join(notes))
        document.append("\n".join(notes) + "\n")
    print(f"wrote {write_runs(args.out_dir, results, window.describe())}")
    md_path = os.path.join(args.out_dir, "study.md")
    with open(md_path, "w", encoding="utf-8") as out:
        out.write("\n".join(document))
    print(f"wrote {md_path}")
    return 0
