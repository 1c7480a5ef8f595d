"""Oil-film fields of each point (Fig. 12, 18): contour maps, 3-D surfaces and centre-line profiles along
and across the entrainment, in Hertzian coordinates x/b, y/a."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
import math

from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.colors import LightSource, Normalize
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
import numpy as np
from scipy.interpolate import RegularGridInterpolator

from facegear_tehl.plots.common import Output, figure, legend, title
from facegear_tehl.results import PointResult, Result
from facegear_tehl.solution import Field
from facegear_tehl.units import CELSIUS, MILLIMETRE, Unit, display

CONTOUR_LEVELS = 40
FILM_COLOUR_LIMIT = 1.6  # film maps and surfaces show h up to this multiple of h_c (the inlet gap is much larger)
SIGNED_CMAP = "RdBu_r"  # fields of both signs: blue below zero, white at zero, red above


@dataclass(frozen=True)
class _Style:
    """How one kind of field is drawn: file-name stem, quantity (axis label), group (fields sharing a profile
    panel), colour map, colour of overlaid lines."""

    stem: str
    quantity: str
    group: str
    cmap: str
    ink: str


def _unit(units: str) -> Unit:
    """The display unit of a field in SI `units`: temperatures (absolute) in °C, the others as in tables."""
    return CELSIUS if units == "K" else display(units)


def _style(name: str) -> _Style | None:
    """The style of a field by its dataset name; None for fields not drawn."""
    if name == "pressure":
        return _Style("pressure", "pressure p", "pressure", "inferno", "white")
    if name == "film_thickness":
        return _Style("film", "film thickness h", "film", "viridis", "black")
    for prefix, label, cmap in (("temperature", "temperature T", "plasma"), ("heat_flux", "heat flux q", "magma")):
        if name.startswith(prefix):
            return _Style(name, label, prefix, cmap, "white")
    return None


@dataclass(frozen=True)
class _Map:
    """A field on Hertzian coordinates X = x/b (nx,), Y = y/a (ny,), values (ny, nx) in display units;
    label: what it is (the dataset's description)."""

    label: str
    X: np.ndarray
    Y: np.ndarray
    values: np.ndarray
    unit: Unit
    style: _Style
    vmin: float
    vmax: float

    @property
    def units(self) -> str:
        return self.unit.label

    @property
    def clipped(self) -> bool:
        return self.vmax < float(self.values.max())

    @property
    def signed(self) -> bool:
        """Values of both signs (a heat flux that reverses): drawn with a diverging map centred on zero."""
        return self.vmin < 0.0 < self.vmax

    @property
    def cmap(self) -> str:
        return SIGNED_CMAP if self.signed else self.style.cmap

    @property
    def ink(self) -> str:
        return "black" if self.signed else self.style.ink

    @property
    def axis_label(self) -> str:
        return f"{self.style.quantity} ({self.units})"


def _map(point: PointResult, name: str, data: Field, style: _Style) -> _Map:
    unit = _unit(data.units)
    values = unit(np.asarray(data.values, dtype=float))
    vmin, vmax = float(values.min()), float(values.max())
    if style.group == "pressure":
        vmin = 0.0
    if style.group == "film" and "h_c" in point.scalars:
        vmax = min(vmax, FILM_COLOUR_LIMIT * point.scalars["h_c"] * unit.factor)
    if vmin < 0.0 < vmax:
        vmax = max(-vmin, vmax)
        vmin = -vmax
    return _Map(
        label=data.description or name.replace("_", " "),
        X=point.axes["x"].values / point.scalars["b"],
        Y=point.axes["y"].values / point.scalars["a"],
        values=values,
        unit=unit,
        style=style,
        vmin=vmin,
        vmax=vmax,
    )


def draw_fields(result: Result, points: Sequence[PointResult], out: Output) -> None:
    """Per point: contour maps and 3-D surfaces of every field, and centre-line profiles (Fig. 12, 18)."""
    for point in points:
        maps, reasons = _point_maps(point)
        for reason in reasons:
            out.skip(f"fields {point.name}", reason)
        for m in maps:
            out.save(_contour_figure(result, point, m), f"{point.name}_{m.style.stem}_contour")
            out.save(_surface_figure(result, point, m), f"{point.name}_{m.style.stem}_surface")
        if maps:
            out.save(_profiles_figure(result, point, maps), f"{point.name}_profiles")
    if points and not any(p.fields for p in points):
        return
    missing = [g for g in ("temperature", "heat_flux") if not any(_has_group(p, g) for p in points)]
    for group in missing:
        out.skip(f"fields {group}", f"no {group}* datasets in the file (written by the thermal model / heat budget)")


def _has_group(point: PointResult, group: str) -> bool:
    return any((s := _style(name)) is not None and s.group == group for name in point.fields)


def _point_maps(point: PointResult) -> tuple[list[_Map], list[str]]:
    """The drawable fields of a point, and why any are not drawn."""
    if not point.fields:
        state = point.message or ("converged" if point.converged else "not converged")
        return [], [f"no fields in the file ({state})"]
    missing = [key for key in ("a", "b") if key not in point.scalars] + [
        axis for axis in ("x", "y") if axis not in point.axes
    ]
    if missing:
        return [], [f"fields without {', '.join(missing)}"]
    maps, reasons = [], []
    for name, data in point.fields.items():
        style = _style(name)
        if style is None:
            continue
        m = _map(point, name, data, style)
        if m.vmax > m.vmin:
            maps.append(m)
        else:
            reasons.append(f"{name} is uniform ({m.vmin:.4g} {m.units})")
    return maps, reasons


def _levels(m: _Map) -> np.ndarray:
    return np.linspace(m.vmin, m.vmax, CONTOUR_LEVELS + 1)


def _contour_figure(result: Result, point: PointResult, m: _Map) -> Figure:
    """Filled contours with the Hertz ellipse, the entrainment direction and the profile sections."""
    fig = figure(height=5.6)
    ax = fig.add_subplot()
    filled = ax.contourf(m.X, m.Y, np.minimum(m.values, m.vmax), levels=_levels(m), cmap=m.cmap,
                         extend="max" if m.clipped else "neither")
    ax.contour(m.X, m.Y, m.values, levels=_levels(m)[::5][1:], colors=m.ink, linewidths=0.3, alpha=0.5)
    colourbar = fig.colorbar(filled, ax=ax, shrink=0.9, label=m.axis_label)
    ticks = MaxNLocator(8).tick_values(m.vmin, m.vmax)
    colourbar.set_ticks(ticks[(ticks >= m.vmin) & (ticks <= m.vmax)])
    along, across = _section_directions(point)
    _draw_ellipse(ax, m.ink)
    for direction, line_style in ((along, "--"), (across, ":")):
        t = np.array([-10.0, 10.0])
        ax.plot(t * direction[0], t * direction[1], line_style, color=m.ink, linewidth=0.8, alpha=0.7)
    _draw_entrainment(ax, point, along, m)
    _mark_extremum(ax, m)
    ax.set_xlim(m.X[0], m.X[-1])
    ax.set_ylim(m.Y[0], m.Y[-1])
    ax.set_aspect("equal")
    _hertz_axis_labels(ax, point)
    clipped = f" (colours clipped at {m.vmax:.3g} {m.units})" if m.clipped else ""
    ax.set_title(title(result, m.label + clipped, point))
    legend(ax, loc="upper left", fontsize="small", framealpha=0.8)
    return fig


def _hertz_axis_labels(ax: Axes, point: PointResult) -> None:
    ax.set_xlabel(f"x / b   (b = {MILLIMETRE.text(point.scalars['b'], '.3g')}, minor axis)")
    ax.set_ylabel(f"y / a   (a = {MILLIMETRE.text(point.scalars['a'], '.3g')}, major axis)")


def _draw_ellipse(ax: Axes, ink: str) -> None:
    angle = np.linspace(0.0, 2.0 * math.pi, 361)
    ax.plot(np.cos(angle), np.sin(angle), "-", color=ink, linewidth=1.2, label="Hertz ellipse")


def _draw_entrainment(ax: Axes, point: PointResult, along: np.ndarray, m: _Map) -> None:
    """An arrow along the entrainment near the inlet, labelled with its true angle to x."""
    length = 0.2 * (m.X[-1] - m.X[0])
    tail = np.array([m.X[0] + 0.08 * (m.X[-1] - m.X[0]), m.Y[0] + 0.1 * (m.Y[-1] - m.Y[0])])
    ax.annotate("", xy=tail + length * along, xytext=tail,
                arrowprops={"arrowstyle": "-|>", "color": m.ink, "linewidth": 1.5})
    angle = point.scalars.get("entrainment_angle", 0.0)
    ax.text(tail[0], tail[1] + 0.04 * (m.Y[-1] - m.Y[0]), f"entrainment (ψ = {angle:.1f}° to x at true scale)",
            color=m.ink, fontsize="small")


def _mark_extremum(ax: Axes, m: _Map) -> None:
    """The pressure maximum or the film minimum, where the eye should go."""
    if m.style.group not in ("pressure", "film"):
        return
    index = np.argmax(m.values) if m.style.group == "pressure" else np.argmin(m.values)
    row, column = np.unravel_index(index, m.values.shape)
    name = "p_max" if m.style.group == "pressure" else "h_min"
    ax.plot(m.X[column], m.Y[row], "o", markerfacecolor="none", markeredgecolor="tab:cyan", markersize=20,
            markeredgewidth=1.2, label=f"{name} = {m.values[row, column]:.4g} {m.units}")


def _surface_figure(result: Result, point: PointResult, m: _Map) -> Figure:
    """3-D surface over the region where the field is in its colour range (pressure above 0.5 % of its
    maximum, film clipped at FILM_COLOUR_LIMIT h_c), lit so the pressure spike stands out, over its contour
    map on the floor of the box with the Hertz ellipse."""
    fig = figure(height=5.6)
    ax = fig.add_subplot(projection="3d", computed_zorder=False)
    rows, columns = _active_region(m)
    X, Y, values = m.X[columns], m.Y[rows], np.minimum(m.values[rows, columns], m.vmax)
    XX, YY = np.meshgrid(X, Y)
    floor = m.vmin - 0.6 * (m.vmax - m.vmin)
    ax.contourf(XX, YY, values, levels=_levels(m), cmap=m.cmap, zdir="z", offset=floor, zorder=0)
    angle = np.linspace(0.0, 2.0 * math.pi, 361)
    ax.plot(np.cos(angle), np.sin(angle), zs=floor, zdir="z", color="tab:cyan", linewidth=1.5,
            label="Hertz ellipse (on the floor map)", zorder=1)
    norm, cmap = Normalize(m.vmin, m.vmax), colormaps[m.cmap]
    # Lit from above to show the shape, except a signed field, whose white zero level lighting would grey.
    colours = cmap(norm(values)) if m.signed else LightSource(azdeg=315, altdeg=50).shade(
        values, cmap=cmap, norm=norm, blend_mode="soft")
    if m.style.group == "pressure":  # left out where there is no pressure, so the floor map shows there
        values = np.where(values <= 0.01 * m.vmax, np.nan, values)
    ax.plot_surface(XX, YY, values, facecolors=colours, rcount=min(len(Y), 160),
                    ccount=min(len(X), 257), linewidth=0, antialiased=False, shade=False, zorder=2)
    ax.set_zlim(floor, m.vmax)
    ticks = MaxNLocator(6).tick_values(m.vmin, m.vmax)
    ax.set_zticks(ticks[(ticks >= m.vmin) & (ticks <= m.vmax)])
    ax.xaxis.set_major_locator(MaxNLocator(6))
    ax.yaxis.set_major_locator(MaxNLocator(6))
    ax.set_xlabel("x / b  (outlet +)")
    ax.set_ylabel("y / a")
    ax.set_zlabel(m.axis_label)
    ax.set_box_aspect((1.3, 1.3, 0.9), zoom=0.92)
    ax.view_init(elev=28, azim=-65)
    clipped = f", clipped at {m.vmax:.3g} {m.units}" if m.clipped else ""
    ax.set_title(title(result, m.label + clipped, point))
    legend(ax, loc="upper left", fontsize="small")
    return fig


def _active_region(m: _Map) -> tuple[slice, slice]:
    """Index ranges (rows, columns) of the box around the drawn part of a field, two nodes of margin,
    never smaller than the Hertz ellipse."""
    if m.style.group == "film":
        active = m.values <= m.vmax
    else:
        rest = 0.0 if m.signed else m.vmin
        active = np.abs(m.values - rest) >= 0.005 * (m.vmax - m.vmin)
    active |= (np.abs(m.X)[None, :] <= 1.0) & (np.abs(m.Y)[:, None] <= 1.0)
    rows, columns = np.nonzero(active)
    return (slice(max(rows.min() - 2, 0), rows.max() + 3), slice(max(columns.min() - 2, 0), columns.max() + 3))


def _section_directions(point: PointResult) -> tuple[np.ndarray, np.ndarray]:
    """Unit vectors in Hertzian coordinates along the entrainment and across it.

    Along: the true entrainment direction (angle psi to x), mapped to (cos psi / b, sin psi / a).
    Across: perpendicular in Hertzian coordinates, i.e. the ellipse diameter conjugate to the entrainment;
    it runs from edge to edge of the ellipse, which the physical perpendicular does not in a skewed,
    elongated contact. Both cross the ellipse edge at +-1.
    """
    psi = math.radians(point.scalars.get("entrainment_angle", 0.0))
    along = np.array([math.cos(psi) / point.scalars["b"], math.sin(psi) / point.scalars["a"]])
    along /= np.hypot(*along)
    return along, np.array([-along[1], along[0]])


def _section(m: _Map, direction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Values along t * direction through the centre, where the line is inside the grid."""
    step = 0.5 * min(m.X[1] - m.X[0], m.Y[1] - m.Y[0])
    reach = float(np.hypot(max(abs(m.X[0]), abs(m.X[-1])), max(abs(m.Y[0]), abs(m.Y[-1]))))
    t = np.arange(-reach, reach + step, step)
    X, Y = t * direction[0], t * direction[1]
    inside = (X >= m.X[0]) & (X <= m.X[-1]) & (Y >= m.Y[0]) & (Y <= m.Y[-1])
    interpolate = RegularGridInterpolator((m.Y, m.X), m.values)
    return t[inside], interpolate(np.column_stack([Y[inside], X[inside]]))


def _profiles_figure(result: Result, point: PointResult, maps: Sequence[_Map]) -> Figure:
    """Rows: pressure, film, temperatures, heat flux; columns: along and across the entrainment."""
    groups: dict[str, list[_Map]] = {}
    for m in maps:
        groups.setdefault(m.style.group, []).append(m)
    fig = figure(width=10.0, height=2.6 * len(groups) + 0.8)
    axes = fig.subplots(len(groups), 2, sharex="col", squeeze=False)
    along, across = _section_directions(point)
    angle = point.scalars.get("entrainment_angle", 0.0)
    titles = (f"along the entrainment (ψ = {angle:.1f}° to x)", "across the entrainment")
    for row, (group, members) in zip(axes, groups.items()):
        for ax, direction in zip(row, (along, across)):
            for m in members:
                t, values = _section(m, direction)
                ax.plot(t, values, label=m.label if len(members) > 1 else None)
            _decorate_profile(ax, point, group, members)
    for ax, column_title in zip(axes[0], titles):
        ax.set_title(column_title)
    axes[-1][0].set_xlabel("position / Hertz radius  (inlet −, outlet +; ellipse edge at ±1)")
    axes[-1][1].set_xlabel("position / Hertz radius  (ellipse edge at ±1)")
    fig.suptitle(title(result, "centre-line profiles", point))
    return fig


def _decorate_profile(ax: Axes, point: PointResult, group: str, members: Sequence[_Map]) -> None:
    m = members[0]
    ax.set_ylabel(m.axis_label)
    for edge in (-1.0, 1.0):
        ax.axvline(edge, color="grey", linewidth=0.6, linestyle=":")
    if group == "pressure" and "p_hertz" in point.scalars:
        t = np.linspace(-1.0, 1.0, 201)
        ax.plot(t, m.unit(point.scalars["p_hertz"]) * np.sqrt(1.0 - t**2), "--", color="grey",
                linewidth=0.8, label="dry Hertz")
    if group == "film":
        ax.set_ylim(0.0, m.vmax)
    ax.grid(alpha=0.3)
    legend(ax, fontsize="small")
