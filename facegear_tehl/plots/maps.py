"""Contour maps of every field of a point, on request (`--what maps`): pressure, film, each temperature
layer as ΔT and each heat flux, in Hertzian coordinates x/b, y/a with the Hertz ellipse, the entrainment
direction and the centre-line sections (Fig. 12, 18 of the seed paper)."""

from __future__ import annotations

from collections.abc import Sequence
import math

from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
import numpy as np

from facegear_tehl.plots.common import Output, figure, legend, title
from facegear_tehl.plots.field_data import FieldMap, section_directions
from facegear_tehl.results import PointResult, Result
from facegear_tehl.units import MILLIMETRE

CONTOUR_LEVELS = 40  # filled levels: smooth to the eye, and every 5th drawn as a line


def draw_maps(result: Result, rows: Sequence[tuple[PointResult, dict[str, FieldMap]]], out: Output) -> None:
    """A contour map per point and field, `<point>_<field>_contour`."""
    for point, maps in rows:
        for m in maps.values():
            out.save(map_figure(result, point, m), f"{point.name}_{_stem(m)}_contour")


def _stem(m: FieldMap) -> str:
    return "film" if m.name == "film_thickness" else m.name


def levels(m: FieldMap) -> np.ndarray:
    return np.linspace(m.vmin, m.vmax, CONTOUR_LEVELS + 1)


def map_figure(result: Result, point: PointResult, m: FieldMap) -> Figure:
    """Filled contours with the Hertz ellipse, the entrainment direction and the profile sections."""
    fig = figure(height=5.6)
    ax = fig.add_subplot()
    values = np.clip(m.values, m.vmin, m.vmax)
    filled = ax.contourf(m.X, m.Y, values, levels=levels(m), cmap=m.cmap, extend="max" if m.clipped else "neither")
    ax.contour(m.X, m.Y, values, levels=levels(m)[::5][1:], colors=m.ink, linewidths=0.3, alpha=0.5)
    colourbar = fig.colorbar(filled, ax=ax, shrink=0.9, label=m.axis_label)
    ticks = MaxNLocator(8).tick_values(m.vmin, m.vmax)
    colourbar.set_ticks(ticks[(ticks >= m.vmin) & (ticks <= m.vmax)])
    along, across = section_directions(point)
    angle = np.linspace(0.0, 2.0 * math.pi, 361)
    ax.plot(np.cos(angle), np.sin(angle), "-", color=m.ink, linewidth=1.2, label="Hertz ellipse")
    for direction, line_style in ((along, "--"), (across, ":")):
        t = np.array([-10.0, 10.0])
        ax.plot(t * direction[0], t * direction[1], line_style, color=m.ink, linewidth=0.8, alpha=0.7)
    _draw_entrainment(ax, point, along, m)
    _mark_extremum(ax, m)
    ax.set_xlim(m.X[0], m.X[-1])
    ax.set_ylim(m.Y[0], m.Y[-1])
    ax.set_aspect("equal")
    ax.set_xlabel(f"$x/b$   ($b$ = {MILLIMETRE.text(point.scalars['b'], '.3g')}, minor axis)")
    ax.set_ylabel(f"$y/a$   ($a$ = {MILLIMETRE.text(point.scalars['a'], '.3g')}, major axis)")
    clipped = f", colours clipped at {m.vmax:.3g} {m.unit.label}" if m.clipped else ""
    ax.set_title(m.label + clipped, fontsize="medium")
    fig.suptitle(title(result, "map", point))
    legend(ax, loc="upper left", fontsize="small", framealpha=0.8)
    return fig


def _draw_entrainment(ax: Axes, point: PointResult, along: np.ndarray, m: FieldMap) -> None:
    """An arrow along the entrainment near the inlet, labelled with its true angle to x."""
    length = 0.2 * (m.X[-1] - m.X[0])
    tail = np.array([m.X[0] + 0.08 * (m.X[-1] - m.X[0]), m.Y[0] + 0.1 * (m.Y[-1] - m.Y[0])])
    ax.annotate("", xy=tail + length * along, xytext=tail,
                arrowprops={"arrowstyle": "-|>", "color": m.ink, "linewidth": 1.5})
    angle = point.scalars.get("entrainment_angle", 0.0)
    ax.text(tail[0], tail[1] + 0.04 * (m.Y[-1] - m.Y[0]), f"entrainment (ψ = {angle:.1f}° to x at true scale)",
            color=m.ink, fontsize="small")


def _mark_extremum(ax: Axes, m: FieldMap) -> None:
    """The pressure maximum or the film minimum, where the eye should go."""
    if m.group not in ("pressure", "film"):
        return
    index = np.argmax(m.values) if m.group == "pressure" else np.argmin(m.values)
    row, column = np.unravel_index(index, m.values.shape)
    name = "$p_{max}$" if m.group == "pressure" else "$h_{min}$"
    ax.plot(m.X[column], m.Y[row], "o", markerfacecolor="none", markeredgecolor="tab:cyan", markersize=20,
            markeredgewidth=1.2, label=f"{name} = {m.values[row, column]:.4g} {m.unit.label}")
