"""Steady-state analysis of many runs: one RunResult per run file (curves and study)."""

import dataclasses
import math

from .metadata import read_metadata
from .runfile import RunFile
from .steady import steady_state


@dataclasses.dataclass
class RunResult:
    """A run's path, grouping metadata and steady_state() statistics."""

    path: str
    metadata: object
    stats: dict

    def mean(self, quantity):
        """Window mean of ``quantity`` (a name of quantities.QUANTITIES)."""
        return self.stats[quantity][0]

    def std(self, quantity):
        """Window standard deviation of ``quantity``."""
        return self.stats[quantity][1]


def analyse_runs(paths, window):
    """RunResults of ``paths`` (in order); PostError on the first unusable file."""
    results = []
    for path in paths:
        with RunFile(path) as run:
            results.append(
                RunResult(path, read_metadata(run), steady_state(run, window))
            )
    return results


def group_label(metadata, group_by):
    """A series label such as 'wheel=lugged_12, soil=GRC-1' for the keys ``group_by``."""
    return ", ".join(f"{k}={getattr(metadata, k)}" for k in group_by)


def slip_text(value):
    """A target slip for tables and labels ('0.2', or 'none' if NaN)."""
    return "none" if math.isnan(value) else f"{value:g}"
