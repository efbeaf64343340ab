"""LIGGGHTS' run summaries in its screen output or log file: one line "Loop time of T on P procs
for S steps with N atoms" per run command. Read by wheel-sweep's rate benchmark, the soil lab's
cost records and the benchmarks in bench/ (one parser, one place)."""
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
