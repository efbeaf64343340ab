"""What the soil lab's integration checks share (check_bed_hold.py, check_kill_lab.py,
check_stall_lab.py): the start (--build-dir and --work plus the check's own options, a skip when
liggghts-wheel is not built, an emptied work directory) and the processes a stopped lab left."""

import argparse
import os
import shutil
from pathlib import Path

SKIP = 77  #: ctest SKIP_RETURN_CODE


def start(add_options=None):
    """The parsed arguments and the emptied work directory, or None (SKIP printed) when
    liggghts-wheel is not built. add_options(parser) adds the check's own options."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--build-dir", required=True)
    ap.add_argument("--work", required=True)
    if add_options is not None:
        add_options(ap)
    a = ap.parse_args()
    if not (Path(a.build_dir) / "bin" / "liggghts-wheel").is_file():
        print("SKIP: liggghts-wheel not built")
        return None
    work = Path(a.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    return a, work


def survivors(tag):
    """{pid: command line} of the live processes (not this one) whose command line contains
    `tag` (the kill and stall checks: what a stopped lab left behind)."""
    out = {}
    for name in os.listdir("/proc"):
        if not name.isdigit() or int(name) == os.getpid():
            continue
        try:
            cmd = Path(f"/proc/{name}/cmdline").read_bytes().replace(b"\0", b" ").decode(
                errors="replace")
            state = Path(f"/proc/{name}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if tag in cmd and state != "Z":
            out[int(name)] = cmd
    return out
