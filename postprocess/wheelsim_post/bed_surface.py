"""The free surface of a DEM bed: the highest particle top in each column of a grid over the bin,
as inputs/soilbin/measure.in defines the bed depth that every coupled run reads sinkage against
(docs/postprocess.md, "surface").

The bin spans x in [0, bin_length], y in [-bin_width/2, bin_width/2]; the floor is z = 0. A
column's surface is the largest z + r of the spheres whose centres lie in it. in.soilbin's bed
depth is the mean of these column tops over its own grid (bed_grid); a profile along x is their
mean across y in each column row (profile_x).

The column tops lie above the grains' mean level (0.50-0.63 d_max on the validation beds). The
equivalent surface (equivalent_surface) is the level a bed packed throughout as its core would
have to hold the same solid volume: a Gibbs dividing surface, the level a continuum has.
"""

import math
import re
from dataclasses import dataclass

import numpy as np

from .errors import PostError

__all__ = ["Particles", "read_dump", "parse_deck_line", "bed_grid", "column_grid",
           "column_tops", "profile_x", "volume_above", "EquivalentSurface", "equivalent_surface"]

#: measure.in's grid: columns about 2 d_max wide, at most 20 along x and 10 across.
BED_GRID_MAX = (20, 10)
_DECK_LINE = re.compile(r"^bedsurface: (.*)$", re.MULTILINE)
_DECK_KEYS = ("step", "soil_dmax", "bed_depth", "bin_length", "bin_width")


@dataclass(frozen=True)
class Particles:
    """Sphere centres and radii of one dump [m] at LIGGGHTS step `step`."""

    step: int
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    radius: np.ndarray


def read_dump(path):
    """The spheres of a LIGGGHTS text dump with columns id x y z radius (inputs/in.bed_surface's
    output; the first snapshot only). PostError naming the file on anything else."""
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as exc:
        raise PostError(f"cannot read the particle dump '{path}': {exc.strerror}") from None
    except UnicodeDecodeError as exc:
        raise PostError(f"'{path}' is not a LIGGGHTS text dump (byte 0x{exc.object[exc.start]:02x} "
                        f"at offset {exc.start} is not UTF-8)") from None
    try:
        step = int(lines[lines.index("ITEM: TIMESTEP") + 1])
        count = int(lines[lines.index("ITEM: NUMBER OF ATOMS") + 1])
        head = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    except (ValueError, IndexError, StopIteration):
        raise PostError(f"'{path}' is not a LIGGGHTS text dump (no TIMESTEP, NUMBER OF ATOMS "
                        "and ATOMS items)") from None
    columns = lines[head].split()[2:]
    need = ("x", "y", "z", "radius")
    if any(c not in columns for c in need):
        raise PostError(f"'{path}': the dump's columns are {' '.join(columns)}; expected "
                        f"{' '.join(need)} among them (inputs/in.bed_surface writes id x y z radius)")
    rows = lines[head + 1: head + 1 + count]
    if len(rows) != count:
        raise PostError(f"'{path}': the dump announces {count} atoms but holds {len(rows)} "
                        "(a cut file?)")
    try:
        data = np.array([r.split() for r in rows], dtype=float).reshape(count, len(columns))
    except ValueError:
        raise PostError(f"'{path}': an atom row is not {len(columns)} numbers") from None
    pick = {c: data[:, columns.index(c)] for c in need}
    if not np.all(np.isfinite(data)):
        raise PostError(f"'{path}': the dump holds a non-finite coordinate or radius")
    return Particles(step, pick["x"], pick["y"], pick["z"], pick["radius"])


def parse_deck_line(text, where):
    """{key: value} of in.bed_surface's `bedsurface: step=S soil_dmax=D bed_depth=H
    bin_length=L bin_width=W` line in `text` (its screen output, read from `where`)."""
    found = _DECK_LINE.findall(text)
    if not found:
        raise PostError(f"{where}: no 'bedsurface:' line: inputs/in.bed_surface did not finish "
                        "(its output is above or in that file)")
    values = dict(item.split("=", 1) for item in found[-1].split() if "=" in item)
    try:
        out = {k: float(values[k]) for k in _DECK_KEYS}
    except (KeyError, ValueError):
        raise PostError(f"{where}: the 'bedsurface:' line '{found[-1]}' lacks one of "
                        f"{', '.join(_DECK_KEYS)}") from None
    out["step"] = int(out["step"])
    return out


def _edges(length, count, lo):
    return lo + np.linspace(0.0, length, count + 1)


def bed_grid(bin_length, bin_width, dmax):
    """(x_edges, y_edges) [m] of measure.in's grid: floor(L / 2 d_max) columns along x, clamped
    to [1, 20], and floor(W / 2 d_max) across, clamped to [1, 10]."""
    nx = min(max(math.floor(bin_length / (2 * dmax)), 1), BED_GRID_MAX[0])
    ny = min(max(math.floor(bin_width / (2 * dmax)), 1), BED_GRID_MAX[1])
    return _edges(bin_length, nx, 0.0), _edges(bin_width, ny, -0.5 * bin_width)


def column_grid(bin_length, bin_width, column_m):
    """(x_edges, y_edges) [m] of columns as close to `column_m` wide as the bin allows (at least
    one each way), with no cap on their number."""
    if not column_m > 0:
        raise PostError(f"--column: expected a width > 0 m, got {column_m:g}")
    nx = max(round(bin_length / column_m), 1)
    ny = max(round(bin_width / column_m), 1)
    return _edges(bin_length, nx, 0.0), _edges(bin_width, ny, -0.5 * bin_width)


def column_tops(particles, x_edges, y_edges):
    """[nx, ny] array of the largest z + r among the spheres whose centres lie in each column
    [m]; NaN where a column holds no centre. Centres on a shared edge count in the column above
    it (the last edge closes the grid); centres outside the grid are left out."""
    x, y = particles.x, particles.y
    inside = ((x >= x_edges[0]) & (x <= x_edges[-1]) & (y >= y_edges[0]) & (y <= y_edges[-1]))
    nx, ny = len(x_edges) - 1, len(y_edges) - 1
    ix = np.clip(np.searchsorted(x_edges, x[inside], side="right") - 1, 0, nx - 1)
    iy = np.clip(np.searchsorted(y_edges, y[inside], side="right") - 1, 0, ny - 1)
    tops = np.full(nx * ny, -np.inf)
    np.maximum.at(tops, ix * ny + iy, (particles.z + particles.radius)[inside])
    tops[np.isneginf(tops)] = np.nan
    return tops.reshape(nx, ny)


def profile_x(tops, y_edges, y_band=None):
    """(mean [m], columns used) per row of columns along x: the mean of the column tops whose
    centres lie in y_band = (y_lo, y_hi) [m] (default: every column), empty columns left out.
    A row with no column holding a sphere is NaN with 0 columns."""
    centres = 0.5 * (y_edges[:-1] + y_edges[1:])
    keep = np.ones(centres.size, bool) if y_band is None else (
        (centres >= y_band[0]) & (centres <= y_band[1]))
    if not keep.any():
        raise PostError(f"--y-band {y_band[0]:g},{y_band[1]:g}: no column centre lies in it "
                        f"(column centres at y = {', '.join(f'{c:.4g}' for c in centres)} m)")
    band = tops[:, keep]
    used = np.sum(np.isfinite(band), axis=1)
    with np.errstate(invalid="ignore"):
        mean = np.where(used > 0, np.nansum(band, axis=1) / np.maximum(used, 1), np.nan)
    return mean, used


def volume_above(particles, level):
    """Volume [m^3] of each sphere above the plane z = ``level``: the spherical cap of height
    h = clip(z + r - level, 0, 2 r), pi h^2 (3 r - h) / 3."""
    r = particles.radius
    h = np.clip(particles.z + r - level, 0.0, 2.0 * r)
    return math.pi * h * h * (3.0 * r - h) / 3.0


@dataclass(frozen=True)
class EquivalentSurface:
    """The bed's equivalent surface ``level_m`` [m]: core_top_m + V / (A phi_core), with V the
    solid volume above core_top_m and phi_core the solid fraction between core_bottom_m and
    core_top_m, both over the area A of the interior (x, y) cell the spheres' centres are
    counted in."""

    level_m: float
    core_solid_fraction: float
    core_bottom_m: float
    core_top_m: float
    area_m2: float
    spheres: int


def equivalent_surface(particles, bin_length, bin_width, dmax, bed_depth):
    """The equivalent surface of a bed (EquivalentSurface), over the interior cell in.soilbin
    measures the core bulk density in (x in [d_max, L - d_max], |y| <= W/2 - d_max; soil-bins.md
    "core_bulk_density"), with the core z in [d_max, bed_depth - 2 d_max]. Each sphere whose
    centre lies in the cell counts whole in (x, y) and by its exact volume in z. The overlaps of
    a multisphere clump's spheres count twice, in the core as above it (the ratio holds where
    clumps are alike throughout). PostError when the bed is too small for a core (depth below
    4 d_max, or no interior)."""
    x_lo, x_hi = dmax, bin_length - dmax
    y_hi = 0.5 * bin_width - dmax
    bottom, top = dmax, bed_depth - 2.0 * dmax
    if x_hi <= x_lo or y_hi <= 0.0 or top <= bottom:
        raise PostError(f"bed {bin_length:g} x {bin_width:g} m, {bed_depth:g} m deep, is too small "
                        f"for a core beyond d_max = {dmax:g} m of its walls and 2 d_max of its top "
                        "(needs a depth of at least 4 d_max): no equivalent surface")
    inside = ((particles.x >= x_lo) & (particles.x <= x_hi) & (np.abs(particles.y) <= y_hi))
    cell = Particles(particles.step, particles.x[inside], particles.y[inside],
                     particles.z[inside], particles.radius[inside])
    area = (x_hi - x_lo) * 2.0 * y_hi
    above_top = float(np.sum(volume_above(cell, top)))
    core = float(np.sum(volume_above(cell, bottom))) - above_top
    phi = core / (area * (top - bottom))
    if not phi > 0.0:
        raise PostError(f"no solid between z = {bottom:g} and {top:g} m in the bed's interior: "
                        "no core to measure the equivalent surface against")
    return EquivalentSurface(top + above_top / (area * phi), phi, bottom, top, area,
                             int(np.count_nonzero(inside)))
