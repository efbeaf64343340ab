"""The files a LIGGGHTS input includes, for the resume hashes of wheel-sweep (a point's or a bed's
inputs) and soil-lab (a bed's or a test's): a changed included file (a soil file's base soil,
resume.in, settle.in, ...) must re-run what was made with it."""
import re
from pathlib import Path

_INCLUDE = re.compile(r"^[ \t]*include[ \t]+(\S+)", re.M)
_DECK_VAR = re.compile(r"\$\{(\w+)\}")


def deck_includes(deck, variables):
    """The files LIGGGHTS input `deck` includes, recursively, in order: each `include` whose
    path, with ${NAME} replaced from `variables` (e.g. inputs_dir), is an existing absolute path.
    Paths built from run-time variables (the soil file, the restart's .vars) are left out: the
    resume hash covers those files on their own."""
    found, todo = [], [Path(deck)]
    while todo:
        try:
            text = todo.pop(0).read_text(errors="replace")
        except OSError:
            continue
        for m in _INCLUDE.finditer(text):
            path = _DECK_VAR.sub(lambda v: variables.get(v.group(1), v.group(0)), m.group(1))
            f = Path(path)
            if "$" in path or not f.is_absolute() or not f.is_file() or f in found:
                continue
            found.append(f)
            todo.append(f)
    return found


def deck_variable(deck, name, liggghts_args=()):
    """The value (a string) LIGGGHTS gives the index variable `name` of input `deck` run with
    `liggghts_args`: the first `-var NAME VALUE` there (LIGGGHTS keeps an index variable's first
    definition), else the deck's first `variable NAME index VALUE` (quotes removed), else None."""
    args = list(liggghts_args)
    for i in range(len(args) - 2):
        if args[i] == "-var" and args[i + 1] == name:
            return args[i + 2]
    try:
        text = Path(deck).read_text(errors="replace")
    except (OSError, TypeError):
        return None
    m = re.search(rf"^\s*variable\s+{re.escape(name)}\s+index\s+(\"[^\"]*\"|\S+)", text, re.M)
    return m.group(1).strip('"') if m else None
