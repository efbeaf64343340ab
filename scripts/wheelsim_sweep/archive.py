"""wheel-sweep --archive DIR: keep the finished points' results somewhere that outlives the run
directory (a folder committed to git), and take them back on the next run.

After each point finishes (exit status 0) its small files — done.json, run.h5, rig.toml, run.log —
are copied to DIR/<WHEEL>/<SOIL>/<sSLIP>/ (run.h5 rewritten with gzip-compressed datasets: the
same groups, datasets, values and attributes in about a third of the bytes) with archived.json
beside them (the sha256 of the bed restart it ran on, the checkout's git commit, the time). At the
start of a run, every archived point whose folder in the output directory has no done.json is
copied back; the usual resume check (runner.finished: exit status, inputs hash, included files,
run.h5) then decides whether it is finished. Checkpoints, LIGGGHTS logs and beds are not kept: a
DEM bed is prepared again from its recipe, and an archived point whose bed hash differs from the
bed now in place is named (docs/sweeps.md, "Keeping finished points").
"""
import datetime
import json
import shutil
import subprocess
from pathlib import Path

from wheelsim_post import step_archive

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


def save(archive, point_dir, rel, bed_sha256, repo):
    """Copies a finished point's kept files to archive/rel, with its archived.json record."""
    dest = Path(archive) / rel
    kept = step_archive.keep(point_dir, dest, KEPT_FILES, copy=_copy)
    record = {"bed_sha256": bed_sha256, "git_commit": _git_commit(repo), "files": kept,
              "archived_utc": datetime.datetime.now(datetime.timezone.utc)
              .strftime("%Y-%m-%dT%H:%M:%SZ")}
    (dest / RECORD).write_text(json.dumps(record, indent=1) + "\n")


def archived_bed(archive, rel):
    """The bed sha256 an archived point ran on (None: not recorded or not a DEM point)."""
    try:
        return json.loads((Path(archive) / rel / RECORD).read_text()).get("bed_sha256")
    except (OSError, ValueError):
        return None
