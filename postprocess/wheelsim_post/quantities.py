"""The steady-state quantities of ``curves``/``study``/``compare``: names, units, CSV columns."""

import dataclasses

from .choices import parse_choices


@dataclasses.dataclass(frozen=True)
class Quantity:
    """A reported quantity: SI ``unit`` in the CSV, ``plot_scale`` × SI in ``plot_unit`` plots."""

    name: str
    unit: str
    label: str
    plot_unit: str
    plot_scale: float = 1.0

    @property
    def suffix(self):
        """Unit suffix of CSV column names ('_N', '_Nm', '_m', '' if dimensionless)."""
        return "" if self.unit == "1" else "_" + self.unit.replace(" ", "")

    @property
    def mean_column(self):
        """CSV column of the window mean, e.g. 'drawbar_pull_mean_N'."""
        return f"{self.name}_mean{self.suffix}"

    @property
    def std_column(self):
        """CSV column of the window standard deviation, e.g. 'drawbar_pull_std_N'."""
        return f"{self.name}_std{self.suffix}"

    @property
    def sem_column(self):
        """CSV column of the standard error of the window mean, e.g. 'drawbar_pull_sem_N'."""
        return f"{self.name}_sem{self.suffix}"

    def axis_label(self):
        """Plot axis label with unit, e.g. 'drawbar pull [N]'."""
        unit = "-" if self.plot_unit == "1" else self.plot_unit
        return f"{self.label} [{unit}]"


QUANTITIES = {
    q.name: q
    for q in (
        Quantity("slip", "1", "slip", "1"),
        Quantity("slip_skid", "1", "skid slip (ω R_eff − v)/v", "1"),
        Quantity("slip_signed", "1", "slip (driving s ≥ 0, skid s < 0)", "1"),
        Quantity("drawbar_pull", "N", "drawbar pull", "N"),
        Quantity("driving_torque", "N m", "driving torque", "N m"),
        Quantity("sinkage", "m", "sinkage", "mm", 1000.0),
        Quantity("tractive_efficiency", "1", "tractive efficiency", "1"),
        Quantity("traction_force", "N", "traction force T/R_eff", "N"),
        Quantity("lateral_force", "N", "lateral force", "N"),
        Quantity("dp_over_w", "1", "drawbar pull coefficient DP/W", "1"),
        Quantity("torque_over_w_reff", "1", "torque coefficient T/(W·R_eff)", "1"),
    )
}

#: Quantities plotted against slip by ``curves`` (one panel each).
CURVE_QUANTITIES = (
    "drawbar_pull",
    "driving_torque",
    "sinkage",
    "tractive_efficiency",
    "traction_force",
    "lateral_force",
)

#: The normalised quantities (W = vertical load, R_eff = effective radius).
NORMALISED_QUANTITIES = ("dp_over_w", "torque_over_w_reff")

#: Panels of ``curves --normalised``.
NORMALISED_CURVE_QUANTITIES = (
    "dp_over_w",
    "torque_over_w_reff",
    "sinkage",
    "tractive_efficiency",
)

#: The slip conventions (slip.py): driving (the rig's), skid and signed (issue 11's).
SLIP_QUANTITIES = ("slip", "slip_skid", "slip_signed")


def of_means(name):
    """Column and stats key of a quantity computed from the window means, e.g.
    'slip_signed_of_means'."""
    return f"{name}_of_means"


#: Extra CSV columns: values computed from the window means (see docs/postprocess.md).
SLIP_OF_MEANS = of_means("slip")
EFFICIENCY_OF_MEANS = "tractive_efficiency_of_means"


def parse_quantities(text, option="--quantity"):
    """A comma-separated list of quantity names (PostError naming ``option`` if unknown)."""
    return parse_choices(text, QUANTITIES, option)
