"""wheel-sweep --archive DIR: keep the finished points' results somewhere that outlives the run
directory (a folder committed to git), and take them back on the next run.

After each point finishes (exit status 0) its small files — done.json, run.h5, rig.toml, run.log —
are copied to DIR/<WHEEL>/<SOIL>/<sSLIP>/ (run.h5 rewritten with gzip-compressed datasets: the
same groups, datasets, values and attributes in about a third of the bytes) with archived.json
beside them (the sha256 of the bed restart it ran on, the checkout's git commit, the time). At the
start of a run, every archived point whose folder in the output directory has no done.json is
copied back; the usual resume check (runner.finished: exit status, inputs hash, included files,
run.h5) then decides whether it is finished. LIGGGHTS logs and beds are not kept: a DEM bed is
prepared again from its recipe, and an archived point whose bed hash differs from the bed now in
place is named (docs/sweeps.md, "Keeping finished points").

`wheel-sweep --park` keeps an unfinished DEM point's newest complete checkpoint pair with its
partial run file in DIR/<WHEEL>/<SOIL>/<sSLIP>/parked/ (step_archive.park), with the sha256 and
the .vars of the bed it runs on in parked.json, and the next run copies it back into a point folder
that has none, so that the point goes on from there on another machine without its bed being
poured again (docs/sweeps.md, "Parking a stopped point").
"""
import datetime
import json
import lzma
import shutil
import subprocess
from pathlib import Path

from wheelsim_post import cosim_checkpoint, step_archive

KEPT_FILES = ("done.json", "run.h5", "rig.toml", "run.log")
RECORD = "archived.json"


def _git_commit(repo):
    try:
        return subprocess.run(["git", "-C", str(repo), "rev-parse", "HEAD"], check=True,
                              capture_output=True, text=True, timeout=30).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def restore(archive, out_dir, reldirs):
    """Copies each archived point of `reldirs` whose output folder has no done.json back into
    out_dir; returns the reldirs restored."""
    return [rel for rel in reldirs
            if step_archive.restore(Path(archive) / rel, Path(out_dir) / rel, KEPT_FILES)]


def compressed_copy(src, dest):
    """Writes the HDF5 file src to dest with every dataset of 64 or more elements gzip-compressed
    (level 6, byte shuffle); groups, values, dtypes and attributes as they are."""
    import h5py  # only archiving needs it

    tmp = Path(f"{dest}.part")
    with h5py.File(src, "r") as fin, h5py.File(tmp, "w") as fout:
        fout.attrs.update(fin.attrs)

        def copy(name, obj):
            if isinstance(obj, h5py.Group):
                fout.require_group(name).attrs.update(obj.attrs)
                return
            big = obj.shape != () and obj.size >= 64
            out = fout.create_dataset(name, data=obj[()], dtype=obj.dtype,
                                      **(dict(compression="gzip", compression_opts=6,
                                              shuffle=True) if big else {}))
            out.attrs.update(obj.attrs)

        fin.visititems(copy)
    tmp.replace(dest)


def _copy(src, dest):
    (compressed_copy if src.name == "run.h5" else shutil.copy2)(src, dest)


def _utc_now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


def save(archive, point_dir, rel, bed_sha256, repo):
    """Copies a finished point's kept files to archive/rel, with its archived.json record; a
    parked checkpoint of the point is removed."""
    dest = Path(archive) / rel
    kept = step_archive.keep(point_dir, dest, KEPT_FILES, copy=_copy)
    record = {"bed_sha256": bed_sha256, "git_commit": _git_commit(repo), "files": kept,
              "archived_utc": _utc_now()}
    (dest / RECORD).write_text(json.dumps(record, indent=1) + "\n")
    step_archive.drop_parked(dest)


# ---- parked checkpoints (wheel-sweep --park) -----------------------------------------------------
CHECKPOINTS = Path("cosim") / "checkpoints"   # in a point folder (scripts/wheel-cosim --work cosim)


def newest_checkpoint(point_dir):
    """The step of the newest complete checkpoint in a point's cosim/checkpoints (None: none)."""
    return cosim_checkpoint.newest(Path(point_dir) / CHECKPOINTS)


def steps_done(point_dir, archive=None, rel=None):
    """The rig steps an unfinished point will resume from: its newest complete checkpoint in
    point_dir, else the one parked in archive/rel/parked/ (xz); 0 without either."""
    step = newest_checkpoint(point_dir)
    try:
        if step is not None:
            text = (Path(point_dir) / CHECKPOINTS / cosim_checkpoint.RIG.format(s=step)).read_text()
        elif archive is not None:
            record = step_archive.parked(Path(archive) / rel)
            if record is None:
                return 0
            name = str(CHECKPOINTS / cosim_checkpoint.RIG.format(s=record["step"])) + ".xz"
            text = lzma.decompress((Path(archive) / rel / step_archive.PARKED / name)
                                   .read_bytes()).decode()
        else:
            return 0
    except (OSError, KeyError, lzma.LZMAError, UnicodeDecodeError):
        return 0
    return cosim_checkpoint.rig_steps(text) or 0


def _snapshot_h5(src, dest):
    """Copies a run file the rig may be committing to: each commit replaces it by rename(2)
    (docs/hdf5-layout.md), so the copy read from one open file is one complete commit; checked
    to open and read (every dataset)."""
    import h5py  # only parking needs it

    shutil.copy2(src, dest)
    try:
        with h5py.File(dest, "r") as f:
            f.visititems(lambda name, obj: obj[()] if isinstance(obj, h5py.Dataset) else None)
    except (OSError, ValueError, RuntimeError, KeyError) as e:
        raise OSError(f"{src}: its copy does not read back ({e})") from None


def park(archive, point_dir, rel, part_file, bed_sha256, repo, extra=None, tries=5):
    """Parks an unfinished point's newest complete checkpoint pair and partial run file in
    archive/rel/parked/, its record naming the bed (bed_sha256 {restart name: sha256}) and holding
    `extra` too (runner.Runner.park: the bed's .vars, the point's inputs); returns (step, bytes
    written), (None, 0) without a checkpoint, or (step, 0) when that step is parked there
    already. The point may be running: when a file of
    the pair is removed meanwhile (each side keeps its newest two), the newest pair is taken
    again, up to `tries` times."""
    point_dir = Path(point_dir)
    kept = Path(archive) / rel
    for attempt in range(tries):
        step = newest_checkpoint(point_dir)
        if step is None or not (point_dir / part_file).is_file():
            return None, 0
        before = step_archive.parked(kept)
        if before is not None and before.get("step") == step:
            return step, 0
        files = [part_file] + [str(CHECKPOINTS / h.format(s=step))
                               for h in (cosim_checkpoint.RIG,) + cosim_checkpoint.LIGGGHTS]
        try:
            info = cosim_checkpoint.info(point_dir / CHECKPOINTS, step)
            record = {"step": step, "time_s": float(info.get("time", "nan")),
                      "inputs_hash": info.get("inputs_hash", ""),
                      "bed_sha256": bed_sha256, "git_commit": _git_commit(repo)}
            record.update(extra or {})
            written = step_archive.park(point_dir, kept, files, record,
                                        snapshot={part_file: _snapshot_h5})
            return step, written
        except FileNotFoundError:
            if attempt == tries - 1:
                raise


def unpark(archive, point_dir, rel):
    """Copies a parked checkpoint back into a point folder that has no checkpoint of its own
    (a new machine); returns its record, else None."""
    if newest_checkpoint(point_dir) is not None:
        return None  # this machine's own checkpoints: at least as new as what was parked from them
    return step_archive.unpark(Path(archive) / rel, point_dir)


def archived_bed(archive, rel):
    """The bed sha256 an archived point ran on (None: not recorded or not a DEM point)."""
    try:
        return json.loads((Path(archive) / rel / RECORD).read_text()).get("bed_sha256")
    except (OSError, ValueError):
        return None
