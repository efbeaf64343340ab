#!/usr/bin/python3
"""The contact-model combination liggghts-wheel compiles itself against LIGGGHTS' generic class
(liggghts_fix/precompiled_contact_models.h; docs/dem-performance.md "Precompiled contact models").

Prepares the same soil bin (inputs/in.soilbin, settling for a fixed simulated time) alternately
with the registration (precompiled) and with WHEELSIM_GENERIC_CONTACT_MODELS=1 (LIGGGHTS' generic
class), `--pairs` times each, and prints per run the LIGGGHTS pair time and loop time (sums over
the deck's runs, from its log) and the process's CPU time, then the medians and the ratios
generic / precompiled, against the reference LIGGGHTS states for its generic class ("increasing
runtime by up to 20 %"). Also checks that every pair of runs wrote identical restart files.

  bench_contact_models.py --exe build/bin/liggghts-wheel --inputs inputs --work DIR \
      [--soil dry_sand] [--bin-length 0.4] [--bin-width 0.2] [--fill-height 0.12] \
      [--settle-time 0.6] [--pairs 3]

The printout (also WORK/result.txt) names the git revision, the command and the machine with its
load average: time it on idle cores, or say what else ran (CPU-time ratios suffer less from a
loaded machine than wall-time ratios, but still suffer).
"""

import argparse
import filecmp
import os
import platform
import re
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

from liggghts_log_path import loops  # the shared parser of LIGGGHTS' "Loop time" lines
PAIR_RE = re.compile(r"^Pair  time \(%\) = ([0-9.eE+-]+)", re.M)
RESULT_RE = re.compile(r"^soilbin: ([a-z_]+) = (.*)$", re.M)
ENV = "WHEELSIM_GENERIC_CONTACT_MODELS"


def run_bed(a, mode, out):
    """One bed preparation; returns dict(pair, loop, cpu, wall, particles, steps, restart)."""
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    env.pop(ENV, None)
    if mode == "generic":
        env[ENV] = "1"
    cmd = [str(Path(a.exe).resolve()), "-in", str(Path(a.inputs).resolve() / "in.soilbin"), "-echo", "none", "-log",
           "log.soilbin", "-var", "inputs_dir", str(Path(a.inputs).resolve()), "-var", "out_dir",
           ".", "-var", "restart_file", "./bed.restart", "-var", "soil", a.soil,
           "-var", "bin_length", str(a.bin_length), "-var", "bin_width", str(a.bin_width),
           "-var", "fill_height", str(a.fill_height), "-var", "max_settle_time",
           str(a.settle_time), "-var", "check_time", "0.05", "-var", "ke_threshold", "1e-30"]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    res = subprocess.run(cmd, cwd=out, env=env, capture_output=True, text=True)
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if res.returncode != 0:
        sys.exit(f"bench: {mode} run failed ({res.returncode}) in {out}:\n{res.stdout[-2000:]}"
                 f"{res.stderr[-2000:]}")
    banner_ok = ("0 contact-model" in res.stdout) == (mode == "generic")
    if not banner_ok:
        sys.exit(f"bench: {mode} run: liggghts-wheel's banner does not match the mode "
                 f"(is this build's registration working?):\n{res.stdout[:500]}")
    logs = "".join(p.read_text() for p in sorted(out.glob("log.soilbin*")))
    runs = loops(logs)
    result = dict(RESULT_RE.findall(res.stdout))
    return {
        "pair": sum(float(x) for x in PAIR_RE.findall(logs)),
        "loop": sum(r.seconds for r in runs),
        "cpu": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
        "wall": wall,
        "particles": int(result.get("particles", "0")),
        "steps": int(result.get("final_step", "0")),
        "restart": out / "bed.restart",
    }


def git_revision(root):
    try:
        return subprocess.run(["git", "-C", str(root), "rev-parse", "--short=12", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", required=True, help="liggghts-wheel")
    ap.add_argument("--inputs", required=True, help="the inputs/ folder")
    ap.add_argument("--work", required=True, help="work folder (created)")
    ap.add_argument("--soil", default="dry_sand", help="a soil of the precompiled combination")
    ap.add_argument("--bin-length", type=float, default=0.40)
    ap.add_argument("--bin-width", type=float, default=0.20)
    ap.add_argument("--fill-height", type=float, default=0.12)
    ap.add_argument("--settle-time", type=float, default=0.6, help="simulated seconds of settling")
    ap.add_argument("--pairs", type=int, default=3, help="runs of each kind, interleaved")
    a = ap.parse_args()
    if a.pairs < 1:
        ap.error(f"--pairs {a.pairs}: expected at least 1")
    work = Path(a.work)
    lines = [f"bench_contact_models: git {git_revision(Path(a.inputs).resolve().parent)}, "
             f"{platform.node()}, {os.cpu_count()} cores, load average at start "
             f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}",
             "command: " + " ".join(sys.argv)]
    print("\n".join(lines), flush=True)
    runs = {"precompiled": [], "generic": []}
    for i in range(a.pairs):
        for mode in ("precompiled", "generic"):
            r = run_bed(a, mode, work / f"{mode}_{i + 1}")
            runs[mode].append(r)
            line = (f"  {mode:11s} run {i + 1}: {r['particles']} spheres, {r['steps']} steps: pair "
                    f"{r['pair']:.2f} s, loop {r['loop']:.2f} s, CPU {r['cpu']:.2f} s, wall "
                    f"{r['wall']:.2f} s")
            print(line, flush=True)
            lines.append(line)
        same = filecmp.cmp(runs["precompiled"][i]["restart"], runs["generic"][i]["restart"],
                           shallow=False)
        line = f"  pair {i + 1}: restart files {'identical' if same else 'DIFFER'}"
        print(line, flush=True)
        lines.append(line)
    lines.append("medians, generic / precompiled (LIGGGHTS' own statement for its generic class: "
                 "'increasing runtime by up to 20 %', i.e. up to 1.20):")
    for key in ("pair", "loop", "cpu", "wall"):
        p = statistics.median(r[key] for r in runs["precompiled"])
        g = statistics.median(r[key] for r in runs["generic"])
        lines.append(f"  {key:5s} {g:8.2f} / {p:8.2f} s = {g / p:.3f}")
    lines.append(f"load average at end {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print("\n".join(lines[-6:]))
    (work / "result.txt").write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
