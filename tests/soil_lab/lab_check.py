"""The start shared by the soil lab's integration checks (check_bed_hold.py, check_kill_lab.py):
--build-dir and --work (plus the check's own options), a skip when liggghts-wheel is not built,
and an emptied work directory."""

import argparse
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
