"""Quantities over the meshing points, shared by the trend, friction and heat figures: values per point, the
x axis (path coordinate or point names) and a series with open markers where a point did not converge."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

from matplotlib.axes import Axes
import numpy as np

from facegear_tehl.results import Result
from facegear_tehl.units import MILLIMETRE

MANY_POINTS = 8  # above this many points, trend axes show the path coordinate without point names
SWEEP_FILE = "a sweep file holds one point on several grids (see sweep_error)"


def per_point(result: Result, key: str) -> dict[str, float]:
    """A quantity per point, from the point scalars or else from a /heat column of that name."""
    values = {name: float(p.scalars[key]) for name, p in result.points.items() if key in p.scalars}
    if not values and key in result.heat:
        values = dict(zip(heat_point_names(result), np.asarray(result.heat[key].values, dtype=float)))
    return values


def heat_point_names(result: Result) -> list[str]:
    """The point names of the /heat rows: its text column, else the file's points in order."""
    for column in result.heat.values():
        if np.asarray(column.values).dtype.kind in "US":
            return [str(v) for v in column.values]
    rows = len(next(iter(result.heat.values())).values)
    names = list(result.points)
    return names if len(names) == rows else [f"row {i + 1}" for i in range(rows)]


def point_axis(result: Result, names: Sequence[str]) -> tuple[dict[str, float], Callable[[Axes], None]]:
    """x position per point name (path coordinate in mm when every point has one), and the axis labeller."""
    coordinates = [result.points[n].scalars.get("path_coordinate") if n in result.points else None for n in names]
    if None not in coordinates and len(set(coordinates)) == len(names) > 1:
        positions = {n: MILLIMETRE(float(s)) for n, s in zip(names, coordinates)}

        def label_path(ax: Axes) -> None:
            if len(names) <= MANY_POINTS:
                ax.set_xticks(list(positions.values()), [f"{n}\n{s:.1f}" for n, s in positions.items()])
            ax.set_xlabel(f"meshing point, path coordinate s ({MILLIMETRE.label})")

        return positions, label_path
    positions = {n: float(i) for i, n in enumerate(names)}

    def label_names(ax: Axes) -> None:
        ax.set_xticks(list(positions.values()), list(names))
        ax.set_xlabel("meshing point")
        ax.set_xlim(-0.5, len(names) - 0.5)

    return positions, label_names


def plot_series(ax: Axes, result: Result, positions: Mapping[str, float], values: Mapping[str, float],
                 label: str, style: str = "o-") -> None:
    """A quantity over the points; open markers for points that did not converge."""
    names = [n for n in positions if n in values]
    x = [positions[n] for n in names]
    (line,) = ax.plot(x, [values[n] for n in names], style, label=label)
    open_names = [n for n in names if n in result.points and not result.points[n].converged]
    if open_names:
        ax.plot([positions[n] for n in open_names], [values[n] for n in open_names], "o", color="white",
                markeredgecolor=line.get_color(), markersize=7)


def not_converged_note(ax: Axes, result: Result) -> None:
    """A legend entry explaining the open markers, when a point did not converge."""
    if not all(p.converged for p in result.points.values()):
        ax.plot([], [], "o", color="white", markeredgecolor="black", label="open marker: not converged")
