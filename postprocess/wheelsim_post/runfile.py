"""Reading wheelsim run files (docs/hdf5-layout.md) with h5py.

Rows with ``step < 0`` (the fill value of rows a crash never wrote) are dropped. The writer
commits ``step``, ``time`` and ``value`` of an observable together (docs/hdf5-layout.md, "Crash
guarantees"), so datasets of one observable that differ in length, or that do not hold numbers,
make a malformed file: PostError naming the observable and what was found.
"""

import dataclasses
import math
import os

import h5py
import numpy as np

from .errors import PostError
from .health import read_health

#: Fields of SCM terrain snapshots (``/terrain/<field>/<step as 9 digits>``), in display
#: order; others the file has follow, sorted.
SNAPSHOT_FIELDS = (
    "height",
    "sinkage",
    "plastic_sinkage",
    "pressure",
    "shear_stress",
    "shear_displacement",
)


@dataclasses.dataclass
class Series:
    """One observable: ``step`` int64[n], ``time`` [s] float64[n], ``value`` [n] or [n][c]."""

    name: str
    step: np.ndarray
    time: np.ndarray
    value: np.ndarray
    unit: str

    def __len__(self):
        return len(self.step)


@dataclasses.dataclass
class Snapshot:
    """One SCM terrain snapshot: ``value[i][j]`` at y = y0 + i*spacing, x = x0 + j*spacing [m]."""

    field: str
    step: int
    time: float
    value: np.ndarray
    unit: str
    x0: float
    y0: float
    spacing: float

    def extent(self):
        """Image extent (left, right, bottom, top) [m] with cells centred on grid points."""
        rows, cols = self.value.shape
        half = 0.5 * self.spacing
        return (
            self.x0 - half,
            self.x0 + (cols - 1) * self.spacing + half,
            self.y0 - half,
            self.y0 + (rows - 1) * self.spacing + half,
        )


def _numbers(dataset, dtype, what):
    """The data of an HDF5 dataset as a ``dtype`` array; PostError starting with ``what`` if it
    holds no numbers (strings, compound records)."""
    if dataset.dtype.kind not in "biuf":
        found = "strings" if dataset.dtype.kind in "OSU" else f"{dataset.dtype} data"
        raise PostError(f"{what} holds {found}, expected numbers")
    if dataset.ndim == 0:
        raise PostError(f"{what} is a scalar, expected one row per sample")
    return np.asarray(dataset[()], dtype=dtype)


def _text(value):
    """An HDF5 string (bytes or str, scalar) as str."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    return str(value)


class RunFile:
    """A run file opened read-only; use as a context manager."""

    def __init__(self, path):
        self.path = str(path)
        if os.path.isdir(self.path):
            raise PostError(f"run file '{self.path}' is a directory, expected an HDF5 file")
        if not os.path.isfile(self.path):
            raise PostError(f"run file '{self.path}' does not exist")
        try:
            self._file = h5py.File(self.path, "r")
        except OSError as exc:
            raise PostError(
                f"cannot open run file '{self.path}' as HDF5: {exc}"
            ) from None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        """Closes the file."""
        self._file.close()

    @property
    def name(self):
        """The file's basename, for messages and tables."""
        return os.path.basename(self.path)

    # Parameters ---------------------------------------------------------------------------

    def has_parameter(self, name):
        """True if ``/parameters/<name>`` is a dataset."""
        obj = self._file.get(f"parameters/{name}")
        return isinstance(obj, h5py.Dataset)

    def parameter(self, name, default=None):
        """``/parameters/<name>`` as str or float/int (``default`` if absent)."""
        if not self.has_parameter(name):
            return default
        data = self._file[f"parameters/{name}"][()]
        if isinstance(data, (bytes, str)):
            return _text(data)
        if isinstance(data, np.ndarray):
            return data
        return data.item() if hasattr(data, "item") else data

    def parameter_text(self, name, default=None):
        """``/parameters/<name>`` as str (numbers formatted with repr), or ``default``."""
        value = self.parameter(name)
        if value is None:
            return default
        return value if isinstance(value, str) else repr(value)

    def parameter_float(self, name):
        """``/parameters/<name>`` as float; PostError naming the file if absent or not a number."""
        value = self.parameter(name)
        try:
            return float(value)
        except (TypeError, ValueError):
            raise PostError(
                f"run file '{self.path}': parameter '/parameters/{name}' "
                f"is missing or not a number (got {value!r})"
            ) from None

    def creator(self):
        """{'name', 'version', 'git_revision'} of /h5md/creator as str ('' where absent)."""
        group = self._file.get("h5md/creator")
        attrs = group.attrs if isinstance(group, h5py.Group) else {}
        return {
            key: _text(attrs[key]) if key in attrs else ""
            for key in ("name", "version", "git_revision")
        }

    def health(self):
        """The rig's health.Health of the run (status 'unchecked' without /health)."""
        return read_health(self._file)

    # Observables --------------------------------------------------------------------------

    def has_observable(self, name):
        """True if ``/observables/<name>`` is a group with a ``value`` dataset."""
        group = self._file.get(f"observables/{name}")
        return isinstance(group, h5py.Group) and "value" in group

    def observable_names(self):
        """Names of all observables (nested names joined with '/'), sorted."""
        names = []
        root = self._file.get("observables")
        if root is None:
            return names

        def visit(name, obj):
            if isinstance(obj, h5py.Group) and "value" in obj and "step" in obj:
                names.append(name)

        root.visititems(visit)
        return sorted(names)

    def observable(self, name):
        """The written rows of ``/observables/<name>`` (PostError if it is missing)."""
        if not self.has_observable(name):
            available = ", ".join(self.observable_names()) or "none"
            raise PostError(
                f"run file '{self.path}' has no observable '{name}' "
                f"(available: {available})"
            )
        group = self._file[f"observables/{name}"]
        where = f"run file '{self.path}': observable '{name}'"
        try:
            step = _numbers(group["step"], np.int64, f"{where}: dataset 'step'")
            time = _numbers(group["time"], np.float64, f"{where}: dataset 'time'")
            value = _numbers(group["value"], np.float64, f"{where}: dataset 'value'")
        except (
            OSError,
            KeyError,
        ) as exc:  # a dataset damaged by a crash inside a flush
            raise PostError(f"{where} cannot be read ({exc})") from None
        if not len(step) == len(time) == len(value):
            raise PostError(
                f"{where} has datasets of different lengths: step {len(step)}, time "
                f"{len(time)}, value {len(value)} rows (expected equal lengths: a malformed "
                "run file)"
            )
        written = step >= 0
        unit = _text(group["value"].attrs.get("unit", "1"))
        return Series(name, step[written], time[written], value[written], unit)

    # Terrain snapshots --------------------------------------------------------------------

    def snapshot_steps(self, field):
        """Steps of the snapshots of ``field`` (sorted; empty if there are none)."""
        group = self._file.get(f"terrain/{field}")
        if not isinstance(group, h5py.Group):
            return []
        steps = []
        for key in group:
            if key.isdigit():
                steps.append(int(key))
        return sorted(steps)

    def snapshot_fields(self):
        """Fields with at least one snapshot, in the order of SNAPSHOT_FIELDS, then others."""
        root = self._file.get("terrain")
        if not isinstance(root, h5py.Group):
            return []
        present = [k for k in root if self.snapshot_steps(k)]
        known = [f for f in SNAPSHOT_FIELDS if f in present]
        return known + sorted(f for f in present if f not in SNAPSHOT_FIELDS)

    def snapshot_time(self, field, step):
        """Time [s] of the snapshot of ``field`` at ``step`` (without reading its grid)."""
        key = f"terrain/{field}/{step:09d}/time"
        if key not in self._file:
            raise PostError(f"run file '{self.path}' has no dataset '/{key}'")
        return float(np.ravel(self._file[key][()])[0])

    def _not_numbers(self, key):
        """The PostError of a snapshot holding a dataset that is not numbers."""
        return PostError(
            f"run file '{self.path}': snapshot '/{key}' holds a dataset that is not "
            "numbers (expected numeric step, time, value, x0, y0, spacing)"
        )

    def snapshot_grid(self, field, step):
        """The grid of the snapshot of ``field`` at ``step``: (shape of its value, x0, y0,
        spacing), checked as ``snapshot`` checks it (PostError if absent or malformed) without
        reading its values, so that a command can check every snapshot before it writes."""
        key = f"terrain/{field}/{step:09d}"
        group = self._file.get(key)
        if not isinstance(group, h5py.Group):
            raise PostError(f"run file '{self.path}' has no snapshot '/{key}'")
        names = ("step", "time", "value", "x0", "y0", "spacing")
        missing = [name for name in names if not isinstance(group.get(name), h5py.Dataset)]
        if missing:
            raise PostError(
                f"run file '{self.path}': snapshot '/{key}' lacks the dataset '{missing[0]}' "
                "(expected step, time, value, x0, y0, spacing)"
            )
        try:
            shape, kind = tuple(group["value"].shape), group["value"].dtype.kind
            x0, y0 = float(group["x0"][()]), float(group["y0"][()])
            spacing = float(group["spacing"][()])
        except (TypeError, ValueError, IndexError):
            kind = None
        if kind is None or kind not in "biuf":
            raise self._not_numbers(key)
        if len(shape) != 2 or 0 in shape:
            raise PostError(
                f"run file '{self.path}': snapshot '/{key}/value' has shape "
                f"{shape}, expected [rows][cols] with rows, cols >= 1"
            )
        if not (math.isfinite(spacing) and spacing > 0.0):
            raise PostError(
                f"run file '{self.path}': snapshot '/{key}' has spacing {spacing:g} m, "
                "expected a finite grid spacing > 0 m"
            )
        for name, origin in (("x0", x0), ("y0", y0)):
            if not math.isfinite(origin):
                raise PostError(
                    f"run file '{self.path}': snapshot '/{key}' has {name} "
                    f"{origin:g} m, expected a finite grid origin"
                )
        return shape, x0, y0, spacing

    def snapshot(self, field, step):
        """The snapshot of ``field`` at ``step`` (PostError if absent or malformed)."""
        _, x0, y0, spacing = self.snapshot_grid(field, step)
        key = f"terrain/{field}/{step:09d}"
        group = self._file[key]
        try:
            value = np.asarray(group["value"][()], dtype=np.float64)
            return Snapshot(
                field=field,
                step=int(np.ravel(group["step"][()])[0]),
                time=float(np.ravel(group["time"][()])[0]),
                value=value,
                unit=_text(group["value"].attrs.get("unit", "1")),
                x0=x0,
                y0=y0,
                spacing=spacing,
            )
        except (TypeError, ValueError, IndexError):
            raise self._not_numbers(key) from None
