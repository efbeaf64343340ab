#!/usr/bin/python3
"""The prediction plot of validation case 2 (blind; README.md): drawbar pull, driving torque and
sinkage against the signed slip, from one or more results tables (wheelsim-post curves --results).
No measured values: the case is a blind prediction.

    plot.py --png prediction.png [--title TEXT] RESULTS.csv | LABEL=RESULTS.csv ...

Error bars are the tables' standard errors (batch means). Points whose run health is not `ok` are
drawn hollow. Exit 0, or 2 with one line naming the bad file or column.
"""
import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "common"))
from results_table import read_rows  # noqa: E402

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PANELS = (  # (column, its SEM column, axis label, scale)
    ("drawbar_pull_N", "drawbar_pull_sem_N", "drawbar pull DP [N]", 1.0),
    ("driving_torque_Nm", "driving_torque_sem_Nm", "driving torque T [N m]", 1.0),
    ("sinkage_m", "sinkage_sem_m", "sinkage [mm]", 1000.0),
)


def read(path):
    need = ["slip", "slip_sem", "health"] + [c for p in PANELS for c in p[:2]]
    return read_rows(path, need, "plot.py")


def num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tables", nargs="+", help="RESULTS.csv or LABEL=RESULTS.csv")
    ap.add_argument("--png", required=True, help="output PNG")
    ap.add_argument("--title", default="blind prediction: smooth wheel r 58 mm, w 50 mm, "
                                        "loose sand 1330 kg/m$^3$, W 24 N")
    a = ap.parse_args()
    series = []
    for t in a.tables:
        label, _, path = t.rpartition("=")
        series.append((label or None, read(path)))
    fig, axes = plt.subplots(1, len(PANELS), figsize=(4.2 * len(PANELS), 3.8))
    for label, rows in series:
        rows = sorted((r for r in rows if math.isfinite(num(r["slip"]))),
                      key=lambda r: num(r["slip"]))
        for ax, (col, sem, ylabel, scale) in zip(axes, PANELS):
            x = [num(r["slip"]) for r in rows]
            y = [num(r[col]) * scale for r in rows]
            line, = ax.plot(x, y, "-", lw=1, label=label)
            for r, xi, yi in zip(rows, x, y):
                ok = r["health"] == "ok"
                ax.errorbar([xi], [yi], xerr=[num(r["slip_sem"])], yerr=[num(r[sem]) * scale],
                            fmt="o", color=line.get_color(), mfc=line.get_color() if ok else "none",
                            ms=5, capsize=2)
            ax.set_xlabel("slip (signed: driving > 0, skid < 0, -1 locked)")
            ax.set_ylabel(ylabel)
            ax.axvline(0.0, color="0.8", lw=0.8, zorder=0)
            ax.grid(True, lw=0.3)
    if any(label for label, _ in series):
        axes[0].legend(fontsize=8)
    fig.suptitle(a.title + " (no measurement shown: blind)", fontsize=9)
    fig.tight_layout()
    fig.savefig(a.png, dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
