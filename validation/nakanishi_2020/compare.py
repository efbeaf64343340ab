#!/usr/bin/python3
"""Validation case 1 (Nakanishi et al. 2020): our results.csv against the published curves.

    compare.py RESULTS.csv REFERENCE.csv --r-eff 0.11 [--scm RESULTS_SCM.csv]
               [--png comparison.png] [--md comparison.md] [--label TEXT]
               [--also LABEL=RESULTS.csv ...]

Net traction = drawbar pull; gross traction = driving torque / R_eff; motion resistance = net -
gross. Each of our rows is matched to the reference row of the same slip (within 0.5 percentage
points). The goal (issue 11): net within 25 % or 1 N (the larger) of Nakanishi at every slip from
13 % to 78 %, gross within 20 %. Prints one line per slip and the verdict; exit 0 whatever the
verdict (it is a report, not a test), 2 on bad input. --scm: also the SCM half (the same rig on
the SCM soil fitted to the DEM soil, matched by target slip): a table of DEM against SCM and SCM's
curves in the plot. --label names our curve in the plot's legend (default "wheelsim"); --also
adds another of our results tables to the plot only (net and gross, grey), e.g. the same case with
another contact model.
"""
import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "common"))
from results_table import read_rows  # noqa: E402


def read_csv(path):
    return read_rows(path, prog="compare.py")


def number(row, key, path):
    try:
        return float(row[key])
    except (KeyError, ValueError):
        sys.exit(f"compare.py: {path}: column '{key}' missing or not a number in row {row}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results")
    ap.add_argument("reference")
    ap.add_argument("--r-eff", type=float, required=True, help="R_eff [m] for the gross traction")
    ap.add_argument("--scm", help="the SCM half's results table (run.sh --scm)")
    ap.add_argument("--png")
    ap.add_argument("--md")
    ap.add_argument("--label", default="wheelsim", help="our curve's name in the legend")
    ap.add_argument("--also", action="append", default=[], metavar="LABEL=CSV",
                    help="another results table of ours, plotted in grey (repeatable)")
    a = ap.parse_args()
    also = []
    for item in a.also:
        label, sep, path = item.partition("=")
        if not sep or not label or not path:
            ap.error(f"--also expects LABEL=RESULTS.csv, got '{item}'")
        rows = read_csv(path)
        also.append((label, sorted(
            (100.0 * number(r, "slip", path), number(r, "drawbar_pull_N", path),
             number(r, "driving_torque_Nm", path) / a.r_eff) for r in rows)))
    if not a.r_eff > 0:
        ap.error(f"--r-eff must be > 0 m, got {a.r_eff}")
    ours = read_csv(a.results)
    ref = read_csv(a.reference)
    if not ours:
        sys.exit(f"compare.py: {a.results} has no rows")
    table = []
    for r in ours:
        s = 100.0 * number(r, "slip", a.results)
        match = [q for q in ref if abs(number(q, "slip_percent", a.reference) - s) < 0.5]
        if not match:
            print(f"slip {s:.2f} %: no reference row within 0.5 points", file=sys.stderr)
            continue
        q = match[0]
        net = number(r, "drawbar_pull_N", a.results)
        net_sem = number(r, "drawbar_pull_sem_N", a.results)
        gross = number(r, "driving_torque_Nm", a.results) / a.r_eff
        gross_sem = float(r.get("driving_torque_sem_Nm") or "nan") / a.r_eff
        ref_net = number(q, "net_N", a.reference)
        ref_gross = number(q, "gross_N", a.reference)
        yade = number(q, "yade_net_N", a.reference)
        net_tol = max(0.25 * abs(ref_net), 1.0)
        in_goal_range = 13.0 <= s <= 78.0
        table.append(dict(
            slip=s, net=net, net_sem=net_sem, gross=gross, gross_sem=gross_sem,
            res=net - gross, ref_net=ref_net, ref_gross=ref_gross,
            ref_res=number(q, "resistance_N", a.reference), yade=yade,
            net_err=net - ref_net, net_ok=abs(net - ref_net) <= net_tol,
            gross_err_pc=100.0 * (gross - ref_gross) / ref_gross,
            gross_ok=abs(gross - ref_gross) <= 0.2 * abs(ref_gross),
            in_goal=in_goal_range,
            sinkage=float(r.get("sinkage_m") or "nan"),
            target=round(number(r, "target_slip", a.results), 4)))
    table.sort(key=lambda t: t["slip"])
    lines = ["| slip [%] | net ours [N] | Nakanishi | Yade | net error [N] | gross ours [N] "
             "| Nakanishi | gross error [%] | resistance ours [N] | Nakanishi | sinkage [mm] "
             "| in goal |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for t in table:
        goal = ("yes" if t["net_ok"] and t["gross_ok"] else "no") if t["in_goal"] else "(outside)"
        lines.append(
            f"| {t['slip']:.2f} | {t['net']:.2f} ± {t['net_sem']:.2f} | {t['ref_net']:.2f} | "
            f"{t['yade']:.2f} | {t['net_err']:+.2f} | {t['gross']:.2f} ± {t['gross_sem']:.2f} | "
            f"{t['ref_gross']:.2f} | {t['gross_err_pc']:+.1f} | {t['res']:.2f} | "
            f"{t['ref_res']:.2f} | {1000 * t['sinkage']:.1f} | {goal} |")
    goal_rows = [t for t in table if t["in_goal"]]
    verdict = (f"goal (net within 25 % or 1 N, gross within 20 %, slips 13-78 %): "
               f"{sum(t['net_ok'] for t in goal_rows)}/{len(goal_rows)} net, "
               f"{sum(t['gross_ok'] for t in goal_rows)}/{len(goal_rows)} gross")
    scm = scm_rows(a.scm, table, a.r_eff) if a.scm else []
    if scm:
        lines += ["", "DEM against SCM on the same soil (SCM: the soil lab's fit to the DEM soil; "
                  "Δ = SCM − DEM):", "",
                  "| slip [%] | net DEM [N] | net SCM [N] | Δ net [N] | gross DEM [N] | "
                  "gross SCM [N] | Δ gross [%] | sinkage DEM [mm] | sinkage SCM [mm] | "
                  "Δ sinkage [%] |", "|---|---|---|---|---|---|---|---|---|---|"]
        for m in scm:
            lines.append(
                f"| {m['slip']:.2f} | {m['net']:.2f} | {m['scm_net']:.2f} | "
                f"{m['scm_net'] - m['net']:+.2f} | {m['gross']:.2f} | {m['scm_gross']:.2f} | "
                f"{100 * (m['scm_gross'] - m['gross']) / m['gross']:+.1f} | "
                f"{1000 * m['sinkage']:.1f} | {1000 * m['scm_sinkage']:.1f} | "
                f"{100 * (m['scm_sinkage'] - m['sinkage']) / m['sinkage']:+.1f} |")
    text = "\n".join(lines + ["", verdict])
    print(text)
    if a.md:
        with open(a.md, "w", encoding="utf-8") as f:
            f.write(text + "\n")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.5))
        rs = [number(q, "slip_percent", a.reference) for q in ref]
        ax.plot(rs, [number(q, "net_N", a.reference) for q in ref], "s-", color="C0",
                label="net, Nakanishi et al. 2020")
        ax.plot(rs, [number(q, "gross_N", a.reference) for q in ref], "s-", color="C1",
                label="gross, Nakanishi et al. 2020")
        ax.plot(rs, [number(q, "yade_net_N", a.reference) for q in ref], "^:", color="C0",
                alpha=0.6, label="net, Yade re-run")
        s = [t["slip"] for t in table]
        ax.errorbar(s, [t["net"] for t in table], yerr=[t["net_sem"] for t in table], fmt="o--",
                    color="C0", mfc="white", capsize=3, label=f"net, {a.label} (± SEM)")
        ax.errorbar(s, [t["gross"] for t in table],
                    yerr=[0 if math.isnan(t["gross_sem"]) else t["gross_sem"] for t in table],
                    fmt="o--", color="C1", mfc="white", capsize=3,
                    label=f"gross T/R_eff, {a.label}")
        for k, (label, rows) in enumerate(also):
            style = ("v", "D", "P")[k % 3]
            ax.plot([r[0] for r in rows], [r[1] for r in rows], style + ":", color="0.45",
                    mfc="white", label=f"net, {label}")
            ax.plot([r[0] for r in rows], [r[2] for r in rows], style + ":", color="0.7",
                    mfc="white", label=f"gross, {label}")
        if scm:
            ss = [m["slip"] for m in scm]
            ax.plot(ss, [m["scm_net"] for m in scm], "x-.", color="C0",
                    label="net, wheelsim SCM (soil fitted to the DEM soil)")
            ax.plot(ss, [m["scm_gross"] for m in scm], "x-.", color="C1",
                    label="gross, wheelsim SCM")
        ax.set_xlabel("slip [%]")
        ax.set_ylabel("traction [N]")
        ax.set_title("Nakanishi et al. 2020 lugged wheel: wheelsim DEM vs published DEM")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.text(0.01, 0.01, verdict, fontsize=7)
        fig.tight_layout(rect=(0, 0.03, 1, 1))
        fig.savefig(a.png, dpi=120)
    return 0


def scm_rows(path, table, r_eff):
    """Our DEM rows (`table`, by slip) with the SCM row of the same target slip: its net, gross
    = T / R_eff and sinkage added as scm_*; a DEM slip without an SCM row is left out (named on
    stderr)."""
    scm = {round(number(r, "target_slip", path), 4): r for r in read_csv(path)}
    rows = []
    for t in table:
        m = scm.get(t["target"])
        if m is None:
            print(f"compare.py: {path}: no SCM row at slip {t['target']}", file=sys.stderr)
            continue
        rows.append(dict(t, scm_net=number(m, "drawbar_pull_N", path),
                         scm_gross=number(m, "driving_torque_Nm", path) / r_eff,
                         scm_sinkage=number(m, "sinkage_m", path)))
    return rows


if __name__ == "__main__":
    sys.exit(main())
