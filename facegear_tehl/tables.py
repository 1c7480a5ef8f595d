"""Plain-text tables for the terminal: aligned columns under headers, and the text of their cells."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
import math

from facegear_tehl.units import Unit, display


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
