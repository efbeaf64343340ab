"""A small TOML writer for rig configs: nested tables of scalars and arrays of scalars."""

import json
import math


def _value(v, where):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)  # a valid TOML basic string
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x, where) for x in v) + "]"
    raise TypeError(f"{where}: cannot write a {type(v).__name__} to TOML")


def _key(k):
    if k and all(c.isalnum() or c in "_-" for c in k):
        return k
    return json.dumps(k)


def dumps(doc, header=""):
    """TOML text of a dict whose values are scalars, arrays of scalars or dicts (tables)."""
    lines = [f"# {line}" if line else "#" for line in header.splitlines()]

    def table(d, path):
        scalars = [(k, v) for k, v in d.items() if not isinstance(v, dict)]
        tables = [(k, v) for k, v in d.items() if isinstance(v, dict)]
        if path and (scalars or not tables):
            if lines:
                lines.append("")
            lines.append("[" + ".".join(_key(p) for p in path) + "]")
        for k, v in scalars:
            lines.append(f"{_key(k)} = {_value(v, '.'.join(path + [k]))}")
        for k, v in tables:
            table(v, path + [k])

    table(doc, [])
    return "\n".join(lines) + "\n"
