"""LIGGGHTS' screen output or log file: its run summaries, one line "Loop time of T on P procs
for S steps with N atoms" per run command (read by wheel-sweep's rate benchmark, the soil lab's
cost records and the benchmarks in bench/), and its thermo tables (read by the benchmarks and the
tests that compare runs step by step). One parser of each, in one place."""
import re
from typing import NamedTuple

_LOOP = re.compile(r"Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms")


class Loop(NamedTuple):
    """One run command's summary: wall time of its loop [s], MPI ranks, steps, atoms."""
    seconds: float
    procs: int
    steps: int
    atoms: int


def loops(text):
    """Every run command's summary in `text`, in order ([] if none)."""
    return [Loop(float(t), int(p), int(s), int(n)) for t, p, s, n in _LOOP.findall(text)]


class Thermo(NamedTuple):
    """One run command's thermo table: the column names as LIGGGHTS 3.8 prints them (``Step``,
    ``Atoms``, then each keyword without its ``v_``/``f_``/``c_`` prefix, cut to 10 characters:
    ``f_wheel[10]`` is ``wheel[10``) and one row of numbers per output step."""
    columns: list
    rows: list

    def column(self, name):
        """{step: value} of the column `name` (KeyError naming the columns if there is none)."""
        if name not in self.columns:
            raise KeyError(f"thermo column '{name}' not in {self.columns}")
        i = self.columns.index(name)
        return {int(r[0]): r[i] for r in self.rows}

    def values(self, name):
        """The column `name` in row order (KeyError naming the columns if there is none)."""
        if name not in self.columns:
            raise KeyError(f"thermo column '{name}' not in {self.columns}")
        i = self.columns.index(name)
        return [r[i] for r in self.rows]


def thermo(text):
    """Every thermo table in `text`, in order. A table starts at a header line whose first word is
    ``Step`` and ends at the run's "Loop time" line or at a line as wide as the header that is not
    numbers; lines of another width inside it (warnings LIGGGHTS prints mid-run) are skipped."""
    tables, current = [], None
    for line in text.splitlines():
        words = line.split()
        if words[:1] == ["Step"]:
            current = Thermo(words, [])
            tables.append(current)
        elif current is not None and line.startswith("Loop time of"):
            current = None
        elif current is not None and len(words) == len(current.columns):
            try:
                current.rows.append([float(w) for w in words])
            except ValueError:
                current = None
    return tables


def merged(text, column):
    """The rows of every thermo table in `text` that has `column`, in order, under the first such
    table's columns (one Thermo for a run made of several `run` commands). ValueError if no table
    has `column`, or if two of them differ in their columns."""
    tables = [t for t in thermo(text) if column in t.columns]
    if not tables:
        raise ValueError(f"no thermo table with a '{column}' column")
    for t in tables[1:]:
        if t.columns != tables[0].columns:
            raise ValueError(f"thermo tables with a '{column}' column differ: {tables[0].columns} "
                             f"and {t.columns}")
    return Thermo(tables[0].columns, [r for t in tables for r in t.rows])
