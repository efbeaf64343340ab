"""validation/common/case.sh finished_runs OUT [KEPT] on a synthetic tree: a point finished in OUT
and kept with the same done.json is named by its kept copy; one kept from an earlier run (another
done.json) by OUT's; one OUT records as failed is left out even though KEPT holds an old copy; one
only KEPT holds is named by it; trailing slashes change nothing; without KEPT, OUT's runs."""
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from script_test import report, work_dir  # noqa: E402

CASE_SH = Path(__file__).resolve().parents[2] / "validation" / "common" / "case.sh"


def point(root, name, done):
    d = root / "wheel1" / "soil" / name
    d.mkdir(parents=True, exist_ok=True)
    (d / "done.json").write_text(done)
    if "failed" not in done:
        (d / "run.h5").write_text("run")


def finished_runs(*args):
    # case.sh expects to be sourced by a run.sh; take the function alone
    script = (f"set -euo pipefail; eval \"$(sed -n '/^finished_runs()/,/^}}/p' {CASE_SH})\"; "
              f"finished_runs {' '.join(map(str, args))}")
    r = subprocess.run(["bash", "-c", script], capture_output=True, text=True, timeout=30)
    print(f"$ finished_runs {' '.join(map(str, args))} -> {r.returncode}\n{r.stdout}{r.stderr}")
    return r.returncode, r.stdout.split()


def main():
    work = work_dir()
    out, kept = work / "out", work / "kept"
    for root in (out, kept):
        subprocess.run(["rm", "-rf", str(root)], check=True)
    point(out, "s0.100", '{"run": 1}')
    point(kept, "s0.100", '{"run": 1}')        # the same run: the kept copy
    point(out, "s0.200", '{"run": 2}')
    point(kept, "s0.200", '{"run": 1}')        # an earlier run: OUT's
    point(out, "s0.300", '{"status": "failed"}')
    point(kept, "s0.300", '{"run": 1}')        # failed in OUT: left out
    point(kept, "s0.400", '{"run": 1}')        # only kept: the kept copy
    want = sorted([f"{kept}/wheel1/soil/s0.100/run.h5", f"{out}/wheel1/soil/s0.200/run.h5",
                   f"{kept}/wheel1/soil/s0.400/run.h5"])  # sorted, as the function prints them
    failures = []
    for args in ((out, kept), (f"{out}/", f"{kept}/")):
        rc, got = finished_runs(*args)
        if rc != 0 or got != want:
            failures.append(f"finished_runs {args}: exit {rc}, {got}; expected {want}")
    rc, got = finished_runs(out)
    if rc != 0 or got != [f"{out}/wheel1/soil/s0.100/run.h5", f"{out}/wheel1/soil/s0.200/run.h5"]:
        failures.append(f"finished_runs OUT alone: exit {rc}, {got}")
    rc, got = finished_runs(work / "missing", kept)
    if rc != 0 or len(got) != 4:
        failures.append(f"finished_runs with an empty OUT: exit {rc}, {got}; expected KEPT's 4")
    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
