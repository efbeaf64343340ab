"""The grouping keys of a run: wheel, soil, terrain and target slip.

Sources, in order: the sweep driver's ``/parameters/sweep/<key>`` strings, then the fallbacks
of docs/postprocess.md (wheel source or mesh file, DEM bed soil or SCM soil name, the rig
config's ``terrain.type`` and ``carriage.slip``).
"""

import dataclasses
import math
import os
import tomllib

from .choices import parse_choices
from .errors import PostError

#: Keys a run can be grouped by (``--group-by``).
GROUP_KEYS = ("wheel", "soil", "terrain")

UNKNOWN = "unknown"


@dataclasses.dataclass
class RunMetadata:
    """Grouping keys of one run; ``target_slip`` is NaN when the run has none."""

    wheel: str
    soil: str
    terrain: str
    target_slip: float

    def key(self, group_by):
        """The tuple of values of ``group_by`` (names from GROUP_KEYS)."""
        return tuple(getattr(self, name) for name in group_by)


def _rig_config(run):
    """The rig config (``/parameters/rig_config``) parsed with tomllib, or {}."""
    text = run.parameter_text("rig_config")
    if not text:
        return {}
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        return {}


def rig_config(run):
    """The rig config (``/parameters/rig_config``) parsed with tomllib, or {}."""
    return _rig_config(run)


def _stem(path_text):
    """Basename without extension of a path ('meshes/lugged_12.stl' -> 'lugged_12')."""
    return os.path.splitext(os.path.basename(path_text.strip()))[0]


def _wheel(run):
    text = run.parameter_text("sweep/wheel")
    if text:
        return text
    # wheel-rig writes wheel/source as "mesh <path>" or "config" (no mesh: radius only).
    source = run.parameter_text("wheel/source") or ""
    if source.startswith("mesh "):
        return _stem(source[len("mesh ") :])
    mesh_file = run.parameter_text("wheel/mesh_file")
    if mesh_file:
        return _stem(mesh_file)
    return source or UNKNOWN


def _soil(run):
    for name in ("sweep/soil", "bed/soil", "terrain/soil_name"):
        text = run.parameter_text(name)
        if text:
            return text
    return UNKNOWN


def _terrain(run, config):
    text = run.parameter_text("sweep/terrain")
    if text:
        return text
    kind = config.get("terrain", {}).get("type")
    return str(kind) if kind else UNKNOWN


def _target_slip(run, config):
    text = run.parameter_text("sweep/slip")
    if text:
        try:
            return float(text)
        except ValueError:
            raise PostError(
                f"run file '{run.path}': /parameters/sweep/slip is '{text}', "
                "expected a number"
            ) from None
    slip = config.get("carriage", {}).get("slip")
    if isinstance(slip, (int, float)):
        return float(slip)
    return math.nan


def read_metadata(run):
    """The RunMetadata of an open RunFile."""
    config = _rig_config(run)
    return RunMetadata(
        wheel=_wheel(run),
        soil=_soil(run),
        terrain=_terrain(run, config),
        target_slip=_target_slip(run, config),
    )


def parse_group_by(text):
    """``--group-by`` text ('wheel,soil') as a tuple of keys (PostError on unknown ones)."""
    return tuple(parse_choices(text, GROUP_KEYS, "--group-by"))
