"""soil-lab's command line (docs/soil-lab.md):

  soil-lab run SOIL [--tests bulk,plate,shear,repose] [--out DIR] [--np N] [--preset P]
                    [--normal-stresses S1,S2,S3] [--bed-var NAME=VALUE ...] [--archive DIR]
                    [--accept-change FILE --reason TEXT] [--stall-timeout MIN] [--build-dir D]
                    [--park | --estimate]
  soil-lab report DIR
  soil-lab scm DIR --out FILE.toml [--name NAME] [--shear-from LAB [--shear-soil NAME]]
               [--relaxed] [--rate-dependent]
  soil-lab compare LABEL=DIR [LABEL=DIR ...] [--at MM,MM,...] [--target C_PA,PHI_DEG]
                   [--tolerance DEG] [--md FILE] [--png FILE]

Exit status: 0 done; 1 a LIGGGHTS or wheel-mesh run failed, or a fit failed; 2 bad command
line, unknown soil or test, or a test size the lab rejects.
"""

import os
import sys
from pathlib import Path

from wheelsim_post import bed_hold, mpi_launch
from wheelsim_post.deck_files import deck_includes
from wheelsim_post.usage import EXIT_USAGE, UsageParser, add_version
from wheelsim_sweep import estimate as sweep_estimate

from . import analysis, compare, estimate, plan, runner, scm_file
from ._inputs import FitInputError

REPO = Path(__file__).resolve().parents[2]  # the source tree, or <prefix>/share/wheelsim
# Default outputs: <repo>/runs, or ./runs when installed (docs/building.md, "Install").
RUNS = REPO / "runs" if (REPO / "CMakeLists.txt").is_file() else Path("runs")


def _list(text, what):
    items = [t.strip() for t in text.split(",") if t.strip()]
    if not items:
        raise plan.LabInputError(f"{what}: expected a comma-separated list, got '{text}'")
    return items


def _invocations(soil_toml):
    """The provenance of earlier `soil-lab run`s into this directory (a resumed lab has several)."""
    import tomllib

    try:
        return tomllib.loads(soil_toml.read_text()).get("invocations", [])
    except (OSError, tomllib.TOMLDecodeError):
        return []


def _provenance(np_ranks):
    """Who made these results: command, git commit (and whether the tree had changes), machine,
    start time (UTC)."""
    import datetime
    import platform
    import shlex
    import subprocess
    import sys

    def git(*args):
        r = subprocess.run(["git", "-C", str(REPO), *args], capture_output=True, text=True)
        return r.stdout.strip() if r.returncode == 0 else "unknown"

    # shell-quoted, so that it can be pasted back (e.g. --bed-var "soil_pair_settings=a b")
    return {"command": shlex.join(["soil-lab"] + sys.argv[1:]), "git_commit": git("rev-parse", "HEAD"),
            "git_changes": git("status", "--porcelain", "--untracked-files=no") not in ("", "unknown"),
            "host": platform.node(), "cores": os.cpu_count() or 0, "np": np_ranks,
            "started_utc": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")}


def _numbers(text, option, expected):
    """The comma-separated numbers of `option` (None if not given), or a LabInputError."""
    if text is None:
        return None
    try:
        return [float(x) for x in _list(text, option)]
    except ValueError:
        raise plan.LabInputError(f"{option}: expected {expected}, got '{text}'") from None


def run_options(a):
    """The options of `soil-lab run` (parsed arguments `a`) as make_plan's keyword arguments
    (without speed_check and dt_check), after every check that needs no soil
    (plan.check_options, and the command line's own): bad input is refused before anything is
    created or started. Returns (tests, options, bed_vars)."""
    tests = _list(a.tests, "--tests")
    for option, n in (("--np", a.np), ("--bed-np", a.bed_np)):
        if n is not None and n < 1:
            raise plan.LabInputError(f"{option} must be >= 1, got {n}")
    options = dict(normal_stresses_Pa=_numbers(a.normal_stresses, "--normal-stresses",
                                               "numbers in Pa"),
                   plate_widths_m=_numbers(a.plate_widths, "--plate-widths", "two widths in m"),
                   plate_bin_m=a.plate_bin, shear_travel=a.shear_travel,
                   plate_speed=a.plate_speed, shear_speed=a.shear_speed,
                   plate_depth=a.plate_depth, plate_hold=a.plate_hold,
                   plate_hold_stages=a.plate_hold_stages, shear_replicates=a.shear_replicates,
                   plate_replicates=a.plate_replicates)
    bed_vars = {}
    for item in a.bed_var or []:
        if "=" not in item or item.startswith("="):
            raise plan.LabInputError(f"--bed-var: expected NAME=VALUE (an in.soilbin variable), "
                                     f"got '{item}'")
        k, v = item.split("=", 1)
        bed_vars[k] = v
    if a.park and a.archive is None:
        raise plan.LabInputError("--park keeps checkpoints in the archive: it needs --archive DIR")
    if a.accept_change and not (a.reason or "").strip():
        raise plan.LabInputError("--accept-change needs --reason TEXT: why the edit changes no "
                                 "result")
    if a.reason is not None and not a.accept_change:
        raise plan.LabInputError("--reason goes with --accept-change")
    if a.estimate and (a.park or a.accept_change):
        raise plan.LabInputError("--estimate runs nothing: not with --park or --accept-change")
    if a.accept_change and a.park:
        raise plan.LabInputError("--accept-change keeps finished steps of a lab that runs: not "
                                 "with --park")
    for f in a.accept_change or []:
        if not Path(f).is_file():
            raise plan.LabInputError(f"--accept-change {f}: no such file")
    if a.checkpoints < 0:
        raise plan.LabInputError(f"--checkpoints: expected a number >= 0 (0: none), got "
                                 f"{a.checkpoints}")
    if not a.bed_hold >= 0:  # also NaN
        raise plan.LabInputError(f"--bed-hold: expected a time >= 0 s (0: no check), got "
                                 f"{a.bed_hold}")
    try:
        mpi_launch.stall_seconds(a.stall_timeout)
    except ValueError as e:
        raise plan.LabInputError(f"--stall-timeout: {e}") from None
    tests = plan.check_options(tests, a.preset, **options)
    return tests, options, bed_vars


def _run(a):
    import tomli_w

    build = Path(a.build_dir or os.environ.get("WHEELSIM_BUILD_DIR") or REPO / "build").resolve()
    # Everything that does not need the soil is checked before anything is created or started;
    # make_plan then checks what needs the soil's sizes (in.lab_soilinfo, a LIGGGHTS run).
    tests, options, bed_vars = run_options(a)
    soil_file = runner.resolve_soil_file(a.soil, REPO / "inputs")
    accept = None
    if a.accept_change:
        _check_includable(a.accept_change, soil_file)
        accept = (a.accept_change, a.reason.strip())
    out = Path(a.out or RUNS / "soil_lab" / Path(soil_file).stem).resolve()
    lab = runner.Lab(REPO, build, out, np=a.np, quiet=a.quiet, archive=a.archive,
                     checkpoints=a.checkpoints, bed_hold_s=a.bed_hold,
                     stall_s=mpi_launch.stall_seconds(a.stall_timeout),
                     accept=accept, bed_np=a.bed_np)  # checks the build
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise plan.LabInputError(f"--out {out}: cannot create the directory: {e.strerror}") \
            from None
    soil = lab.soil_info(soil_file)
    p = plan.make_plan(soil, tests, a.preset, bed_vars=bed_vars, speed_check=a.speed_check,
                       dt_check=a.dt_check, **options)
    if a.park:
        return lab.park(p)
    if a.estimate:
        try:
            machine = estimate.MachineRate.of_this_machine(
                lab.liggghts, a.np, soil.file, REPO / "inputs", REPO / "inputs" / "in.soilbin",
                bed_np=lab.bed_np)
        except sweep_estimate.EstimateError as e:
            machine = None
            lab.say(f"estimate: this machine's rate not available ({e}): what the lab has no "
                    "pace of is not priced")
        for line in estimate.lab_estimate(p, out, a.archive, machine, a.np):
            lab.say(line)
        return 0
    # The soil file as the checkout names it (inputs/soils/x.in), so results do not carry the
    # path of the machine that ran them; a file outside the checkout keeps its absolute path.
    soil_path = Path(soil.file).resolve()
    shown_file = (str(soil_path.relative_to(REPO.resolve()))
                  if soil_path.is_relative_to(REPO.resolve()) else str(soil_path))
    (out / "soil.toml").write_text(tomli_w.dumps({
        "name": soil.name, "file": shown_file, "preset": a.preset, "tests": list(p.tests),
        "dmin_m": soil.dmin_m, "dmax_m": soil.dmax_m, "dref_m": soil.dref_m,
        "density_kg_m3": soil.density_kg_m3, "multisphere": soil.multisphere, "dt_s": soil.dt_s,
        "youngs_Pa": soil.youngs_Pa,
        "invocations": _invocations(out / "soil.toml") + [_provenance(a.np)]}))
    lab.say(f"soil '{soil.name}' ({soil.file}): d {soil.dmin_m:g}..{soil.dmax_m:g} m, dt "
            f"{soil.dt_s:.4g} s; tests {', '.join(p.tests)} ({a.preset}); {len(p.beds)} beds, "
            f"{len(p.runs)} runs on {a.np} rank(s)"
            + (f" (beds prepared on {lab.bed_np})" if lab.bed_np != a.np else "")
            + f" into {out}")
    lab.run_plan(p)
    if accept:
        kept = {f for files in lab.accepted.values() for f in files}  # resolved paths
        lab.say(f"--accept-change: {len(lab.accepted)} finished step(s) kept across the edit "
                f"(reason: {accept[1]})")
        for f in a.accept_change:
            if str(Path(f).resolve()) not in kept:
                lab.say(f"--accept-change {f}: no finished step had recorded another version "
                        "of it (nothing to keep)")
    return _report(out, a.quiet)


def _check_includable(files, soil_file):
    """--accept-change takes only files that the soil file, in.soilbin, in.bedhold or the lab's
    decks include in turn (a LabInputError otherwise): an edit of the soil file or of a deck is
    part of every step's inputs hash and always re-runs."""
    variables = {"inputs_dir": str(REPO / "inputs")}
    tops = [Path(soil_file), REPO / "inputs" / "in.soilbin", REPO / "inputs" / bed_hold.DECK,
            *sorted(runner.DECKS.glob("in.*"))]
    included = {str(Path(g).resolve()) for t in tops for g in deck_includes(t, variables)}
    shown = sorted(str(Path(g).relative_to(REPO.resolve())) if Path(g).is_relative_to(
        REPO.resolve()) else g for g in included)
    for f in files:
        if str(Path(f).resolve()) not in included:
            raise plan.LabInputError(
                f"--accept-change {f}: not a file the soil file or the lab's decks include "
                "(only included files can be accepted: an edit of the soil file itself or of a "
                f"deck always re-runs; included: {', '.join(shown)})")


def _report(directory, quiet=False):
    r = analysis.analyse(directory)
    try:
        written = analysis.write_report(r)
    except OSError as e:
        raise analysis.LabResultError(f"{e.filename or directory}: cannot write the report: "
                                      f"{e.strerror}") from None
    for path in written:
        if not quiet:
            print(f"soil-lab: wrote {path}")
    if not quiet:
        s = analysis.summary(r)
        for test in ("bulk", "plate", "shear", "repose"):
            if test in s:
                vals = {k: v for k, v in s[test].items() if isinstance(v, float)}
                if vals:
                        print(f"soil-lab: {test}: "
                          + ", ".join(f"{k} {v:.4g}" for k, v in vals.items()))
        if r.repose_error:
            print(f"soil-lab: warning: repose: {r.repose_error}")
        for w in s.get("shear", {}).get("warnings", []):
            print(f"soil-lab: warning: {w}")
        if r.replicates:
            _print_replicates(r.replicates)
        if r.plate_replicates:
            _print_plate_replicates(r.plate_replicates)
        for bed, h in sorted(r.bed_holds.items()):
            # a failed check in the report: the lab ran on with --bed-hold 0
            failed = bed_hold.failure(h, bed, Path(directory) / "beds" / bed / "hold" /
                                      "liggghts.log")
            print(f"soil-lab: warning: {failed} (this lab ran with the check off)" if failed else
                  f"soil-lab: bed '{bed}': {bed_hold.verdict(h)} under the test settings: "
                  f"{bed_hold.describe(h)}")
        if r.costs or r.bed_costs:
            c = s["cost_total"]
            print(f"soil-lab: cost: beds {c['beds_wall_s']:.0f} s + runs {c['runs_wall_s']:.0f} s "
                  f"= {c['lab_wall_s'] / 60:.1f} min of wall time")
        for w, hs in sorted(r.holds.items()):
            for h in hs:
                f = h["fit"]
                print(f"soil-lab: plate b = {w:.4g} m held {h['hold_s']:.3g} s at z "
                      f"{1e3 * h['z_m']:.3g} mm: p {h['p_moving_Pa'] / 1e3:.4g} -> "
                      f"{h['p_end_Pa'] / 1e3:.4g} kPa ({-100 * h['relaxation']:+.1f} %; "
                      f"{-100 * h['step_at_stop']:+.1f} % within "
                      f"{1e3 * analysis.HOLD_STEP_S:g} ms)"
                      + ("" if f is None else f"; fit tau {f.tau_s:.3g} s, p_inf "
                         f"{f.p_inf_Pa / 1e3:.4g} kPa")
                      + ("" if h["converged"] else f" (still relaxing: "
                         f"{-100 * h['late_drop']:+.1f} % over its second half)"))
        if r.bekker_relaxed:
            b = r.bekker_relaxed
            print(f"soil-lab: plate, relaxed (hold ends): n {b.n:.4g}, kc {b.kc:.4g}, kphi "
                  f"{b.kphi:.4g}, R2 {b.r2:.4g}")
        for w, e in sorted(r.unload_errors.items()):
            print(f"soil-lab: warning: plate b = {w:.4g} m: no elastic stiffness: {e}")
        for q in r.quasi_static:
            diff = f"{100 * q['difference']:+.1f} %" if q["relative"] else \
                f"{q['difference']:+.2f} {q['unit']}"
            tol = f"{100 * q['tolerance']:g} %" if q["relative"] else f"{q['tolerance']:g} {q['unit']}"
            print(f"soil-lab: quasi-static: {q['run']}: {q['quantity']} at half speed {diff} "
                  f"(tolerance {tol}): {'ok' if q['passed'] else 'NOT quasi-static'}")
            if "profile_depth_m" in q:
                print(f"soil-lab: quasi-static: {q['run']}: pressure at half speed by depth: "
                      f"{_bands(q, 'profile_depth_m')}")
            if "profile_displacement_m" in q:
                print(f"soil-lab: quasi-static: {q['run']}: shear stress at half speed by "
                      f"displacement (quarters of the travel): {_bands(q, 'profile_displacement_m')}; "
                      "lid over the shear "
                      f"{1e3 * q['lid_full_m']:+.2f} mm at full speed, "
                      f"{1e3 * q['lid_half_m']:+.2f} mm at half speed")
                if "replicate_differences" in q:
                    n_sd = q["half_speed_sds_from_mean"]
                    within = abs(n_sd) <= analysis.REPLICATE_SCATTER_SDS
                    print(f"soil-lab: quasi-static: {q['run']}: its replicates at the same speed "
                          "(other beds) peak "
                          + ", ".join(f"{100 * x:+.1f} %" for x in q["replicate_differences"])
                          + f" from it; the half-speed peak is {100 * q['half_speed_from_mean']:+.1f}"
                          f" % from the mean of the {len(q['replicate_differences']) + 1} "
                          f"same-speed boxes ({n_sd:+.2f} sd): "
                          + ("within their scatter, so the check cannot tell a rate effect of "
                             "this size from the box-to-box scatter" if within else
                             f"outside {analysis.REPLICATE_SCATTER_SDS:g} sd of their scatter: "
                             "a rate effect"))
                elif q["profile_changes_sign"]:
                    print(f"soil-lab: quasi-static: {q['run']}: the difference changes sign along "
                          "the travel, so the verdict rests on where the peaks fell: one pair of "
                          "runs cannot tell the box's own fluctuation (stick-slip) from a rate "
                          "effect that grows along the travel (a slower sample of a creeping "
                          "soil compacts more: compare the lids); replicates at the same speed "
                          "(--shear-replicates) would measure the fluctuation")
    for c in r.paired_speed_checks:
        _print_paired(c, "quasi-static", "at half speed against its {tool} at full speed",
                      {"quasi-static": "quasi-static (the whole interval within it)",
                       "rate effect": "a rate effect (the whole interval outside it): NOT "
                                      "quasi-static"})
    for q in r.time_step:
        at = "profile_depth_m" if "profile_depth_m" in q else "profile_displacement_m"
        print(f"soil-lab: time step: {q['run']}: {q['quantity']} at half the step "
              f"({q['half_dt_s']:.4g} against {q['full_dt_s']:.4g} s) "
              f"{100 * q['difference']:+.1f} % (tolerance {100 * q['tolerance']:g} %): "
              f"{'ok' if q['passed'] else 'STEP-DEPENDENT'}; by "
              f"{'depth' if at == 'profile_depth_m' else 'displacement'}: {_bands(q, at)} "
              f"(mean {100 * sum(q['profile_difference']) / len(q['profile_difference']):+.1f} %)")
    for c in r.paired_step_checks:
        _print_paired(c, "time step", "at half the step against its {tool} at the soil's step",
                      {"step-converged": "step-converged (the whole interval within it)",
                       "step effect": "a step effect (the whole interval outside it): "
                                      "STEP-DEPENDENT"})
    return 0


def _print_paired(c, check, pair, verdicts):
    """The report's line on a check paired over beds (analysis.paired_check's result `c`;
    `verdicts`: the text of each verdict but "cannot tell")."""
    at, tool = ((f"plate b {c['b_m']:.4g} m", "plate") if c["test"] == "plate" else
                (f"{c['sigma_target_Pa'] / 1e3:.3g} kPa", "box"))
    print(f"soil-lab: {check} over {c['beds']} beds at {at} "
          f"(each bed's {tool} {pair.format(tool=tool)}: "
          + ", ".join(f"{100 * x:+.1f} %" for x in c["differences"])
          + f"): mean {100 * c['mean_difference']:+.1f} % ± {100 * c['sem_difference']:.1f} % "
          f"(standard error), 95 % interval {100 * c['interval_low']:+.1f} to "
          f"{100 * c['interval_high']:+.1f} % against the tolerance ±{100 * c['tolerance']:g} %: "
          + verdicts.get(c["verdict"],
                         "cannot tell (the interval straddles the tolerance; more beds narrow it)"))


def _print_plate_replicates(rep):
    """The report's lines on replicate plates (analysis.plate_replicates' summary)."""
    for b in rep["by_width"]:
        print(f"soil-lab: plate replicates b {b['b_m']:.4g} m: {b['plates']} plates, pressure at "
              f"the end of loading {b['p_end_mean_Pa'] / 1e3:.4g} kPa, sd "
              f"{b['p_end_sd_Pa'] / 1e3:.3g} kPa, spread {100 * b['p_end_spread']:.1f} %")
    if rep["fitted_replicates"]:
        rho = rep.get("bed_bulk_density_kg_m3", {})
        print("soil-lab: plate replicates, each bed's own fit: " + "; ".join(
            f"bed {k}: n {n:.3g}, kc {kc:.4g}, kphi {kphi:.4g}"
            + (f" ({rho[f'bed{k}']:.4g} kg/m3)" if f"bed{k}" in rho else "")
            for k, n, kc, kphi in zip(rep["fitted_replicates"], rep["n"], rep["kc_N_m_n1"],
                                      rep["kphi_N_m_n2"]))
            + ("" if "n_sd" not in rep else
               f" (sd n {rep['n_sd']:.3g}, kc {rep['kc_N_m_n1_sd']:.3g}, kphi "
               f"{rep['kphi_N_m_n2_sd']:.3g})"))


def _print_replicates(rep):
    """The report's lines on replicate boxes (analysis.shear_replicates' summary)."""
    for b in rep["by_stress"]:
        print(f"soil-lab: shear replicates at {b['sigma_target_Pa'] / 1e3:.3g} kPa: {b['boxes']} "
              f"boxes, peak {b['tau_peak_mean_Pa'] / 1e3:.4g} kPa, sd "
              f"{b['tau_peak_sd_Pa'] / 1e3:.3g} kPa, spread {100 * b['tau_peak_spread']:.1f} %")
    if rep["fitted_replicates"]:
        print("soil-lab: shear replicates, each bed's own fit: " + "; ".join(
            f"bed {k}: phi {phi:.2f} deg, c {c / 1e3:.3g} kPa" for k, phi, c in
            zip(rep["fitted_replicates"], rep["friction_deg"], rep["cohesion_Pa"]))
            + ("" if "friction_sd_deg" not in rep else
               f" (sd {rep['friction_sd_deg']:.2f} deg, {rep['cohesion_sd_Pa'] / 1e3:.3g} kPa)"))


def _bands(q, at):
    """A speed check's band differences as "<position> mm <difference> %, ..." (at: the key of
    the band positions [m])."""
    return ", ".join(f"{1e3 * x:.3g} mm {100 * d:+.1f} %" for x, d in
                     zip(q[at], q["profile_difference"]))


def _compare(a):
    at = _numbers(a.at, "--at", "shear displacements > 0 [mm]")
    if any(v <= 0 for v in at):
        raise plan.LabInputError(f"--at: expected shear displacements > 0 [mm], got '{a.at}'")
    target = a.target and compare.check_target(
        _numbers(a.target, "--target", "C_PA,PHI_DEG (numbers)"))
    labs, plate_labs = compare.load_all([compare.parse_source(s) for s in a.sources])
    if not (0 < a.tolerance < 90):
        raise plan.LabInputError(f"--tolerance: expected a friction angle tolerance in (0, 90) "
                                 f"[deg], got {a.tolerance:g}")
    with_boxes = [(label, bs) for label, bs in labs if bs]
    with_plates = [(label, ps) for label, ps in plate_labs if ps]
    text = "\n".join(([compare.table(with_boxes, at, target, a.tolerance)] if with_boxes else [])
                     + ([compare.plate_table(with_plates)] if with_plates else []))
    print(text, end="")
    for option, path, write in (("--md", a.md, lambda p: Path(p).write_text(text)),
                                ("--png", a.png,
                                 lambda p: compare.plot(p, with_boxes, with_plates))):
        if path:
            try:
                write(path)
            except OSError as e:
                raise plan.LabInputError(f"{option} {path}: cannot write it: {e.strerror}") from None
            print(f"soil-lab: wrote {path}")
    return 0


def _scm_out(path):
    """A LabInputError unless `soil-lab scm --out` names a file in an existing directory."""
    p = Path(path)
    if p.is_dir():
        raise plan.LabInputError(f"--out {path}: is a directory; expected the path of the SCM "
                                 f"soil file to write (FILE.toml)")
    parent = p.parent
    if not parent.exists():
        raise plan.LabInputError(f"--out {path}: its directory {parent} does not exist (create "
                                 f"it first)")
    if not parent.is_dir():
        raise plan.LabInputError(f"--out {path}: {parent} is not a directory")


def main(argv=None):
    ap = UsageParser(prog="soil-lab", description="The virtual soil lab: standard bulk tests on "
                     "a DEM soil, their fits, and an SCM soil file fitted to it "
                     "(docs/soil-lab.md).",
                     epilog="Exit status: 0 done; 1 a run or a fit failed; 2 bad command line, "
                            "unknown soil or test, or a test size the lab rejects.")
    add_version(ap, "soil-lab", start=__file__)
    sub = ap.add_subparsers(dest="command", required=True, parser_class=UsageParser)
    r = sub.add_parser("run", help="run the tests on a soil, then report")
    r.add_argument("soil", help="a shipped soil name (inputs/soils/NAME.in) or a soil file path")
    r.add_argument("--tests", default=",".join(plan.TEST_NAMES),
                   help=f"comma-separated, from {', '.join(plan.TEST_NAMES)} (default: all)")
    r.add_argument("--out", metavar="DIR", help="output directory (default: runs/soil_lab/SOIL)")
    r.add_argument("--np", type=int, default=1, help="MPI ranks per LIGGGHTS run (default 1)")
    r.add_argument("--bed-np", type=int, metavar="N",
                   help="MPI ranks that prepare a bed (default --np): part of the bed's recipe, "
                        "so a lab resumed on more ranks keeps its runs by preparing its beds as "
                        "before")
    r.add_argument("--preset", choices=plan.PRESETS, default="standard",
                   help="test sizes: standard (docs/soil-lab.md) or quick (CI smoke)")
    r.add_argument("--normal-stresses", metavar="S1,S2,S3",
                   help="shear box normal stresses [Pa] (default 5e3,1e4,2e4; quick 3e3,6e3,9e3)")
    r.add_argument("--plate-widths", metavar="B1,B2",
                   help="the two square plates' sides [m] (default 5 and 8 d_max; quick 2.5, 4)")
    r.add_argument("--plate-bin", type=float, metavar="SIDE",
                   help="the plate test's square bin side [m] (default 3 x the larger plate)")
    r.add_argument("--shear-travel", type=float, metavar="FRACTION",
                   help="shear box travel as a fraction of the box side (default 0.12; "
                        "at most 0.5)")
    r.add_argument("--plate-speed", type=float, metavar="M_S",
                   help="the plates' speed [m/s] (default 0.02; quick 0.04)")
    r.add_argument("--plate-depth", type=float, metavar="M",
                   help="the plates' sinkage at the end of the reload [m] (default 3 d_max; quick "
                        "1.5): loading to 2/3 of it, unloading by 1/6; a deeper plate gets a "
                        "deeper bed. Press to the wheel's sinkage so SCM is not extrapolated")
    r.add_argument("--plate-hold", type=float, metavar="S",
                   help="stress relaxation: the plates stand still S seconds at the end of the "
                        "loading (and at each --plate-hold-stages stop) before going on")
    r.add_argument("--plate-hold-stages", type=int, metavar="N",
                   help="hold N times, at N equally spaced depths of the loading, the last at its "
                        "end (default 1; 2 or more give a relaxed Bekker fit)")
    r.add_argument("--shear-speed", type=float, metavar="M_S",
                   help="the shear box's speed [m/s] (default 0.005; quick 0.02)")
    r.add_argument("--shear-replicates", type=int, metavar="N",
                   help="the shear boxes on N beds of the same recipe, each poured with its own "
                        f"seed (1..{plan.MAX_SHEAR_REPLICATES}; default 1): the report gives the "
                        "scatter of the peaks per stress and of c and phi between beds; N times "
                        "the boxes' cost (docs/soil-lab.md \"Replicate boxes\")")
    r.add_argument("--plate-replicates", type=int, metavar="N",
                   help="the two plates on N plate beds of the same recipe, each poured with its "
                        f"own seed (1..{plan.MAX_PLATE_REPLICATES}; default 1): the Bekker fit "
                        "takes every bed's plates, the report gives the scatter of the pressures "
                        "and of n, kc, kphi between beds, and the checks pair each bed's larger "
                        "plate with its own; N times the plates' cost (docs/soil-lab.md "
                        "\"Replicate plates\")")
    r.add_argument("--speed-check", action="store_true",
                   help="quasi-static check: also run the larger plate, the middle normal stress "
                        "(on every bed with --plate-replicates, --shear-replicates: a check "
                        "paired on the bed) and "
                        "the repose test (not in the quick preset) at half speed and report the "
                        "differences")
    r.add_argument("--dt-check", action="store_true",
                   help="time-step check: also run the larger plate and the middle normal "
                        "stress (every bed's box) at half the soil's time step, on the same bed "
                        "at the same speed, and report the differences (with "
                        "--plate-replicates, --shear-replicates: the check paired on the bed)")
    r.add_argument("--bed-var", action="append", metavar="NAME=VALUE",
                   help="an inputs/in.soilbin variable for every bed (e.g. compaction=plate)")
    r.add_argument("--bed-hold", type=float, default=bed_hold.DEFAULT_HOLD_S, metavar="S",
                   help="the bed-hold check: each bed is left alone S seconds under the soil's "
                        "test settings, and the lab stops if it settles by more than "
                        f"{100 * bed_hold.SETTLE_LIMIT:.0f} %% (default "
                        f"{bed_hold.DEFAULT_HOLD_S:g}; 0: no check)")
    r.add_argument("--archive", metavar="DIR",
                   help="keep each finished test run's files (CSV or dump, log, done.json) in "
                        "DIR/<run>/ (e.g. a folder committed to git) and restore them from there "
                        "first: a lab can span sessions whose output directory does not survive")
    r.add_argument("--park", action="store_true",
                   help="with --archive: keep each unfinished plate or shear run's newest "
                        "checkpoint (and its CSV) in DIR/<run>/parked/ too, xz-compressed, so that "
                        "the lab goes on from it on another machine; runs nothing, and may run "
                        "beside the lab that writes the checkpoints (docs/soil-lab.md, "
                        "\"Parking a stopped run\")")
    r.add_argument("--estimate", action="store_true",
                   help="print what the lab has left to run (steps per run, finished or parked "
                        "runs) and the wall time at the paces this lab measured; runs nothing but "
                        "the soil's size query")
    r.add_argument("--accept-change", action="append", metavar="FILE",
                   help="an edit of FILE (a file the soil file or the lab's decks include, e.g. "
                        "the base soil of a variant) changes no result: finished steps whose "
                        "records differ from this lab's inputs only by FILE are kept, their "
                        "records updated and annotated, instead of run again; needs --reason "
                        "(repeatable; docs/soil-lab.md \"Accepting an edit that changes no "
                        "result\")")
    r.add_argument("--reason", metavar="TEXT",
                   help="why the --accept-change edit changes no result (recorded)")
    r.add_argument("--checkpoints", type=int, default=runner.DEFAULT_CHECKPOINTS, metavar="N",
                   help="restart files written over each plate and shear run, from which a "
                        f"stopped lab goes on (default {runner.DEFAULT_CHECKPOINTS}; 0: none)")
    r.add_argument("--stall-timeout", type=float, default=mpi_launch.DEFAULT_STALL_MIN,
                   metavar="MIN",
                   help="a LIGGGHTS run whose log has not grown for MIN minutes is taken for hung "
                        "(an MPI rank stuck), killed, and the lab stops (exit 1) (default "
                        f"{mpi_launch.DEFAULT_STALL_MIN:g}; 0: no limit)")
    r.add_argument("--build-dir", metavar="D", help="build directory (default: <repo>/build)")
    r.add_argument("--quiet", action="store_true", help="no progress lines")
    rep = sub.add_parser("report", help="fit and plot a lab directory's results")
    rep.add_argument("dir")
    rep.add_argument("--quiet", action="store_true")
    s = sub.add_parser("scm", help="write an SCM soil file fitted to the DEM soil")
    s.add_argument("dir")
    s.add_argument("--out", required=True, metavar="FILE.toml")
    s.add_argument("--name", help="the SCM soil's name (default: '<DEM soil> (fitted from DEM)')")
    s.add_argument("--shear-from", metavar="LAB",
                   help="take the shear boxes (c, phi, K) from another lab of the same soil: its "
                        "directory, results.toml or a folder of archived boxes (for a lab that "
                        "pressed plates only)")
    s.add_argument("--shear-soil", metavar="NAME",
                   help="with --shear-from: its boxes ran as the soil NAME, which you vouch is "
                        "this soil's recipe under another name (a trial later shipped); recorded "
                        "in the file's [source]")
    s.add_argument("--rate-dependent", action="store_true",
                   help="write the file although the lab's plate speed check failed (the plates' "
                        "pressure still depends on their speed); its [source] says so")
    s.add_argument("--relaxed", action="store_true",
                   help="fit Bekker to the pressures at the ends of the plates' holds (a lab run "
                        "with --plate-hold and --plate-hold-stages >= 2) instead of the loading")
    c = sub.add_parser("compare", help="the shear boxes and plates of several labs side by side "
                                       "(trials)")
    c.add_argument("sources", nargs="+", metavar="LABEL=DIR",
                   help="a lab directory, a folder of finished runs (shear_s<stress>/, "
                        "plate_b<width>/) or one run's folder, with the label its rows get")
    c.add_argument("--at", default=",".join(f"{v:g}" for v in compare.DEFAULT_AT_MM),
                   metavar="MM,MM,...", help="shear displacements to read tau at [mm] (default "
                                             "%(default)s)")
    c.add_argument("--target", metavar="C_PA,PHI_DEG",
                   help="the soil's Mohr-Coulomb target (cohesion [Pa], friction angle [deg]): "
                        "each peak is also given against c + sigma tan(phi) at its box's stress")
    c.add_argument("--tolerance", type=float, default=compare.DEFAULT_TOLERANCE_DEG,
                   metavar="DEG", help="with --target: the fitted phi is judged within +-DEG of "
                                       "the target's (default %(default)g)")
    c.add_argument("--md", metavar="FILE", help="also write the tables to FILE (Markdown)")
    c.add_argument("--png", metavar="FILE", help="plot tau(j) of every source, a panel per "
                                                  "stress, and p(z), a panel per plate width")
    a = ap.parse_args(argv)
    try:
        if a.command == "run":
            return _run(a)
        if a.command == "report":
            return _report(a.dir, a.quiet)
        if a.command == "compare":
            return _compare(a)
        _scm_out(a.out)  # before the analysis
        r = analysis.analyse(a.dir)
        if a.shear_soil and not a.shear_from:
            raise plan.LabInputError("--shear-soil: only with --shear-from (the boxes it names)")
        shear = (analysis.shear_strength_from(a.shear_from, r.soil.get("name"), a.shear_soil)
                 if a.shear_from else None)
        try:
            path = analysis.write_scm(r, a.out, a.name, shear, a.relaxed, a.rate_dependent)
        except OSError as e:
            raise plan.LabInputError(f"--out {a.out}: cannot write it: {e.strerror}") from None
        print(f"soil-lab: wrote {path}")
        return 0
    except (plan.LabInputError, analysis.LabResultError) as e:
        print(f"soil-lab: error: {e}", file=sys.stderr)
        return EXIT_USAGE
    # SoilValueError: a fitted value outside what the SCM loader accepts (scm_file)
    except (runner.LabRunError, FitInputError, scm_file.SoilValueError) as e:
        print(f"soil-lab: error: {e}", file=sys.stderr)
        return 1
