#!/usr/bin/python3
"""validation/common/dem_vs_scm.py on synthetic results tables with known differences: the
table's rows (matched by target slip, in slip order), SCM − DEM in N, N m and mm, a slip in one
table only named and left out, and the errors (no slip in common, a missing column: exit 2 with
one line naming the file).

    test_dem_vs_scm.py --work DIR
"""
import sys
from pathlib import Path

from script_test import checker, report, run_script, work_dir

SCRIPT = Path(__file__).resolve().parents[2] / "validation" / "common" / "dem_vs_scm.py"
HEAD = ("# wheelsim-post curves --results (synthetic)\n"
        "slip,target_slip,drawbar_pull_N,drawbar_pull_sem_N,driving_torque_Nm,sinkage_m\n")


def table(path, rows):
    path.write_text(HEAD + "".join(f"{s},{s},{dp},{sem},{t},{z}\n" for s, dp, sem, t, z in rows))
    return path


def run(*args):
    return run_script(SCRIPT, *args)


def main():
    work = work_dir()
    fails, check = checker()

    dem = table(work / "dem.csv", [(0.5, -7.5, 0.2, 0.4, 0.047), (-1.0, -20.0, 0.3, -0.2, 0.056),
                                   (0.9, -5.5, 0.2, 0.55, 0.062)])
    scm = table(work / "scm.csv", [(0.5, 4.75, 0.02, 0.85, 0.0245), (-1.0, -33.0, 0.02, -1.25, 0.043),
                                   (0.23, 4.8, 0.02, 0.84, 0.0246)])
    md = work / "out.md"
    r = run(dem, scm, "--md", md)
    check(r.returncode == 0, f"exit {r.returncode}, expected 0")
    rows = [l for l in md.read_text().splitlines() if l.startswith("| ") and l[2:3] in "-0123456789"]
    want = ["| -1 | -20.00 ± 0.30 | -33.00 | -13.00 | -0.200 | -1.250 | -1.050 | 56.0 | 43.0 | -13.0 |",
            "| 0.5 | -7.50 ± 0.20 | 4.75 | +12.25 | 0.400 | 0.850 | +0.450 | 47.0 | 24.5 | -22.5 |"]
    check(rows == want, f"rows\n{rows}\nexpected\n{want}")
    check("slip 0.9 only in" in r.stderr and "slip 0.23 only in" in r.stderr,
          "the unmatched slips 0.9 (DEM) and 0.23 (SCM) are not named")
    r = run(dem, table(work / "other.csv", [(0.1, 1.0, 0.1, 0.1, 0.01)]), "--md", work / "x.md")
    check(r.returncode == 2 and "no target slip in common" in r.stderr, "no common slip: exit 2")
    bad = work / "bad.csv"
    bad.write_text("slip,target_slip,drawbar_pull_N\n0.5,0.5,1.0\n")
    r = run(dem, bad, "--md", work / "y.md")
    check(r.returncode == 2 and str(bad) in r.stderr and "missing" in r.stderr
          and len(r.stderr.strip().splitlines()) == 1, "a missing column: one line naming the file")
    return report(fails)


if __name__ == "__main__":
    sys.exit(main())
