"""wheel-sweep's command line. Reference: docs/sweeps.md.

Bad usage is one line on stderr and exit status 2, naming the nearest valid option
(wheelsim_post.usage, shared with wheelsim-post; scripts/wheel-sweep puts postprocess/ on the
path).
"""

import os
import sys
from pathlib import Path

from wheelsim_post.usage import EXIT_USAGE, UsageParser, add_version

from . import config, runner

REPO = Path(__file__).resolve().parents[2]


def default_jobs(sweep):
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    cores = cores or 1
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
    ap.add_argument("config", help="sweep config (TOML)")
    ap.add_argument("--jobs", "-j", type=int, metavar="N",
                    help="points run at once (default: cores // dem.np for DEM, cores otherwise)")
    ap.add_argument("--out-dir", metavar="DIR",
                    help="output directory (default: <repo>/runs/sweeps/<config name>)")
    ap.add_argument("--dry-run", action="store_true",
                    help="list the points, whether each is finished, and the commands; "
                         "write nothing")
    ap.add_argument("--force", action="store_true", help="re-run finished points too")
    ap.add_argument("--build-dir", metavar="D",
                    help="build directory (default: $WHEELSIM_BUILD_DIR, else <repo>/build)")
    a = ap.parse_args(argv)

    if a.jobs is not None and a.jobs < 1:
        ap.error(f"--jobs must be >= 1, got {a.jobs}")
    build = Path(a.build_dir or os.environ.get("WHEELSIM_BUILD_DIR") or REPO / "build").resolve()
    try:
        sweep = config.load(a.config, REPO, build)
    except config.ConfigError as e:
        print(f"wheel-sweep: error: {e}", file=sys.stderr)
        return EXIT_USAGE
    needed = [build / "bin" / "wheel-rig"]
    if sweep.terrain == "dem":
        needed += [REPO / "scripts" / "wheel-cosim", build / "bin" / "liggghts-wheel"]
    for f in needed:
        if not os.access(f, os.X_OK) and not a.dry_run:
            print(f"wheel-sweep: error: {f} not found or not executable (build it, or pass "
                  "--build-dir)", file=sys.stderr)
            return EXIT_USAGE
    out = Path(a.out_dir) if a.out_dir else REPO / "runs" / "sweeps" / Path(a.config).stem
    jobs = a.jobs or default_jobs(sweep)
    try:
        return runner.Runner(sweep, out, REPO, build, jobs, force=a.force,
                             dry_run=a.dry_run).run()
    except RuntimeError as e:
        print(f"wheel-sweep: error: {e}", file=sys.stderr)
        return 1
