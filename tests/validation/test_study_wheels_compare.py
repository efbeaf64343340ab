#!/usr/bin/python3
"""validation/study_wheels/compare.py (case 3's comparison) on synthetic results tables with known
values: the DEM-beside-SCM row (SCM's difference in % of DEM for F_T and sinkage, in kN for DP;
an unhealthy SCM point marked † and its code named under the table), the split of SCM − DEM into
traction force and motion resistance (ΔDP = ΔF_T − ΔR), a point under another setting (the sinkage
allowance's, the wheel friction's, the speed's and the time step's sections), the wheel pressed in at
each time step (release-phase contact force at fixed sinkages, from synthetic run files with a
known force-sinkage line), and a missing column (exit 2, one line naming the file).

    test_study_wheels_compare.py --work DIR
"""
import sys
from pathlib import Path

from script_test import checker, report, run_script, work_dir

SCRIPT = Path(__file__).resolve().parents[2] / "validation" / "study_wheels" / "compare.py"
COLUMNS = ("slip,target_slip,drawbar_pull_N,drawbar_pull_sem_N,driving_torque_Nm,"
           "driving_torque_sem_Nm,traction_force_N,traction_force_sem_N,sinkage_m,sinkage_sem_m,"
           "wall_s,particles,np,health,health_codes,run_file")


def table(path, terrain, rows):
    """rows: (soil, slip, DP [N], F_T [N], sinkage [m], health, codes); R_eff 0.5 m."""
    lines = ["# wheelsim-post curves --results (synthetic)", COLUMNS]
    for soil, s, dp, ft, z, health, codes in rows:
        lines.append(f"{s},{s},{dp},50,{ft * 0.5},20,{ft},40,{z},0.001,60,1000,2,{health},{codes},"
                     f"{terrain}/wheel1/{soil}/s{s:.3f}/run.h5")
    path.write_text("\n".join(lines) + "\n")
    return path


def release(run_h5, k_N_m, z_release_m, z_settle_m):
    """A run file with a release phase (0) in which the contact force is k z, sampled every
    0.1 mm down to z_release, then a settle phase (1) down to z_settle."""
    import h5py
    import numpy as np

    z = np.concatenate([np.arange(0.0, z_release_m + 1e-9, 1e-4),
                        np.linspace(z_release_m + 1e-3, z_settle_m, 20)])
    phase = np.where(z <= z_release_m + 1e-9, 0.0, 1.0)
    force = np.zeros((z.size, 3))
    force[:, 2] = k_N_m * z
    run_h5.parent.mkdir(parents=True, exist_ok=True)
    step = np.arange(z.size, dtype=np.int64)
    with h5py.File(run_h5, "w") as f:
        for name, value in (("sinkage", z), ("phase", phase), ("contact/force", force)):
            f[f"observables/{name}/step"] = step
            f[f"observables/{name}/time"] = 1e-3 * step
            f[f"observables/{name}/value"] = value


def main():
    work = work_dir()
    fails, check = checker()

    dem = table(work / "dem.csv", "dem", [("sand", 0.1, -2000.0, 4000.0, 0.25, "ok", ""),
                                          ("sand", 0.2, -1000.0, 5000.0, 0.3, "warning",
                                           "floor_clearance")])
    scm = table(work / "scm.csv", "scm", [("fit", 0.1, 2000.0, 7000.0, 0.4, "warning",
                                           "scm_rim_skid"),
                                          ("fit", 0.2, 2500.0, 7200.0, 0.42, "ok", "")])
    md = work / "out.md"
    r = run_script(SCRIPT, dem, "--scm", scm, "--md", md)
    check(r.returncode == 0, f"exit {r.returncode}, expected 0")
    text = md.read_text() if md.is_file() else ""
    rows = [l for l in text.splitlines() if l.startswith("| 0.")]
    # TE = DP/F_T (1 - s): DEM -2/4 x 0.9 = -0.45, SCM 2/7 x 0.9 = 0.257
    want = ["| 0.100 | 4.00 ± 0.04 | -2.00 ± 0.05 | 250.0 ± 1.0 | -0.45 | 7.00 (+75) † | "
            "2.00 (+4.00) † | 400.0 (+60) | 0.26 |",
            "| 0.200 | 5.00 ± 0.04 | -1.00 ± 0.05 | 300.0 ± 1.0 | -0.16 | 7.20 (+44) | "
            "2.50 (+3.50) | 420.0 (+40) | 0.28 | (health: warning)"]
    check(rows == want, f"comparison rows\n{rows}\nexpected\n{want}")
    check("† SCM point with health warnings: scm_rim_skid" in text, "the † footnote names the code")
    gap = [l for l in text.splitlines() if l.startswith("| wheel1 |")]
    # 0.1: dDP = 4.0, dF_T = 3.0, R DEM 6.0, SCM 5.0 -> dR = -1.0; 0.2: dDP 3.5, dF_T 2.2, R 6.0/4.7
    want = ["| wheel1 | 0.100 | fit † | +4.00 | +3.00 | -1.00 | 6.00 | 5.00 |",
            "| wheel1 | 0.200 | fit | +3.50 | +2.20 | -1.30 | 6.00 | 4.70 |"]
    check(gap == want, f"gap rows\n{gap}\nexpected\n{want}")
    # a point under another setting (here the sinkage allowance): its own section, row by row
    allowance = table(work / "results_allowance.csv", "dem",
                      [("sand", 0.2, -900.0, 5000.0, 0.33, "ok", "")])
    r = run_script(SCRIPT, dem, "--allowance", allowance, "--md", md)
    text = md.read_text() if r.returncode == 0 and md.is_file() else ""
    check("## The active domain's sinkage allowance: 0.3 m (sweep.toml) against 0.45 m" in text,
          f"the allowance section (exit {r.returncode})")
    # the difference is in % of the other setting's value: (-1.0 - -0.9) / 0.9, and says so
    check("| point | quantity | sweep.toml | 0.45 m allowance | (sweep.toml − 0.45 m allowance) "
          "/ \\|0.45 m allowance\\| |" in text, "the allowance table's header names its difference")
    check("| wheel1 s 0.2 | drawbar pull [kN] | -1 ± 0.05 | -0.9 ± 0.05 | -11.11 % |" in text,
          "the allowance row: DP -1.0 against -0.9 kN")
    r = run_script(SCRIPT, dem, "--wheel-mu", allowance, "--md", md)
    text = md.read_text() if r.returncode == 0 and md.is_file() else ""
    check("## The wheel-sand friction: 0.5 (sweep.toml) against the grains' 0.7869" in text,
          f"the wheel_mu section (exit {r.returncode})")
    r = run_script(SCRIPT, dem, "--speed", allowance, "--md", md)
    text = md.read_text() if r.returncode == 0 and md.is_file() else ""
    check("## The wheel's speed: 1.05 rad/s (sweep.toml) against 0.525 rad/s" in text,
          f"the speed section (exit {r.returncode})")
    r = run_script(SCRIPT, dem, "--dt", allowance, "--md", md)
    text = md.read_text() if r.returncode == 0 and md.is_file() else ""
    check("## The time step: 4.4e-5 s (sweep.toml) against 2.2e-5 s" in text
          and "| wheel1 s 0.2 | drawbar pull [kN] | -1 ± 0.05 | -0.9 ± 0.05 | -11.11 % |" in text,
          f"the time step's section and row (exit {r.returncode})")
    # the wheel pressed in at each step: the release phase of each run file (phase 0), contact
    # force k z; the table reads it at 20 / 50 / 100 / 140 / 180 mm, — below the release's end;
    # the quarter step's run file is not there
    release(work / "dem/wheel1/sand/s0.200/run.h5", 50e3, 0.19, 0.26)
    dt2 = table(work / "results_dt2.csv", "dt2", [("sand", 0.2, -600.0, 5000.0, 0.25, "ok", "")])
    release(work / "dt2/wheel1/sand/s0.200/run.h5", 80e3, 0.15, 0.22)
    dt4 = table(work / "results_dt4.csv", "dt4", [("sand", 0.2, -400.0, 5000.0, 0.22, "ok", "")])
    r = run_script(SCRIPT, dem, "--dt", dt2, "--dt4", dt4, "--md", md)
    text = md.read_text() if r.returncode == 0 and md.is_file() else ""
    check("## The time step: 4.4e-5 s (sweep.toml) against 1.1e-5 s" in text,
          f"the quarter step's section (exit {r.returncode})")
    press = [l for l in text.splitlines() if l.startswith("| wheel1 s 0.2 | ")
             and ("sweep.toml |" in l or "dt 2.2e-5 s |" in l or "dt 1.1e-5 s |" in l)
             and l.count("|") == 10]
    want = ["| wheel1 s 0.2 | sweep.toml | 1.00 | 2.50 | 5.00 | 7.00 | 9.00 | 190.0 | 260.0 |",
            "| wheel1 s 0.2 | dt 2.2e-5 s | 1.60 | 4.00 | 8.00 | 11.20 | — | 150.0 | 220.0 |"]
    check(press[:2] == want, f"press-in rows\n{press}\nexpected (the first two)\n{want}")
    check(len(press) == 3 and "unreadable" in press[2],
          f"a run file that is not there is named, not fatal ({press[2:]})")
    # the epsdt recipe: its point against the case's (the rolling model), its own step check
    # against its half-step point, and a press-in table of its own beside cdt's
    r = run_script(SCRIPT, dem, "--dt", dt2, "--epsdt", dt2, "--epsdt-dt", dt2, "--md", md)
    text = md.read_text() if r.returncode == 0 and md.is_file() else ""
    check("## The rolling model: cdt, μr 0.45 (sweep.toml) against epsdt" in text
          and "## The time step on epsdt: 4.4e-5 s (sweep_epsdt.toml) against 2.2e-5 s" in text,
          f"the epsdt sections (exit {r.returncode})")
    check("| wheel1 s 0.2 | drawbar pull [kN] | -0.6 ± 0.05 | -0.6 ± 0.05 | +0.00 % |" in text,
          "the epsdt step row: sweep_epsdt.toml's point against its half-step point")
    heads = [l for l in text.splitlines() if l.startswith("## The wheel pressed in")]
    check(heads == ["## The wheel pressed in, at each time step (cdt)",
                    "## The wheel pressed in, at each time step (epsdt)"],
          f"a press-in table per rolling model: {heads}")
    # the coarser grain at the case's step: against the case's point (grain alone) and against
    # the same grain at its own step (the step on that grain)
    r = run_script(SCRIPT, dem, "--goal-wide", dt2, "--goal-wide-dt", dt4, "--md", md)
    text = md.read_text() if r.returncode == 0 and md.is_file() else ""
    check("## Grain size at one time step: 16-40 mm (sweep.toml) against 21-52 mm" in text
          and "## The time step on 21-52 mm grains: 5.7e-5 s (sweep_goal_wide.toml)" in text,
          f"the grain-at-one-step sections (exit {r.returncode})")
    check("| wheel1 s 0.2 | drawbar pull [kN] | -0.6 ± 0.05 | -0.4 ± 0.05 | -50.00 % |" in text,
          "the step row on the coarser grain: sweep_goal_wide.toml's point against its 4.4e-5 s one")
    # with the point re-run on the re-poured bed: a bed-to-bed section, and the step read on one
    # bed (the re-poured point against the 4.4e-5 s one), not across the two pours
    r = run_script(SCRIPT, dem, "--goal-wide", dt2, "--goal-wide-dt", dt4,
                   "--goal-wide-repour", allowance, "--md", md)
    text = md.read_text() if r.returncode == 0 and md.is_file() else ""
    check("## Bed to bed: 21-52 mm at 5.7e-5 s (sweep_goal_wide.toml) against the same point" in text
          and "## The time step on 21-52 mm grains: 5.7e-5 s (sweep_goal_wide_repour.toml) "
          "against 4.4e-5 s (sweep_goal_wide_dt.toml: the same bed, grains and ranks)" in text
          and "sweep_goal_wide.toml) against 4.4e-5 s" not in text,
          f"the bed-to-bed section and the step on one bed (exit {r.returncode})")
    check("| wheel1 s 0.2 | drawbar pull [kN] | -0.6 ± 0.05 | -0.9 ± 0.05 | +33.33 % |" in text,
          "the bed-to-bed row: sweep_goal_wide.toml's point against the re-poured one")
    # a skid point: TE = (DP / F_T)(1 - s) needs the driving convention, the table's
    # slip_driving (-1 at skid slip -0.5: v = 2 omega R_eff), not its signed slip (-0.5)
    skid = work / "skid.csv"
    skid.write_text("# synthetic\n" + COLUMNS + ",slip_driving\n"
                    "-0.5,-0.5,1000,50,1000,20,2000,40,0.25,0.001,60,1000,2,ok,,"
                    "dem/wheel1/sand/s-0.500/run.h5,-1\n")
    r = run_script(SCRIPT, skid, "--md", md)
    text = md.read_text() if r.returncode == 0 and md.is_file() else ""
    row = [l for l in text.splitlines() if l.startswith("| -0.500 |")]
    check(len(row) == 1 and row[0].rstrip(" |").endswith("| 1"),
          f"a skid point's TE from slip_driving: 0.5 x 2 = 1 (got {row})")
    bad = work / "bad.csv"
    bad.write_text("slip,target_slip,drawbar_pull_N\n0.1,0.1,1.0\n")
    r = run_script(SCRIPT, dem, "--scm", bad, "--md", work / "x.md")
    check(r.returncode == 2 and str(bad) in r.stderr
          and len(r.stderr.strip().splitlines()) == 1, "a missing column: one line naming the file")
    return report(fails)


if __name__ == "__main__":
    sys.exit(main())
