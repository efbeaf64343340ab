"""Angle of repose from a heap's free surface (docs/soil-lab.md, section "Fits").

surface_profile turns particle positions into the free-surface profile h(x); repose_angle fits
the two flanks of that profile with straight lines between fixed fractions of the heap height.
"""

from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from ._inputs import FitInputError, finite_array, finite_scalar, same_length

__all__ = ["FlankFit", "ReposeFit", "surface_profile", "repose_angle", "REPOSE_BAND"]

#: The part of the heap height whose flank points are fitted: 20 % to 80 % above the base.
REPOSE_BAND = (0.2, 0.8)


@dataclass(frozen=True)
class FlankFit:
    """One flank: h = intercept_m + slope x over the points inside the height band."""

    slope: float  #: dh/dx [-] (> 0 on the left flank, < 0 on the right)
    intercept_m: float  #: h of the fitted line at x = 0 [m]
    angle_deg: float  #: atan(|slope|) [deg]
    rms_m: float  #: RMS of the line's residual in h [m]
    r2: float  #: coefficient of determination [-]
    n_points: int  #: profile points fitted
    x_range_m: Tuple[float, float]  #: smallest and largest x fitted [m]


@dataclass(frozen=True)
class ReposeFit:
    """Angle of repose: the mean of the two flanks' angles, and each flank's fit."""

    angle_deg: float  #: (left.angle_deg + right.angle_deg) / 2 [deg]
    left: FlankFit  #: flank at x < axis_m
    right: FlankFit  #: flank at x > axis_m
    top_m: float  #: highest point of the profile [m]
    base_m: float  #: base level [m] (given, or the lowest point of the profile)
    band_m: Tuple[float, float]  #: the heights fitted, base + band x (top − base) [m]
    axis_m: float  #: x of the heap axis separating the flanks [m]


def surface_profile(x, z, radius, bins, x_range: Optional[Tuple[float, float]] = None):
    """Free-surface profile of a heap of particles: the highest particle top in each x bin.

    x [m]: signed horizontal position of each particle centre across the heap (measured from the
    heap axis, so the two flanks have x < 0 and x > 0); z [m]: vertical position of the centre;
    radius [m]: one radius per particle, or one for all. The top of a particle is z + radius; a
    particle counts in the bin holding its centre. For an axisymmetric heap (a cone) all
    particles may be given with their x alone: the highest top across the other horizontal
    direction is the meridian profile. bins: the number of equal bins over x_range (default
    [min x, max x]) or the bin edges [m]. Bin widths of 1–2 particle diameters give one surface
    particle per bin.

    Returns (x_centres_m, h_m): the centres of the bins that hold a particle and the highest top
    in each (empty bins are left out, so the profile has no gaps filled in).
    """
    x = finite_array("x", x, "m")
    z = finite_array("z", z, "m")
    same_length(("x", "z"), (x, z))
    r = finite_array("radius", radius, "m")
    if r.size == 1:
        r = np.full(x.size, r[0])
    same_length(("x", "radius"), (x, r))
    if (r < 0).any():
        i = int(np.flatnonzero(r < 0)[0])
        raise FitInputError(f"radius[{i}] is {r[i]!r}: radii must be >= 0 m")
    if np.ndim(bins) == 0:
        nb = int(bins)
        if nb < 1 or nb != bins:
            raise FitInputError(f"bins must be a positive integer or the bin edges, got {bins!r}")
        lo, hi = (float(x.min()), float(x.max())) if x_range is None else map(float, x_range)
        if not hi > lo:
            raise FitInputError(f"x_range must be (low, high) with high > low, got ({lo}, {hi}) m")
        edges = np.linspace(lo, hi, nb + 1)
    else:
        edges = finite_array("bins", bins, "m")
        if edges.size < 2 or (np.diff(edges) <= 0).any():
            raise FitInputError("bin edges must be at least 2 strictly increasing values in m")
    inside = (x >= edges[0]) & (x <= edges[-1])
    idx = np.clip(np.searchsorted(edges, x[inside], side="right") - 1, 0, edges.size - 2)
    top = np.full(edges.size - 1, -np.inf)
    np.maximum.at(top, idx, (z + r)[inside])
    filled = np.isfinite(top)
    if not filled.any():
        raise FitInputError("no particle lies inside the bins")
    centres = 0.5 * (edges[:-1] + edges[1:])
    return centres[filled], top[filled]


def _fit_flank(name, x, h):
    if x.size < 3:
        raise FitInputError(
            f"the {name} flank has {x.size} profile point(s) between "
            f"{REPOSE_BAND[0]:.0%} and {REPOSE_BAND[1]:.0%} of the heap height; at least 3 are "
            "needed (finer bins, or check axis_m and base_m)"
        )
    if np.ptp(x) <= 0:
        raise FitInputError(f"the {name} flank's points all have the same x")
    slope, intercept = np.polyfit(x, h, 1)
    residual = intercept + slope * x - h
    ss_tot = float(np.sum((h - h.mean()) ** 2))
    return FlankFit(
        slope=float(slope),
        intercept_m=float(intercept),
        angle_deg=float(np.degrees(np.arctan(abs(slope)))),
        rms_m=float(np.sqrt(np.mean(residual**2))),
        r2=1.0 - float(residual @ residual) / ss_tot if ss_tot > 0 else float("nan"),
        n_points=int(x.size),
        x_range_m=(float(x.min()), float(x.max())),
    )


def repose_angle(x_m, h_m, axis_m=0.0, base_m: Optional[float] = None):
    """Angle of repose [deg] of a heap from its free-surface profile h(x).

    x_m [m]: signed horizontal position (both flanks, e.g. from surface_profile); h_m [m]: surface
    height. The heap's top is max h, its base base_m (default: the lowest point of the profile,
    e.g. the floor or the bed around the heap). Each flank (x < axis_m, x > axis_m) is fitted by a
    straight line through its points with base + 20 % H <= h <= base + 80 % H (H = top − base) by
    linear least squares of h on x; the rounded top and the foot, where the heap meets the floor,
    are left out. A flank's angle is atan(|slope|); the angle of repose is the mean of the two.
    A flank that rises away from the axis is an error (the axis is not inside the heap).

    Returns ReposeFit (angle_deg, left, right: FlankFit with slope, intercept_m, angle_deg,
    rms_m, r2, n_points, x_range_m; top_m, base_m, band_m, axis_m).
    """
    x = finite_array("x_m", x_m, "m")
    h = finite_array("h_m", h_m, "m")
    same_length(("x_m", "h_m"), (x, h))
    axis = finite_scalar("axis_m", axis_m, "m")
    top = float(h.max())
    base = float(h.min()) if base_m is None else finite_scalar("base_m", base_m, "m")
    if not top > base:
        raise FitInputError(
            f"the heap has no height: top {top:g} m is not above the base {base:g} m"
        )
    lo = base + REPOSE_BAND[0] * (top - base)
    hi = base + REPOSE_BAND[1] * (top - base)
    band = (h >= lo) & (h <= hi)
    left = _fit_flank("left", x[band & (x < axis)], h[band & (x < axis)])
    right = _fit_flank("right", x[band & (x > axis)], h[band & (x > axis)])
    if left.slope <= 0 or right.slope >= 0:
        raise FitInputError(
            f"the flanks do not rise towards the axis at x = {axis:g} m (left slope "
            f"{left.slope:.3g}, right slope {right.slope:.3g}): is axis_m inside the heap?"
        )
    return ReposeFit(
        angle_deg=0.5 * (left.angle_deg + right.angle_deg),
        left=left,
        right=right,
        top_m=top,
        base_m=base,
        band_m=(float(lo), float(hi)),
        axis_m=axis,
    )
