"""Steady-state analysis of many runs: one RunResult per run file (curves and study)."""

import dataclasses
import math

from .health import (ACTIVE_ALLOWANCE_PARAMETER, BED_DEPTH_PARAMETER, BIN_LENGTH_PARAMETER,
                     EFFECTIVE_RADIUS_PARAMETER, LUG_HEIGHT_PARAMETER, PARTICLES_END_PARAMETER,
                     PARTICLES_START_PARAMETER, RIM_RADIUS_PARAMETER, SHEAR_SURFACE_PARAMETER,
                     WHEEL_WIDTH_PARAMETER, Health, postprocess_findings)
from .metadata import read_metadata
from .runfile import RunFile
from .steady import Stat, steady_state
from .wheelinfo import lug_count


@dataclasses.dataclass
class RunResult:
    """A run's path, grouping metadata, steady_state() statistics and health."""

    path: str
    metadata: object
    stats: dict
    health: Health

    def mean(self, quantity):
        """Window mean of ``quantity`` (a name of quantities.QUANTITIES)."""
        return self.stats[quantity].mean

    def std(self, quantity):
        """Window standard deviation (ddof 0) of ``quantity``."""
        return self.stats[quantity].std

    def sem(self, quantity):
        """Standard error of the window mean of ``quantity`` (batch means)."""
        return self.stats[quantity].sem

    @property
    def span(self):
        """The steady.WindowSpan."""
        return self.stats["span"]


def analyse_run(path, window, lugs=None):
    """The RunResult of one run file (PostError if it is unusable).

    ``lugs``: lug count from the command line (None: found by wheelinfo.lug_count)."""
    with RunFile(path) as run:
        metadata = read_metadata(run)
        count, source = lug_count(run, metadata.wheel, lugs)
        stats = steady_state(run, window, count, source)
        health = run.health()
        parameters = [run.parameter(name) for name in (
            ACTIVE_ALLOWANCE_PARAMETER, BED_DEPTH_PARAMETER, WHEEL_WIDTH_PARAMETER,
            BIN_LENGTH_PARAMETER, RIM_RADIUS_PARAMETER, PARTICLES_START_PARAMETER,
            PARTICLES_END_PARAMETER, LUG_HEIGHT_PARAMETER, EFFECTIVE_RADIUS_PARAMETER)]
        shear_surface = run.parameter_text(SHEAR_SURFACE_PARAMETER)
    *parameters, lug_height, effective_radius = (None if v is None else float(v)
                                                 for v in parameters)
    health.findings = health.findings + postprocess_findings(
        stats, *parameters, terrain=metadata.terrain, lug_height_m=lug_height,
        effective_radius_m=effective_radius, shear_surface=shear_surface)
    return RunResult(path, metadata, stats, health)


def analyse_runs(paths, window, lugs=None):
    """RunResults of ``paths`` (in order); PostError on the first unusable file."""
    return [analyse_run(path, window, lugs) for path in paths]


def offset_sinkage(results, offset_m):
    """Reads every result's sinkage against a surface ``offset_m`` below the one its run recorded
    (e.g. a DEM bed's equivalent surface, bed_surface.equivalent_surface): the mean less
    ``offset_m``, std and SEM unchanged. The health findings keep the recorded surface (their
    limits are geometry measured from it)."""
    for r in results:
        s = r.stats["sinkage"]
        r.stats["sinkage"] = Stat(s.mean - offset_m, s.std, s.sem)


def sinkage_offset_comment(offset_m):
    """The tables' header line on a sinkage offset ([] for none)."""
    if not offset_m:
        return []
    return [f"sinkage: read against a surface {offset_m:g} m below the one each run recorded "
            "(--sinkage-offset); health findings keep the recorded one"]


def group_label(metadata, group_by):
    """A series label such as 'wheel=lugged_12, soil=GRC-1' for the keys ``group_by``."""
    return ", ".join(f"{k}={getattr(metadata, k)}" for k in group_by)


def slip_text(value):
    """A target slip for tables and labels ('0.2', or 'none' if NaN)."""
    return "none" if math.isnan(value) else f"{value:g}"


def window_lines(result):
    """Console lines: the window chosen for a run and its notes."""
    span = result.span
    lines = [f"{result.path}: {span.describe()}"]
    lines += [f"{result.path}: note: {note}" for note in span.notes]
    return lines
