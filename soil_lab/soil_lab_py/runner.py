"""`soil-lab run`: prepares the tool meshes and beds, runs the lab decks with LIGGGHTS, resumably.

Layout of the output directory (docs/soil-lab.md, "Outputs"):
  soil.toml                  the soil's variables the tests were sized by, the preset
  meshes/<name>.obj          tool meshes (wheel-mesh tool)
  beds/<bed>/                in.soilbin's restart, .vars and log (bulk density, porosity)
  <run>/                     one directory per deck run: its CSV or dump, log, done.json
Every step writes done.json (inputs hash, wall time, particles) last; a step whose done.json
matches its inputs is skipped on a re-run, so an interrupted lab resumes where it stopped. A test
run's inputs name its bed by the bed's recipe (what in.soilbin made it from, and on how many
ranks), not by the restart file's bytes: a multisphere bed's restart holds memory addresses, so
the same recipe never writes the same file twice (docs/soil-lab.md "A lab across sessions"). A plate
or shear run that was stopped goes on from its last checkpoint (<run>/checkpoints/: restart files
lab-<start step>-<step>.restart, soil_lab/decks/lab_run.in), not from its start.
"""

import hashlib
import json
import os
import re
import shutil
import subprocess
import time
from pathlib import Path
from typing import NamedTuple

from wheelsim_post import accepted_change, bed_hold, liggghts_log, mpi_launch, step_archive
from wheelsim_post.deck_files import deck_includes

from .checkpoints import STATE, Checkpoints
from .plan import OUTPUTS, LabInputError, SoilInfo, run_dt_s
from .progress import RunProgress, run_length, run_progress, run_steps

DECKS = Path(__file__).resolve().parent.parent / "decks"
# Tests whose decks write checkpoints (lab_start.in, lab_checkpoints.in, lab_run.in); the repose
# test does not (its frozen base is a group made from positions at its start, and its output is
# one dump at the end).
CHECKPOINTED_TESTS = ("plate", "shear")
SHEAR_START_FILE = "shear_start_step.txt"  # in.lab_shear's record of the step its shear began
DEFAULT_CHECKPOINTS = 10  # restart files over a plate or shear run: at most 10 % of it is redone


class LabRunError(RuntimeError):
    """A LIGGGHTS or wheel-mesh run failed; the message names it and its log."""


class StepKey(NamedTuple):
    """What decides a step's result (Lab._key)."""
    inputs: str  #: hash of the settings and the files' contents
    included: dict  #: {path: sha256} of the files the LIGGGHTS inputs include in turn
    parts: dict  #: {"settings": sha256, path: sha256 per file}: which of them changed (done.json)
    made_from: tuple = ()  #: Lab._key's (parts, files, named): rebuilt with accepted files' old hashes


class Bed(NamedTuple):
    """A prepared bed: its restart, that file's sha256 (read once per lab), and its recipe (what
    test runs on it name it by)."""
    restart: str
    restart_sha256: str
    recipe: dict  #: {"inputs", "included_sha256", "np"}: the bed's StepKey and the ranks that made it

    def prepared(self):
        return self


class LazyBed:
    """A bed of the plan not prepared here whose record the archive holds (ARCHIVE/beds/<bed>/,
    restored into OUT/beds/<bed>/: done.json, the bed-hold record, the restart's .vars): the
    runs on it name it by that record's recipe and restart path, so a finished run is kept and a
    parked one resumes (from its checkpoint and the .vars) without pouring the bed again;
    `prepared()` pours it the first time a run must start from it (docs/soil-lab.md "Beds
    poured only when a run needs them")."""

    def __init__(self, lab, soil, spec, record):
        self._lab, self._soil, self._spec, self._bed = lab, soil, spec, None
        self.restart = record["result"]["restart"]
        self.restart_sha256 = record.get("restart_sha256")
        self.recipe = _recipe(record)

    def prepared(self):
        if self._bed is None:
            self._bed = self._lab.bed(self._soil, self._spec)
        return self._bed


def _recipe(done):
    """A bed's recipe from its done.json (Lab.bed): what the runs on it name it by."""
    return {"inputs": done["inputs"], "included_sha256": done.get("included_sha256"),
            "np": done.get("np")}


def _sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _with_hashes(value, hashes):
    """`value` (settings: dicts, lists, strings) with each dict entry whose key is a path of
    `hashes` set to that hash: a bed recipe as it was before an accepted edit (Lab._accept)."""
    if isinstance(value, dict):
        return {k: hashes[k] if k in hashes and isinstance(v, str) else _with_hashes(v, hashes)
                for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(_with_hashes(v, hashes) for v in value)
    return value


def resolve_soil_file(soil, inputs_dir):
    """SOIL is a shipped name (inputs/soils/NAME.in) or a path to any soil include file."""
    p = Path(soil)
    if p.suffix == ".in" or os.sep in soil:
        if not p.is_file():
            raise LabInputError(f"soil file '{soil}' not found")
        return str(p.resolve())
    shipped = Path(inputs_dir) / "soils" / f"{soil}.in"
    if not shipped.is_file():
        names = sorted(q.stem for q in (Path(inputs_dir) / "soils").glob("*.in"))
        raise LabInputError(f"unknown soil '{soil}': no {shipped} (shipped soils: "
                            f"{', '.join(names)}; or give the path of your own soil file)")
    return str(shipped.resolve())


def lab_eta(walls_s, runs_left):
    """", ~X min left" of a lab with `runs_left` runs to go (the one starting counted less the
    share of it its checkpoint holds), each at the mean wall time of the runs finished so far
    (`walls_s`; runs skipped as done before at their recorded cost, not at 0 s); "" before any
    has finished."""
    if not walls_s:
        return ""
    return f", ~{sum(walls_s) / len(walls_s) * runs_left / 60:.1f} min left"


class Lab:
    def __init__(self, repo, build_dir, out_dir, np=1, quiet=False, archive=None,
                 checkpoints=DEFAULT_CHECKPOINTS, bed_hold_s=bed_hold.DEFAULT_HOLD_S,
                 stall_s=60.0 * mpi_launch.DEFAULT_STALL_MIN, accept=None, bed_np=None):
        self.repo = Path(repo)
        self.build = Path(build_dir)
        self.out = Path(out_dir)
        # --archive DIR: each finished test run's files kept in DIR/<run>/ and restored from there
        # (docs/soil-lab.md, "Stopping and resuming")
        self.archive = Path(archive).resolve() if archive is not None else None
        self.np = np
        # --bed-np: the ranks that prepare a bed. They are part of the bed's recipe (another
        # decomposition pours other grains), so a lab resumed on more ranks keeps its finished
        # and parked runs only when its beds are poured as before (docs/soil-lab.md "Resuming on
        # more ranks")
        self.bed_np = bed_np or np
        self.checkpoints = checkpoints  # restart files per plate or shear run (0: none)
        self.bed_hold_s = bed_hold_s  # [s] the bed-hold check's length (0: no check)
        # [s] a LIGGGHTS run whose log stays unchanged this long is killed (0: never); not part
        # of any step's inputs
        self.stall_s = stall_s
        # --accept-change FILE ... --reason TEXT: ({resolved path}, reason); docs/soil-lab.md
        # "Accepting an edit that changes no result"
        self.accept_files, self.accept_reason = (
            ({str(Path(f).resolve()) for f in accept[0]}, accept[1]) if accept else (set(), ""))
        self.accepted = {}  # {step directory: [accepted files, resolved]} of this invocation
        self.quiet = quiet
        self.inputs = self.repo / "inputs"
        self.liggghts = self.build / "bin" / "liggghts-wheel"
        self.wheel_mesh = self.build / "bin" / "wheel-mesh"
        for exe in (self.liggghts, self.wheel_mesh):
            if not exe.is_file():
                raise LabInputError(f"{exe} not found: build wheelsim first (scripts/build.sh) or "
                                    f"pass --build-dir")

    def say(self, msg):
        if not self.quiet:
            print(f"soil-lab: {msg}", flush=True)

    def _liggghts(self, deck, variables, log, cwd, while_running=None, np=None):
        """Runs `deck` with LIGGGHTS on `np` ranks (default the lab's --np); `while_running()` is
        called every few seconds meanwhile.
        A run whose log has not grown for stall_s is killed: LabRunError naming the deck and the
        log (the stall guard, mpi_launch.wait_watching)."""
        # mpirun dies with this process and each rank with mpirun (SIGKILL, also when the lab is
        # killed: docs/soil-lab.md "Stopping and resuming"), so no run outlives the lab; a stalled
        # run is ended the same way: mpirun SIGKILLed, its ranks die with it.
        cmd = mpi_launch.mpirun(np or self.np) + list(mpi_launch.rank_death_prefix()) + [
            str(self.liggghts), "-in", str(deck), "-log", "none", "-var", "inputs_dir",
            str(self.inputs)]
        for k, v in variables.items():
            cmd += ["-var", k, str(v)]
        with open(log, "w") as f:
            p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=cwd,
                                 preexec_fn=mpi_launch.die_with_parent(os.getpid(), who="soil-lab"))
            try:
                mpi_launch.wait_watching(p, f, self.stall_s, p.kill, Path(deck).name,
                                         "--stall-timeout", while_running)
            except mpi_launch.Stalled as e:
                raise LabRunError(str(e)) from None
        text = Path(log).read_text(errors="replace")
        if p.returncode != 0:
            errors = [ln for ln in text.splitlines() if "ERROR" in ln]
            raise LabRunError(f"{Path(deck).name} failed (exit {p.returncode}): "
                              f"{errors[-1] if errors else 'see the log'} (log: {log})")
        return text

    # --- soil ------------------------------------------------------------------------------------
    def soil_info(self, soil_file):
        log = self.out / "soil_info.log"
        text = self._liggghts(DECKS / "in.lab_soilinfo", {"soil_file": soil_file}, log, self.out)
        m = re.search(r"^soil-lab: soil (.*)$", text, re.M)
        if not m:
            raise LabRunError(f"in.lab_soilinfo printed no soil line (log: {log})")
        kv = dict(item.split("=", 1) for item in m.group(1).split())
        return SoilInfo(name=kv["name"], file=soil_file, dmin_m=float(kv["dmin"]),
                        dmax_m=float(kv["dmax"]), dref_m=float(kv["dref"]),
                        density_kg_m3=float(kv["density"]),
                        multisphere=float(kv["multisphere"]) != 0, dt_s=float(kv["dt"]),
                        youngs_Pa=float(kv["E"]))

    # --- steps with resume -----------------------------------------------------------------------
    def _done(self, directory, key):
        """The step's done.json if it finished with these inputs (a key of _key), else None."""
        f = Path(directory) / "done.json"
        if not f.is_file():
            return None
        try:
            done = json.loads(f.read_text())
        except ValueError:
            return None
        if done.get("inputs") == key.inputs and (
                # a record from before the included files were recorded is compared without them
                "included_sha256" not in done or done["included_sha256"] == key.included):
            return done
        return self._accept(f, done, key)

    def _accept(self, record_file, done, key):
        """The record `done` (of `record_file`) kept across the accepted edits (--accept-change),
        or None: only when it matches `key` rebuilt with the accepted files' recorded hashes, i.e.
        nothing but those files changed. The record then takes the new hashes and an
        `accepted_changes` entry {file, old_sha256, new_sha256, reason, utc}, written back."""
        recorded = done.get("included_sha256")
        if not self.accept_files or not key.made_from or not isinstance(recorded, dict):
            return None
        old = {f: h for f, h in recorded.items() if f in key.included and h != key.included[f]
               and str(Path(f).resolve()) in self.accept_files}
        if not old:
            return None
        parts, files, named = key.made_from
        then = self._key(*parts, files=files, named=_with_hashes(named, old), hashes=old)
        if then.inputs != done.get("inputs") or then.included != recorded:
            return None
        utc = accepted_change.utc_now()
        accepted_change.append(done, [accepted_change.entry(f, old[f], key.included[f],
                                                            self.accept_reason, utc)
                                      for f in sorted(old)])
        step = record_file.parent
        info = {k: v for k, v in done.items()
                if k not in ("inputs", "included_sha256", "inputs_parts")}
        self._finish(step, key, **info)  # the record with the new key
        done.update(inputs=key.inputs, included_sha256=key.included, inputs_parts=key.parts)
        self.accepted[str(step)] = sorted(str(Path(f).resolve()) for f in old)
        self.say(f"{step.relative_to(self.out) if step.is_relative_to(self.out) else step}: "
                 f"finished before, kept across the edit of "
                 f"{', '.join(Path(f).name for f in sorted(old))} (--accept-change)")
        return done

    @staticmethod
    def changed_inputs(directory, key):
        """Why the step's done.json does not match `key`: the names of what changed (the settings,
        files, included files), as far as the record tells; [] without a record."""
        try:
            done = json.loads((Path(directory) / "done.json").read_text())
        except (OSError, ValueError):
            return []
        old = done.get("inputs_parts")
        changed = ([name for name in sorted(set(old) | set(key.parts))
                    if old.get(name) != key.parts.get(name)] if isinstance(old, dict) else [])
        old_included = done.get("included_sha256") or {}
        changed += [f for f in sorted(set(old_included) | set(key.included))
                    if old_included.get(f) != key.included.get(f)]
        if not changed and done.get("inputs") != key.inputs:
            changed = ["its inputs (recorded before a step kept what they were made of)"]
        return changed

    def _finish(self, directory, key, **info):
        tmp = Path(directory) / "done.json.tmp"
        tmp.write_text(json.dumps({"inputs": key.inputs, "included_sha256": key.included,
                                   "inputs_parts": key.parts, **info}, indent=1) + "\n")
        os.replace(tmp, Path(directory) / "done.json")

    def _restore_step(self, directory, name):
        """Copies the archived files of step `name` into `directory` when it has no done.json
        (the resume check then decides whether it counts as finished); True if it did."""
        if step_archive.restore(self.archive / name, directory):
            self.say(f"{name}: restored from the archive {self.archive}")
            return True
        return False

    def _keep_step(self, directory, name):
        """Copies a finished step's files (its CSV or dump, log, done.json) to the archive, unless
        it holds that record already; a parked checkpoint of it is removed."""
        if not step_archive.holds(self.archive / name, directory):
            step_archive.keep(directory, self.archive / name)
        step_archive.drop_parked(self.archive / name)

    # ---- parked checkpoints (soil-lab run --park; docs/soil-lab.md "Parking a stopped run") -----
    @staticmethod
    def _checkpoints(d, run, dt_s, key=None):
        return Checkpoints(d / "checkpoints", d / OUTPUTS[run.test]["out_csv"], dt_s, key)

    def park(self, plan):
        """Keeps the newest complete checkpoint of every unfinished plate and shear run (with its
        CSV, checkpoints/state.json and the shear's start record) in ARCHIVE/<run>/parked/,
        xz-compressed, so that the lab goes on from it on another machine; runs nothing, and may
        run beside the lab that writes the checkpoints. The records of the beds prepared here go to
        ARCHIVE/beds/ too (_keep_bed), so that the next lab resumes without pouring them. Returns
        the exit status."""
        for spec in plan.beds.values():
            d, _, key = self._bed_key(plan.soil, spec)
            done = self._done(d, key)
            if done is not None and Path(done["result"]["restart"]).is_file():
                self._keep_bed(d, spec.name, done["result"]["restart"])
        parked = same = 0
        for run in plan.runs:
            d = self.out / run.name
            if run.test not in CHECKPOINTED_TESTS or (d / "done.json").exists():
                continue
            dt_s = run_dt_s(run, plan.soil.dt_s)
            ckpt = self._checkpoints(d, run, dt_s)
            c = ckpt.newest_complete()
            if c is None:
                continue
            start, step, path = c
            progress = run_progress(run, d, (step - start) * dt_s)
            kept = self.archive / run.name
            before = step_archive.parked(kept)
            if before is not None and before.get("step") == step:
                same += 1
                self.say(f"{run.name}: step {step} is parked already ({progress})")
                continue
            files = [str(path.relative_to(d)), f"checkpoints/{STATE}",
                     OUTPUTS[run.test]["out_csv"]]
            if (d / SHEAR_START_FILE).is_file():
                files.append(SHEAR_START_FILE)
            written = step_archive.park(d, kept, files, {
                "step": step, "start_step": start, "time_s": (step - start) * dt_s})
            parked += 1
            self.say(f"{run.name}: parked at step {step} ({step - start} steps into the run, "
                     f"{progress}; {written / 1e6:.1f} MB in {kept / step_archive.PARKED})")
        self.say(f"--park: {parked} run(s) parked, {same} unchanged"
                 + ("" if parked or same else " (no unfinished run has a complete checkpoint)"))
        return 0

    def _unpark(self, d, run, dt_s):
        """Copies a parked checkpoint back into a run folder that has no complete checkpoint of
        its own (a new machine); Checkpoints.prepare then takes it if the inputs are the same."""
        if self._checkpoints(d, run, dt_s).newest_complete() is not None:
            return
        record = step_archive.unpark(self.archive / run.name, d)
        if record is not None:
            self.say(f"{run.name}: its checkpoint at step {record['step']} (parked "
                     f"{record['parked_utc']}) restored from the archive {self.archive}")

    def _key(self, *parts, files=(), named=None, hashes=None):
        """The StepKey of `parts` (settings), `named` ({name: settings}, each told apart when it
        changes, e.g. the bed's recipe) and the contents of `files`: a hash of all, the
        {path: sha256} of the files the LIGGGHTS inputs among `files` (decks, soil files) include
        in turn (e.g. a soil file's base soil), and each part's hash. `hashes` ({path: sha256})
        stands in for included files' contents (_accept: the key as it was before an edit)."""
        h = hashlib.sha256()
        settings = hashlib.sha256()
        for p in parts:
            text = json.dumps(p, sort_keys=True).encode()
            h.update(text)
            settings.update(text)
        components = {"settings": settings.hexdigest()}
        for name, p in (named or {}).items():
            text = json.dumps({name: p}, sort_keys=True).encode()
            h.update(text)
            components[name] = hashlib.sha256(text).hexdigest()
        included = {}
        for f in files:
            components[str(f)] = _sha256(f)
            h.update(components[str(f)].encode())
            name = Path(f).name
            if name.endswith(".in") or name.startswith("in."):
                for g in deck_includes(f, {"inputs_dir": str(self.inputs)}):
                    included[str(g)] = (hashes or {}).get(str(g)) or _sha256(g)
        return StepKey(h.hexdigest()[:16], included, components, (parts, tuple(files), named))

    def mesh(self, name, args):
        """The tool mesh wheel-mesh tool ARGS, as meshes/<name>.obj (made once)."""
        d = self.out / "meshes"
        d.mkdir(parents=True, exist_ok=True)
        path = d / f"{name}.obj"
        key = self._key(args)[0]
        stamp = d / f"{name}.args"
        if path.is_file() and stamp.is_file() and stamp.read_text() == key:
            return path
        cmd = [str(self.wheel_mesh), "tool", *args, "--out", str(d / name), "--formats", "obj"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise LabRunError(f"wheel-mesh tool {' '.join(args)} failed: {r.stderr.strip()}")
        stamp.write_text(key)
        return path

    def _bed_key(self, soil, bed):
        """(folder, in.soilbin's variables, StepKey) of preparing `bed`."""
        d = self.out / "beds" / bed.name
        variables = {"soil_file": soil.file, "bin_length": f"{bed.length_m:.6g}",
                     "bin_width": f"{bed.width_m:.6g}", "fill_height": f"{bed.fill_height_m:.6g}",
                     "out_dir": str(d), **bed.extra_vars}
        return d, variables, self._key(variables, files=(soil.file, self.inputs / "in.soilbin"))

    def plan_bed(self, soil, bed):
        """The plan's bed `bed`: prepared here already or now (a Bed), or, when this folder has
        no preparation of it and the archive holds its record, a LazyBed (its record restored
        here for the runs' keys and the report; poured only when a run must start from it)."""
        d, _, key = self._bed_key(soil, bed)
        done = self._done(d, key)
        if done is None and self.archive is not None and not (d / "done.json").exists():
            kept = self.archive / "beds" / bed.name
            try:
                restart = json.loads((kept / "done.json").read_text())["result"]["restart"]
            except (OSError, ValueError, KeyError, TypeError):
                restart = None
            if restart is not None:
                d.mkdir(parents=True, exist_ok=True)
                for name, dest in self._bed_record_files(d, restart).items():
                    if (kept / name).is_file():
                        dest.parent.mkdir(parents=True, exist_ok=True)
                        shutil.copy2(kept / name, dest)
                done = self._done(d, key)
                if done is None:
                    self.say(f"bed '{bed.name}': the archived record does not match this lab's "
                             f"inputs: prepared again")
        if done is not None and not Path(done["result"]["restart"]).is_file():
            self.say(f"bed '{bed.name}': its record restored from the archive "
                     f"{self.archive}; poured only if a run must start from it")
            return LazyBed(self, soil, bed, done)
        return self.bed(soil, bed)

    @staticmethod
    def _bed_record_files(d, restart):
        """{name in ARCHIVE/beds/<bed>/: its place in OUT/beds/<bed>/} of a bed's record, in the
        order they are archived (done.json last): the .vars beside its restart (resume.in reads
        them with a checkpoint), the bed-hold record, done.json."""
        return {"restart.vars": Path(f"{restart}.vars"), "hold.json": d / "hold" / "done.json",
                "done.json": d / "done.json"}

    def _keep_bed(self, d, name, restart):
        """Copies a prepared bed's record (_bed_record_files: small text) to ARCHIVE/beds/<name>/,
        so that a lab on another machine need not pour it again when no run must start from it
        (plan_bed)."""
        kept = self.archive / "beds" / name
        kept.mkdir(parents=True, exist_ok=True)
        for dest, src in self._bed_record_files(d, restart).items():
            if src.is_file():  # done.json last: a half-copied record is not taken
                shutil.copy2(src, kept / dest)

    def bed(self, soil, bed):
        """Prepares `bed` with inputs/in.soilbin (skipped if done); returns its Bed."""
        d, variables, key = self._bed_key(soil, bed)
        d.mkdir(parents=True, exist_ok=True)
        deck = self.inputs / "in.soilbin"
        done = self._done(d, key)
        if done is not None and not Path(done["result"]["restart"]).is_file():
            # a record restored from the archive (plan_bed) and a run must start from the bed:
            # pour it, and check it, again
            done = None
            (d / "hold" / "done.json").unlink(missing_ok=True)
        if done is None:
            self.say(f"bed '{bed.name}': preparing {bed.length_m:.3g} x {bed.width_m:.3g} m, "
                     f"{bed.fill_height_m:.3g} m deep")
            t0 = time.monotonic()
            # soil_preparing_bed: a soil file may prepare its bed with other contact settings
            # (docs/soils.md "Preparing the bed with other contact settings"); not in the key
            text = self._liggghts(deck, {**variables, "soil_preparing_bed": 1},
                                  d / "soilbin.log", d, np=self.bed_np)
            result = dict(re.findall(r"^soilbin: (\w+) = (\S+)$", text, re.M))
            done = {"result": result, "wall_s": round(time.monotonic() - t0, 1),
                    "np": self.bed_np, "restart_sha256": _sha256(result["restart"])}
            self._finish(d, key, **done)
            self.say(f"bed '{bed.name}': {result.get('spheres')} particles, bed depth "
                     f"{float(result.get('bed_depth', 'nan')):.4g} m, bulk density "
                     f"{float(result.get('bulk_density', 'nan')):.5g} kg/m^3 ({done['wall_s']} s)")
        else:
            self.say(f"bed '{bed.name}': done before, skipped")
        restart = done["result"]["restart"]
        if self.bed_hold_s > 0:
            self.bed_hold(soil, bed.name, restart, key,
                          settled=done["result"].get("settled", "1") != "0")
        if self.archive is not None:
            self._keep_bed(d, bed.name, restart)
        return Bed(restart, _sha256(restart),
                   {"inputs": key.inputs, "included_sha256": key.included, "np": done.get("np")})

    def bed_hold(self, soil, name, restart, bed_key, settled=True):
        """The bed-hold check of bed `name` (skipped if done for this bed recipe; docs/soil-bins.md
        "The bed-hold check"): inputs/in.bedhold leaves the bed alone under the soil's test
        settings for bed_hold_s; writes beds/<name>/hold/done.json and returns its result. Raises
        LabRunError when the bed settles by more than bed_hold.SETTLE_LIMIT: the tests would run
        on another bed than the one prepared and measured."""
        d = self.out / "beds" / name / "hold"
        d.mkdir(parents=True, exist_ok=True)
        deck = self.inputs / bed_hold.DECK
        key = self._key({"hold_s": self.bed_hold_s}, named={"bed recipe": bed_key.inputs},
                        files=(deck, soil.file))
        log = d / "liggghts.log"
        done = self._done(d, key)
        when = "checked before, in "  # the record's wall time, not this run's
        if done is None:
            when = ""
            t0 = time.monotonic()
            text = self._liggghts(deck, {"restart_file": restart, "hold_s": self.bed_hold_s},
                                  log, d)
            try:
                result = bed_hold.parse(text, log)
            except bed_hold.BedHoldError as e:
                raise LabRunError(str(e)) from None
            # bed_inputs: the bed the record is of, for the report (analysis.analyse)
            done = {"result": result, "wall_s": round(time.monotonic() - t0, 1), "np": self.np,
                    "bed_inputs": bed_key.inputs}
            self._finish(d, key, **done)
        r = done["result"]
        error = bed_hold.failure(r, name, log, settled)
        if error:
            raise LabRunError(error)
        self.say(f"bed '{name}': {bed_hold.verdict(r)} under the test settings: "
                 f"{bed_hold.describe(r)} ({when}{done['wall_s']} s)")
        return r

    def run(self, soil, run, bed, progress=""):
        """Runs one plate, shear or repose deck on `bed` (a Bed, or a LazyBed poured only if the
        run must start from it; skipped when done before, resumed from its newest checkpoint when
        stopped); returns its wall time [s] (a skipped run's from its done.json). `progress`: the
        prefix of its lines, or a function of the share of this run done before (a resumed run's
        steps up to its checkpoint over its steps) that returns it (run_plan: the lab's ETA)."""
        prefix_at = progress if callable(progress) else (lambda done=0.0, text=progress: text)
        progress = prefix_at()
        d = self.out / run.name
        d.mkdir(parents=True, exist_ok=True)
        # a half-speed or half-step run uses its model's meshes
        base = run.meta.get("half_of", run.meta.get("half_dt_of", run.name))
        meshes = {var: str(self.mesh(f"{base}_{var}", args)) for var, args in run.meshes.items()}
        outputs = OUTPUTS[run.test]
        dt_s = run_dt_s(run, soil.dt_s)
        # a run at another step than the soil's (--dt-check) reads the soil through this file,
        # written below only when it runs
        soil_at_step = d / "soil_at_step.in" if dt_s != soil.dt_s else None
        deck = DECKS / run.deck

        def inputs(b):
            """(deck variables, StepKey) of the run on bed `b`."""
            v = {"restart_file": b.restart, **meshes, **run.variables,
                 **{k: str(d / f) for k, f in outputs.items()}}
            if soil_at_step:
                v["soil_file"] = str(soil_at_step)
            # the bed by its recipe, not its restart's bytes (the module's docstring)
            return v, self._key(v, run.meta, named={"bed recipe": b.recipe},
                                files=(deck, soil.file, *meshes.values()))
        variables, key = inputs(bed)
        restored = self.archive is not None and self._restore_step(d, run.name)
        done = self._done(d, key)
        if done is None and self.archive is not None and run.test in CHECKPOINTED_TESTS:
            self._unpark(d, run, dt_s)
        if done is None and restored:
            self.say(f"{progress}{run.name}: the archived record does not match this lab's inputs "
                     f"(changed: {', '.join(self.changed_inputs(d, key)) or 'unknown'}): runs again")
        if done is not None:
            bed_sha = done.get("bed_restart_sha256")
            other_bed = bed_sha is not None and bed_sha != bed.restart_sha256
            self.say(f"{progress}{run.name}: done before"
                     + (" on another preparation of the same bed recipe" if other_bed else "")
                     + ", skipped")
            if self.archive is not None:
                self._keep_step(d, run.name)
            return done.get("wall_s")
        # a run that resumes needs only its checkpoint and the bed's .vars; one that starts needs
        # the bed (a LazyBed is poured now; as another preparation it may name another recipe)
        resumes = (run.test in CHECKPOINTED_TESTS and Path(f"{bed.restart}.vars").is_file()
                   and self._checkpoints(d, run, dt_s, key[0]).resumable())
        if not resumes:
            ready = bed.prepared()
            if ready is not bed and (ready.restart, ready.recipe) != (bed.restart, bed.recipe):
                variables, key = inputs(ready)
            bed = ready
        restart = bed.restart
        if soil_at_step:
            self._write_soil_at_step(soil_at_step, soil, dt_s)
        ckpt = None
        if run.test in CHECKPOINTED_TESTS:
            csv = d / outputs["out_csv"]
            ckpt = Checkpoints(d / "checkpoints", csv, dt_s, key[0])
            resume = ckpt.prepare(restart, np=self.np)
            variables = {**variables, "lab_decks": str(DECKS),
                         "checkpoint_count": self.checkpoints, "checkpoint_dir": str(ckpt.dir),
                         **resume}
            if run.test == "shear":
                variables.update(self._shear_start(d, ckpt))
            if ckpt.resuming:
                done_steps, steps = ckpt.resumed_step - ckpt.start_step, run_steps(run, dt_s)
                share = f"{done_steps} steps done"
                if steps:
                    progress = prefix_at(min(done_steps / steps, 1.0))
                    share = f"{done_steps} of {steps} steps done, {100 * done_steps / steps:.0f} %"
                self.say(f"{progress}{run.name}: resuming from its checkpoint at step "
                         f"{ckpt.resumed_step} ({share})")
        if not (ckpt and ckpt.resuming):
            length = run_length(run, dt_s)
            self.say(f"{progress}{run.name}: running" + (f" ({length})" if length else ""))
        t0 = time.monotonic()
        watch = None
        if ckpt:
            report = RunProgress(run, d, self.say, f"{progress}{run.name}")

            def watch():
                ckpt.prune()
                report()
        text = self._liggghts(deck, variables, d / "liggghts.log", d, while_running=watch)
        wall = time.monotonic() - t0
        runs = liggghts_log.loops(text)
        n_steps = sum(r.steps for r in runs)
        particles = max((r.atoms for r in runs), default=0)
        resumed = {}
        if ckpt and ckpt.resuming:
            # the attempts before: the steps up to the checkpoint and their wall time
            n_steps += ckpt.resumed_step - ckpt.start_step
            resumed = {"resumed_at_step": ckpt.resumed_step,
                       "wall_s_before_resume": round(ckpt.wall_before_s, 1)}
            wall += ckpt.wall_before_s
        self._finish(d, key, wall_s=round(wall, 1), np=self.np, steps=n_steps,
                     particles=particles, dt_s=dt_s, meta=run.meta,
                     bed_restart_sha256=bed.restart_sha256, **resumed)
        if ckpt:
            ckpt.clear()
        if self.archive is not None:
            self._keep_step(d, run.name)
        rate = n_steps * particles / wall if wall > 0 else 0
        self.say(f"{progress}{run.name}: {n_steps} steps, {particles} particles, {wall:.0f} s "
                 f"({rate / 1e6:.2f} M particle-steps/s)")
        return wall

    @staticmethod
    def _write_soil_at_step(f, soil, dt_s):
        """The soil file `f` a run at another time step than the soil's (--dt-check) reads instead
        of the bed's (resume.in's soil_file): it includes the soil's file, both stages, and then
        sets soil_dt, which resume.in gives to `timestep` after the restart. The bed and
        everything else stay the soil's."""
        f.write_text(f"# written by soil-lab (--dt-check, docs/soil-lab.md \"The time-step check\"): "
                     f"the soil file\n# {soil.file}\n# with the time step {dt_s!r} s instead of "
                     f"{soil.dt_s!r} s.\ninclude {soil.file}\nvariable soil_dt equal {dt_s!r}\n")

    @staticmethod
    def _shear_start(d, ckpt):
        """in.lab_shear's variables for the step its shear began: the deck writes that step
        and whether the sample had consolidated (1/0) to shear_start_file when its consolidation
        ends, and a resumed attempt that had got so far passes them back (it does not consolidate
        again). A fresh start removes the file."""
        f = d / SHEAR_START_FILE
        out = {"shear_start_file": str(f)}
        if not ckpt.resuming:
            f.unlink(missing_ok=True)
        elif f.is_file():
            step, consolidated = f.read_text().split()[:2]
            out.update(shear_start_step=int(step), shear_start_consolidated=int(consolidated))
        return out

    def run_plan(self, plan):
        self.out.mkdir(parents=True, exist_ok=True)
        beds = {name: self.plan_bed(plan.soil, bed) for name, bed in plan.beds.items()}
        walls = []  # wall time of each run finished so far, in this lab or before (done.json)
        for i, run in enumerate(plan.runs):
            def prefix(done=0.0, i=i):
                """The run's line prefix; `done`: the share of it done before (resumed)."""
                return f"[{i + 1}/{len(plan.runs)}{lab_eta(walls, len(plan.runs) - i - done)}] "
            wall_s = self.run(plan.soil, run, beds[run.bed], progress=prefix)
            if wall_s:
                walls.append(float(wall_s))
