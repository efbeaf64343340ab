"""`soil-lab report` and `soil-lab scm`: read a lab directory's outputs, fit, summarise, plot.

What is read (runner.py writes it): soil.toml; beds/plate/done.json (bulk density, porosity);
beds/shear/done.json and beds/shear_r<k>/done.json (the sample's mass); beds/*/hold/done.json (the bed-hold check);
plate_b*/plate.csv; shear_s*/shear.csv; repose/repose.dump; each run's done.json (cost).
What is written by write_report: results.toml, results.csv, plate.png, shear_curves.png,
mohr_coulomb.png, repose.png (for the tests that ran). docs/soil-lab.md, "Outputs".
"""

import csv
import json
import re
import tomllib
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Dict, List, Optional

import numpy as np

from . import fits, plan, repose, report, scm_file
from ._inputs import FitInputError


class LabResultError(ValueError):
    """A lab directory lacks an output its analysis needs; the message names it."""


@dataclass
class Results:
    soil: dict
    directory: Path
    bulk: Optional[dict] = None
    plates: List[dict] = field(default_factory=list)  # b_m, replicate, run, t, z, p, phase, done
    bekker: Optional[fits.BekkerFit] = None
    holds: Dict[float, List[dict]] = field(default_factory=dict)  # by b_m (first bed): plate_holds
    bekker_relaxed: Optional[fits.BekkerFit] = None  # on the pressures at the ends of the holds
    unload: Dict[float, fits.UnloadFit] = field(default_factory=dict)  # by b_m (first bed)
    unload_errors: Dict[float, str] = field(default_factory=dict)  # by b_m: why no Ke was fitted
    shears: List[dict] = field(default_factory=list)  # sigma_Pa, j, tau, peak, janosi, done
    mc_peak: Optional[fits.MohrCoulombFit] = None
    mc_residual: Optional[fits.MohrCoulombFit] = None
    replicates: Optional[dict] = None  # with --shear-replicates: shear_replicates' summary
    plate_replicates: Optional[dict] = None  # with --plate-replicates: plate_replicates' summary
    repose_fits: List[repose.ReposeFit] = field(default_factory=list)
    repose_profiles: List[tuple] = field(default_factory=list)
    repose_error: Optional[str] = None  # why no angle could be fitted (too small a heap, ...)
    quasi_static: List[dict] = field(default_factory=list)  # half-speed comparisons
    time_step: List[dict] = field(default_factory=list)  # half-step comparisons (--dt-check)
    paired_speed_checks: List[dict] = field(default_factory=list)  # over beds: paired_check
    paired_step_checks: List[dict] = field(default_factory=list)  # the same for --dt-check
    costs: List[dict] = field(default_factory=list)
    bed_costs: Dict[str, float] = field(default_factory=dict)  # bed name -> wall time [s]
    bed_holds: Dict[str, dict] = field(default_factory=dict)  # bed name -> bed-hold check result
    shear_bed_bulk_density: Optional[float] = None  # beds/shear as poured (in.soilbin's measure)

    @property
    def janosi_K_m(self):
        Ks = [s["janosi"].K_m for s in self.shears if s["janosi"] is not None]
        return float(np.mean(Ks)) if Ks else None

    @property
    def repose_angle_deg(self):
        return float(np.mean([f.angle_deg for f in self.repose_fits])) if self.repose_fits else None


# --- reading a lab directory's files: what is not what soil-lab run writes is a LabResultError
# naming the file (and its line and column, or its field) and what was expected.

def _read_text(path):
    """The text of the file `path`; a LabResultError if it cannot be read or is not UTF-8 text
    (a binary or damaged file: the line of its first bad byte)."""
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise LabResultError(f"{path}: cannot read it: {e.strerror}") from None
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as e:
        line = raw.count(b"\n", 0, e.start) + 1
        raise LabResultError(f"{path}, line {line}: byte 0x{raw[e.start]:02x} is not UTF-8 "
                             f"text: expected a text file (a binary or damaged file?)") from None


def _read_toml(path):
    """The TOML file `path` as a dict; a LabResultError naming its line and column if it is not
    TOML."""
    try:
        return tomllib.loads(_read_text(path))
    except tomllib.TOMLDecodeError as e:
        raise LabResultError(f"{path}: not valid TOML: {e}") from None


def _read_json_object(path):
    """The JSON object in the file `path`; a LabResultError naming its line and column if it is
    not JSON, or if it is not an object."""
    try:
        data = json.loads(_read_text(path))
    except json.JSONDecodeError as e:
        raise LabResultError(f"{path}: not valid JSON: {e.msg} (line {e.lineno}, column "
                             f"{e.colno})") from None
    if not isinstance(data, dict):
        raise LabResultError(f"{path}: expected a JSON object {{...}}, got "
                             f"{type(data).__name__} {str(data)[:40]}")
    return data


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v)


def _number(where, table, key, expected, ok=lambda v: True, text=False, required=True,
            prefix=""):
    """table[key] of the file `where` as a float (None if it is absent and not `required`): a
    finite number for which ok(value) holds, also written as a string if `text` (in.soilbin's
    printed results); else a LabResultError naming the file, the key (after `prefix`, e.g.
    "meta.") and `expected`."""
    if key not in table:
        if not required:
            return None
        raise LabResultError(f"{where}: {prefix}{key} is missing: expected {expected}")
    v = table[key]
    if text and isinstance(v, str):
        try:
            v = float(v)
        except ValueError:
            pass
    if not (_is_number(v) and ok(float(v))):
        raise LabResultError(f"{where}: {prefix}{key} = {table[key]!r}: expected {expected}")
    return float(v)


def _table(path, names, skip_lines=0):
    """The whitespace-separated table in the file `path` (after `skip_lines` lines; '#' starts a
    comment) as {name: column array}. A LabResultError names the file, and the line and column,
    if it cannot be read, has no rows, or a row has another number of columns than `names` or
    holds anything but finite numbers (a damaged or truncated file)."""
    lines = _read_text(path).splitlines()[skip_lines:]
    what = f"rows of {len(names)} numbers ({' '.join(names)})"
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # loadtxt's "input contained no data"
            data = np.loadtxt(lines, comments="#", ndmin=2)
    except ValueError:
        data = None
    if data is not None and data.shape[0] == 0:
        raise LabResultError(f"{path}: no data rows: expected {what}")
    if data is None or data.shape[1] != len(names) or not np.isfinite(data).all():
        for i, line in enumerate(lines):
            fields = line.split("#", 1)[0].split()
            if not fields:
                continue
            at = f"{path}, line {skip_lines + i + 1}"
            if len(fields) != len(names):
                raise LabResultError(f"{at}: {len(fields)} columns, expected {what}")
            for k, (value, name) in enumerate(zip(fields, names)):
                try:
                    ok = np.isfinite(float(value))
                except ValueError:
                    ok = False
                if not ok:
                    raise LabResultError(f"{at}, column {k + 1} ({name}): '{value}' is not a "
                                         f"finite number: expected {what}")
        raise LabResultError(f"{path}: expected {what}")
    return {n: data[:, i] for i, n in enumerate(names)}


def _done(directory):
    """A step's done.json (written last, when it finished), or None if it has none."""
    f = Path(directory) / "done.json"
    return _read_json_object(f) if f.is_file() else None


def _meta(run, done, key, expected, required=True):
    """done.json's meta[key] of the run `run`, a size or a stress (a finite number > 0; None if
    absent and not `required`)."""
    where = Path(run) / "done.json"
    meta = done.get("meta")
    if not isinstance(meta, dict):
        raise LabResultError(f"{where}: meta = {meta!r}: expected a table of the run's sizes "
                             f"(with {key})")
    return _number(where, meta, key, expected, lambda v: v > 0, required=required,
                   prefix="meta.")


#: A bed-hold check's result (bed_hold.parse) as the report uses it (bed_hold.describe, failure).
HOLD_RESULT_KEYS = ("hold_s", "zcm_start_m", "zcm_end_m", "settlement",
                    "settlement_last_quarter")


def _hold_result(where, hold):
    """The result of a bed-hold record (beds/<bed>/hold/done.json), its numbers checked."""
    res = hold.get("result")
    if not isinstance(res, dict):
        raise LabResultError(f"{where}: result = {res!r}: expected the table of the bed-hold "
                             "check's result")
    for key in HOLD_RESULT_KEYS + ("sink_rate_m_s",):
        _number(where, res, key, "a number", required=key != "sink_rate_m_s", prefix="result.")
    return res


#: soil.toml's fields (soil-lab run writes them from in.lab_soilinfo), each checked when present:
#: (what is expected, test). SOIL_REQUIRED are needed by every report.
SOIL_FIELDS = {
    "name": ("the soil's name, a non-empty string", lambda v: isinstance(v, str) and v.strip()),
    "file": ("the soil file's path, a string", lambda v: isinstance(v, str)),
    "preset": (f"one of {', '.join(plan.PRESETS)}", lambda v: isinstance(v, str)
               and v in plan.PRESETS),
    "tests": (f"a list of tests from {', '.join(plan.TEST_NAMES)}",
              lambda v: isinstance(v, list) and all(isinstance(t, str) and t in plan.TEST_NAMES
                                                    for t in v)),
    "dmin_m": ("the smallest grain diameter, a number > 0 [m]", lambda v: _is_number(v) and v > 0),
    "dmax_m": ("the largest grain diameter, a number > 0 [m]", lambda v: _is_number(v) and v > 0),
    "dref_m": ("the reference grain diameter, a number > 0 [m]",
               lambda v: _is_number(v) and v > 0),
    "density_kg_m3": ("the particle density, a number > 0 [kg/m^3]",
                      lambda v: _is_number(v) and v > 0),
    "multisphere": ("true or false", lambda v: isinstance(v, bool)),
    "dt_s": ("the time step, a number > 0 [s]", lambda v: _is_number(v) and v > 0),
    "youngs_Pa": ("the particles' Young's modulus, a number > 0 [Pa] (-1: not named)",
                  lambda v: _is_number(v) and (v > 0 or v == -1)),
    "invocations": ("an array of tables ([[invocations]])",
                    lambda v: isinstance(v, list) and all(isinstance(i, dict) for i in v)),
}
SOIL_REQUIRED = ("name", "dmax_m")


def read_soil(path):
    """A lab's soil.toml as a dict, its fields checked (SOIL_FIELDS): a LabResultError names the
    file and the field."""
    soil = _read_toml(path)
    for key in SOIL_REQUIRED:
        if key not in soil:
            raise LabResultError(f"{path}: {key} is missing: expected {SOIL_FIELDS[key][0]}")
    for key, (expected, ok) in SOIL_FIELDS.items():
        if key in soil and not ok(soil[key]):
            raise LabResultError(f"{path}: {key} = {soil[key]!r}: expected {expected}")
    if "dmin_m" in soil and soil["dmin_m"] > soil["dmax_m"]:
        raise LabResultError(f"{path}: dmin_m = {soil['dmin_m']!r} is larger than dmax_m = "
                             f"{soil['dmax_m']!r}: expected dmin_m <= dmax_m")
    return soil


COST_KEYS = ("wall_s", "steps", "particles", "np", "dt_s")
#: The checks: the result at half the speed (the quasi-static check) or at half the time step
#: (--dt-check) must differ by less than this (docs/soil-lab.md).
QUASI_STATIC_TOLERANCE = {"plate": 0.05, "shear": 0.05, "repose": 1.5}  # relative, relative, deg
CHECK_SUFFIXES = ("_half", "_halfdt")  # the checks' runs: not points of the lab's own fits


def _runs(d, pattern):
    """The finished runs matching `pattern`, without the checks' (half speed, half step)."""
    runs = [(run, _done(run)) for run in sorted(d.glob(pattern))
            if not run.name.endswith(CHECK_SUFFIXES)]
    return [(run, done) for run, done in runs if done is not None]


def read_plate(run, done):
    path = Path(run) / "plate.csv"
    t = _table(path, ("time_s", "sinkage_m", "force_N", "pressure_Pa", "contacts", "phase"))
    if np.count_nonzero((t["phase"] == PLATE_LOAD) & (t["sinkage_m"] > 0)) < 2:
        raise LabResultError(f"{path}: fewer than 2 rows of the loading (phase {PLATE_LOAD}) "
                             f"below the surface (sinkage_m > 0) in its {len(t['phase'])} rows: "
                             "expected a finished run's record (a truncated file?)")
    return {"b_m": _meta(run, done, "b_m", "the plate's width, a number > 0 [m]"),
            "replicate": _replicate(run, done, "plate"), "run": Path(run).name,
            "t": t["time_s"], "z": t["sinkage_m"], "p": t["pressure_Pa"], "phase": t["phase"],
            "done": done}


def _replicate(run, done, tool):
    """A run's bed among a lab's replicate beds (meta replicate; 1, the lab's first bed, when
    absent); a LabResultError when it is not a whole number >= 1."""
    replicate = (done.get("meta") or {}).get("replicate", 1)
    if isinstance(replicate, bool) or not isinstance(replicate, int) or replicate < 1:
        raise LabResultError(f"{Path(run) / 'done.json'}: meta.replicate = {replicate!r}: expected "
                             f"a whole number >= 1 (the {tool}'s bed: 1 the lab's first)")
    return replicate


#: in.lab_plate's phase codes
PLATE_LOAD, PLATE_UNLOAD, PLATE_RELOAD, PLATE_HOLD = 1, 2, 3, 4
#: A hold's pressure at speed is the straight line through the last HOLD_APPROACH_S of the motion
#: into it, taken at the stop; its pressure at the end the mean over the hold's last
#: HOLD_END_FRACTION.
HOLD_APPROACH_S = 0.02
HOLD_END_FRACTION = 0.1
#: The pressure just after the stop: the mean over the hold's first HOLD_STEP_S (a few samples).
HOLD_STEP_S = 0.002
#: A hold has relaxed (`converged`) if its exponential fit says so and, whatever the fit, the
#: pressure fell by less than this share of the moving pressure from the hold's middle tenth to its
#: last tenth: a long-tailed (creeping) relaxation can fit an exponential that looks done.
HOLD_LATE_DROP_TOLERANCE = 0.02


def loading_branch(plate):
    """(z [m], p [Pa]) of a plate run's loading branch (phase 1: moving down, holds left out)."""
    load = plate["phase"] == PLATE_LOAD
    return plate["z"][load], plate["p"][load]


def unrelaxed_holds(r):
    """The holds of lab `r` still relaxing at their end, as (b_m, hold) pairs."""
    return [(b, h) for b, hs in r.holds.items() for h in hs if not h["converged"]]


def plate_holds(plate):
    """The hold stages of a plate run (in.lab_plate, hold > 0; [] without), in time order: per
    stage its sinkage z_m [m], hold_s [s], the pressure at speed at the stop p_moving_Pa and at
    the hold's end p_end_Pa [Pa], relaxation = 1 - p_end / p_moving, step_at_stop = 1 - p_stop /
    p_moving (p_stop_Pa: the mean over the hold's first HOLD_STEP_S), late_drop (the
    fall from the hold's middle tenth to its last, over p_moving), the exponential fit
    (fits.fit_relaxation of the pressure against the time since the stop) and converged (the fit
    converged and late_drop < HOLD_LATE_DROP_TOLERANCE)."""
    t, z, p, phase = plate["t"], plate["z"], plate["p"], plate["phase"]
    held = np.flatnonzero(phase == PLATE_HOLD)
    if held.size == 0:
        return []
    stages = np.split(held, np.flatnonzero(np.diff(held) > 1) + 1)
    out = []
    for idx in stages:
        t_stop = t[idx[0]]
        moving = (phase == PLATE_LOAD) & (t < t_stop) & (t >= t_stop - HOLD_APPROACH_S)
        th, ph = t[idx] - t_stop, p[idx]
        end = th >= (1.0 - HOLD_END_FRACTION) * th[-1]
        middle = np.abs(th - 0.5 * th[-1]) <= 0.5 * HOLD_END_FRACTION * th[-1]
        if np.count_nonzero(moving) >= 2:
            _, at_stop = np.polyfit(t[moving] - t_stop, p[moving], 1)
            p_moving = float(at_stop)
        else:
            p_moving = float(ph[0])
        p_end = float(np.mean(ph[end]))
        try:
            fit = fits.fit_relaxation(th, ph)
        except FitInputError:
            fit = None
        late_drop = (float(np.mean(ph[middle])) - p_end) / p_moving if p_moving > 0 else \
            float("nan")
        p_stop = float(np.mean(ph[th <= HOLD_STEP_S]))
        out.append({"z_m": float(np.mean(z[idx])), "hold_s": float(th[-1]),
                    "p_moving_Pa": p_moving, "p_end_Pa": p_end,
                    "relaxation": 1.0 - p_end / p_moving if p_moving > 0 else float("nan"),
                    "late_drop": late_drop, "p_stop_Pa": p_stop,
                    "step_at_stop": 1.0 - p_stop / p_moving if p_moving > 0 else float("nan"),
                    "converged": bool(fit is not None and fit.converged
                                      and abs(late_drop) < HOLD_LATE_DROP_TOLERANCE),
                    "fit": fit, "t_s": th, "p_Pa": ph})
    return out


#: The plate speed check compares the two runs' loading branches in this many equal bands of
#: sinkage, not only at the end: a rate effect shows at every depth, a chance force chain in one.
#: The last band (the last 20 % of the range) is the check's "pressure at the end of loading".
PLATE_PROFILE_BANDS = 5


def plate_pressure_profile(plate):
    """(band centres [m], mean pressure [Pa] in each band) of the loading branch, its sinkage range
    [0, z_max] cut into PLATE_PROFILE_BANDS equal bands (the last one ends at z_max, included)."""
    z, p = loading_branch(plate)
    return band_means(z, p, z.max(), PLATE_PROFILE_BANDS)


def band_means(x, y, top, bands):
    """(band centres, mean of y in each band): [0, top] cut into `bands` equal bands of x (the last
    one ends at top, included; x beyond top is left out); NaN for a band with no sample."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    edges = np.linspace(0.0, float(top), bands + 1)
    band = np.searchsorted(edges, x, side="right") - 1
    band[x == top] = bands - 1
    means = [float(np.mean(y[band == k])) if np.any(band == k) else float("nan")
             for k in range(bands)]
    return 0.5 * (edges[:-1] + edges[1:]), np.array(means)


#: The shear box's speed check also compares the two runs band by band: the travel cut into this
#: many equal bands of shear displacement (quarters), the mean shear stress in each.
SHEAR_PROFILE_BANDS = 4


def shear_stress_profile(j_m, tau_Pa, j_max_m=None):
    """(band centres [m], mean shear stress [Pa] in each band) of a shear run: band_means over
    [0, j_max_m] (default: the run's largest j) in SHEAR_PROFILE_BANDS bands."""
    top = float(np.max(j_m)) if j_max_m is None else float(j_max_m)
    return band_means(j_m, tau_Pa, top, SHEAR_PROFILE_BANDS)


def profile_changes_sign(differences, floor=0.01):
    """True when a speed check's band differences lie on both sides of zero by more than
    `floor` (relative): the slower run is stronger along part of the travel and weaker along
    another, so its verdict rests on where the peaks fell; one pair of runs cannot tell the
    runs' own fluctuation (stick-slip) from a rate effect that grows along the travel (a creeping
    sample compacting more in the slower run's longer time)."""
    d = np.asarray(differences, dtype=float)
    d = d[np.isfinite(d)]
    return bool(d.size and d.max() > floor and d.min() < -floor)


def plate_end_pressure(plate):
    """Mean pressure over the last band (20 %) of the loading branch's sinkage range [Pa]."""
    return float(plate_pressure_profile(plate)[1][-1])


#: A shear box that has lost more than this share of its particles by the peak, or by the end, is
#: reported (docs/soil-lab.md). Boxes run before 2026-11-26 lost grains over the upper frame's
#: overhang; since then the lower frame's rim and a wider domain keep them, and this is a check.
SHEAR_LOSS_WARNING = 0.01
_SHEAR_THERMO_HEADER = re.compile(r"^\s*Step\s+Atoms\s+j\s+tau\b", re.M)


def shear_particle_counts(log_text):
    """(j [m], particles) of the shear run's thermo rows (in.lab_shear's `thermo_style custom
    step atoms v_j ...`: one block per LIGGGHTS run, the consolidation's checks and the shear), or
    None when the log has none."""
    j, n = [], []
    for m in _SHEAR_THERMO_HEADER.finditer(log_text):
        for line in log_text[m.end():].splitlines()[1:]:
            cols = line.split()
            try:
                n_i, j_i = int(cols[1]), float(cols[2])
            except (IndexError, ValueError):
                break  # the end of the thermo block
            n.append(n_i)
            j.append(j_i)
    return (np.array(j), np.array(n)) if n else None


def shear_particle_loss(counts, j_peak_m):
    """{particles, lost_by_peak, lost_at_end} (fractions of the particles at the start of the
    shear) from shear_particle_counts, or None."""
    if counts is None:
        return None
    j, n = counts
    at_peak = n[np.searchsorted(j, j_peak_m)] if j_peak_m <= j[-1] else n[-1]
    return {"particles": int(n[0]), "lost_by_peak": float(1.0 - at_peak / n[0]),
            "lost_at_end": float(1.0 - n[-1] / n[0])}


def shear_peak_and_residual(j_m, tau_Pa, smooth_fraction=0.05):
    """fits.PeakResidual of a shear box's curve: the peak is that of a centred running mean over
    `smooth_fraction` of the points (the raw maximum is biased upwards by the DEM signal's
    noise), taken only where the window is full (a zero-padded mean at the ends would read low);
    the residual, the mean over the last 20 % of the displacement, is the raw curve's."""
    j, tau = np.asarray(j_m, dtype=float), np.asarray(tau_Pa, dtype=float)
    raw = fits.peak_and_residual(j, tau)
    w = max(1, int(len(tau) * smooth_fraction))
    if len(tau) <= w:
        return raw
    smooth = np.convolve(tau, np.ones(w) / w, mode="valid")  # smooth[k]: tau[k .. k+w-1]
    k = int(np.argmax(smooth))
    return replace(raw, tau_peak_Pa=float(smooth[k]), j_peak_m=float(j[k + w // 2]))


def shear_consolidation(time_s, sigma_Pa, lid_z_m, phase, log_text=""):
    """How the box consolidated before it sheared: {consolidation_s (the time the shear began),
    sigma_start_ratio (the mean normal stress over the first 2 % of the shear's rows / its mean
    over the shear), lid_z_start_m (the sample's height then, above the floor), lid_travel_m (the
    lid's vertical displacement over the shear: < 0 the sample contracted), not_consolidated (the
    deck's WARNING: still creeping at consolidate_max)}."""
    s = np.asarray(phase) == 2
    z = np.asarray(lid_z_m, dtype=float)[s]
    sig = np.asarray(sigma_Pa, dtype=float)[s]
    head = sig[: max(1, len(sig) // 50)]
    return {"consolidation_s": float(np.asarray(time_s, dtype=float)[s][0]),
            "sigma_start_ratio": float(np.mean(head) / np.mean(sig)),
            "lid_z_start_m": float(z[0]), "lid_travel_m": float(z[-1] - z[0]),
            "not_consolidated": "WARNING: not consolidated" in log_text}


def read_shear(run, done):
    run = Path(run)
    path = run / "shear.csv"
    t = _table(path, ("time_s", "displacement_m", "shear_force_N", "tau_Pa", "sigma_Pa",
                      "lid_z_m", "phase"))
    sigma_target = _meta(run, done, "normal_stress_Pa", "the normal stress, a number > 0 [Pa]")
    _meta(run, done, "box_m", "the box's side, a number > 0 [m]", required=False)
    s = t["phase"] == 2
    if not s.any():
        raise LabResultError(f"{path}: no rows of the shear (phase 2) in its {len(s)} rows: "
                             "expected a finished run's record (a truncated file?)")
    j, tau, sigma = t["displacement_m"][s], t["tau_Pa"][s], t["sigma_Pa"][s]
    try:
        peak = shear_peak_and_residual(j, tau)
        janosi = fits.fit_janosi(j, tau)
    except FitInputError as e:
        raise LabResultError(f"{path}: its shear rows (phase 2) cannot be fitted: {e} (a "
                             "truncated or damaged file?)") from None
    log = run / "liggghts.log"
    text = log.read_text(errors="replace") if log.is_file() else ""
    counts = shear_particle_counts(text) if text else None
    replicate = _replicate(run, done, "box")
    return {"sigma_Pa": float(np.mean(sigma)), "sigma_target_Pa": sigma_target,
            "replicate": replicate,
            "j": j, "tau": tau, "lid_dz": t["lid_z_m"][s] - t["lid_z_m"][s][0], "peak": peak,
            "janosi": janosi, "loss": shear_particle_loss(counts, peak.j_peak_m),
            "consolidation": shear_consolidation(t["time_s"], t["sigma_Pa"], t["lid_z_m"],
                                                 t["phase"], text),
            "done": done}


def shear_sample_density(shears, bed_dir):
    """The sample's bulk density in each box when its shear began and when it ended [kg/m³]: the
    shear bed's particle mass (beds/shear/done.json: the whole bed is the sample) over the box's
    area times the lid's height above the floor, less the particles lost by then; None for a box
    whose side is not the bed's. The lid rests on the highest grains, so this reads a few % below
    in.soilbin's measure of the same bed (its mean column top); the bed's own is returned beside
    it. Returns (bed bulk density, [(start, end) per box]), (None, []) without the bed's record."""
    done = _done(bed_dir)
    res = done.get("result") if done else None
    if not isinstance(res, dict):
        return None, []
    where = Path(bed_dir) / "done.json"
    mass = _number(where, res, "particle_mass", "the bed's particle mass > 0 [kg]",
                   lambda v: v > 0, text=True, required=False, prefix="result.")
    dims = [_number(where, res, k, "a size > 0 [m]", lambda v: v > 0, text=True,
                    required=False, prefix="result.") for k in ("bin_length", "bin_width")]
    bed_rho = _number(where, res, "bulk_density", "a density > 0 [kg/m3]", lambda v: v > 0,
                      text=True, required=False, prefix="result.")
    spheres = _number(where, res, "spheres", "a count > 0", lambda v: v > 0, text=True,
                      required=False, prefix="result.")
    if mass is None or None in dims:
        return bed_rho, []
    out = []
    for s in shears:
        c, box = s.get("consolidation"), (s.get("done") or {}).get("meta", {}).get("box_m")
        if c is None or not isinstance(box, (int, float)) or any(
                abs(box - L) > 1e-9 * L for L in dims):
            out.append(None)
            continue
        # the particles still in the box (the thermo's sphere counts) carry the bed's mean mass
        loss = s.get("loss")
        kept = 1.0 if loss is None or not spheres else min(1.0, loss["particles"] / spheres)
        kept_end = kept * (1.0 - loss["lost_at_end"]) if loss is not None else 1.0
        area, h = dims[0] * dims[1], c["lid_z_start_m"]
        start = mass * kept / (area * h)
        end = mass * kept_end / (area * (h + c["lid_travel_m"]))
        out.append((float(start), float(end)))
    return bed_rho, out


def read_shears(d):
    """The finished shear boxes in `d` (read_shear's records, by normal stress on the plane, then
    replicate; each consolidation record with the sample's densities where its bed's
    d/beds/<bed>/done.json is there) and the first shear bed's bulk density as poured (None
    without its record)."""
    shears = sorted((read_shear(run, done) for run, done in _runs(Path(d), "shear_s*")),
                    key=lambda s: (s["sigma_Pa"], s["replicate"]))
    bed_rho = None
    for k in sorted({s["replicate"] for s in shears}):
        group = [s for s in shears if s["replicate"] == k]
        rho_k, densities = shear_sample_density(group, Path(d) / "beds" / plan.shear_bed_name(k))
        bed_rho = rho_k if k == 1 else bed_rho
        for s, rho in zip(group, densities):
            if rho is not None:
                s["consolidation"]["sample_bulk_density_kg_m3"] = rho[0]
                s["consolidation"]["sample_bulk_density_end_kg_m3"] = rho[1]
    return shears, bed_rho


def shear_stress_count(shears):
    """The number of different target normal stresses among the finished boxes (replicates of
    one stress count once): the Mohr-Coulomb fit needs 3."""
    return len({s["sigma_target_Pa"] for s in shears})


def shear_replicates(shears):
    """How much the boxes scatter from bed to bed, for a lab with replicate boxes
    (--shear-replicates; None without a second replicate): per target normal stress the peaks'
    count, mean, sample standard deviation and spread ((max - min) / mean), and per replicate
    whose boxes cover >= 3 stresses its own Mohr-Coulomb fit (c, phi), with the spread of those
    fits (sample standard deviations over the replicates)."""
    reps = sorted({s["replicate"] for s in shears})
    if len(reps) < 2:
        return None
    by_stress = []
    for target in sorted({s["sigma_target_Pa"] for s in shears}):
        peaks = np.array([s["peak"].tau_peak_Pa for s in shears if s["sigma_target_Pa"] == target])
        mean = float(peaks.mean())
        by_stress.append({"sigma_target_Pa": float(target), "boxes": int(peaks.size),
                          "tau_peak_mean_Pa": mean,
                          "tau_peak_sd_Pa": float(peaks.std(ddof=1)) if peaks.size > 1 else 0.0,
                          "tau_peak_spread": float(np.ptp(peaks) / mean) if mean > 0 else 0.0})
    per = []
    for k in reps:
        group = [s for s in shears if s["replicate"] == k]
        if shear_stress_count(group) < 3:
            continue
        f = fits.fit_mohr_coulomb([s["sigma_Pa"] for s in group],
                                  [s["peak"].tau_peak_Pa for s in group])
        per.append((k, f.friction_deg, f.cohesion_Pa))
    out = {"replicates": reps, "by_stress": by_stress,
           "fitted_replicates": [k for k, _, _ in per],
           "friction_deg": [phi for _, phi, _ in per], "cohesion_Pa": [c for _, _, c in per]}
    if len(per) >= 2:
        out["friction_sd_deg"] = float(np.std([phi for _, phi, _ in per], ddof=1))
        out["cohesion_sd_Pa"] = float(np.std([c for _, _, c in per], ddof=1))
    return out


def plate_replicates(plates, directory=None):
    """How much the plates scatter from bed to bed, for a lab with replicate plate beds
    (--plate-replicates; None without a second bed): per plate width the pressures at the end of
    loading (plate_end_pressure): count, mean, sample standard deviation and spread ((max - min) /
    mean); per bed with both widths its own Bekker fit (n, kc, kphi) and, with `directory`, its
    bed's bulk density as poured (beds/<bed>/done.json, the core cell's where measured); the
    sample standard deviations of n, kc, kphi over the beds."""
    reps = sorted({q["replicate"] for q in plates})
    if len(reps) < 2:
        return None
    by_width = []
    for b in sorted({q["b_m"] for q in plates}):
        ends = np.array([plate_end_pressure(q) for q in plates if q["b_m"] == b])
        mean = float(ends.mean())
        by_width.append({"b_m": float(b), "plates": int(ends.size), "p_end_mean_Pa": mean,
                         "p_end_sd_Pa": float(ends.std(ddof=1)) if ends.size > 1 else 0.0,
                         "p_end_spread": float(np.ptp(ends) / mean) if mean > 0 else 0.0})
    out = {"replicates": reps, "by_width": by_width, "fitted_replicates": [], "n": [],
           "kc_N_m_n1": [], "kphi_N_m_n2": []}
    for k in reps:
        group = [q for q in plates if q["replicate"] == k]
        if len({q["b_m"] for q in group}) < 2:
            continue
        f = fits.fit_bekker([(q["b_m"], *loading_branch(q)) for q in group])
        out["fitted_replicates"].append(k)
        out["n"].append(f.n)
        out["kc_N_m_n1"].append(f.kc)
        out["kphi_N_m_n2"].append(f.kphi)
    if len(out["fitted_replicates"]) >= 2:
        for key in ("n", "kc_N_m_n1", "kphi_N_m_n2"):
            out[f"{key}_sd"] = float(np.std(out[key], ddof=1))
    if directory is not None:
        densities = {}
        for k in reps:
            done = _done(Path(directory) / "beds" / plan.plate_bed_name(k))
            res = (done or {}).get("result")
            where = Path(directory) / "beds" / plan.plate_bed_name(k) / "done.json"
            rho = None
            if isinstance(res, dict):
                rho = next((v for key in ("core_bulk_density", "bulk_density") if (
                    v := _number(where, res, key, "a density > 0 [kg/m3]", lambda v: v > 0,
                                 text=True, required=False, prefix="result.")) is not None), None)
            if rho is not None:
                densities[k] = rho
        if densities:
            out["bed_bulk_density_kg_m3"] = {f"bed{k}": v for k, v in densities.items()}
    return out


# A shear box whose smoothed shear stress falls below -UNSTABLE_SHEAR_FRACTION x its peak pulls
# the soil backwards: not a quasi-static test (nakanishi_2020 at its own time step, E 5e5 Pa:
# -2.4 kPa against a 1.2 kPa peak), so its peak and fits are no soil property.
UNSTABLE_SHEAR_FRACTION = 0.25


def shear_stability_errors(shears):
    """A line for each shear box whose curve is not a resisting soil's: a fitted Janosi tau_max
    <= 0, or a smoothed shear stress below -UNSTABLE_SHEAR_FRACTION x the peak."""
    out = []
    for s in shears:
        if s.get("tau") is None or s.get("janosi") is None:
            continue  # a summary without its curve (nothing to check)
        tau = np.asarray(s["tau"], dtype=float)
        w = max(1, len(tau) // 50)
        smooth = np.convolve(tau, np.ones(w) / w, mode="valid") if len(tau) > w else tau
        low, peak = float(np.min(smooth)), s["peak"].tau_peak_Pa
        at = _box_at(s)
        if s["janosi"].tau_max_Pa <= 0 or low < -UNSTABLE_SHEAR_FRACTION * abs(peak):
            out.append(at + f"unstable: the shear stress reached {low:.4g} Pa (peak {peak:.4g} "
                       f"Pa, Janosi tau_max {s['janosi'].tau_max_Pa:.4g} Pa): a resisting soil "
                       "cannot pull the frame; the run is not quasi-static (time step or speed too "
                       "large for these grains), so its peak and fits are not the soil's")
    return out


# A shear box whose mean shear stress over the last quarter of the travel exceeds the mean over
# the quarter before by more than this share of its peak has not reached its peak. Means over
# quarters, not a slope: the stick-slip waves of coarse grains (about a grain diameter long) make a
# fitted end slope swing by +-15 % on curves that have levelled off. Chosen on the lab runs of
# 2026-11-25/26: level curves (loose_sand_1330, dry_sand at 5.75 kPa) read -1 to +8 %, curves
# still climbing by eye (dry_sand at 10.4 kPa, dry_sand_coarse at 0.25 L) +11 to +23 %.
RISING_AT_END_WARNING = 0.08


def shear_rise_at_end(j_m, tau_Pa):
    """(mean tau over the last quarter of the displacement range - mean over the quarter before)
    / the largest tau: the share by which the curve still rose at the end of the travel."""
    j, tau = np.asarray(j_m, dtype=float), np.asarray(tau_Pa, dtype=float)
    span = float(np.ptp(j)) if j.size else 0.0
    peak = float(np.max(tau)) if tau.size else 0.0
    last = j >= j.min() + 0.75 * span
    before = (j >= j.min() + 0.5 * span) & ~last
    if span <= 0 or peak <= 0 or not last.any() or not before.any():
        return 0.0
    return float((tau[last].mean() - tau[before].mean()) / peak)


def shear_peak_warnings(shears):
    """A line for each shear box still rising at the end of its travel (shear_rise_at_end >
    RISING_AT_END_WARNING): its peak was not reached."""
    out = []
    for s in shears:
        if s.get("tau") is None or s.get("j") is None:
            continue
        rise = shear_rise_at_end(s["j"], s["tau"])
        if rise > RISING_AT_END_WARNING:
            box = (s.get("done") or {}).get("meta", {}).get("box_m")
            travel = f"{float(np.ptp(s['j'])) / box:.2g}" if box else "this"
            out.append(_box_at(s) + "the shear stress still rises "
                       f"at the end of the travel (its last quarter, to j {float(np.max(s['j'])):.3g} "
                       f"m, {100 * rise:.1f} % of the peak above the quarter before): the "
                       "peak was not reached, so this box's peak strength, and the friction angle "
                       "fitted through it, are lower bounds (the strength at this displacement, "
                       f"not a peak); a longer travel than {travel} of the box side "
                       "(--shear-travel) would show whether it levels off")
    return out


# With replicate boxes, the speed check's half-speed peak lies "within the scatter" of the
# same-speed boxes when it is within this many of their sample standard deviations of their mean
# (about a 95 % band for a normal scatter; with 2-5 boxes the sd itself is uncertain by 35-70 %).
REPLICATE_SCATTER_SDS = 2.0


# Two-sided 95 % quantiles of Student's t by degrees of freedom (1..4: 2..5 beds, the most
# --shear-replicates pours), for the interval of a mean over so few beds.
STUDENT_T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776}


# A paired check's verdicts: (the whole interval within the tolerance, wholly outside it).
SPEED_VERDICTS = ("quasi-static", "rate effect")
STEP_VERDICTS = ("step-converged", "step effect")


def paired_check(differences, tolerance, verdicts=SPEED_VERDICTS):
    """A check over beds: each bed's box with one thing changed (half the speed, half the time
    step) against its own box (relative peak differences, one per bed, >= 2). A pairing on the
    bed removes the bed-to-bed scatter (the packings differ, each pair shares one); what is left
    is the change's effect and each box's own fluctuation, whose spread over the beds is
    measured. Returns the mean difference, its sample sd and standard error, the 95 % interval
    (Student's t on n - 1 degrees of freedom) and the verdict: verdicts[0] ("quasi-static",
    "step-converged") when the whole interval lies within +-tolerance, verdicts[1] ("rate
    effect", "step effect") when it lies wholly outside, "cannot tell" otherwise (more beds
    narrow it); `passed` is the single pair's rule (|mean| <= tolerance) on the mean."""
    d = np.asarray(differences, dtype=float)
    if d.size < 2 or d.size - 1 not in STUDENT_T95:
        raise ValueError(f"a paired check needs 2..{max(STUDENT_T95) + 1} beds, got {d.size}")
    mean, sd = float(d.mean()), float(d.std(ddof=1))
    sem = sd / np.sqrt(d.size)
    t = STUDENT_T95[d.size - 1]
    lo, hi = mean - t * sem, mean + t * sem
    verdict = (verdicts[0] if -tolerance <= lo and hi <= tolerance else
               verdicts[1] if lo > tolerance or hi < -tolerance else "cannot tell")
    return {"beds": int(d.size), "differences": [float(x) for x in d],
            "mean_difference": mean, "sd_difference": sd, "sem_difference": float(sem),
            "t95": t, "interval_low": float(lo), "interval_high": float(hi),
            "tolerance": float(tolerance), "passed": bool(abs(mean) <= tolerance),
            "verdict": verdict}


def _box_name(s):
    """A box as the report names it: "<sigma> kPa", with " (bed k)" for a replicate's
    (--shear-replicates)."""
    bed = "" if s.get("replicate", 1) == 1 else f" (bed {s['replicate']})"
    return f"{s['sigma_Pa'] / 1e3:.3g} kPa{bed}"


def _box_at(s):
    """A warning's prefix naming the box: "shear box at <sigma> kPa[ (bed k)]: "."""
    return f"shear box at {_box_name(s)}: "


def _boxes_with(shears, key):
    """(a warning's "shear box at <sigma> kPa: " prefix, box[key], box) for each box that has
    `key` (a summary without it is skipped)."""
    for s in shears:
        if s.get(key) is not None:
            yield _box_at(s), s[key], s


# A box whose normal stress over the first 2 % of its shear is below this share of its mean over
# the shear began shearing before the lid had loaded the sample (before 2026-11-27 the box sheared
# after a fixed 0.5 s: clayey loam with tangential_reduce and rolling friction 0.01 began at 0.12).
SHEAR_START_SIGMA_WARNING = 0.9


def shear_consolidation_warnings(shears):
    """A line for each shear box that began shearing before its sample had consolidated: the deck
    said so (still creeping at consolidate_max), or its normal stress at the start of the shear
    was below SHEAR_START_SIGMA_WARNING x its mean."""
    out = []
    for at, c, _ in _boxes_with(shears, "consolidation"):
        if c["sigma_start_ratio"] < SHEAR_START_SIGMA_WARNING:
            out.append(at + f"the shear began at {100 * c['sigma_start_ratio']:.0f} % of the normal "
                       f"stress (after {c['consolidation_s']:.3g} s of consolidation): the sample "
                       "was loaded while it was sheared, so its strength is not that of a "
                       "consolidated sample; re-run the box (in.lab_shear waits for consolidation "
                       "since 2026-11-27)")
        elif c["not_consolidated"]:
            out.append(at + f"the sample still settled when the shear began (after "
                       f"{c['consolidation_s']:.3g} s: the log's WARNING); its lid moved "
                       f"{1e3 * c['lid_travel_m']:+.3g} mm over the shear (sample "
                       f"{1e3 * c['lid_z_start_m']:.4g} mm high): a soil that creeps under its "
                       "load, whose density changes while it is sheared")
    return out


def shear_count_warnings(shears):
    """A line when the finished shear boxes cover fewer normal stresses than the Mohr-Coulomb fit
    needs (a lab stopped before its last boxes, or reported while it runs): c and phi are then
    not fitted."""
    n = shear_stress_count(shears)
    if not 0 < n < 3:
        return []
    return [f"only {len(shears)} shear box(es) finished, at {n} normal stress(es): the "
            "Mohr-Coulomb fit needs >= 3 normal stresses, so c and phi are not fitted (the same "
            "soil-lab run command finishes the lab)"]


def shear_loss_warnings(shears):
    """A line for each shear box that lost more than SHEAR_LOSS_WARNING of its particles."""
    out = []
    for at, loss, s in _boxes_with(shears, "loss"):
        if loss["lost_by_peak"] > SHEAR_LOSS_WARNING:
            out.append(at + f"{100 * loss['lost_by_peak']:.1f} % of its {loss['particles']} "
                       f"particles had left the box by the peak (j {s['peak'].j_peak_m:.3g} m, over "
                       "the upper frame's overhang): the peak is not that of the full sample; "
                       "re-run the box (the lower frame's rim keeps them since 2026-11-26)")
        elif loss["lost_at_end"] > SHEAR_LOSS_WARNING:
            out.append(at + f"{100 * loss['lost_at_end']:.1f} % of its {loss['particles']} "
                       "particles had left the box by the end (over the upper frame's overhang, "
                       f"after the peak at j {s['peak'].j_peak_m:.3g} m): the residual strength "
                       "is that of a thinning sample")
    return out


def read_repose(run, done, dmax):
    """(fits, profiles, error) of a repose run: profiles along x and y through the heap's top."""
    # LIGGGHTS' write_dump custom: 9 header lines, then "id x y z radius" per particle
    t = _table(Path(run) / "repose.dump", ("id", "x", "y", "z", "radius"), skip_lines=9)
    x, y, z, rad = t["x"], t["y"], t["z"], t["radius"]
    B = _meta(run, done, "base_m", "the base's side, a number > 0 [m]")
    found, profiles = [], []
    # bands |y| < B/4 and |x - B/2| < B/4, bins of d_max / 2 over the base
    for u, v in ((x - 0.5 * B, y), (y, x - 0.5 * B)):
        band = np.abs(v) < 0.25 * B
        edges = np.arange(-0.5 * B, 0.5 * B + 1e-12, 0.5 * dmax)
        px, ph = repose.surface_profile(u[band], z[band], rad[band], edges)
        try:  # the heap's axis: the profile's highest point
            found.append(repose.repose_angle(px, ph, axis_m=float(px[np.argmax(ph)])))
        except FitInputError as e:
            return [], [], (f"no angle of repose: {e} ({len(x)} particles left on a "
                            f"{B:.3g} m base)")
        profiles.append((px, ph))
    return found, profiles, None


def analyse(directory):
    """Fits every test found in the lab directory `directory`."""
    d = Path(directory)
    soil_file = d / "soil.toml"
    if not soil_file.is_file():
        raise LabResultError(f"{d} is not a soil-lab directory (no soil.toml): run `soil-lab run`")
    r = Results(soil=read_soil(soil_file), directory=d)
    dmax = float(r.soil["dmax_m"])

    bed = _done(d / "beds" / "plate")
    if bed is not None:
        where = d / "beds" / "plate" / "done.json"
        res = bed.get("result")
        if not isinstance(res, dict):
            raise LabResultError(f"{where}: result = {res!r}: expected the table of "
                                 "in.soilbin's printed results")
        # the summary's bulk density, porosity and bed depth; the core cell's when measured
        r.bulk = {k: _number(where, res, k, "a number", text=True, prefix="result.",
                             required=not k.startswith("core_"))
                  for k in ("bulk_density", "porosity", "core_bulk_density", "core_porosity",
                            "bed_depth")}
        r.bulk = {k: v for k, v in r.bulk.items() if v is not None}
        r.bulk["particles"] = int(_number(where, res, "spheres", "a count >= 0",
                                          lambda v: v >= 0 and v == int(v), text=True,
                                          required=False, prefix="result.") or 0)
        r.bulk["compaction"] = str(res.get("compaction", "none"))

    for run, done in _runs(d, "plate_b*"):
        r.plates.append(read_plate(run, done))
    r.plates.sort(key=lambda p: (p["replicate"], p["b_m"]))
    # the first bed's plates: the elastic stiffness and the holds (with --plate-replicates the
    # other beds' plates enter the Bekker fit and the scatter, not these)
    first = [p for p in r.plates if p["replicate"] == 1]
    if len({p["b_m"] for p in r.plates}) >= 2:
        # every plate of every bed is a set of points of one fit (as every box is of Mohr-Coulomb)
        loading = [(p["b_m"], *loading_branch(p)) for p in r.plates]
        r.bekker = fits.fit_bekker(loading)
        r.plate_replicates = plate_replicates(r.plates, d)
        for p in first:
            # The unloading branch starts at the turning point (the last sample before the unload:
            # of the loading, or of the hold at its end): a noisy pressure maximum earlier in the
            # loading must not be taken for the start of unloading.
            i_unload = np.flatnonzero(p["phase"] == PLATE_UNLOAD)
            i_turn = (i_unload[0] - 1 if i_unload.size
                      else np.flatnonzero(p["phase"] == PLATE_LOAD)[-1])
            branch = slice(i_turn, None)
            cycle = (p["phase"][branch] <= PLATE_UNLOAD) | (p["phase"][branch] == PLATE_HOLD)
            try:
                r.unload[p["b_m"]] = fits.fit_unload_stiffness(p["z"][branch][cycle],
                                                               p["p"][branch][cycle])
            except FitInputError as e:
                r.unload_errors[p["b_m"]] = str(e)
            holds = plate_holds(p)
            if holds:
                r.holds[p["b_m"]] = holds
        # The relaxed curve: the pressures at the ends of the holds, when each plate held at 2
        # depths or more (docs/soil-lab.md, "Held plates").
        if first and len(r.holds) == len(first) and all(len(h) >= 2 for h in r.holds.values()):
            r.bekker_relaxed = fits.fit_bekker(
                [(b, [h["z_m"] for h in hs], [h["p_end_Pa"] for h in hs])
                 for b, hs in r.holds.items()])

    r.shears, r.shear_bed_bulk_density = read_shears(d)
    if shear_stress_count(r.shears) >= 3:
        # every finished box is a point: replicates of a stress are points of their own
        sig = [s["sigma_Pa"] for s in r.shears]
        r.mc_peak = fits.fit_mohr_coulomb(sig, [s["peak"].tau_peak_Pa for s in r.shears])
        r.mc_residual = fits.fit_mohr_coulomb(sig, [s["peak"].tau_residual_Pa for s in r.shears])
    r.replicates = shear_replicates(r.shears)

    for run, done in _runs(d, "repose"):
        r.repose_fits, r.repose_profiles, r.repose_error = read_repose(run, done, dmax)

    # The checks: each run at half the speed (the quasi-static check) or at half the time step
    # (--dt-check) against the run it repeats, on the same bed with the same tools.
    for suffix, checks in (("_half", r.quasi_static), ("_halfdt", r.time_step)):
        for run in sorted(d.glob("*" + suffix)):
            full_dir = d / run.name[: -len(suffix)]
            half, full = _done(run), _done(full_dir)
            compared = (None if half is None or full is None
                        else _compare_runs(r, full_dir, full, run, half, dmax))
            if compared is None:
                continue
            test, what, unit, a, b, diff, extra = compared
            tol = QUASI_STATIC_TOLERANCE[test]
            entry = {"run": full_dir.name, "quantity": what, "unit": unit,
                     "difference": float(diff), "tolerance": tol, "relative": test != "repose",
                     "passed": bool(abs(diff) <= tol)}
            if suffix == "_half":
                entry.update(full_speed=float(a), half_speed=float(b), **extra)
            else:  # the steps from the records; the curves compared and the box's bed, not
                # the half-speed box's lid and replicate extras
                entry.update(full_dt_s=float(full.get("dt_s", float("nan"))),
                             half_dt_s=float(half.get("dt_s", float("nan"))),
                             full_step=float(a), half_step=float(b),
                             **{k: v for k, v in extra.items() if k.startswith("profile_")
                                or k in ("sigma_target_Pa", "b_m", "replicate")})
            checks.append(entry)
    # with --plate-replicates, --shear-replicates: each bed's difference for a plate width or at
    # a stress, paired on its bed
    for checks, paired, verdicts in ((r.quasi_static, r.paired_speed_checks, SPEED_VERDICTS),
                                     (r.time_step, r.paired_step_checks, STEP_VERDICTS)):
        groups = {}
        for q in checks:
            if "replicate" in q:   # a plate's or a shear box's comparison (not the heap's)
                key = ("b_m", q["b_m"]) if "b_m" in q else ("sigma_target_Pa",
                                                            q["sigma_target_Pa"])
                groups.setdefault(key, []).append(q)
        for (what, value), pairs in sorted(groups.items()):
            if len(pairs) >= 2:
                pairs.sort(key=lambda q: q["replicate"])
                test = "plate" if what == "b_m" else "shear"
                paired.append({
                    "test": test, what: float(value), "runs": [q["run"] for q in pairs],
                    "replicates": [q["replicate"] for q in pairs],
                    **paired_check([q["difference"] for q in pairs],
                                   QUASI_STATIC_TOLERANCE[test], verdicts)})

    for run, done in [(q, _done(q)) for q in sorted(d.iterdir()) if q.is_dir()]:
        if done is not None and "steps" in done:
            for k in COST_KEYS:  # written as they are (steps, particles, np: integers)
                _number(run / "done.json", done, k, "a number >= 0", lambda v: v >= 0)
            r.costs.append({"run": run.name, **{k: done[k] for k in COST_KEYS}})
    beds = d / "beds"
    for bed, done in [(q, _done(q)) for q in sorted(beds.iterdir())] if beds.is_dir() else []:
        if done is not None and "wall_s" in done:
            r.bed_costs[bed.name] = _number(bed / "done.json", done, "wall_s",
                                            "a wall time >= 0 [s]", lambda v: v >= 0)
        hold = _done(bed / "hold")  # the bed-hold check (runner.Lab.bed_hold) of this bed only
        if (hold is not None and "result" in hold and done is not None
                and hold.get("bed_inputs") == done.get("inputs")):
            where = bed / "hold" / "done.json"
            r.bed_holds[bed.name] = _hold_result(where, hold)
            r.bed_costs[f"{bed.name}/hold"] = _number(where, hold, "wall_s",
                                                      "a wall time >= 0 [s]", lambda v: v >= 0,
                                                      required=False) or 0.0
    return r


def _compare_runs(r, full_dir, full, run, half, dmax):
    """A run (its folder `run`, record `half`) against the run it repeats with one thing changed
    (`full_dir`, `full`): half the speed (the quasi-static check) or half the time step (the
    time-step check), on the same bed with the same tools. Returns (test, quantity, unit, value
    of the full run, of the other, difference, extra), the difference relative (plate: pressure
    at the end of loading, shear: peak shear stress) or in degrees (repose), or None when a
    repose heap could not be fitted; `extra` compares the whole curve (by depth, by
    displacement) and, for a box, its lid and its replicates."""
    test = run.name.split("_")[0]
    extra = {}
    if test == "plate":
        # the full-speed run is one of the lab's plates, read above (that of its own bed)
        plate = next((p for p in r.plates if p["run"] == full_dir.name), None) or \
            read_plate(full_dir, full)
        za, ma = plate_pressure_profile(plate)
        zb, mb = plate_pressure_profile(read_plate(run, half))
        a, b = ma[-1], mb[-1]  # plate_end_pressure of each
        what, unit, diff = "pressure at the end of loading", "Pa", (b - a) / a
        # by depth: the half-speed band mean at the full-speed run's band depths
        extra = {"profile_depth_m": [float(x) for x in za],
                 "profile_difference": [float(x) for x in np.interp(za, zb, mb) / ma - 1.0],
                 "b_m": plate["b_m"], "replicate": plate["replicate"]}
    elif test == "shear":
        # the full-speed run is one of the lab's boxes, read above
        sa = next((s for s in r.shears if s["done"] == full), None) or \
            read_shear(full_dir, full)
        sb = read_shear(run, half)
        a, b = sa["peak"].tau_peak_Pa, sb["peak"].tau_peak_Pa
        what, unit, diff = "peak shear stress", "Pa", (b - a) / a
        # by displacement: both runs' band means over the full-speed run's travel
        ja, ma = shear_stress_profile(sa["j"], sa["tau"])
        _, mb = shear_stress_profile(sb["j"], sb["tau"], j_max_m=float(np.max(sa["j"])))
        bands = mb / ma - 1.0
        extra = {"sigma_target_Pa": sa["sigma_target_Pa"], "replicate": sa["replicate"],
                 "profile_displacement_m": [float(x) for x in ja],
                 "profile_difference": [float(x) for x in bands],
                 "profile_changes_sign": profile_changes_sign(bands),
                 # how far each lid moved over the shear (< 0: the sample compacted): a
                 # creeping soil compacts more in the slower run's longer time
                 "lid_full_m": sa["consolidation"]["lid_travel_m"],
                 "lid_half_m": sb["consolidation"]["lid_travel_m"]}
        # with replicates: how far the same-speed boxes of this stress lie from the first
        # bed's, the scatter the half-speed difference is to be read against
        same = [s["peak"].tau_peak_Pa for s in r.shears
                if s["sigma_target_Pa"] == sa["sigma_target_Pa"] and s is not sa]
        if same:
            extra["replicate_differences"] = [float((t - a) / a) for t in same]
            # the half-speed peak against all same-speed boxes of the stress (the first
            # bed's among them, shear_replicates' row of it): how many of their standard
            # deviations it lies from their mean
            row = next(x for x in r.replicates["by_stress"]
                       if x["sigma_target_Pa"] == sa["sigma_target_Pa"])
            mean, sd = row["tau_peak_mean_Pa"], row["tau_peak_sd_Pa"]
            extra.update(replicate_peak_mean_Pa=mean, replicate_peak_sd_Pa=sd,
                         half_speed_from_mean=float((b - mean) / mean),
                         half_speed_sds_from_mean=float((b - mean) / sd) if sd > 0
                         else float("inf"))
    else:
        fa, _, ea = read_repose(full_dir, full, dmax)
        fb, _, eb = read_repose(run, half, dmax)
        if ea or eb:
            return None
        a, b = np.mean([f.angle_deg for f in fa]), np.mean([f.angle_deg for f in fb])
        what, unit, diff = "angle of repose", "deg", b - a
    return test, what, unit, a, b, diff, extra


def hold_summary(h):
    """A hold stage (plate_holds) as results.toml writes it."""
    f = h["fit"]
    return {"z_m": h["z_m"], "hold_s": h["hold_s"], "p_moving_Pa": h["p_moving_Pa"],
            "p_end_Pa": h["p_end_Pa"], "relaxation": h["relaxation"], "p_stop_Pa": h["p_stop_Pa"],
            "step_at_stop": h["step_at_stop"], "late_drop": h["late_drop"],
            "converged": h["converged"],
            **({} if f is None else {"tau_s": f.tau_s, "p_inf_Pa": f.p_inf_Pa, "fit_r2": f.r2,
                                     "p0_Pa": f.p0_Pa})}


def summary(r: Results):
    """results.toml's content: every measured value with its unit in the key."""
    out = {"soil": {k: r.soil[k] for k in ("name", "file", "preset", "invocations")
                    if k in r.soil}}
    if r.bulk:
        out["bulk"] = {"bulk_density_kg_m3": r.bulk["bulk_density"],
                       "porosity": r.bulk["porosity"],
                       "core_bulk_density_kg_m3": r.bulk.get("core_bulk_density", -1),
                       "core_porosity": r.bulk.get("core_porosity", -1),
                       "bed_depth_m": r.bulk["bed_depth"], "particles": r.bulk["particles"],
                       "compaction": r.bulk["compaction"]}
    if r.bekker:
        b = r.bekker
        out["plate"] = {"n": b.n, "kc_N_m_n1": b.kc, "kphi_N_m_n2": b.kphi, "rms_Pa": b.rms_Pa,
                        "r2": b.r2, "points": b.n_points, "plate_widths_m": list(b.widths_m),
                        "at_bound": list(b.at_bound),
                        "elastic_K_Pa_m": {f"b{w:.4g}": u.Ke_Pa_m for w, u in r.unload.items()}}
        if r.plate_replicates:
            out["plate"]["replicates"] = r.plate_replicates
        if r.unload_errors:
            out["plate"]["elastic_K_errors"] = {f"b{w:.4g}": e for w, e in r.unload_errors.items()}
        if r.holds:
            out["plate"]["holds"] = {f"b{w:.4g}": [hold_summary(h) for h in hs]
                                     for w, hs in r.holds.items()}
        if r.bekker_relaxed:
            b = r.bekker_relaxed
            out["plate"]["relaxed"] = {
                "n": b.n, "kc_N_m_n1": b.kc, "kphi_N_m_n2": b.kphi, "rms_Pa": b.rms_Pa, "r2": b.r2,
                "points": b.n_points, "at_bound": list(b.at_bound),
                "converged": not unrelaxed_holds(r),
                "source": "the pressures at the ends of the holds"}
    if r.shears:
        out["shear"] = {"stresses": [
            {"sigma_n_Pa": s["sigma_Pa"], "sigma_target_Pa": s["sigma_target_Pa"],
             "tau_peak_Pa": s["peak"].tau_peak_Pa, "j_peak_m": s["peak"].j_peak_m,
             "tau_residual_Pa": s["peak"].tau_residual_Pa,
             "janosi_K_m": s["janosi"].K_m, "janosi_tau_max_Pa": s["janosi"].tau_max_Pa,
             "janosi_rms_Pa": s["janosi"].rms_Pa,
             "rise_at_end": shear_rise_at_end(s["j"], s["tau"]),
             **({} if s["replicate"] == 1 else {"replicate": s["replicate"]}),
             "stable": not shear_stability_errors([s]),
             **({} if s.get("consolidation") is None else {
                 "consolidation_s": s["consolidation"]["consolidation_s"],
                 "sigma_start_ratio": s["consolidation"]["sigma_start_ratio"],
                 "sample_height_m": s["consolidation"]["lid_z_start_m"],
                 "lid_travel_m": s["consolidation"]["lid_travel_m"],
                 **{k: s["consolidation"][k] for k in ("sample_bulk_density_kg_m3",
                                                       "sample_bulk_density_end_kg_m3")
                    if k in s["consolidation"]}}),
             **({} if s.get("loss") is None else {
                 "particles": s["loss"]["particles"],
                 "particles_lost_by_peak": s["loss"]["lost_by_peak"],
                 "particles_lost_at_end": s["loss"]["lost_at_end"]})} for s in r.shears]}
        warnings = (shear_count_warnings(r.shears) + shear_stability_errors(r.shears)
                    + shear_consolidation_warnings(r.shears) + shear_peak_warnings(r.shears)
                    + shear_loss_warnings(r.shears))
        if warnings:
            out["shear"]["warnings"] = warnings
        if r.shear_bed_bulk_density is not None:
            out["shear"]["bed_bulk_density_kg_m3"] = r.shear_bed_bulk_density
        if r.mc_peak:
            out["shear"].update({
                "cohesion_Pa": r.mc_peak.cohesion_Pa, "friction_deg": r.mc_peak.friction_deg,
                "mc_rms_Pa": r.mc_peak.rms_Pa, "mc_r2": r.mc_peak.r2,
                "cohesion_se_Pa": r.mc_peak.cohesion_se_Pa,
                "friction_se_deg": r.mc_peak.friction_se_deg,
                "residual_cohesion_Pa": r.mc_residual.cohesion_Pa,
                "residual_friction_deg": r.mc_residual.friction_deg,
                "janosi_K_m": r.janosi_K_m})
        if r.replicates:
            out["shear"]["replicates"] = r.replicates
    if r.repose_error:
        out["repose"] = {"error": r.repose_error}
    if r.repose_fits:
        out["repose"] = {"angle_deg": r.repose_angle_deg,
                         "flank_angles_deg": [f.angle_deg for rf in r.repose_fits
                                              for f in (rf.left, rf.right)],
                         "method": "lifted frame on a fixed rough base; profiles along x and y "
                                   "through the axis, flanks fitted between 20 % and 80 % of the "
                                   "heap height"}
    if r.quasi_static:
        out["quasi_static"] = {q["run"]: {k: q[k] for k in ("quantity", "unit", "full_speed",
                                                              "half_speed", "difference",
                                                              "tolerance", "relative", "passed",
                                                              "profile_depth_m",
                                                              "profile_displacement_m",
                                                              "profile_difference",
                                                              "profile_changes_sign",
                                                              "lid_full_m", "lid_half_m",
                                                              "replicate_differences",
                                                              "replicate_peak_mean_Pa",
                                                              "replicate_peak_sd_Pa",
                                                              "half_speed_from_mean",
                                                              "half_speed_sds_from_mean")
                                              if k in q}
                               for q in r.quasi_static}
    if r.time_step:
        out["time_step"] = {q["run"]: {k: v for k, v in q.items() if k != "run"}
                            for q in r.time_step}
    for name, paired in (("quasi_static_paired", r.paired_speed_checks),
                         ("time_step_paired", r.paired_step_checks)):
        if paired:
            out[name] = {_paired_key(c): {k: v for k, v in c.items()
                                          if k not in ("sigma_target_Pa", "test")}
                         for c in paired}
    if r.bed_holds:
        out["bed_hold"] = r.bed_holds
    if r.costs:
        out["cost"] = {c["run"]: {k: c[k] for k in COST_KEYS} for c in r.costs}
    if r.costs or r.bed_costs:
        runs_s, beds_s = sum(c["wall_s"] for c in r.costs), sum(r.bed_costs.values())
        out["cost_total"] = {"beds_wall_s": beds_s, "runs_wall_s": runs_s,
                             "lab_wall_s": beds_s + runs_s,
                             "beds": {k: v for k, v in r.bed_costs.items()}}
    return out


def _paired_key(c):
    """results.toml's key of a paired check: shear_s<target stress [Pa]> or plate_b<width [m]>
    (the first bed's box or plate at the soil's speed and step is named so)."""
    if c["test"] == "plate":
        return f"plate_b{plan._f(c['b_m'])}"
    return f"shear_s{c['sigma_target_Pa']:g}"


def write_report(r: Results, quiet=False):
    """results.toml, results.csv and the PNG plots into the lab directory; returns their paths."""
    import tomli_w

    d = r.directory
    s = summary(r)
    written = []
    (d / "results.toml").write_text(tomli_w.dumps(s))
    written.append(d / "results.toml")
    with open(d / "results.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["test", "quantity", "value"])
        for test, table in s.items():
            if test in ("soil", "cost"):
                continue
            for k, v in table.items():
                if isinstance(v, (int, float)) and not isinstance(v, bool):
                    w.writerow([test, k, f"{v:.6g}"])
        rep = r.replicates or {}
        if rep:  # the replicate boxes' scatter (results.toml [shear.replicates]), flattened
            for k in ("friction_sd_deg", "cohesion_sd_Pa"):
                if k in rep:
                    w.writerow(["shear", f"replicates_{k}", f"{rep[k]:.6g}"])
            for k, phi, c in zip(rep["fitted_replicates"], rep["friction_deg"],
                                 rep["cohesion_Pa"]):
                w.writerow(["shear", f"bed{k}_friction_deg", f"{phi:.6g}"])
                w.writerow(["shear", f"bed{k}_cohesion_Pa", f"{c:.6g}"])
            for b in rep["by_stress"]:
                at = f"s{b['sigma_target_Pa']:g}"
                for k in ("tau_peak_mean_Pa", "tau_peak_sd_Pa", "tau_peak_spread"):
                    w.writerow(["shear", f"replicates_{at}_{k}", f"{b[k]:.6g}"])
        prep = r.plate_replicates or {}
        if prep:  # the replicate plates' scatter (results.toml [plate.replicates]), flattened
            for k in ("n_sd", "kc_N_m_n1_sd", "kphi_N_m_n2_sd"):
                if k in prep:
                    w.writerow(["plate", f"replicates_{k}", f"{prep[k]:.6g}"])
            for i, k in enumerate(prep["fitted_replicates"]):
                for key in ("n", "kc_N_m_n1", "kphi_N_m_n2"):
                    w.writerow(["plate", f"bed{k}_{key}", f"{prep[key][i]:.6g}"])
            for b in prep["by_width"]:
                for k in ("p_end_mean_Pa", "p_end_sd_Pa", "p_end_spread"):
                    w.writerow(["plate", f"replicates_b{plan._f(b['b_m'])}_{k}", f"{b[k]:.6g}"])
        for test, paired in (("quasi_static_paired", r.paired_speed_checks),
                             ("time_step_paired", r.paired_step_checks)):
            for c in paired:  # results.toml [<test>.<key>], flattened
                for k in ("mean_difference", "sem_difference", "interval_low", "interval_high"):
                    w.writerow([test, f"{_paired_key(c)}_{k}", f"{c[k]:.6g}"])
    written.append(d / "results.csv")
    name = r.soil.get("name", "?")
    if r.plates:
        report.plot_pressure_sinkage(d / "plate.png", name,
                                     [(p["b_m"], p["z"], p["p"], p["replicate"])
                                      for p in r.plates], r.bekker)
        written.append(d / "plate.png")
    if r.holds:
        report.plot_holds(d / "plate_holds.png", name, r.holds)
        written.append(d / "plate_holds.png")
    if r.shears:
        report.plot_shear_curves(d / "shear_curves.png", name,
                                 [(s["sigma_Pa"], s["j"], s["tau"]) for s in r.shears],
                                 [s["janosi"] for s in r.shears],
                                 [s["lid_dz"] for s in r.shears],
                                 [f"σn = {_box_name(s)}" for s in r.shears])
        written.append(d / "shear_curves.png")
    if r.mc_peak:
        sig = [s["sigma_Pa"] for s in r.shears]
        report.plot_mohr_coulomb(d / "mohr_coulomb.png", name, sig,
                                 [s["peak"].tau_peak_Pa for s in r.shears], r.mc_peak, sig,
                                 [s["peak"].tau_residual_Pa for s in r.shears], r.mc_residual)
        written.append(d / "mohr_coulomb.png")
    if r.repose_fits:
        px, ph = r.repose_profiles[0]
        report.plot_repose(d / "repose.png", name, px, ph, r.repose_fits[0])
        written.append(d / "repose.png")
    return written


@dataclass(frozen=True)
class ShearStrength:
    """What an SCM file takes from the shear boxes: each box's normal stress, peak shear stress and
    Janosi K, and where they were measured (for the file's [source] strings)."""

    sigmas_Pa: tuple
    tau_peaks_Pa: tuple
    K_m: tuple
    where: str = ""  #: "" for the lab directory itself, else the other lab it was taken from
    declared_soil: str = ""  #: the --shear-soil name the boxes were run under ("": this soil's)


def shear_strength(r: Results):
    """The shear boxes of the lab `r` as a ShearStrength (None without 3 boxes); unstable boxes
    are an error."""
    return None if r.mc_peak is None else _shear_strength_of(r.shears, r.directory)


def _shear_strength_of(shears, where):
    """The boxes `shears` (read_shears' records) as a ShearStrength; unstable boxes are an error
    naming `where`."""
    unstable = shear_stability_errors(shears)
    if unstable:
        raise LabResultError(f"{where}: no SCM file from unstable shear boxes: "
                             + "; ".join(unstable))
    return ShearStrength(tuple(s["sigma_Pa"] for s in shears),
                         tuple(s["peak"].tau_peak_Pa for s in shears),
                         tuple(s["janosi"].K_m for s in shears if s["janosi"] is not None))


def shear_strength_from(path, soil_name, declared_soil=None):
    """The shear boxes of another lab of the soil `soil_name`: a lab directory (its shear runs, or
    the results.toml `soil-lab report` wrote in it, e.g. a committed soil_lab/results/<soil>/), a
    results.toml file, or a folder of archived boxes (shear_s*/ with shear.csv and done.json, as
    `--archive` keeps them: they record no soil name). For plates pressed in a lab of their own
    (`--plate-depth`) whose shear boxes were measured in the standard lab (docs/soil-lab.md, "SCM
    soil file from DEM").

    `declared_soil` (--shear-soil NAME): the boxes were run under the soil name NAME, a recipe the
    caller vouches is this soil's (a calibration trial later shipped under the soil's own name):
    accepted where the source names NAME (or, an archive folder, no name), recorded in the
    result (ShearStrength.declared_soil) and so in the SCM file's [source]."""
    p = Path(path)
    if p.is_dir() and any(_runs(p, "shear_s*")) and not (p / "soil.toml").is_file():
        if not declared_soil:
            raise LabResultError(f"--shear-from {p}: a folder of archived shear boxes records no "
                                 f"soil name: give --shear-soil NAME, the soil they were run as "
                                 f"(if that is this lab's soil, '{soil_name}', say so)")
        shears, _ = read_shears(p)
        if shear_stress_count(shears) < 3:
            raise LabResultError(f"--shear-from {p}: fewer than 3 finished shear boxes")
        shear, name = _shear_strength_of(shears, f"--shear-from {p}"), declared_soil
    elif p.is_dir() and any(_runs(p, "shear_s*")):
        other = analyse(p)
        shear, name = shear_strength(other), other.soil.get("name")
        if shear is None:
            raise LabResultError(f"--shear-from {p}: fewer than 3 finished shear boxes")
    else:
        f = p / "results.toml" if p.is_dir() else p
        if not f.is_file():
            raise LabResultError(f"--shear-from {p}: neither shear box runs nor a results.toml "
                                 "(written by `soil-lab report`)")
        data = _read_toml(f)
        shear_table = data.get("shear", {})
        boxes = shear_table.get("stresses", []) if isinstance(shear_table, dict) else None
        if not isinstance(boxes, list) or not all(isinstance(b, dict) for b in boxes):
            raise LabResultError(f"--shear-from {f}: shear.stresses = {boxes!r}: expected an "
                                 "array of tables ([[shear.stresses]])")
        if len(boxes) < 3:
            raise LabResultError(f"--shear-from {f}: {len(boxes)} shear box(es) in [shear], "
                                 "need 3 normal stresses")
        soil_table = data.get("soil", {})
        name = soil_table.get("name") if isinstance(soil_table, dict) else None

        def column(key, expected, required=True):
            return tuple(_number(f"--shear-from {f}", b, key, expected, required=required,
                                 prefix=f"shear.stresses[{i}].") for i, b in enumerate(boxes))
        shear = ShearStrength(column("sigma_n_Pa", "a normal stress [Pa]"),
                              column("tau_peak_Pa", "a shear stress [Pa]"),
                              column("janosi_K_m", "Janosi's K [m]"))
        tau_max = column("janosi_tau_max_Pa", "a shear stress [Pa]", required=False)
        # The curves are not in the summary: its per-box verdict ("stable", written since
        # 2026-11-29), else the one check a summary allows (Janosi tau_max > 0).
        unstable = [f"{sigma / 1e3:.3g} kPa" for b, sigma, t in zip(boxes, shear.sigmas_Pa, tau_max)
                    if b.get("stable") is False or (t is not None and t <= 0)]
        if unstable:
            raise LabResultError(f"--shear-from {f}: unstable shear box(es) at "
                                 f"{', '.join(unstable)} (see its [shear] warnings): no SCM file "
                                 "from them")
    if declared_soil:
        if name != declared_soil:
            raise LabResultError(f"--shear-from {p}: its soil is {name!r}, not the --shear-soil "
                                 f"{declared_soil!r}")
        return replace(shear, where=str(p),
                       declared_soil="" if declared_soil == soil_name else declared_soil)
    if name != soil_name:
        raise LabResultError(f"--shear-from {p}: its soil is {name!r}, this lab's is "
                             f"{soil_name!r}: both must be the same DEM soil (boxes of the same "
                             f"recipe run under another name: --shear-soil {name})")
    return replace(shear, where=str(p))


def plate_speed_statement(r: Results, rate_dependent_ok=False):
    """What the lab's quasi-static check of its plates says, for the SCM file's Bekker [source]:
    each half-speed plate's change of the pressure at the end of loading against its tolerance,
    or that no check was run. A failed check is a LabResultError unless `rate_dependent_ok`
    (soil-lab scm --rate-dependent): a Bekker fit at a speed the pressure still depends on."""
    checks = [q for q in r.quasi_static if q["run"].startswith("plate")]
    if not checks:
        return ("plate speed not checked (no --speed-check half-speed plate in the lab)"
                + plate_step_statement(r))
    parts, failed = [], []
    # with --plate-replicates the verdict is the check paired over the beds (a single pair's
    # difference holds the plate's own fluctuation too)
    paired = [c for c in r.paired_speed_checks if c["test"] == "plate"]
    for q in checks:
        verdict = ("" if paired else
                   ": quasi-static" if q["passed"] else ": NOT quasi-static")
        parts.append(f"{q['run']} at half speed: {100 * q['difference']:+.1f} % at the end of "
                     f"loading (tolerance {100 * q['tolerance']:g} %){verdict}")
        if not q["passed"] and not paired:
            failed.append(parts[-1])
    for c in paired:
        parts.append(_paired_statement(c, "rate effect", "NOT quasi-static"))
        if c["verdict"] == "rate effect":
            failed.append(parts[-1])
    if failed and not rate_dependent_ok:
        raise LabResultError(f"{r.directory}: the plates' speed check failed ({'; '.join(failed)}):"
                             f" a Bekker fit at this speed depends on the speed; write it anyway, "
                             f"said in its [source], with --rate-dependent")
    return "speed check: " + "; ".join(parts) + plate_step_statement(r)


def plate_step_statement(r: Results):
    """The plates' time-step check (--dt-check) for the SCM file's Bekker [source], stated, not a
    reason to refuse (the soil is calibrated at its step); without one, that it was not checked
    and the step the plates ran at (the fit holds at it: on cdt soils the plate pressure moves
    with the step, docs/soil-lab.md "The time-step check")."""
    checks = [q for q in r.time_step if q["run"].startswith("plate")]
    if not checks:
        steps = sorted({v for p in r.plates
                        if isinstance(v := (p.get("done") or {}).get("dt_s"), (int, float))})
        at = f", fitted at dt {', '.join(f'{v:.4g}' for v in steps)} s" if steps else ""
        return f"; time step not checked (no --dt-check half-step plate in the lab{at})"
    paired = [c for c in r.paired_step_checks if c["test"] == "plate"]
    return "".join(f"; time-step check: {q['run']} at half the step ({q['half_dt_s']:.4g} s): "
                   f"{100 * q['difference']:+.1f} % at the end of loading (tolerance "
                   f"{100 * q['tolerance']:g} %)"
                   + ("" if q["passed"] or paired else ": step-dependent")
                   for q in checks) + "".join(
        "; time-step check " + _paired_statement(c, "step effect", "step-dependent")
        for c in paired)


def _paired_statement(c, effect, effect_words):
    """A plate check paired over beds (paired_check's result `c`) in the SCM file's [source]:
    its mean, 95 % interval and verdict (`effect`, the verdict read as `effect_words`)."""
    verdict = effect_words if c["verdict"] == effect else c["verdict"]
    return (f"over {c['beds']} beds (plate b {c['b_m']:.4g} m, each paired on its bed): mean "
            f"{100 * c['mean_difference']:+.1f} %, 95 % interval {100 * c['interval_low']:+.1f} "
            f"to {100 * c['interval_high']:+.1f} % (tolerance {100 * c['tolerance']:g} %): "
            f"{verdict}")


def write_scm(r: Results, path, name=None, shear: Optional[ShearStrength] = None,
              relaxed=False, rate_dependent_ok=False):
    """An SCM soil file fitted to the DEM soil: its plates (their loading branches, or with
    `relaxed` the pressures at the ends of their holds), and its shear boxes or `shear`
    (shear_strength_from another lab of the same soil). The Bekker [source] states the plates'
    speed and its quasi-static check (plate_speed_statement: a failed check is refused unless
    `rate_dependent_ok`, or `relaxed`, whose fit is not of the moving plates)."""
    if r.bekker is None:
        raise LabResultError(f"{r.directory}: no plate sinkage results (2 plates): run the "
                             f"'plate' test first")
    speeds = sorted({v for p in r.plates
                     if isinstance(v := ((p.get("done") or {}).get("meta") or {}).get("speed_m_s"),
                                   (int, float)) and v > 0})
    # a relaxed fit takes the pressures at the ends of the holds, not the moving plates': their
    # speed check is stated, not a reason to refuse
    speed_text = (f"pressed at {', '.join(f'{v:g}' for v in speeds)} m/s; " if speeds else "") + \
        plate_speed_statement(r, rate_dependent_ok or relaxed)
    widths = ", ".join(f"{b:.3g}" for b in sorted({p["b_m"] for p in r.plates}))
    rep = r.plate_replicates or {}
    if rep and not relaxed:   # --plate-replicates: every bed's plates in one fit, and how far
        # the beds' own fits differ (the holds, and so a relaxed fit, are the first bed's)
        widths += f" m on {len(rep['replicates'])} beds of the recipe" + (
            "" if "kphi_N_m_n2_sd" not in rep else
            f" (each bed's own fit: n sd {rep['n_sd']:.3g}, kphi sd "
            f"{100 * rep['kphi_N_m_n2_sd'] / np.mean(rep['kphi_N_m_n2']):.3g} %)")
    else:
        widths += " m"
    if relaxed:
        bekker = r.bekker_relaxed
        if bekker is None:
            raise LabResultError(f"{r.directory}: no relaxed pressure-sinkage curve: its plates "
                                 f"need holds at 2 depths or more (soil-lab run --plate-hold S "
                                 f"--plate-hold-stages N)")
        stages = [h for hs in r.holds.values() for h in hs]
        open_ = [f"b = {b:.3g} m at z = {1e3 * h['z_m']:.3g} mm" for b, h in unrelaxed_holds(r)]
        if open_:
            raise LabResultError(f"{r.directory}: the plates were still relaxing at the end of "
                                 f"their holds ({'; '.join(open_)}): their end pressures are not "
                                 f"the relaxed ones; hold longer (--plate-hold)")
        z_fitted = max(h["z_m"] for h in stages)
        how = (f"square plates b = {widths}, the pressures at the ends of holds of "
               f"{min(h['hold_s'] for h in stages):.3g} s at {len(stages)} depths to "
               f"z = {z_fitted:.3g} m (stress relaxation; deeper sinkage extrapolates)")
    else:
        bekker = r.bekker
        # the deepest loading sample: SCM below it extrapolates the fit (docs/soil-lab.md)
        z_fitted = max(float(np.max(loading_branch(p)[0])) for p in r.plates)
        how = (f"square plates b = {widths}, loading branches to z = {z_fitted:.3g} m (deeper "
               f"sinkage extrapolates)")
    if shear is not None and r.mc_peak is not None:
        raise LabResultError(f"{r.directory} has shear boxes of its own; leave out --shear-from "
                             f"{shear.where} (or use a lab directory without them)")
    shear = shear or shear_strength(r)
    if shear is None:
        raise LabResultError(f"{r.directory}: no shear box results (3 normal stresses): run the "
                             f"'shear' test first, or take them from another lab of the same "
                             f"soil (--shear-from)")
    dem = r.soil["name"]
    if not r.unload:
        raise LabResultError(f"{r.directory}: no plate's unloading branch could be fitted for the "
                             "elastic stiffness: " + "; ".join(
                                 f"b = {w:.3g} m: {e}" for w, e in sorted(r.unload_errors.items())))
    b_large = max(r.unload)  # the largest plate whose unloading branch was fitted
    ke = r.unload[b_large]
    sigmas = ", ".join(f"{s / 1e3:.3g}" for s in shear.sigmas_Pa)
    k_values = ", ".join(f"{k:.3g}" for k in shear.K_m)
    lab = f" (the lab {shear.where})" if shear.where else ""
    if shear.declared_soil:
        lab = (f" (the lab {shear.where}: its soil '{shear.declared_soil}', the same recipe "
               f"under another name as declared with --shear-soil)")
    mc = fits.fit_mohr_coulomb(shear.sigmas_Pa, shear.tau_peaks_Pa)
    sources = {
        "bekker": scm_file.dem_source(dem, "plate sinkage", bekker, f"{how}; {speed_text}"),
        "mohr_coulomb": scm_file.dem_source(dem, "direct shear box, peak strength", mc,
                                            f"normal stresses {sigmas} kPa{lab}"),
        "janosi.shear_modulus": scm_file.dem_source(
            dem, "direct shear box", None, f"mean of the Janosi fits at {sigmas} kPa "
            f"(K = {k_values} m){lab}"),
        "scm.elastic_stiffness": scm_file.dem_source(
            dem, "plate sinkage, unloading slope", ke, f"plate b = {b_large:.3g} m"),
    }
    if mc.cohesion_Pa < 0.0:
        # An intercept below zero is no cohesion: c = 0 and phi of the least-squares line through
        # the origin (not the free fit's phi, which the negative intercept steepened).
        free = mc
        mc = fits.fit_mohr_coulomb(shear.sigmas_Pa, shear.tau_peaks_Pa,
                                   clip_negative_cohesion=True)
        sources["mohr_coulomb"] = scm_file.dem_source(
            dem, "direct shear box, peak strength", mc,
            f"normal stresses {sigmas} kPa{lab}; the free fit's intercept was "
            f"{free.cohesion_Pa:.4g} Pa (< 0: no cohesion), so c = 0 and phi from the line "
            f"through the origin (free fit: phi {free.friction_deg:.4g} deg)")
    return scm_file.write_scm_soil(
        path, name or f"{dem} (fitted from DEM)",
        f"SCM parameters fitted to the DEM soil '{dem}' ({r.soil.get('file', '?')}) by the "
        f"virtual soil lab ({r.soil.get('preset', '?')} preset)",
        bekker.n, bekker.kc, bekker.kphi, mc.cohesion_Pa, mc.friction_deg,
        float(np.mean(shear.K_m)), ke.Ke_Pa_m, sources)
