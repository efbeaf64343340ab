#!/usr/bin/env python3
"""Runs in.adhesive_slide (a sphere sliding along a wall, a sphere sliding under another, both at
held overlaps, SJKR cohesion) and checks the sliding forces against the Coulomb caps.

    check_adhesive_slide.py --launch "mpirun -np 1 liggghts-wheel" --deck in.adhesive_slide

Material of the deck: E 5e6 Pa, ν 0.3 (Y* = E / (2 (1 − ν²)), the wall has the particles' type),
R 2 mm, μ 0.5, k_coh 9.2e4 J/m³. For a contact of effective radius R* (the wall: R; the pair:
R/2) at overlap δ: Hertz F_H = 4/3 Y* √(R* δ) δ (no normal velocity, so no damping), SJKR pull
k_coh A (A the intersection circle, as LIGGGHTS' cohesion sjkr takes it), pull-off force
F_po = (2/3) π³ k_coh³ R*² / Y*². Once sliding, |F_t| must equal:
- tangential history_adhesive: μ max(0, F_H − k_coh A + 2 F_po) (Thornton's cap), at the
  overlap where a bonded contact carries no load (F_H = k_coh A: 2 μ F_po) and deeper, with and
  without SJKR's tangential_reduce on between the particles (the model takes the pull off itself
  when the switch has not);
- tangential history (LIGGGHTS' own, the reference the method is checked on): μ F_H;
all within 1e-6 relative over the last 40 % of the run. And with k_coh 0, history_adhesive must
give the forces of history to 1e-12 at every printed step (the spring, damping and cap of a
compressed contact without cohesion are history's).
"""
import argparse
import math
import sys
import tempfile
from pathlib import Path

sys.dont_write_bytecode = True  # keep the source tree clean
from spin_deck import run_deck  # noqa: E402

E, NU, R, MU, KCOH = 5e6, 0.3, 0.002, 0.5, 9.2e4
Y_EFF = E / (2.0 * (1.0 - NU**2))


def k_hertz(r_eff):
    return 4.0 / 3.0 * Y_EFF * math.sqrt(r_eff)


def pull_off(r_eff, kcoh):
    return 2.0 / 3.0 * math.pi**3 * kcoh**3 * r_eff**2 / Y_EFF**2


def zero_load_overlap(r_eff, kcoh):
    """δ where K δ^1.5 = C δ (C = 2π R* k_coh): a bonded contact at rest carrying no load."""
    return (2.0 * math.pi * r_eff * kcoh / k_hertz(r_eff)) ** 2


OMEGA = 50.0  # [rad/s] spin of spheres 1 and 2 about y: the contacts slide at ~0.1 m/s


def write_data(path, d_w, d_p):
    """The deck's three spheres: 1 on the wall z = 0 at overlap d_w, 2 under 3 at overlap d_p,
    spheres 1 and 2 spinning at OMEGA about y."""
    z1, z2 = R - d_w, 0.006
    Path(path).write_text(
        "LIGGGHTS data file: three spheres for in.adhesive_slide\n\n3 atoms\n1 atom types\n\n"
        "-0.01 0.01 xlo xhi\n-0.01 0.01 ylo yhi\n-0.005 0.015 zlo zhi\n\nAtoms\n\n"
        f"1 1 {2 * R!r} 2500 0.0 0.0 {z1!r}\n2 1 {2 * R!r} 2500 0.005 0.0 {z2!r}\n"
        f"3 1 {2 * R!r} 2500 0.005 0.0 {z2 + 2 * R - d_p!r}\n\nVelocities\n\n"
        f"1 0 0 0 0 {OMEGA!r} 0\n2 0 0 0 0 {OMEGA!r} 0\n3 0 0 0 0 0 0\n")


def run(args, d_w, d_p, **variables):
    data = Path(args.work) / "adhesive_slide.data"
    write_data(data, d_w, d_p)
    return run_deck(args.launch, args.deck, str(data), "adhesive_slide", variables)


def expected_caps(tangential, kcoh, d_w, d_p):
    """(wall cap, pair cap) [N] at the overlaps d_w (sphere 1 on the wall) and d_p (the pair)."""
    caps = []
    z1 = R - d_w  # sphere 1's centre above the wall
    area_w = math.pi * (R * R - z1 * z1)
    r = 2.0 * R - d_p  # the pair's centres
    area_p = -math.pi / 4.0 * ((r - 2 * R) * r * r * (r + 2 * R)) / (r * r)
    for r_eff, d, area in ((R, d_w, area_w), (0.5 * R, d_p, area_p)):
        f_h = k_hertz(r_eff) * d**1.5
        if tangential == "history":
            caps.append(MU * f_h)
        else:
            caps.append(MU * max(0.0, f_h - kcoh * area + 2.0 * pull_off(r_eff, kcoh)))
    return caps


def tangential_forces(row):
    """(|F_t| of sphere 1 on the wall, |F_t| of sphere 2 in the pair) [N]: both contact normals
    are along z."""
    _, fx1, fy1, _, fx2, fy2, _ = row
    return math.hypot(fx1, fy1), math.hypot(fx2, fy2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--launch", required=True, help="command that runs liggghts-wheel")
    ap.add_argument("--deck", required=True)
    ap.add_argument("--work", help="directory for the data file (default: a temporary one)")
    args = ap.parse_args()
    if args.work is None:
        tmp = tempfile.TemporaryDirectory()
        args.work = tmp.name
    Path(args.work).mkdir(parents=True, exist_ok=True)
    common = {"mu": MU, "dt": 1e-6, "steps": 2000}
    failed = []

    dw0, dp0 = zero_load_overlap(R, KCOH), zero_load_overlap(0.5 * R, KCOH)
    cases = [  # (label, tangential, pair_settings, dw, dp)
        ("history_adhesive at zero load", "history_adhesive", "", dw0, dp0),
        ("history_adhesive deeper", "history_adhesive", "", 2e-4, 1e-4),
        ("history_adhesive deeper, tangential_reduce on", "history_adhesive",
         "tangential_reduce on", 2e-4, 1e-4),
        ("LIGGGHTS history deeper (reference)", "history", "", 2e-4, 1e-4),
    ]
    for label, tangential, settings, dw, dp in cases:
        rows = run(args, dw, dp, tangential=tangential, pair_settings=settings, kcoh=KCOH,
                   **common)
        tail = rows[int(0.6 * len(rows)):]
        worst = [0.0, 0.0]
        for row in tail:
            for k, (got, want) in enumerate(zip(tangential_forces(row),
                                                expected_caps(tangential, KCOH, dw, dp))):
                worst[k] = max(worst[k], abs(got / want - 1.0))
        wall, pair = expected_caps(tangential, KCOH, dw, dp)
        print(f"{label}: sliding force / cap - 1 worst over {len(tail)} samples: wall "
              f"{worst[0]:.1e} (cap {wall:.5g} N), pair {worst[1]:.1e} (cap {pair:.5g} N); "
              "tolerance 1e-6")
        if max(worst) > 1e-6:
            failed.append(f"{label}: the sliding force is not the cap")
        if tangential == "history_adhesive" and dw == dw0:
            # at zero load the cap is ~Thornton's 2 μ F_po (printed for the record)
            for r_eff in (R, 0.5 * R):
                d0 = zero_load_overlap(r_eff, KCOH)
                print(f"  R* {r_eff * 1e3:g} mm: 2 μ F_po = {2 * MU * pull_off(r_eff, KCOH):.5g} N; "
                      f"LIGGGHTS' history caps the same contact at μ F_H = "
                      f"{MU * k_hertz(r_eff) * d0**1.5:.5g} N")

    # without cohesion history_adhesive is history, step by step (sticking phase included)
    a = run(args, 2e-4, 1e-4, tangential="history_adhesive", pair_settings="", kcoh=0.0, **common)
    b = run(args, 2e-4, 1e-4, tangential="history", pair_settings="", kcoh=0.0, **common)
    diff = max(abs(x - y) / max(abs(y), 1e-30) for ra, rb in zip(a, b)
               for x, y in zip(ra[1:], rb[1:]) if y != 0.0)
    print(f"k_coh 0: history_adhesive against history, worst relative difference of the forces "
          f"over {len(a)} samples {diff:.1e} (tolerance 1e-12)")
    if len(a) != len(b) or diff > 1e-12:
        failed.append("k_coh 0: history_adhesive differs from history")

    if failed:
        print("FAILED: " + "; ".join(failed))
        return 1
    print("passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
