"""Finished steps kept outside a work directory that may not outlive its session: one step is a
directory whose done.json, written last, says it finished (a wheel-sweep point, a soil-lab test
run). Used by `wheel-sweep --archive` (scripts/wheelsim_sweep/archive.py) and `soil-lab run
--archive` (soil_lab/soil_lab_py/runner.py); whether a restored step counts as finished is their
own resume check's decision."""

import shutil
from pathlib import Path

DONE = "done.json"


def holds(kept, step):
    """True when the directory `kept` holds the step's done.json byte for byte."""
    mine, theirs = Path(step) / DONE, Path(kept) / DONE
    return theirs.is_file() and mine.is_file() and theirs.read_bytes() == mine.read_bytes()


def restore(kept, step, names=None):
    """Copies the files of `kept` (those of `names`, else all) into `step` when `kept` holds a
    done.json and `step` none; True if it did."""
    kept, step = Path(kept), Path(step)
    if not (kept / DONE).is_file() or (step / DONE).exists():
        return False
    step.mkdir(parents=True, exist_ok=True)
    for f in kept.iterdir():
        if f.is_file() and (names is None or f.name in names):
            shutil.copy2(f, step / f.name)
    return True


def keep(step, kept, names=None, copy=shutil.copy2):
    """Copies the files of `step` (those of `names`, else all) into `kept` with `copy(src, dest)`,
    done.json last so that a half-copied step does not look finished; returns the names copied."""
    step, kept = Path(step), Path(kept)
    kept.mkdir(parents=True, exist_ok=True)
    files = sorted((f for f in step.iterdir()
                    if f.is_file() and (names is None or f.name in names)),
                   key=lambda f: f.name == DONE)
    for f in files:
        copy(f, kept / f.name)
    return [f.name for f in files]
