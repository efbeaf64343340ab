"""Where a run's recorded positions lie in LIGGGHTS' box (docs/hdf5-layout.md, `wheel/position`).

In a coupled run the rig records x and y from the wheel's start in the box (z is the box's); a
`--kinematic` run records the box frame itself. To place the wheel in the bin (its far wall, a
surface profile) add the start: box x = recorded x + origin_x. Sources, in order:

1. ``/parameters/coupling/origin_x`` (wheel-rig records it since 2026-12-01);
2. for an earlier rig-driven coupled run (``coupling/start_step`` and a ``phase`` observable):
   the ``-var x0 V`` of ``/parameters/liggghts/extra_args``, else the ``variable x0 index V`` line
   of the deck ``/parameters/liggghts/deck`` if that file is still there (deck_files.deck_variable,
   as LIGGGHTS resolves it; the decks' x0 is the fix's origin, where the rig starts the wheel);
3. a run that is not coupled (SCM, flat ground) has no box: 0.

Otherwise the origin is unknown (None).
"""

import shlex

from .deck_files import deck_variable

ORIGIN_X_PARAMETER = "coupling/origin_x"


def origin_x(run):
    """(origin [m] or None, where it came from) for an open RunFile."""
    recorded = run.parameter(ORIGIN_X_PARAMETER)
    if recorded is not None:
        return float(recorded), f"/parameters/{ORIGIN_X_PARAMETER}"
    if not run.has_parameter("coupling/start_step"):
        return 0.0, "not a coupled run"
    if not run.has_observable("phase"):  # --kinematic: the box frame itself
        return 0.0, "a --kinematic run (box frame)"
    args = shlex.split(run.parameter_text("liggghts/extra_args", "") or "")
    try:
        return (float(deck_variable(run.parameter_text("liggghts/deck"), "x0", args)),
                "x0 of /parameters/liggghts/deck run with /parameters/liggghts/extra_args")
    except (TypeError, ValueError):
        return None, "unknown (no coupling/origin_x, no x0 given, deck not found)"
