"""``approach``: how a run approaches steady state — the means of observables over successive
segments of the carriage's travel in the test phase, and the change from one segment to the next
(docs/postprocess.md, "approach"). A run whose last changes have not died out is not steady,
whatever its window's SEM says."""

import math
import sys

import numpy as np

from .choices import split_list
from .csvio import write_csv
from .errors import PostError
from .runfile import RunFile
from .steady import TEST_PHASE, require_scalar

HELP = ("means of drawbar pull, torque and sinkage over successive segments of travel in the "
        "test phase: how far a run is from steady state")
DEFAULT_OBSERVABLES = ("drawbar_pull", "driving_torque", "sinkage")
DEFAULT_SEGMENT_M = 0.025
# Where the travel comes from, in this order: the carriage moves the wheel (imposed speed or the
# rig's carriage); a run without a carriage observable falls back on the wheel centre.
TRAVEL_OBSERVABLES = ("carriage/position", "wheel/position")


def add_parser(subparsers):
    """Registers the subcommand."""
    parser = subparsers.add_parser("approach", help=HELP, description=HELP)
    parser.add_argument("runs", nargs="+", metavar="RUN.h5", help="run files")
    parser.add_argument(
        "--segment",
        type=float,
        default=DEFAULT_SEGMENT_M,
        metavar="M",
        help=f"segment length of travel [m] (default {DEFAULT_SEGMENT_M})",
    )
    parser.add_argument(
        "--observables",
        metavar="A,B,...",
        help="comma-separated one-component observables (default: "
        + ",".join(DEFAULT_OBSERVABLES)
        + ")",
    )
    parser.add_argument("--csv", metavar="OUT.csv", help="write the table here")
    parser.set_defaults(func=run)
    return parser


def travel_series(run):
    """(step, travel [m]) over the test phase: the x of the carriage (else of the wheel centre)
    from its first finite test-phase sample. PostError naming what is missing."""
    phase = run.observable("phase")
    test_steps = phase.step[np.rint(np.ravel(phase.value)) == TEST_PHASE]
    if len(test_steps) == 0:
        raise PostError(f"run file '{run.path}' has no test-phase samples (phase never 3)")
    for name in TRAVEL_OBSERVABLES:
        if run.has_observable(name):
            series = run.observable(name)
            keep = np.isin(series.step, test_steps)
            x = series.value.reshape(len(series), -1)[keep, 0]
            finite = np.isfinite(x)
            if np.any(finite):
                return series.step[keep][finite], np.abs(x[finite] - x[finite][0])
    raise PostError(
        f"run file '{run.path}' has none of the observables {', '.join(TRAVEL_OBSERVABLES)} "
        "with a finite x in its test phase: no travel to segment"
    )


def segment_bounds(travel, segment_m):
    """[(from_m, to_m)]: successive segments [k L, (k + 1) L) of ``travel`` [m]; the last ends
    at the largest travel and is kept only if at least half a segment long."""
    total = float(np.max(travel)) if len(travel) else 0.0
    count = int(math.floor(total / segment_m + 1e-9))
    if total - count * segment_m >= 0.5 * segment_m:
        count += 1
    return [(k * segment_m, min((k + 1) * segment_m, total)) for k in range(count)]


def segment_means(travel_step, travel, series_step, values, bounds):
    """[(n, mean)] of the finite ``values`` (at ``series_step``) per segment of ``bounds``
    (segment_bounds) of ``travel`` (at ``travel_step``, sorted); (0, NaN) where a segment holds
    none, so that the segments of every observable line up."""
    keep = np.isin(series_step, travel_step)
    where = np.searchsorted(travel_step, series_step[keep])
    x, v = travel[where], np.asarray(values)[keep]
    finite = np.isfinite(v)
    x, v = x[finite], v[finite]
    out = []
    for k, (lo, hi) in enumerate(bounds):
        inside = (x >= lo) & ((x < hi) if k < len(bounds) - 1 else (x <= hi))
        n = int(np.sum(inside))
        out.append((n, float(np.mean(v[inside])) if n else math.nan))
    return out


def run(args):
    """Prints (and optionally writes) the segment table of every run; returns 0."""
    if not (args.segment > 0 and math.isfinite(args.segment)):
        raise PostError(f"--segment: expected a finite length > 0 m, got {args.segment:g}")
    names = split_list(args.observables) if args.observables else list(DEFAULT_OBSERVABLES)
    if not names:
        raise PostError("--observables: expected a comma-separated list of names")
    rows = []
    for path in args.runs:
        with RunFile(path) as run_file:
            travel_step, travel = travel_series(run_file)
            order = np.argsort(travel_step)
            travel_step, travel = travel_step[order], travel[order]
            segments = segment_bounds(travel, args.segment)
            if not segments:
                hint = "; choose a shorter --segment" if np.max(travel) > 0 else ""
                raise PostError(
                    f"run file '{path}': the test phase travels {np.max(travel):.4g} m, less "
                    f"than half a segment of {args.segment:g} m (--segment): no segment to "
                    f"average over{hint}"
                )
            table = {}
            for name in names:
                series = require_scalar(run_file, run_file.observable(name))
                means = segment_means(travel_step, travel, series.step, series.value, segments)
                if not any(n for n, _ in means):
                    raise PostError(
                        f"run file '{path}': observable '{name}' has no finite sample in the "
                        f"test phase's {np.max(travel):.4g} m of travel; expected numbers: the "
                        "run went wrong or did not record it"
                    )
                table[name] = (series.unit, means)
        units = {name: unit for name, (unit, _) in table.items()}
        print(f"{path}: means over {args.segment * 1e3:g} mm of test-phase travel "
              f"(change from the segment before)")
        header = "  travel [mm]   " + "".join(f"{n} [{units[n]}]".rjust(28) for n in names)
        print(header)
        previous = {}
        for i, (lo, hi) in enumerate(segments):
            cells = []
            row = {"run": path, "from_m": lo, "to_m": hi}
            for name in names:
                mean = table[name][1][i][1]
                change = mean - previous[name] if name in previous else math.nan
                previous[name] = mean
                row[name] = mean
                row[f"{name}_change"] = change
                text = f"{mean:.4g}" + ("" if math.isnan(change) else f" ({change:+.3g})")
                cells.append(text.rjust(28))
            print(f"  {lo * 1e3:5.0f} - {hi * 1e3:5.0f}  " + "".join(cells))
            rows.append(row)
        print()
    if args.csv:
        columns = ["run", "from_m", "to_m"] + [c for n in names for c in (n, f"{n}_change")]
        write_csv(args.csv,
                  [f"wheelsim-post approach: means over {args.segment:g} m of test-phase "
                   "travel; *_change: minus the segment before"],
                  columns, [[r[c] for c in columns] for r in rows])
        print(f"wheelsim-post approach: wrote {args.csv}", file=sys.stderr)
    return 0
