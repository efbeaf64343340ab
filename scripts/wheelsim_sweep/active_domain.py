"""The active domain in the cost estimate (issue 12 items 1 and 4). Reference: docs/sweeps.md,
"Cost estimate", and docs/fix-wheel-active.md.

With `fix wheel/active` (the coupled deck's `-var active_domain 1`) only the soil within
R + D of the wheel centre moves: R the wheel mesh's bounding radius (the sphere about the wheel
centre holding the whole mesh, lugs and width included), D the fix's `distance` (default
0.5 R + 2 z, z its `sinkage` allowance, default R / 4). A frozen particle still costs part of
an active one's step (estimate.FROZEN_COST: neighbour-list builds, per-particle passes), so a
point of N particles costs as N x (a + FROZEN_COST x (1 - a)) active ones, a the mean active
share computed here.

The active share is geometric: the volume of the bed (0 <= x <= bin length, |y| <= width / 2,
0 <= z <= bed depth) inside the sphere of radius R + D about the wheel centre, divided by the
bed's volume (the spheres fill it uniformly), averaged over the point's simulated time: the
wheel at x0 through release and settle, then travelling at (1 - s) omega R_outer (s >= 0) or
omega R_outer / (1 + s) (s < 0) through the ramp (half speed on average) and the test phase.
Its centre is at z = bed depth + R_outer - z (the sinkage allowance; the real sinkage is not
known beforehand), y = 0 (the bin is centred on y = 0).
"""

import math
import shlex
from dataclasses import dataclass

import numpy as np

from wheelsim_post.deck_files import deck_variable
from wheelsim_post.slip import forward_speed

GRID_X = 400  # cells along the bin (and 100 across it) for the share's volume integral
GRID_Y = 100
TIME_SAMPLES = 48  # positions of the wheel over the simulated time


@dataclass
class ActiveSettings:
    """fix wheel/active's keywords as the deck passes them (None: the fix's default)."""
    distance: float | None = None  # D [m]
    sinkage: float | None = None  # z [m]

    def reach(self, bounding_radius):
        """R + D [m]: particles with their centre this close to the wheel centre move."""
        r = bounding_radius
        z = self.sinkage if self.sinkage is not None else 0.25 * r
        d = self.distance if self.distance is not None else 0.5 * r + 2.0 * z
        return r + d

    def sinkage_allowance(self, bounding_radius):
        return self.sinkage if self.sinkage is not None else 0.25 * bounding_radius


def settings(deck, liggghts_args=()):
    """ActiveSettings when the point runs with the active domain (`-var active_domain N`, N > 0,
    in liggghts_args, else the deck's `variable active_domain index N`), else None. Its keywords
    come from `-var active_args "distance D sinkage Z ..."` (else the deck's default)."""
    on = deck_variable(deck, "active_domain", liggghts_args)
    try:
        if on is None or float(on) <= 0:
            return None
    except ValueError:
        return None
    words = shlex.split(deck_variable(deck, "active_args", liggghts_args) or "")
    out = ActiveSettings()
    for key, value in zip(words[::2], words[1::2]):
        if key in ("distance", "sinkage"):
            try:
                setattr(out, key, float(value))
            except ValueError:
                pass  # LIGGGHTS will say so at the run
    return out


def mesh_extent(mesh, scale=1.0):
    """(bounding radius, outer radius) [m] of an ASCII STL wheel mesh in the wheel frame
    (centre at the origin, axle along y): the largest vertex distance from the centre, and from
    the axle; None if the mesh cannot be read or has no extent off the axle."""
    r2_centre = r2_axle = 0.0
    try:
        with open(mesh, errors="replace") as f:
            for line in f:
                t = line.split()
                if len(t) == 4 and t[0] == "vertex":
                    x, y, z = float(t[1]), float(t[2]), float(t[3])
                    r2_axle = max(r2_axle, x * x + z * z)
                    r2_centre = max(r2_centre, x * x + y * y + z * z)
    except (OSError, TypeError, ValueError):
        return None
    if r2_axle <= 0:
        return None
    return math.sqrt(r2_centre) * scale, math.sqrt(r2_axle) * scale


def sphere_share(length, width, depth, reach, centres):
    """Mean share of the bed [0, length] x [-width/2, width/2] x [0, depth] inside a sphere of
    radius `reach` about each of `centres` ((x, z) pairs, y = 0): a midpoint rule over the bed's
    footprint of the sphere's chord clipped to [0, depth]."""
    dx, dy = length / GRID_X, width / GRID_Y
    x = (np.arange(GRID_X) + 0.5) * dx
    y = (np.arange(GRID_Y) + 0.5) * dy - 0.5 * width
    shares = []
    for xc, zc in centres:
        r2 = (x[:, None] - xc) ** 2 + y[None, :] ** 2
        half = np.sqrt(np.clip(reach * reach - r2, 0.0, None))
        chord = np.clip(zc + half, 0.0, depth) - np.clip(zc - half, 0.0, depth)
        shares.append(float(chord.sum()) * dx * dy / (length * width * depth))
    return float(np.mean(shares))


def wheel_path(phases, x0, speed, length, samples=TIME_SAMPLES):
    """The wheel centre's x at `samples` instants spread evenly over the simulated time: x0
    through release and settle, then accelerating linearly to `speed` [m/s] over the ramp and
    keeping it through the test; clipped to the bin."""
    total = sum(phases.values())
    return [min(max(x0 + travel(phases, speed, (k + 0.5) * total / samples), 0.0), length)
            for k in range(samples)]


def travel(phases, speed, t):
    """How far [m] the wheel centre has moved at simulated time `t` [s]: nothing through release
    and settle, accelerating linearly to `speed` [m/s] over the ramp, then at that speed."""
    t_hold, ramp = phases["release"] + phases["settle"], phases["ramp"]
    if t <= t_hold:
        return 0.0
    if t <= t_hold + ramp:
        return 0.5 * speed * (t - t_hold) ** 2 / ramp if ramp > 0 else speed * (t - t_hold)
    return 0.5 * speed * ramp + speed * (t - t_hold - ramp)


def travel_speed(rig, slip, outer_radius):
    """The wheel's forward speed [m/s] at `slip` for a rig driven at motor.omega (the rim speed
    omega R, wheelsim_post.slip.forward_speed); an imposed carriage.speed wins. 0 if unknown."""
    carriage = rig.get("carriage", {})
    if isinstance(carriage.get("speed"), (int, float)) and not isinstance(carriage["speed"], bool):
        return abs(float(carriage["speed"]))
    omega = rig.get("motor", {}).get("omega")
    if not isinstance(omega, (int, float)) or isinstance(omega, bool) or slip is None:
        return 0.0
    v = forward_speed(abs(omega) * outer_radius, slip)
    return v if math.isfinite(v) else 0.0


def start_x(deck, liggghts_args=()):
    """The wheel centre's x at the start [m]: `-var x0` in liggghts_args, else the deck's
    `variable x0 index X`, else 0."""
    try:
        return float(deck_variable(deck, "x0", liggghts_args))
    except (TypeError, ValueError):
        return 0.0
