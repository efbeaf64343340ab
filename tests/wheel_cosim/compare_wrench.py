#!/usr/bin/python3
"""Compare the wheel wrench (thermo columns fx..tz of in.wheel_roll) of two LIGGGHTS runs.

  compare_wrench.py early  OURS REF --window STEPS --tol REL --force-floor N --lever M
  compare_wrench.py window OURS REF --from STEP --to STEP --tol REL
  compare_wrench.py equal  OURS REF --from STEP --to STEP --tol REL --force-floor N --lever M

OURS and REF are the screen outputs (or logs) of the two runs. Exit status 0 on pass, 1 on fail,
2 on unusable input; one summary line `compare_wrench: ... PASS|FAIL` is always printed.

early  : the first contact step s0 is the first step at which |F_ref| > 0. Over steps
         s0 .. s0+STEPS: e_F = max_s |F_ours(s) - F_ref(s)| / max(|F_ref(s)|, floor_F), the same
         for the torque with floor_T = floor_F * lever. Pass if both < tol.
window : time averages over STEP_from..STEP_to of F and T (vectors); e_F = |<F_ours> - <F_ref>|
         / |<F_ref>|, e_T = |<T_ours> - <T_ref>| / max(|<T_ref>|, lever |<F_ref>|). Pass if both
         < tol. --from-offset K starts the window K steps after the first common thermo step.
equal  : like early, over a fixed step range (restart continuity).
"""
import argparse
import sys

import numpy as np

COLS = ["fx", "fy", "fz", "tx", "ty", "tz"]  # thermo header of v_fx .. v_tz


def read_thermo(path):
    """All thermo rows (Step + the wrench columns) of every `run` in the file; later rows with
    the same step replace earlier ones (a `run 0` prints step 0 again)."""
    rows = {}
    header = None
    with open(path, errors="replace") as fh:
        for line in fh:
            tok = line.split()
            if not tok:
                continue
            if tok[0] == "Step":
                header = tok
                continue
            if header is None:
                continue
            if tok[0] == "Loop":
                header = None
                continue
            if len(tok) != len(header) or not all(c in header for c in COLS):
                continue
            try:
                vals = [float(t) for t in tok]
            except ValueError:
                continue
            rows[int(vals[0])] = [vals[header.index(c)] for c in COLS]
    if not rows:
        raise SystemExit(f"compare_wrench: no thermo rows with {COLS} in {path}")
    steps = np.array(sorted(rows))
    return steps, np.array([rows[s] for s in steps])


def common(a, b):
    sa, wa = a
    sb, wb = b
    steps = np.intersect1d(sa, sb)
    ia = np.searchsorted(sa, steps)
    ib = np.searchsorted(sb, steps)
    return steps, wa[ia], wb[ib]


def rel_max(steps, ours, ref, floor_f, floor_t):
    out = []
    for cols, floor in ((slice(0, 3), floor_f), (slice(3, 6), floor_t)):
        d = np.linalg.norm(ours[:, cols] - ref[:, cols], axis=1)
        scale = np.maximum(np.linalg.norm(ref[:, cols], axis=1), floor)
        e = d / scale
        k = int(np.argmax(e))
        out.append((e[k], int(steps[k]), np.linalg.norm(ref[k, cols])))
    return out


def main():
    p = argparse.ArgumentParser()
    p.add_argument("mode", choices=["early", "window", "equal"])
    p.add_argument("ours")
    p.add_argument("ref")
    p.add_argument("--window", type=int, default=300)
    p.add_argument("--from", dest="first", type=int, default=0)
    p.add_argument("--to", dest="last", type=int, default=-1)
    p.add_argument("--from-offset", type=int, default=None,
                   help="first step = first common step + this (instead of --from)")
    p.add_argument("--tol", type=float, required=True)
    p.add_argument("--force-floor", type=float, default=0.0)
    p.add_argument("--lever", type=float, default=0.1)
    p.add_argument("--label", default="")
    a = p.parse_args()

    steps, ours, ref = common(read_thermo(a.ours), read_thermo(a.ref))
    tag = f"compare_wrench: {a.label} {a.mode}:"
    if a.from_offset is not None:
        a.first = int(steps[0]) + a.from_offset
    if a.mode in ("early", "equal"):
        if a.mode == "early":
            touching = np.nonzero(np.linalg.norm(ref[:, :3], axis=1) > 0.0)[0]
            if len(touching) == 0:
                print(f"{tag} the reference never touches the bed FAIL")
                return 2
            s0 = int(steps[touching[0]])
            sel = (steps >= s0) & (steps <= s0 + a.window)
            rng = f"steps {s0}..{s0 + a.window} (first contact {s0})"
        else:
            last = a.last if a.last >= 0 else int(steps[-1])
            sel = (steps >= a.first) & (steps <= last)
            rng = f"steps {a.first}..{last}"
        if sel.sum() < 2:
            print(f"{tag} fewer than 2 common steps in {rng} FAIL")
            return 2
        (ef, sf, nf), (et, st, nt) = rel_max(steps[sel], ours[sel], ref[sel], a.force_floor,
                                             a.force_floor * a.lever)
        ok = ef < a.tol and et < a.tol
        print(f"{tag} {rng}, {int(sel.sum())} steps, floors {a.force_floor:g} N / "
              f"{a.force_floor * a.lever:g} N m: max rel. diff force {ef:.3e} (step {sf}, |F_ref| "
              f"{nf:.4g} N), torque {et:.3e} (step {st}, |T_ref| {nt:.4g} N m); peak |F_ref| "
              f"{np.linalg.norm(ref[sel, :3], axis=1).max():.4g} N; tolerance {a.tol:g} "
              f"{'PASS' if ok else 'FAIL'}")
        return 0 if ok else 1

    last = a.last if a.last >= 0 else int(steps[-1])
    sel = (steps >= a.first) & (steps <= last)
    if sel.sum() < 10:
        print(f"{tag} fewer than 10 common steps in {a.first}..{last} FAIL")
        return 2
    mo, mr = ours[sel].mean(axis=0), ref[sel].mean(axis=0)
    ef = np.linalg.norm(mo[:3] - mr[:3]) / np.linalg.norm(mr[:3])
    # The mean torque about the centre can be close to 0 in some components (tx, tz: lateral
    # noise), so its scale is max(|<T_ref>|, lever |<F_ref>|): the torque error is measured as
    # an equivalent force error at the wheel radius when the torque itself is small.
    et = np.linalg.norm(mo[3:] - mr[3:]) / max(np.linalg.norm(mr[3:]),
                                               a.lever * np.linalg.norm(mr[:3]))
    ok = ef < a.tol and et < a.tol
    fmt = lambda v: "(" + ", ".join(f"{x:.4g}" for x in v) + ")"
    print(f"{tag} steps {a.first}..{last} ({int(sel.sum())} samples): <F> ours {fmt(mo[:3])} ref "
          f"{fmt(mr[:3])} N, rel. diff {ef:.3e}; <T> ours {fmt(mo[3:])} ref {fmt(mr[3:])} N m, "
          f"rel. diff {et:.3e}; tolerance {a.tol:g} {'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
