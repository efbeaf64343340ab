"""What `soil-lab run` runs: the soil's grain sizes, and the tests sized from them.

Sizes follow the standards' rules relative to the largest grain d = d_max (docs/soil-lab.md,
"Procedures"); the `quick` preset shrinks every test for CI (minutes on 2 cores, numbers not
meant to be representative). Every size is in metres, every stress in Pa, every speed in m/s.
"""

import math
from dataclasses import dataclass, field
from typing import Dict, List, Tuple

TEST_NAMES = ("bulk", "plate", "shear", "repose")
PRESETS = ("standard", "quick")


class LabInputError(ValueError):
    """A bad soil, test name or test size; the message names it and what was expected."""


@dataclass(frozen=True)
class SoilInfo:
    """The soil file's variables the lab sizes its tests by (soil_lab/decks/in.lab_soilinfo)."""

    name: str
    file: str  #: absolute path of the soil include file
    dmin_m: float
    dmax_m: float
    dref_m: float
    density_kg_m3: float  #: mass-weighted particle density
    multisphere: bool
    dt_s: float
    youngs_Pa: float  #: particle Young's modulus, -1 if the file does not name it


@dataclass
class Bed:
    """A bed prepared by inputs/in.soilbin: bin inner size and intended depth [m]."""

    name: str
    length_m: float
    width_m: float
    fill_height_m: float
    extra_vars: Dict[str, str] = field(default_factory=dict)


@dataclass
class Run:
    """One LIGGGHTS run of a lab deck on a bed, with its meshes (wheel-mesh tool arguments)."""

    name: str  #: directory name, e.g. plate_b0.032
    test: str  #: plate, shear or repose
    deck: str  #: in.lab_plate, ...
    bed: str  #: Bed.name
    meshes: Dict[str, List[str]]  #: deck variable -> wheel-mesh tool KIND PARAMETERS
    variables: Dict[str, str]  #: deck variables (sizes, speeds, targets)
    meta: Dict[str, float]  #: what the analysis needs (plate width, normal stress, ...)


@dataclass
class Plan:
    soil: SoilInfo
    preset: str
    tests: Tuple[str, ...]
    beds: Dict[str, Bed]
    runs: List[Run]


def _f(x):
    return f"{x:.6g}"


# Tool speeds [m/s]: the defaults (docs/soil-lab.md) and the accepted range of --plate-speed and
# --shear-speed (a faster tool is no longer a quasi-static soil test; a value above it is most
# likely a unit slip, e.g. mm/s).
PLATE_SPEED = {"standard": 0.02, "quick": 0.04}
SHEAR_SPEED = {"standard": 0.005, "quick": 0.02}  # quick: CI smoke, I ~ 4e-3 on ci at 3 kPa
MAX_TOOL_SPEED = 0.1
# --plate-hold [s]: a standstill longer than this is most likely a unit slip (ms); the relaxation
# of the DEM soils measured so far is a matter of seconds (docs/soil-lab.md, "Held plates").
MAX_PLATE_HOLD = 60.0
MAX_HOLD_STAGES = 20
# --shear-replicates N: the shear boxes again on N - 1 more beds of the same recipe, each poured
# with its own insertion seed (in.soilbin's `seed`, a prime > 10000; the first bed keeps the
# recipe's), so that the report can say how much one box per stress scatters (docs/soil-lab.md,
# "Replicate boxes"). Each replicate costs as much as the boxes themselves. --plate-replicates N:
# the same for the two plates, on N - 1 more plate beds poured with the same seeds ("Replicate
# plates").
MAX_SHEAR_REPLICATES = 5
MAX_PLATE_REPLICATES = MAX_SHEAR_REPLICATES
REPLICATE_SEEDS = (67867967, 86028121, 104395301, 122949823)   # replicates 2..5 (primes)


def shear_bed_name(replicate):
    """The bed the boxes of replicate k are sheared on: the lab's `shear` bed for the first."""
    return "shear" if replicate == 1 else f"shear_r{replicate}"


def plate_bed_name(replicate):
    """The bed the plates of replicate k press into: the lab's `plate` bed for the first."""
    return "plate" if replicate == 1 else f"plate_r{replicate}"


def _add_replicate_beds(beds, first, bed_name, count, option):
    """Beds 2..count of the bed `first` into `beds` (named bed_name(k)): the same bin and depth,
    each poured with its REPLICATE_SEEDS seed. A user's --bed-var seed that one of them is poured
    with is refused (LabInputError naming `option`)."""
    if count > 1 and first.extra_vars.get("seed") in {str(x) for x in REPLICATE_SEEDS}:
        raise LabInputError(f"--bed-var seed={first.extra_vars['seed']}: a replicate bed's seed "
                            f"({option} pours its beds with "
                            f"{', '.join(str(x) for x in REPLICATE_SEEDS)}): choose another")
    for k in range(2, count + 1):
        beds[bed_name(k)] = Bed(bed_name(k), first.length_m, first.width_m, first.fill_height_m,
                                {**first.extra_vars, "seed": str(REPLICATE_SEEDS[k - 2])})


def _replicates(value, option, test, maximum):
    """The checked replicate count of `option` (None: not given); a LabInputError naming it."""
    if value is None:
        return
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= maximum:
        what = "boxes at each normal stress" if test == "shear" else "two plates"
        raise LabInputError(f"{option} {value}: expected a whole number in 1..{maximum} (the "
                            f"{what}, each on its own bed; 1: no replicate)")


def _speed(value, default, option):
    if value is None:
        return default
    if not 0 < value <= MAX_TOOL_SPEED:
        raise LabInputError(f"{option} {value:g} m/s is outside (0, {MAX_TOOL_SPEED:g}] m/s (a "
                            f"quasi-static tool speed in m/s; default {default:g})")
    return value


def _nearest_test(name):
    """" (did you mean 'X'?)" for a misspelt test name, or "" (as wheelsim_post.usage.nearest,
    which this module, imported by the tests alone, does without)."""
    import difflib

    near = difflib.get_close_matches(name, TEST_NAMES, n=1, cutoff=0.6)
    return f" (did you mean '{near[0]}'?)" if near else ""


def _finite_positive(x):
    return isinstance(x, (int, float)) and math.isfinite(x) and x > 0


def check_options(tests, preset="standard", normal_stresses_Pa=None, plate_widths_m=None,
                  plate_bin_m=None, shear_travel=None, plate_speed=None, shear_speed=None,
                  plate_depth=None, plate_hold=None, plate_hold_stages=None,
                  shear_replicates=None, plate_replicates=None):
    """The checks of make_plan's options that need no soil (the same arguments, None: the
    default): `soil-lab run` makes them before it creates or starts anything, make_plan again
    before the checks that need the soil's grain sizes and stiffness (a plate wider than its bin,
    a plate depth under one grain, a normal stress the box cannot hold for these particles).
    Raises LabInputError naming the option and what was expected: no test, an unknown test or
    preset, a tool speed outside (0, MAX_TOOL_SPEED] m/s; with the plates (tests plate or bulk)
    plate widths that are not two different finite widths > 0, a plate bin or plate depth that is
    not a finite length > 0, a hold outside (0, MAX_PLATE_HOLD] s or stages outside
    1..MAX_HOLD_STAGES or without a hold; with the shear box fewer than 3 normal stresses, one not
    a finite stress > 0, a travel outside (0, 0.5], replicates outside 1..MAX_SHEAR_REPLICATES;
    replicates without the shear box; plate replicates outside 1..MAX_PLATE_REPLICATES or without
    the plates. Returns the tests as a tuple."""
    tests = tuple(tests)
    if not tests:
        raise LabInputError(f"--tests: expected at least one test of {', '.join(TEST_NAMES)}")
    for t in tests:
        if t not in TEST_NAMES:
            raise LabInputError(f"--tests: unknown test '{t}'{_nearest_test(t)}; tests: "
                                f"{', '.join(TEST_NAMES)}")
    if preset not in PRESETS:
        raise LabInputError(f"--preset: unknown preset '{preset}' (expected one of "
                            f"{', '.join(PRESETS)})")
    _speed(plate_speed, PLATE_SPEED[preset], "--plate-speed")
    _speed(shear_speed, SHEAR_SPEED[preset], "--shear-speed")
    if "plate" in tests or "bulk" in tests:
        if plate_widths_m is not None:
            widths = list(plate_widths_m)
            if len(widths) != 2 or not all(_finite_positive(b) for b in widths) or \
                    widths[0] == widths[1]:
                raise LabInputError(f"--plate-widths: expected two different widths > 0 m (the "
                                    f"Bekker fit separates kc from kphi by b), got {widths}")
        if plate_bin_m is not None and not _finite_positive(plate_bin_m):
            raise LabInputError(f"--plate-bin {plate_bin_m:g} m: expected a finite side > 0 m (at "
                                f"least 8 grains, d_max; default 3 x the larger plate)")
        if plate_depth is not None and not _finite_positive(plate_depth):
            raise LabInputError(f"--plate-depth {plate_depth:g} m: expected a finite depth > 0 m "
                                f"(at least one grain, d_max; default 3 d_max, quick 1.5)")
        _plate_hold(plate_hold, plate_hold_stages)
    if "shear" in tests:
        if normal_stresses_Pa is not None:
            stresses = list(normal_stresses_Pa)
            if len(stresses) < 3:
                raise LabInputError(f"--normal-stresses: the shear test needs >= 3 normal "
                                    f"stresses for the Mohr-Coulomb fit, got {len(stresses)}")
            for s in stresses:
                if not _finite_positive(s):
                    raise LabInputError(f"--normal-stresses: normal stress {s:g} Pa is outside "
                                        f"what the shear box can hold: expected a finite stress "
                                        f"> 0 Pa (at most 1 % of the particles' Young's modulus)")
        if shear_travel is not None and not 0 < shear_travel <= 0.5:  # also NaN
            raise LabInputError(f"--shear-travel {shear_travel:g} is outside (0, 0.5] (a fraction "
                                f"of the box side: the upper frame must stay over the lower one)")
    if shear_replicates is not None and "shear" not in tests:
        raise LabInputError("--shear-replicates repeats the shear boxes: add shear to --tests")
    _replicates(shear_replicates, "--shear-replicates", "shear", MAX_SHEAR_REPLICATES)
    if plate_replicates is not None and "plate" not in tests:
        raise LabInputError("--plate-replicates repeats the plates: add plate to --tests")
    _replicates(plate_replicates, "--plate-replicates", "plate", MAX_PLATE_REPLICATES)
    return tests


def make_plan(soil: SoilInfo, tests, preset="standard", normal_stresses_Pa=None, bed_vars=None,
              plate_widths_m=None, plate_bin_m=None, speed_check=False, shear_travel=None,
              plate_speed=None, shear_speed=None, plate_depth=None, plate_hold=None,
              plate_hold_stages=None, shear_replicates=None, dt_check=False,
              plate_replicates=None):
    """The beds and runs for `tests` on `soil`. Raises LabInputError for what check_options
    refuses (it needs no soil), and for plates narrower than 2 grains (d_max) or that do not fit
    their bin with 3/4 of a plate width of soil on every side, a plate bin narrower than 8 grains,
    a plate depth [m] under one grain, or a normal stress the box cannot hold for this soil (above
    1 % of the particles' Young's modulus). Speeds [m/s] default to PLATE_SPEED, SHEAR_SPEED; the
    shear travel is a fraction of the box side (default 0.12). The plate depth (the sinkage at the
    end of the reload; default 3 d_max, quick 1.5): a deeper one loads to 2/3 of it and unloads by
    1/6, on a bed as much deeper, so that the soil under the plate's deepest point is the
    default's. plate_hold [s]: the plates stand still that long at plate_hold_stages (default 1)
    equally spaced depths of the loading, the last at its end (stress relaxation). speed_check:
    also the larger plate, the middle normal stress and (standard preset) the repose test at half
    speed (runs named <run>_half), for the quasi-static check. shear_replicates N (default 1):
    the boxes again on beds shear_r2..shear_rN, poured with REPLICATE_SEEDS (runs
    shear_s<σ>_r<k>, meta replicate k); with speed_check, every bed's middle-stress box gets its
    half-speed twin (shear_s<σ>[_r<k>]_half: a paired check, analysis.paired_speed_checks).
    plate_replicates N (default 1): the two plates again on beds plate_r2..plate_rN, poured with
    REPLICATE_SEEDS (runs plate_b<b>_r<k>, meta replicate k); the checks take every bed's larger
    plate (paired on its bed).
    dt_check: also the larger plate and the middle normal stress's box (every bed's) at half the
    soil's time step, on the same bed, at the same speed (runs named <run>_halfdt, meta
    dt_factor 0.5; run_dt_s), for the time-step check."""
    tests = check_options(tests, preset, normal_stresses_Pa, plate_widths_m, plate_bin_m,
                          shear_travel, plate_speed, shear_speed, plate_depth, plate_hold,
                          plate_hold_stages, shear_replicates, plate_replicates)
    quick = preset == "quick"
    plate_speed = _speed(plate_speed, PLATE_SPEED[preset], "--plate-speed")
    shear_speed = _speed(shear_speed, SHEAR_SPEED[preset], "--shear-speed")
    d = soil.dmax_m
    bed_vars = dict(bed_vars or {})
    beds: Dict[str, Bed] = {}
    runs: List[Run] = []

    if "plate" in tests or "bulk" in tests:
        # Two square plates of side b1 < b2; the bin leaves >= b2 of soil on each side of the
        # larger plate and a bed >= 1.5 b2 deep (quick: less).
        b1, b2 = (2.5 * d, 4.0 * d) if quick else (5.0 * d, 8.0 * d)
        if plate_widths_m is not None:   # two different widths > 0 (check_options)
            b1, b2 = sorted(plate_widths_m)
            if b1 < 2 * d:
                raise LabInputError(f"plate width {b1:g} m is less than 2 grains (d_max "
                                    f"{d:g} m): a plate must span several grains")
        side = plate_bin_m if plate_bin_m is not None else (2.5 if quick else 3.0) * b2
        # The bulk density is measured on this bed; without plates a narrower bin is allowed (a
        # cheap bulk probe), down to the 8 d_max that leave the core cell 6 d_max across.
        if side < 8.0 * d:
            raise LabInputError(f"the plate bin (side {side:g} m) is narrower than 8 grains (d_max "
                                f"{d:g} m): the bulk density's core cell keeps d_max from each "
                                f"wall; use --plate-bin >= {8.0 * d:g}")
        if "plate" in tests and side < 2.5 * b2:
            raise LabInputError(f"plate {b2:g} m is too wide for the plate bin (side {side:g} m): "
                                f"the bin needs at least {2.5 * b2:g} m (the plate and 3/4 of its "
                                f"width of soil on each side), or use narrower plates")
        # The loading ends at 2/3 of the plate depth, the unloading rises by 1/6 of it, the
        # reload ends at it (default 3 d_max, quick 1.5); a deeper plate gets a bed as much
        # deeper (fill height), so the soil under its deepest point is the default's.
        default_depth2 = (1.5 if quick else 3.0) * d
        depth2 = default_depth2 if plate_depth is None else plate_depth
        if depth2 < d:   # a finite depth > 0 (check_options)
            raise LabInputError(f"--plate-depth {depth2:g} m is under one grain (d_max {d:g} m): "
                                f"a plate must sink at least a grain (default {default_depth2:g})")
        hold_vars = _plate_hold(plate_hold, plate_hold_stages)
        depth = (1.25 if quick else 1.5) * b2 + max(0.0, depth2 - default_depth2)
        beds["plate"] = Bed("plate", side, side, depth, bed_vars)
        if "plate" in tests:
            depth1, unload = depth2 * 2.0 / 3.0, depth2 / 6.0
            speed = plate_speed
            thickness = max(0.5 * d, 0.005)
            replicates = plate_replicates or 1
            _add_replicate_beds(beds, beds["plate"], plate_bed_name, replicates,
                                "--plate-replicates")
            for k, b in [(k, b) for k in range(1, replicates + 1) for b in (b1, b2)]:
                # the first bed's plates keep their names and records (as the boxes')
                suffix, rep_meta = ("", {}) if k == 1 else (f"_r{k}", {"replicate": k})
                runs.append(Run(
                    name=f"plate_b{_f(b)}{suffix}", test="plate", deck="in.lab_plate",
                    bed=plate_bed_name(k),
                    meshes={"plate_mesh": ["plate-rect", _f(b), _f(b), _f(thickness)]},
                    variables={"plate_area": _f(b * b), "plate_thickness": _f(thickness),
                               "plate_speed": _f(speed), "gap": _f(0.25 * d),
                               "depth1": _f(depth1), "unload": _f(unload), "depth2": _f(depth2),
                               **hold_vars},
                    meta={"b_m": b, "area_m2": b * b, "speed_m_s": speed, **rep_meta}))

    if "shear" in tests:
        # Square box of inner side L >= 10 d_max (ASTM D3080), soil height >= 6 d_max, the shear
        # plane at mid-height; shear over 12 % of L (or shear_travel x L: coarse grains need more
        # to reach their peak, docs/soil-lab.md).
        L = (8.0 if quick else 12.0) * d
        H = (5.0 if quick else 8.0) * d
        beds["shear"] = Bed("shear", L, L, H, bed_vars)
        # >= 3 finite stresses > 0 (check_options)
        stresses = list(((3e3, 6e3, 9e3) if quick else (5e3, 1e4, 2e4))
                        if normal_stresses_Pa is None else normal_stresses_Pa)
        # Largest stress: the contact overlap stays small, sigma < 1 % of the particles' E
        # (Hertz: overlap/R ~ (sigma/E)^(2/3), 4.6 % at 1 %).
        s_max = 0.01 * soil.youngs_Pa if soil.youngs_Pa > 0 else float("inf")
        for s in stresses:
            if s > s_max:
                raise LabInputError(
                    f"--normal-stresses: normal stress {s:g} Pa is outside what the shear box "
                    f"can hold for this soil: expected 0 < sigma <= {s_max:g} Pa (1 % of the "
                    f"particles' Young's modulus {soil.youngs_Pa:g} Pa; above it the contact "
                    f"overlaps exceed ~5 % of R)")
        wall = max(0.5 * d, 0.005)
        low_h = 0.5 * H
        up_h = 0.5 * H + 3.0 * d  # room for the lid above the soil
        lid_t = max(0.5 * d, 0.005)
        clear = 0.25 * soil.dmin_m
        speed = shear_speed
        travel = 0.12 if shear_travel is None else shear_travel   # in (0, 0.5] (check_options)
        distance = travel * L
        # The upper frame's leading part moves out over the lower frame by up to `distance`: the
        # lower frame's wall is a rim at least that wide (plus d), so the soil carried out there
        # rests on it instead of falling beside the box, and the domain reaches past the upper
        # frame's furthest position (in.lab_shear's change_box to shear_xhi), so no grain leaves
        # it. Until 2026-11-26 the rim was `wall` wide and the domain ended 2 d beyond the bin's
        # plate margin: at 0.25 L on 16-40 mm grains 1-2 % of the grains were lost by the peaks.
        rim = max(wall, distance + wall + d)
        replicates = shear_replicates or 1
        _add_replicate_beds(beds, beds["shear"], shear_bed_name, replicates, "--shear-replicates")
        for k, s in [(k, s) for k in range(1, replicates + 1) for s in stresses]:
            # the first replicate's runs keep their names and records (labs run before
            # --shear-replicates existed stay valid)
            suffix, rep_meta = ("", {}) if k == 1 else (f"_r{k}", {"replicate": k})
            bed = shear_bed_name(k)
            runs.append(Run(
                name=f"shear_s{_f(s)}{suffix}", test="shear", deck="in.lab_shear", bed=bed,
                meshes={"frame_low_mesh": ["frame", _f(L), _f(L), _f(rim), _f(low_h)],
                        "frame_up_mesh": ["frame", _f(L), _f(L), _f(wall), _f(up_h)],
                        "lid_mesh": ["plate-rect", _f(L - 2 * clear), _f(L - 2 * clear), _f(lid_t)]},
                variables={"frame_low_h": _f(low_h), "frame_up_h": _f(up_h),
                           "frame_gap": _f(0.1 * soil.dmin_m), "lid_thickness": _f(lid_t),
                           "normal_stress": _f(s), "shear_speed": _f(speed),
                           "shear_distance": _f(distance),
                           "shear_xhi": _f(L + distance + wall + 2.0 * d),
                           # shortest and longest consolidation [s] (in.lab_shear)
                           "consolidate": "0.2" if quick else "0.3",
                           "consolidate_max": "1.5" if quick else "3.0"},
                meta={"normal_stress_Pa": s, "box_m": L, "speed_m_s": speed, **rep_meta}))

    if "repose" in tests:
        # Lifted frame on a fixed rough base of side B, column 0.5 B high. The heap left on the
        # base is a pyramid of height B tan(theta) / 2: B = 20 d_max makes it 5.5 grains high at
        # 29 deg, 8.4 at 40 deg (10 d_max left ~3 grains, too few surface points for a fit; 30
        # d_max would cost 3.4x the particles). Its volume B^3 tan(theta) / 6 needs a column of
        # at least B tan(theta) / 6, and a column lower than the pyramid, B tan(theta) / 2, leaves
        # a flat top (seen at 39 deg with 0.4 B): 0.5 B holds a full pyramid up to 45 deg.
        B = (12.0 if quick else 20.0) * d
        Hc = 0.5 * B
        beds["repose"] = Bed("repose", B, B, Hc, bed_vars)
        wall = max(0.5 * d, 0.005)
        frame_h = Hc * 1.4 + 2 * d
        runs.append(Run(
            name="repose", test="repose", deck="in.lab_repose", bed="repose",
            meshes={"frame_mesh": ["frame", _f(B), _f(B), _f(wall), _f(frame_h)],
                    # multisphere: the plate the base's free clumps rest on (in.lab_repose)
                    **({"base_mesh": ["plate-rect", _f(B), _f(B), _f(wall)]}
                       if soil.multisphere else {})},
            variables={"frame_h": _f(frame_h), "lift_speed": "0.05" if quick else "0.02",
                       "settle": "0.5" if quick else "1.0", "clearance": _f(d),
                       **({"base_plate_t": _f(wall)} if soil.multisphere else {})},
            meta={"base_m": B}))
    if speed_check:
        # The quick heap (~3400 spheres, 5 grains high) scatters by more than the check's 1.5 deg
        # from flank to flank (23.7-33.0 deg in CI), so its half-speed twin, the quick lab's
        # longest run (47 s of 177), would compare noise: quick checks the plate and the box only.
        runs += _half_speed_runs(runs, repose=not quick)
    if dt_check:
        runs += _half_step_runs(runs)
    return Plan(soil=soil, preset=preset, tests=tests, beds=beds, runs=runs)


def _plate_hold(hold, stages):
    """in.lab_plate's hold variables ({} without a hold, so the runs of labs without one keep
    their inputs), or a LabInputError (check_options and make_plan)."""
    if hold is None:
        if stages is not None:
            raise LabInputError(f"--plate-hold-stages {stages} without --plate-hold: give the "
                                f"standstill of each stage in seconds")
        return {}
    if not 0 < hold <= MAX_PLATE_HOLD:   # also NaN
        raise LabInputError(f"--plate-hold {hold:g} s is outside (0, {MAX_PLATE_HOLD:g}] s (the "
                            f"standstill of each hold stage, in seconds)")
    stages = 1 if stages is None else stages
    if not 1 <= stages <= MAX_HOLD_STAGES:
        raise LabInputError(f"--plate-hold-stages {stages} is outside 1..{MAX_HOLD_STAGES} (the "
                            f"number of stops over the loading, the last at its end)")
    return {"hold": _f(hold), "hold_stages": str(int(stages))}


def plate_test_time_s(variables):
    """A plate run's simulated length [s] from its variables: the gap, the loading with its holds,
    the unloading and the reload at plate_speed (soil_lab/decks/lab_plate_schedule.in's t3)."""
    v = {k: float(x) for k, x in variables.items()}
    holds = v.get("hold_stages", 1.0) * v.get("hold", 0.0)
    return ((v["gap"] + v["depth1"] + 2 * v["unload"] + v["depth2"] - v["depth1"])
            / v["plate_speed"] + holds)


SPEED_VARIABLES = {"plate": "plate_speed", "shear": "shear_speed", "repose": "lift_speed"}
OUTPUTS = {"plate": {"out_csv": "plate.csv"}, "shear": {"out_csv": "shear.csv"},
           "repose": {"out_dump": "repose.dump"}}  # each test's deck output, in its run folder


def _checked_runs(runs, repose):
    """The runs a check repeats with one thing changed: the larger plate and the middle normal
    stress's box, each on every bed (with --plate-replicates, --shear-replicates: the difference
    is then measured on each bed, and its mean is read against its own scatter), the repose test
    (if `repose`)."""
    picked = []
    plates = [r for r in runs if r.test == "plate"]
    shears = [r for r in runs if r.test == "shear" and "replicate" not in r.meta]
    if plates:
        b_max = max(r.meta["b_m"] for r in plates)
        picked += [r for r in plates if r.meta["b_m"] == b_max]
    if shears:
        middle = sorted(shears, key=lambda r: r.meta["normal_stress_Pa"])[len(shears) // 2]
        picked += [r for r in runs if r.test == "shear" and
                   r.meta["normal_stress_Pa"] == middle.meta["normal_stress_Pa"]]
    if repose:
        picked += [r for r in runs if r.test == "repose"]
    return picked


def _half_speed_runs(runs, repose=True):
    """The quasi-static check's runs (_checked_runs), each at half its speed (same bed and
    tools)."""
    out = []
    for r in _checked_runs(runs, repose):
        var = SPEED_VARIABLES[r.test]
        half = float(r.variables[var]) / 2
        out.append(Run(name=f"{r.name}_half", test=r.test, deck=r.deck, bed=r.bed,
                       meshes=r.meshes, variables={**r.variables, var: _f(half)},
                       meta={**r.meta, "speed_m_s": half, "half_of": r.name}))
    return out


# --dt-check: a run's time step relative to the soil's (meta dt_factor; 1 for every other run).
# The bed keeps the step it was prepared at; only the test runs at the fraction (runner.Lab.run
# passes it to LIGGGHTS as a soil file that includes the soil's and sets soil_dt).
DT_CHECK_FACTOR = 0.5


def run_dt_s(run, soil_dt_s):
    """The time step [s] `run` runs at: the soil's, or DT_CHECK_FACTOR of it (--dt-check)."""
    return soil_dt_s * float(run.meta.get("dt_factor", 1.0))


def _half_step_runs(runs):
    """The time-step check's runs: the larger plate and the middle normal stress's boxes
    (_checked_runs; not the repose test: its heap is the longest run of a lab, and a step
    sensitivity of the soil shows under the tools first), each at DT_CHECK_FACTOR of the soil's
    time step, at the same speed on the same bed with the same tools."""
    return [Run(name=f"{r.name}_halfdt", test=r.test, deck=r.deck, bed=r.bed, meshes=r.meshes,
                variables=dict(r.variables),
                meta={**r.meta, "dt_factor": DT_CHECK_FACTOR, "half_dt_of": r.name})
            for r in _checked_runs([r for r in runs if "half_of" not in r.meta], repose=False)]
