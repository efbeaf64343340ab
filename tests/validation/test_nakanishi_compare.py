#!/usr/bin/python3
"""validation/nakanishi_2020/compare.py on a synthetic results table with a known error against
the case's reference.csv: the goal verdict (net within 25 % or 1 N, gross within 20 %), the
comparison PNG with another table of ours overlaid (--also, --label), and a malformed --also
(exit 2 naming it).

    test_nakanishi_compare.py --work DIR
"""
import sys
from pathlib import Path

from script_test import report, run_script, work_dir

CASE = Path(__file__).resolve().parents[2] / "validation" / "nakanishi_2020"
HEAD = ("# wheelsim-post curves --results (synthetic)\n"
        "slip,target_slip,drawbar_pull_N,drawbar_pull_sem_N,driving_torque_Nm,"
        "driving_torque_sem_Nm,sinkage_m\n")


def table(path, rows):
    path.write_text(HEAD + "".join(f"{s},{s},{dp},0.1,{t},0.01,0.025\n" for s, dp, t in rows))
    return path


def run(*args):
    return run_script(CASE / "compare.py", *args)


def main():
    work = work_dir()
    ref = CASE / "reference.csv"
    # 13.05 %: net 2.54 + 0.9 N (inside 1 N), gross 4.95 * 1.1 (inside 20 %);
    # 35.42 %: net 7.53 * 0.7 (outside 25 %), gross 10.06 * 0.85 (inside)
    ours = table(work / "ours.csv", [(0.1305, 3.44, 1.1 * 4.95 * 0.11),
                                     (0.3542, 0.7 * 7.53, 0.85 * 10.06 * 0.11)])
    other = table(work / "other.csv", [(0.1305, 2.6, 0.55), (0.3542, 7.5, 1.1)])
    png = work / "comparison.png"
    png.unlink(missing_ok=True)
    r = run(ours, ref, "--r-eff", "0.11", "--label", "ours", "--also", f"other={other}",
            "--png", png)
    failures = []
    if r.returncode != 0:
        failures.append(f"exit {r.returncode}")
    if "1/2 net, 2/2 gross" not in r.stdout:
        failures.append("verdict is not '1/2 net, 2/2 gross'")
    if "| 13.05 | 3.44 ± 0.10 | 2.54 |" not in r.stdout or "+0.90" not in r.stdout:
        failures.append("the 13.05 % row or its net error +0.90 N is missing")
    if not png.is_file() or png.stat().st_size < 10_000:
        failures.append("no comparison PNG")
    bad = run(ours, ref, "--r-eff", "0.11", "--also", str(other))
    if bad.returncode != 2 or "--also expects LABEL=RESULTS.csv" not in bad.stderr:
        failures.append("a malformed --also is not named (exit 2)")
    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
