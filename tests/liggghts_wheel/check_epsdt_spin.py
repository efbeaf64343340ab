#!/usr/bin/env python3
"""Runs in.epsdt_spin (rolling_friction epsdt: a pair and a sphere on a wall, held in place and
spinning) twice and checks the spins against the analytic elastic-plastic rotational oscillator.

    check_epsdt_spin.py --launch "mpirun -np 1 liggghts-wheel" --deck in.epsdt_spin --data FILE

The spring of each contact is k_r = k_t R*² with LIGGGHTS' Hertz k_t = 8 G* sqrt(R* δ); its cap
is μr R* Fn with Fn = 4/3 E* sqrt(R* δ) δ (held spheres: no normal damping). With G*, E* of the
deck's material (E 5e6 Pa, ν 0.3; the wall has the particles' type) and the data file's overlaps
(δ = 0.1 mm, R 2 mm):
- elastic (μr 10, the cap out of reach): as in.krot_spin, ω1,2 = ω0/2 (1 ± cos Ω2 t) for the pair,
  Ω2 = sqrt(2 k_r,pair / I), and ω3 = ω0 cos Ω1 t on the wall, Ω1 = sqrt(k_r,wall / I); within
  2e-4 ω0 over 1.5 periods of the pair (measured 4.5e-5: the explicit update's phase error and
  the spring's half step lag, at Ω dt ~ 8e-3);
- plastic (μr 0.01): the wall sphere slides on the cap, so ω3 falls at the constant rate
  μr R Fn / I (the slope fitted while 0.8 ω0 >= ω3 >= 0.3 ω0, within 1 %), then swings within
  the cap: |ω3| <= μr R Fn / (I Ω1) (+2 %) after it has stopped.
"""
import argparse
import math
import sys

sys.dont_write_bytecode = True  # keep the source tree clean
from spin_deck import DELTA, INERTIA, R, W0, oscillator_error, run_spin_deck  # noqa: E402

E, NU = 5e6, 0.3  # [Pa], [-]: the deck's material
G_EFF = 1.0 / (2 * 2.0 * (2.0 - NU) * (1.0 + NU) / E)  # LIGGGHTS' Geff, both sides alike
Y_EFF = 1.0 / (2 * (1.0 - NU**2) / E)


def spring_and_cap(r_eff, mur):
    """(k_r [N m/rad], cap [N m]) of a held contact of effective radius r_eff [m]."""
    root = math.sqrt(r_eff * DELTA)
    return 8.0 * G_EFF * root * r_eff**2, mur * r_eff * 4.0 / 3.0 * Y_EFF * root * DELTA


def run(args, mur, steps):
    return run_spin_deck(args.launch, args.deck, args.data, "epsdt_spin",
                         {"mur": repr(mur), "dt": repr(args.dt), "steps": steps})


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--launch", required=True, help="command that runs liggghts-wheel")
    ap.add_argument("--deck", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--dt", type=float, default=1e-6)
    args = ap.parse_args()
    failed = []

    kr_wall, _ = spring_and_cap(R, 10.0)
    kr_pair, _ = spring_and_cap(0.5 * R, 10.0)
    omega1, omega2 = math.sqrt(kr_wall / INERTIA), math.sqrt(2.0 * kr_pair / INERTIA)
    rows = run(args, 10.0, int(round(1.5 * 2.0 * math.pi / omega2 / args.dt / 10.0)) * 10)
    worst, swung = oscillator_error(rows, omega1, omega2)
    print(f"epsdt elastic: {len(rows)} samples, Ω1 {omega1:.0f} rad/s (k_r {kr_wall:.4g} N m/rad), "
          f"Ω2 {omega2:.0f} rad/s (k_r {kr_pair:.4g}), worst |Δω|/ω0 = {worst:.2e} (tolerance 2e-4)")
    if worst > 2e-4 or not swung:
        failed.append("elastic: the spins do not follow the undamped rotational oscillator")

    mur = 0.01
    _, cap = spring_and_cap(R, mur)
    rate = cap / INERTIA  # [rad/s^2] while sliding on the cap
    t_stop = W0 / rate
    rows = run(args, mur, int(round(2.0 * t_stop / args.dt / 10.0)) * 10)
    sliding = [(t, w3) for t, _, _, w3 in rows if 0.3 * W0 <= w3 <= 0.8 * W0]
    n = len(sliding)
    tm = sum(t for t, _ in sliding) / n
    wm = sum(w for _, w in sliding) / n
    slope = sum((t - tm) * (w - wm) for t, w in sliding) / sum((t - tm) ** 2 for t, _ in sliding)
    stopped = [abs(w3) for t, _, _, w3 in rows if t > 1.2 * t_stop]
    bound = cap / (INERTIA * omega1)
    print(f"epsdt plastic (μr {mur}): ω3 falls at {-slope:.5g} rad/s² (cap / I = {rate:.5g}, "
          f"{n} samples), then swings within {max(stopped):.4g} rad/s "
          f"(cap / (I Ω1) = {bound:.4g})")
    if abs(-slope / rate - 1.0) > 0.01:
        failed.append("plastic: ω3 does not fall at the capped moment's rate")
    if not stopped or max(stopped) > 1.02 * bound:
        failed.append("plastic: after stopping, ω3 swings beyond the cap's elastic bound")
    if failed:
        sys.exit("FAIL: " + "; ".join(failed))
    print("PASS")


if __name__ == "__main__":
    main()
