"""Run health: the rig's ``/health`` group and the findings of post-processing.

Layout written by the rig (docs/hdf5-layout.md): group ``/health`` with attribute ``status``
("running" while the run is in progress or after a crash, then "healthy", "warnings" or
"unhealthy") and equal-length datasets ``step`` (int64), ``time`` (float64, s), ``code``,
``severity`` ("warning" or "error") and ``message`` (strings). A run file without it is
"unchecked".

The ``health`` column: the worst of the rig's verdict and post-processing's findings, in the
order ok < unchecked < warning < incomplete < unhealthy (findings are warnings).
"""

import dataclasses
import math

import h5py
import numpy as np

from .quantities import EFFICIENCY_OF_MEANS, SLIP_OF_MEANS

HEALTH_ORDER = ("ok", "unchecked", "warning", "incomplete", "unhealthy")
STATUS_HEALTH = {
    "healthy": "ok",
    "warnings": "warning",
    "unhealthy": "unhealthy",
    "running": "incomplete",
}
#: Tolerance of the efficiency bound, in standard errors.
EFFICIENCY_BOUND_SEM = 2.0
#: A drawbar-pull trend is reported when the fitted change over the window exceeds this many
#: standard errors of that change (and TREND_MEAN_SEM standard errors of the mean).
TREND_SLOPE_SE = 3.0
TREND_MEAN_SEM = 2.0


@dataclasses.dataclass
class Finding:
    """One health entry: a code, 'warning' or 'error', and a message."""

    code: str
    severity: str
    message: str


@dataclasses.dataclass
class Health:
    """The health of one run: its verdict, findings (rig's first) and the rig's status."""

    status: str  # the rig's /health status, or "unchecked"
    findings: list

    @property
    def verdict(self):
        """ok / unchecked / warning / incomplete / unhealthy."""
        verdict = STATUS_HEALTH.get(self.status, "unchecked")
        if self.status not in STATUS_HEALTH and self.status != "unchecked":
            verdict = "incomplete"  # an unknown status: do not trust it
        for finding in self.findings:
            level = "unhealthy" if finding.severity == "error" else "warning"
            verdict = worst(verdict, level)
        return verdict

    @property
    def codes(self):
        """Distinct codes in order of first appearance, ';'-joined."""
        return ";".join(dict.fromkeys(f.code for f in self.findings))


def worst(a, b):
    """The worse of two health values."""
    return max(a, b, key=HEALTH_ORDER.index)


def _strings(dataset):
    data = dataset[()]
    return [d.decode("utf-8") if isinstance(d, bytes) else str(d) for d in np.ravel(data)]


def read_health(h5file):
    """The rig's Health of an open h5py.File ('unchecked', no findings, without /health)."""
    group = h5file.get("health")
    if not isinstance(group, h5py.Group):
        return Health("unchecked", [])
    status = group.attrs.get("status", "running")
    status = status.decode("utf-8") if isinstance(status, bytes) else str(status)
    columns = []
    for name in ("code", "severity", "message"):
        columns.append(_strings(group[name]) if name in group else [])
    n = min(len(c) for c in columns)
    findings = [Finding(*(c[i] for c in columns)) for i in range(n)]
    return Health(status, findings)


#: LIGGGHTS' atom count at the start and at the end of a DEM run, recorded by wheel-cosim from the
#: "Loop time" lines of its log (first and last run command).
PARTICLES_START_PARAMETER = "liggghts/atoms_start"
PARTICLES_END_PARAMETER = "liggghts/atoms"
#: particles_lost: a warning when more than this fraction of the particles left the box during a
#: run. LIGGGHTS drops an atom that crosses a fixed boundary (the decks ignore lost atoms, so the
#: run goes on): in a bin with walls, grains thrown or carried above the box's top. A few grains
#: are harmless; a thousandth of the bed is soil the wheel no longer meets.
PARTICLES_LOST_FRACTION = 1e-3
#: The run-file parameter wheel-cosim records from fix wheel/active's setup line [m].
ACTIVE_ALLOWANCE_PARAMETER = "liggghts/active_sinkage_allowance"
#: The DEM bed's depth (surface above the bin's rigid floor) wheel-cosim records [m].
BED_DEPTH_PARAMETER = "bed/bed_depth_m"
#: The wheel mesh's extent along the axle, recorded by wheel-rig [m].
WHEEL_WIDTH_PARAMETER = "wheel/width"
#: The DEM bin's inner length (x in [0, bin_length]) wheel-cosim records [m].
BIN_LENGTH_PARAMETER = "bed/bin_length_m"
#: The wheel's outer radius, recorded by wheel-rig [m].
RIM_RADIUS_PARAMETER = "wheel/rim_radius"
#: end_wall_clearance: a warning when the rim's front comes closer to the far end wall than this
#: many times the sinkage. The Rankine passive zone ahead of a blade pushed at depth z reaches
#: z tan(45 deg + phi/2) = 1.6 - 2.0 z for phi 25 - 37 deg; the pile there must not meet the wall.
END_WALL_CLEARANCE_SINKAGES = 2.0
#: SCM's shear surface, recorded by wheel-rig: "wheel" (default, as Chrono) or "lug_tips".
SHEAR_SURFACE_PARAMETER = "terrain/shear_surface"
#: The wheel's lug height (0 or absent: smooth) and slip radius, recorded by wheel-rig [m].
LUG_HEIGHT_PARAMETER = "wheel/lug_height"
EFFECTIVE_RADIUS_PARAMETER = "wheel/effective_radius"
#: floor_clearance: a warning when the wheel's bottom runs closer to the bin's rigid floor than
#: this many wheel widths. Under a square contact of side b, about a third of the contact pressure
#: still reaches one side b deeper (Boussinesq); a rigid floor there carries part of the load.
FLOOR_CLEARANCE_WIDTHS = 1.0


def postprocess_findings(stats, active_allowance_m=None, bed_depth_m=None, wheel_width_m=None,
                         bin_length_m=None, rim_radius_m=None, particles_start=None,
                         particles_end=None, terrain=None, lug_height_m=None,
                         effective_radius_m=None, shear_surface=None):
    """Findings of the window statistics (steady.steady_state's dict); ``active_allowance_m``:
    the active domain's sinkage allowance (ACTIVE_ALLOWANCE_PARAMETER; None: no active domain);
    ``bed_depth_m``, ``wheel_width_m``: a DEM bed's depth and the wheel's width (None: unknown,
    no floor check); ``bin_length_m``, ``rim_radius_m``: the bin's length and the wheel's outer
    radius (None: no end-wall check); ``particles_start``, ``particles_end``: LIGGGHTS' atom
    counts at the run's start and end (None: not recorded, no check); ``terrain``, ``lug_height_m``,
    ``effective_radius_m``: the terrain type ("scm", "dem", ...) and the wheel's lug height and
    slip radius (None: no SCM lug check); ``shear_surface``: SCM's (SHEAR_SURFACE_PARAMETER;
    "lug_tips" has no rim skid, None is read as the default "wheel")."""
    findings = []
    slip = stats[SLIP_OF_MEANS]
    if (terrain == "scm" and shear_surface != "lug_tips"
            and lug_height_m is not None and lug_height_m > 0.0
            and effective_radius_m is not None and effective_radius_m > lug_height_m
            and math.isfinite(slip.mean)):
        onset = lug_height_m / effective_radius_m
        if 0.0 <= slip.mean < onset:
            findings.append(
                Finding(
                    "scm_rim_skid",
                    "warning",
                    f"SCM with a lugged wheel at slip {slip.mean:.4g}, below lug height / "
                    f"effective radius = {lug_height_m:.4g} / {effective_radius_m:.4g} m = "
                    f"{onset:.4g}: the rim between the lugs moves forward over the soil, so SCM's "
                    "Janosi shear on it brakes the wheel (a height field carries no soil between "
                    "the lugs); SCM's pull and torque jump where the rim's slip changes sign, at "
                    "this slip: below it they are the model's artefact, not a prediction; "
                    "terrain.shear_surface = \"lug_tips\" shears at the lug tips instead "
                    "(docs/scm.md \"Shear surface\", docs/run-health.md)",
                )
            )
    if particles_start is not None and particles_end is not None and particles_start > 0:
        lost = particles_start - particles_end
        if lost > PARTICLES_LOST_FRACTION * particles_start:
            findings.append(
                Finding(
                    "particles_lost",
                    "warning",
                    f"{lost:.0f} of {particles_start:.0f} particles "
                    f"({100.0 * lost / particles_start:.2g} %) "
                    "left the simulation box during the run (LIGGGHTS drops atoms that cross a "
                    "fixed boundary; in a walled bin, grains thrown or carried above the box's "
                    "top): that soil is gone from the bin; give the box more height above the bed "
                    "(docs/run-health.md)",
                )
            )
    sinkage = stats["sinkage"].mean
    x_max = stats.get("wheel_x_max", math.nan)
    if (bin_length_m is not None and rim_radius_m is not None and math.isfinite(x_max)
            and math.isfinite(sinkage) and sinkage > 0.0):
        gap = bin_length_m - (x_max + rim_radius_m)
        if gap < END_WALL_CLEARANCE_SINKAGES * sinkage:
            findings.append(
                Finding(
                    "end_wall_clearance",
                    "warning",
                    f"the rim's front came to {gap:.4g} m from the bin's far wall (bin length "
                    f"{bin_length_m:.4g} m, wheel centre at x = {x_max:.4g} m, rim radius "
                    f"{rim_radius_m:.4g} m), less than {END_WALL_CLEARANCE_SINKAGES:g} x the "
                    f"sinkage {sinkage:.4g} m: the soil pushed ahead of the wheel may meet the "
                    "wall; lengthen the bin or end the window earlier (docs/run-health.md)",
                )
            )
    if bed_depth_m is not None and wheel_width_m is not None and math.isfinite(sinkage):
        clearance = bed_depth_m - sinkage
        if clearance < FLOOR_CLEARANCE_WIDTHS * wheel_width_m:
            findings.append(
                Finding(
                    "floor_clearance",
                    "warning",
                    f"the wheel's bottom ran {clearance:.4g} m above the bin's rigid floor (bed "
                    f"depth {bed_depth_m:.4g} m, sinkage {sinkage:.4g} m), less than "
                    f"{FLOOR_CLEARANCE_WIDTHS:g} x its width {wheel_width_m:.4g} m: the floor "
                    "may carry part of the wheel's load; deepen the bed or compare one point on "
                    "a deeper one (docs/run-health.md)",
                )
            )
    if active_allowance_m is not None and math.isfinite(sinkage) and sinkage > active_allowance_m:
        findings.append(
            Finding(
                "active_domain_sinkage",
                "warning",
                f"the wheel sank {sinkage:.4g} m, deeper than the active domain's sinkage "
                f"allowance {active_allowance_m:.4g} m (fix wheel/active): the frozen soil may "
                "carry part of the wheel's load; set its 'sinkage' to at least the sinkage and "
                "compare one point with the full domain (docs/fix-wheel-active.md, \"Sinkage "
                "allowance\")",
            )
        )
    eta = stats[EFFICIENCY_OF_MEANS]
    if slip.mean >= 0.0 and math.isfinite(eta.mean):
        bound = 1.0 - slip.mean
        tolerance = EFFICIENCY_BOUND_SEM * math.hypot(
            eta.sem if math.isfinite(eta.sem) else 0.0,
            slip.sem if math.isfinite(slip.sem) else 0.0,
        )
        if eta.mean > bound + tolerance:
            findings.append(
                Finding(
                    "efficiency_bound",
                    "warning",
                    f"tractive efficiency of the means {eta.mean:.4g} exceeds 1 - s = "
                    f"{bound:.4g} by more than {EFFICIENCY_BOUND_SEM:g} SEM ({tolerance:.2g})",
                )
            )
    change, change_se = stats["dp_trend"]
    dp_sem = stats["drawbar_pull"].sem
    if (
        math.isfinite(change)
        and change_se > 0.0
        and abs(change) > TREND_SLOPE_SE * change_se
        and abs(change) > TREND_MEAN_SEM * dp_sem
    ):
        findings.append(
            Finding(
                "steady_state_trend",
                "warning",
                f"drawbar pull changes by {change:.4g} N over the window (linear fit to the "
                f"batch means; > {TREND_SLOPE_SE:g} standard errors {change_se:.2g} N and > "
                f"{TREND_MEAN_SEM:g} SEM of the mean {dp_sem:.2g} N)",
            )
        )
    return findings
