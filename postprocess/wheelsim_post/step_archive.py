"""Finished steps kept outside a work directory that may not outlive its session: one step is a
directory whose done.json, written last, says it finished (a wheel-sweep point, a soil-lab test
run). Used by `wheel-sweep --archive` (scripts/wheelsim_sweep/archive.py) and `soil-lab run
--archive` (soil_lab/soil_lab_py/runner.py); whether a restored step counts as finished is their
own resume check's decision.

An unfinished step can be *parked* too: the files it needs to go on from its newest checkpoint
(chosen by the caller) are copied, xz-compressed, into KEPT/parked/ with parked.json written last,
so that a step hours long can go on on another machine (docs/sweeps.md "Parking a stopped point").
Whether the restored checkpoint is taken is again the caller's resume check's decision."""

import datetime
import json
import lzma
import os
import shutil
from pathlib import Path

DONE = "done.json"
PARKED = "parked"            # KEPT/parked/: an unfinished step's checkpoint
PARKED_RECORD = "parked.json"
XZ_PRESET = 1                # a LIGGGHTS restart: fast (tens of MB/s), most of preset 6's ratio


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


def _xz(src, dest):
    with open(src, "rb") as fin, lzma.open(dest, "wb", preset=XZ_PRESET) as fout:
        shutil.copyfileobj(fin, fout, 1 << 20)


def _unxz(src, dest):
    tmp = Path(f"{dest}.unparking")
    with lzma.open(src, "rb") as fin, open(tmp, "wb") as fout:
        shutil.copyfileobj(fin, fout, 1 << 20)
    tmp.replace(dest)


def parked(kept):
    """The parked.json record of KEPT/parked/ ({"files": [...], ...}), None when nothing (complete)
    is parked there."""
    try:
        return json.loads((Path(kept) / PARKED / PARKED_RECORD).read_text())
    except (OSError, ValueError):
        return None


def _stage(step, relpaths, snapshot):
    """Takes the files to park into STEP/.parking/ at once: hard links (a file the running step
    removes meanwhile, an older checkpoint, stays readable there), else copies, and the
    `snapshot` files by their copy function. Returns the staging directory."""
    stage = step / ".parking"
    shutil.rmtree(stage, ignore_errors=True)
    for rel in relpaths:
        dest = stage / rel
        dest.parent.mkdir(parents=True, exist_ok=True)
        if snapshot and rel in snapshot:
            continue  # after the links: they are the checkpoint the snapshot must not predate
        try:
            os.link(step / rel, dest)
        except FileNotFoundError:
            shutil.rmtree(stage, ignore_errors=True)
            raise
        except OSError:
            shutil.copy2(step / rel, dest)  # a filesystem without hard links
    for rel in relpaths:
        if snapshot and rel in snapshot:
            snapshot[rel](step / rel, stage / rel)
            shutil.copystat(step / rel, stage / rel)
    return stage


def park(step, kept, relpaths, record, snapshot=None):
    """Copies the files `relpaths` (relative to `step`) of an unfinished step into KEPT/parked/,
    each xz-compressed (name + ".xz"), with parked.json (`record` plus the time and the file list, their
    sizes and modification times, given back on unparking) written last; an earlier parked copy is
    replaced only once the new one is complete. The files are first hard-linked together
    (_stage), so that a running step removing one meanwhile does not matter; `snapshot` maps a
    relpath to `copy(src, dest)`, which takes a file that may change while it is read (a run file
    being committed) to a consistent copy, after the others. FileNotFoundError: a file was gone
    before it could be linked (the caller picks the newest checkpoint again). Returns the bytes
    written."""
    step, kept = Path(step), Path(kept)
    stage = _stage(step, relpaths, snapshot)
    tmp, final = kept / f"{PARKED}.part", kept / PARKED
    shutil.rmtree(tmp, ignore_errors=True)
    files, written = [], 0
    try:
        for rel in relpaths:
            dest = tmp / f"{rel}.xz"
            dest.parent.mkdir(parents=True, exist_ok=True)
            _xz(stage / rel, dest)
            st = (stage / rel).stat()
            files.append({"path": rel, "bytes": st.st_size, "xz_bytes": dest.stat().st_size,
                          "mtime_unix": st.st_mtime})
            written += dest.stat().st_size
    finally:
        shutil.rmtree(stage, ignore_errors=True)
    parked_utc = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    (tmp / PARKED_RECORD).write_text(
        json.dumps({**record, "parked_utc": parked_utc, "files": files}, indent=1) + "\n")
    old = kept / f"{PARKED}.old"
    shutil.rmtree(old, ignore_errors=True)
    if final.exists():
        final.rename(old)
    tmp.rename(final)
    shutil.rmtree(old, ignore_errors=True)
    return written


def unpark(kept, step):
    """Decompresses the parked files of KEPT into `step` when KEPT holds a complete parked copy
    and neither KEPT nor `step` a done.json; returns its record, else None."""
    kept, step = Path(kept), Path(step)
    record = parked(kept)
    if record is None or (kept / DONE).is_file() or (step / DONE).exists():
        return None
    for f in record["files"]:
        dest = step / f["path"]
        dest.parent.mkdir(parents=True, exist_ok=True)
        _unxz(kept / PARKED / f"{f['path']}.xz", dest)
        if "mtime_unix" in f:  # soil-lab dates a checkpoint's wall time by its file's mtime
            os.utime(dest, (f["mtime_unix"], f["mtime_unix"]))
    return record


def drop_parked(kept):
    """Removes KEPT's parked copy (the step finished, or runs from scratch)."""
    for name in (PARKED, f"{PARKED}.part", f"{PARKED}.old"):
        shutil.rmtree(Path(kept) / name, ignore_errors=True)
