"""The sweep config (TOML): parsing, validation and the point matrix. Reference: docs/sweeps.md.

Every error is a ConfigError whose message starts with the config file and names the key, e.g.
`sweep.toml: unknown key 'slip'; did you mean 'slips'?` or `sweep.toml: wheels[1]: no mesh ...`.
Relative paths in a config are relative to the file that holds them.
"""

import copy
import difflib
import math
import os
import json
import re
import subprocess
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .estimate import wheel_radius

# The terrain types are wheel-rig's (its registry, read from `wheel-rig --list-keys`: terrains());
# these two have soils of their own kind here: "scm" soil files, "dem" beds (prepared by the
# sweep). Every other type (flat and any new one) takes soils as labels or tables of [terrain] keys.
TOP_KEYS = ("description", "terrain", "base", "override", "wheels", "soils", "slips", "dem",
            "slip_control")
# How a point's slip is imposed (docs/sweeps.md, "Slip control"): "imposed_slip" (the default)
# sets carriage.mode = "imposed_slip" and carriage.slip (driving convention, the carriage follows
# the wheel); "wheel_speed" keeps the base's carriage.mode = "imposed_speed" (carriage speed v)
# and sets motor.omega from the target slip in the signed convention (wheel_omega).
SLIP_CONTROLS = ("imposed_slip", "wheel_speed")
DEM_KEYS = ("np", "bed_np", "deck", "liggghts_args", "budget_h", "checkpoint_every_s",
            "checkpoint_every_steps")
WHEEL_ENTRY_KEYS = ("name", "mesh", "mesh_scale", "mass", "inertia", "density", "effective_radius")
# inputs/in.soilbin variables a DEM bed recipe may set (docs/soil-bins.md); inputs_dir, out_dir
# and restart_file are the driver's.
SOILBIN_VARS = ("bin_length", "bin_width", "fill_height", "fill_solid_fraction", "insert_fraction",
                "seed", "ke_threshold", "check_time", "max_settle_time", "compaction",
                "plate_pressure", "plate_speed", "plate_time", "drop_height", "drop_stroke",
                "drop_count", "drop_rest", "thermo_every", "steel_E", "steel_nu", "wall_mu",
                "wheel_mu", "wall_kcoh", "wheel_kcoh_ratio", "pour_mu", "tile_length",
                "tile_relax_time", "tile_end_zone", "tile_relax_max")
# Tiled beds (docs/soil-bins.md "Tiled beds"): how a bed is prepared, not what it is; a bed whose
# recorded recipe differs from the config's in these keys only is prepared again (runner.py).
TILE_VARS = ("tile_length", "tile_relax_time", "tile_end_zone", "tile_relax_max")
MESH_SUFFIXES = (".stl", ".obj", ".ply")
LABEL_RE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.+-]*$")


class ConfigError(Exception):
    """A bad sweep config; the message names the file and the key."""


@dataclass
class Wheel:
    label: str
    mesh: Path  # absolute
    keys: dict  # further [wheel] keys of this entry (mass, inertia, ...)


@dataclass
class Soil:
    label: str  # the point directories' name
    name: str = ""  # the soil name of the run files (sweep/soil) and the manifest; soil_name()
    terrain_keys: dict = field(default_factory=dict)  # scm/flat: [terrain] keys of this soil
    soil_file: Path | None = None  # scm: the soil file
    restart: Path | None = None  # dem: the bed restart (prepared if recipe is set)
    recipe: dict | None = None  # dem: in.soilbin variables incl. soil or soil_file; None = a bed
    dem_soil_file: Path | None = None  # dem: the soil include file of the bed (None: not known)
    dem_soil_name: str = ""  # dem recipe: the file's soil_name (names the bed's restart)


@dataclass
class Point:
    index: int
    wheel: Wheel
    soil: Soil
    slip: float
    reldir: str  # wheel/soil/s<slip>, relative to the output directory
    rig: dict  # the point's rig config
    setting: str = ""  # what the driver set to impose the slip, for the listing and rig.toml


@dataclass
class Sweep:
    path: Path
    terrain: str
    description: str
    wheels: list
    soils: list
    slips: list
    points: list
    np: int = 1
    bed_np: int = 1
    deck: Path | None = None
    liggghts_args: list = field(default_factory=list)
    budget_h: float | None = None  # dem.budget_h: refuse a sweep estimated longer (estimate.py)
    # dem.checkpoint_every_s / _steps: wheel-cosim's checkpoint interval (None: its default);
    # not part of a point's inputs (a checkpoint changes no result)
    checkpoint_every_s: float | None = None
    checkpoint_every_steps: int | None = None
    slip_control: str = "imposed_slip"  # SLIP_CONTROLS


def _suggest(key, allowed):
    close = difflib.get_close_matches(key, allowed, n=1)
    return f"; did you mean '{close[0]}'?" if close else f"; expected one of {', '.join(allowed)}"


class _Ctx:
    def __init__(self, path):
        self.path = path
        self.dir = path.parent

    def err(self, msg):
        return ConfigError(f"{self.path}: {msg}")

    def check_keys(self, table, allowed, where):
        for k in table:
            if k not in allowed:
                name = f"{where}.{k}" if where else k
                raise self.err(f"unknown key '{name}'{_suggest(k, list(allowed))}")

    def path_of(self, value, key, base_dir=None):
        if not isinstance(value, str) or not value:
            raise self.err(f"{key} must be a non-empty path string, got {value!r}")
        p = Path(os.path.expanduser(value))
        return p if p.is_absolute() else (base_dir or self.dir) / p

    def existing(self, p, key, what):
        if not p.is_file():
            raise self.err(f"{key}: {what} '{p}' not found")
        return p.resolve()

    def number(self, v, key):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise self.err(f"{key} must be a finite number, got {v!r}")
        return float(v)

    def label(self, v, key):
        if not isinstance(v, str) or not LABEL_RE.match(v):
            raise self.err(f"{key} must be a name of letters, digits, '_', '.', '+', '-' "
                           f"(used as a directory name), got {v!r}")
        return v


def _looks_like_path(s, suffixes):
    return "/" in s or s.lower().endswith(suffixes)


def _deep_merge(base, over):
    out = copy.deepcopy(base)
    for k, v in over.items():
        if isinstance(v, dict) and isinstance(out.get(k), dict):
            out[k] = _deep_merge(out[k], v)
        else:
            out[k] = copy.deepcopy(v)
    return out


_SCHEMAS = {}


def _rig_schema(build_dir):
    """The schema `<build>/bin/wheel-rig --list-keys` prints (docs/rig-config.md, "The schema and
    the registries"), as {"keys": {table: (key, ...)}, "terrains": (name, ...)}: the keys and the
    terrain types are declared once, in wheel-rig. Read once per executable."""
    rig = Path(build_dir) / "bin" / "wheel-rig"
    if rig not in _SCHEMAS:
        how = f"build it: cmake --build {build_dir} --target wheel-rig"
        if not rig.is_file():
            raise ConfigError(f"{rig} not found: the terrain types and the [override] keys are "
                              f"read from its --list-keys ({how})")
        try:
            r = subprocess.run([str(rig), "--list-keys"], capture_output=True, text=True,
                               timeout=60)
            schema = json.loads(r.stdout) if r.returncode == 0 else None
        except (OSError, subprocess.TimeoutExpired, json.JSONDecodeError):
            schema = None
        if (not isinstance(schema, dict) or not isinstance(schema.get("keys"), list)
                or not isinstance(schema.get("terrain_types"), dict)):
            raise ConfigError(f"{rig} --list-keys did not print the rig-config schema (JSON "
                              f"with keys and terrain_types); an older wheel-rig? ({how})")
        keys = {t: [] for t in schema.get("tables", ())}
        for k in schema["keys"]:
            if k["key"] not in keys.setdefault(k["table"], []):
                keys[k["table"]].append(k["key"])
        _SCHEMAS[rig] = {"keys": {t: tuple(v) for t, v in keys.items()},
                         "terrains": tuple(schema["terrain_types"])}
    return _SCHEMAS[rig]


def rig_keys(build_dir):
    """{table: (key, ...)} of the rig config, from wheel-rig's schema (_rig_schema)."""
    return _rig_schema(build_dir)["keys"]


def terrains(build_dir):
    """The terrain types wheel-rig registers (terrain.type values, in its order), from its
    schema (_rig_schema)."""
    return _rig_schema(build_dir)["terrains"]


def _check_rig_tables(ctx, doc, where, build_dir=None):
    """The rig tables of `doc` (base file or [override]); relative paths made absolute. Keys are
    checked for [override] only (against wheel-rig's schema, from `build_dir`): the base is a rig
    config that wheel-rig checks itself."""
    if not isinstance(doc, dict):
        raise ctx.err(f"{where} must be a table of rig-config tables")
    for t, v in (doc.items() if build_dir is not None else ()):
        name = f"{where}.{t}" if where else t
        try:
            keys = rig_keys(build_dir)
        except ConfigError as e:
            raise ctx.err(f"{where}: {e}")
        if t not in keys:
            raise ctx.err(f"unknown table '{name}'{_suggest(t, list(keys))}")
        if not isinstance(v, dict):
            raise ctx.err(f"'{name}' must be a table")
        ctx.check_keys(v, keys[t], name)
    for t, k in (("wheel", "mesh"), ("terrain", "soil")):
        if k in doc.get(t, {}):
            doc[t][k] = str(ctx.path_of(doc[t][k], f"{where + '.' if where else ''}{t}.{k}")
                            .resolve())
    return doc


def _load_toml(path, ctx_for_errors=None):
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except FileNotFoundError:
        raise (ctx_for_errors.err(f"base: rig config '{path}' not found") if ctx_for_errors
               else ConfigError(f"{path}: not found"))
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"{path}: TOML syntax error: {e}")
    except UnicodeDecodeError as e:
        raise ConfigError(f"{path}: not a TOML file: byte {e.object[e.start]:#04x} at offset "
                          f"{e.start} is not UTF-8 text (TOML files are UTF-8)")
    except IsADirectoryError:
        raise ConfigError(f"{path}: is a directory, not a TOML file")


def _wheels(ctx, entries, terrain, build_dir):
    if not isinstance(entries, list) or not entries:
        raise ctx.err("wheels must be a non-empty array of wheel names, mesh paths or tables")
    mesh_dir = build_dir / "meshes"
    out = []
    for i, e in enumerate(entries):
        key = f"wheels[{i}]"
        keys = {}
        if isinstance(e, dict):
            ctx.check_keys(e, WHEEL_ENTRY_KEYS, key)
            keys = {k: v for k, v in e.items() if k not in ("name", "mesh")}
            name = e.get("name")
            mesh_spec = e.get("mesh", name)
            if name is None and mesh_spec is None:
                raise ctx.err(f"{key} needs 'name' (a catalogue wheel or a label) or 'mesh'")
        elif isinstance(e, str) and e:
            name, mesh_spec = None, e
        else:
            raise ctx.err(f"{key} must be a wheel name, a mesh path or a table, got {e!r}")
        if not isinstance(mesh_spec, str) or not mesh_spec:
            raise ctx.err(f"{key}.mesh must be a non-empty string, got {mesh_spec!r}")
        if _looks_like_path(mesh_spec, MESH_SUFFIXES):
            mesh = ctx.existing(ctx.path_of(mesh_spec, key), key, "mesh")
        else:
            mesh = mesh_dir / f"{mesh_spec}.stl"
            if not mesh.is_file():
                known = sorted(p.stem for p in mesh_dir.glob("*.stl")) if mesh_dir.is_dir() else []
                hint = (f"known: {', '.join(known)}" if known else
                        "build them with `cmake --build BUILD --target wheel_meshes`")
                raise ctx.err(f"{key}: no catalogue wheel '{mesh_spec}' ({mesh} not found; {hint})")
            mesh = mesh.resolve()
        if terrain == "dem" and mesh.suffix.lower() != ".stl":
            raise ctx.err(f"{key}: DEM runs need an STL mesh (LIGGGHTS reads STL), got '{mesh}'")
        label = ctx.label(name if name is not None else Path(mesh_spec).stem,
                          f"{key}.name" if name is not None else key)
        out.append(Wheel(label, mesh, keys))
    return out


def soil_name(soil_file=None, bed_vars=None, default=""):
    """The soil name a direct run records for this soil, so that a sweep's runs group with
    direct runs of the same soil (wheelsim-post --group-by soil): wheel-rig writes an SCM soil
    file's `name` as /parameters/terrain/soil_name, wheel-cosim writes a bed's `soil` variable
    (its .vars file) as /parameters/bed/soil. `default` when the file does not say."""
    if soil_file is not None:
        try:
            with open(soil_file, "rb") as f:
                name = tomllib.load(f).get("name")
        except (OSError, tomllib.TOMLDecodeError):
            name = None  # wheel-rig reports a bad soil file when the point runs
        return name if isinstance(name, str) and name else default
    if bed_vars is not None:
        try:
            for line in Path(bed_vars).read_text().splitlines():
                f = line.split()
                if len(f) >= 4 and f[0] == "variable" and f[1] == "soil":
                    return f[3]
        except OSError:
            pass
    return default


DEM_SOIL_SUFFIXES = (".in",)
_SOIL_NAME_RE = re.compile(r"^\s*variable\s+soil_name\s+(?:string|index)\s+(\S+)", re.M)


def dem_soil_name(soil_in):
    """The `soil_name` a DEM soil include file defines (`variable soil_name string NAME`), the
    name in.soilbin gives its bed and log files; None when the file does not say."""
    try:
        m = _SOIL_NAME_RE.search(Path(soil_in).read_text(errors="replace"))
    except OSError:
        return None
    return m.group(1).strip('"\'') if m else None


def bed_vars(bed_vars_file, key):
    """The value of `variable KEY <style> VALUE` in a bed's .vars file, or None."""
    try:
        for line in Path(bed_vars_file).read_text().splitlines():
            f = line.split()
            if len(f) >= 4 and f[0] == "variable" and f[1] == key:
                return f[3]
    except OSError:
        pass
    return None


def _bed_soil_file(ctx, vars_file, key):
    """The soil file a prepared bed was made with (soil_file in its .vars; None for a bed made
    before in.soilbin recorded it); an error if it has gone."""
    f = bed_vars(vars_file, "soil_file")
    if f is not None and not Path(f).is_file():
        raise ctx.err(f"{key}: the bed's soil file '{f}' (soil_file in '{vars_file}') not found; "
                      "resuming the bed needs it")
    return Path(f) if f is not None else None


def _dem_recipe_soil(ctx, e, key, repo):
    """A bin recipe's soil: `soil = "NAME"` (inputs/soils/NAME.in), or a soil include file by
    path: `soil = "path/my_sand.in"` (a value with '/' or ending in .in) or `soil_file = "..."`,
    relative to the config file. Returns (file, its soil_name, the key used, recipe entries)."""
    if "soil" in e and "soil_file" in e:
        raise ctx.err(f"{key}: give 'soil' (a name or a soil file) or 'soil_file', not both")
    k = "soil_file" if "soil_file" in e else "soil"
    spec = e[k]
    if not isinstance(spec, str) or not spec:
        raise ctx.err(f"{key}.{k} must be a non-empty string, got {spec!r}")
    if k == "soil_file" or _looks_like_path(spec, DEM_SOIL_SUFFIXES):
        f = ctx.path_of(spec, f"{key}.{k}")
        if not f.is_file():
            raise ctx.err(f"{key}.{k}: DEM soil file '{f}' not found")
        f = f.resolve()
        name = dem_soil_name(f)
        if name is None:
            raise ctx.err(f"{key}.{k}: soil file '{f}' does not define variable soil_name "
                          "(`variable soil_name string NAME`: names the bed; docs/soils.md, "
                          "\"Writing your own soil file\")")
        return f, name, k, {"soil_file": str(f)}
    f = repo / "inputs" / "soils" / f"{spec}.in"
    if not f.is_file():
        d = f.parent
        known = sorted(p.stem for p in d.glob("*.in")) if d.is_dir() else []
        raise ctx.err(f"{key}.soil: no DEM soil '{spec}' ({f} not found"
                      + (f"; known: {', '.join(known)}" if known else "")
                      + "; your own soil file: soil = \"path/to/my_sand.in\")")
    return f, spec, k, {"soil": spec}


def _soils(ctx, entries, terrain, repo):
    if entries is None:
        if terrain not in ("scm", "dem"):  # one soil, the type's [terrain] keys of the base
            return [Soil(terrain)]
        raise ctx.err(f"missing key 'soils' (required for terrain = \"{terrain}\")")
    if not isinstance(entries, list) or not entries:
        raise ctx.err("soils must be a non-empty array")
    out = []
    for i, e in enumerate(entries):
        key = f"soils[{i}]"
        if terrain not in ("scm", "dem"):  # flat and any other registered type
            if isinstance(e, str):
                out.append(Soil(ctx.label(e, key), name=e))
            elif isinstance(e, dict):
                if "name" not in e:
                    raise ctx.err(f"{key} needs 'name'")
                tk = {k: v for k, v in e.items() if k != "name"}
                if "type" in tk:
                    raise ctx.err(f"{key}.type: the terrain type is the top-level key 'terrain'")
                out.append(Soil(ctx.label(e["name"], f"{key}.name"), name=e["name"],
                                terrain_keys=tk))
            else:
                raise ctx.err(f"{key} must be a label or a table of [terrain] keys, got {e!r}")
        elif terrain == "scm":
            if isinstance(e, str):
                spec, name, tk = e, None, {}
            elif isinstance(e, dict):
                spec, name = e.get("soil", e.get("name")), e.get("name")
                if spec is None:
                    raise ctx.err(f"{key} needs 'soil' (a soil name or file) or 'name'")
                tk = {k: v for k, v in e.items() if k not in ("name", "soil")}
                if "type" in tk:
                    raise ctx.err(f"{key}.type: the terrain type is the top-level key 'terrain'")
            else:
                raise ctx.err(f"{key} must be an SCM soil name, a soil file or a table, got {e!r}")
            if not isinstance(spec, str) or not spec:
                raise ctx.err(f"{key}.soil must be a non-empty string, got {spec!r}")
            if _looks_like_path(spec, (".toml",)):
                f = ctx.existing(ctx.path_of(spec, key), key, "SCM soil file")
            else:
                f = repo / "inputs" / "scm_soils" / f"{spec}.toml"
                if not f.is_file():
                    d = f.parent
                    known = sorted(p.stem for p in d.glob("*.toml")) if d.is_dir() else []
                    raise ctx.err(f"{key}: no SCM soil '{spec}' ({f} not found"
                                  + (f"; known: {', '.join(known)})" if known else ")"))
            label = ctx.label(name if name is not None else Path(spec).stem,
                              f"{key}.name" if name is not None else key)
            out.append(Soil(label, name=name if name is not None else soil_name(f, default=label),
                            terrain_keys=tk, soil_file=f.resolve()))
        else:  # dem: beds
            if isinstance(e, str):
                p = ctx.path_of(e, key)
                if not p.is_file():
                    raise ctx.err(f"{key}: bed restart '{p}' not found (a soil name alone is not "
                                  "a bed: give a recipe table, e.g. { soil = \"ci\", bin_length = "
                                  "0.36, bin_width = 0.12, fill_height = 0.035 })")
                if not Path(f"{p}.vars").is_file():
                    raise ctx.err(f"{key}: '{p}.vars' not found (written by inputs/in.soilbin)")
                label = ctx.label(p.stem, key)
                out.append(Soil(label, name=soil_name(bed_vars=f"{p}.vars", default=label),
                                restart=p.resolve(),
                                dem_soil_file=_bed_soil_file(ctx, f"{p}.vars", key)))
            elif isinstance(e, dict):
                ctx.check_keys(e, ("name", "soil", "soil_file", "restart") + SOILBIN_VARS, key)
                recipe = {k: v for k, v in e.items()
                          if k not in ("name", "restart", "soil", "soil_file")}
                for k, v in recipe.items():
                    if isinstance(v, bool) or not isinstance(v, (int, float, str)):
                        raise ctx.err(f"{key}.{k} must be a number or a string, got {v!r}")
                _check_recipe_values(ctx, recipe, key)
                _check_tile_keys(ctx, recipe, key)
                restart = ctx.path_of(e["restart"], f"{key}.restart") if "restart" in e else None
                if "soil" in e or "soil_file" in e:
                    soil_in, dem_name, k, soil_entry = _dem_recipe_soil(ctx, e, key, repo)
                    recipe = {**soil_entry, **recipe}
                    label = ctx.label(e.get("name", dem_name),
                                      f"{key}.name" if "name" in e else f"{key}.{k}")
                    out.append(Soil(label, name=label, restart=restart, recipe=recipe,
                                    dem_soil_file=soil_in, dem_soil_name=dem_name))
                else:
                    if restart is None:
                        raise ctx.err(f"{key} needs 'soil' (a bin recipe: a soil name or a soil "
                                      "file) or 'restart' (a bed)")
                    if len(recipe):
                        raise ctx.err(f"{key}: bin variables ({', '.join(recipe)}) need 'soil'")
                    ctx.existing(restart, f"{key}.restart", "bed restart")
                    if not Path(f"{restart}.vars").is_file():
                        raise ctx.err(f"{key}.restart: '{restart}.vars' not found")
                    label = ctx.label(e.get("name", restart.stem),
                                      f"{key}.name" if "name" in e else f"{key}.restart")
                    name = e.get("name") or soil_name(bed_vars=f"{restart}.vars", default=label)
                    out.append(Soil(label, name=name, restart=restart.resolve(),
                                    dem_soil_file=_bed_soil_file(ctx, f"{restart}.vars",
                                                                 f"{key}.restart")))
            else:
                raise ctx.err(f"{key} must be a bed restart path or a bin recipe table, got {e!r}")
    return out


# Ranges of the bin recipe's in.soilbin variables, checked before anything runs (the deck would
# stop on some of them only after mpirun started; others it would take): name -> (lower bound,
# bound excluded, upper bound or None, integer, unit, what it is).
RECIPE_RANGES = {
    "bin_length": (0.0, True, None, False, "m", "the bin's inner length"),
    "bin_width": (0.0, True, None, False, "m", "the bin's inner width"),
    "fill_height": (0.0, True, None, False, "m", "the intended settled bed depth"),
    "fill_solid_fraction": (0.0, True, 1.0, False, "", "the solid fraction assumed for fill_height"),
    "insert_fraction": (0.0, True, 1.0, False, "", "the insertion cloud's solid fraction"),
    "ke_threshold": (0.0, True, None, False, "", "the settling criterion KE / (M g d_ref)"),
    "check_time": (0.0, True, None, False, "s", "how often the criterion is checked"),
    "max_settle_time": (0.0, True, None, False, "s", "the bound of the settling"),
    "plate_pressure": (0.0, True, None, False, "Pa", "the compaction plate's pressure"),
    "plate_speed": (0.0, True, None, False, "m/s", "the compaction plate's speed"),
    "plate_time": (0.0, True, None, False, "s", "the time under the compaction plate"),
    "drop_height": (0.0, True, None, False, "m", "the drop's free-fall height"),
    "drop_stroke": (0.0, True, None, False, "d_ref", "the penetration per blow"),
    "drop_count": (1, False, None, True, "", "the number of blows"),
    "drop_rest": (0.0, False, None, False, "s", "the pause after each blow"),
    "thermo_every": (1, False, None, True, "steps", "the thermo interval"),
    "steel_E": (0.0, True, None, False, "Pa", "the walls' Young's modulus"),
    "steel_nu": (0.0, False, 0.5, False, "", "the walls' Poisson ratio"),
    "wall_mu": (0.0, False, None, False, "", "the wall friction"),
    "wheel_mu": (0.0, False, None, False, "", "the wheel friction"),
    "wall_kcoh": (0.0, False, None, False, "", "the wall cohesion"),
    "wheel_kcoh_ratio": (0.0, False, None, False, "", "the wheel's share of the soil's cohesion"),
}
COMPACTIONS = ("none", "plate", "drop")


def _is_prime(n):
    return n > 1 and all(n % k for k in range(2, math.isqrt(n) + 1))


def _check_recipe_values(ctx, recipe, key):
    """The values of a bin recipe's in.soilbin variables (RECIPE_RANGES, compaction, seed,
    pour_mu), each named with what it is when out of range."""
    for k, (lo, strict, hi, integer, unit, what) in RECIPE_RANGES.items():
        if k not in recipe:
            continue
        v = recipe[k]
        number = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
        ok = number and (v > lo if strict else v >= lo) and (hi is None or v < hi) and \
            (not integer or float(v).is_integer())
        if not ok:
            kind = "an integer" if integer else "a number"
            rng = f"{'>' if strict else '>='} {lo:g}" + (f" and < {hi:g}" if hi is not None else "")
            raise ctx.err(f"{key}.{k} must be {kind} {rng}{' ' + unit if unit else ''} ({what}), "
                          f"got {v!r}")
    if "compaction" in recipe and recipe["compaction"] not in COMPACTIONS:
        raise ctx.err(f"{key}.compaction must be one of {', '.join(COMPACTIONS)}, got "
                      f"{recipe['compaction']!r}")
    if "seed" in recipe:
        v = recipe["seed"]
        if not (isinstance(v, int) and not isinstance(v, bool) and v > 10000 and _is_prime(v)):
            raise ctx.err(f"{key}.seed must be a prime integer > 10000 (LIGGGHTS' insertion "
                          f"seed), got {v!r}")
    if "pour_mu" in recipe:
        v = recipe["pour_mu"]
        if not (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                and (v >= 0 or v == -1)):
            raise ctx.err(f"{key}.pour_mu must be a friction >= 0, or -1 (off), got {v!r}")


def _check_tile_keys(ctx, recipe, key):
    """A recipe's tiled-bed keys (in.soilbin's tile_check.in repeats the checks that need the
    soil): tile_length a number > 0 m, the relaxation keys numbers >= 0 (tile_relax_max > 0),
    only with tile_length, and no compaction with it."""
    for k, lo, strict, unit, what in (
            ("tile_length", 0.0, True, "m", "the length of the block settled periodic in x and "
             "tiled along the bin; leave the key out to settle the whole bin"),
            ("tile_relax_time", 0.0, False, "s", "the relaxation at the end walls before the "
             "settling criterion is checked"),
            ("tile_end_zone", 0.0, False, "d_max", "how far from the end walls grains move in "
             "the first relaxation; 0: all grains"),
            ("tile_relax_max", 0.0, True, "s", "the bound of each relaxation stage")):
        if k not in recipe:
            continue
        v = recipe[k]
        ok = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and \
            (v > lo if strict else v >= lo)
        if not ok:
            raise ctx.err(f"{key}.{k} must be a number {'>' if strict else '>='} {lo:g} {unit} "
                          f"({what}), got {v!r}")
    if "tile_length" not in recipe:
        extra = [k for k in TILE_VARS if k in recipe]
        if extra:
            raise ctx.err(f"{key}: {', '.join(extra)} only apply to a tiled bed: add tile_length")
        return
    comp = recipe.get("compaction", "none")
    if comp != "none":
        raise ctx.err(f"{key}.tile_length needs compaction = \"none\" (got {comp!r}): a compacted "
                      "bed is settled whole (leave tile_length out)")


def _slips(ctx, entries, slip_control="imposed_slip"):
    wheel_speed = slip_control == "wheel_speed"
    rng = "[-1, 1) (signed convention)" if wheel_speed else "[-1, 1]"
    if not isinstance(entries, list) or not entries:
        raise ctx.err(f"slips must be a non-empty array of numbers in {rng}")
    out = []
    for i, v in enumerate(entries):
        s = ctx.number(v, f"slips[{i}]")
        if wheel_speed and not -1.0 <= s < 1.0:
            raise ctx.err(f"slips[{i}] must be in [-1, 1) with slip_control = \"wheel_speed\" "
                          "(signed convention: 0 <= s < 1 driving, -1 <= s < 0 skid, -1 a locked "
                          f"wheel; s = 1 would need an infinite wheel speed), got {v!r}")
        if not -1.0 <= s <= 1.0:
            raise ctx.err(f"slips[{i}] must be in [-1, 1], got {v!r}")
        if s in out:
            raise ctx.err(f"slips[{i}]: slip {v!r} appears twice")
        out.append(s)
    return out


def wheel_omega(slip, speed, r_eff):
    """The wheel speed ω [rad/s] that gives the target slip `slip` (signed convention, DESIGN.md
    §5) at carriage speed `speed` v [m/s] > 0 and effective radius `r_eff` [m] > 0:
    driving, 0 <= s < 1, s = 1 - v/(ω R_eff): ω = v / ((1 - s) R_eff);
    skid, -1 <= s < 0, s = (ω R_eff - v)/v: ω = v (1 + s) / R_eff (s = -1: ω = 0, locked).
    ValueError for s outside [-1, 1) or v, R_eff not > 0."""
    if not (isinstance(slip, (int, float)) and -1.0 <= slip < 1.0):
        raise ValueError(f"slip must be in [-1, 1) (signed convention), got {slip!r}")
    if not (isinstance(speed, (int, float)) and speed > 0 and math.isfinite(speed)):
        raise ValueError(f"carriage speed must be > 0 m/s, got {speed!r}")
    if not (isinstance(r_eff, (int, float)) and r_eff > 0 and math.isfinite(r_eff)):
        raise ValueError(f"effective radius must be > 0 m, got {r_eff!r}")
    if slip >= 0.0:
        return speed / ((1.0 - slip) * r_eff)
    return speed * (1.0 + slip) / r_eff


def _wheel_speed_base(ctx, rig):
    """slip_control = "wheel_speed": the base (with [override]) must impose the carriage speed:
    carriage.mode = "imposed_speed", carriage.speed > 0 m/s, no motor.torque. Returns v [m/s]."""
    c = rig.get("carriage", {})
    mode = c.get("mode")
    if mode != "imposed_speed":
        got = f"carriage.mode = \"{mode}\"" if mode is not None else "no carriage.mode"
        raise ctx.err(f"slip_control = \"wheel_speed\" needs carriage.mode = \"imposed_speed\" "
                      f"(the carriage speed v imposed, the wheel speed set per point) in the base "
                      f"rig config or [override.carriage], got {got}")
    if "speed" not in c:
        raise ctx.err("slip_control = \"wheel_speed\" needs carriage.speed (the carriage speed "
                      "v [m/s], > 0) in the base rig config or [override.carriage]")
    v = c["speed"]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not (v > 0 and math.isfinite(v)):
        raise ctx.err(f"carriage.speed must be > 0 m/s with slip_control = \"wheel_speed\" "
                      f"(forward travel; the slips are defined for v > 0), got {v!r}")
    if "torque" in rig.get("motor", {}):
        raise ctx.err("slip_control = \"wheel_speed\" sets motor.omega per point; the base rig "
                      "config has motor.torque (remove it)")
    return float(v)


def _point_r_eff(ctx, rig, wheel):
    """R_eff [m] of a point: the wheel entry's or base's wheel.effective_radius, else the mesh's
    outer radius (the rig's default: largest vertex distance from the axle x mesh_scale)."""
    r = wheel_radius(rig, str(wheel.mesh))
    if r is None or not r > 0:
        raise ctx.err(f"wheels: '{wheel.label}': slip_control = \"wheel_speed\" needs R_eff to "
                      f"set motor.omega: give effective_radius [m] in the wheel entry or the base's "
                      f"[wheel] (the outer radius of '{wheel.mesh}' could not be read: an ASCII STL "
                      "is needed for that)")
    return r


def slip_dirname(slip, slips):
    """s0.300 style; more digits when three decimals do not tell the slips apart."""
    for fmt in (".3f", ".6f", "r"):
        names = {(repr(s) if fmt == "r" else format(s, fmt)) for s in slips}
        if len(names) == len(slips):
            return "s" + (repr(slip) if fmt == "r" else format(slip, fmt))
    raise AssertionError("unreachable")


def _unique(ctx, items, key):
    seen = set()
    for it in items:
        if it.label in seen:
            raise ctx.err(f"{key}: two entries are named '{it.label}' (give one a 'name')")
        seen.add(it.label)
    names = {}
    for i, it in enumerate(items):
        name = getattr(it, "name", it.label)
        if name in names:
            raise ctx.err(f"{key}[{names[name]}] and {key}[{i}] have the same soil name "
                          f"'{name}' (their files say so): their runs could not be told apart; "
                          "give one a 'name'")
        names[name] = i


def load(path, repo, build_dir):
    """Parse and validate a sweep config; returns a Sweep with its points (wheel-major order)."""
    path = Path(path).resolve()
    ctx = _Ctx(path)
    if not path.is_file():
        raise ConfigError(f"{path}: sweep config not found")
    doc = _load_toml(path)
    ctx.check_keys(doc, TOP_KEYS, "")
    for k in ("terrain", "wheels", "slips"):
        if k not in doc:
            raise ctx.err(f"missing key '{k}'")
    terrain = doc["terrain"]
    try:
        known = terrains(build_dir)
    except ConfigError as e:
        raise ctx.err(f"terrain: {e}")
    if terrain not in known:
        raise ctx.err(f"terrain must be one of {', '.join(known)} (wheel-rig's terrain types), "
                      f"got {terrain!r}")
    description = doc.get("description", "")
    if not isinstance(description, str):
        raise ctx.err("description must be a string")

    # The base rig config: the file, then [override] on top.
    rig = {}
    if "base" in doc:
        bpath = ctx.path_of(doc["base"], "base")
        bctx = _Ctx(bpath.resolve())
        rig = _check_rig_tables(bctx, _load_toml(bpath, ctx), "")
    if "override" in doc:
        over = _check_rig_tables(ctx, copy.deepcopy(doc["override"]), "override", build_dir)
        # A terrain switch (override.terrain.type other than the base's): the base's [terrain]
        # keys belong to its type, so the override's [terrain] replaces it instead of merging
        # (the same rig on another terrain without a second rig file).
        switch = over.get("terrain", {}).get("type")
        base_terrain = rig.get("terrain")
        if (switch is not None and isinstance(base_terrain, dict)
                and base_terrain.get("type") not in (None, switch)):
            rig.pop("terrain")
        rig = _deep_merge(rig, over)
    if not rig:
        raise ctx.err("no rig config: give 'base' (a rig config file) and/or [override] tables")
    base_type = rig.get("terrain", {}).get("type")
    if base_type is not None and base_type != terrain:
        raise ctx.err(f"terrain = \"{terrain}\" but the base rig config has terrain.type = "
                      f"\"{base_type}\" (use a base for this terrain or set override.terrain.type)")
    slip_control = doc.get("slip_control", "imposed_slip")
    if slip_control not in SLIP_CONTROLS:
        raise ctx.err(f"slip_control must be one of {', '.join(repr(x) for x in SLIP_CONTROLS)} "
                      f"(\"imposed_slip\": carriage.slip per point; \"wheel_speed\": motor.omega per "
                      f"point at the base's imposed carriage speed), got {slip_control!r}")
    speed = None
    if slip_control == "wheel_speed":
        speed = _wheel_speed_base(ctx, rig)
    else:
        mode = rig.get("carriage", {}).get("mode")
        if mode is not None and mode != "imposed_slip":
            raise ctx.err(f"the base rig config has carriage.mode = \"{mode}\"; a slip sweep needs "
                          "\"imposed_slip\" (or, for carriage.mode = \"imposed_speed\", "
                          "slip_control = \"wheel_speed\": the slip set by the wheel speed)")
    if "soil" in doc.get("override", {}).get("terrain", {}):
        raise ctx.err("override.terrain.soil: the soil is set per point from 'soils'")
    # the same for what the slip control sets per point: an override of it would be replaced
    per_point = ("carriage", "slip") if slip_control == "imposed_slip" else ("motor", "omega")
    if per_point[1] in doc.get("override", {}).get(per_point[0], {}):
        raise ctx.err(f"override.{'.'.join(per_point)}: set per point from 'slips' "
                      f"(slip_control = \"{slip_control}\")")
    rig.get("terrain", {}).pop("soil", None)  # a base's soil is replaced per point

    sweep = Sweep(path=path, terrain=terrain, description=description,
                  wheels=_wheels(ctx, doc["wheels"], terrain, build_dir),
                  soils=_soils(ctx, doc.get("soils"), terrain, repo),
                  slips=_slips(ctx, doc["slips"], slip_control), points=[],
                  slip_control=slip_control)
    _unique(ctx, sweep.wheels, "wheels")
    _unique(ctx, sweep.soils, "soils")

    if "dem" in doc:
        if terrain != "dem":
            raise ctx.err(f"[dem] is only used with terrain = \"dem\" (terrain is \"{terrain}\")")
        dem = doc["dem"]
        if not isinstance(dem, dict):
            raise ctx.err("dem must be a table")
        ctx.check_keys(dem, DEM_KEYS, "dem")
    else:
        dem = {}
    if terrain == "dem":
        for k in ("np", "bed_np"):
            v = dem.get(k, dem.get("np", 1))
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise ctx.err(f"dem.{k} must be an integer >= 1, got {v!r}")
            setattr(sweep, k, v)
        deck = (ctx.path_of(dem["deck"], "dem.deck") if "deck" in dem
                else repo / "inputs" / "examples" / "in.wheel_coupled")
        sweep.deck = ctx.existing(deck, "dem.deck", "LIGGGHTS deck")
        args = dem.get("liggghts_args", [])
        if not isinstance(args, list) or not all(isinstance(a, str) for a in args):
            raise ctx.err("dem.liggghts_args must be an array of strings")
        sweep.liggghts_args = args
        if "budget_h" in dem:
            b = dem["budget_h"]
            if isinstance(b, bool) or not isinstance(b, (int, float)) or not b > 0:
                raise ctx.err(f"dem.budget_h must be a number of hours > 0, got {b!r}")
            sweep.budget_h = float(b)
        if "checkpoint_every_s" in dem:
            v = dem["checkpoint_every_s"]
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not v >= 0:
                raise ctx.err("dem.checkpoint_every_s must be a wall time in s >= 0 (0: not by "
                              f"time), got {v!r}")
            sweep.checkpoint_every_s = float(v)
        if "checkpoint_every_steps" in dem:
            v = dem["checkpoint_every_steps"]
            if isinstance(v, bool) or not isinstance(v, int) or v < 0:
                raise ctx.err("dem.checkpoint_every_steps must be an integer >= 0 (0: not by "
                              f"steps), got {v!r}")
            sweep.checkpoint_every_steps = v

    # The points.
    n = 0
    r_effs = {}
    for w in sweep.wheels:
        for s in sweep.soils:
            for slip in sweep.slips:
                r = copy.deepcopy(rig)
                wt = r.setdefault("wheel", {})
                if "mass" in w.keys or "inertia" in w.keys:
                    wt.pop("density", None)
                if "density" in w.keys:
                    wt.pop("mass", None)
                    wt.pop("inertia", None)
                wt.update(copy.deepcopy(w.keys))
                wt["mesh"] = str(w.mesh)
                c = r.setdefault("carriage", {})
                if slip_control == "wheel_speed":
                    if w.label not in r_effs:  # the same for every soil and slip
                        r_effs[w.label] = _point_r_eff(ctx, r, w)
                    r_eff = r_effs[w.label]
                    wt["effective_radius"] = r_eff  # the R_eff omega is computed with
                    omega = wheel_omega(slip, speed, r_eff)
                    r.setdefault("motor", {})["omega"] = omega
                    conv = "driving" if slip >= 0 else "skid"
                    setting = (f"motor.omega = {omega!r} rad/s for slip {slip!r} ({conv} "
                               f"convention) at carriage.speed = {speed!r} m/s, "
                               f"wheel.effective_radius = {r_eff!r} m")
                else:
                    c["mode"] = "imposed_slip"
                    c["slip"] = slip
                    setting = f"carriage.slip = {slip!r} (driving convention)"
                t = r.setdefault("terrain", {})
                t["type"] = terrain
                t.update(copy.deepcopy(s.terrain_keys))
                if s.soil_file is not None:
                    t["soil"] = str(s.soil_file)
                reldir = f"{w.label}/{s.label}/{slip_dirname(slip, sweep.slips)}"
                sweep.points.append(Point(n, w, s, slip, reldir, r, setting))
                n += 1
    return sweep
