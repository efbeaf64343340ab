#!/usr/bin/python3
"""The repose deck on a multisphere soil (soil_lab/decks/in.lab_repose, docs/soil-lab.md "Angle of
repose"), on real LIGGGHTS: a small ci_clumps bed (inputs/in.soilbin, a 0.07 m square bin, ~30 mm
deep, a few hundred grains) under a lifted frame, lifted fast and settled briefly (a smoke, not a
measurement). Checks:
- the deck runs through (exit 0, its "done" line) and part of the column flowed off the base
  (fewer particles left than the bed had, but some);
- the base layer is split as the deck says: some single spheres frozen, some clump spheres free;
- the frozen spheres did not move (their ids at the end, at the positions the bed had, within
  1e-6 m: the deck's dump has 6 digits);
- the free clumps of the base layer stayed on the base plate: at the end at least as many sphere
  centres lie in the base layer as it held (frozen + free; grains that flowed down onto it add to
  them), and no sphere over the base reaches below the plate's top by more than a contact
  overlap.
Without the plate under the base the free clumps fall through the floor's gaps out of the domain
(the layer count drops), and without the single spheres frozen the ids move.

  check_repose_clumps.py --build-dir BUILD --work DIR
Exit 0 pass, 1 fail, 77 skip (liggghts-wheel not built).
"""

import re
import subprocess
import sys
from pathlib import Path

import lab_check

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
INPUTS = ROOT / "inputs"
DECK = ROOT / "soil_lab" / "decks" / "in.lab_repose"
SIDE = 0.07          # m, bin (and base) side
FILL = 0.03          # m
WALL = 0.005         # m, frame wall and base plate thickness (the lab's: max(d_max / 2, 5 mm))


def run(cmd, cwd, what):
    r = subprocess.run([str(c) for c in cmd], cwd=cwd, capture_output=True, text=True,
                       timeout=600, stdin=subprocess.DEVNULL)
    print(f"$ {' '.join(str(c) for c in cmd)}\n  exit {r.returncode}")
    if r.returncode != 0:
        print("\n".join((r.stdout + r.stderr).splitlines()[-15:]))
        raise SystemExit(f"FAIL: {what} exited {r.returncode}")
    return r.stdout


def read_dump(path):
    """{id: (x, y, z, radius)} of a LIGGGHTS text dump written by `write_dump ... custom id x y z
    radius`."""
    lines = Path(path).read_text().splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith("ITEM: ATOMS")) + 1
    out = {}
    for ln in lines[start:]:
        f = ln.split()
        if len(f) >= 5:
            out[int(f[0])] = tuple(float(v) for v in f[1:5])
    return out


def main():
    started = lab_check.start()
    if started is None:
        return lab_check.SKIP
    a, work = started
    work.mkdir(parents=True)
    build = Path(a.build_dir).resolve()
    liggghts, wheel_mesh = build / "bin" / "liggghts-wheel", build / "bin" / "wheel-mesh"
    restart = work / "bed.restart"
    run([liggghts, "-in", INPUTS / "in.soilbin", "-log", "none", "-echo", "none",
         "-var", "inputs_dir", INPUTS, "-var", "soil", "ci_clumps", "-var", "out_dir", work,
         "-var", "restart_file", restart, "-var", "bin_length", SIDE, "-var", "bin_width", SIDE,
         "-var", "fill_height", FILL, "-var", "ke_threshold", "1e-4",
         "-var", "max_settle_time", "1.0"], work, "the ci_clumps bed (in.soilbin)")
    # the bed's particles, as prepared (the frozen ones must end where they start)
    run([liggghts, "-in", ROOT / "inputs" / "in.bed_surface", "-log", "none", "-echo", "none",
         "-var", "inputs_dir", INPUTS, "-var", "restart_file", restart,
         "-var", "dump_file", work / "bed.dump"], work, "the bed's particles (in.bed_surface)")
    bed = read_dump(work / "bed.dump")
    frame_h = 0.5 * SIDE * 1.4 + 2 * 0.009
    run([wheel_mesh, "tool", "frame", SIDE, SIDE, WALL, frame_h, "--out", work / "frame",
         "--formats", "obj"], work, "the frame mesh")
    run([wheel_mesh, "tool", "plate-rect", SIDE, SIDE, WALL, "--out", work / "base",
         "--formats", "obj"], work, "the base plate mesh")
    out = run([liggghts, "-in", DECK, "-log", "none", "-echo", "none", "-var", "inputs_dir",
               INPUTS, "-var", "restart_file", restart, "-var", "frame_mesh", work / "frame.obj",
               "-var", "frame_h", frame_h, "-var", "base_mesh", work / "base.obj",
               "-var", "base_plate_t", WALL, "-var", "lift_speed", "0.2", "-var", "settle", "0.1",
               "-var", "clearance", "0.009", "-var", "out_dump", work / "repose.dump"],
              work, "in.lab_repose")
    fails = []

    def check(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            fails.append(what)

    m_base = re.search(r"frozen base z < (\S+) m", out)
    m_layer = re.search(r"base layer: (\d+) single spheres frozen, (\d+) clump spheres free", out)
    m_done = re.search(r"repose: done: (\d+) particles left", out)
    check(m_base is not None and m_layer is not None and m_done is not None,
          "the deck's base, base-layer and done lines")
    if fails:
        return 1
    base_z = float(m_base.group(1))
    frozen, free = int(m_layer.group(1)), int(m_layer.group(2))
    left = int(m_done.group(1))
    check(frozen > 0 and free > 0, f"the base layer: {frozen} single spheres frozen and {free} "
                                   "clump spheres free (both present)")
    check(0 < left < len(bed), f"{left} of {len(bed)} particles left on the base: some flowed off")
    end = read_dump(work / "repose.dump")
    layer_ids = [i for i, (x, y, z, r) in bed.items() if z < base_z]
    still = [i for i in layer_ids if i in end and
             max(abs(end[i][k] - bed[i][k]) for k in range(3)) < 1e-6]
    check(len(still) >= frozen, f"{len(still)} base-layer spheres unmoved (>= the {frozen} frozen)")
    in_layer = sum(1 for x, y, z, r in end.values() if z < base_z)
    check(in_layer >= frozen + free, f"{in_layer} sphere centres in the base layer at the end "
                                     f"(>= {frozen} + {free}: the free clumps stayed on the plate)")
    # over the base only: grains that flowed off its edge fall past it until they leave the domain
    over = [z - r for x, y, z, r in end.values() if abs(x - 0.5 * SIDE) < 0.5 * SIDE
            and abs(y) < 0.5 * SIDE]
    lowest = min(over, default=0.0)
    check(lowest > -0.1 * 0.0022, f"the lowest bottom of a sphere over the base at "
                                  f"{lowest * 1e3:.3f} mm (the plate's top at 0: less than a tenth "
                                  "of the smallest grain below)")
    print("PASS" if not fails else f"FAIL: {len(fails)} check(s)")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
