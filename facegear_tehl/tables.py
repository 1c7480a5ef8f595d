"""Plain-text tables for the terminal: aligned columns under headers, and the text of their cells."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
import math

from facegear_tehl.units import CELSIUS, MILLIMETRE, PERCENT, Unit, display


def format_table(headers: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    """Headers, a rule of dashes, then the rows; first column left-aligned, the others right-aligned, two
    spaces between columns, no trailing blanks."""
    widths = [max(len(str(cell)) for cell in column) for column in zip(headers, *rows)]

    def line(cells: Sequence[str]) -> str:
        first, *rest = cells
        return "  ".join([f"{first:<{widths[0]}}", *(f"{c:>{w}}" for c, w in zip(rest, widths[1:]))]).rstrip()

    return "\n".join([line(headers), line(["-" * w for w in widths]), *(line(r) for r in rows)])


def format_pairs(pairs: Sequence[tuple[str, str]]) -> str:
    """'key  value' lines, the values aligned after the longest key."""
    width = max(len(key) for key, _ in pairs)
    return "\n".join(f"{key:<{width}}  {value}" for key, value in pairs)


def cell(value: float | None, spec: str, missing: str = "") -> str:
    """`value` formatted with the format spec `spec` ('.4g', '+.2f', ...); `missing` for None or NaN."""
    return missing if value is None or math.isnan(value) else f"{value:{spec}}"


def yes_no(flag: bool) -> str:
    return "yes" if flag else "no"


@dataclass(frozen=True)
class Column:
    """A column of one quantity: name, key of its value, SI units, format spec of the value shown in
    `unit` (default: the display unit of `units`)."""

    name: str
    key: str
    units: str = "1"
    spec: str = ".4g"
    unit: Unit | None = None

    @property
    def shown(self) -> Unit:
        return self.unit or display(self.units)

    @property
    def header(self) -> str:
        """The name, then the unit shown unless the value is dimensionless: 'h_c µm', 'mu'."""
        label = self.shown.label
        return self.name if label == "-" else f"{self.name} {label}"

    def text(self, value: float | None, missing: str = "-") -> str:
        """The cell of `value` (SI); `missing` for None or NaN."""
        return missing if value is None else cell(self.shown(value), self.spec, missing)


COST = (Column("cycles", "iterations", spec=".0f"), Column("work units", "work_units", spec=".1f"),
        Column("wall time", "wall_time", "s", ".2f"))
"""The cost of a solve: in the run summary and in the sweep report."""


# Absolute temperatures (the contact temperature θ_B of each flank, solved and by Blok's formula): shown in °C, as
# the verdict and the cycle table give them; every other scalar in K is a rise, shown in K.
ABSOLUTE_TEMPERATURE_KEYS = ("contact_temperature_1", "contact_temperature_2", "contact_temperature_blok_1",
                             "contact_temperature_blok_2")
# `tehl info`: the per-point scalars by theme, in this order; a scalar of none of them is listed under "other".
SCALAR_GROUPS = (
    ("film", ("h_c", "h_min", "film_parameter", "film_parameter_central", "x_h_min", "y_h_min", "inlet_gap_ratio",
              "side_pressure_ratio", "error_estimate_h_c", "error_estimate_h_min", "error_estimate_y_h_c",
              "error_estimate_y_h_min", "error_bound_h_c", "error_bound_h_min", "unresolved_h_c", "unresolved_h_min")),
    ("pressure", ("p_max", "p_hertz", "load", "a", "b", "ellipticity", "radius_x", "radius_y", "moes_m",
                  "moes_l", "path_coordinate", "error_estimate_p_max", "error_estimate_y_p_max", "error_bound_p_max",
                  "unresolved_p_max")),
    ("temperature", ("dT_max", "dT_min", "x_dT_min", "y_dT_min", "dT_mid_max", "dT_surface_1_max",
                     "dT_surface_2_max", "surface_rise_max", "flash_temperature", "thermal_loading",
                     "error_estimate_dT_max", "error_estimate_dT_min", "error_bound_dT_max", "error_bound_dT_min",
                     "unresolved_dT_max", "unresolved_dT_min", *ABSOLUTE_TEMPERATURE_KEYS)),
    ("friction", ("mu", "mu_1", "mu_2", "mu_xu", "error_estimate_mu", "error_bound_mu", "unresolved_mu",
                  "entrainment_speed", "sliding_speed",
                  "slide_roll_ratio", "entrainment_angle", "friction_power", "dissipated_power",
                  "dissipated_power_ellipse", "partition_1", "partition_2", "friction_power_1", "friction_power_2")),
    ("heat", ("heat_generated", "heat_conducted", "heat_convected", "heat_mass_defect", "dwell_time",
              "duty_ratio_1", "duty_ratio_2", "steady_power_1", "steady_power_2", "frictional_heat",
              "frictional_heat_seed", "frictional_heat_ellipse", "oil_film_heat", "oil_film_heat_domain",
              "oil_to_friction_ratio", "oil_to_ellipse_friction_ratio", "oil_to_seed_friction_ratio",
              "distribution_difference")),
    ("convergence", ("load_error", "iterations", "work_units", "wall_time", "grid", "grid_y", "coarsest_grid",
                     "thermal_iterations", "thermal_layers", "energy_balance_error", "algebraic_floor",
                     "thermal_floor", "viscosity_floor")),
)
FILM_KEYS = frozenset({"h_c", "h_min", "error_estimate_h_c", "error_estimate_h_min"})  # lengths shown in µm
# Dimensionless fractions shown in %: relative errors, shares and ratios.
PERCENT_KEYS = frozenset({"load_error", "energy_balance_error", "error_estimate_h_c", "error_estimate_h_min",
                          "error_estimate_dT_max", "error_estimate_mu", "error_estimate_p_max", "error_estimate_dT_min",
                          *(f"error_{kind}_{name}" for kind in ("bound", "estimate_y")
                            for name in ("h_c", "h_min", "p_max", "dT_max", "dT_min", "mu")),
                          "partition_1", "partition_2",
                          "oil_to_friction_ratio", "oil_to_ellipse_friction_ratio", "oil_to_seed_friction_ratio",
                          "distribution_difference", "load_share"})
UNRESOLVED = "unresolved_"  # prefix of the flags of quantities a solve cannot bound (ehl/error_bounds.py)
UNRESOLVED_WORD = "unresolved"  # what a table shows for such a quantity, never a number
UNRESOLVED_REASON = "unresolved_reason_"  # prefix of why (ehl/unresolved.py's code), worded apart from the tables
BOUNDED_FIGURES = ("h_c", "h_min", "p_max", "dT_max", "dT_min", "mu")  # the figures with error_bound_/unresolved_


def error_bound(scalars: Mapping[str, float], name: str) -> float | str | None:
    """A figure's relative error bound from a point's scalars (ehl/error_bounds.py): UNRESOLVED_WORD where the solve
    cannot bound it, else the bound; None in a file without either (written before the bounds)."""
    if scalars.get(f"{UNRESOLVED}{name}") == 1.0:
        return UNRESOLVED_WORD
    return scalars.get(f"error_bound_{name}")
ROUND_OFF = 1e-12  # |x| below this fraction of the largest value of its unit in its group: shown as 0 (round-off)


def scalar_unit(key: str, units: str) -> Unit:
    """The unit a scalar is shown in: films in µm, other lengths in mm, fractions in %, absolute temperatures in
    °C, the rest by `display`."""
    if units == "K" and key in ABSOLUTE_TEMPERATURE_KEYS:
        return CELSIUS
    if units == "m":
        return display("m") if key in FILM_KEYS else MILLIMETRE
    if units == "1" and key in PERCENT_KEYS:
        return PERCENT
    return display(units)


def group_of(key: str) -> str:
    """The SCALAR_GROUPS theme of a scalar, 'other' if none."""
    return next((name for name, keys in SCALAR_GROUPS if key in keys), "other")
