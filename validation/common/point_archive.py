#!/usr/bin/python3
"""Keep a validation case's finished DEM points in git, so that a later session resumes the sweep.

A point takes up to an hour and a case a dozen; a session's work directory (runs/, not committed)
does not outlive it. This copies each finished point's small files — done.json, run.h5, rig.toml,
run.log — from a wheel-sweep output directory into a committed archive folder of the case, and
copies them back before the next run, where wheel-sweep then skips them as finished (its usual
check: done.json's inputs hash against the current inputs; a point whose inputs changed is run
again). Checkpoints, LIGGGHTS logs and beds are not kept.

    point_archive.py save    OUT_DIR ARCHIVE_DIR [--sweep CONFIG] [--bed RESTART ...]
    point_archive.py restore ARCHIVE_DIR OUT_DIR

--sweep names the beds by the sweep config's soils' `restart` (relative to the config, as
wheel-sweep reads it); --bed names one directly.

The beds are not kept either: a later session prepares them again from the same recipe (on one
rank, so bit for bit the same, docs/sweeps.md "Beds"). `save` writes archived.json beside each
new point: the sha256 of the bed restart(s) it ran on, the git commit and the time. A restored
point whose bed hash differs from today's bed is named on stderr and in the archive's beds.json:
its result came from a different preparation of the same recipe.
"""
import argparse
import datetime
import hashlib
import json
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

KEPT_FILES = ("done.json", "run.h5", "rig.toml", "run.log")
DONE = "done.json"
RECORD = "archived.json"


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def finished_points(out_dir):
    """Point directories under out_dir whose done.json says exit status 0 with a run.h5."""
    points = []
    for done in sorted(Path(out_dir).rglob(DONE)):
        d = done.parent
        if "beds" in d.relative_to(out_dir).parts:
            continue
        try:
            status = json.loads(done.read_text()).get("exit_status")
        except (OSError, ValueError):
            continue
        if status == 0 and (d / "run.h5").is_file():
            points.append(d)
    return points


def sweep_beds(config):
    """The existing bed restarts a sweep config's soils name (`restart`, relative to it)."""
    config = Path(config)
    try:
        soils = tomllib.loads(config.read_text()).get("soils", [])
    except (OSError, tomllib.TOMLDecodeError) as e:
        sys.exit(f"point_archive: cannot read sweep config '{config}': {e}")
    beds = [config.parent / s["restart"] for s in soils if isinstance(s, dict) and "restart" in s]
    return [str(b.resolve()) for b in beds if b.is_file()]


def git_commit(repo):
    try:
        return subprocess.run(["git", "-C", str(repo), "rev-parse", "HEAD"], check=True,
                              capture_output=True, text=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def save(out_dir, archive, beds):
    out_dir, archive = Path(out_dir), Path(archive)
    bed_hashes = {}
    for bed in beds:
        if not Path(bed).is_file():
            sys.exit(f"point_archive: bed restart '{bed}' does not exist")
        bed_hashes[Path(bed).name] = sha256(bed)
    commit = git_commit(Path(__file__).resolve().parent)
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    saved = kept = 0
    mismatched = []
    for d in finished_points(out_dir):
        rel = d.relative_to(out_dir)
        dest = archive / rel
        if (dest / DONE).is_file() and (dest / DONE).read_bytes() == (d / DONE).read_bytes():
            kept += 1  # archived before (restored or saved): keep its record
            record = json.loads((dest / RECORD).read_text()) if (dest / RECORD).is_file() else {}
            if record.get("bed_sha256", bed_hashes) != bed_hashes:
                mismatched.append(str(rel))
            continue
        dest.mkdir(parents=True, exist_ok=True)
        for name in KEPT_FILES:
            if (d / name).is_file():
                shutil.copy2(d / name, dest / name)
        (dest / RECORD).write_text(json.dumps(
            {"bed_sha256": bed_hashes, "git_commit": commit, "archived_utc": now,
             "files": [n for n in KEPT_FILES if (d / n).is_file()]}, indent=1) + "\n")
        saved += 1
    beds_file = archive / "beds.json"
    archive.mkdir(parents=True, exist_ok=True)
    beds_file.write_text(json.dumps({"current_bed_sha256": bed_hashes,
                                     "points_on_another_bed": mismatched}, indent=1) + "\n")
    print(f"point_archive: {saved} point(s) archived, {kept} already there, into {archive}")
    for rel in mismatched:
        print(f"point_archive: warning: {rel} ran on another preparation of the bed "
              f"(its {RECORD} names that bed's sha256)", file=sys.stderr)


def restore(archive, out_dir):
    archive, out_dir = Path(archive), Path(out_dir)
    if not archive.is_dir():
        print(f"point_archive: no archive at {archive}: nothing to restore")
        return
    restored = 0
    for done in sorted(archive.rglob(DONE)):
        rel = done.parent.relative_to(archive)
        dest = out_dir / rel
        if (dest / DONE).is_file():
            continue  # this session's own record wins
        dest.mkdir(parents=True, exist_ok=True)
        for name in KEPT_FILES:
            if (done.parent / name).is_file():
                shutil.copy2(done.parent / name, dest / name)
        restored += 1
    print(f"point_archive: {restored} finished point(s) restored from {archive} into {out_dir}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    s = sub.add_parser("save", help="copy finished points into the archive")
    s.add_argument("out_dir")
    s.add_argument("archive")
    s.add_argument("--bed", action="append", default=[], metavar="RESTART",
                   help="a bed restart the points ran on (its sha256 is recorded)")
    s.add_argument("--sweep", metavar="CONFIG",
                   help="the sweep config: its soils' bed restarts are recorded")
    r = sub.add_parser("restore", help="copy archived points into a sweep's output directory")
    r.add_argument("archive")
    r.add_argument("out_dir")
    a = ap.parse_args(argv)
    if a.command == "save":
        save(a.out_dir, a.archive, a.bed + (sweep_beds(a.sweep) if a.sweep else []))
    else:
        restore(a.archive, a.out_dir)


if __name__ == "__main__":
    main()
