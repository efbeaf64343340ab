#!/usr/bin/python3
"""scripts/wheel-cosim's command line (docs/coupled-runs.md, "Exit codes"): --help and --version
exit 0, bad usage exits 2 with one line naming the bad flag (and the nearest valid one), before
anything is started; a missing mesh and a rig config that fails wheel-rig --check too.

  check_wheel_cosim_cli.py --cosim scripts/wheel-cosim --build BUILD_DIR
Exit 0 pass, 1 fail.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cosim", required=True)
    ap.add_argument("--build", required=True)
    a = ap.parse_args()
    env = dict(os.environ, WHEELSIM_BUILD_DIR=a.build)
    failures = []

    def run(*args):
        r = subprocess.run([a.cosim, *args], capture_output=True, text=True, env=env, timeout=30)
        return r.returncode, r.stdout, r.stderr

    def expect(args, code, stream_pattern, which="stderr"):
        rc, out, err = run(*args)
        text = out if which == "stdout" else err
        ok = rc == code and re.search(stream_pattern, text) is not None
        if code == 2:
            ok = ok and len(err.strip().splitlines()) == 1
        print(f"{'ok  ' if ok else 'FAIL'} wheel-cosim {' '.join(args)}: exit {rc}, "
              f"{which} {text.strip()[:160]!r}")
        if not ok:
            failures.append(args)

    expect(["--help"], 0, r"(?s)--rig RIG\.toml.*--checkpoint-every-seconds", "stdout")
    expect(["-h"], 0, r"Docs: docs/coupled-runs\.md", "stdout")
    expect(["--version"], 0, r"^wheel-cosim \d+\.\d+\.\d+", "stdout")
    expect(["--verison"], 2, r"unknown option '--verison' \(did you mean '--version'\?\)")
    expect(["--rig", "r.toml", "--soilfile", "s.in"], 2,
           r"unknown option '--soilfile' \(did you mean '--soil-file'\?\)")
    expect(["--rig"], 2, r"--rig: expects a value")
    expect(["--np", "--rig", "r.toml"], 2, r"--np: expects a value")
    expect(["--parameter", "novalue"], 2, r"--parameter: expected KEY=VALUE")
    expect([], 2, r"--rig: rig config '' not found")
    # Before anything starts: the mesh must exist, and the rig config passes wheel-rig --check
    # (a misspelt key is named with its line, not found once LIGGGHTS has read the bed).
    with tempfile.TemporaryDirectory() as tmp:
        t = Path(tmp)
        for f in ("bed.restart", "bed.restart.vars", "deck.in", "wheel.stl"):
            (t / f).write_text("")
        (t / "rig.toml").write_text("[wheel]\nmas = 2.0\n")
        files = ["--bed", str(t / "bed.restart"), "--deck", str(t / "deck.in"), "--work",
                 str(t / "work")]
        expect(["--rig", str(t / "rig.toml"), *files, "--mesh", str(t / "none.stl")], 2,
               r"--mesh: wheel mesh '.*none\.stl' not found")
        expect(["--rig", str(t / "rig.toml"), *files, "--mesh", str(t / "wheel.stl")], 2,
               r"--rig: wheel-rig: .*rig\.toml:2: unknown key 'wheel\.mas'; did you mean "
               r"'wheel\.mass'\?")
        # --bed-sha256 (a resume without the bed restart, docs/coupled-runs.md)
        rig = ["--rig", str(t / "rig.toml"), "--deck", str(t / "deck.in"), "--work", str(t / "work")]
        expect([*rig, "--bed", str(t / "gone.restart"), "--resume", "--bed-sha256", "xyz"], 2,
               r"--bed-sha256: expected a sha256 \(64 lowercase hex digits\), got 'xyz'")
        expect([*rig, "--bed", str(t / "gone.restart"), "--bed-sha256", "0" * 64], 2,
               r"--bed-sha256: only with --resume")
        expect([*rig, "--bed", str(t / "gone.restart")], 2, r"--bed: bed restart '.*gone\.restart' not found")
        if (t / "work").exists():
            print("FAIL the rejected runs made their work directory")
            failures.append(["work directory"])
    if failures:
        print(f"{len(failures)} failed")
        return 1
    print("all passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
