"""`wheelsim-post surface` on two real beds of the soil-bin tests (ctest fixtures soilbin_ci_np2
and soilbin_ci_plate_np2: the ci soil loose and plate-compacted, same bin and seed):

- on in.soilbin's own grid (--bed-grid) the mean of the profile is the bed depth in.soilbin
  measured and recorded in the bed's .vars (to 1e-8 m: the dump's 10 digits);
- the compacted bed against the loose one (--reference): the mean change is the difference of
  their recorded depths (to 1e-8 m), and it is a settlement (< 0);
- the default grid (2 d_max columns) and a y band write a CSV and a PNG;
- a restart without its .vars, a missing restart and a y band no column lies in are errors
  naming what to give.

  check_surface.py --build-dir BUILD --beds BUILD/tests/soilbin
"""
import argparse
import csv
import os
import re
import sys
import tempfile

from helpers import is_png, run_cli


def depth(vars_file):
    with open(vars_file) as f:
        for line in f:
            w = line.split()
            if w[:2] == ["variable", "bed_depth"]:
                return float(w[3])
    raise SystemExit(f"FAIL: no bed_depth in {vars_file}")


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def expect(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build-dir", required=True)
    ap.add_argument("--beds", required=True)
    a = ap.parse_args()
    loose = os.path.join(a.beds, "ci_np2", "soilbin.restart")
    dense = os.path.join(a.beds, "ci_plate_np2", "soilbin.restart")
    for bed in (loose, dense):
        if not os.path.isfile(bed + ".vars"):
            print(f"FAIL: the fixture bed {bed} (.vars) is missing")
            return 1
    common = ["--build-dir", a.build_dir]
    good = True
    with tempfile.TemporaryDirectory(prefix="check_surface_") as work:
        out = os.path.join(work, "loose.csv")
        p = run_cli("surface", loose, "--bed-grid", "--csv", out, *common)
        print(p.stdout + p.stderr)
        good &= expect(p.returncode == 0, "surface --bed-grid on the loose bed exits 0")
        if p.returncode == 0:
            r = rows(out)
            full = all(int(row["columns"]) == int(r[0]["columns"]) for row in r)
            mean = sum(float(row["surface_m"]) for row in r) / len(r)
            good &= expect(full, f"every row has all its columns ({r[0]['columns']})")
            good &= expect(abs(mean - depth(loose + ".vars")) < 1e-8,
                           f"mean {mean!r} m is the recorded bed depth {depth(loose + '.vars')!r} m")

        out = os.path.join(work, "dense.csv")
        p = run_cli("surface", dense, "--bed-grid", "--reference", loose, "--csv", out, *common)
        print(p.stdout + p.stderr)
        good &= expect(p.returncode == 0, "surface --reference exits 0")
        if p.returncode == 0:
            r = rows(out)
            change = sum(float(row["change_from_reference_m"]) for row in r) / len(r)
            want = depth(dense + ".vars") - depth(loose + ".vars")
            good &= expect(abs(change - want) < 1e-8 and change < 0,
                           f"mean change {change * 1e3:+.4f} mm is the compaction's "
                           f"{want * 1e3:+.4f} mm (depths recorded by in.soilbin)")

        out, png = os.path.join(work, "band.csv"), os.path.join(work, "band.png")
        p = run_cli("surface", loose, "--y-band=-0.02,0.02", "--csv", out, "--png", png, *common)
        good &= expect(p.returncode == 0 and len(rows(out)) == 8 and is_png(png)
                       and all(row["columns"] == "3" for row in rows(out)),
                       "default grid (2 d_max = 16 mm: 8 rows over 0.12 m) with a y band of 3 "
                       "of its 5 columns: CSV and PNG "
                       f"(exit {p.returncode}: {p.stderr.strip()})")

        lone = os.path.join(work, "liggghts-100.restart")
        os.symlink(os.path.abspath(loose), lone)
        for args, pattern in (
                ((lone,), "needs --bed-vars"),
                ((os.path.join(work, "none.restart"),), "restart file '.*none.restart' does not exist"),
                ((loose, "--y-band", "0.3,0.4"), r"--y-band 0.3,0.4: no column centre lies in it")):
            p = run_cli("surface", *args, *common)
            good &= expect(p.returncode == 2 and re.search(pattern, p.stderr) is not None,
                           f"{' '.join(os.path.basename(x) for x in args)}: exit 2 with "
                           f"'{pattern}' (got {p.returncode}: {p.stderr.strip()})")
        p = run_cli("surface", lone, "--bed-vars", loose + ".vars", *common)
        good &= expect(p.returncode == 0, "the same restart under another name with --bed-vars")
    return 0 if good else 1


if __name__ == "__main__":
    sys.exit(main())
