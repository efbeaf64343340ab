"""The machine's particle-step rate for the cost estimate: measured once by `wheel-sweep
--measure-rate`, cached per host, CPU model and liggghts-wheel version. Reference:
docs/sweeps.md, "Cost estimate".

The cache is a TOML file (`cache_path()`: $WHEELSIM_RATE_CACHE, else
$XDG_CACHE_HOME/wheelsim/dem_rate.toml, else ~/.cache/wheelsim/dem_rate.toml) with one
[[rate]] table per host and CPU model. An entry of another commit of the same liggghts-wheel
release is used and the estimate says so; an entry of another release is stale: the estimate then
uses the defaults below and says so.

The benchmark (`measure`): prepares a ci bed of BENCH_BIN (about 14 000 spheres) with
inputs/in.soilbin on one rank (the bed rate: particle-steps per second of LIGGGHTS' loop while
it inserts and settles), then runs rate_bench.in (fix wheel/cosim with prescribed motion, the
soil's contact model, BENCH_STEPS steps) on one rank and on two: rate_per_rank from the np-1
loop time, efficiency_np2 = speed-up / 2, startup_s = the np-1 run's wall time outside its loop.
About a CPU-minute; the load average at the time is recorded (a shared machine measures low).
"""

import datetime
import os
import platform
import shutil
import subprocess
import tempfile
import time
import tomllib
from pathlib import Path

import tomli_w
from wheelsim_post import liggghts_log, mpi_launch

from . import watchdog
from .estimate import Rate, EstimateError

# Defaults without a measurement: issue 12's numbers on this project's 2-core machine (LIGGGHTS
# with fix wheel/cosim, 11 624 spheres: 2.9 M particle-steps/s on one rank, 1.7x on two), and a
# startup of a few seconds (launch, read the bed, write the run file).
DEFAULT = {"rate_per_rank": 2.9e6, "efficiency_np2": 0.85, "startup_s": 3.0,
           "bed_rate_per_rank": 2.9e6}
BENCH_SOIL = "ci"
BENCH_BIN = {"bin_length": 0.30, "bin_width": 0.15, "fill_height": 0.04, "check_time": 0.02,
             "max_settle_time": 0.2}
BENCH_STEPS = 2000
KEYS = ("host", "cpu", "liggghts_wheel")


def cache_path():
    if os.environ.get("WHEELSIM_RATE_CACHE"):
        return Path(os.environ["WHEELSIM_RATE_CACHE"])
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "wheelsim" / "dem_rate.toml"


def cpu_model():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def liggghts_version(liggghts):
    """`liggghts-wheel --version` (e.g. 'liggghts-wheel 0.1.0 (git 968c6fe30faf)')."""
    try:
        r = subprocess.run([str(liggghts), "--version"], capture_output=True, text=True,
                           timeout=30, stdin=subprocess.DEVNULL)
    except (OSError, subprocess.SubprocessError) as e:
        raise EstimateError(f"{liggghts} --version failed: {e}")
    line = (r.stdout.strip().splitlines() or [""])[-1]
    if r.returncode != 0 or not line:
        raise EstimateError(f"{liggghts} --version exited {r.returncode}")
    return line


def release(liggghts_version_text):
    """The release part of a `liggghts-wheel --version` line, without its commit:
    'liggghts-wheel 0.1.0 (git 968c6fe30faf)' -> 'liggghts-wheel 0.1.0'."""
    return liggghts_version_text.split(" (git", 1)[0].strip()


def machine_key(liggghts_version_text):
    return {"host": platform.node(), "cpu": cpu_model(), "liggghts_wheel": liggghts_version_text}


def read_cache(path):
    """The cache's [[rate]] entries ([] when the file is missing). A damaged file is an
    EstimateError naming it."""
    try:
        with open(path, "rb") as f:
            doc = tomllib.load(f)
    except FileNotFoundError:
        return []
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise EstimateError(f"rate cache {path}: cannot be read ({e}); delete it or re-measure "
                            "with --measure-rate")
    entries = doc.get("rate", [])
    if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
        raise EstimateError(f"rate cache {path}: 'rate' must be an array of tables")
    return entries


def write_cache(path, entry):
    """Stores `entry`, replacing the entry of the same host and CPU (any version)."""
    path = Path(path)
    entries = [e for e in read_cache(path)
               if (e.get("host"), e.get("cpu")) != (entry["host"], entry["cpu"])]
    entries.append(entry)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    text = ("# wheel-sweep --measure-rate: LIGGGHTS particle-step rates per host, CPU model and\n"
            "# liggghts-wheel version (docs/sweeps.md, \"Cost estimate\"). Safe to delete.\n"
            + tomli_w.dumps({"rate": entries}))
    tmp.write_text(text)
    os.replace(tmp, path)


def _entry_rate(e, path):
    try:
        vals = {k: float(e[k]) for k in DEFAULT}
    except (KeyError, TypeError, ValueError) as err:
        raise EstimateError(f"rate cache {path}: entry for {e.get('host')} lacks or has a bad "
                            f"{err}; re-measure with --measure-rate")
    bad = [k for k, v in vals.items() if not (v >= 0 if k == "startup_s" else v > 0)]
    if bad:
        raise EstimateError(f"rate cache {path}: {', '.join(bad)} out of range (rates and the "
                            "efficiency > 0, startup_s >= 0); re-measure with --measure-rate")
    return vals


def lookup(path, key):
    """The Rate for this machine and build: the cached measurement, or the defaults with the
    reason (no cache, no entry for this host/CPU, a stale liggghts-wheel version)."""
    entries = read_cache(path)
    same_machine = [e for e in entries if (e.get("host"), e.get("cpu")) == (key["host"],
                                                                              key["cpu"])]
    def measured(e, note=""):
        load = e.get("load_average_1min")
        return Rate(**_entry_rate(e, path),
                    source=f"measured {e.get('measured_at', '?')} on {key['host']}"
                    + (f" (load average {load:.1f} on {e.get('cores', '?')} cores)"
                       if isinstance(load, (int, float)) else "") + note + f" [{path}]")

    for e in same_machine:
        if e.get("liggghts_wheel") == key["liggghts_wheel"]:
            return measured(e)
    # Another commit of the same release: the rate of LIGGGHTS' loop on this machine barely
    # moves between commits, and a developer's cache would otherwise never match. Used, and said.
    for e in same_machine:
        if release(e.get("liggghts_wheel", "")) == release(key["liggghts_wheel"]):
            return measured(e, f" with {e.get('liggghts_wheel')}, this build is "
                            f"{key['liggghts_wheel']}: re-measure (--measure-rate) if the fix "
                            "or the build flags changed")
    if same_machine:
        why = (f"the cached rate ({path}) is for {same_machine[0].get('liggghts_wheel')}, this "
               f"build is {key['liggghts_wheel']}")
    elif entries or Path(path).is_file():
        why = f"no rate for host {key['host']} ({key['cpu']}) in {path}"
    else:
        why = f"no rate measured on this machine ({path} missing)"
    return Rate(**DEFAULT, source=f"DEFAULT (issue 12's 2-core machine): {why}; measure with "
                                  "wheel-sweep --measure-rate")


# ---- the benchmark ------------------------------------------------------------------------------
def _launch(np_):
    return [] if np_ <= 1 else mpi_launch.mpirun(np_)


def _loop(text, what):
    m = liggghts_log.loops(text)
    if not m:
        raise EstimateError(f"rate benchmark: {what}: no 'Loop time' in LIGGGHTS' output")
    return m


def _last_lines(text):
    return "\n".join(text.strip().splitlines()[-5:])


def _run(cmd, cwd, what, say, stall_s):
    """Runs one benchmark step with its output in cwd/bench.log; returns (output, wall [s]). In a
    session of its own that dies with this process; killed whole (mpirun and its ranks) when its
    output has not grown for stall_s (the stall guard, mpi_launch.wait_watching; 0: never)."""
    say(f"measure-rate: {what}: {' '.join(cmd)}")
    log = Path(cwd) / "bench.log"
    t0 = time.monotonic()
    with open(log, "w+") as f:
        p = subprocess.Popen(cmd, cwd=cwd, stdout=f, stderr=subprocess.STDOUT,
                             stdin=subprocess.DEVNULL,
                             preexec_fn=mpi_launch.die_with_parent(os.getpid(), new_session=True,
                                                                   who="wheel-sweep"))
        try:
            rc = mpi_launch.wait_watching(
                p, f, stall_s, lambda: watchdog.kill_sessions_until_empty([p.pid]),
                f"rate benchmark: {what}", "--stall-timeout")
        except mpi_launch.Stalled as e:
            f.seek(0)
            raise EstimateError(f"{e}\nits last lines (the log goes with the benchmark's "
                                f"temporary directory):\n{_last_lines(f.read())}") from None
        finally:
            watchdog.kill_sessions_until_empty([p.pid])  # what it left in its session
        f.seek(0)
        out = f.read()
    wall = time.monotonic() - t0
    if rc != 0:
        raise EstimateError(f"rate benchmark: {what} failed (exit {rc}):\n{_last_lines(out)}")
    return out, wall


def measure(liggghts, repo, mesh, say=print, np2=True,
            stall_s=60.0 * mpi_launch.DEFAULT_STALL_MIN):
    """Runs the benchmark (module docstring); returns the cache entry (dict). stall_s: the stall
    guard of each of its LIGGGHTS runs [s] (wheel-sweep --stall-timeout; 0: none)."""
    inputs = repo / "inputs"
    deck = Path(__file__).resolve().parent / "rate_bench.in"
    load0 = os.getloadavg()[0]
    cores = len(os.sched_getaffinity(0))
    with tempfile.TemporaryDirectory(prefix="wheel-sweep-rate-") as tmp:
        restart = Path(tmp) / "soilbin_ci.restart"
        cmd = [str(liggghts), "-in", str(inputs / "in.soilbin"), "-log", "none", "-echo", "none",
               "-var", "inputs_dir", str(inputs), "-var", "soil", BENCH_SOIL,
               "-var", "out_dir", tmp, "-var", "restart_file", str(restart)]
        for k, v in BENCH_BIN.items():
            cmd += ["-var", k, str(v)]
        out, _ = _run(cmd, tmp, "bed (in.soilbin, 1 rank)", say, stall_s)
        loops = _loop(out, "bed")
        bed_time = sum(m.seconds for m in loops)
        bed_psteps = sum(m.steps * m.atoms for m in loops)
        runs = {}
        for np_ in ((1, 2) if np2 else (1,)):
            cmd = _launch(np_) + [str(liggghts), "-in", str(deck), "-log", "none", "-echo", "none",
                                  "-var", "inputs_dir", str(inputs), "-var", "restart_file",
                                  str(restart), "-var", "mesh", str(mesh),
                                  "-var", "steps", str(BENCH_STEPS)]
            out, wall = _run(cmd, tmp, f"wheel run ({np_} rank(s), {BENCH_STEPS} steps)", say,
                             stall_s)
            last = [m for m in _loop(out, f"wheel run np {np_}") if m.steps == BENCH_STEPS][-1]
            runs[np_] = (last.seconds, last.atoms, wall)
    loop1, atoms, wall1 = runs[1]
    rate1 = atoms * BENCH_STEPS / loop1
    e2 = runs[1][0] / runs[2][0] / 2.0 if np2 else DEFAULT["efficiency_np2"]
    entry = machine_key(liggghts_version(liggghts))
    entry.update(
        measured_at=datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        cores=cores, load_average_1min=round(max(load0, os.getloadavg()[0]), 2),
        particles=atoms, steps=BENCH_STEPS,
        rate_per_rank=float(f"{rate1:.4g}"), efficiency_np2=round(e2, 3),
        startup_s=round(max(wall1 - loop1, 0.0), 2),
        bed_rate_per_rank=float(f"{bed_psteps / bed_time:.4g}"),
        np2_measured=np2,
        note="measured while the machine ran other work if load_average_1min exceeds 0; a "
             "busy machine measures low")
    return entry


def have_mpirun():
    return shutil.which("mpirun") is not None
