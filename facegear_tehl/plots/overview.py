"""One sheet of all points: the pressure, film and mid-film ΔT maps in Hertzian coordinates, pressure and film on
one colour scale for every point, ΔT on each point's own scale centred at 0 (a colour bar per map), and the
pressure at true scale in mm, where the Hertz ellipse of a face gear is a strip 35-58 times longer than wide."""

from __future__ import annotations

from collections.abc import Sequence
import math
import textwrap

from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.font_manager import FontProperties
from matplotlib.image import AxesImage
import numpy as np

from facegear_tehl.plots.common import Output, figure, title
from facegear_tehl.plots.field_data import FieldMap, interior_place
from facegear_tehl.results import PointResult, Result
from facegear_tehl.units import MILLIMETRE

COLUMNS = ("pressure", "film_thickness", "temperature_mid")  # the maps of the sheet, left to right
VIEW_X = (-2.5, 1.5)  # x/b shown (the film and ΔT downstream of the ellipse, the inlet meniscus region left out)
VIEW_Y = (-1.5, 1.5)  # y/a shown
STRIP_REACH = 1.3  # the true-scale strip shows +-1.3 semi-axes around the centre
ROW_HEIGHT = 1.75  # inches per point
ELLIPSE = np.linspace(0.0, 2.0 * math.pi, 181)


def draw_overview(result: Result, rows: Sequence[tuple[PointResult, dict[str, FieldMap]]], out: Output) -> None:
    """The sheet of the points with a pressure or film field, `overview`."""
    shown = [(point, maps) for point, maps in rows if {"pressure", "film_thickness"} & maps.keys()]
    if shown:
        out.save(overview_figure(result, shown), "overview")


def overview_figure(result: Result, rows: Sequence[tuple[PointResult, dict[str, FieldMap]]]) -> Figure:
    """One row per point (its maps by name): the COLUMNS it has, then the true-scale pressure strip."""
    columns = [name for name in COLUMNS if any(name in maps for _, maps in rows)]
    fig = figure(width=3.0 * len(columns) + 4.2, height=ROW_HEIGHT * len(rows) + 1.6)
    axes = fig.subplots(len(rows), len(columns) + 1, squeeze=False,
                        width_ratios=[1.0] * len(columns) + [1.6])
    limits = {name: _common_limits([maps[name] for _, maps in rows if name in maps]) for name in columns}
    for j, name in enumerate(columns):
        own = name == "temperature_mid"  # each point's ΔT on its own scale, a colour bar per map
        meshes = [_hertz_map(ax, point, maps[name], (maps[name].vmin, maps[name].vmax) if own else limits[name])
                  for ax, (point, maps) in zip(axes[:, j], rows) if name in maps]
        for ax, (_, maps) in zip(axes[:, j], rows):
            if name not in maps:
                ax.set_axis_off()
        if meshes and own:
            for mesh in meshes:
                bar = fig.colorbar(mesh, ax=mesh.axes, location="right", shrink=0.9, aspect=12)
                bar.set_label("mid-film ΔT (K)", fontsize="x-small")
                bar.ax.tick_params(labelsize="x-small")
        elif meshes:
            first = next(maps[name] for _, maps in rows if name in maps)
            bar = fig.colorbar(meshes[0], ax=axes[:, j], location="bottom", shrink=0.9, aspect=25)
            bar.set_label(first.axis_label + (" (mid-film)" if first.group == "temperature" else ""))
    for ax, (point, maps) in zip(axes[:, -1], rows):
        if "pressure" in maps:
            _true_scale(ax, point, maps["pressure"], limits["pressure"])
        else:
            ax.set_axis_off()
    for ax, (point, _) in zip(axes[:, 0], rows):
        ax.set_ylabel(f"{point.name}\n$y/a$")
    for ax in axes[:-1, : len(columns)].ravel():  # the maps share their Hertzian axes: tick labels outside only
        ax.tick_params(labelbottom=False)
    for ax in axes[:, 1: len(columns)].ravel():
        ax.tick_params(labelleft=False)
    for ax in axes[-1, : len(columns)]:
        ax.set_xlabel("$x/b$ (inlet −, outlet +)")
    subject = "pressure, film and temperature rise" if "temperature_mid" in columns else "pressure and film"
    heading = title(result, f"{subject} at every point") + "\n" + _grid_note(rows[0][0], rows[0][1][columns[0]])
    fig.suptitle(_fitted(heading, fig))
    return fig


def _fitted(text: str, fig: Figure) -> str:
    """`text` broken into lines as wide as the sheet at the title's size (a one-point sheet is narrower than the grid
    note; a character of the default sans serif is about 0.55 em wide)."""
    size = FontProperties(size="large").get_size_in_points()
    width = max(int(fig.get_figwidth() * 72.0 / (0.55 * size)), 20)
    return "\n".join(textwrap.fill(line, width) for line in text.split("\n"))


def _grid_note(point: PointResult, m: FieldMap) -> str:
    """The stepped outlines of the maps (the outlet crescent) are the node spacing, not physics: a line for the
    title."""
    return (f"stepped outlines (the outlet crescent) are the solver's nodes, Δx/b = {m.X[1] - m.X[0]:.3g}, "
            f"Δy/a = {m.Y[1] - m.Y[0]:.3g} at {point.name}, not a shape of the film")


def _common_limits(maps: Sequence[FieldMap]) -> tuple[float, float]:
    """One colour range for a column: from the lowest to the highest limit of its maps."""
    return min(m.vmin for m in maps), max(m.vmax for m in maps)


def _extent(horizontal: np.ndarray, vertical: np.ndarray) -> tuple[float, float, float, float]:
    """The image extent of values on the uniform node coordinates of the solver grid (cells centred on nodes)."""
    dh, dv = 0.5 * (horizontal[1] - horizontal[0]), 0.5 * (vertical[1] - vertical[0])
    return horizontal[0] - dh, horizontal[-1] + dh, vertical[0] - dv, vertical[-1] + dv


def _image_style(m: FieldMap, limits: tuple[float, float]) -> dict:
    """An image of the field, interpolated between the nodes, on the column's colour range."""
    return {"cmap": m.cmap, "vmin": limits[0], "vmax": limits[1], "origin": "lower", "interpolation": "bilinear",
            "aspect": "auto"}


def _hertz_map(ax: Axes, point: PointResult, m: FieldMap, limits: tuple[float, float]) -> AxesImage:
    """The map in Hertzian coordinates with the Hertz ellipse (the unit circle), its extreme in the title."""
    mesh = ax.imshow(m.values, extent=_extent(m.X, m.Y), **_image_style(m, limits))
    ax.plot(np.cos(ELLIPSE), np.sin(ELLIPSE), color=m.ink, linewidth=0.7)
    ax.set_xlim(max(VIEW_X[0], m.X[0]), min(VIEW_X[1], m.X[-1]))
    ax.set_ylim(max(VIEW_Y[0], m.Y[0]), min(VIEW_Y[1], m.Y[-1]))
    ax.set_aspect("equal")
    ax.set_title(_extremes(point, m), fontsize="small")
    place = interior_place(point) if m.group == "temperature" else None
    if place is not None:
        ax.plot(*place, "v", color="tab:cyan", markeredgecolor="black", markersize=6)
    return mesh


def _extremes(point: PointResult, m: FieldMap) -> str:
    """The extremes of a map that the eye looks for, from the point's scalars (whole film)."""
    s = point.scalars
    if m.group == "pressure" and "p_max" in s:
        return f"$p_{{max}}$ = {m.unit(s['p_max']):.0f} {m.unit.label}"
    if m.group == "film" and {"h_c", "h_min"} <= s.keys():
        return f"$h_c$ = {m.unit(s['h_c']):.3g}, $h_{{min}}$ = {m.unit(s['h_min']):.3g} {m.unit.label}"
    if m.group == "temperature" and {"dT_max", "dT_min"} <= s.keys():
        mark = " (▼)" if interior_place(point) is not None else ""
        return rf"$\Delta T_{{max}}$ = {s['dT_max']:.1f}, $\Delta T_{{min}}$ = {s['dT_min']:.1f} K{mark}"
    return m.label


def _true_scale(ax: Axes, point: PointResult, m: FieldMap, limits: tuple[float, float]) -> None:
    """The pressure at true scale in mm, major axis (y) across the page, minor axis (x) up."""
    a_mm, b_mm = MILLIMETRE(point.scalars["a"]), MILLIMETRE(point.scalars["b"])
    ax.imshow(m.values.T, extent=_extent(m.Y * a_mm, m.X * b_mm), **_image_style(m, limits))
    ax.plot(a_mm * np.sin(ELLIPSE), b_mm * np.cos(ELLIPSE), color="grey", linewidth=0.5)
    ax.set_xlim(-STRIP_REACH * a_mm, STRIP_REACH * a_mm)
    ax.set_ylim(-STRIP_REACH * b_mm, STRIP_REACH * b_mm)
    ax.set_aspect("equal")
    ax.set_yticks([])
    ax.set_title(f"true scale: 2a = {2 * a_mm:.3g} mm, 2b = {2 * b_mm:.3g} mm", fontsize="small")
    ax.set_xlabel(f"$y$ ({MILLIMETRE.label}), pressure")
