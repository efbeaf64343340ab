"""Reading a validation case's results table (`wheelsim-post curves --results`, docs/postprocess.md
"The results table"): comment lines start with '#'. Shared by the cases' plot and compare scripts
(they put this folder on sys.path)."""
import csv
import sys


def read_rows(path, need=(), prog="validation"):
    """The table's rows as dicts. A missing file, or a row without one of the columns `need`,
    stops with one line naming the file (exit status 2)."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    except OSError as e:
        _fail(prog, f"{path}: {e.strerror}")
    for i, r in enumerate(rows):
        missing = [c for c in need if c not in r]
        if missing:
            _fail(prog, f"{path}: row {i + 1}: columns {missing} missing (expected a table of "
                        "wheelsim-post curves --results)")
    return rows


def _fail(prog, msg):
    print(f"{prog}: error: {msg}", file=sys.stderr)
    raise SystemExit(2)
