"""Display units: how a value in SI units is shown in printed tables and on figure axes.

`DISPLAY` maps the SI units of the result file to the unit a reader sees (m -> µm, Pa -> MPa, J -> mJ, ...);
`display` looks a unit up. The few quantities shown otherwise (lengths along the contact path in mm,
absolute temperatures in °C, ratios in %) have their own unit below.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Unit:
    """A display unit: label, factor from SI, offset added after the factor, decimals of a table cell."""

    label: str
    factor: float = 1.0
    offset: float = 0.0
    decimals: int = 4

    def __call__(self, value: float | np.ndarray) -> float | np.ndarray:
        """`value` (SI) in this unit."""
        scaled = value * self.factor
        return scaled + self.offset if self.offset else scaled

    def text(self, value: float, spec: str) -> str:
        """'449 MPa': `value` (SI) in this unit, formatted with `spec` (e.g. '.0f'), then the label."""
        return f"{self(value):{spec}} {self.label}"


MILLIMETRE = Unit("mm", 1e3)  # lengths along the contact path and of the Hertz ellipse
CELSIUS = Unit("°C", offset=-273.15)  # absolute temperatures of fields on figures
CELSIUS_RISE = Unit("°C")  # a temperature rise on figures: the same number as in K
PERCENT = Unit("%", 100.0)  # ratios and relative changes, from fractions

DISPLAY: dict[str, Unit] = {
    "m": Unit("µm", 1e6, decimals=4),
    "Pa": Unit("MPa", 1e-6, decimals=1),
    "K": Unit("K", decimals=2),  # temperature rises
    "1": Unit("-", decimals=5),
    "J": Unit("mJ", 1e3),
    "W/m^2": Unit("MW/m²", 1e-6),
    "W/m2": Unit("MW/m²", 1e-6),
}
"""SI units of a result file -> display unit; units not listed (W, N, s, m/s, deg, ...) are shown as they are."""


def display(units: str) -> Unit:
    """The display unit of a value in SI `units`; the SI unit itself (factor 1) when it has none."""
    return DISPLAY.get(units, Unit(units))
