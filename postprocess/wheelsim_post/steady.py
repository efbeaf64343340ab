"""Steady-state statistics of a run over a window of its test phase (phase == 3).

Window (docs/postprocess.md, "Steady-state window"). Let t0/t1 be the first/last test-phase
sample, D = t1 - t0 and theta(t) the angle the wheel has turned (trapezoidal integral of
``wheel/omega``). The default ("passes") is the largest whole number k >= 1 of lug passes
(angle 2 pi / n_lugs; whole revolutions when the lug count is 0 or unknown) that fits in the
second half of the test phase, ending at t1: [t_start, t1] with theta(t1) - theta(t_start) =
k * pass angle. If not even one pass fits there, the second half of the test phase is used
with a note. User windows (``--window-fraction A B``, ``--window-start S --window-end E``)
are kept as given; their number of passes is reported. Windows with fewer than MIN_PASSES
passes get a note. Both ends are included (relative tolerance WINDOW_TOLERANCE).

A window in which v, ω, DP, T or sinkage has no finite sample is an error naming the run, the
observable and the window (REQUIRED_FINITE), not a row of NaN.

Statistics per quantity (class Stat): the mean and population standard deviation (ddof = 0)
of the finite samples, and the standard error of the mean (SEM) by **batch means**: the
samples are cut into N_BATCHES consecutive batches of equal length m = N // N_BATCHES (the
earliest N mod N_BATCHES samples are left out of the SEM only), and SEM = std(batch means,
ddof = 1) / sqrt(N_BATCHES). This accounts for the correlation of successive samples as long
as a batch is much longer than the correlation time (a note says when the drawbar pull's batch
means are themselves correlated, lag-1 > MAX_BATCH_CORRELATION, and adds their lag-1 about a
fitted line when that is at most MAX_BATCH_CORRELATION: a drift may be the cause); functions of several means
(slip and efficiency of the means, DP/W) get their SEM from the function of each batch's means.
"""

import dataclasses
import math
import sys
from typing import NamedTuple

import numpy as np

from . import box_frame
from .errors import PostError
from .metadata import rig_config
from .quantities import EFFICIENCY_OF_MEANS, of_means
from .slip import CONVENTIONS

#: Phase codes of the ``phase`` observable.
PHASES = {0: "release", 1: "settle", 2: "ramp", 3: "test"}
TEST_PHASE = 3
#: Relative tolerance of the window boundaries (times within it of a boundary are inside).
WINDOW_TOLERANCE = 1e-9
#: Number of batches of the batch-means SEM.
N_BATCHES = 20
#: Lag-1 correlation of the drawbar pull's batch means above which a note says the SEM is
#: probably too small (its scatter for independent batches is about 1/sqrt(N_BATCHES) = 0.22).
MAX_BATCH_CORRELATION = 0.5
#: A window with fewer lug passes (or revolutions) than this gets a note.
MIN_PASSES = 3
#: Fraction of the test phase the default window may use (its second half).
DEFAULT_FRACTION = (0.5, 1.0)


@dataclasses.dataclass(frozen=True)
class Window:
    """A window definition: whole passes in the second half of the test phase ("passes"),
    fractions of the test phase ("fraction") or seconds after its start ("time")."""

    kind: str  # "passes", "fraction" or "time"
    start: float
    end: float

    def describe(self):
        """One line for the console and CSV headers."""
        if self.kind == "passes":
            return (
                "steady-state window: the most whole lug passes (whole wheel revolutions "
                "when the lug count is 0 or unknown) that fit in the second half of the test "
                "phase (phase == 3), ending at its last sample; ends included"
            )
        if self.kind == "fraction":
            return (
                f"steady-state window: test phase (phase == 3) from {self.start:g} to "
                f"{self.end:g} of its duration (t0 + {self.start:g}*D .. t0 + {self.end:g}*D, "
                "t0 = first test-phase sample, D = test-phase duration), ends included"
            )
        return (
            f"steady-state window: test phase (phase == 3) from t0 + {self.start:g} s to "
            f"t0 + {self.end:g} s (t0 = first test-phase sample), ends included"
        )


DEFAULT_WINDOW = Window("passes", *DEFAULT_FRACTION)


def make_window(start, end, fraction):
    """The Window of the CLI options (PostError on inconsistent or out-of-range values)."""
    if fraction is not None and (start is not None or end is not None):
        raise PostError(
            "--window-fraction cannot be combined with --window-start/--window-end"
        )
    if fraction is not None:
        a, b = fraction
        if not (0.0 <= a < b <= 1.0):
            raise PostError(
                f"--window-fraction: expected 0 <= A < B <= 1, got A = {a:g}, B = {b:g}"
            )
        return Window("fraction", a, b)
    if start is None and end is None:
        return DEFAULT_WINDOW
    if start is None or end is None:
        raise PostError("--window-start and --window-end [s] must be given together")
    if not (0.0 <= start < end) or not math.isfinite(end):
        raise PostError(
            f"--window-start/--window-end: expected 0 <= S < E [s], got S = {start:g} s, "
            f"E = {end:g} s"
        )
    return Window("time", start, end)


@dataclasses.dataclass
class WindowSpan:
    """A window resolved on one run: absolute times [s], the window's steps and its length
    in lug passes (or revolutions when ``lug_count`` is 0 or None)."""

    test_start: float
    test_end: float
    start: float
    end: float
    steps: np.ndarray
    passes: float = math.nan
    lug_count: object = None
    lug_source: str = "unknown"
    notes: list = dataclasses.field(default_factory=list)

    @property
    def pass_name(self):
        """'lug passes' or 'revolutions'."""
        return "lug passes" if self.lug_count else "revolutions"

    def describe(self):
        """'0.8 s .. 1.3 s, 6 lug passes (15 lugs: <source>)' for the console."""
        lugs = (
            f"{self.lug_count} lugs from {self.lug_source}"
            if self.lug_count
            else f"lug count {'0' if self.lug_count == 0 else 'unknown'}"
            + (f" ({self.lug_source})" if self.lug_count == 0 else "")
        )
        return (
            f"window {self.start:.6g} s .. {self.end:.6g} s, {self.passes:.3g} "
            f"{self.pass_name} ({lugs}), {len(self.steps)} samples"
        )


def turned_angle(time, omega):
    """theta(t) [rad]: cumulative trapezoidal integral of omega [rad/s] over ``time`` [s]."""
    if len(time) == 0:
        return np.zeros(0)
    increments = 0.5 * (omega[1:] + omega[:-1]) * np.diff(time)
    return np.concatenate(([0.0], np.cumsum(increments)))


def _pass_angle(lug_count):
    return 2.0 * math.pi / lug_count if lug_count else 2.0 * math.pi


def resolve_window(run, window, lug_count=None, lug_source="unknown"):
    """The WindowSpan of ``window`` in an open RunFile (PostError if it holds no sample).

    ``lug_count``: lugs on the wheel (0 or None: count whole revolutions instead)."""
    phase = run.observable("phase")
    test = np.rint(np.ravel(phase.value)) == TEST_PHASE
    if not np.any(test):
        raise PostError(
            f"run file '{run.path}' has no test-phase samples (observable 'phase' never 3)"
        )
    times = phase.time[test]
    t0, t1 = float(times[0]), float(times[-1])
    pass_angle = _pass_angle(lug_count)
    pass_name = "lug passes" if lug_count else "revolutions"
    angle_time, angle = _test_angle(run, phase.step[test])
    notes = []
    if window.kind == "passes":
        start, end = t0 + window.start * (t1 - t0), t0 + window.end * (t1 - t0)
        whole = _whole_passes_start(angle_time, angle, start, end, pass_angle)
        if whole is not None:
            start = whole
        else:
            single = "lug pass" if lug_count else "revolution"
            notes.append(
                f"not even one whole {single} fits in the second half of the test phase: "
                f"window = that half ({pass_name} not whole)"
            )
    elif window.kind == "fraction":
        start = t0 + window.start * (t1 - t0)
        end = t0 + window.end * (t1 - t0)
    else:
        start, end = t0 + window.start, t0 + window.end
        # a window ending with the test phase (--window-end = its duration) ends up to one
        # sample interval after its last sample (t0 is the first sample): not worth a warning
        interval = float(np.median(np.diff(times))) if len(times) > 1 else 0.0
        if end > (t1 + interval) * (1 + WINDOW_TOLERANCE) + WINDOW_TOLERANCE:
            print(
                f"wheelsim-post: warning: run file '{run.path}': window end "
                f"{end:g} s is after the last test-phase sample ({t1:g} s); "
                "using the samples there are",
                file=sys.stderr,
            )
    tol = WINDOW_TOLERANCE * max(abs(start), abs(end), 1.0)
    inside = (times >= start - tol) & (times <= end + tol)
    if not np.any(inside):
        raise PostError(
            f"run file '{run.path}': the window {start:g} s .. {end:g} s holds no "
            f"test-phase sample (test phase {t0:g} s .. {t1:g} s)"
        )
    passes = math.nan
    if len(angle_time) >= 2:
        a = np.interp([start, min(end, t1)], angle_time, angle)
        passes = abs(float(a[1] - a[0])) / pass_angle
        if window.kind == "passes" and not notes:
            passes = round(passes, 6)  # a whole number up to the interpolation's rounding
    # a smooth wheel (lug count 0, known) has no angular period for the window's start to fall
    # on: its short windows get no note; an unknown lug count keeps it
    if not passes >= MIN_PASSES and not notes and lug_count != 0:
        notes.append(
            f"the window holds {passes:.3g} {pass_name} (< {MIN_PASSES}): the mean may "
            "depend on where the window starts relative to the lugs"
        )
    return WindowSpan(
        t0, t1, start, end, phase.step[test][inside], passes, lug_count, lug_source, notes
    )


def _test_angle(run, test_steps):
    """(time, theta) of the wheel over the test-phase steps (empty without wheel/omega)."""
    if not run.has_observable("wheel/omega"):
        return np.zeros(0), np.zeros(0)
    omega = run.observable("wheel/omega")
    keep = np.isin(omega.step, test_steps) & np.isfinite(np.ravel(omega.value))
    time = omega.time[keep]
    return time, turned_angle(time, np.ravel(omega.value)[keep])


def _whole_passes_start(time, angle, start, end, pass_angle):
    """Start time of the most whole passes in [start, end] that end at ``end`` (None if not
    even one fits or the wheel does not turn one way)."""
    steps = np.diff(angle)
    if len(time) < 2 or not (np.all(steps >= 0.0) or np.all(steps <= 0.0)):
        return None
    sign = 1.0 if angle[-1] >= angle[0] else -1.0
    theta = sign * angle
    a_start, a_end = np.interp([start, end], time, theta)
    k = math.floor((a_end - a_start) / pass_angle + 1e-9)
    if k < 1:
        return None
    target = a_end - k * pass_angle
    # theta is non-decreasing; np.interp needs increasing x: use the first time theta reaches
    # the target.
    index = int(np.searchsorted(theta, target, side="left"))
    index = min(max(index, 1), len(theta) - 1)
    a0, a1 = theta[index - 1], theta[index]
    frac = 0.0 if a1 == a0 else (target - a0) / (a1 - a0)
    return float(time[index - 1] + frac * (time[index] - time[index - 1]))


class Stat(NamedTuple):
    """Window statistics of one quantity: mean, population std (ddof 0), SEM (batch means)."""

    mean: float
    std: float
    sem: float


NAN_STAT = Stat(math.nan, math.nan, math.nan)


def batch_means(values, n_batches=N_BATCHES):
    """Means of ``n_batches`` consecutive batches of equal length (the earliest len mod
    n_batches samples left out); None if there are fewer than 2 samples."""
    values = np.asarray(values, dtype=float)
    b = min(n_batches, len(values))
    if b < 2:
        return None
    m = len(values) // b
    return values[len(values) - b * m :].reshape(b, m).mean(axis=1)


def sem_of_batches(batches):
    """std(ddof 1) / sqrt(count) of per-batch values (NaN if fewer than 2 are finite)."""
    if batches is None:
        return math.nan
    finite = np.asarray(batches)[np.isfinite(batches)]
    if len(finite) < 2:
        return math.nan
    return float(np.std(finite, ddof=1) / math.sqrt(len(finite)))


def batch_sem(values, n_batches=N_BATCHES):
    """The batch-means standard error of the mean of the finite ``values``."""
    values = np.asarray(values, dtype=float)
    return sem_of_batches(batch_means(values[np.isfinite(values)], n_batches))


def batch_correlation(values, n_batches=N_BATCHES):
    """Lag-1 autocorrelation of the batch means of the finite ``values`` (NaN if undefined).
    Near 0 when batches are much longer than the correlation time."""
    values = np.asarray(values, dtype=float)
    means = batch_means(values[np.isfinite(values)], n_batches)
    if means is None or len(means) < 3:
        return math.nan
    centred = means - means.mean()
    denominator = float(np.sum(centred**2))
    if denominator == 0.0:
        return math.nan
    return float(np.sum(centred[1:] * centred[:-1]) / denominator)


def _stats(values):
    """Stat of the finite samples (all NaN if there are none)."""
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return NAN_STAT
    return Stat(float(np.mean(finite)), float(np.std(finite)), batch_sem(finite))


def scaled(stat, factor):
    """A Stat times a constant ``factor``."""
    return Stat(stat.mean * factor, stat.std * abs(factor), stat.sem * abs(factor))


def require_scalar(run, series):
    """``series`` (an observable of ``run``) if it has one component, else PostError."""
    if series.value.ndim != 1:
        raise PostError(
            f"run file '{run.path}': observable '{series.name}' has {series.value.shape[1]} "
            "components, expected 1"
        )
    return series


def _scalar_series(run, name, steps):
    """(step, value) of a 1-component observable restricted to ``steps``."""
    series = require_scalar(run, run.observable(name))
    keep = np.isin(series.step, steps)
    return series.step[keep], series.value[keep]


#: Observables of steady_state that must have a finite sample in the window (the slip's v and
#: ω, and the curves' quantities): without one the run gives no point, only NaN.
REQUIRED_FINITE = ("carriage/velocity", "wheel/omega", "drawbar_pull", "driving_torque", "sinkage")


def require_finite(run, name, values, span):
    """PostError naming the run, the observable and the window if ``values`` (of ``name`` in
    the window ``span``) hold no finite sample: a run that went wrong (NaN or inf) or whose
    observable has no row there must not become a row of NaN."""
    finite = int(np.sum(np.isfinite(values)))
    if finite == 0:
        found = (f"its {len(values)} samples there are all NaN or inf" if len(values)
                 else "it has no sample there")
        raise PostError(
            f"run file '{run.path}': observable '{name}' has no finite sample in the window "
            f"{span.start:.6g} s .. {span.end:.6g} s ({found}); expected numbers: the run "
            "went wrong or did not record it"
        )


def _window_max_x(run, name, steps):
    """The largest x [m] of a 3-component position observable over ``steps`` (NaN without it)."""
    if not run.has_observable(name):
        return math.nan
    series = run.observable(name)
    x = series.value[np.isin(series.step, steps)]
    return float(np.max(x[:, 0])) if x.ndim == 2 and len(x) else math.nan


def _aligned(*pairs):
    """Values of several (step, value) pairs at their common steps."""
    common = pairs[0][0]
    for step, _ in pairs[1:]:
        common = np.intersect1d(common, step)
    out = []
    for step, value in pairs:
        index = {s: i for i, s in enumerate(step.tolist())}
        out.append(value[[index[s] for s in common.tolist()]])
    return out


def _ratio(numerator, denominator):
    """numerator / denominator with NaN where the denominator is 0."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(denominator != 0.0, numerator / denominator, np.nan)


def _of_means(function, *series):
    """(value, SEM) of ``function`` of the means of aligned ``series``: the SEM from the
    function of each batch's means (batch means; NaN with fewer than 2 batches)."""
    value = function(*(float(np.mean(s)) for s in series))
    batches = [batch_means(s) for s in series]
    if any(b is None for b in batches):
        return value, math.nan
    with np.errstate(divide="ignore", invalid="ignore"):
        per_batch = np.array([function(*v) for v in zip(*batches)], dtype=float)
    return value, sem_of_batches(per_batch)


def _safe_ratio(numerator, denominator):
    return numerator / denominator if denominator != 0.0 else math.nan


def vertical_load(run, steps):
    """(W [N], source) over the window: the mean of the ``vertical_load`` observable, else
    ``rig.vertical_load`` of the rig config; (NaN, 'unknown') if neither exists."""
    if run.has_observable("vertical_load"):
        values = _scalar_series(run, "vertical_load", steps)[1]
        values = values[np.isfinite(values)]
        if values.size:
            return float(np.mean(values)), "observable vertical_load"
    load = rig_config(run).get("rig", {}).get("vertical_load")
    if isinstance(load, (int, float)) and load > 0:
        return float(load), "rig.vertical_load"
    return math.nan, "unknown"


def detrended_batch_correlation(time, values, n_batches=N_BATCHES):
    """Lag-1 autocorrelation of the batch means of ``values`` about the straight line fitted to
    them against the batches' mean times (NaN if undefined): whether correlated batch means
    come from a trend over the window rather than from a long correlation time."""
    finite = np.isfinite(values)
    t_b, v_b = batch_means(time[finite], n_batches), batch_means(values[finite], n_batches)
    if t_b is None or len(t_b) < 4:
        return math.nan
    residual = v_b - np.polyval(np.polyfit(t_b, v_b, 1), t_b)
    denominator = float(np.sum(residual**2))
    if denominator == 0.0:
        return math.nan
    return float(np.sum(residual[1:] * residual[:-1]) / denominator)


def linear_trend(time, values, n_batches=N_BATCHES):
    """(change over the window, its standard error) of a straight line fitted to the batch
    means of ``values`` against the batches' mean times; NaN with fewer than 3 batches."""
    finite = np.isfinite(values)
    t_b, v_b = batch_means(time[finite], n_batches), batch_means(values[finite], n_batches)
    if t_b is None or len(t_b) < 3:
        return math.nan, math.nan
    length = float(time[finite][-1] - time[finite][0])
    tc = t_b - t_b.mean()
    sxx = float(np.sum(tc**2))
    if sxx == 0.0:
        return math.nan, math.nan
    slope = float(np.sum(tc * (v_b - v_b.mean())) / sxx)
    residual = v_b - v_b.mean() - slope * tc
    se_slope = math.sqrt(float(np.sum(residual**2)) / (len(t_b) - 2) / sxx)
    return slope * length, se_slope * length


def steady_state(run, window, lug_count=None, lug_source="unknown"):
    """Window statistics of an open RunFile: a dict of column name -> value.

    Keys: '<quantity>' -> Stat for every name in quantities.QUANTITIES (slip in the three
    conventions of slip.py: 'slip' driving, 'slip_skid', 'slip_signed'), of_means(<slip
    name>) and EFFICIENCY_OF_MEANS -> Stat (std NaN), 'n_samples', 'span' (the WindowSpan), 'r_eff',
    'vertical_load' and 'vertical_load_source', 'dp_trend' ((change, standard error) [N]),
    'wheel_x_max' (the wheel centre's largest x in the window [m] in LIGGGHTS' box, box_frame.py;
    NaN without wheel/position or where the box origin is unknown).
    """
    span = resolve_window(run, window, lug_count, lug_source)
    r_eff = run.parameter_float("wheel/effective_radius")
    v = _scalar_series(run, "carriage/velocity", span.steps)
    omega = _scalar_series(run, "wheel/omega", span.steps)
    dp = _scalar_series(run, "drawbar_pull", span.steps)
    torque = _scalar_series(run, "driving_torque", span.steps)
    sinkage = _scalar_series(run, "sinkage", span.steps)
    for name, (_, values) in zip(REQUIRED_FINITE, (v, omega, dp, torque, sinkage)):
        require_finite(run, name, values, span)

    v_a, omega_a, dp_a, torque_a = _aligned(v, omega, dp, torque)
    eta_series = _ratio(dp_a * v_a, torque_a * omega_a)

    result = {name: _stats(f(v_a, omega_a * r_eff)) for name, f in CONVENTIONS.items()}
    result.update({
        "drawbar_pull": _stats(dp[1]),
        "driving_torque": _stats(torque[1]),
        "sinkage": _stats(sinkage[1]),
        "tractive_efficiency": _stats(eta_series),
        "traction_force": scaled(_stats(torque[1]), 1.0 / r_eff),
    })
    if run.has_observable("lateral_force"):
        result["lateral_force"] = _stats(
            _scalar_series(run, "lateral_force", span.steps)[1]
        )
    else:
        print(
            f"wheelsim-post: warning: run file '{run.path}' has no observable "
            "'lateral_force'; its columns are NaN",
            file=sys.stderr,
        )
        result["lateral_force"] = NAN_STAT

    for name, function in CONVENTIONS.items():
        slip_m, slip_sem = _of_means(
            lambda vm, om, f=function: f(vm, om * r_eff), v_a, omega_a
        )
        result[of_means(name)] = Stat(slip_m, math.nan, slip_sem)
    eta_m, eta_sem = _of_means(
        lambda d, vm, t, om: _safe_ratio(d * vm, t * om), dp_a, v_a, torque_a, omega_a
    )
    result[EFFICIENCY_OF_MEANS] = Stat(eta_m, math.nan, eta_sem)

    load, load_source = vertical_load(run, span.steps)
    result["dp_over_w"] = scaled(result["drawbar_pull"], 1.0 / load)
    result["torque_over_w_reff"] = scaled(result["driving_torque"], 1.0 / (load * r_eff))
    dp_series = run.observable("drawbar_pull")
    dp_time = dp_series.time[np.isin(dp_series.step, span.steps)]
    result["dp_trend"] = linear_trend(dp_time, dp[1])
    correlation = batch_correlation(dp[1])
    if correlation > MAX_BATCH_CORRELATION:
        note = (f"successive batch means of the drawbar pull are correlated ({correlation:.2f} "
                f"> {MAX_BATCH_CORRELATION:g}): the batches are not much longer than the "
                "correlation time, so the SEMs are probably too small (use a longer window)")
        # a drift over the window correlates the batches too; one window cannot tell it from a
        # slow fluctuation (an AR(1) with a correlation time near the window's is detrended below
        # the limit about half the time), so the note gives the number and keeps its warning
        detrended = detrended_batch_correlation(dp_time, dp[1])
        if detrended <= MAX_BATCH_CORRELATION:
            note += (f"; about a straight line fitted to them they correlate {detrended:.2f}: if "
                     f"the window drifts ({result['dp_trend'][0]:+.3g} N over it) rather than "
                     "fluctuates slowly, the SEM is the noise's about the drift and the mean's "
                     "error is the drift's (steady_state_trend)")
        span.notes.append(note)
    result["dp_batch_correlation"] = correlation
    origin, _ = box_frame.origin_x(run)  # the recorded x is from the wheel's start
    result["wheel_x_max"] = (_window_max_x(run, "wheel/position", span.steps) + origin
                             if origin is not None else math.nan)
    result["n_samples"] = int(len(span.steps))
    result["span"] = span
    result["r_eff"] = r_eff
    result["vertical_load"] = load
    result["vertical_load_source"] = load_source
    return result
