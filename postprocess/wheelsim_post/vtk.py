"""Reading the fix's wheel-surface files (legacy VTK POLYDATA, ASCII; docs/fix-wheel-cosim.md).

Layout written by liggghts_fix/wheel_surface_vtk.cpp: a title line 'wheelsim wheel surface,
step N, time T s', POINTS (world frame, m, pose applied), POLYGONS (triangles) and CELL_DATA
with SCALARS contact_pressure [Pa] and contact_count, one value per triangle.
"""

import dataclasses
import math
import re

import numpy as np

from .errors import PostError


@dataclasses.dataclass
class WheelSurface:
    """Triangles of the wheel surface and their cell data."""

    path: str
    title: str
    step: int
    time: float
    points: np.ndarray  # [n][3] m, world frame
    triangles: np.ndarray  # [m][3] point indices
    cell_data: dict  # name -> float64[m]

    def centroids(self):
        """Triangle centroids [m][3] (m)."""
        return self.points[self.triangles].mean(axis=1)

    def areas(self):
        """Triangle areas [m] (m²)."""
        p = self.points[self.triangles]
        return 0.5 * np.linalg.norm(
            np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1
        )


def _fail(path, what):
    raise PostError(f"VTK file '{path}': {what}")


def _take(tokens, pos, count, path, what):
    if pos + count > len(tokens):
        _fail(path, f"ends inside {what} (expected {count} more values)")
    return tokens[pos : pos + count], pos + count


def read_wheel_surface(path):
    """A WheelSurface from ``path`` (PostError naming the file if it is not in the format)."""
    try:
        with open(path, encoding="utf-8") as src:
            lines = src.read().splitlines()
    except OSError as exc:
        raise PostError(f"--vtk: cannot read '{path}': {exc.strerror}") from None
    except UnicodeDecodeError as exc:
        _fail(path, f"not a text file (byte 0x{exc.object[exc.start]:02x} at offset "
              f"{exc.start} is not UTF-8), expected a legacy ASCII VTK file")
    if len(lines) < 4 or not lines[0].startswith("# vtk DataFile"):
        _fail(path, "not a legacy VTK file (first line '# vtk DataFile Version ...')")
    title = lines[1].strip()
    if lines[2].strip() != "ASCII" or lines[3].split() != ["DATASET", "POLYDATA"]:
        _fail(path, "expected 'ASCII' and 'DATASET POLYDATA' on lines 3 and 4")
    match = re.search(r"step (-?\d+), time (\S+) s", title)
    step = int(match.group(1)) if match else -1
    time = float(match.group(2)) if match else math.nan
    tokens = " ".join(lines[4:]).split()
    points = triangles = None
    cell_data = {}
    cells = None
    pos = 0
    try:
        while pos < len(tokens):
            key = tokens[pos]
            if key == "POINTS":
                n = int(tokens[pos + 1])
                values, pos = _take(tokens, pos + 3, 3 * n, path, "POINTS")
                points = np.array(values, dtype=float).reshape(n, 3)
            elif key == "POLYGONS":
                n, size = int(tokens[pos + 1]), int(tokens[pos + 2])
                values, pos = _take(tokens, pos + 3, size, path, "POLYGONS")
                table = np.array(values, dtype=np.int64)
                if size != 4 * n or np.any(table.reshape(n, 4)[:, 0] != 3):
                    _fail(path, "POLYGONS must be triangles ('3 i j k' per cell)")
                triangles = table.reshape(n, 4)[:, 1:]
            elif key == "CELL_DATA":
                cells = int(tokens[pos + 1])
                pos += 2
            elif key == "SCALARS":
                name = tokens[pos + 1]
                pos += 3
                if tokens[pos].isdigit():  # optional component count
                    pos += 1
                if tokens[pos] == "LOOKUP_TABLE":
                    pos += 2
                if cells is None:
                    _fail(path, f"SCALARS {name} before CELL_DATA")
                values, pos = _take(tokens, pos, cells, path, f"SCALARS {name}")
                cell_data[name] = np.array(values, dtype=float)
            else:
                _fail(path, f"unexpected keyword '{key}'")
    except (ValueError, IndexError):
        _fail(path, "malformed numbers or a truncated section")
    if points is None or triangles is None:
        _fail(path, "needs POINTS and POLYGONS sections")
    if triangles.size and triangles.max() >= len(points):
        _fail(path, "a triangle refers to a point that does not exist")
    if "contact_pressure" not in cell_data:
        _fail(path, "has no cell data 'contact_pressure'")
    if len(cell_data["contact_pressure"]) != len(triangles):
        _fail(path, "contact_pressure has not one value per triangle")
    return WheelSurface(path, title, step, time, points, triangles, cell_data)


def axle_angle(points, centre):
    """Angle θ [deg] of ``points`` [n][3] about the axle (+y) through ``centre``.

    0 straight below the centre, positive towards +x, in (−180, 180].
    """
    return np.degrees(
        np.arctan2(points[..., 0] - centre[0], -(points[..., 2] - centre[2]))
    )


def unrolled_triangles(surface, centre):
    """The triangles in the unrolled plane: [m][3][2] of (θ [deg], y − centre_y [m]).

    A triangle across the ±180° seam keeps its vertices next to its centroid's angle (its
    angles may then pass ±180), so no triangle spans the whole map.
    """
    corners = surface.points[surface.triangles]  # [m][3][3]
    theta = axle_angle(corners, centre)
    theta_c = axle_angle(surface.centroids(), centre)[:, None]
    theta = theta_c + (theta - theta_c + 180.0) % 360.0 - 180.0
    return np.stack([theta, corners[..., 1] - centre[1]], axis=-1)


def unrolled_pressure(surface, centre, angle_edges, y_edges):
    """Area-weighted mean contact pressure [Pa] on an (angle, y) grid: [len(y)-1][len(a)-1].

    Each triangle goes to the bin of its centroid: angle θ [deg] about the axle (+y) through
    ``centre`` (x, y, z) [m], 0 straight below the centre, positive towards +x; y relative to
    the centre. A bin holds Σ p·A / Σ A (the normal force per area); NaN where no triangle lies.
    """
    c = surface.centroids()
    theta = axle_angle(c, centre)
    y = c[:, 1] - centre[1]
    area = surface.areas()
    pressure = surface.cell_data["contact_pressure"]
    force, _, _ = np.histogram2d(
        y, theta, bins=[y_edges, angle_edges], weights=pressure * area
    )
    total, _, _ = np.histogram2d(y, theta, bins=[y_edges, angle_edges], weights=area)
    count, _, _ = np.histogram2d(y, theta, bins=[y_edges, angle_edges])
    with np.errstate(divide="ignore", invalid="ignore"):
        grid = np.where(total > 0.0, force / total, 0.0)
    grid[count == 0] = np.nan
    return grid


def bounding_box_centre(surface):
    """The centre (x, y, z) [m] of the points' bounding box (the wheel centre if symmetric)."""
    return 0.5 * (surface.points.min(axis=0) + surface.points.max(axis=0))
