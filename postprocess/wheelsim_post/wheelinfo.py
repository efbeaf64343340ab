"""The lug count of a run's wheel, for windows of whole lug passes (docs/postprocess.md).

Sources, in order (the first that gives a number wins):

1. ``--lugs N`` on the command line (0: count whole revolutions);
2. ``/parameters/wheel/lug_count`` (a number), if the run has it;
3. the properties file ``<mesh stem>.props.toml`` that ``wheel-mesh`` writes next to the mesh
   (table ``wheel``: ``lug_count``, ``smooth``), the mesh being ``/parameters/wheel/mesh_file``,
   the path of ``/parameters/wheel/source`` ("mesh <path>") or ``wheel.mesh`` of the rig config
   (relative to ``/parameters/rig_config_file``'s directory);
4. the wheel's name (grouping key ``wheel``) in ``meshes/catalog.toml`` of this checkout
   (``lugs``; an entry without ``lugs`` is smooth).

Otherwise the count is unknown (None) and windows count whole revolutions.
"""

import os
import tomllib

from .metadata import rig_config
from .usage import find_project_root


def _load_toml(path):
    try:
        with open(path, "rb") as stream:
            return tomllib.load(stream)
    except (OSError, tomllib.TOMLDecodeError):
        return None


def _mesh_paths(run):
    """Candidate mesh paths of the run (may not exist)."""
    texts = []
    mesh_file = run.parameter_text("wheel/mesh_file")
    if mesh_file:
        texts.append(mesh_file.strip())
    source = run.parameter_text("wheel/source") or ""
    if source.startswith("mesh "):
        texts.append(source[len("mesh ") :].strip())
    mesh = rig_config(run).get("wheel", {}).get("mesh")
    if isinstance(mesh, str):
        texts.append(mesh)
    bases = [os.path.dirname(os.path.abspath(run.path))]
    config_file = run.parameter_text("rig_config_file")
    if config_file:
        bases.insert(0, os.path.dirname(os.path.abspath(config_file)))
    paths = []
    for text in texts:
        if os.path.isabs(text):
            paths.append(text)
        else:
            paths += [os.path.join(base, text) for base in bases]
    return paths


def _from_props(run):
    for mesh in _mesh_paths(run):
        props_path = os.path.splitext(mesh)[0] + ".props.toml"
        props = _load_toml(props_path) if os.path.isfile(props_path) else None
        wheel = (props or {}).get("wheel", {})
        if wheel.get("smooth") is True:
            return 0, props_path
        if isinstance(wheel.get("lug_count"), int):
            return wheel["lug_count"], props_path
    return None


def _from_catalog(wheel_name):
    root = find_project_root()
    if not root or not wheel_name:
        return None
    path = os.path.join(root, "meshes", "catalog.toml")
    catalog = _load_toml(path) or {}
    for entry in catalog.get("wheel", []):
        if entry.get("name") == wheel_name:
            lugs = entry.get("lugs", 0)
            return (lugs if isinstance(lugs, int) else 0), f"{path} (wheel '{wheel_name}')"
    return None


def lug_count(run, wheel_name=None, override=None):
    """(lug count or None, where it came from) of an open RunFile."""
    if override is not None:
        return override, "--lugs"
    value = run.parameter("wheel/lug_count")
    if isinstance(value, (int, float)) and value >= 0:
        return int(value), "/parameters/wheel/lug_count"
    found = _from_props(run) or _from_catalog(wheel_name)
    if found:
        return found
    return None, "unknown"
