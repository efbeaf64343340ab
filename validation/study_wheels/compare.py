#!/usr/bin/python3
"""Validation case 3 (README.md): the study wheels on DEM dry sand beside SCM, per wheel and slip:
traction force T/R_eff, drawbar pull, sinkage and tractive efficiency, and the active domain's
effect (the full-domain run of the same point), its run-to-run scatter (the same point on another
ranks' grid), the grain-size sensitivity, issue 12's goal point (21-52 mm grains) and the active
domain's sinkage allowance and the wheel-sand friction (the same point with each raised), the
wheel's speed and the time step (the same point at half of each; the step at a quarter too, and
the resistance the wheel meets while pressed in at each step); and where SCM and DEM part, split
into traction force and motion resistance.

    compare.py RESULTS.csv [--scm RESULTS_SCM.csv ...] [--full-domain RESULTS_FULL.csv]
               [--repeat RESULTS_REPEAT.csv] [--grain RESULTS_GRAIN.csv] [--goal RESULTS_GOAL.csv]
               [--goal-wide RESULTS_GOAL_WIDE.csv] [--goal-wide-dt RESULTS_GOAL_WIDE_DT.csv]
               [--goal-wide-repour RESULTS_GOAL_WIDE_REPOUR.csv]
               [--allowance RESULTS_ALLOWANCE.csv]
               [--wheel-mu RESULTS_WHEEL_MU.csv] [--speed RESULTS_SPEED.csv] [--dt RESULTS_DT.csv]
               [--dt4 RESULTS_DT4.csv] [--label CONFIG]
               [--md OUT.md] [--png OUT.png]

Inputs are tables of `wheelsim-post curves --results` (docs/postprocess.md); the wheel and the soil
of each row are the run file's folders (<out>/<wheel>/<soil>/s<slip>/run.h5, as wheel-sweep lays
them out). Tractive efficiency TE = DP v / (T omega) = (DP / F_T) (1 - s), s in the driving
convention (the table's slip_driving; its signed slip only where s >= 0). Exit 0, or 2 with one
line naming the bad file or column.
"""
import argparse
import functools
import math
import sys
from pathlib import Path

sys.path[:0] = [str(Path(__file__).resolve().parents[1] / "common"),
                str(Path(__file__).resolve().parents[2] / "postprocess")]
from results_table import read_rows  # noqa: E402

# the active domain's acceptance (issue 12 item 1): window means within 2 % of the full domain's
ACTIVE_TOLERANCE = 0.02
NEED = ("slip", "drawbar_pull_N", "drawbar_pull_sem_N", "driving_torque_Nm",
        "driving_torque_sem_Nm", "traction_force_N", "traction_force_sem_N", "sinkage_m",
        "sinkage_sem_m", "wall_s", "particles", "np", "target_slip", "health", "run_file")


def fail(msg):
    print(f"compare.py: error: {msg}", file=sys.stderr)
    sys.exit(2)


def num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


@functools.lru_cache(maxsize=None)
def read(path):
    """Rows of a results table, each with 'wheel' and 'soil' from its run file's folders (each
    table read once: several sections use the same one; the rows are not changed after)."""
    rows = read_rows(path, NEED, "compare.py")
    for i, r in enumerate(rows):
        parts = Path(r["run_file"]).parts
        if len(parts) < 4:
            fail(f"{path}: row {i + 1}: run_file '{r['run_file']}' is not <out>/<wheel>/<soil>/"
                 "s<slip>/run.h5")
        r["wheel"], r["soil"] = parts[-4], parts[-3]
        # TE = (DP / F_T) v / (omega R_eff) = (DP / F_T)(1 - s) holds in the driving convention
        # at every sign; the table's signed 'slip' is the skid convention below 0
        s = num(r["slip_driving"]) if r.get("slip_driving") else num(r["slip"])
        r["te"] = num(r["drawbar_pull_N"]) / num(r["traction_force_N"]) * (1.0 - s) \
            if num(r["traction_force_N"]) and (s >= 0 or r.get("slip_driving")) else math.nan
    return rows


def by_point(rows):
    return {(r["wheel"], r["soil"], round(num(r["target_slip"]), 4)): r for r in rows}


def pct(a, b):
    """(a - b) / |b| in %."""
    return (a - b) / abs(b) * 100.0 if b else math.nan


def fmt(v, digits=3):
    return "—" if not math.isfinite(v) else f"{v:.{digits}g}"


def comparison_table(dem, scm):
    """Markdown: per wheel and slip, DEM beside each SCM soil, SCM's difference in % of DEM
    (F_T, sinkage) or in kN (DP: it crosses zero, where a relative difference means nothing);
    an SCM point whose health is not ok is marked † and its codes listed under the table."""
    scm_soils = sorted({r["soil"] for r in scm})
    out, scm_codes = [], set()
    for wheel in sorted({r["wheel"] for r in dem}):
        out += [f"### {wheel}", ""]
        head = ["slip", "DEM F_T [kN]", "DEM DP [kN]", "DEM sinkage [mm]", "DEM TE"]
        for s in scm_soils:
            head += [f"{s}: F_T [kN] (Δ %)", "DP [kN] (Δ kN)", "sinkage [mm] (Δ %)", "TE"]
        out += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        scm_at = by_point(scm)
        for r in sorted((r for r in dem if r["wheel"] == wheel), key=lambda r: num(r["slip"])):
            ft, dp, z = (num(r["traction_force_N"]), num(r["drawbar_pull_N"]),
                         num(r["sinkage_m"]))
            cells = [f"{num(r['slip']):.3f}",
                     f"{ft / 1e3:.2f} ± {num(r['traction_force_sem_N']) / 1e3:.2f}",
                     f"{dp / 1e3:.2f} ± {num(r['drawbar_pull_sem_N']) / 1e3:.2f}",
                     f"{z * 1e3:.1f} ± {num(r['sinkage_sem_m']) * 1e3:.1f}", fmt(r["te"], 2)]
            for s in scm_soils:
                m = scm_at.get((wheel, s, round(num(r["target_slip"]), 4)))
                if m is None:
                    cells += ["—"] * 4
                    continue
                mft, mdp, mz = (num(m["traction_force_N"]), num(m["drawbar_pull_N"]),
                                num(m["sinkage_m"]))
                mark = ""
                if m["health"] != "ok":
                    mark = " †"
                    scm_codes.update(c for c in m.get("health_codes", "").split(";") if c)
                cells += [f"{mft / 1e3:.2f} ({pct(mft, ft):+.0f}){mark}",
                          f"{mdp / 1e3:.2f} ({(mdp - dp) / 1e3:+.2f}){mark}",
                          f"{mz * 1e3:.1f} ({pct(mz, z):+.0f})", fmt(m["te"], 2)]
            flag = "" if r["health"] == "ok" else f" (health: {r['health']})"
            out.append("| " + " | ".join(cells) + " |" + flag)
        out.append("")
    if scm_codes:
        out += [f"† SCM point with health warnings: {', '.join(sorted(scm_codes))} "
                "(docs/run-health.md; `scm_rim_skid`: a lugged wheel below s = lug height / "
                "R_eff, where SCM's pull and torque are the model's artefact).", ""]
    return out


def gap_table(dem, scm):
    """Markdown: SCM − DEM per wheel, slip and SCM soil, split into its two parts: drawbar pull
    DP = F_T − R, with F_T = T/R_eff the traction force and R = F_T − DP the motion resistance,
    so ΔDP = ΔF_T − ΔR. SCM points whose health is not ok are marked †."""
    scm_at = by_point(scm)
    out = ["## Where SCM and DEM part: traction and motion resistance", "",
           "SCM − DEM in kN. DP = F_T − R with F_T = T/R_eff the traction force and R = F_T − DP "
           "the motion resistance, so ΔDP = ΔF_T − ΔR: a gap that is mostly ΔF_T is the soil's "
           "shear (traction), one that is mostly −ΔR its bearing and bulldozing (resistance).", "",
           "| wheel | slip | SCM soil | ΔDP | ΔF_T (traction) | ΔR (resistance) | DEM R | SCM R |",
           "|---|---|---|---|---|---|---|---|"]
    scm_soils = sorted({m["soil"] for m in scm})
    for r in sorted(dem, key=lambda r: (r["wheel"], num(r["slip"]))):
        ft, dp = num(r["traction_force_N"]), num(r["drawbar_pull_N"])
        for soil in scm_soils:
            m = scm_at.get((r["wheel"], soil, round(num(r["target_slip"]), 4)))
            if m is None:
                continue
            mft, mdp = num(m["traction_force_N"]), num(m["drawbar_pull_N"])
            mark = "" if m["health"] == "ok" else " †"
            out.append(f"| {r['wheel']} | {num(r['slip']):.3f} | {soil}{mark} | "
                       f"{(mdp - dp) / 1e3:+.2f} | {(mft - ft) / 1e3:+.2f} | "
                       f"{((mft - mdp) - (ft - dp)) / 1e3:+.2f} | {(ft - dp) / 1e3:.2f} | "
                       f"{(mft - mdp) / 1e3:.2f} |")
    return out + [""]


def sweep_name(results):
    """The sweep config a run.sh results table comes from: results_<part>.csv -> sweep_<part>.toml."""
    return Path(results).name.replace("results_", "sweep_").replace(".csv", ".toml")


def point_table(dem, other, other_name, tolerance=None, ref="sweep.toml"):
    """Markdown: each run of `other` against the DEM half's run of the same wheel and slip (a
    sensitivity: another soil file or other deck variables), with the wall-time ratio. With a
    tolerance (a fraction) each difference gets a verdict, also returned."""
    dem_at = {(r["wheel"], round(num(r["target_slip"]), 4)): r for r in dem}
    verdict_head = f" within {tolerance:.0%} |" if tolerance is not None else ""
    # the difference is the reference's (the case, or the active domain) against the other run,
    # in % of the other run's value: said in the header, since it reads the other way round from
    # a sensitivity's "what the change did"
    out = [f"| point | quantity | {ref} | {other_name} | ({ref} − {other_name}) / "
           f"\\|{other_name}\\| |{verdict_head}",
           "|---|---|---|---|---|" + ("---|" if tolerance is not None else "")]
    verdicts = []
    for f in other:
        key = (f["wheel"], round(num(f["target_slip"]), 4))
        a = dem_at.get(key)
        if a is None:
            out.append(f"| {key[0]} s {key[1]} | no run of this point in {ref} | | | |")
            continue
        for col, sem, label, scale, unit in (
                ("drawbar_pull_N", "drawbar_pull_sem_N", "drawbar pull", 1e-3, "kN"),
                ("driving_torque_Nm", "driving_torque_sem_Nm", "torque", 1e-3, "kN m"),
                ("sinkage_m", "sinkage_sem_m", "sinkage", 1e3, "mm")):
            va, vf = num(a[col]), num(f[col])
            d = pct(va, vf)
            cells = (f"| {key[0]} s {key[1]} | {label} [{unit}] | {va * scale:.4g} ± "
                     f"{num(a[sem]) * scale:.2g} | {vf * scale:.4g} ± {num(f[sem]) * scale:.2g} | "
                     f"{d:+.2f} % |")
            if tolerance is not None:
                ok = abs(d) <= tolerance * 100.0
                verdicts.append(ok)
                cells += f" {'yes' if ok else 'NO'} |"
            out.append(cells)
        wa, wf = num(a["wall_s"]), num(f["wall_s"])
        out.append(f"| {key[0]} s {key[1]} | wall time [min], particles | {wa / 60:.1f}, "
                   f"{a['particles']} | {wf / 60:.1f}, {f['particles']} | ratio {wf / wa:.2f} |"
                   + (" |" if tolerance is not None else ""))
    return out, verdicts


# the release phase (the run file's phase "release"): the wheel lowered at a fixed speed until it
# carries its load; the press-in table reads the vertical contact force at these sinkages
PRESS_IN_SINKAGES_M = (0.02, 0.05, 0.10, 0.14, 0.18)
PRESS_IN_BAND_M = 0.002  # samples within +- this of each sinkage are averaged


def release_curve(run_h5):
    """(sinkage [m], vertical contact force [N]) of a run file's release phase, and the sinkage
    at the end of its release and of its settle phase (a PostError if the file cannot give them)."""
    import numpy as np
    from wheelsim_post.errors import PostError
    from wheelsim_post.runfile import RunFile
    from wheelsim_post.steady import PHASES

    code = {name: c for c, name in PHASES.items()}
    with RunFile(run_h5) as f:
        z = f.observable("sinkage").value
        phase = np.rint(f.observable("phase").value)
        fz = f.observable("contact/force").value[:, 2]
    if not len(z) == len(phase) == len(fz):
        raise PostError(f"{run_h5}: sinkage, phase and contact/force have different lengths")
    rel = np.flatnonzero(phase == code["release"])
    settle = np.flatnonzero(phase == code["settle"])
    if rel.size == 0:
        raise PostError(f"{run_h5}: no release phase")
    return z[rel], fz[rel], z[rel[-1]], (z[settle[-1]] if settle.size else math.nan)


def press_in_table(steps, model="cdt"):
    """Markdown: the resistance the wheel meets while it is pressed in (its release phase, at the
    same fixed speed in every run), at a few sinkages, for the same point at each time step:
    where a difference in the time step first shows. steps: (results table, its name); the run
    files are found from each table's run_file column, relative to the table. model: the soil's
    rolling model, for the heading."""
    import numpy as np

    heads = " | ".join(f"{z * 1e3:.0f} mm" for z in PRESS_IN_SINKAGES_M)
    out = [f"## The wheel pressed in, at each time step ({model})", "",
           "The release phase: the wheel lowered at the rig's fixed release speed until it carries "
           "its load. Vertical contact force [kN] at each sinkage (mean of the samples within "
           f"±{PRESS_IN_BAND_M * 1e3:.0f} mm; — where the release ended above it), and the sinkage "
           "at the end of the release and of the settle phase.", "",
           f"| point | run | {heads} | end of release [mm] | end of settle [mm] |",
           "|---|---|" + "---|" * len(PRESS_IN_SINKAGES_M) + "---|---|"]
    from wheelsim_post.errors import PostError

    ref = {(r["wheel"], round(num(r["target_slip"]), 4)) for r in read(steps[1][0])}
    for path, name in steps:
        for r in read(path):
            key = (r["wheel"], round(num(r["target_slip"]), 4))
            if key not in ref:
                continue
            run_h5 = Path(path).resolve().parent / r["run_file"]
            try:
                z, fz, z_release, z_settle = release_curve(run_h5)
            except PostError as e:
                out.append(f"| {key[0]} s {key[1]} | {name} | {r['run_file']} unreadable ({e}) |"
                           + " |" * (len(PRESS_IN_SINKAGES_M) + 1))
                continue
            cells = []
            for level in PRESS_IN_SINKAGES_M:
                near = np.abs(z - level) <= PRESS_IN_BAND_M
                cells.append(f"{fz[near].mean() * 1e-3:.2f}" if near.any() else "—")
            out.append(f"| {key[0]} s {key[1]} | {name} | " + " | ".join(cells)
                       + f" | {z_release * 1e3:.1f} | {z_settle * 1e3:.1f} |")
    return out


def plot(png, dem, scm):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    panels = (("traction_force_N", "traction force T/R$_{eff}$ [kN]", 1e-3),
              ("drawbar_pull_N", "drawbar pull DP [kN]", 1e-3),
              ("sinkage_m", "sinkage [mm]", 1e3),
              ("te", "tractive efficiency", 1.0))
    wheels = sorted({r["wheel"] for r in dem})
    fig, axes = plt.subplots(len(wheels), len(panels), figsize=(3.6 * len(panels),
                                                                 3.2 * len(wheels)),
                             squeeze=False)
    series = [("DEM " + s, [r for r in dem if r["soil"] == s], "o-")
              for s in sorted({r["soil"] for r in dem})]
    series += [("SCM " + s, [r for r in scm if r["soil"] == s], "s--")
               for s in sorted({r["soil"] for r in scm})]
    for row, wheel in zip(axes, wheels):
        for ax, (col, label, scale) in zip(row, panels):
            for name, rows, style in series:
                rows = sorted((r for r in rows if r["wheel"] == wheel),
                              key=lambda r: num(r["slip"]))
                ax.plot([num(r["slip"]) for r in rows],
                        [num(r[col]) * scale for r in rows], style, ms=4, lw=1, label=name)
            ax.set_xlabel("slip")
            ax.set_ylabel(label)
            ax.set_title(wheel, fontsize=9)
            ax.grid(True, lw=0.3)
    axes[0][0].legend(fontsize=7)
    fig.suptitle("study wheels, 13.2 kN, 1.05 rad/s: DEM dry sand (16-40 mm) and SCM", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dem", help="the DEM half's results.csv")
    ap.add_argument("--scm", action="append", default=[],
                    help="an SCM results table (repeatable: e.g. the default and the lug-tip shear)")
    ap.add_argument("--full-domain", help="the full-domain runs' results table")
    ap.add_argument("--grain", help="the grain-size sensitivity's results table")
    ap.add_argument("--goal", help="issue 12's goal point's results table (21-52 mm grains)")
    ap.add_argument("--goal-wide", help="the goal point with sweep.toml's 0.3 m sinkage allowance "
                    "(sweep_goal_wide.toml): the like-for-like coarser grain")
    ap.add_argument("--goal-wide-dt", help="--goal-wide's point at sweep.toml's time step "
                    "(sweep_goal_wide_dt.toml): the grain size at one step")
    ap.add_argument("--goal-wide-repour", help="--goal-wide's point again on its recipe poured "
                    "again (sweep_goal_wide_repour.toml): bed-to-bed scatter, and the step on "
                    "one bed with --goal-wide-dt")
    ap.add_argument("--allowance", help="a point with the active domain's sinkage allowance "
                    "raised from sweep.toml's 0.3 m (sweep_allowance.toml)")
    ap.add_argument("--wheel-mu", help="a point with the wheel-sand friction raised from 0.5 to "
                    "the grains' (sweep_wheel_mu.toml)")
    ap.add_argument("--speed", help="a point at half the wheel speed over the same travel "
                    "(sweep_speed.toml)")
    ap.add_argument("--dt", help="a point at half the time step (sweep_dt.toml)")
    ap.add_argument("--dt4", help="a point at a quarter of the time step (sweep_dt4.toml)")
    ap.add_argument("--epsdt", help="a point on the epsdt recipe of the sand (sweep_epsdt.toml)")
    ap.add_argument("--epsdt-dt", help="the epsdt point at half the time step "
                    "(sweep_epsdt_dt.toml)")
    ap.add_argument("--wide", help="the active domain's point with a larger distance (its sinkage "
                    "allowance raised), compared with --full-domain's")
    ap.add_argument("--repeat", help="the repeat of the active domain's point on another ranks' "
                    "grid (the run-to-run scatter)")
    ap.add_argument("--label", default="sweep.toml",
                    help="the sweep config the positional table comes from, for the text (default "
                    "sweep.toml; the active-domain check: sweep_active_domain.toml)")
    ap.add_argument("--md", help="write the comparison as Markdown")
    ap.add_argument("--png", help="write the comparison plot")
    ap.add_argument("--window", default="2-6",
                    help="the tables' window in test-phase seconds, for the text (default 2-6)")
    a = ap.parse_args()
    dem = read(a.dem)
    scm = [row for path in a.scm for row in read(path)]
    lines = ["# Validation case 3: comparison (written by compare.py)", "",
             f"DEM: mean ± standard error over test-phase seconds {a.window}; SCM: the same window; Δ: "
             "SCM − DEM, in % of DEM for F_T and sinkage, in kN for DP (DEM's DP crosses zero, where a "
             "difference in % means nothing). TE = (DP / F_T)(1 - s).", ""]
    lines += comparison_table(dem, scm)
    if scm:
        lines += gap_table(dem, scm)
    verdicts = []
    if a.full_domain:
        lines += ["## The active domain against the full domain", "",
                  f"The difference is {a.label}'s (active domain) against the full domain's.", ""]
        t, verdicts = point_table(dem, read(a.full_domain), "full domain", ACTIVE_TOLERANCE,
                                  ref=a.label)
        lines += t + [""]
    wide_verdicts = []
    if a.wide and a.full_domain:
        wide = sweep_name(a.wide)
        lines += ["## A wider active domain against the full domain", "",
                  f"{wide}'s point (the active domain with its sinkage allowance raised) against "
                  "the full domain's.", ""]
        t, wide_verdicts = point_table(read(a.wide), read(a.full_domain), "full domain",
                                       ACTIVE_TOLERANCE, ref=wide)
        lines += t + [""]
    if a.repeat:
        lines += ["## Run-to-run scatter: the same point, ranks cut along the bin", "",
                  f"{a.label}'s point (ranks across the width) against "
                  f"{sweep_name(a.repeat)}'s "
                  "(the same inputs, procs_x 2): another trajectory of the same experiment.", ""]
        lines += point_table(dem, read(a.repeat), "repeat (procs_x 2)", ref=a.label)[0] + [""]
    # the same point under another setting: (table, heading after the case's label, column name)
    for table, heading, name in (
            (a.grain, "Grain size: 16-40 mm ({}) against 12-30 mm (sweep_grain.toml)",
             "12-30 mm grains"),
            (a.goal_wide, "Grain size, like for like: 16-40 mm ({}) against 21-52 mm "
             "(sweep_goal_wide.toml: the same 0.3 m sinkage allowance, time step x 1.3)",
             "21-52 mm grains"),
            (a.goal_wide_dt, "Grain size at one time step: 16-40 mm ({}) against 21-52 mm "
             "(sweep_goal_wide_dt.toml: the same 0.3 m sinkage allowance and 4.4e-5 s step)",
             "21-52 mm grains, dt 4.4e-5 s"),
            (a.goal, "Issue 12's goal: 16-40 mm ({}) against 21-52 mm (sweep_goal.toml, time step "
             "x 1.3, the active domain at its default distance: not like for like since "
             "sweep.toml sets the 0.3 m allowance)", "21-52 mm grains"),
            (a.allowance, "The active domain's sinkage allowance: 0.3 m ({}) against 0.45 m "
             "(sweep_allowance.toml: same bed, grains and ranks)", "0.45 m allowance"),
            (a.wheel_mu, "The wheel-sand friction: 0.5 ({}) against the grains' 0.7869 "
             "(sweep_wheel_mu.toml: same bed, grains and ranks)", "wheel_mu 0.7869"),
            (a.speed, "The wheel's speed: 1.05 rad/s ({}) against 0.525 rad/s (sweep_speed.toml: "
             "same bed, grains, ranks and travel; window 4-12 s)", "0.525 rad/s"),
            (a.dt, "The time step: 4.4e-5 s ({}) against 2.2e-5 s (sweep_dt.toml: same bed, "
             "grains and ranks)", "dt 2.2e-5 s"),
            (a.dt4, "The time step: 4.4e-5 s ({}) against 1.1e-5 s (sweep_dt4.toml: same bed, "
             "grains and ranks)", "dt 1.1e-5 s"),
            (a.epsdt, "The rolling model: cdt, μr 0.45 ({}) against epsdt, μr 0.03 poured at 0.1 "
             "(sweep_epsdt.toml: the same grains and bulk density, a bed of its own)",
             "epsdt")):
        if table:
            lines += ["## " + heading.format(a.label), ""]
            lines += point_table(dem, read(table), name, ref=a.label)[0] + [""]
    # two points of the same side study against each other: (reference table, its config, the
    # other table, heading after "## ", the other's column name)
    one_bed = ((a.goal_wide_repour, "sweep_goal_wide_repour.toml", "the same bed, grains and ranks")
               if a.goal_wide_repour else  # the step on the coarser grain: on one bed when it can
               (a.goal_wide, "sweep_goal_wide.toml", "the same bed recipe, grains and ranks; its "
                "bed poured again on a later build, 2 spheres fewer"))
    for ref_table, ref_name, table, heading, name in (
            (a.goal_wide, "sweep_goal_wide.toml", a.goal_wide_repour,
             "Bed to bed: 21-52 mm at 5.7e-5 s (sweep_goal_wide.toml) against the same point on "
             "the recipe poured again (sweep_goal_wide_repour.toml)", "poured again"),
            (one_bed[0], one_bed[1], a.goal_wide_dt,
             f"The time step on 21-52 mm grains: 5.7e-5 s ({one_bed[1]}) against 4.4e-5 s "
             f"(sweep_goal_wide_dt.toml: {one_bed[2]})", "dt 4.4e-5 s"),
            (a.epsdt, "sweep_epsdt.toml", a.epsdt_dt,
             "The time step on epsdt: 4.4e-5 s (sweep_epsdt.toml) against 2.2e-5 s "
             "(sweep_epsdt_dt.toml: same bed, grains and ranks)", "epsdt, dt 2.2e-5 s")):
        if ref_table and table:
            lines += ["## " + heading, ""]
            lines += point_table(read(ref_table), read(table), name, ref=ref_name)[0] + [""]
    for steps, model in (([(a.dem, a.label), (a.dt, "dt 2.2e-5 s"), (a.dt4, "dt 1.1e-5 s")],
                          "cdt"),
                         ([(a.epsdt, "sweep_epsdt.toml"), (a.epsdt_dt, "epsdt, dt 2.2e-5 s")],
                          "epsdt")):
        steps = [(path, name) for path, name in steps if path]
        if len(steps) > 1:
            lines += press_in_table(steps, model) + [""]
    text = "\n".join(lines) + "\n"
    if a.md:
        Path(a.md).write_text(text, encoding="utf-8")
    else:
        print(text)
    if a.png:
        plot(a.png, dem, scm)
    for name, v in (("active domain", verdicts), ("wider active domain", wide_verdicts)):
        if v:
            print(f"compare.py: {name} within {ACTIVE_TOLERANCE:.0%} of the full domain: "
                  f"{sum(v)} of {len(v)} quantities")
    return 0


if __name__ == "__main__":
    sys.exit(main())
