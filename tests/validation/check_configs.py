#!/usr/bin/python3
"""Every committed sweep config of the validation cases (validation/*/sweep*.toml) still loads:
`wheel-sweep CONFIG --dry-run` (config keys and values, wheels and soils found, each point's rig
config through `wheel-rig --check`) exits 0 and names its points. Most of these configs run only
by hand, hours long, so a key renamed in wheel-sweep or a wheel dropped from the catalog would
otherwise show up sessions later. The check is shown to fail on a copy of one config with an
unknown key.

  check_configs.py --build-dir BUILD --work DIR
Exit 0 pass, 1 fail.
"""

import argparse
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SWEEP = ROOT / "scripts" / "wheel-sweep"


def dry_run(config, build, out):
    shutil.rmtree(out, ignore_errors=True)
    return subprocess.run([str(SWEEP), str(config), "--dry-run", "--build-dir", str(build),
                           "--out-dir", str(out)], capture_output=True, text=True, timeout=120)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build-dir", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    work = Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    configs = sorted(ROOT.glob("validation/*/sweep*.toml"))
    failed = 0
    if len(configs) < 3:
        print(f"FAIL: only {len(configs)} validation sweep configs found under {ROOT / 'validation'}")
        return 1
    for config in configs:
        r = dry_run(config, a.build_dir, work / "out")
        m = re.search(r"dry run: (\d+) point\(s\) to run", r.stdout + r.stderr)
        ok = r.returncode == 0 and m is not None and int(m.group(1)) > 0
        failed += not ok
        print(f"{'ok:  ' if ok else 'FAIL:'} {config.relative_to(ROOT)}: "
              f"{m.group(0) if m else (r.stdout + r.stderr).strip()[-600:]}")

    # the check can fail: one config with a key wheel-sweep does not know
    # (beside the original: its relative paths to base, deck and soil files resolve from there;
    # a dot file, which the glob above and git (.gitignore) leave alone)
    placed = configs[0].parent / ".check_configs_bad_key.toml"
    placed.write_text(configs[0].read_text().replace('terrain = "', 'terrian_typo = 1\nterrain = "', 1))
    try:
        r = dry_run(placed, a.build_dir, work / "out_bad")
    finally:
        placed.unlink()
    said = r.stdout + r.stderr
    ok = r.returncode != 0 and "terrian_typo" in said
    failed += not ok
    print(f"{'ok:  ' if ok else 'FAIL:'} a config with an unknown key is refused naming it "
          f"(exit {r.returncode}: {said.strip()[-300:]})")
    print("all checks passed" if not failed else f"{failed} check(s) failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
