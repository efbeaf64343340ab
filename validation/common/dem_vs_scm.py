#!/usr/bin/python3
"""DEM against SCM on the same soil: a Markdown table of one case's two halves, matched by target
slip (both results tables from `wheelsim-post curves --results`, docs/postprocess.md).

    dem_vs_scm.py DEM.csv SCM.csv --md OUT.md [--title TEXT]

Per slip: drawbar pull, driving torque and sinkage of both halves and SCM − DEM in their units
(not in %: torque and pull cross zero along a slip sweep). A DEM slip without an SCM row (or the
reverse) is named on stderr and left out. Exit 0, or 2 with one line naming the bad file or
column.
"""
import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_table import read_rows  # noqa: E402

NEED = ("target_slip", "drawbar_pull_N", "drawbar_pull_sem_N", "driving_torque_Nm", "sinkage_m")


def by_slip(path):
    rows = {}
    for r in read_rows(path, NEED, "dem_vs_scm.py"):
        try:
            rows[round(float(r["target_slip"]), 6)] = {k: float(r[k]) for k in NEED}
        except ValueError:
            print(f"dem_vs_scm.py: error: {path}: a value of {NEED} is not a number in the row "
                  f"of target slip {r['target_slip']!r}", file=sys.stderr)
            raise SystemExit(2)
    return rows


def table(dem, scm, slips):
    lines = ["| slip | DP DEM [N] | DP SCM [N] | Δ DP [N] | T DEM [N m] | T SCM [N m] | Δ T [N m] | "
             "sinkage DEM [mm] | sinkage SCM [mm] | Δ sinkage [mm] |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for s in slips:
        d, m = dem[s], scm[s]
        lines.append(
            f"| {s:g} | {d['drawbar_pull_N']:.2f} ± {d['drawbar_pull_sem_N']:.2f} | "
            f"{m['drawbar_pull_N']:.2f} | {m['drawbar_pull_N'] - d['drawbar_pull_N']:+.2f} | "
            f"{d['driving_torque_Nm']:.3f} | {m['driving_torque_Nm']:.3f} | "
            f"{m['driving_torque_Nm'] - d['driving_torque_Nm']:+.3f} | "
            f"{1000 * d['sinkage_m']:.1f} | {1000 * m['sinkage_m']:.1f} | "
            f"{1000 * (m['sinkage_m'] - d['sinkage_m']):+.1f} |")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dem", help="the DEM half's results table")
    ap.add_argument("scm", help="the SCM half's results table")
    ap.add_argument("--md", required=True, help="output Markdown file")
    ap.add_argument("--title", default="DEM against SCM on the same soil (SCM: the soil lab's fit "
                                       "to the DEM soil; Δ = SCM − DEM)")
    a = ap.parse_args()
    dem, scm = by_slip(a.dem), by_slip(a.scm)
    for s in sorted(set(dem) ^ set(scm)):
        print(f"dem_vs_scm.py: slip {s:g} only in {a.dem if s in dem else a.scm}: left out",
              file=sys.stderr)
    common = sorted(set(dem) & set(scm))
    if not common:
        print(f"dem_vs_scm.py: error: {a.dem} and {a.scm} have no target slip in common",
              file=sys.stderr)
        raise SystemExit(2)
    Path(a.md).write_text("\n".join([a.title, ""] + table(dem, scm, common)) + "\n",
                          encoding="utf-8")
    print(f"wrote {a.md}")


if __name__ == "__main__":
    main()
