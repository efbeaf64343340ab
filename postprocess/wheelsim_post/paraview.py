"""ParaView files: Data collections (.pvd) with physical times and VTK XML image data (.vti).

A .pvd lists one file per time (``<DataSet timestep="T" file="F"/>``, T in seconds, F relative
to the .pvd's folder); ParaView opens it as one time series. The layout is the one fix
wheel/cosim writes for its wheel surface (liggghts_fix/wheel_surface_vtk.cpp, ``write_pvd``).
Every file here is written atomically: into ``PATH.tmp``, flushed to disk, renamed over PATH.
"""

import base64
import os
import re
import xml.etree.ElementTree as ET

import numpy as np

from .errors import PostError


def write_atomically(path, text):
    """Writes ``text`` to ``path`` through ``path + '.tmp'`` and a rename (no torn file)."""
    tmp = path + ".tmp"
    try:
        with open(tmp, "w", encoding="utf-8") as out:
            out.write(text)
            out.flush()
            os.fsync(out.fileno())
        os.replace(tmp, path)
    except OSError as exc:
        try:
            os.remove(tmp)
        except OSError:
            pass
        raise PostError(f"cannot write '{path}': {exc.strerror}") from None


def _attr(text):
    """``text`` escaped for an XML attribute value."""
    return (
        text.replace("&", "&amp;")
        .replace("<", "&lt;")
        .replace(">", "&gt;")
        .replace('"', "&quot;")
    )


def pvd_text(entries):
    """The .pvd XML of ``entries``: (time [s], file) pairs, in the given order."""
    lines = [
        '<?xml version="1.0"?>',
        '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
        "  <Collection>",
    ]
    for time, name in entries:
        lines.append(
            f'    <DataSet timestep="{float(time)!r}" group="" part="0" '
            f'file="{_attr(name)}"/>'
        )
    lines += ["  </Collection>", "</VTKFile>", ""]
    return "\n".join(lines)


def write_pvd(path, entries):
    """Writes the collection ``path`` atomically; ``entries``: (time [s], absolute or
    current-directory-relative path) pairs, listed relative to ``path``'s folder."""
    folder = os.path.dirname(os.path.abspath(path))
    rel = [(t, os.path.relpath(os.path.abspath(f), folder)) for t, f in entries]
    write_atomically(path, pvd_text(rel))


def read_pvd(path):
    """(time [s], file as written) pairs of a .pvd (PostError naming the file if malformed)."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise PostError(f"cannot read the collection '{path}': {exc}") from None
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        raise PostError(f"'{path}' is not a ParaView collection (VTKFile type=\"Collection\")")
    entries = []
    for data_set in root.iterfind("./Collection/DataSet"):
        try:
            entries.append((float(data_set.get("timestep")), data_set.get("file")))
        except (TypeError, ValueError):
            raise PostError(
                f"'{path}': a DataSet without a numeric timestep or a file"
            ) from None
    return entries


def step_of_name(name):
    """The step number at the end of a file name's stem (``wheel_surface_2000.vtk`` → 2000),
    or None."""
    match = re.search(r"(\d+)$", os.path.splitext(os.path.basename(name))[0])
    return int(match.group(1)) if match else None


def _binary(values, numpy_type):
    """``values`` as a VTK XML binary (base64, UInt32 byte-count header) inline block."""
    raw = np.ascontiguousarray(values, dtype=numpy_type).tobytes()
    header = np.array([len(raw)], dtype="<u4").tobytes()
    return base64.b64encode(header + raw).decode("ascii")


def vti_text(shape, origin, spacing, point_data, time=None, step=None):
    """A VTK XML ImageData file (one piece, binary base64, little-endian Float64).

    ``shape``: (rows, cols) = points along y and x; ``origin`` (x0, y0, z0) [m], ``spacing``
    [m] (the same in x and y, also given as the z spacing of the flat image); ``point_data``:
    name → float array of ``shape``, row-major (row i at y0 + i*spacing), which is VTK's point
    order (x fastest). ``time`` [s] and ``step`` go into field data (TimeValue, step).
    """
    rows, cols = shape
    extent = f"0 {cols - 1} 0 {rows - 1} 0 0"
    x0, y0, z0 = (float(v) for v in origin)
    d = float(spacing)
    lines = [
        '<?xml version="1.0"?>',
        '<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian" '
        'header_type="UInt32">',
        f'  <ImageData WholeExtent="{extent}" Origin="{x0!r} {y0!r} {z0!r}" '
        f'Spacing="{d!r} {d!r} {d!r}">',
    ]
    if time is not None or step is not None:
        lines.append("    <FieldData>")
        if time is not None:
            lines.append(
                '      <DataArray type="Float64" Name="TimeValue" NumberOfTuples="1" '
                f'format="binary">{_binary([time], "<f8")}</DataArray>'
            )
        if step is not None:
            lines.append(
                '      <DataArray type="Int64" Name="step" NumberOfTuples="1" '
                f'format="binary">{_binary([step], "<i8")}</DataArray>'
            )
        lines.append("    </FieldData>")
    lines.append(f'    <Piece Extent="{extent}">')
    first = next(iter(point_data), None)
    lines.append(f'      <PointData Scalars="{_attr(first)}">' if first else "      <PointData>")
    for name, values in point_data.items():
        values = np.asarray(values, dtype=np.float64)
        if values.shape != (rows, cols):
            raise PostError(f"point data '{name}' has shape {values.shape}, expected {shape}")
        lines.append(
            f'        <DataArray type="Float64" Name="{_attr(name)}" format="binary">'
            f"{_binary(values.ravel(order='C'), '<f8')}</DataArray>"
        )
    lines += ["      </PointData>", "      <CellData/>", "    </Piece>", "  </ImageData>"]
    lines += ["</VTKFile>", ""]
    return "\n".join(lines)
