"""`soil-lab run ... --estimate`: what the lab has left to run and how long it may take, from what
this lab (its output directory and archive) already knows; runs nothing (docs/soil-lab.md "Cost
estimate"). Per run: its steps (progress.run_steps), whether it finished (a done.json here or in the
archive; its inputs are not compared: the lab does that when it runs), or was parked (the steps
done); the wall time left at a pace measured on this lab: a parked run's own last attempt (steps
from its resume to its parked checkpoint over that wall time), else the mean steps per second of
the lab's finished and parked runs on the same bed (the same particles; a plate's or box's size
moves the cost per step a little). A run with no such pace, and a bed still to prepare, are priced
at this machine's particle-step rate (`MachineRate`: wheel-sweep's `--measure-rate` cache, or its
defaults, said so) when the lab can give one; else they are named without a cost."""

import json
import lzma
import math
from pathlib import Path

from wheelsim_post import step_archive
from wheelsim_sweep import estimate as sweep_estimate
from wheelsim_sweep import rate as sweep_rate

from .plan import run_dt_s
from .progress import _int, run_steps


def _json(path, xz=False):
    try:
        raw = lzma.decompress(Path(path).read_bytes()) if xz else Path(path).read_bytes()
        return json.loads(raw)
    except (OSError, ValueError, lzma.LZMAError):
        return None


def _finished(run, out, archive):
    """(where, done.json) of a finished run: 'here' (OUT) or 'archive'; None if neither."""
    for where, d in (("here", out), ("archive", archive)):
        if d is not None:
            done = _json(Path(d) / run.name / "done.json")
            if done is not None:
                return where, done
    return None


def _parked_pace(kept):
    """(steps done at the parked checkpoint, steps per second of its last attempt or None, the
    ranks of that attempt or None when its record predates them) of a parked run
    (ARCHIVE/<run>/parked/), None when nothing is parked."""
    record = step_archive.parked(kept)
    if record is None:
        return None
    done = record["step"] - record["start_step"]
    state = _json(Path(kept) / step_archive.PARKED / "checkpoints" / "state.json.xz", xz=True)
    restart = next((f for f in record.get("files", []) if f["path"].endswith(".restart")), None)
    try:
        last = state["attempts"][-1]
        steps = record["step"] - last.get("resumed_at_step", record["start_step"])
        wall = restart["mtime_unix"] - last["start_unix"]
        return done, (steps / wall if steps > 0 and wall > 0 else None), last.get("np")
    except (TypeError, KeyError, IndexError):
        return done, None, None


def rescaled(pace, ranks_then, ranks_now, efficiency_np2):
    """(steps per second, how) of a pace measured on `ranks_then` ranks, at `ranks_now` (the
    ranks' throughput with wheel-sweep's efficiency model); unchanged when either is unknown or
    they are the same."""
    if not ranks_then or not ranks_now or ranks_then == ranks_now:
        return pace, ""
    speed = (ranks_now * sweep_estimate.efficiency(ranks_now, efficiency_np2)
             / (ranks_then * sweep_estimate.efficiency(ranks_then, efficiency_np2)))
    return pace * speed, f"measured on {ranks_then} rank(s), x {speed:.2f} for {ranks_now}"


class MachineRate:
    """This machine's LIGGGHTS throughput (a wheel-sweep Rate: particle-steps per second per rank,
    its 2-rank efficiency, its bed rate) for the runs and beds this lab has no pace of: a run's
    pace is rate x np x efficiency / its bed's spheres. `sv` is the soil file's variables
    (wheel-sweep's soil query: sieve classes, density, dt) and `defaults` in.soilbin's, for the
    spheres of a bed not prepared yet (its bin x fill height x fill solid fraction / the mean
    grain: an estimate) and its preparation's steps (in.soilbin's upper bounds). A multisphere
    soil's particles are counted in spheres: `mix` is wheel-sweep's spheres_per_particle (ratio,
    how), the ratio None when the distribution does not tell it."""

    def __init__(self, rate, np_, sv, defaults, mix=(1.0, "single spheres"), bed_np=None):
        self.rate, self.np, self.sv, self.defaults = rate, np_, sv, defaults
        self.bed_np = bed_np or np_  # the ranks that prepare a bed (--bed-np)
        self.mix = mix

    @property
    def clumps_uncounted(self):
        """True for a multisphere soil whose spheres per particle are not known (its estimate is
        low by the clumps' extra spheres)."""
        return bool(self.sv.get("soil_multisphere")) and self.mix[0] is None

    @classmethod
    def of_this_machine(cls, liggghts, np_, soil_file, inputs_dir, soilbin, bed_np=None):
        """The cached rate (or wheel-sweep's defaults, said in `source`); an EstimateError (from
        wheel-sweep) when LIGGGHTS or the soil cannot be asked."""
        key = sweep_rate.machine_key(sweep_rate.liggghts_version(liggghts))
        rate = sweep_rate.lookup(sweep_rate.cache_path(), key)
        sv = sweep_estimate.soil_vars(liggghts, soil_file, inputs_dir)
        mix = (sweep_estimate.spheres_per_particle(liggghts, soil_file, inputs_dir)
               if sv.get("soil_multisphere") else (1.0, "single spheres"))
        return cls(rate, np_, sv, sweep_estimate.soilbin_defaults(soilbin), mix, bed_np)

    def pace(self, spheres, bed=False):
        """Steps per second of a run (or a bed's preparation) on `spheres` spheres."""
        per_rank = self.rate.bed_rate_per_rank if bed else self.rate.rate_per_rank
        n = self.bed_np if bed else self.np
        return (per_rank * n * sweep_estimate.efficiency(n, self.rate.efficiency_np2)
                / spheres)

    def _recipe(self, bed):
        return {"bin_length": bed.length_m, "bin_width": bed.width_m,
                "fill_height": bed.fill_height_m, **bed.extra_vars}

    def bed_spheres(self, bed):
        """(spheres, how) of a bed to prepare: an estimate from its recipe."""
        vol, how = sweep_estimate.mean_grain_volume(self.sv)
        r = self._recipe(bed)
        fill = float(r.get("fill_solid_fraction", self.defaults.get("fill_solid_fraction", 0.6)))
        n = bed.length_m * bed.width_m * bed.fill_height_m * fill / vol
        how = f"bin x fill solid fraction {fill:g} / mean grain, {how}"
        if self.clumps_uncounted:
            # the sieve classes count a clump once, its cost goes by its spheres (loose sand's
            # plate bed: 32 067 particles, 67 348 spheres)
            how += (f"; multisphere: clumps counted once, so low by their extra spheres "
                    f"({self.mix[1]})")
        elif self.sv.get("soil_multisphere"):
            # the particles (a clump's volume taken as a sieve-class grain's) times the spheres
            # each carries on average (loose sand's plate bed: 32 067 particles x 2.1 = 67 348)
            n *= self.mix[0]
            how += f"; multisphere: x {self.mix[1]}"
        return n, how

    def bed_steps(self, bed):
        """Steps of preparing `bed` (in.soilbin's upper bounds at the soil's dt)."""
        parts = sweep_estimate.bed_prep_times(self._recipe(bed), self.defaults, self.sv)
        return math.ceil(sum(parts.values()) / self.sv["soil_dt"] - 1e-9)


def _bed_spheres(record):
    """Spheres of a bed by its done.json (`record`, a path), None if not known."""
    done = _json(record) or {}
    try:
        return int(float(done["result"]["spheres"]))
    except (KeyError, TypeError, ValueError):
        return None


def lab_estimate(plan, out, archive=None, machine=None, np_=None):
    """The estimate's lines (without the 'soil-lab: ' prefix). machine: a MachineRate for what
    this lab has no pace of (None: left unpriced). np_: the ranks the lab will run on (default
    the machine's); a pace measured on other ranks is rescaled to them (`rescaled`)."""
    lines, total_steps, total_wall, unknown = [], 0, 0.0, 0
    machine_used = False
    np_ = np_ or (machine.np if machine is not None else None)
    e2 = (machine.rate.efficiency_np2 if machine is not None
          else sweep_rate.DEFAULT["efficiency_np2"])
    paces = {}   # bed -> [(steps/s, how)] of the lab's finished and parked runs on it, at np_
    parked = {}  # run -> (steps done, (steps/s, how) or None)
    finished = {}  # run -> (where, done.json) of the runs finished here or in the archive
    for run in plan.runs:
        found = finished[run.name] = _finished(run, out, archive)
        if found and found[1].get("wall_s") and found[1].get("steps"):
            paces.setdefault(run.bed, []).append(rescaled(
                found[1]["steps"] / found[1]["wall_s"], found[1].get("np"), np_, e2))
        elif not found and archive is not None:
            kept = _parked_pace(Path(archive) / run.name)
            if kept is not None:
                done, pace, ranks = kept
                parked[run.name] = done, (rescaled(pace, ranks, np_, e2) if pace else None)
                if pace:
                    paces.setdefault(run.bed, []).append(parked[run.name][1])
    # each bed's spheres for the machine's rate, read or estimated once: (spheres, as the run
    # lines name them)
    counts = {}
    for name, bed in plan.beds.items():
        record = Path(out) / "beds" / name / "done.json"
        prepared = record.is_file()
        # a bed whose record the archive keeps is poured only when a run must start from it
        # (runner.LazyBed): not when each of its runs finished or was parked
        archived = archive is not None and (Path(archive) / "beds" / name / "done.json").is_file()
        if not prepared and archived:
            record = Path(archive) / "beds" / name / "done.json"
        if machine is not None and bed is not None:
            spheres = _bed_spheres(record) if prepared or archived else None
            if spheres is not None:
                counts[name] = spheres, f"its bed's {_int(spheres)} spheres"
            else:
                spheres, how = machine.bed_spheres(bed)
                counts[name] = spheres, f"~{_int(int(round(spheres, -2)))} spheres estimated" + (
                    ", clumps counted once: low" if machine.clumps_uncounted else "")
        if prepared:
            continue
        if archived and all(r.name in parked or finished[r.name]
                            for r in plan.runs if r.bed == name):
            lines.append(f"estimate: bed '{name}': not poured (its record in the archive, every "
                         "run on it finished or parked)")
            continue
        if machine is None or bed is None:
            lines.append(f"estimate: bed '{name}': to prepare here (its cost is not estimated)")
            continue
        steps = machine.bed_steps(bed)
        wall = steps / machine.pace(spheres, bed=True)
        total_wall += wall
        machine_used = True
        lines.append(f"estimate: bed '{name}': to prepare here, ~{_int(int(round(spheres, -2)))} "
                     f"spheres ({how}), <= {_int(steps)} steps, <= "
                     f"{sweep_estimate.fmt_time(wall)} at this machine's rate (+ its bed-hold "
                     "check)")
    for i, run in enumerate(plan.runs, 1):
        head = f"estimate: [{i}/{len(plan.runs)}] {run.name}"
        found = finished[run.name]
        if found:
            lines.append(f"{head}: finished before ({found[0]}; the lab compares its inputs)")
            continue
        steps = run_steps(run, run_dt_s(run, plan.soil.dt_s))
        if steps is None:
            lines.append(f"{head}: to run (length not known beforehand)")
            unknown += 1
            continue
        left, pace, how, at = steps, None, "", ""
        if parked.get(run.name) is not None:
            done, own = parked[run.name]
            left = max(0, steps - done)
            how = f"parked with {_int(done)} of {_int(steps)} steps done"
            if own is not None:
                pace, at = own[0], (f" ({own[1]})" if own[1] else "")
        if pace is None and paces.get(run.bed):
            pace = sum(p for p, _ in paces[run.bed]) / len(paces[run.bed])
            scaled = sorted({h for _, h in paces[run.bed] if h})
            at = f" ({'; '.join(scaled)})" if scaled else ""
        text = f"{head}: {_int(left)} steps to run" + (f" ({how})" if how else "")
        if pace is None and run.bed in counts:
            spheres, count = counts[run.bed]
            pace = machine.pace(spheres)
            at = f" (this machine's rate, {count})"
            machine_used = True
        if pace:
            wall = left / pace
            text += (f", ~{wall / 60:.0f} min" if wall >= 60 else f", ~{wall:.0f} s") + \
                f" at {pace:.0f} steps/s{at}"
            total_wall += wall
        else:
            text += ", pace unknown (no finished or parked run of this lab on its bed)"
            unknown += 1
        total_steps += left
        lines.append(text)
    if machine_used:
        r = machine.rate
        lines.append(f"estimate: this machine's rate: {r.rate_per_rank:.3g} particle-steps/s per "
                     f"rank (beds {r.bed_rate_per_rank:.3g}), {machine.np} rank(s)"
                     + (f" (beds {machine.bed_np})" if machine.bed_np != machine.np else "")
                     + f", np-2 "
                     f"efficiency {r.efficiency_np2:.2f}: {r.source}")
    lines.append(f"estimate: {_int(total_steps)} steps to run, ~{total_wall / 3600:.1f} h of wall "
                 "time at the measured paces" + (" and this machine's rate" if machine_used
                                                 else "")
                 + (f" + {unknown} run(s) of unknown length or pace" if unknown else "")
                 + "; nothing was run")
    return lines
