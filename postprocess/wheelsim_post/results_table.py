"""``curves --results OUT.csv``: the validation-case table (``validation/<case>/results.csv``,
issue 11).

One row per run file: slip in the three conventions, drawbar pull, driving torque, traction
force and sinkage with their batch-means standard errors, the normal load, and the run's cost
(wall time, particle count, MPI ranks). Header comments: the git revision of the checkout and
the command line that made the file.
"""

import math
import os
import shlex
import subprocess

from .analysis import sinkage_offset_comment
from .csvio import write_csv
from .errors import PostError
from .health import PARTICLES_END_PARAMETER
from .metadata import rig_config
from .quantities import of_means
from .runfile import RunFile
from .usage import find_project_root

#: Help of the curves option that writes the table.
HELP = (
    "write the validation-case table here: one row per run with slip (signed convention), "
    "slip_driving, slip_skid, DP, T, F_T and sinkage with their SEMs, normal load, wall time, "
    "particles, MPI ranks; header: git revision and command (docs/postprocess.md)"
)

#: Columns of results.csv, in order (units in the names; docs/postprocess.md, "results").
COLUMNS = (
    "slip",
    "slip_sem",
    "slip_driving",
    "slip_skid",
    "drawbar_pull_N",
    "drawbar_pull_sem_N",
    "driving_torque_Nm",
    "driving_torque_sem_Nm",
    "traction_force_N",
    "traction_force_sem_N",
    "sinkage_m",
    "sinkage_sem_m",
    "normal_load_N",
    "wall_s",
    "particles",
    "np",
    "target_slip",
    "terrain",
    "n_samples",
    "window_start_s",
    "window_end_s",
    "health",
    "health_codes",
    "run_git_revision",
    "run_file",
)

#: Run-file parameters the cost columns come from (docs/hdf5-layout.md; the particle count:
#: health.PARTICLES_END_PARAMETER).
WALL_TIME_PARAMETER = "run/wall_time"
RANKS_PARAMETER = "liggghts/np"


def _count(run, name, expected):
    """``/parameters/<name>`` as an int >= 1, None if absent; PostError if it is not one."""
    value = run.parameter(name)
    if value is None:
        return None
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not (number >= 1 and number == int(number)):
        raise PostError(
            f"run file '{run.path}': /parameters/{name} is {value!r}, expected {expected} "
            "(a whole number >= 1)"
        )
    return int(number)


def wall_time(run):
    """``/parameters/run/wall_time`` [s] as float, None if absent; PostError if not >= 0."""
    value = run.parameter(WALL_TIME_PARAMETER)
    if value is None:
        return None
    try:
        seconds = float(value)
    except (TypeError, ValueError):
        seconds = math.nan
    if not seconds >= 0.0:
        raise PostError(
            f"run file '{run.path}': /parameters/{WALL_TIME_PARAMETER} is {value!r}, expected "
            "the run's wall time in s (>= 0)"
        )
    return seconds


def writer_revisions(run):
    """The git revisions that wrote a run file, in order: ``/h5md/creator``'s (the first start)
    then each resume's (``/parameters/resume/<k>/git_revision``, k = 1, 2, ...), a revision
    written once where consecutive ones repeat, joined by ' > '."""
    revisions = [run.creator()["git_revision"]]
    k = 1
    while run.has_parameter(f"resume/{k}/step"):
        revision = run.parameter_text(f"resume/{k}/git_revision", "")
        if revision != revisions[-1]:
            revisions.append(revision)
        k += 1
    return " > ".join(revisions)


def run_cost(path):
    """(wall_s, particles, np, writer_revisions()) of a run file; None for a value that is not
    recorded.

    particles: ``/parameters/liggghts/atoms`` (DEM runs through scripts/wheel-cosim); np:
    ``/parameters/liggghts/np``, else 1 when the rig config's terrain is not "dem" (SCM and
    the flat ground run in the rig process alone)."""
    with RunFile(path) as run:
        wall = wall_time(run)
        particles = _count(run, PARTICLES_END_PARAMETER, "the number of particles")
        ranks = _count(run, RANKS_PARAMETER, "the number of MPI ranks of LIGGGHTS")
        terrain = rig_config(run).get("terrain", {}).get("type")
        revision = writer_revisions(run)
    if ranks is None and terrain in ("scm", "flat"):
        ranks = 1
    return wall, particles, ranks, revision


def _blank(value):
    """'' for None, else the value (csvio formats floats)."""
    return "" if value is None else value


def result_row(result, cost, run_file):
    """One results.csv row (order of COLUMNS) of a RunResult, its run_cost() and the name of its
    run file in the table (table_name())."""
    s, span = result.stats, result.span
    wall, particles, ranks, revision = cost
    signed = s[of_means("slip_signed")]
    row = [signed.mean, signed.sem]
    row += [s[of_means("slip")].mean, s[of_means("slip_skid")].mean]
    for name in ("drawbar_pull", "driving_torque", "traction_force", "sinkage"):
        row += [s[name].mean, s[name].sem]
    row += [s["vertical_load"], _blank(wall), _blank(particles), _blank(ranks)]
    row += [result.metadata.target_slip, result.metadata.terrain, s["n_samples"]]
    row += [span.start, span.end, result.health.verdict, result.health.codes]
    row += [revision or "unknown", run_file]
    return row


def table_name(run_path, table_path):
    """A run file's name in the results table at ``table_path``: its path relative to the table's
    folder, so that a table names the same runs on every machine and in every clone (a committed
    table and the run files committed beside it move together)."""
    table_dir = os.path.dirname(os.path.abspath(table_path))
    return os.path.relpath(os.path.abspath(run_path), table_dir)


def tree_revision(root):
    """'<full hash>' of the checkout at ``root``, with ' (uncommitted changes in tracked
    files)' when the tree differs from it; 'unknown (...)' without git or a checkout."""
    if not root or not os.path.exists(os.path.join(root, ".git")):
        return f"unknown (no git checkout at {root or 'the tool'})"
    try:
        head = subprocess.run(
            ["git", "-C", root, "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10
        )
        status = subprocess.run(
            ["git", "-C", root, "status", "--porcelain", "--untracked-files=no"],
            capture_output=True,
            text=True,
            timeout=10,
        )
    except (OSError, subprocess.SubprocessError) as exc:
        return f"unknown (git failed: {exc})"
    if head.returncode != 0 or not head.stdout.strip():
        return f"unknown (git rev-parse failed: {head.stderr.strip()})"
    dirty = status.returncode == 0 and status.stdout.strip() != ""
    return head.stdout.strip() + (" (uncommitted changes in tracked files)" if dirty else "")


def command_text(args):
    """The command line that made the file, quoted for a shell, and the directory it ran in."""
    argv = getattr(args, "argv", None) or []
    return f"wheelsim-post {shlex.join(argv)}  (in {os.getcwd()})"


def sort_key(row):
    """Rows in order of signed slip, NaN last."""
    slip = row[0]
    return (math.isnan(slip), slip if not math.isnan(slip) else 0.0)


def write_results(path, results, window, args):
    """Writes the table of the RunResults ``results`` (window ``window``) to ``path``; the
    header records the checkout's git revision and the command line in ``args.argv``."""
    rows = sorted((result_row(r, run_cost(r.path), table_name(r.path, path)) for r in results),
                  key=sort_key)
    for row in rows:
        record = dict(zip(COLUMNS, row))
        print(
            f"results: slip {record['slip']:.4g} (driving {record['slip_driving']:.4g}, skid "
            f"{record['slip_skid']:.4g}), DP {record['drawbar_pull_N']:.4g} ± "
            f"{record['drawbar_pull_sem_N']:.2g} N, T {record['driving_torque_Nm']:.4g} ± "
            f"{record['driving_torque_sem_Nm']:.2g} N m, sinkage {record['sinkage_m']:.4g} m, "
            f"W {record['normal_load_N']:.4g} N, health {record['health']}  "
            f"({record['run_file']})"
        )
    comments = [
        "wheelsim-post curves --results: one row per run, in order of slip "
        "(docs/postprocess.md, 'The results table')",
        f"git: {tree_revision(find_project_root())}",
        f"command: {command_text(args)}",
        window.describe(),
        "slip: signed convention of the window means: driving 1 - v/(omega*R_eff) for s >= 0, "
        "skid (omega*R_eff - v)/v for s < 0 (-1 = locked wheel); slip_driving, slip_skid: the "
        "two conventions alone (nan where undefined)",
        "_sem: standard error of the window mean (batch means, 20 batches), not the signal's "
        "std; normal_load_N = W (rig vertical load); traction_force_N = T/R_eff",
        "wall_s: the rig process's wall time; particles: LIGGGHTS atoms; np: LIGGGHTS MPI "
        "ranks (1 for SCM and the flat ground); blank where the run file does not record it",
    ] + sinkage_offset_comment(args.sinkage_offset)
    notes = [
        f"{r.path}: health {r.health.verdict} ({r.health.codes})"
        for r in results
        if r.health.verdict != "ok"
    ]
    for r in results:
        notes += [f"{r.path}: {note}" for note in r.span.notes]
    footer = ["notes:"] + notes if notes else []
    write_csv(path, comments, list(COLUMNS), rows, footer)
