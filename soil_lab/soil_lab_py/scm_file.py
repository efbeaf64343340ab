"""An SCM soil file fitted from a DEM soil (docs/soil-lab.md, section "SCM soil file from DEM").

The file has the format of inputs/scm_soils/*.toml (docs/scm-soils.md, loader
scm/soil/src/soil_file.cpp): name, description, [bekker] n kc kphi, [mohr_coulomb] cohesion
friction_angle, [janosi] shear_modulus, optionally [scm] elastic_stiffness, and a
[source.<table>] string for every value saying where it comes from. Values outside the loader's
ranges raise SoilValueError before anything is written. Values are written to
SIGNIFICANT_DIGITS significant digits.
"""

import json
import math
import os
import tempfile
import tomllib
from typing import Mapping, Optional

__all__ = ["SoilValueError", "SOURCE_KEYS", "dem_source", "write_scm_soil"]


class SoilValueError(ValueError):
    """A soil value the SCM loader would reject (names the key, the range and the value)."""


#: Every value key the writer writes, as "table.key" (the loader's schema, without scm.damping).
SOURCE_KEYS = (
    "bekker.n",
    "bekker.kc",
    "bekker.kphi",
    "mohr_coulomb.cohesion",
    "mohr_coulomb.friction_angle",
    "janosi.shear_modulus",
    "scm.elastic_stiffness",
)


def dem_source(dem_soil, test, fit=None, detail=None):
    """A [source] string for a value fitted from a DEM soil, e.g.
    "fitted from the DEM soil 'loose_sand' by the virtual soil lab: plate sinkage, 2 plates
    (b 0.05, 0.1 m); fit RMS 3.66e+03 Pa, R² 0.9990, 118 points".

    dem_soil: the DEM soil's name (e.g. its inputs/soils/ include file); test: the bulk test;
    fit: a result of soil_lab_py.fits or .repose whose residual (rms_Pa or rms_m, r2) and
    n_points are quoted; detail: any further text (plates, normal stresses, ...)."""
    text = f"fitted from the DEM soil '{dem_soil}' by the virtual soil lab: {test}"
    if detail:
        text += f", {detail}"
    if fit is not None:
        parts = []
        for attr, unit in (("rms_Pa", "Pa"), ("rms_m", "m")):
            if hasattr(fit, attr):
                parts.append(f"RMS {getattr(fit, attr):.3g} {unit}")
        if hasattr(fit, "r2"):
            parts.append(f"R² {fit.r2:.4f}")
        if hasattr(fit, "n_points"):
            parts.append(f"{fit.n_points} points")
        if parts:
            text += "; fit " + ", ".join(parts)
    return text


#: Digits a value is written with: a fit's residual leaves no more than these meaningful, and a
#: shorter decimal survives the 15-digit soil writers of scm/soil (soil file -> Chrono JSON ->
#: soil file) unchanged, where a 17-digit one would not.
SIGNIFICANT_DIGITS = 6


def _number(key, value, unit, range_text, ok):
    in_unit = f" in {unit}" if unit else ""
    if isinstance(value, (bool, str, bytes)):
        raise SoilValueError(f"{key} must be a number{in_unit}, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise SoilValueError(f"{key} must be a number{in_unit}, got {value!r}") from None
    if not math.isfinite(v):
        raise SoilValueError(f"{key} must be a finite number{in_unit}, got {v!r}")
    # A fitted value carries no more than SIGNIFICANT_DIGITS digits; rounded before the range
    # check, so the value checked is the value written.
    v = float(f"{v:.{SIGNIFICANT_DIGITS}g}")
    if not ok(v):
        raise SoilValueError(f"{key} must be {range_text}{' ' + unit if unit else ''}, got {v!r}")
    return v


def _toml_string(s):
    # JSON string escapes are valid TOML basic-string escapes; DEL must be escaped in TOML.
    return json.dumps(s, ensure_ascii=False).replace("\x7f", "\\u007f")


def _line(key, value, comment):
    return f"{key} = {value}".ljust(25) + f" # {comment}"


def _resolve_sources(sources, written):
    """{"table.key": text} for every written key, from sources given per key ("bekker.n") or per
    table ("bekker", for all its keys)."""
    if sources is None:
        sources = {}
    if not isinstance(sources, Mapping):
        raise SoilValueError("sources must be a mapping of 'table.key' (or 'table') to a string")
    tables = {k.split(".")[0] for k in SOURCE_KEYS}
    resolved = {}
    for key, text in sources.items():
        if key not in SOURCE_KEYS and key not in tables:
            raise SoilValueError(
                f"unknown source key {key!r}: expected one of {', '.join(SOURCE_KEYS)} or a table "
                f"({', '.join(sorted(tables))})"
            )
        if not isinstance(text, str) or not text.strip():
            raise SoilValueError(f"sources[{key!r}] must be a non-empty string, got {text!r}")
    for key in written:
        table = key.split(".")[0]
        text = sources.get(key, sources.get(table))
        if text is None:
            raise SoilValueError(
                f"missing source for {key}: give sources={{'{key}': ...}} (or one for "
                f"'{table}'), e.g. dem_source(dem_soil, test, fit)"
            )
        resolved[key] = text
    unused = [k for k in sources if k in SOURCE_KEYS and k not in written]
    if unused:
        raise SoilValueError(f"sources given for values not written: {', '.join(unused)}")
    return resolved


def write_scm_soil(
    path,
    name,
    description,
    n,
    kc,
    kphi,
    cohesion_Pa,
    friction_deg,
    janosi_K_m,
    elastic_K_Pa_m: Optional[float] = None,
    sources: Optional[Mapping[str, str]] = None,
):
    """Write an SCM soil file (TOML, the format of inputs/scm_soils/*.toml) and return its path.

    Values in SI units, checked against the loader's ranges (docs/scm-soils.md) before anything is
    written: n [-] in (0, 2]; kc [N/m^(n+1)] >= 0; kphi [N/m^(n+2)] >= 0 with kc + kphi > 0;
    cohesion_Pa [Pa] >= 0; friction_deg [deg] in [0, 90); janosi_K_m [m] > 0; elastic_K_Pa_m
    [Pa/m] > 0 or None (then [scm] is left out and the SCM terrain uses its default Ke; its
    damping is always the default). name: a non-empty string; description: a string or None.

    sources: {"table.key": text} for each value written (keys of SOURCE_KEYS), or {"table": text}
    for all values of a table; every written value needs one (dem_source() formats the DEM
    soil, the test and the fit residual). A bad value raises SoilValueError naming it, as the
    loader would ("bekker.n must be in (0, 2], got 2.5"). The file is written to a temporary
    file next to path, parsed back, and renamed onto path.
    """
    if not isinstance(name, str) or not name.strip():
        raise SoilValueError(f"name must be a non-empty string, got {name!r}")
    if description is not None and not isinstance(description, str):
        raise SoilValueError(f"description must be a string or None, got {description!r}")
    v = {
        "bekker.n": _number("bekker.n", n, "", "in (0, 2]", lambda x: 0 < x <= 2),
        "bekker.kc": _number("bekker.kc", kc, "N/m^(n+1)", ">= 0", lambda x: x >= 0),
        "bekker.kphi": _number("bekker.kphi", kphi, "N/m^(n+2)", ">= 0", lambda x: x >= 0),
        "mohr_coulomb.cohesion": _number(
            "mohr_coulomb.cohesion", cohesion_Pa, "Pa", ">= 0", lambda x: x >= 0
        ),
        "mohr_coulomb.friction_angle": _number(
            "mohr_coulomb.friction_angle", friction_deg, "deg", "in [0, 90)", lambda x: 0 <= x < 90
        ),
        "janosi.shear_modulus": _number(
            "janosi.shear_modulus", janosi_K_m, "m", "> 0", lambda x: x > 0
        ),
    }
    if not v["bekker.kc"] + v["bekker.kphi"] > 0:
        raise SoilValueError(
            "bekker.kc + bekker.kphi must be > 0 (the soil must resist sinkage), got kc = "
            f"{v['bekker.kc']!r} N/m^(n+1) and kphi = {v['bekker.kphi']!r} N/m^(n+2)"
        )
    if elastic_K_Pa_m is not None:
        v["scm.elastic_stiffness"] = _number(
            "scm.elastic_stiffness", elastic_K_Pa_m, "Pa/m", "> 0", lambda x: x > 0
        )
    src = _resolve_sources(sources, list(v))

    n_ = v["bekker.n"]
    lines = [
        f"# {name}: an SCM soil fitted from a DEM soil by the virtual soil lab (soil_lab/,",
        "# docs/soil-lab.md). Format and ranges: docs/scm-soils.md. Units are SI. Every value has",
        "# its source (DEM soil, bulk test, fit residual) in the [source] tables below.",
        f"name = {_toml_string(name)}",
    ]
    if description is not None:
        lines.append(f"description = {_toml_string(description)}")
    lines += [
        "",
        "[bekker]                  # p = (kc/b + kphi) z^n",
        _line("n", repr(n_), "sinkage exponent [-], in (0, 2]"),
        _line(
            "kc",
            repr(v["bekker.kc"]),
            f"cohesive modulus [N/m^(n+1)], >= 0   ({v['bekker.kc'] / 1000:.6g} kN/m^(n+1))",
        ),
        _line(
            "kphi",
            repr(v["bekker.kphi"]),
            f"frictional modulus [N/m^(n+2)], >= 0 ({v['bekker.kphi'] / 1000:.6g} kN/m^(n+2))",
        ),
        "",
        "[mohr_coulomb]            # tau_max = c + sigma tan(phi)",
        _line(
            "cohesion",
            repr(v["mohr_coulomb.cohesion"]),
            f"c [Pa], >= 0 ({v['mohr_coulomb.cohesion'] / 1000:.6g} kPa)",
        ),
        _line("friction_angle", repr(v["mohr_coulomb.friction_angle"]), "phi [deg], in [0, 90)"),
        "",
        "[janosi]                  # tau = tau_max (1 - exp(-j/K))",
        _line("shear_modulus", repr(v["janosi.shear_modulus"]), "K [m], > 0"),
        "",
    ]
    if "scm.elastic_stiffness" in v:
        lines += [
            "[scm]                     # damping is not set: the SCM default (3e4 Pa s/m) applies",
            _line(
                "elastic_stiffness",
                repr(v["scm.elastic_stiffness"]),
                "Ke [Pa/m], > 0 (plate unloading)",
            ),
        ]
    else:
        lines += [
            "# [scm] is omitted, so the SCM terrain uses the defaults (Chrono's demo values):",
            "# elastic_stiffness = 2e8 Pa/m, damping = 3e4 Pa s/m.",
        ]
    for table in ("bekker", "mohr_coulomb", "janosi", "scm"):
        keys = [k for k in SOURCE_KEYS if k.startswith(table + ".") and k in src]
        if not keys:
            continue
        lines += ["", f"[source.{table}]"]
        lines += [f"{k.split('.')[1]} = {_toml_string(src[k])}" for k in keys]
    text = "\n".join(lines) + "\n"

    # Self-check: the text parses as TOML and holds exactly the values given.
    doc = tomllib.loads(text)
    for key, value in v.items():
        table, k = key.split(".")
        if doc[table][k] != value:
            raise AssertionError(f"scm_file: {key} written as {doc[table][k]!r}, not {value!r}")

    path = os.fspath(path)
    directory = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".soil-", suffix=".toml", dir=directory)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path
