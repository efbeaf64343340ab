"""The bed-hold check (docs/soil-bins.md "The bed-hold check"): does a prepared bed hold itself
under the contact settings its tests and wheel runs use? `inputs/in.bedhold` leaves the bed alone
for a while and prints its centre of mass height at the start and after each quarter; this module
reads those lines and judges them. soil-lab and wheel-sweep run it on every bed they prepare.

A bed that compacts uniformly from the floor gains in bulk density the fraction its centre of mass
sinks by (the settlement), so the limit is the calibration's bulk-density tolerance.
"""

import re

DECK = "in.bedhold"  #: in inputs/
DEFAULT_HOLD_S = 0.2  #: [s] how long a bed is left alone
SETTLE_LIMIT = 0.03  #: a larger settlement (or rise) stops the tool: not the bed prepared
SETTLE_NOTE = 0.01  #: a larger one is reported as "settles, within the limit"


class BedHoldError(RuntimeError):
    """in.bedhold's output is incomplete or impossible; the message names its log."""


def parse(text, log="the log"):
    """in.bedhold's printed lines as the check's result: the hold's length [s], the centre of mass
    and the highest grain at its start and end [m], and how far the centre of mass sank as a
    fraction of its starting height, over the whole hold (`settlement`) and over its last quarter
    (`settlement_last_quarter`, relative to the height before that quarter), and the speed it
    sank at over that quarter (`sink_rate_m_s`, > 0 sinking: a bed that creeps at rest, e.g. on
    `cdt`, keeps that up)."""
    lines = [m.group(1) for m in re.finditer(r"^bedhold: (.*)$", text, re.M)]
    if len(lines) != 5:
        raise BedHoldError(f"{DECK} printed {len(lines)} of its 5 lines (log: {log})")
    try:
        rows = [dict(kv.split("=", 1) for kv in line.split()) for line in lines]
        z = [float(r["zcm"]) for r in rows]
        t = [float(r["t"]) for r in rows]
        ztop = [float(r["ztop"]) for r in rows]
    except (ValueError, KeyError) as e:
        raise BedHoldError(f"{DECK}: a line not of the form 'bedhold: quarter=Q t=T zcm=Z "
                           f"ztop=Z' ({type(e).__name__}: {e}) (log: {log})") from None
    if not all(v > 0 for v in z):
        raise BedHoldError(f"{DECK}: a centre of mass at or below the floor, {z} m (log: {log})")
    if not all(b > a for a, b in zip(t, t[1:])):
        raise BedHoldError(f"{DECK}: times {t} s do not increase (log: {log})")
    return {"hold_s": t[-1], "zcm_start_m": z[0], "zcm_end_m": z[-1],
            "ztop_start_m": ztop[0], "ztop_end_m": ztop[-1],
            "settlement": 1.0 - z[-1] / z[0], "settlement_last_quarter": 1.0 - z[-1] / z[-2],
            "sink_rate_m_s": (z[-2] - z[-1]) / (t[-1] - t[-2])}


def describe(r):
    """One line on a result of parse: the centre of mass before and after, in m and %."""
    rate = r.get("sink_rate_m_s")  # (not in records written before 2026-11-29, 22:00)
    return (f"centre of mass {r['zcm_start_m']:.5g} -> {r['zcm_end_m']:.5g} m "
            f"({-100 * r['settlement']:+.2f} %) over {r['hold_s']:.3g} s, last quarter "
            f"{-100 * r['settlement_last_quarter']:+.3f} %"
            + ("" if rate is None else f" (sinking {1e3 * rate:.2g} mm/s)"))


def failure(r, bed, log, settled=True):
    """The error message when bed `bed` (its name, for the message) settled, or rose, by more
    than SETTLE_LIMIT, else None. `settled`: in.soilbin's verdict on the bed's preparation (its
    printed `settled`); a bed whose settling was cut off is told so, not blamed on its settings."""
    if abs(r["settlement"]) <= SETTLE_LIMIT:
        return None
    if r["settlement"] < 0:
        return (f"bed '{bed}' does not hold under the soil's test settings: it rises, "
                f"{describe(r)}, by more than the {100 * SETTLE_LIMIT:.0f} % a bed may move (its "
                f"bulk density would be off by as much as the calibration's tolerance): the test "
                f"settings push its grains apart (e.g. a cohesion or overlap the preparation did "
                f"not have). Prepare it with settings it can hold (docs/soils.md \"Preparing the "
                f"bed with other contact settings\"; log: {log})")
    if not settled:
        return (f"bed '{bed}' had not settled when it was prepared (in.soilbin: settled = 0, its "
                f"settling cut off by max_settle_time) and is still falling: {describe(r)}, more "
                f"than the {100 * SETTLE_LIMIT:.0f} % a bed may settle. Give it more settling "
                f"time, or switch the check off (--bed-hold 0) for a bed meant to be unsettled "
                f"(log: {log})")
    return (f"bed '{bed}' does not hold under the soil's test settings: {describe(r)}, more "
            f"than the {100 * SETTLE_LIMIT:.0f} % a bed may settle (its bulk density would be off "
            f"by as much as the calibration's tolerance): its skeleton rests on contact settings "
            f"the tests take away. Prepare it with settings it can hold (docs/soils.md \"Preparing "
            f"the bed with other contact settings\"; log: {log})")


def verdict(r):
    """'holds' or 'settles (rises), within the limit' (beyond SETTLE_NOTE) for a result that
    passed."""
    if r["settlement"] > SETTLE_NOTE:
        return "settles, within the limit"
    return "rises, within the limit" if r["settlement"] < -SETTLE_NOTE else "holds"
