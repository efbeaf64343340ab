"""The cost of a DEM sweep before it runs (issue 12 item 4). Reference: docs/sweeps.md,
"Cost estimate".

Model (one formula, `point_wall`): a coupled point costs

    wall = startup + steps * N / (rate * np * eff(np)) * oversubscription

N the bed's particles (spheres), steps = ceil(simulated time / dt), rate the particle-step rate
of one LIGGGHTS rank [particle-steps/s] measured on this machine (rate.py, cached), eff(np) the
parallel efficiency (1 at np 1, the measured np-2 efficiency e2 at np 2, e2^log2(np) beyond: an
extrapolation, not a measurement), oversubscription = max(1, ranks running at once / cores).
The simulated time is the rig's phases (docs/rig-config.md): release (the held spindle closing
run.release_gap plus RELEASE_SINK_FRACTION x the wheel's outer radius at run.release_speed,
reached over 0.1 s), settle (run.settle_max_time: an upper bound), ramp (motor.ramp_time) and
test (run.duration); LIGGGHTS runs whole chunks of the deck's `chunk` steps. A point also costs
COSIM_OVERHEAD_S for wheel-cosim's launch and finish. Points run `jobs` at a time in config order
(list scheduling, as the driver starts them); beds from recipes not yet prepared are prepared
one after another before the points, their settling counted up to max_settle_time (an upper
bound; compaction phases added).

Particles: a prepared bed's LIGGGHTS log (`soilbin: spheres = N`), else its .vars (bulk density x
bin volume / (particle density x mean grain volume)), else the recipe: bin_length x bin_width x
fill_height x fill_solid_fraction / mean grain volume. Grain sizes come from LIGGGHTS itself:
the soil file is run with soil_vars_only = 1 (`soil_vars`), so expressions in soil files are
evaluated as LIGGGHTS does. Time step: run.dt, else the bed's bed_dt, else the soil's soil_dt.
"""

import math
import re
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from wheelsim_post.deck_files import deck_includes, deck_variable

from . import active_domain

RELEASE_ACCEL_TIME_S = 0.1  # the rig reaches run.release_speed linearly over 0.1 s (rig-config.md)
# After closing the gap the held spindle goes on sinking into the soil until the soil carries the
# load; that depth is not known beforehand. Allowance: 0.15 x the wheel's outer radius (measured:
# test_small, R 0.10 m, 15 N on the ci bin of dem_small_slips: release 0.423 s = 0.13 s to close
# the 4 mm gap + 14.7 mm more at 0.05 m/s = 0.147 R; docs/sweeps.md "Cost estimate").
RELEASE_SINK_FRACTION = 0.15
# wheel-cosim's own cost per point beyond LIGGGHTS' start-up (mpirun, the rig's start, waiting
# for both to finish, the run file's last write): measured 3.3-6.5 s minus the benchmark's 1 s
# start-up on the busy 2-core machine (dem_small_slips, 3 points).
COSIM_OVERHEAD_S = 3.0
# rig defaults of the [run] and [motor] keys used here (docs/rig-config.md, "Configuration keys")
RIG_DEFAULTS = {"release_gap": 0.002, "release_speed": 0.01, "settle_max_time": 5.0,
                "ramp_time": 1.0}
SOIL_QUERY_TIMEOUT_S = 30.0
# With the active domain, a frozen particle's cost per step as a fraction of an active one's:
# not only mask tests but LIGGGHTS' neighbour-list builds over every particle (with the frozen
# pairs' exclusion test) and its per-particle passes. Measured at study scale, where it matters
# (docs/sweeps.md "Cost estimate"): validation case 3's wheel1 point at 20 % slip, np 2, with and
# without the active domain on the same bed.
FROZEN_COST = 0.23


class EstimateError(Exception):
    """The estimate cannot be made; the message says which input is missing or bad."""


def fmt_time(s):
    """Wall time for people: 42.0 s, 3 min 5 s, 2 h 10 min."""
    if s < 60:
        return f"{s:.1f} s"
    if s < 3600:
        return f"{int(s // 60)} min {int(s % 60)} s"
    return f"{int(s // 3600)} h {int(s % 3600 // 60)} min"


def fmt_int(n):
    return f"{int(round(n)):,}".replace(",", " ")


# ---- the rate and the wall-time formula ---------------------------------------------------------
@dataclass
class Rate:
    """LIGGGHTS' throughput on this machine. rate_per_rank: particle-steps/s of one rank running
    a coupled-like wheel run; efficiency_np2: speed-up at np 2 / 2; startup_s: wall time of a run
    outside its steps (start, read the bed, finish); bed_rate_per_rank: the same as rate_per_rank
    while a bed settles (in.soilbin)."""
    rate_per_rank: float
    efficiency_np2: float
    startup_s: float
    bed_rate_per_rank: float
    source: str = ""  # where the numbers come from, for the printout


def efficiency(np_, e2):
    """Parallel efficiency at np ranks: 1 at np 1, e2 at np 2, e2^log2(np) beyond."""
    return 1.0 if np_ <= 1 else e2 ** math.log2(np_)


def oversubscription(ranks_at_once, cores):
    return max(1.0, ranks_at_once / cores)


def run_wall(particles, steps, np_, rate_per_rank, e2, startup_s, over=1.0):
    """Wall time [s] of one LIGGGHTS run of `steps` steps of `particles` on np ranks."""
    return startup_s + steps * particles / (rate_per_rank * np_ * efficiency(np_, e2)) * over


def schedule(walls, jobs):
    """Wall time of running `walls` (in order) `jobs` at a time: each starts on the first free
    slot, as the driver's thread pool does."""
    slots = [0.0] * max(1, min(jobs, len(walls)))
    for w in walls:
        i = slots.index(min(slots))
        slots[i] += w
    return max(slots) if walls else 0.0


# ---- the rig's simulated time -------------------------------------------------------------------
def release_time(gap, speed, accel_time=RELEASE_ACCEL_TIME_S):
    """Time [s] for the held spindle to close `gap` [m]: speed rises linearly to `speed` [m/s]
    over accel_time, then stays."""
    d_accel = 0.5 * speed * accel_time
    if gap <= d_accel:
        return math.sqrt(2.0 * gap * accel_time / speed)
    return accel_time + (gap - d_accel) / speed


def wheel_extent(rig, mesh=None):
    """(bounding radius, outer radius) [m] of the wheel mesh `mesh` (else the rig's wheel.mesh;
    ascii STL, as LIGGGHTS reads) x wheel.mesh_scale (active_domain.mesh_extent), else None."""
    w = rig.get("wheel", {})
    return active_domain.mesh_extent(mesh or w.get("mesh"), float(w.get("mesh_scale", 1.0)))


def wheel_radius(rig, mesh=None):
    """The wheel's outer radius [m]: wheel.effective_radius, else the largest distance of the
    mesh's vertices from the axle (y; wheel_extent), else None."""
    w = rig.get("wheel", {})
    if isinstance(w.get("effective_radius"), (int, float)):
        return float(w["effective_radius"])
    ext = wheel_extent(rig, mesh)
    return ext[1] if ext else None


def phases(rig, radius=None):
    """The point's simulated phases [s] from its rig config: release (closing the gap and
    sinking RELEASE_SINK_FRACTION x radius [m], if given), settle (upper bound), ramp, test.
    Raises EstimateError naming a missing or bad key."""
    run, motor = rig.get("run", {}), rig.get("motor", {})

    def num(table, tname, key, default=None):
        v = table.get(key, default)
        if v is None:
            raise EstimateError(f"rig config: {tname}.{key} is not set (needed for the "
                                "simulated time)")
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not v >= 0:
            raise EstimateError(f"rig config: {tname}.{key} must be a number >= 0, got {v!r}")
        return float(v)
    gap = num(run, "run", "release_gap", RIG_DEFAULTS["release_gap"])
    speed = num(run, "run", "release_speed", RIG_DEFAULTS["release_speed"])
    if speed <= 0:
        raise EstimateError(f"rig config: run.release_speed must be > 0 m/s, got {speed!r}")
    sink = RELEASE_SINK_FRACTION * radius if radius else 0.0
    return {"release": release_time(gap + sink, speed),
            "settle": num(run, "run", "settle_max_time", RIG_DEFAULTS["settle_max_time"]),
            "ramp": num(motor, "motor", "ramp_time", RIG_DEFAULTS["ramp_time"]),
            "test": num(run, "run", "duration")}


# ---- soils and beds -----------------------------------------------------------------------------
_VAR_NAME_RE = re.compile(r"^\s*variable\s+(soil_[dw]\d+)\s+equal\s", re.M)
_SCALARS = ("soil_name", "soil_dt", "soil_density", "soil_dref", "soil_dmax", "soil_multisphere")


def soil_vars(liggghts, soil_file, inputs_dir):
    """The soil file's variables as LIGGGHTS evaluates them (soil_vars_only = 1): soil_name,
    soil_dt [s], soil_density [kg/m^3], soil_dref [m], soil_multisphere, and the sieve classes
    soil_d<i> [m] and mass fractions soil_w<i> that the file defines. Runs liggghts-wheel once
    (serial, under a second)."""
    # the sieve classes may be defined in a file the soil file includes (a variant of a base soil)
    files = [Path(soil_file)] + deck_includes(soil_file, {"inputs_dir": str(inputs_dir)})
    text = "".join(f.read_text(errors="replace") for f in files)
    names = list(_SCALARS) + sorted(set(_VAR_NAME_RE.findall(text)))
    try:
        r = _ask_soil(liggghts, soil_file, inputs_dir,
                      [f"wheel_sweep_var {n} ${{{n}}}" for n in names])
    except (OSError, subprocess.SubprocessError) as e:
        raise EstimateError(f"soil file {soil_file}: LIGGGHTS ({liggghts}) could not be asked "
                            f"for its variables: {e}")
    out = {}
    for line in r.stdout.splitlines():
        f = line.split()
        if len(f) >= 3 and f[0] == "wheel_sweep_var":
            out[f[1]] = f[2]
    missing = [n for n in names if n not in out]
    if r.returncode != 0 or missing:
        last = (r.stdout.strip().splitlines() or [""])[-1]
        raise EstimateError(f"soil file {soil_file}: LIGGGHTS did not give "
                            f"{', '.join(missing) or 'its variables'} "
                            f"(exit {r.returncode}: {last})")
    return {k: (v if k == "soil_name" else float(v)) for k, v in out.items()}


# A multisphere soil's particles carry several spheres each, and LIGGGHTS' cost goes by spheres:
# its particle distribution (the templates' nspheres, the number-based weights) says how many.
_TEMPLATE_RE = re.compile(r"^[ \t]*fix\s+(\S+)\s+\S+\s+particletemplate/(sphere|multisphere)\b"
                          r"([^\n]*)", re.M)
_DIST_RE = re.compile(r"^[ \t]*fix\s+(\S+)\s+\S+\s+particledistribution/discrete(/numberbased)?"
                      r"\s+\S+\s+(\d+)\s+([^\n]*)", re.M)
_DIST_NAME_RE = re.compile(r"^[ \t]*variable\s+soil_distribution\s+string\s+(\S+)", re.M)


def particle_mix(text):
    """The soil's particle distribution read from its deck text (the soil file and what it
    includes; `&` continuations joined, comments dropped): (number-based?, [(template, weight
    token, spheres per particle)]) of the distribution fix named by `soil_distribution` (else the
    last one), or a str saying why it cannot be read (no distribution, a template not found, a
    multisphere template without nspheres). Weight tokens are as written (`0.1`, `${soil_n1}`)."""
    text = re.sub(r"&[ \t]*\r?\n", " ", text)
    text = re.sub(r"#[^\n]*", "", text)
    spheres = {}
    for tid, kind, rest in _TEMPLATE_RE.findall(text):
        m = re.search(r"\bnspheres\s+(\d+)", rest)
        spheres[tid] = 1 if kind == "sphere" else int(m.group(1)) if m else None
    dists = {fid: (bool(nb), int(n), rest.split()) for fid, nb, n, rest in _DIST_RE.findall(text)}
    if not dists:
        return "no particledistribution/discrete in the soil file"
    named = _DIST_NAME_RE.findall(text)
    fid = named[-1] if named and named[-1] in dists else list(dists)[-1]
    numberbased, n, words = dists[fid]
    pairs = list(zip(words[0:2 * n:2], words[1:2 * n:2]))
    if len(pairs) != n:
        return f"distribution {fid}: {n} templates announced, {len(pairs)} given"
    for tid, _ in pairs:
        if spheres.get(tid) is None:
            return (f"distribution {fid}: template {tid} not found"
                    if tid not in spheres else f"template {tid}: no nspheres")
    return numberbased, [(tid, w, spheres[tid]) for tid, w in pairs]


def spheres_per_particle(liggghts, soil_file, inputs_dir):
    """(spheres per particle, how) of a soil's particle distribution (particle_mix), its weights
    evaluated by LIGGGHTS as the soil file defines them (soil_vars_only = 1); (None, why) when it
    cannot be told: a mass-based distribution of clumps (that needs the clumps' volumes), weights
    the variables stage does not define, no distribution. 1.0 for a soil of single spheres."""
    files = [Path(soil_file)] + deck_includes(soil_file, {"inputs_dir": str(inputs_dir)})
    mix = particle_mix("\n".join(f.read_text(errors="replace") for f in files))
    if isinstance(mix, str):
        return None, mix
    numberbased, pairs = mix
    if all(k == 1 for _, _, k in pairs):
        return 1.0, "single spheres"
    if not numberbased:
        return None, "a mass-based distribution of clumps (their volumes are not known here)"
    try:
        r = _ask_soil(liggghts, soil_file, inputs_dir,
                      [f"wheel_sweep_w {i} {w}" for i, (_, w, _) in enumerate(pairs)])
    except (OSError, subprocess.SubprocessError) as e:
        return None, f"LIGGGHTS could not be asked for the weights: {e}"
    weights = {}
    for line in r.stdout.splitlines():
        f = line.split()
        if len(f) == 3 and f[0] == "wheel_sweep_w":
            try:
                weights[int(f[1])] = float(f[2])
            except ValueError:
                pass
    if r.returncode != 0 or len(weights) != len(pairs) or sum(weights.values()) <= 0:
        return None, "the distribution's weights are not defined by the soil's variables stage"
    total = sum(weights.values())
    ratio = sum(weights[i] * k for i, (_, _, k) in enumerate(pairs)) / total
    clumps = ", ".join(f"{tid} {weights[i] / total:.3g} x {k}" for i, (tid, _, k)
                       in enumerate(pairs) if k > 1)
    return ratio, f"{ratio:.3g} spheres per particle (number fractions: {clumps} spheres)"


def _ask_soil(liggghts, soil_file, inputs_dir, prints):
    """LIGGGHTS' CompletedProcess of a deck that includes the soil file's variables stage
    (soil_vars_only = 1) and then prints each of `prints` (its variables substituted); serial,
    within SOIL_QUERY_TIMEOUT_S. Raises what subprocess.run raises."""
    with tempfile.TemporaryDirectory(prefix="wheel-sweep-soil-") as tmp:
        deck = Path(tmp) / "in.soil_query"
        deck.write_text("variable soil_vars_only equal 1\n"
                        f"include {soil_file}\n"
                        + "".join(f'print "{line}"\n' for line in prints))
        return subprocess.run([str(liggghts), "-in", str(deck), "-log", "none", "-echo", "none",
                               "-var", "inputs_dir", str(inputs_dir)], cwd=tmp,
                              capture_output=True, text=True, stdin=subprocess.DEVNULL,
                              timeout=SOIL_QUERY_TIMEOUT_S)


def mean_grain_volume(sv):
    """Mean volume [m^3] of one grain, and how it was found. Sieve classes soil_d<i> with mass
    fractions soil_w<i>: number fractions ~ w_i / V_i, so the mean is sum(w) / sum(w_i / V_i);
    classes without mass fractions: equal numbers per class; no classes: a sphere of soil_dref."""
    d = {int(k[6:]): v for k, v in sv.items() if re.fullmatch(r"soil_d\d+", k)}
    w = {int(k[6:]): v for k, v in sv.items() if re.fullmatch(r"soil_w\d+", k)}
    vol = {i: math.pi / 6.0 * di ** 3 for i, di in d.items()}
    if d and set(w) >= set(d) and sum(w[i] for i in d) > 0:
        return (sum(w[i] for i in d) / sum(w[i] / vol[i] for i in d),
                f"{len(d)} sieve classes by mass fraction")
    if d:
        return sum(vol.values()) / len(vol), f"{len(d)} size classes, equal numbers assumed"
    dref = sv.get("soil_dref")
    if not dref or dref <= 0:
        raise EstimateError("the soil file defines neither soil_d<i> classes nor soil_dref")
    return math.pi / 6.0 * dref ** 3, "one sphere of soil_dref (rough)"


def vars_file(path):
    """`variable KEY style VALUE` lines of a bed's .vars file (or in.soilbin's defaults) as a
    dict of strings."""
    return vars_text(Path(path).read_text(errors="replace"))


def vars_text(text):
    """vars_file of a .vars file's text."""
    out = {}
    for line in text.splitlines():
        f = line.split()
        if len(f) >= 4 and f[0] == "variable":
            out.setdefault(f[1], f[3])
    return out


def soilbin_defaults(soilbin):
    """in.soilbin's `variable NAME index DEFAULT` values (the recipe keys' defaults)."""
    return {k: v for k, v in vars_file(soilbin).items()}


_LOG_KEY_RE = re.compile(r"^soilbin: (spheres|particles|restart|settle_steps|final_step) = (\S+)",
                         re.M)


def bed_log_spheres(restart):
    """(spheres, log file) from the in.soilbin log next to a prepared bed whose result block names
    this restart (or the temporary .part.restart the driver renames), else None."""
    restart = Path(restart)
    names = {restart.name, restart.name.replace(".restart", ".part.restart")}
    logs = [restart.parent / "soilbin.log", restart.parent / "log.soilbin"]
    logs += sorted(restart.parent.glob("log.soilbin_*"))
    for log in logs:
        try:
            text = log.read_text(errors="replace")
        except OSError:
            continue
        block = {}
        found = None
        for k, v in _LOG_KEY_RE.findall(text):
            block[k] = v
            if k == "restart":
                if Path(v).name in names and "spheres" in block:
                    found = int(float(block["spheres"]))
                block = {}
        if found is not None:
            return found, log
    return None


@dataclass
class BedInfo:
    """What the estimate knows of one soil's bed."""
    label: str
    particles: float
    particles_source: str
    dt: float | None  # the bed's (or soil's) time step [s]
    dt_source: str
    prepared: bool
    soil_name: str = ""
    # the bed's box [m] (length, width, depth) for the active domain's share; None if unknown
    box: tuple | None = None
    prep_steps: int = 0  # beds to prepare: an upper bound
    prep_parts: dict = field(default_factory=dict)  # [s] insertion, settle, compaction
    # tiled beds: the fraction of the bed's particles each part runs with (a part not named: 1)
    prep_weights: dict = field(default_factory=dict)
    hold_pending: bool = False  # prepared, its bed-hold check still to run (add_bed_hold)


class SoilQuery:
    """soil_vars once per soil file (and spheres_per_particle once per multisphere soil)."""

    def __init__(self, liggghts, inputs_dir):
        self.liggghts = liggghts
        self.inputs_dir = inputs_dir
        self._cache = {}
        self._mix = {}

    def spheres_per_particle(self, soil_file):
        """spheres_per_particle of `soil_file` (after a call of this query on it)."""
        key = str(soil_file)
        if key not in self._mix:
            self._mix[key] = spheres_per_particle(self.liggghts, soil_file, self.inputs_dir)
        return self._mix[key]

    def __call__(self, soil_file):
        key = str(soil_file)
        if key not in self._cache:
            if soil_file is None or not Path(soil_file).is_file():
                raise EstimateError(f"soil file {soil_file} not found (needed for its grain "
                                    "sizes or time step)")
            if not Path(self.liggghts).is_file():
                raise EstimateError(f"{self.liggghts} not found (asked for the soil's variables)")
            self._cache[key] = soil_vars(self.liggghts, soil_file, self.inputs_dir)
        return self._cache[key]


def _recipe_num(recipe, defaults, key):
    v = recipe.get(key, defaults.get(key))
    try:
        return float(v)
    except (TypeError, ValueError):
        raise EstimateError(f"recipe key {key} = {v!r}: expected a number")


def bed_info(soil, restart, query, soilbin, hold_s=0.0, parked_vars=None):
    """BedInfo of a sweep soil: `restart` is where its bed is (or will be), `query` a SoilQuery,
    `soilbin` inputs/in.soilbin (the recipe keys' defaults), `hold_s` [s] the bed-hold check run
    after a bed is prepared (wheel-sweep --bed-hold; counted in a bed to prepare). parked_vars:
    the text of the bed's .vars when the bed is not here and need not be poured (its points resume
    from parked checkpoints, runner.Runner.parked_beds): a prepared bed, known by its .vars."""
    restart = Path(restart)
    vf = Path(f"{restart}.vars")
    if parked_vars is not None or (restart.is_file() and vf.is_file()):
        v = vars_text(parked_vars) if parked_vars is not None else vars_file(vf)
        dt = float(v["bed_dt"]) if "bed_dt" in v else None
        box = None
        try:
            box = tuple(float(v[k]) for k in ("bin_length", "bin_width", "bed_depth"))
        except (KeyError, ValueError):
            pass
        got = bed_log_spheres(restart) if restart.is_file() else None
        if got is not None:
            return BedInfo(soil.label, got[0], f"bed log {got[1]}", dt, "bed_dt (.vars)", True,
                           box=box)
        need = ("bulk_density", "bin_length", "bin_width", "bed_depth")
        if any(k not in v for k in need):
            raise EstimateError(f"bed {restart}: no in.soilbin log beside it and its .vars lacks "
                                f"{', '.join(k for k in need if k not in v)}: particles unknown")
        soil_file = soil.dem_soil_file or (soilbin.parent / "soils" / f"{v.get('soil')}.in")
        sv = query(soil_file)
        vol, how = mean_grain_volume(sv)
        n = (float(v["bulk_density"]) * float(v["bin_length"]) * float(v["bin_width"])
             * float(v["bed_depth"]) / (sv["soil_density"] * vol))
        n, how = _in_spheres(n, how, sv, query, soil_file)
        return BedInfo(soil.label, n, f"bed .vars bulk density / mean grain ({how}; estimate)",
                       dt, "bed_dt (.vars)", True, box=box)
    if soil.recipe is None:
        raise EstimateError(f"bed {restart} not found")
    sv = query(soil.dem_soil_file)
    defaults = soilbin_defaults(soilbin)
    r = soil.recipe
    vol, how = mean_grain_volume(sv)
    dims = [_recipe_num(r, defaults, k) for k in ("bin_length", "bin_width", "fill_height",
                                                  "fill_solid_fraction")]
    n, how = _in_spheres(math.prod(dims) / vol, how, sv, query, soil.dem_soil_file)
    # (the settled bed's depth is not known before it settles: the fill height stands for it)
    info = BedInfo(soil.label, n, f"recipe: bin x fill solid fraction / mean grain ({how})",
                   sv["soil_dt"], "soil_dt (soil file)", False, soil_name=sv["soil_name"],
                   box=(dims[0], dims[1], dims[2]))
    info.prep_parts = bed_prep_times(r, defaults, sv)
    if hold_s > 0:  # the whole bed, left alone (inputs/in.bedhold)
        info.prep_parts[BED_HOLD_PART] = hold_s
    dt = sv["soil_dt"]
    if "tile_length" in r:
        info.prep_weights = tile_weights(r, defaults, sv)
    # (tiled: particle-weighted steps, so that particles x steps is the preparation's work)
    info.prep_steps = 1 + math.ceil(sum(math.ceil(t / dt - 1e-9) * info.prep_weights.get(k, 1.0)
                                        for k, t in info.prep_parts.items()) - 1e-9)
    return info


def _in_spheres(particles, how, sv, query, soil_file):
    """(spheres, how) of a bed of `particles` grains: a multisphere soil's particles times its
    spheres per particle (the query's spheres_per_particle; LIGGGHTS' cost goes by spheres), said
    in `how`, or left as they are with the reason the ratio is not known."""
    if not sv.get("soil_multisphere"):
        return particles, how
    ratio, why = (query.spheres_per_particle(soil_file) if hasattr(query, "spheres_per_particle")
                  else (None, "not asked"))
    if ratio is None:
        return particles, f"{how}; multisphere: clumps counted once, so low ({why})"
    return particles * ratio, f"{how}; multisphere: x {why}"


def tile_weights(recipe, defaults, sv):
    """A tiled bed's parts (bed_prep_times) as fractions of the bed's particles: the block
    1/n (n = ceil(bin_length / tile_length) blocks), the end zones 2 tile_end_zone d_max /
    bin_length (at most 1), the whole bed 1."""
    def num(k):
        return _recipe_num(recipe, defaults, k)
    length = num("bin_length")
    n = max(math.ceil(length / num("tile_length") - 1e-6), 1)
    zone = num("tile_end_zone") * sv.get("soil_dmax", sv.get("soil_dref", 0.0))
    return {"block settle": 1.0 / n, "end-zone relax": min(1.0, 2.0 * zone / length),
            "relax": 1.0}


BED_HOLD_PART = "bed-hold check"  #: its name among a bed's prep_parts


def add_bed_hold(info, hold_s):
    """A prepared bed whose bed-hold check (hold_s [s] on the whole bed) has still to run: counted
    like a bed to prepare with that one part (needs the bed's time step)."""
    if info.dt is None:
        raise EstimateError(f"bed {info.label}: its bed-hold check needs the bed's time step "
                            "(bed_dt in its .vars)")
    info.hold_pending = True
    info.prep_parts = {BED_HOLD_PART: hold_s}
    info.prep_steps = math.ceil(hold_s / info.dt - 1e-9)


def bed_prep_times(recipe, defaults, sv):
    """Simulated time [s] of preparing a bed from a recipe, upper bounds (in.soilbin): settling
    up to max_settle_time (in whole check_time chunks), plus the compaction and its second
    settling."""
    def num(k):
        return _recipe_num(recipe, defaults, k)
    check = num("check_time")
    settle_max = math.ceil(num("max_settle_time") / check - 1e-9) * check
    if "tile_length" in recipe:
        # tiled (inputs/soilbin/tile.in): the block settles (up to max_settle_time), then the
        # end zones relax for tile_relax_time and up to tile_relax_max more, then the whole bed
        # up to tile_relax_max (without end zones: one stage of tile_relax_time + the bound)
        relax_max = math.ceil(num("tile_relax_max") / check - 1e-9) * check
        relax_min = math.ceil(num("tile_relax_time") / sv["soil_dt"] - 1e-9) * sv["soil_dt"]
        zone = num("tile_end_zone") * sv.get("soil_dmax", sv.get("soil_dref", 0.0))
        if zone > 0 and 2.0 * zone < num("bin_length"):
            return {"block settle": settle_max, "end-zone relax": relax_min + relax_max,
                    "relax": relax_max}
        return {"block settle": settle_max, "relax": relax_min + relax_max}
    parts = {"settle": settle_max}
    comp = str(recipe.get("compaction", defaults.get("compaction", "none")))
    if comp == "plate":
        parts["plate"] = 1.25 * num("plate_time")
        parts["settle_after"] = settle_max
    elif comp == "drop":
        v = math.sqrt(2.0 * 9.81 * num("drop_height"))
        gap = 0.5 * sv.get("soil_dref", 0.0)  # drop_gap = 0.5 d_max; d_ref is close enough
        stroke = num("drop_stroke") * sv.get("soil_dref", 0.0)
        parts["drop"] = num("drop_count") * (2.0 * (gap + stroke) / v + num("drop_rest"))
        parts["settle_after"] = settle_max
    return parts


# ---- the whole estimate -------------------------------------------------------------------------
@dataclass
class PointEstimate:
    point: object
    particles: float
    particles_source: str
    dt: float
    dt_source: str
    phases: dict
    sim_time: float
    steps: int
    wall: float
    finished: bool
    active_share: float | None = None  # the active domain's mean share of the particles
    active_note: str = ""  # how it was found, or why the active domain was left out
    # measured / modelled wall of the finished points on the same bed (wall is scaled by it)
    calibration: float | None = None
    calibration_points: int = 0
    # where the wheel's travel ends: its rim's front from the bin's far wall [m] (None: unknown)
    end_gap_m: float | None = None
    end_note: str = ""
    # rig steps done at the checkpoint it resumes from (its own or a parked one): wall is the rest's
    steps_done: int = 0


@dataclass
class BedEstimate:
    info: BedInfo
    dt: float
    steps: int
    wall: float


@dataclass
class SweepEstimate:
    points: list
    beds: list
    jobs: int
    np: int
    bed_np: int
    cores: int
    rate: Rate
    points_wall: float = 0.0
    beds_wall: float = 0.0

    @property
    def total(self):
        return self.points_wall + self.beds_wall

    @property
    def todo(self):
        return [p for p in self.points if not p.finished]


def deck_chunk(deck, liggghts_args=()):
    """The steps LIGGGHTS runs between checks of the rig's end (`chunk` of the coupled deck,
    `-var chunk N` in liggghts_args wins): steps are run in whole chunks. 1 if not known."""
    try:
        return max(1, int(deck_variable(deck, "chunk", liggghts_args)))
    except (TypeError, ValueError):
        return 1


def active_share(point, info, active, x0, ph):
    """(mean active share, how it was found) of a point run with the active domain `active`
    (active_domain.ActiveSettings); (None, why) when it cannot be told (then the estimate counts
    every particle as active)."""
    ext = wheel_extent(point.rig, getattr(getattr(point, "wheel", None), "mesh", None))
    if ext is None:
        return None, "active domain left out: the wheel mesh could not be read for its size"
    if info.box is None:
        return None, "active domain left out: the bed's size is not known"
    length, width, depth = info.box
    bounding, outer = ext
    reach = active.reach(bounding)
    zc = depth + outer - active.sinkage_allowance(bounding)
    speed = active_domain.travel_speed(point.rig, getattr(point, "slip", None), outer)
    xs = active_domain.wheel_path(ph, x0, speed, length)
    share = active_domain.sphere_share(length, width, depth, reach, [(x, zc) for x in xs])
    note = (f"active domain: the soil within {reach:.3g} m of the wheel centre (bounding "
            f"radius {bounding:.3g} m) moves: {100 * share:.0f} % of the bed on average "
            f"from x0 {x0:g} m at {speed:.3g} m/s")
    if active.distance is None and active.sinkage is None:
        # the default allowance under-reached a soft soil (docs/fix-wheel-active.md, "On the
        # goal's deep bed": drawbar pull -39 %)
        note += (f"; the distance assumes the default sinkage allowance R/4 = "
                 f"{active.sinkage_allowance(bounding):.3g} m: if the wheel sinks deeper, set "
                 f"-var active_args \"sinkage Z\" (docs/fix-wheel-active.md)")
    return share, note


def end_of_travel(point, info, x0, ph):
    """(gap [m], note) of a DEM point: where its wheel centre ends (active_domain.travel: held
    through release and settle, the ramp, the test at the slip's speed) and how far
    its rim's front then is from the bin's far wall; (None, "") when the bed's length, the mesh
    or the speed is not known. The run-health check end_wall_clearance warns after the run when
    the gap is under 2 x the window's sinkage (docs/run-health.md): the soil the wheel pushes
    ahead then meets the wall (case 3's bow wave reached 0.7 m ahead of its rim)."""
    ext = wheel_extent(point.rig, getattr(getattr(point, "wheel", None), "mesh", None))
    if info.box is None or ext is None:
        return None, ""
    outer = ext[1]
    speed = active_domain.travel_speed(point.rig, getattr(point, "slip", None), outer)
    if not speed > 0:
        return None, ""
    length = info.box[0]
    x_end = x0 + active_domain.travel(ph, speed, sum(ph.values()))
    gap = length - (x_end + outer)
    where = (f"its rim's front {gap:.3g} m from the far wall ({gap / outer:.2g} outer radii)"
             if gap > 0 else f"past the far wall: its rim's front would be {-gap:.3g} m beyond it")
    return gap, (f"travel: from x0 {x0:g} m at {speed:.3g} m/s the wheel centre ends at x = "
                 f"{x_end:.4g} m of the {length:g} m bin, {where}; the run-health check warns "
                 "when that gap is under 2 x the sinkage (end_wall_clearance)")


def estimate(points, infos, rate, np_, bed_np, jobs, cores, finished=lambda p: False, chunk=1,
             overhead_s=COSIM_OVERHEAD_S, active=None, x0=0.0, measured_wall=lambda p: None,
             steps_done=lambda p: 0):
    """The sweep's estimate. points: the sweep's points (each with .rig and .soil.label; a
    .wheel.mesh is used for the radius when the rig has no wheel.effective_radius); infos: soil
    label -> BedInfo; finished(p): True for a point that will be skipped; chunk: the deck's
    chunk (deck_chunk); overhead_s: per point, beyond the rate's startup; active: the active
    domain's settings (active_domain.settings; None: off) and x0 [m] the wheel's start: the
    particles then cost as N x (share + FROZEN_COST x (1 - share)); measured_wall(p): the wall
    time [s] a finished point took (None if not known): the points still to run on the same bed
    are scaled by measured / estimated of its finished points (`calibration`); steps_done(p): the
    rig steps an unfinished point resumes from (a checkpoint, its own or parked): its wall is that
    of the steps left."""
    todo = [p for p in points if not finished(p)]
    at_once = max(1, min(jobs, len(todo)))
    over = oversubscription(at_once * np_, cores)
    out = []
    for p in points:
        info = infos[p.soil.label]
        run = p.rig.get("run", {})
        if run.get("dt") is not None:
            dt, dt_src = float(run["dt"]), "run.dt"
        elif info.dt is not None:
            dt, dt_src = info.dt, info.dt_source
        else:
            raise EstimateError(f"point {p.reldir}: no time step (run.dt, the bed's bed_dt or the "
                                "soil's soil_dt)")
        if not dt > 0:
            raise EstimateError(f"point {p.reldir}: run.dt must be > 0 s, got {dt!r}")
        mesh = getattr(getattr(p, "wheel", None), "mesh", None)
        ph = phases(p.rig, wheel_radius(p.rig, mesh))
        sim = sum(ph.values())
        steps = math.ceil(math.ceil(sim / dt - 1e-9) / chunk) * chunk
        share, note = active_share(p, info, active, x0, ph) if active else (None, "")
        cost = info.particles * (1.0 if share is None else
                                 share + FROZEN_COST * (1.0 - share))
        wall = run_wall(cost, steps, np_, rate.rate_per_rank, rate.efficiency_np2,
                        rate.startup_s + overhead_s, over)
        gap, end_note = end_of_travel(p, info, x0, ph)
        out.append(PointEstimate(p, info.particles, info.particles_source, dt, dt_src, ph, sim,
                                 steps, wall, finished(p), share, note, end_gap_m=gap,
                                 end_note=end_note))
    # the sweep's own measurements: measured / modelled wall of its finished points, per bed
    sums = {}
    for e in out:
        got = measured_wall(e.point) if e.finished else None
        if got is not None and got > 0:
            m, w, n = sums.get(e.point.soil.label, (0.0, 0.0, 0))
            sums[e.point.soil.label] = (m + got, w + e.wall, n + 1)
    for e in out:
        if e.point.soil.label in sums and not e.finished:
            m, w, n = sums[e.point.soil.label]
            e.calibration, e.calibration_points = m / w, n
            e.wall *= m / w
        done = 0 if e.finished else min(max(0, int(steps_done(e.point) or 0)), e.steps)
        if done:
            e.steps_done = done
            e.wall *= (e.steps - done) / e.steps
    beds = []
    used = {p.soil.label for p in todo}
    for label, info in infos.items():
        if (info.prepared and not info.hold_pending) or label not in used:
            continue
        wall = run_wall(info.particles, info.prep_steps, bed_np, rate.bed_rate_per_rank,
                        rate.efficiency_np2, rate.startup_s, oversubscription(bed_np, cores))
        beds.append(BedEstimate(info, info.dt, info.prep_steps, wall))
    est = SweepEstimate(out, beds, at_once, np_, bed_np, cores, rate)
    est.points_wall = schedule([e.wall for e in out if not e.finished], at_once)
    est.beds_wall = sum(b.wall for b in beds)
    return est


# ---- printing -----------------------------------------------------------------------------------
def _range(values, fmt):
    lo, hi = min(values), max(values)
    return fmt(lo) if fmt(lo) == fmt(hi) else f"{fmt(lo)}-{fmt(hi)}"


def summary_line(est):
    """The one line at the start of a DEM sweep."""
    todo = est.todo
    if not todo:
        return "estimate: no point to run"
    shares = [e.active_share for e in todo if e.active_share is not None]
    active = (f"active domain {_range([100 * a for a in shares], lambda x: f'{x:.0f}')} % of "
              "the particles; " if shares else "")
    checks = sum(b.info.hold_pending for b in est.beds)
    what = " + ".join(w for w in (f"{len(est.beds) - checks} bed(s) to prepare" if
                                  len(est.beds) > checks else "",
                                  f"{checks} bed-hold check(s)" if checks else "") if w)
    beds = (f" (points {fmt_time(est.points_wall)} + {what} <= {fmt_time(est.beds_wall)})"
            if est.beds else "")
    return (f"estimate: {len(todo)} point(s) to run, "
            f"{_range([e.particles for e in todo], fmt_int)} particles, "
            f"dt {_range([e.dt for e in todo], lambda x: f'{x:.4g}')} s, "
            f"{_range([e.sim_time for e in todo], lambda x: f'{x:.3g}')} s simulated = "
            f"{_range([e.steps for e in todo], fmt_int)} steps each; " + active +
            f"{_range([e.wall for e in todo], fmt_time)} per point, "
            f"{fmt_time(est.total)} for the sweep{beds} ({est.jobs} at a time x {est.np} "
            f"rank(s) on {est.cores} core(s); rate {est.rate.source}; details: --estimate)")


def report(est, sweep_name):
    """The --estimate printout: rate, every point, every bed to prepare, the sweep."""
    r = est.rate
    lines = [f"estimate: {sweep_name}: {len(est.points)} point(s), {len(est.todo)} to run; "
             f"{est.jobs} at a time x {est.np} rank(s) on {est.cores} core(s)",
             f"estimate: rate {r.rate_per_rank:.3g} particle-steps/s per rank (beds "
             f"{r.bed_rate_per_rank:.3g}), np-2 efficiency {r.efficiency_np2:.2f}, startup "
             f"{r.startup_s:.1f} s per run: {r.source}"]
    for e in est.points:
        ph = e.phases
        state = "finished, skipped" if e.finished else "to run"
        lines.append(
            f"estimate: point {e.point.reldir} ({state}): particles {fmt_int(e.particles)} "
            f"({e.particles_source}); dt {e.dt:.6g} s ({e.dt_source}); simulated {e.sim_time:.4g}"
            f" s = release {ph['release']:.4g} + settle <= {ph['settle']:.4g} + ramp "
            f"{ph['ramp']:.4g} + test {ph['test']:.4g}; steps {fmt_int(e.steps)}; wall "
            f"{fmt_time(e.wall)} ({e.wall:.0f} s)")
        if e.steps_done:
            lines.append(f"estimate:   resumes from a checkpoint at step {fmt_int(e.steps_done)} "
                         f"of {fmt_int(e.steps)}: the wall is that of the "
                         f"{fmt_int(e.steps - e.steps_done)} steps left")
        if e.calibration is not None:
            lines.append(f"estimate:   scaled by {e.calibration:.3g}: the measured / estimated "
                         f"wall of {e.calibration_points} finished point(s) on this bed (the "
                         f"model alone: {fmt_time(e.wall / e.calibration)})")
        if e.active_note:
            cost = ""
            if e.active_share is not None:
                n_eff = e.particles * (e.active_share + FROZEN_COST * (1 - e.active_share))
                cost = (f"; a frozen particle costs {FROZEN_COST:.3g} of an active one: the "
                        f"point costs as {fmt_int(n_eff)} active particles")
            lines.append(f"estimate:   {e.active_note}{cost}")
        if e.end_note:
            lines.append(f"estimate:   {e.end_note}")
    for b in est.beds:
        w = b.info.prep_weights
        parts = " + ".join(f"{k} {v:.4g}" + (f" x {w[k]:.3g} of the particles" if k in w and
                                              w[k] != 1.0 else "")
                           for k, v in b.info.prep_parts.items())
        what = ("prepared, its bed-hold check to run" if b.info.hold_pending else "to prepare")
        lines.append(
            f"estimate: bed {b.info.label} ({what}, {est.bed_np} rank(s)): particles "
            f"{fmt_int(b.info.particles)} ({b.info.particles_source}); dt {b.dt:.6g} s "
            f"({b.info.dt_source}); simulated <= {sum(b.info.prep_parts.values()):.4g} s "
            f"({parts}); {'particle-weighted steps' if w else 'steps'} <= {fmt_int(b.steps)}; "
            f"wall <= {fmt_time(b.wall)} "
            f"({b.wall:.0f} s)")
    todo = est.todo
    psteps = sum(e.particles * e.steps for e in todo)
    lines.append(
        f"estimate: sweep: {len(todo)} point(s), {fmt_int(psteps)} particle-steps, "
        f"{fmt_int(sum(e.steps for e in todo))} steps; wall {fmt_time(est.total)} "
        f"({est.total:.0f} s, {est.total / 3600:.3g} h) = points {fmt_time(est.points_wall)} + "
        f"beds <= {fmt_time(est.beds_wall)}")
    return lines
