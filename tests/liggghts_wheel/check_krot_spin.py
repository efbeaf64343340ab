#!/usr/bin/env python3
"""Runs in.krot_spin (rolling_friction krot: a pair and a sphere on a wall, held in place and
spinning) and checks each spin against the undamped rotational oscillator it must be.

    check_krot_spin.py --launch "mpirun -np 1 liggghts-wheel" --deck in.krot_spin --data FILE

Tolerance: 1e-4 of ω0 at every printed step over 1.5 periods of the pair (measured 2e-7: the
explicit update's phase error, ~(Ω dt)² / 24 per radian, and the half step by which the spring
lags the spin). Tangential damping is off in the deck: with μ 0 it alone gives each contact's
first step a tangential force, whose lever torque shifts the spins by ~2e-3 ω0.
"""
import argparse
import math
import sys

sys.dont_write_bytecode = True  # keep the source tree clean
from spin_deck import INERTIA, oscillator_error, run_spin_deck  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--launch", required=True, help="command that runs liggghts-wheel")
    ap.add_argument("--deck", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--kr", type=float, default=5e-5, help="rolling spring stiffness [N m/rad]")
    ap.add_argument("--dt", type=float, default=1e-6)
    ap.add_argument("--tol", type=float, default=1e-4, help="max |ω − ω_exact| / ω0")
    args = ap.parse_args()

    omega1 = math.sqrt(args.kr / INERTIA)
    omega2 = math.sqrt(2.0 * args.kr / INERTIA)
    steps = int(round(1.5 * 2.0 * math.pi / omega2 / args.dt / 50.0)) * 50
    rows = run_spin_deck(args.launch, args.deck, args.data, "krot_spin",
                         {"kr": repr(args.kr), "dt": repr(args.dt), "steps": steps})
    worst, swung = oscillator_error(rows, omega1, omega2)
    print(f"krot spin check: {len(rows)} samples over {rows[-1][0]:.4g} s, Ω1 {omega1:.1f} rad/s, "
          f"Ω2 {omega2:.1f} rad/s, worst |Δω|/ω0 = {worst:.2e} (tolerance {args.tol:g})")
    if worst > args.tol or not swung:
        sys.exit("FAIL: the spins do not follow the undamped rotational oscillator")
    print("PASS")


if __name__ == "__main__":
    main()
