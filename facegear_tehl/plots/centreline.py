"""The literature view of a point (as Fig. 12 of the seed paper and the thermal EHL papers it follows): the
centre line along the entrainment with pressure and film thickness on twin axes, h_c and h_min marked, and
the temperature rise ΔT across the film (mid-film, both surfaces) below it."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from matplotlib.axes import Axes
from matplotlib.figure import Figure
import numpy as np

from facegear_tehl.plots.common import Output, figure, title
from facegear_tehl.plots.field_data import FieldMap, interior_place, section, section_directions, section_length
from facegear_tehl.results import PointResult, Result
from facegear_tehl.units import MILLIMETRE

FILM_AXIS_MARGIN = 0.15  # the film axis spans h_min .. FILM_COLOUR_LIMIT h_c widened by this share each side
PROFILE_COLOURS = {"pressure": "tab:red", "film": "tab:blue"}
TEMPERATURES = ("temperature_mid", "temperature_surface_1", "temperature_surface_2")  # drawn, in this order
TEMPERATURE_STYLES = ("-", "--", ":")


def draw_centreline(result: Result, rows: Sequence[tuple[PointResult, dict[str, FieldMap]]], out: Output) -> None:
    """The centre-line figure of each point with a pressure or film field, `<point>_centreline`."""
    for point, maps in rows:
        if {"pressure", "film_thickness"} & maps.keys():
            out.save(centreline_figure(result, point, maps), f"{point.name}_centreline")


def centreline_figure(result: Result, point: PointResult, maps: Mapping[str, FieldMap]) -> Figure:
    """Pressure and film on twin axes above, ΔT profiles below (when the point has temperatures), along the
    entrainment through the contact centre; t in Hertz radii, true length in mm on the top axis."""
    temperatures = [maps[name] for name in TEMPERATURES if name in maps]
    fig = figure(width=9.5, height=6.6 if temperatures else 4.0)
    grid = fig.subplots(2 if temperatures else 1, 2, squeeze=False, width_ratios=[2.6, 1.0])
    axes, legend_boxes = grid[:, 0], grid[:, 1]
    if temperatures:
        axes[1].sharex(axes[0])
        axes[0].tick_params(labelbottom=False)
    along, _ = section_directions(point)
    handles = _pressure_and_film(axes[0], point, maps, along)
    if temperatures:
        _temperatures(axes[1], point, temperatures, along)
    for box, row_handles in zip(legend_boxes, (handles, axes[-1].get_legend_handles_labels()[0])):
        box.set_axis_off()  # a legend box beside each panel (the right axis of the top one holds the film)
        box.legend(handles=row_handles, loc="upper left", fontsize="small", borderaxespad=0.0)
    axes[-1].set_xlabel("position along the entrainment / Hertz radius (inlet −, outlet +)")
    millimetres = 1e3 * section_length(point, along)
    top = axes[0].secondary_xaxis("top", functions=(lambda t: t * millimetres, lambda s: s / millimetres))
    top.set_xlabel(f"true distance from the centre ({MILLIMETRE.label})")
    angle = point.scalars.get("entrainment_angle", 0.0)
    fig.suptitle(title(result, f"centre line along the entrainment (ψ = {angle:.1f}° to x)", point))
    return fig


def _pressure_and_film(ax: Axes, point: PointResult, maps: Mapping[str, FieldMap], along: np.ndarray) -> list:
    """Pressure (left axis, with dry Hertz) and film thickness (right axis, h_c and h_min marked); the
    legend handles."""
    handles = []
    if "pressure" in maps:
        m = maps["pressure"]
        t, values = section(m, along)
        handles += ax.plot(t, values, color=PROFILE_COLOURS["pressure"], label="pressure $p$ (EHL)")
        if "p_hertz" in point.scalars:
            t_h = np.linspace(-1.0, 1.0, 201)
            handles += ax.plot(t_h, m.unit(point.scalars["p_hertz"]) * np.sqrt(1.0 - t_h**2), "--", color="grey",
                               linewidth=0.9, label=f"dry Hertz, $p_h$ = {m.unit(point.scalars['p_hertz']):.0f} "
                                                    f"{m.unit.label}")
        ax.set_ylabel(m.axis_label, color=PROFILE_COLOURS["pressure"])
        ax.set_ylim(bottom=0.0)
    for edge in (-1.0, 1.0):
        ax.axvline(edge, color="grey", linewidth=0.6, linestyle=":")
    ax.grid(alpha=0.3)
    if "film_thickness" in maps:
        handles += _film(ax.twinx(), point, maps["film_thickness"], along)
    return handles


def _film(ax: Axes, point: PointResult, m: FieldMap, along: np.ndarray) -> list:
    """The film on its own axis, which starts near h_min (not at 0): the film varies by tens of % only."""
    t, values = section(m, along)
    handles = ax.plot(t, values, color=PROFILE_COLOURS["film"], label="film thickness $h$")
    low = float(values.min())
    for key, style, text in (("h_c", "--", "$h_c$ (central)"), ("h_min", ":", "$h_{min}$ (whole film)")):
        if key in point.scalars:
            value = m.unit(point.scalars[key])
            low = min(low, value)
            handles.append(ax.axhline(value, color=PROFILE_COLOURS["film"], linestyle=style, linewidth=0.8, alpha=0.7,
                                      label=f"{text} = {value:.3g} {m.unit.label}"))
    high = m.vmax
    margin = FILM_AXIS_MARGIN * (high - low)
    ax.set_ylim(max(low - margin, 0.0), high + margin)
    ax.set_ylabel(m.axis_label, color=PROFILE_COLOURS["film"])
    return handles


def _temperatures(ax: Axes, point: PointResult, temperatures: list[FieldMap], along: np.ndarray) -> None:
    """ΔT across the film along the centre line, the extremes of the whole film in the legend."""
    for m, style in zip(temperatures, TEMPERATURE_STYLES):
        t, values = section(m, along)
        ax.plot(t, values, style, label=m.label)
    ax.axhline(0.0, color="black", linewidth=0.6)
    for edge in (-1.0, 1.0):
        ax.axvline(edge, color="grey", linewidth=0.6, linestyle=":")
    for key, text in (("dT_max", r"$\Delta T_{max}$"), ("dT_min", r"$\Delta T_{min}$")):
        if key in point.scalars:
            ax.plot([], [], " ", label=f"{text} = {point.scalars[key]:.1f} K{_where(point, key)}")
    ax.set_ylabel(temperatures[0].axis_label)
    ax.grid(alpha=0.3)


def _where(point: PointResult, key: str) -> str:
    """' at x/b = 0.81, y/a = -0.01' for an extreme whose place the file holds (x_<key>, y_<key>); for ΔT_min
    only when it is interior (field_data.interior_place), else what the value is."""
    if f"x_{key}" not in point.scalars or f"y_{key}" not in point.scalars:
        return " (whole film)"
    if key == "dT_min":
        place = interior_place(point)
        if place is None:
            return (": none below the inlet" if point.scalars[key] >= 0.0
                    else " on the domain boundary (whole film)")
        x, y = place
    else:
        x, y = point.scalars[f"x_{key}"] / point.scalars["b"], point.scalars[f"y_{key}"] / point.scalars["a"]
    return f" at $x/b$ = {x:.2f}, $y/a$ = {y:.2f}"
