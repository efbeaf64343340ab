"""Steady-state statistics of a run over a window of its test phase (phase == 3).

The window is ``[t0 + a, t0 + b]`` (both ends included, with a tolerance of WINDOW_TOLERANCE
relative to the times for floating-point rounding), where t0 is the time of the first
test-phase sample and D the time from the first to the last test-phase sample, with either
``a = A·D, b = B·D`` (``--window-fraction A B``, default 0.5 1.0: the second half of the test
phase) or ``a = S, b = E`` (``--window-start S --window-end E``, seconds after t0). Only
test-phase samples count. Statistics: mean and population standard deviation (ddof = 0) of
the samples in the window; NaN samples (e.g. slip while ω R_eff = 0) are left out.
"""

import dataclasses
import math
import sys

import numpy as np

from .errors import PostError
from .quantities import EFFICIENCY_OF_MEANS, SLIP_OF_MEANS

#: Phase codes of the ``phase`` observable.
PHASES = {0: "release", 1: "settle", 2: "ramp", 3: "test"}
TEST_PHASE = 3
#: Relative tolerance of the window boundaries (times within it of a boundary are inside).
WINDOW_TOLERANCE = 1e-9


@dataclasses.dataclass(frozen=True)
class Window:
    """A window definition: fractions of the test phase, or seconds after its start."""

    kind: str  # "fraction" or "time"
    start: float
    end: float

    def describe(self):
        """One line for the console and CSV headers."""
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


DEFAULT_WINDOW = Window("fraction", 0.5, 1.0)


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
    """A window resolved on one run: absolute times [s] and the window's steps."""

    test_start: float
    test_end: float
    start: float
    end: float
    steps: np.ndarray


def resolve_window(run, window):
    """The WindowSpan of ``window`` in an open RunFile (PostError if it holds no sample)."""
    phase = run.observable("phase")
    test = np.rint(np.ravel(phase.value)) == TEST_PHASE
    if not np.any(test):
        raise PostError(
            f"run file '{run.path}' has no test-phase samples (observable 'phase' never 3)"
        )
    times = phase.time[test]
    t0, t1 = float(times[0]), float(times[-1])
    if window.kind == "fraction":
        start = t0 + window.start * (t1 - t0)
        end = t0 + window.end * (t1 - t0)
    else:
        start, end = t0 + window.start, t0 + window.end
        if end > t1 * (1 + WINDOW_TOLERANCE) + WINDOW_TOLERANCE:
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
    return WindowSpan(t0, t1, start, end, phase.step[test][inside])


def _scalar_series(run, name, steps):
    """(step, value) of a 1-component observable restricted to ``steps``."""
    series = run.observable(name)
    value = series.value
    if value.ndim != 1:
        raise PostError(
            f"run file '{run.path}': observable '{name}' has {value.shape[1]} components, "
            "expected 1"
        )
    keep = np.isin(series.step, steps)
    return series.step[keep], value[keep]


def _stats(values):
    """(mean, std) of the finite samples (NaN, NaN if there are none)."""
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return math.nan, math.nan
    return float(np.mean(finite)), float(np.std(finite))


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


def steady_state(run, window):
    """Window statistics of an open RunFile: a dict of column name -> value.

    Keys: '<quantity>' -> (mean, std) for every name in quantities.QUANTITIES, plus
    SLIP_OF_MEANS, EFFICIENCY_OF_MEANS, 'n_samples', 'span' (the WindowSpan), 'r_eff'.
    """
    span = resolve_window(run, window)
    r_eff = run.parameter_float("wheel/effective_radius")
    v = _scalar_series(run, "carriage/velocity", span.steps)
    omega = _scalar_series(run, "wheel/omega", span.steps)
    dp = _scalar_series(run, "drawbar_pull", span.steps)
    torque = _scalar_series(run, "driving_torque", span.steps)
    sinkage = _scalar_series(run, "sinkage", span.steps)

    v_a, omega_a, dp_a, torque_a = _aligned(v, omega, dp, torque)
    slip_series = 1.0 - _ratio(v_a, omega_a * r_eff)
    eta_series = _ratio(dp_a * v_a, torque_a * omega_a)

    result = {
        "slip": _stats(slip_series),
        "drawbar_pull": _stats(dp[1]),
        "driving_torque": _stats(torque[1]),
        "sinkage": _stats(sinkage[1]),
        "tractive_efficiency": _stats(eta_series),
        "traction_force": _stats(torque[1] / r_eff),
    }
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
        result["lateral_force"] = (math.nan, math.nan)

    v_mean, omega_mean = float(np.mean(v[1])), float(np.mean(omega[1]))
    dp_mean, t_mean = result["drawbar_pull"][0], result["driving_torque"][0]
    result[SLIP_OF_MEANS] = (
        1.0 - v_mean / (omega_mean * r_eff) if omega_mean != 0.0 else math.nan
    )
    result[EFFICIENCY_OF_MEANS] = (
        dp_mean * v_mean / (t_mean * omega_mean)
        if t_mean * omega_mean != 0.0
        else math.nan
    )
    result["n_samples"] = int(len(span.steps))
    result["span"] = span
    result["r_eff"] = r_eff
    return result
