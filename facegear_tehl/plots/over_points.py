"""Quantities over the meshing points, shared by the trend, friction and heat figures: values per point, the
x axis (path coordinate or point names) and a series with open markers where a point did not converge."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

from matplotlib.axes import Axes
import numpy as np

from facegear_tehl.results import Result
from facegear_tehl.units import MILLIMETRE

MANY_POINTS = 8  # above this many points, trend axes show the path coordinate without point names
LOAD_JUMP = 0.1  # a change of the tooth load between neighbouring path rows above this share of its largest
# value is a jump between one and two tooth pairs in contact (the smooth change over a row is ~1 %)
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


def on_path(result: Result, names: Sequence[str]) -> bool:
    """The points `names` all have distinct path coordinates: the trend axis is the path coordinate s."""
    coordinates = [result.points[n].scalars.get("path_coordinate") if n in result.points else None for n in names]
    return None not in coordinates and len(set(coordinates)) == len(names) > 1


def point_axis(result: Result, names: Sequence[str]) -> tuple[dict[str, float], Callable[[Axes], None]]:
    """x position per point name (path coordinate in mm when every point has one), and the axis labeller."""
    if on_path(result, names):
        positions = {n: MILLIMETRE(float(result.points[n].scalars["path_coordinate"])) for n in names}

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


def continuous_runs(result: Result, names: Sequence[str]) -> list[list[str]]:
    """`names` (in path order) cut into runs between which the tooth load jumps, where a line joining the
    points would draw a trend that is not there: the load of the /contact path changes by more than
    LOAD_JUMP of the pair's load between two neighbouring rows whose midpoint lies between the points. One
    run without a /contact path."""
    table = result.contact
    s_points = [result.points[n].scalars.get("path_coordinate") if n in result.points else None for n in names]
    if not {"s", "load"} <= table.keys() or None in s_points:
        return [list(names)]
    s = np.asarray(table["s"].values, dtype=float)
    load = np.asarray(table["load"].values, dtype=float)
    jumps = 0.5 * (s[1:] + s[:-1])[np.abs(np.diff(load)) > LOAD_JUMP * np.abs(load).max()]
    runs = [[names[0]]]
    for name, s_from, s_to in zip(names[1:], s_points, s_points[1:]):
        low, high = sorted((s_from, s_to))
        if np.any((jumps > low) & (jumps < high)):
            runs.append([])
        runs[-1].append(name)
    return runs


def plot_series(ax: Axes, result: Result, positions: Mapping[str, float], values: Mapping[str, float],
                label: str, style: str = "o-", errors: Mapping[str, float] | None = None,
                unresolved: Sequence[str] = ()) -> None:
    """A quantity over the points: markers, with error bars where `errors` (absolute, display units) has
    them and a cross over the `unresolved` points, joined by lines within the runs of `continuous_runs`; open
    markers for points that did not converge."""
    names = [n for n in positions if n in values]
    marker, line_style = style[0], style[1:] or "-"
    x = [positions[n] for n in names]
    y = [values[n] for n in names]
    error = None if not errors else [abs(errors.get(n, 0.0)) for n in names]
    container = ax.errorbar(x, y, yerr=error, fmt=marker, capsize=3, label=label)
    colour = container.lines[0].get_color()
    for run in continuous_runs(result, names):
        if len(run) > 1:
            ax.plot([positions[n] for n in run], [values[n] for n in run], line_style, color=colour)
    crossed = [n for n in names if n in unresolved]
    if crossed:
        ax.plot([positions[n] for n in crossed], [values[n] for n in crossed], "x", color="black", markersize=9)
    open_names = [n for n in names if n in result.points and not result.points[n].converged]
    if open_names:
        ax.plot([positions[n] for n in open_names], [values[n] for n in open_names], "o", color="white",
                markeredgecolor=colour, markersize=7)


def error_bars(result: Result, key: str, values: Mapping[str, float]) -> tuple[dict[str, float], list[str]]:
    """The error bar of `key` per point in the units of `values` and the points whose `key` is unresolved (no bar):
    the solve's error bound error_bound_<key> |value| (ehl/error_bounds.py); in a file written before the bounds,
    |error_estimate_<key>| |value| and no point unresolved."""
    flags = per_point(result, f"unresolved_{key}")
    if not flags:
        estimates = per_point(result, f"error_estimate_{key}")
        return {n: abs(estimates[n] * v) for n, v in values.items()
                if n in estimates and np.isfinite(estimates[n])}, []
    bounds = per_point(result, f"error_bound_{key}")
    unresolved = [n for n in values if flags.get(n, 0.0) != 0.0]
    return {n: bounds[n] * abs(v) for n, v in values.items() if n in bounds and n not in unresolved}, unresolved


def bars_note(ax: Axes, result: Result) -> None:
    """A legend entry saying what the error bars are: the error bounds (a cross over a point whose figure is
    unresolved) or, in a file written before the bounds, the error estimates."""
    bounded = any(k.startswith("unresolved_") for p in result.points.values() for k in p.scalars)
    ax.plot([], [], " ", label="error bars: the solver's error bounds" if bounded
            else "error bars: the solver's error estimates")
    if bounded:
        ax.plot([], [], "x", color="black", label="cross: unresolved (no bound)")


def jump_note(ax: Axes, result: Result, names: Sequence[str]) -> None:
    """A legend entry saying why lines break, when they do."""
    if len(continuous_runs(result, names)) > 1:
        ax.plot([], [], " ", label="no line across a jump of the tooth load")


def not_converged_note(ax: Axes, result: Result) -> None:
    """A legend entry explaining the open markers, when a point did not converge."""
    if not all(p.converged for p in result.points.values()):
        ax.plot([], [], "o", color="white", markeredgecolor="black", label="open marker: not converged")
