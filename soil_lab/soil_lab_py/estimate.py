"""`soil-lab run ... --estimate`: what the lab has left to run and how long it may take, from what
this lab (its output directory and archive) already knows; runs nothing (docs/soil-lab.md "Cost
estimate"). Per run: its steps (progress.run_steps), whether it finished (a done.json here or in the
archive; its inputs are not compared: the lab does that when it runs), or was parked (the steps
done); the wall time left at a pace measured on this lab: a parked run's own last attempt (steps
from its resume to its parked checkpoint over that wall time), else the mean steps per second of
the lab's finished and parked runs on the same bed (the same particles; a plate's or box's size
moves the cost per step a little). Beds still to prepare are named (their cost is not
estimated)."""

import json
import lzma
from pathlib import Path

from wheelsim_post import step_archive

from .plan import run_dt_s
from .progress import _int, run_steps


def _json(path, xz=False):
    try:
        raw = lzma.decompress(Path(path).read_bytes()) if xz else Path(path).read_bytes()
        return json.loads(raw)
    except (OSError, ValueError, lzma.LZMAError):
        return None


def _finished(run, out, archive):
    """(where, done.json) of a finished run: 'here' (OUT) or 'archive'; None if neither."""
    for where, d in (("here", out), ("archive", archive)):
        if d is not None:
            done = _json(Path(d) / run.name / "done.json")
            if done is not None:
                return where, done
    return None


def _parked_pace(kept):
    """(steps done at the parked checkpoint, steps per second of its last attempt or None) of a
    parked run (ARCHIVE/<run>/parked/), None when nothing is parked."""
    record = step_archive.parked(kept)
    if record is None:
        return None
    done = record["step"] - record["start_step"]
    state = _json(Path(kept) / step_archive.PARKED / "checkpoints" / "state.json.xz", xz=True)
    restart = next((f for f in record.get("files", []) if f["path"].endswith(".restart")), None)
    try:
        last = state["attempts"][-1]
        steps = record["step"] - last.get("resumed_at_step", record["start_step"])
        wall = restart["mtime_unix"] - last["start_unix"]
        return done, (steps / wall if steps > 0 and wall > 0 else None)
    except (TypeError, KeyError, IndexError):
        return done, None


def lab_estimate(plan, out, archive=None):
    """The estimate's lines (without the 'soil-lab: ' prefix)."""
    lines, total_steps, total_wall, unknown = [], 0, 0.0, 0
    paces = {}   # bed -> steps/s of the lab's finished and parked runs on it
    parked = {}
    for run in plan.runs:
        found = _finished(run, out, archive)
        if found and found[1].get("wall_s") and found[1].get("steps"):
            paces.setdefault(run.bed, []).append(found[1]["steps"] / found[1]["wall_s"])
        elif not found and archive is not None:
            parked[run.name] = _parked_pace(Path(archive) / run.name)
            if parked[run.name] and parked[run.name][1]:
                paces.setdefault(run.bed, []).append(parked[run.name][1])
    for name in plan.beds:
        if not (Path(out) / "beds" / name / "done.json").is_file():
            lines.append(f"estimate: bed '{name}': to prepare here (its cost is not estimated)")
    for i, run in enumerate(plan.runs, 1):
        head = f"estimate: [{i}/{len(plan.runs)}] {run.name}"
        found = _finished(run, out, archive)
        if found:
            lines.append(f"{head}: finished before ({found[0]}; the lab compares its inputs)")
            continue
        steps = run_steps(run, run_dt_s(run, plan.soil.dt_s))
        if steps is None:
            lines.append(f"{head}: to run (length not known beforehand)")
            unknown += 1
            continue
        left, pace, how = steps, None, ""
        if parked.get(run.name) is not None:
            done, pace = parked[run.name]
            left = max(0, steps - done)
            how = f"parked with {_int(done)} of {_int(steps)} steps done"
        if pace is None and paces.get(run.bed):
            pace = sum(paces[run.bed]) / len(paces[run.bed])
        text = f"{head}: {_int(left)} steps to run" + (f" ({how})" if how else "")
        if pace:
            text += f", ~{left / pace / 60:.0f} min at {pace:.0f} steps/s"
            total_wall += left / pace
        else:
            text += ", pace unknown (no finished or parked run of this lab on its bed)"
            unknown += 1
        total_steps += left
        lines.append(text)
    lines.append(f"estimate: {_int(total_steps)} steps to run, ~{total_wall / 3600:.1f} h of wall "
                 f"time at the measured paces" + (f" + {unknown} run(s) of unknown length or pace"
                                                  if unknown else "") + "; nothing was run")
    return lines
