#!/usr/bin/env python3
"""A settled bed left alone stays put with `rolling_friction epsdt`, and creeps with `cdt`.

    check_bed_at_rest.py --launch "mpirun -np 1 liggghts-wheel" --inputs DIR --creep-deck FILE --work DIR

The shipped ci soil (inputs/soils/ci.in, cdt) and the same file with its rolling model swapped to
epsdt each fill and settle a small bin (inputs/in.soilbin: 0.08 x 0.08 m, fill 0.04 m, ~2000
spheres of 4-6 mm, the same seed), then run on with no tool for STEPS steps
(soil_lab/trials/in.creep_check). cdt's torque cannot hold a rolling moment at rest (it switches
sign every step), so its bed goes on sinking; epsdt's capped spring holds it (docs/contact-law.md
"Rolling: rolling_friction epsdt"). Over the second half of the run (the first half lets the end
of the settling pass: in.soilbin stops at a kinetic energy of 1e-5 m g d_ref), with what was
measured on 2026-11-29 (one rank; 4000 steps = 0.20 s):
- epsdt: the centre of mass moves by less than 0.05 um (measured 0.010 um) and the translational
  kinetic energy is below 1e-8 m g d_ref (measured 4e-10): at rest;
- cdt: the centre of mass sinks by more than 0.5 um and 20x epsdt's move (measured 2.6 um): the
  check sees a creep where there is one.
"""
import argparse
import shlex
import subprocess
import sys
from pathlib import Path

STEPS = 8000


def _numbers(words):
    """True if `words` are a step (an integer) followed by numbers."""
    try:
        int(words[0])
        for w in words[1:]:
            float(w)
    except ValueError:
        return False
    return True


def run(cmd, cwd):
    out = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True, timeout=600)
    if out.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {out.returncode}:\n{out.stdout[-3000:]}")
    return out.stdout


def bed_and_creep(args, name, soil_file, work):
    """(centre-of-mass move [m] over the run's second half, last ke_ratio) of a fresh bed of
    soil_file run on with no tool."""
    d = work / name
    d.mkdir(parents=True, exist_ok=True)
    launch = shlex.split(args.launch)
    run(launch + ["-in", str(Path(args.inputs) / "in.soilbin"), "-log", "none", "-echo", "none",
                  "-var", "inputs_dir", args.inputs, "-var", "out_dir", str(d),
                  "-var", "soil_file", str(soil_file), "-var", "bin_length", "0.08",
                  "-var", "bin_width", "0.08", "-var", "fill_height", "0.04"], d)
    restart, = d.glob("soilbin_*.restart")
    text = run(launch + ["-in", args.creep_deck, "-log", "none", "-echo", "none",
                         "-var", "inputs_dir", args.inputs, "-var", "restart_file", str(restart),
                         "-var", "soil_file", str(soil_file), "-var", "n", str(STEPS),
                         "-var", "thermo_every", "1000"], d)
    # thermo rows: step t zcm ztop ke_ratio rot_ratio
    rows = [w for w in map(str.split, text.splitlines()) if len(w) == 6 and _numbers(w)]
    half = [r for r in rows if int(r[0]) >= int(rows[0][0]) + STEPS // 2]
    if len(half) < 3:
        sys.exit(f"FAIL: {name}: no creep-check rows in the output:\n{text[-3000:]}")
    return float(half[-1][2]) - float(half[0][2]), float(half[-1][4])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--launch", required=True, help="command that runs liggghts-wheel")
    ap.add_argument("--inputs", required=True, help="the repository's inputs/ folder")
    ap.add_argument("--creep-deck", required=True, help="soil_lab/trials/in.creep_check")
    ap.add_argument("--work", required=True, help="a scratch folder")
    args = ap.parse_args()
    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    shipped = Path(args.inputs) / "soils" / "ci.in"
    text = shipped.read_text()
    if "rolling_friction cdt" not in text:
        sys.exit(f"FAIL: {shipped} no longer uses rolling_friction cdt: update this check")
    epsdt = work / "ci_epsdt.in"
    epsdt.write_text(text.replace("rolling_friction cdt", "rolling_friction epsdt"))

    cdt_move, cdt_ke = bed_and_creep(args, "cdt", shipped, work)
    epsdt_move, epsdt_ke = bed_and_creep(args, "epsdt", epsdt, work)
    print(f"bed at rest over the last {STEPS // 2} of {STEPS} steps: centre of mass cdt {cdt_move * 1e6:+.3f} um "
          f"(ke_ratio {cdt_ke:.2g}), epsdt {epsdt_move * 1e6:+.3f} um (ke_ratio {epsdt_ke:.2g})")
    failed = []
    if abs(epsdt_move) >= 5e-8:
        failed.append(f"the epsdt bed moved {epsdt_move * 1e6:.3f} um (limit 0.05 um)")
    if epsdt_ke >= 1e-8:
        failed.append(f"the epsdt bed's ke_ratio is {epsdt_ke:.2g} (limit 1e-8)")
    if not (-cdt_move > 5e-7 and -cdt_move > 20 * abs(epsdt_move)):
        failed.append(f"the cdt bed sank {-cdt_move * 1e6:.2f} um: not > 0.5 um and 20x the "
                      "epsdt bed's move")
    if failed:
        sys.exit("FAIL: " + "; ".join(failed))
    print("PASS")


if __name__ == "__main__":
    main()
