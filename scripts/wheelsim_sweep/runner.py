"""Runs a sweep's points: concurrency, resume markers, DEM bed preparation, signals, manifest.

Per point directory (OUT/<wheel>/<soil>/s<slip>/): rig.toml (the point's rig config), run.log
(the child's output), run.part.h5 while running, run.h5 once it finished with exit status 0,
done.json (written last, atomically; also for a failed point, with its exit status). A point is
finished when done.json says exit status 0, its inputs hash matches and run.h5 exists.
"""

import csv
import fcntl
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor, wait, FIRST_COMPLETED
from pathlib import Path

from wheelsim_post import bed_hold, cosim_checkpoint, mpi_launch, step_archive
from wheelsim_post.deck_files import deck_includes

from . import active_domain, archive, estimate, health, toml_out, watchdog
from .config import TILE_VARS

RUN_FILE = "run.h5"
PART_FILE = "run.part.h5"
DONE_FILE = "done.json"
KILL_GRACE_S = 5.0


def _run_wall_time(path):
    """The run's wall time [s] as its run file records it (/parameters/run/wall_time: for a
    point resumed from a checkpoint, the attempts before it up to the checkpoint plus the last
    one; wheel-rig, docs/hdf5-layout.md); None if it is missing or cannot be read."""
    from wheelsim_post.errors import PostError  # h5py: only a resumed DEM point needs these
    from wheelsim_post.results_table import wall_time
    from wheelsim_post.runfile import RunFile
    try:
        with RunFile(path) as run:
            return wall_time(run)
    except PostError:  # the caller says so in done.json
        return None


def _write_atomic(path, text):
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "w") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


# the deck files a tiled bed is made with besides in.soilbin (docs/soil-bins.md "Tiled beds")
TILE_DECKS = ("tile.in", "tile_check.in")
# What the records write for the output, sweep-file, build and checkout directories
# (Runner.portable)
OUT_TOKEN, CONFIG_TOKEN, BUILD_TOKEN, REPO_TOKEN = "<out>", "<config>", "<build>", "<repo>"


def _recorded(record_file, portable):
    """A JSON record's contents with its paths made portable (Runner.portable); None if it cannot
    be read."""
    try:
        return portable(json.loads(Path(record_file).read_text()))
    except (OSError, ValueError):
        return None


def _prep_keys_changed(recipe_file, recipe, portable):
    """When a bed's recorded recipe (recipe_file, JSON) differs from `recipe` (paths portable) in
    the preparation keys of a tiled bed only (config.TILE_VARS): 'key old -> new, ...'; None when
    any other key differs or the record cannot be read."""
    old = _recorded(recipe_file, portable)
    if not isinstance(old, dict):
        return None
    keys = sorted(k for k in set(old) | set(recipe) if old.get(k) != recipe.get(k))
    if not keys or any(k not in TILE_VARS for k in keys):
        return None
    return ", ".join(f"{k} {old.get(k, 'unset')} -> {recipe.get(k, 'unset')}" for k in keys)


def _sha256_json(value):
    return hashlib.sha256(json.dumps(value, sort_keys=True).encode()).hexdigest()


def _same_bed_inputs(inputs_file, inputs, portable):
    """True if a bed's recorded inputs (its .inputs.json) are `inputs` (Runner.bed_inputs), the
    record's paths made portable as `inputs`' are (records before 2026-12-03 named absolute
    paths). A record from before the included files were recorded is compared without them."""
    recorded = _recorded(inputs_file, portable)
    if not isinstance(recorded, dict):
        return False
    recorded.pop("accepted_changes", None)  # wheel-sweep --accept-change's notes (accept.py)
    if "included_sha256" not in recorded:
        inputs = {k: v for k, v in inputs.items() if k != "included_sha256"}
    return recorded == inputs


def _last_error(log):
    try:
        lines = Path(log).read_text(errors="replace").splitlines()
    except OSError:
        return ""
    for i in range(len(lines) - 1, -1, -1):
        line = lines[i]
        if "error" in line.lower() or "failed" in line.lower():
            # the decks' own checks print "ERROR: <what and why>", then stop on an unknown
            # command named after the problem: the line before says more
            if line.startswith("ERROR: Unknown command") and i > 0 \
                    and lines[i - 1].startswith("ERROR: "):
                return lines[i - 1].strip()
            return line.strip()
    return lines[-1].strip() if lines else ""


def _park_progress(point, point_dir, step):
    """How far a point had come at checkpoint `step`, for whoever parks it: its rig phase and, in
    the test phase, the test time of run.duration (a point near its end is then seen as such)."""
    try:
        phase, t, t0 = cosim_checkpoint.rig_progress(point_dir / archive.CHECKPOINTS, step)
    except (OSError, KeyError, ValueError, IndexError) as e:
        return f"progress unknown: {e}"
    duration = point.rig.get("run", {}).get("duration")
    known = isinstance(duration, (int, float)) and duration > 0
    if phase != "test" or t0 is None or not known:
        return (f"{phase} phase, t {t:.3f} s simulated"
                + (f", the {duration:g} s test phase to come" if known and phase != "test" else ""))
    return (f"test phase, {t - t0:.3f} of {duration:g} s, {100 * (t - t0) / duration:.0f} %; "
            f"t {t:.3f} s simulated")


class Interrupted(Exception):
    pass


class Runner:
    def __init__(self, sweep, out_dir, repo, build_dir, jobs, force=False, dry_run=False,
                 cost=None, beds_only=False, archive_dir=None, bed_hold_s=bed_hold.DEFAULT_HOLD_S,
                 stall_s=60.0 * mpi_launch.DEFAULT_STALL_MIN):
        self.sweep = sweep
        self.bed_hold_s = bed_hold_s  # [s] the bed-hold check's length (cli --bed-hold; 0: none)
        # [s] a bed's in.soilbin or bed-hold check whose log stays unchanged this long is killed
        # (cli --stall-timeout; 0: never). Not the points: wheel-cosim and wheel-rig time out on
        # their own (socket timeouts), and none of this enters a point's or a bed's inputs.
        self.stall_s = stall_s
        # --archive DIR: finished points are kept there and restored from there (archive.py)
        self.archive = Path(archive_dir).resolve() if archive_dir is not None else None
        self.restored = []  # reldirs of the points restored from the archive by this run
        self.unparked = {}  # reldir: parked record, the points whose checkpoint the archive gave
        # soil label: {"sha256", "vars", "points"}: recipe beds not poured, their points to run
        # resuming from checkpoints parked on them (parked_beds)
        self.parked_bed = {}
        self.beds_only = beds_only  # DEM: prepare the points' beds, run no point (cli --beds-only)
        # DEM cost check before running (cli.py): {"rate": callable -> estimate.Rate, "cores",
        # "budget_h" (None: no budget), "yes"}; None: no estimate line
        self.cost = cost
        self.out = Path(out_dir).resolve()
        self.repo = repo
        self.build = build_dir
        self.jobs = jobs
        self.force = force
        self.dry_run = dry_run
        self.lock = threading.RLock()
        self.procs = {}  # Popen -> True once we signalled it
        self.watchdog = None  # the watchdog process (watchdog.py), while points run
        self.preexec = watchdog.child_preexec(os.getpid())
        self.stop_signal = None
        self.status = {}  # point index -> done | failed | interrupted | pending
        self.exit_status = {}
        self._file_hashes = {}  # path -> ((size, mtime), sha256) of its contents (file_hash)
        self._includes = {}  # deck path -> the files it includes in turn (included_files)
        # The directories whose absolute paths a point's and a bed's records name as tokens, so
        # that the records hold when the output directory, the sweep file's directory (with the
        # decks, meshes and soil files beside it), the build or the checkout moves (portable,
        # local; docs/sweeps.md "Resume semantics"): longest path first, each as given and
        # resolved.
        anchors = {}
        config_dir = Path(sweep.path).parent if getattr(sweep, "path", None) else None
        for path, token in ((self.out, OUT_TOKEN), (config_dir, CONFIG_TOKEN),
                            (build_dir, BUILD_TOKEN), (repo, REPO_TOKEN)):
            if path is None:
                continue
            for form in (str(Path(path)), str(Path(path).resolve())):
                if len(form) > 1:
                    anchors.setdefault(form, token)
        self._anchors = sorted(anchors.items(), key=lambda a: -len(a[0]))
        self.health = {}  # point index -> (status, codes) of its run file (check_health)

    # ---- output ---------------------------------------------------------------------------------
    def say(self, msg):
        with self.lock:
            print(msg, flush=True)

    # ---- child processes ------------------------------------------------------------------------
    def start_watchdog(self):
        """Starts the watchdog that kills the children's sessions if this process dies."""
        self.watchdog = subprocess.Popen(
            [sys.executable, str(Path(watchdog.__file__).resolve())], stdin=subprocess.PIPE,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)

    def stop_watchdog(self):
        if self.watchdog is not None:
            try:
                self.watchdog.stdin.close()
            except OSError:
                pass
            self.watchdog.wait()
            self.watchdog = None

    def _tell_watchdog(self, line):
        if self.watchdog is None:
            return
        try:
            self.watchdog.stdin.write(f"{line}\n".encode())
            self.watchdog.stdin.flush()
        except OSError:
            self.say("wheel-sweep: warning: the watchdog is gone; children may outlive a killed "
                     "driver")
            self.watchdog = None

    def _run_child(self, cmd, log, cwd=None, stall=None):
        """Runs cmd in a session of its own that dies with this process (watchdog.py); returns
        its exit status or raises Interrupted. stall: what the child runs (e.g. "bed 'x':
        in.soilbin"), for the stall guard: when its log has not grown for self.stall_s, its
        session is killed and mpi_launch.Stalled (a RuntimeError) names it and the log; None: no
        guard (the points)."""
        env = dict(os.environ, WHEELSIM_BUILD_DIR=str(self.build))
        with open(log, "w") as f:
            with self.lock:
                if self.stop_signal is not None:
                    raise Interrupted()
                proc = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT,
                                        stdin=subprocess.DEVNULL, cwd=cwd, env=env,
                                        preexec_fn=self.preexec)
                self.procs[proc] = False
                self._tell_watchdog(f"+{proc.pid}")
            stalled = None
            try:
                if stall is None:
                    rc = proc.wait()
                else:
                    rc = mpi_launch.wait_watching(
                        proc, f, self.stall_s,
                        lambda: watchdog.kill_sessions_until_empty([proc.pid]), stall,
                        "--stall-timeout")
            except mpi_launch.Stalled as e:
                stalled = e
            finally:
                # what the child left behind in its session (e.g. an MPI rank) goes with it
                watchdog.kill_sessions_until_empty([proc.pid])
                with self.lock:
                    killed = self.procs.pop(proc)
                    self._tell_watchdog(f"-{proc.pid}")
        if killed:
            raise Interrupted()
        if stalled is not None:
            raise stalled
        return rc

    def _signal_children(self, sig):
        """SIGTERM: to each child's process group (mpirun forwards it to its ranks); SIGKILL:
        to every process of each child's session."""
        with self.lock:
            for proc in self.procs:
                self.procs[proc] = True
                if sig == signal.SIGKILL:
                    watchdog.kill_session(proc.pid, sig)
                    continue
                try:
                    os.killpg(proc.pid, sig)
                except ProcessLookupError:
                    pass

    def _on_signal(self, signum, _frame):
        if self.stop_signal is None:
            self.stop_signal = signum
            self.say(f"wheel-sweep: {signal.Signals(signum).name}: stopping the running points "
                     "(they stay unfinished and re-run next time)")
        self._signal_children(signal.SIGTERM)

    # ---- points ---------------------------------------------------------------------------------
    def point_dir(self, p):
        return self.out / p.reldir

    def bed_restart(self, soil):
        if soil.restart is not None:
            return soil.restart
        return self.out / "beds" / soil.label / f"soilbin_{soil.dem_soil_name}.restart"

    def rig_text(self, p):
        return toml_out.dumps(p.rig)

    def rig_file_text(self, p):
        """The point's rig.toml: a comment header, then the rig config."""
        header = (f"written by wheel-sweep from {self.sweep.path}\npoint {p.reldir}: wheel "
                  f"{p.wheel.label}, soil {p.soil.name}, slip {p.slip!r}, terrain "
                  f"{self.sweep.terrain}\nslip_control = \"{self.sweep.slip_control}\": "
                  f"{p.setting}\n")
        return toml_out.dumps(p.rig, header)

    def command(self, p, resume=False):
        d = self.point_dir(p)
        params = []
        for k, v in (("wheel", p.wheel.label), ("soil", p.soil.name), ("slip", repr(p.slip)),
                     ("terrain", self.sweep.terrain), ("config", str(self.sweep.path)),
                     ("slip_control", self.sweep.slip_control)):
            params += ["--parameter", f"sweep/{k}={v}"]
        if self.sweep.terrain == "dem":
            cmd = [str(self.repo / "scripts" / "wheel-cosim"), "--rig", str(d / "rig.toml"),
                   "--bed", str(self.bed_restart(p.soil)), "--deck", str(self.sweep.deck),
                   "--np", str(self.sweep.np), "--out", str(d / PART_FILE),
                   "--work", str(d / "cosim"), "--mesh", str(p.wheel.mesh)] + params
            if p.soil.recipe is not None:
                # the soil file of this checkout that the bed's record vouches for (bed_inputs),
                # not the absolute path its .vars names: the checkout may have moved since
                cmd += ["--soil-file", str(p.soil.dem_soil_file)]
            if resume:
                cmd.append("--resume")
                parked = self._unpoured(p.soil)
                if parked is not None:
                    cmd += ["--bed-sha256", parked["sha256"]]
            if self.sweep.checkpoint_every_s is not None:
                cmd += ["--checkpoint-every-seconds",
                        f"{self.sweep.checkpoint_every_s:.6f}".rstrip("0").rstrip(".")]
            if self.sweep.checkpoint_every_steps is not None:
                cmd += ["--checkpoint-every-steps", str(self.sweep.checkpoint_every_steps)]
            if self.sweep.liggghts_args:
                cmd += ["--"] + self.sweep.liggghts_args
            return cmd
        return [str(self.build / "bin" / "wheel-rig"), "--config", str(d / "rig.toml"),
                "--out", str(d / PART_FILE), "--quiet"] + params

    def file_hash(self, path):
        """sha256 of a file's contents ("missing" if it cannot be read); kept while the file's
        size and modification time stay the same (a bed restart may be large), so a file edited
        while the driver runs is hashed again: a point records what it read when it started."""
        path = str(path)
        try:
            st = os.stat(path)
        except OSError:
            return "missing"
        stamp = (st.st_size, st.st_mtime_ns)
        kept = self._file_hashes.get(path)
        if kept is None or kept[0] != stamp:
            h = hashlib.sha256()
            try:
                with open(path, "rb") as f:
                    for block in iter(lambda: f.read(1 << 20), b""):
                        h.update(block)
            except OSError:
                return "missing"
            kept = self._file_hashes[path] = (stamp, h.hexdigest())
        return kept[1]

    def portable(self, value):
        """`value` (a string, or a dict / list of them, keys included) with the absolute paths of
        the output, sweep-file, build and checkout directories replaced by <out>, <config>,
        <build> and <repo>: what the records compare, so that moving any of them re-runs
        nothing."""
        if isinstance(value, str):
            for path, token in self._anchors:
                value = value.replace(path, token)
            return value
        if isinstance(value, dict):
            return {self.portable(k): self.portable(v) for k, v in value.items()}
        if isinstance(value, (list, tuple)):
            return [self.portable(v) for v in value]
        return value

    def local(self, text):
        """A portable path (`portable`) as a path of this run: the tokens replaced by the
        directories they stand for."""
        for path, token in reversed(self._anchors):  # a directory's shorter form, if two
            text = text.replace(token, path)
        return text

    def inputs_hash(self, p):
        """The sha256 of `inputs_ident` with the directories it names as tokens (`portable`):
        what a finished point records (done.json inputs_sha256)."""
        return _sha256_json(self.portable(self.inputs_ident(p)))

    def inputs_hashes(self, p):
        """The hashes a finished point's record may hold for the same inputs: `inputs_hash`, and
        the one of records written before 2026-12-03, which named absolute paths (valid while the
        directories have not moved)."""
        ident = self.inputs_ident(p)
        return {_sha256_json(self.portable(ident)), _sha256_json(ident)}

    def inputs_ident(self, p):
        """What decides a point's result (not the out dir): its rig config, its run settings, and
        the contents of the files they name: the mesh, the SCM soil file; for DEM the deck, the
        bed (a restart and its .vars, or the bin recipe with in.soilbin), the DEM soil's include
        file wherever it is (a recipe's soil name or path; a bed's soil_file from its .vars, which
        resume.in includes again), the np and LIGGGHTS arguments. docs/sweeps.md, "Resume
        semantics"."""
        ident = {"rig": self.rig_text(p), "terrain": self.sweep.terrain, "wheel": p.wheel.label,
                 "soil": p.soil.label, "slip": p.slip, "mesh": str(p.wheel.mesh),
                 "mesh_sha256": self.file_hash(p.wheel.mesh)}
        if p.soil.soil_file is not None:
            ident["soil_file_sha256"] = self.file_hash(p.soil.soil_file)
        if self.sweep.terrain == "dem":
            bed = self.bed_restart(p.soil)
            ident.update(bed=str(bed), deck=str(self.sweep.deck),
                         deck_sha256=self.file_hash(self.sweep.deck),
                         np=self.sweep.np, liggghts_args=self.sweep.liggghts_args)
            if p.soil.recipe is not None:  # the bed is made from these (it may not exist yet)
                ident.update(bed_recipe=p.soil.recipe,
                             soilbin_sha256=self.file_hash(self.repo / "inputs" / "in.soilbin"),
                             bed_soil_sha256=self.file_hash(p.soil.dem_soil_file))
                ident.update(self.tile_hashes(p.soil))
            else:
                ident.update(bed_sha256=self.file_hash(bed),
                             bed_vars_sha256=self.file_hash(f"{bed}.vars"))
                if p.soil.dem_soil_file is not None:  # (beds from before soil_file: by name)
                    ident.update(bed_soil_sha256=self.file_hash(p.soil.dem_soil_file))
        return ident

    def included_hashes(self, p):
        """{path: sha256} of the files a DEM point's LIGGGHTS inputs include in turn: the deck's
        (resume.in, bed_fixes.in, soil_check.in, ...), the DEM soil file's (materials.in) and, for
        a bin recipe, in.soilbin's (settle.in, ...). Recorded in done.json beside inputs_sha256 and
        compared when present (points finished before it was recorded are not re-run for it)."""
        if self.sweep.terrain != "dem":
            return {}
        roots = [self.sweep.deck]
        if p.soil.dem_soil_file is not None:
            roots.append(p.soil.dem_soil_file)
        if p.soil.recipe is not None:
            roots.append(self.repo / "inputs" / "in.soilbin")
        return self.included_files(roots)

    def included_files(self, roots):
        """{path: sha256} of the files the LIGGGHTS inputs `roots` include in turn
        (deck_includes with inputs_dir; each root is read once per run of the driver); the paths
        portable (`portable`)."""
        out = {}
        for r in roots:
            if str(r) not in self._includes:
                self._includes[str(r)] = deck_includes(r, {"inputs_dir": str(self.repo / "inputs")})
            out.update((self.portable(str(f)), self.file_hash(f)) for f in self._includes[str(r)])
        return out

    def bed_inputs_file(self, soil):
        """A recipe bed's record of the files it was made from (<restart>.inputs.json)."""
        restart = self.bed_restart(soil)
        return restart.parent / f"{restart.name}.inputs.json"

    def bed_inputs(self, soil):
        """What a recipe bed is made from, as its .inputs.json records it: a changed soil file or
        in.soilbin (same paths) makes the bed stale, as it makes a finished point re-run
        (inputs_hash); included_sha256 holds what in.soilbin and the soil file include in turn
        (settle.in, ...)."""
        soilbin = self.repo / "inputs" / "in.soilbin"
        return {"soilbin_sha256": self.file_hash(soilbin),
                "soil_file": self.portable(str(soil.dem_soil_file)),
                "soil_file_sha256": self.file_hash(soil.dem_soil_file),
                **self.tile_hashes(soil),
                "included_sha256": self.included_files((soilbin, soil.dem_soil_file))}

    def tile_hashes(self, soil):
        """A tiled recipe's (tile_length set) extra deck files: {name_sha256: sha256}; {} for a
        bed settled whole (so the records of existing beds stay as they were)."""
        if soil.recipe is None or "tile_length" not in soil.recipe:
            return {}
        d = self.repo / "inputs" / "soilbin"
        return {f"{f.replace('.', '_')}_sha256": self.file_hash(d / f) for f in TILE_DECKS}

    def finished(self, p):
        """(True, "") when the point is finished with the same inputs, else (False, why). With
        --archive, a point without done.json in the output directory is judged by its archived
        record (restored once the run starts: _sync_archive)."""
        d = self.point_dir(p)
        if self.archive is not None and not (d / DONE_FILE).exists():
            if (self.archive / p.reldir / DONE_FILE).is_file():
                d = self.archive / p.reldir
        return self.finished_in(d, p)

    def finished_in(self, d, p, included=True):
        """`finished` for the record in folder d (the output's or the archive's); included=False
        leaves out the included files' hashes (what --accept-change judges itself)."""
        try:
            done = json.loads((d / DONE_FILE).read_text())
        except FileNotFoundError:
            return False, "not run" if not d.exists() else "unfinished"
        except (OSError, ValueError):
            return False, "unreadable done.json"
        if done.get("exit_status") != 0:
            return False, f"failed before (exit {done.get('exit_status')})"
        if done.get("inputs_sha256") not in self.inputs_hashes(p):
            return False, "inputs changed since it finished"
        recorded = done.get("included_sha256") if included else None
        if recorded is not None:
            recorded = self.portable(recorded)
            now = self.included_hashes(p)
            changed = sorted(f for f in set(recorded) | set(now) if recorded.get(f) != now.get(f))
            if changed:
                return False, f"included file {self.local(changed[0])} changed since it finished"
        if not (d / RUN_FILE).is_file():
            return False, f"{RUN_FILE} missing"
        return True, ""

    def describe(self, p):
        return f"{p.wheel.label} {p.soil.label} s={p.slip:g}"

    def run_point(self, p, counter):
        if self.stop_signal is not None:
            return  # stopping: the point stays pending
        d = self.point_dir(p)
        d.mkdir(parents=True, exist_ok=True)
        # A DEM point stopped before its end (no done.json) with a checkpoint of LIGGGHTS' side
        # goes on from it (wheel-cosim --resume, docs/coupled-runs.md "Checkpoint and resume");
        # else from scratch, which clears its old checkpoints.
        ckpt = d / "cosim" / "checkpoints"
        resume = (self.sweep.terrain == "dem" and not (d / DONE_FILE).exists()
                  and (d / PART_FILE).is_file() and ckpt.is_dir()
                  and any(ckpt.glob("liggghts-*.restart.info")))
        stale = (DONE_FILE, RUN_FILE, PART_FILE + ".writing") + (() if resume else (PART_FILE,))
        for name in stale:
            (d / name).unlink(missing_ok=True)
        _write_atomic(d / "rig.toml", self.rig_file_text(p))
        with self.lock:
            counter["started"] += 1
            self.say(f"[started {counter['started']}/{counter['total']}] {self.describe(p)} "
                     f"({p.reldir}{', resuming from its checkpoint' if resume else ''})")
        # its inputs and included files as this point reads them: an edit while it runs (a later
        # point's inputs) must not be recorded as what this one ran with
        inputs = self.inputs_hash(p)
        included = self.included_hashes(p) if self.sweep.terrain == "dem" else None
        t0 = time.monotonic()
        with self.lock:
            counter["running"][p.index] = t0
        try:
            rc = self._run_child(self.command(p, resume), d / "run.log", cwd=d)
        except Interrupted:
            with self.lock:
                self.status[p.index] = "interrupted"
                counter["running"].pop(p.index, None)
                counter["finished"] += 1
                self.say(f"[{counter['finished']}/{counter['total']}] {self.describe(p)} "
                         f"interrupted after {estimate.fmt_time(time.monotonic() - t0)}")
            return
        wall = time.monotonic() - t0
        if rc == 0 and not (d / PART_FILE).is_file():
            rc = 1  # an exit status 0 without a run file is a failure all the same
            note = f"exited 0 but wrote no {PART_FILE}"
        else:
            note = ""
        if rc == 0:
            os.replace(d / PART_FILE, d / RUN_FILE)
        attempt = wall
        total = _run_wall_time(d / RUN_FILE) if rc == 0 and resume else None
        if total is not None:  # the point's cost: the attempts before the checkpoint too
            wall = total
        done = {"wheel": p.wheel.label, "soil": p.soil.name, "slip": p.slip,
                "terrain": self.sweep.terrain, "exit_status": rc,
                "status": "done" if rc == 0 else "failed", "wall_time_s": round(wall, 3),
                "run_file": RUN_FILE if rc == 0 else None, "inputs_sha256": inputs}
        if resume:
            done.update(resumed_from_checkpoint=True, wall_time_s_this_attempt=round(attempt, 3))
            if rc == 0 and total is None:
                done["wall_time_note"] = ("the run file records no run/wall_time: wall_time_s "
                                          "is this attempt's only")
        if included is not None:
            done["included_sha256"] = included
        _write_atomic(d / DONE_FILE, json.dumps(done, indent=2) + "\n")
        if rc == 0 and self.archive is not None:
            self._archive_point(p)
        with self.lock:
            self.status[p.index] = done["status"]
            self.exit_status[p.index] = rc
            counter["finished"] += 1
            k = counter["finished"]
            counter["walls"].append(wall)
            del counter["running"][p.index]
            eta = self._eta(counter)
        if rc == 0:
            also = (f" ({estimate.fmt_time(attempt)} in this attempt, resumed from its "
                    "checkpoint)" if resume else "")
            self.say(f"[{k}/{counter['total']}] {self.describe(p)} done in "
                     f"{estimate.fmt_time(wall)}{also}{eta}")
        else:
            why = note or _last_error(d / "run.log")
            self.say(f"[{k}/{counter['total']}] {self.describe(p)} FAILED (exit {rc}) after "
                     f"{estimate.fmt_time(wall)}: {why} [log {d / 'run.log'}]{eta}")

    def _eta(self, counter):
        """Mean wall time of the finished points x the work left (running points count by their
        expected remainder), spread over the job slots."""
        pending = counter["total"] - counter["finished"] - len(counter["running"])
        if not counter["walls"] or pending + len(counter["running"]) == 0:
            return ""
        mean = sum(counter["walls"]) / len(counter["walls"])
        now = time.monotonic()
        work = pending * mean + sum(max(mean - (now - t), 0.0) for t in counter["running"].values())
        return f"; ETA {estimate.fmt_time(work / self.jobs_used)}"

    # ---- DEM cost -------------------------------------------------------------------------------
    def cost_estimate(self, rate, cores):
        """The sweep's estimate.SweepEstimate with rate() (called once the points are known to
        be estimable); raises estimate.EstimateError."""
        query = estimate.SoilQuery(self.build / "bin" / "liggghts-wheel", self.repo / "inputs")
        soilbin = self.repo / "inputs" / "in.soilbin"
        done = {p.index for p in self.sweep.points if self.finished(p)[0]} if not self.force \
            else set()
        parked = self.parked_beds([(p, "") for p in self.sweep.points if p.index not in done])
        infos = {s.label: estimate.bed_info(s, self.bed_restart(s), query, soilbin,
                                            self.bed_hold_s,
                                            parked_vars=parked.get(s.label, {}).get("vars"))
                 for s in self.sweep.soils}
        for s in self.sweep.soils:  # a prepared recipe bed whose bed-hold check is still to run
            info = infos[s.label]
            if (info.prepared and s.recipe is not None and self.bed_hold_s > 0
                    and s.label not in parked  # (checked where it was poured)
                    and self.bed_hold_record(s, self.bed_restart(s)) is None):
                estimate.add_bed_hold(info, self.bed_hold_s)
        return estimate.estimate(self.sweep.points, infos, rate(), self.sweep.np,
                                 self.sweep.bed_np, self.jobs, cores,
                                 finished=lambda p: p.index in done,
                                 chunk=estimate.deck_chunk(self.sweep.deck,
                                                           self.sweep.liggghts_args),
                                 active=active_domain.settings(self.sweep.deck,
                                                               self.sweep.liggghts_args),
                                 x0=active_domain.start_x(self.sweep.deck,
                                                          self.sweep.liggghts_args),
                                 measured_wall=self.measured_wall,
                                 steps_done=lambda p: archive.steps_done(
                                     self.point_dir(p), self.archive, p.reldir))

    def measured_wall(self, p):
        """The wall time [s] a finished point took (its done.json), else None."""
        try:
            done = json.loads((self.point_dir(p) / DONE_FILE).read_text())
        except (OSError, ValueError):
            return None
        w = done.get("wall_time_s")
        return float(w) if isinstance(w, (int, float)) and not isinstance(w, bool) else None

    def _check_cost(self):
        """The estimate line at the start of a DEM sweep and the budget check: returns 2 (and
        says why) when the estimate exceeds the budget without --yes, else None."""
        c = self.cost
        budget = c.get("budget_h")
        try:
            est = self.cost_estimate(c["rate"], c["cores"])
        except estimate.EstimateError as e:
            self.say(f"wheel-sweep: estimate unavailable: {e}")
            if budget is not None and not c.get("yes"):
                print(f"wheel-sweep: error: budget {budget:g} h set (dem.budget_h or --budget) "
                      "but the cost cannot be estimated (above); nothing run. --yes runs anyway",
                      file=sys.stderr, flush=True)
                return 2
            return None
        self.say(f"wheel-sweep: {estimate.summary_line(est)}")
        if budget is not None and est.total > budget * 3600.0:
            if c.get("yes"):
                self.say(f"wheel-sweep: the estimate {estimate.fmt_time(est.total)} exceeds the "
                         f"budget of {budget:g} h; running anyway (--yes)")
                return None
            beds = f" + beds <= {estimate.fmt_time(est.beds_wall)}" if est.beds else ""
            print(f"wheel-sweep: error: estimated wall time {estimate.fmt_time(est.total)} "
                  f"({est.total / 3600:.3g} h: points {estimate.fmt_time(est.points_wall)}"
                  f"{beds}) exceeds the budget of "
                  f"{budget:g} h (dem.budget_h or --budget); nothing run. See --estimate; run "
                  "anyway with --yes, or raise the budget", file=sys.stderr, flush=True)
            return 2
        return None

    # ---- DEM beds -------------------------------------------------------------------------------
    def prepare_beds(self):
        """Prepares each bin recipe's bed once (skipped when its restart exists), for the soils
        of the sweep's points (all of them, unless wheel-sweep --points chose some)."""
        used = {id(p.soil) for p in self.sweep.points}
        for soil in self.sweep.soils:
            if soil.recipe is None or id(soil) not in used:
                continue
            restart = self.bed_restart(soil)
            parked = self.parked_bed.get(soil.label)
            if parked is not None:
                if not self.dry_run:  # wheel-cosim reads the bed's depth, step and soil from it
                    restart.parent.mkdir(parents=True, exist_ok=True)
                    _write_atomic(Path(f"{restart}.vars"), parked["vars"])
                self.say(f"bed {soil.label}: {'would not pour' if self.dry_run else 'not poured'}"
                         f": its {parked['points']} point(s) to run resume from checkpoints "
                         f"parked on it (sha256 {parked['sha256'][:12]}..., its .vars from the "
                         "archive); it is poured when a point must start from it")
                continue
            bdir = restart.parent
            recipe_file = bdir / f"{restart.name}.recipe.json"
            recipe = self.portable(soil.recipe)  # recorded and compared with portable paths
            recipe_text = json.dumps(recipe, sort_keys=True, indent=2) + "\n"
            inputs_file = self.bed_inputs_file(soil)
            inputs = self.bed_inputs(soil)
            inputs_text = json.dumps(inputs, sort_keys=True, indent=2) + "\n"
            why = ""
            if restart.is_file() and Path(f"{restart}.vars").is_file():
                changed = None
                if recipe_file.is_file() and _recorded(recipe_file, self.portable) != recipe:
                    changed = _prep_keys_changed(recipe_file, recipe, self.portable)
                    if changed is None:
                        raise RuntimeError(f"bed '{soil.label}': {restart} exists but was "
                                           f"prepared from another recipe ({recipe_file}); "
                                           "delete it or rename the soil")
                if changed:  # the same bed, another preparation (tiled or whole): make it again
                    why = f" again: its preparation keys changed ({changed})"
                elif not inputs_file.is_file():  # a bed from before the inputs were recorded
                    self.say(f"bed {soil.label}: reusing {restart} (prepared before its input "
                             "files' hashes were recorded: not checked against them)")
                    self.check_bed_hold(soil, restart)
                    continue
                elif _same_bed_inputs(inputs_file, inputs, self.portable):
                    self.say(f"bed {soil.label}: reusing {restart}")
                    self.check_bed_hold(soil, restart)
                    continue
                else:
                    why = (" again: its soil file, inputs/in.soilbin or a file they include "
                           f"changed since it was prepared ({inputs_file})")
            if self.dry_run:
                self.say(f"bed {soil.label}: would prepare {restart}{why} (in.soilbin, "
                         f"{self.sweep.bed_np} rank(s))")
                continue
            bdir.mkdir(parents=True, exist_ok=True)
            part = bdir / f"{restart.stem}.part.restart"
            for f in (part, Path(f"{part}.vars")):
                f.unlink(missing_ok=True)
            cmd = mpi_launch.mpirun(self.sweep.bed_np)
            cmd += [str(self.build / "bin" / "liggghts-wheel"),
                    "-in", str(self.repo / "inputs" / "in.soilbin"),
                    "-var", "inputs_dir", str(self.repo / "inputs"),
                    # a soil file may prepare its bed with other contact settings (docs/soils.md
                    # "Preparing the bed with other contact settings"); not part of the recipe
                    "-var", "soil_preparing_bed", "1"]
            for k, v in soil.recipe.items():
                cmd += ["-var", k, str(v)]
            cmd += ["-var", "out_dir", str(bdir), "-var", "restart_file", str(part),
                    "-log", str(bdir / "log.soilbin")]
            self.say(f"bed {soil.label}: preparing {restart}{why} ({self.sweep.bed_np} rank(s); "
                     f"log {bdir / 'soilbin.log'})")
            t0 = time.monotonic()
            rc = self._run_child(cmd, bdir / "soilbin.log", cwd=bdir,
                                 stall=f"bed '{soil.label}': in.soilbin")
            if rc != 0 or not part.is_file() or not Path(f"{part}.vars").is_file():
                log = bdir / "soilbin.log"
                raise RuntimeError(f"bed '{soil.label}': in.soilbin failed (exit {rc}): "
                                   f"{_last_error(log)} [log {log}]")
            _write_atomic(recipe_file, recipe_text)
            _write_atomic(inputs_file, inputs_text)
            os.replace(f"{part}.vars", f"{restart}.vars")
            os.replace(part, restart)
            self.say(f"bed {soil.label}: ready in {estimate.fmt_time(time.monotonic() - t0)}")
            self.check_bed_hold(soil, restart)

    @staticmethod
    def bed_hold_file(restart):
        """The bed-hold check's record of a recipe bed."""
        return restart.parent / f"{restart.name}.hold.json"

    def bed_hold_key(self, soil, restart):
        """What a bed-hold check's result depends on: its length, the bed (the restart's bytes,
        what it was made from) and in.bedhold with what it includes."""
        deck = self.repo / "inputs" / bed_hold.DECK
        return {"hold_s": self.bed_hold_s, "restart_sha256": self.file_hash(restart),
                "bed_inputs": self.bed_inputs(soil), "deck_sha256": self.file_hash(deck),
                "deck_included_sha256": self.included_files((deck,))}

    def bed_hold_record(self, soil, restart):
        """The bed-hold check's record of this bed as it is now ({key, result, wall_s, np}), or
        None (none, unreadable, or of other inputs)."""
        try:
            done = json.loads(self.bed_hold_file(restart).read_text())
        except (OSError, ValueError):
            return None
        return done if self.portable(done.get("key")) == self.bed_hold_key(soil, restart) else None

    def check_bed_hold(self, soil, restart):
        """The bed-hold check (docs/soil-bins.md "The bed-hold check") of a recipe bed: the bed
        left alone bed_hold_s under the soil's test settings (inputs/in.bedhold, on the bed's
        ranks). Recorded in <restart>.hold.json with what it was made from (the hashes of the
        restart, of the soil's inputs and of in.bedhold and what it includes; bed_hold_s) and not
        run again for the same; raises RuntimeError when the bed settles (or rises) by more than
        bed_hold.SETTLE_LIMIT (a dry run says it would)."""
        if self.bed_hold_s <= 0:
            return
        log = restart.parent / "bedhold.log"
        deck = self.repo / "inputs" / bed_hold.DECK
        done = self.bed_hold_record(soil, restart)
        when = "checked before, in "  # the record's wall time, not this run's
        if done is None:
            when = ""
            if self.dry_run:
                self.say(f"bed {soil.label}: would leave it alone {self.bed_hold_s:g} s under the "
                         f"soil's test settings (the bed-hold check)")
                return
            cmd = mpi_launch.mpirun(self.sweep.bed_np)
            cmd += [str(self.build / "bin" / "liggghts-wheel"), "-in", str(deck),
                    "-var", "inputs_dir", str(self.repo / "inputs"),
                    "-var", "restart_file", str(restart), "-var", "hold_s", str(self.bed_hold_s),
                    "-log", "none"]
            t0 = time.monotonic()
            rc = self._run_child(cmd, log, cwd=restart.parent,
                                 stall=f"bed '{soil.label}': {bed_hold.DECK}")
            if rc != 0:
                raise RuntimeError(f"bed '{soil.label}': {bed_hold.DECK} failed (exit {rc}): "
                                   f"{_last_error(log)} [log {log}]")
            try:
                result = bed_hold.parse(log.read_text(errors="replace"), log)
            except bed_hold.BedHoldError as e:
                raise RuntimeError(f"bed '{soil.label}': {e}") from None
            done = {"key": self.bed_hold_key(soil, restart), "result": result,
                    "wall_s": round(time.monotonic() - t0, 1), "np": self.sweep.bed_np}
            _write_atomic(self.bed_hold_file(restart), json.dumps(done, indent=1) + "\n")
        r = done["result"]
        # in.soilbin's verdict on its settling, read only for a bed beyond the limit
        prep_log = restart.parent / "soilbin.log"
        unsettled = (abs(r["settlement"]) > bed_hold.SETTLE_LIMIT and prep_log.is_file()
                     and re.search(r"^soilbin: settled = 0\b",
                                   prep_log.read_text(errors="replace"), re.M) is not None)
        error = bed_hold.failure(r, soil.label, log, settled=not unsettled)
        if error and self.dry_run:
            self.say(f"bed {soil.label}: would stop the sweep (its bed-hold check, recorded): "
                     f"{error}")
            return
        if error:
            raise RuntimeError(error)
        self.say(f"bed {soil.label}: {bed_hold.verdict(r)} under the soil's test settings: "
                 f"{bed_hold.describe(r)} ({when}{estimate.fmt_time(done['wall_s'])})")

    # ---- the sweep ------------------------------------------------------------------------------
    def write_manifest(self):
        rows = []
        for p in self.sweep.points:
            st = self.status.get(p.index, "pending")
            rows.append({"wheel": p.wheel.label, "soil": p.soil.name, "slip": repr(p.slip),
                         "terrain": self.sweep.terrain, "status": st,
                         "run_file": f"{p.reldir}/{RUN_FILE}" if st == "done" else "",
                         "point_dir": p.reldir,
                         "exit_status": self.exit_status.get(p.index, ""),
                         "health": self.health.get(p.index, ("", ""))[0],
                         "health_codes": self.health.get(p.index, ("", ""))[1]})
        tmp = self.out / "manifest.csv.tmp"
        with open(tmp, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
        os.replace(tmp, self.out / "manifest.csv")

    def lock_out_dir(self):
        """Takes OUT/.wheel-sweep.lock (one driver per output directory; released when this
        process ends): the open lock file, or None (said) when another driver holds it."""
        self.out.mkdir(parents=True, exist_ok=True)
        lock = open(self.out / ".wheel-sweep.lock", "w")
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            self.say(f"wheel-sweep: error: another wheel-sweep is running in {self.out}")
            lock.close()
            return None
        return lock

    def run(self):
        sw = self.sweep
        n = len(sw.points)
        shape = f"{len(sw.wheels)} wheel(s) x {len(sw.soils)} soil(s) x {len(sw.slips)} slip(s)"
        todo = []
        for p in sw.points:
            ok, why = self.finished(p)
            if ok and not self.force:
                self.status[p.index] = "done"
                self.exit_status[p.index] = 0
            else:
                todo.append((p, "--force" if ok else why))
        skipped = n - len(todo)
        self.say(f"wheel-sweep: {sw.path.name}: terrain {sw.terrain}, {shape} = {n} point(s); "
                 f"output {self.out}")
        self.parked_bed = self.parked_beds(todo)
        if self.dry_run:
            return self._dry_run(todo)

        if sw.terrain == "dem" and todo and self.cost is not None and not self.beds_only:
            refuse = self._check_cost()
            if refuse is not None:
                return refuse
        lock = self.lock_out_dir()
        if lock is None:
            return 2
        if self.archive is not None:
            self._sync_archive()
            if sw.terrain == "dem":
                self.unparked = self._unpark(todo)
                # a bed left unpoured needs each of its points to resume from a checkpoint here
                self.parked_bed = {
                    k: v for k, v in self.parked_bed.items()
                    if all(p.soil.label != k or archive.newest_checkpoint(self.point_dir(p))
                           is not None for p, _ in todo)}
        if sw.path != (self.out / "sweep.toml").resolve():
            shutil.copyfile(sw.path, self.out / "sweep.toml")
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, self._on_signal)
        self.start_watchdog()
        if skipped:
            self.say(f"wheel-sweep: skipping {skipped} finished point(s) (--force re-runs them):")
            for p in sw.points:
                if self.status.get(p.index) == "done":
                    self.say(f"    {self.describe(p)}: finished ({p.reldir}/{RUN_FILE})")
        again = [(p, why) for p, why in todo if why != "not run"]
        if again:
            self.say(f"wheel-sweep: re-running {len(again)} point(s):")
            for p, why in again:
                self.say(f"    {self.describe(p)} ({why})")
        try:
            if sw.terrain == "dem" and (todo or self.beds_only):
                try:
                    self.prepare_beds()
                except RuntimeError as e:
                    self.say(f"wheel-sweep: error: {e}")
                    self.write_manifest()
                    return 1
            if self.restored and sw.terrain == "dem":
                self._check_restored_beds()
            if self.unparked:
                self._check_unparked_beds()
            if self.beds_only:
                self.say(f"wheel-sweep: --beds-only: the beds are ready; {len(todo)} point(s) "
                         "left to run")
                return 0
            self._run_points(todo)
        except Interrupted:
            pass
        finally:
            self.stop_watchdog()
        self.check_health()
        self.write_manifest()
        return self._summary(n, skipped, len(todo))

    # ---- --archive DIR (archive.py) -------------------------------------------------------------
    def _bed_sha(self, p):
        """{bed restart file name: sha256} of a DEM point's bed (a bed not poured: the one its
        checkpoint was parked on); {} for SCM and flat points."""
        if self.sweep.terrain != "dem":
            return {}
        bed = self.bed_restart(p.soil)
        parked = self._unpoured(p.soil)
        return {bed.name: parked["sha256"] if parked is not None else self.file_hash(bed)}

    def _unpoured(self, soil):
        """The parked_bed entry of a soil whose bed this run left unpoured and that is still not
        here (a point that must start from it pours it on a later run), else None."""
        parked = self.parked_bed.get(soil.label)
        return parked if parked is not None and not self.bed_restart(soil).is_file() else None

    def _park_record(self, p):
        """What a parked record holds beside the bed's sha256 (archive.park extra): the bed's
        .vars and the point's inputs as the resume check compares them (inputs_hash,
        included_hashes), so that another machine can resume the point without pouring its bed
        (parked_beds)."""
        extra = {"point_inputs_sha256": self.inputs_hash(p),
                 "point_included_sha256": self.included_hashes(p)}
        try:
            extra["bed_vars"] = Path(f"{self.bed_restart(p.soil)}.vars").read_text()
        except OSError:
            pass
        return extra

    def parked_beds(self, todo):
        """{soil label: {"sha256", "vars", "points"}} of the recipe beds not prepared here whose
        every point to run (todo: [(point, why)]) has a checkpoint parked in the archive on that
        bed, recorded with the bed's .vars and with the point's inputs as they are now: those
        points resume from their checkpoints (wheel-cosim --bed-sha256), so the bed is not
        poured. A point that must start from the bed (none parked, another bed, other inputs)
        makes it be poured as before."""
        if self.archive is None or self.sweep.terrain != "dem":
            return {}
        out = {}
        for soil in self.sweep.soils:
            points = [p for p, _ in todo if p.soil is soil]
            restart = self.bed_restart(soil)
            if soil.recipe is None or not points or restart.is_file():
                continue
            beds = set()
            for p in points:
                r = step_archive.parked(self.archive / p.reldir) or {}
                sha = (r.get("bed_sha256") or {}).get(restart.name)
                if (not r.get("bed_vars") or not re.fullmatch(r"[0-9a-f]{64}", sha or "")
                        or r.get("point_inputs_sha256") != self.inputs_hash(p)
                        or self.portable(r.get("point_included_sha256"))
                        != self.included_hashes(p)):
                    break
                beds.add((sha, r["bed_vars"]))
            else:
                if len(beds) == 1:
                    sha, text = beds.pop()
                    out[soil.label] = {"sha256": sha, "vars": text, "points": len(points)}
        return out

    def _archive_point(self, p):
        try:
            archive.save(self.archive, self.point_dir(p), p.reldir, self._bed_sha(p), self.repo)
        except OSError as e:
            self.say(f"wheel-sweep: warning: could not archive {p.reldir} in {self.archive}: {e}")

    def restore_archived(self, points):
        """Copies those of `points` finished in the archive whose output folder has no done.json
        into the output directory (said); returns their reldirs."""
        restored = archive.restore(self.archive, self.out, [p.reldir for p in points])
        if restored:
            self.say(f"wheel-sweep: restored {len(restored)} finished point(s) from the "
                     f"archive {self.archive}")
        return restored

    def _sync_archive(self):
        """Copies the points finished only in the archive into the output directory, and
        archives the finished points the archive lacks."""
        done = [p for p in self.sweep.points if self.status.get(p.index) == "done"]
        self.restored = self.restore_archived(done)
        added = 0
        for p in done:
            if p.reldir not in self.restored and not step_archive.holds(
                    self.archive / p.reldir, self.point_dir(p)):
                self._archive_point(p)
                added += 1
        if added:
            self.say(f"wheel-sweep: archived {added} finished point(s) the archive lacked")

    def park(self):
        """wheel-sweep --park: parks the newest checkpoint of every unfinished DEM point in the
        archive (archive.park); reads the output directory only, so it may run beside the sweep
        that writes the checkpoints. Returns the exit status."""
        if self.sweep.terrain != "dem":
            self.say(f"wheel-sweep: --park: {self.sweep.path.name} is an "
                     f"{self.sweep.terrain.upper()} sweep: its points have no checkpoints, "
                     "nothing to park")
            return 0
        parked = same = 0
        # a sweep running on a bed it did not pour: the bed its points' checkpoints name
        self.parked_bed = self.parked_beds([(p, "") for p in self.sweep.points
                                            if not (self.point_dir(p) / DONE_FILE).exists()])
        for p in self.sweep.points:
            d = self.point_dir(p)
            if (d / DONE_FILE).exists():
                continue
            try:
                step, written = archive.park(self.archive, d, p.reldir, PART_FILE,
                                             self._bed_sha(p), self.repo,
                                             extra=self._park_record(p))
            except (OSError, ValueError, KeyError) as e:
                self.say(f"wheel-sweep: error: could not park {p.reldir}: {e}")
                return 1
            if step is None:
                continue
            progress = _park_progress(p, d, step)
            if written:
                parked += 1
                self.say(f"wheel-sweep: parked {p.reldir} at step {step} ({progress}; "
                         f"{written / 1e6:.1f} MB in {self.archive / p.reldir / 'parked'})")
            else:
                same += 1
                self.say(f"wheel-sweep: {p.reldir}: step {step} is parked already ({progress})")
        self.say(f"wheel-sweep: --park: {parked} point(s) parked, {same} unchanged"
                 + ("" if parked or same else " (no unfinished point has a checkpoint)"))
        return 0

    def _unpark(self, todo):
        """Copies back the parked checkpoints of the points to run that have none here (a new
        machine); returns {reldir: parked record}."""
        out = {}
        for p, _ in todo:
            record = archive.unpark(self.archive, self.point_dir(p), p.reldir)
            if record is not None:
                out[p.reldir] = record
                self.say(f"wheel-sweep: {p.reldir}: its checkpoint at step {record['step']} "
                         f"(t = {record['time_s']:g} s, parked {record['parked_utc']}) restored "
                         "from the archive")
        return out

    def _check_unparked_beds(self):
        """A point unparked onto another preparation of its bed cannot resume (the bed is one
        of its checkpoint's inputs): its checkpoint is removed here, so it runs from scratch."""
        for p in self.sweep.points:
            record = self.unparked.get(p.reldir)
            if record is None or record.get("bed_sha256") == self._bed_sha(p):
                continue  # (a bed not poured: the one its checkpoint was parked on)
            shutil.rmtree(self.point_dir(p) / archive.CHECKPOINTS, ignore_errors=True)
            self.say(f"wheel-sweep: warning: {p.reldir}: its parked checkpoint ran on another "
                     f"preparation of its bed (sha256 {record.get('bed_sha256')} then, "
                     f"{self._bed_sha(p)} now): it runs from scratch")

    def _check_restored_beds(self):
        """Names the restored points that ran on another preparation of their bed."""
        for p in self.sweep.points:
            if p.reldir not in self.restored or self.status.get(p.index) != "done":
                continue
            if not self.bed_restart(p.soil).is_file():
                continue  # no bed prepared (nothing left to run): nothing to compare
            then = archive.archived_bed(self.archive, p.reldir)
            now = self._bed_sha(p)
            if then is not None and then != now:
                self.say(f"wheel-sweep: warning: {p.reldir} (restored from the archive) ran on "
                         f"another preparation of its bed: sha256 {then} then, {now} now")

    def _run_points(self, todo):
        if not todo:
            return
        jobs = max(1, min(self.jobs, len(todo)))
        self.say(f"wheel-sweep: running {len(todo)} point(s), {jobs} at a time")
        self.jobs_used = jobs
        counter = {"started": 0, "finished": 0, "total": len(todo), "running": {}, "walls": []}
        with ThreadPoolExecutor(max_workers=jobs) as ex:
            pending = {ex.submit(self.run_point, p, counter) for p, _ in todo}
            kill_at = None
            while pending:
                done, pending = wait(pending, timeout=0.5, return_when=FIRST_COMPLETED)
                for f in done:
                    if not f.cancelled():  # cancelled: a point not started before a stop
                        f.result()  # re-raise a bug in run_point
                if self.stop_signal is not None:
                    for f in pending:
                        f.cancel()
                    if kill_at is None:
                        kill_at = time.monotonic() + KILL_GRACE_S
                    elif time.monotonic() > kill_at:
                        self._signal_children(signal.SIGKILL)

    def _dry_run(self, todo):
        runs = {p.index: why for p, why in todo}
        if self.sweep.terrain == "dem" and todo:
            self.prepare_beds()
        for p in self.sweep.points:
            if p.index in runs:
                self.say(f"  would run {self.describe(p)} ({runs[p.index]}): {p.reldir}")
                self.say(f"      {p.setting}")
                self.say("      " + " ".join(self.command(p)))
            else:
                self.say(f"  finished  {self.describe(p)}: {p.reldir}/{RUN_FILE}")
        bad = self.check_points()
        if bad is None:
            pass
        elif bad:
            for p, msg in bad:
                print(f"wheel-sweep: error: point {p.reldir} ({self.describe(p)}): {msg}",
                      file=sys.stderr, flush=True)
            self.say(f"wheel-sweep: dry run: {len(bad)} of {len(self.sweep.points)} point(s) "
                     "have an invalid rig config (wheel-rig --check); nothing written")
            return 2
        else:
            self.say(f"wheel-sweep: dry run: the {len(self.sweep.points)} rig config(s) pass "
                     "wheel-rig --check")
        self.say(f"wheel-sweep: dry run: {len(todo)} point(s) to run, "
                 f"{len(self.sweep.points) - len(todo)} finished; nothing written")
        return 0

    def check_points(self):
        """Every point's rig config through `wheel-rig --check` (the checks of a run, nothing
        run): [(point, message)] of the invalid ones; None (with a warning) when this build's
        wheel-rig cannot check. The configs go to a temporary directory; messages name the
        point's rig.toml."""
        rig = self.build / "bin" / "wheel-rig"
        try:
            helptext = subprocess.run([str(rig), "--help"], capture_output=True, text=True,
                                      timeout=30).stdout
        except (OSError, subprocess.SubprocessError):
            helptext = ""
        if "--check" not in helptext:
            self.say(f"wheel-sweep: warning: rig configs not checked ({rig} not built, or "
                     "without --check)")
            return None
        with tempfile.TemporaryDirectory(prefix="wheel-sweep-check-") as tmp:
            def check(p):
                path = Path(tmp) / f"{p.index}.toml"
                path.write_text(self.rig_file_text(p))  # as rig.toml: same line numbers
                cmd = [str(rig), "--check", "--quiet", "--config", str(path)]
                if self.sweep.terrain == "dem":  # what wheel-cosim adds
                    cmd += ["--endpoint", f"ipc://{tmp}/rig.sock"]
                    depth = self._bed_depth(p.soil)
                    if depth is not None:
                        cmd += ["--surface-height", depth]
                r = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp,
                                   stdin=subprocess.DEVNULL)
                if r.returncode == 0:
                    return None
                msg = (r.stderr.strip() or r.stdout.strip()
                       or f"wheel-rig --check exited {r.returncode}")
                msg = msg.replace(str(path), str(self.point_dir(p) / "rig.toml"))
                return p, msg.removeprefix("wheel-rig: ")
            with ThreadPoolExecutor(max_workers=max(1, self.jobs)) as ex:
                results = list(ex.map(check, self.sweep.points))
        return [r for r in results if r is not None]

    def _bed_depth(self, soil):
        """A DEM bed's bed_depth (its .vars file) as text, or None before it is prepared."""
        try:
            for line in Path(f"{self.bed_restart(soil)}.vars").read_text().splitlines():
                f = line.split()
                if len(f) >= 4 and f[0] == "variable" and f[1] == "bed_depth":
                    return f[3]
        except OSError:
            pass
        return None

    def check_health(self):
        """Reads /health of every point's run file (run.h5, or run.part.h5 of a failed point)
        and lists the points whose run is not healthy."""
        for p in self.sweep.points:
            st = self.status.get(p.index)
            f = self.point_dir(p) / (RUN_FILE if st == "done" else PART_FILE)
            if st in ("done", "failed") and f.is_file():
                self.health[p.index] = health.run_health(f)
        rows = [(p.reldir, *self.health[p.index]) for p in self.sweep.points
                if self.health.get(p.index, ("healthy",))[0] != "healthy"]
        if rows:
            self.say(f"wheel-sweep: {len(rows)} point(s) whose run is not healthy (their /health; "
                     f"{', '.join(health.UNTRUSTED)} count as failed):")
            for line in health.table(rows):
                self.say(line)

    def untrusted(self):
        """Indices of done points whose run is not to be trusted (health.UNTRUSTED)."""
        return [p.index for p in self.sweep.points if self.status.get(p.index) == "done"
                and self.health.get(p.index, ("",))[0] in health.UNTRUSTED]

    def _summary(self, n, skipped, ran):
        counts = {}
        for p in self.sweep.points:
            st = self.status.get(p.index, "pending")
            counts[st] = counts.get(st, 0) + 1
        parts = [f"{counts.get('done', 0)} done ({skipped} skipped as finished)"]
        bad = self.untrusted()
        if bad:
            parts[0] += f" of which {len(bad)} not to be trusted (unhealthy, crashed or unreadable)"
        for st in ("failed", "interrupted", "pending"):
            if counts.get(st):
                parts.append(f"{counts[st]} {st}")
        self.say(f"wheel-sweep: {n} point(s): {', '.join(parts)}.")
        self.say(f"wheel-sweep: output {self.out}; manifest {self.out / 'manifest.csv'}")
        if self.stop_signal is not None:
            return 128 + self.stop_signal
        return 0 if counts.get("done", 0) == n and not bad else 1
