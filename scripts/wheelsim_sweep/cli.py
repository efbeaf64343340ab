"""wheel-sweep's command line. Reference: docs/sweeps.md.

Bad usage is one line on stderr and exit status 2, naming the nearest valid option
(wheelsim_post.usage, shared with wheelsim-post; scripts/wheel-sweep puts postprocess/ on the
path).
"""

import fnmatch
import os
import sys
from pathlib import Path

from wheelsim_post import bed_hold, mpi_launch
from wheelsim_post.usage import EXIT_USAGE, UsageParser, add_version

from . import accept, config, estimate, rate, runner

REPO = Path(__file__).resolve().parents[2]  # the source tree, or <prefix>/share/wheelsim
# Default outputs: <repo>/runs, or ./runs when installed (docs/building.md, "Install").
RUNS = REPO / "runs" if (REPO / "CMakeLists.txt").is_file() else Path("runs")


def machine_cores():
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return cores or 1


def default_jobs(sweep):
    cores = machine_cores()
    return max(1, cores // sweep.np) if sweep.terrain == "dem" else cores


def main(argv=None):
    ap = UsageParser(
        prog="wheel-sweep",
        description="Run a slip sweep or a study matrix (wheels x soils x slips) of wheel tests "
                    "(SCM, DEM or flat) from one config file. Docs: docs/sweeps.md.",
        epilog="Exit status: 0 every point done and none unhealthy; 1 a point or a bed failed, "
               "or a run is unhealthy; 2 bad command line or config (with --dry-run also a "
               "point's rig config that wheel-rig --check rejects); 128 + signal number when "
               "interrupted.")
    add_version(ap, "wheel-sweep", start=__file__)
    ap.add_argument("config", nargs="?",
                    help="sweep config (TOML); optional with --measure-rate")
    ap.add_argument("--jobs", "-j", type=int, metavar="N",
                    help="points run at once (default: cores // dem.np for DEM, cores otherwise)")
    ap.add_argument("--out-dir", metavar="DIR",
                    help="output directory (default: <repo>/runs/sweeps/<config name>; "
                         "./runs/sweeps/<config name> when installed)")
    ap.add_argument("--dry-run", action="store_true",
                    help="list the points, whether each is finished, and the commands; "
                         "write nothing")
    ap.add_argument("--force", action="store_true", help="re-run finished points too")
    ap.add_argument("--beds-only", action="store_true",
                    help="DEM: prepare (or reuse) the beds of the sweep's points, then stop: run "
                         "no point (e.g. a cluster's bed job before the point jobs)")
    ap.add_argument("--points", metavar="GLOBS",
                    help="only the points whose folder (WHEEL/SOIL/sSLIP, e.g. wheel1/*/s0.200) "
                         "matches one of these comma-separated shell patterns")
    ap.add_argument("--accept-change", action="append", metavar="FILE",
                    help="DEM: an edit of FILE, a file the deck, soil file or in.soilbin "
                         "include, changes no result: record its new hash in the finished "
                         "points and beds (with --reason, kept in their records) instead of "
                         "re-running them, and with --archive in the archive's finished and "
                         "parked points too; runs nothing (repeatable)")
    ap.add_argument("--reason", metavar="TEXT",
                    help="why the --accept-change edit changes no result (required with it)")
    ap.add_argument("--bed-hold", type=float, default=bed_hold.DEFAULT_HOLD_S, metavar="S",
                    help="the bed-hold check: each prepared bed is left alone S seconds under "
                         "the soil's test settings, and the sweep stops if it settles by more "
                         f"than {100 * bed_hold.SETTLE_LIMIT:.0f} %% (default "
                         f"{bed_hold.DEFAULT_HOLD_S:g}; 0: no check; docs/soil-bins.md)")
    ap.add_argument("--stall-timeout", type=float, default=mpi_launch.DEFAULT_STALL_MIN,
                    metavar="MIN",
                    help="DEM: a bed's in.soilbin or bed-hold check (or a --measure-rate run) "
                         "whose log has not grown for MIN minutes is taken for hung (an MPI rank "
                         "stuck), killed, and the sweep stops (exit 1) (default "
                         f"{mpi_launch.DEFAULT_STALL_MIN:g}; 0: no limit; the points have "
                         "timeouts of their own)")
    ap.add_argument("--archive", metavar="DIR",
                    help="keep each finished point's done.json, run.h5, rig.toml and run.log in "
                         "DIR (e.g. a folder committed to git) and restore them from there into "
                         "the output directory first (docs/sweeps.md, \"Keeping finished "
                         "points\")")
    ap.add_argument("--park", action="store_true",
                    help="with --archive: keep each unfinished DEM point's newest checkpoint "
                         "(and its partial run file) in the archive too, xz-compressed, so that "
                         "a later run on another machine goes on from it; runs nothing, and may "
                         "run beside the sweep that writes the checkpoints (docs/sweeps.md, "
                         "\"Parking a stopped point\")")
    ap.add_argument("--build-dir", metavar="D",
                    help="build directory (default: $WHEELSIM_BUILD_DIR, else <repo>/build)")
    cost = ap.add_argument_group("DEM cost estimate (docs/sweeps.md, \"Cost estimate\")")
    cost.add_argument("--estimate", action="store_true",
                      help="print each DEM point's and the sweep's particles, time step, "
                           "simulated time, steps and predicted wall time; run nothing")
    cost.add_argument("--measure-rate", action="store_true",
                      help="measure this machine's LIGGGHTS particle-step rate (about a "
                           "CPU-minute) and cache it (then go on with CONFIG if given)")
    cost.add_argument("--budget", type=float, metavar="HOURS",
                      help="refuse a DEM sweep whose estimate exceeds HOURS of wall time "
                           "(overrides dem.budget_h)")
    cost.add_argument("--yes", action="store_true",
                      help="run a DEM sweep even if its estimate exceeds the budget")
    cost.add_argument("--cores", type=int, metavar="N",
                      help="cores the estimate assumes (default: this machine's)")
    a = ap.parse_args(argv)

    if a.jobs is not None and a.jobs < 1:
        ap.error(f"--jobs must be >= 1, got {a.jobs}")
    if a.cores is not None and a.cores < 1:
        ap.error(f"--cores must be >= 1, got {a.cores}")
    if not a.bed_hold >= 0:  # also NaN
        ap.error(f"--bed-hold must be a time >= 0 s (0: no check), got {a.bed_hold:g}")
    try:
        stall_s = mpi_launch.stall_seconds(a.stall_timeout)
    except ValueError as e:
        ap.error(f"--stall-timeout: {e}")
    if a.budget is not None and not a.budget > 0:
        ap.error(f"--budget must be a number of hours > 0, got {a.budget:g}")
    if a.config is None and not a.measure_rate:
        ap.error("the following arguments are required: config")
    if a.beds_only and (a.dry_run or a.estimate):
        ap.error("--beds-only prepares beds: not with --dry-run or --estimate")
    if a.accept_change:
        if not (a.reason or "").strip():
            ap.error("--accept-change needs --reason TEXT: why the edit changes no result")
        if a.dry_run or a.estimate or a.beds_only or a.force or a.measure_rate:
            ap.error("--accept-change runs nothing: not with --dry-run, --estimate, "
                     "--beds-only, --force or --measure-rate")
        missing = [f for f in a.accept_change if not Path(f).is_file()]
        if missing:
            ap.error(f"--accept-change {missing[0]}: no such file")
    elif a.reason is not None:
        ap.error("--reason goes with --accept-change")
    if a.park:
        if a.archive is None:
            ap.error("--park keeps checkpoints in the archive: it needs --archive DIR")
        if a.dry_run or a.estimate or a.beds_only or a.force or a.measure_rate:
            ap.error("--park runs nothing: not with --dry-run, --estimate, --beds-only, --force "
                     "or --measure-rate")
    build = Path(a.build_dir or os.environ.get("WHEELSIM_BUILD_DIR") or REPO / "build").resolve()
    liggghts = build / "bin" / "liggghts-wheel"
    if a.measure_rate:
        rc = measure_rate(liggghts, build, stall_s)
        if rc != 0 or a.config is None:
            return rc
    try:
        sweep = config.load(a.config, REPO, build)
    except config.ConfigError as e:
        print(f"wheel-sweep: error: {e}", file=sys.stderr)
        return EXIT_USAGE
    if a.points is not None:
        globs = [g for g in a.points.split(",") if g]
        chosen = [p for p in sweep.points if any(fnmatch.fnmatchcase(p.reldir, g) for g in globs)]
        if not chosen:
            print(f"wheel-sweep: error: --points {a.points!r} matches none of the sweep's points: "
                  f"{', '.join(p.reldir for p in sweep.points)}", file=sys.stderr)
            return EXIT_USAGE
        sweep.points = chosen
    if a.beds_only and sweep.terrain != "dem":
        print(f"wheel-sweep: error: --beds-only: {a.config} is an {sweep.terrain.upper()} sweep; "
              "only DEM sweeps have beds", file=sys.stderr)
        return EXIT_USAGE
    needed = [build / "bin" / "wheel-rig"]
    if sweep.terrain == "dem":
        needed += [REPO / "scripts" / "wheel-cosim", build / "bin" / "liggghts-wheel"]
    for f in needed:
        if not os.access(f, os.X_OK) and not (a.dry_run or a.accept_change):
            print(f"wheel-sweep: error: {f} not found or not executable (build it, or pass "
                  "--build-dir)", file=sys.stderr)
            return EXIT_USAGE
    out = Path(a.out_dir) if a.out_dir else RUNS / "sweeps" / Path(a.config).stem
    jobs = a.jobs or default_jobs(sweep)
    cores = a.cores or machine_cores()

    def machine_rate():
        try:
            key = rate.machine_key(rate.liggghts_version(liggghts))
        except estimate.EstimateError as e:
            raise estimate.EstimateError(f"the rate cache is keyed by the liggghts-wheel version: "
                                         f"{e}")
        return rate.lookup(rate.cache_path(), key)
    cost = {"rate": machine_rate, "cores": cores, "yes": a.yes,
            "budget_h": a.budget if a.budget is not None else sweep.budget_h}
    r = runner.Runner(sweep, out, REPO, build, jobs, force=a.force, dry_run=a.dry_run,
                      cost=cost, beds_only=a.beds_only, archive_dir=a.archive,
                      bed_hold_s=a.bed_hold, stall_s=stall_s)
    if a.estimate:
        return print_estimate(r, sweep, cost)
    if a.accept_change:
        return accept.accept_changes(r, a.accept_change, a.reason.strip())
    if a.park:
        return r.park()
    try:
        return r.run()
    except RuntimeError as e:
        print(f"wheel-sweep: error: {e}", file=sys.stderr)
        return 1


def measure_rate(liggghts, build, stall_s):
    mesh = build / "meshes" / "test_small.stl"
    for f in (liggghts, mesh):
        if not f.is_file():
            print(f"wheel-sweep: error: --measure-rate needs {f} (build it, or pass --build-dir)",
                  file=sys.stderr)
            return EXIT_USAGE
    np2 = rate.have_mpirun() and machine_cores() >= 2
    try:
        entry = rate.measure(liggghts, REPO, mesh, np2=np2, stall_s=stall_s)
        path = rate.cache_path()
        rate.write_cache(path, entry)
    except (estimate.EstimateError, OSError) as e:
        print(f"wheel-sweep: error: --measure-rate: {e}", file=sys.stderr)
        return 1
    print(f"measure-rate: {entry['particles']} particles, {entry['steps']} steps: "
          f"{entry['rate_per_rank']:.4g} particle-steps/s per rank, np-2 efficiency "
          f"{entry['efficiency_np2']:.3f}" + ("" if np2 else " (default: np 2 not measured)")
          + f", startup {entry['startup_s']} s, beds {entry['bed_rate_per_rank']:.4g} "
          f"particle-steps/s; load average {entry['load_average_1min']} on {entry['cores']} "
          f"cores; cached in {path}", flush=True)
    return 0


def print_estimate(r, sweep, cost):
    """--estimate: the whole printout; exit 0 (2 when it cannot be made)."""
    if sweep.terrain != "dem":
        print(f"estimate: {sweep.path.name}: terrain {sweep.terrain}: the cost estimate covers "
              "DEM sweeps only")
        return 0
    try:
        est = r.cost_estimate(cost["rate"], cost["cores"])
    except estimate.EstimateError as e:
        print(f"wheel-sweep: error: estimate: {e}", file=sys.stderr)
        return EXIT_USAGE
    for line in estimate.report(est, sweep.path.name):
        print(line)
    b = cost["budget_h"]
    if b is not None:
        verdict = "exceeds" if est.total > b * 3600.0 else "within"
        print(f"estimate: budget {b:g} h: {verdict} (a run " +
              ("stops unless --yes" if verdict == "exceeds" else "goes ahead") + ")")
    return 0
