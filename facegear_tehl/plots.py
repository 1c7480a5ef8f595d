"""Figures from a result file: oil-film fields, trends over the meshing points, friction, heat budget,
the face gear contact path and convergence (matplotlib; the seed paper's figure numbers in the docstrings).

Everything is read through `results.read_result`; nothing is solved again. `plot_result` draws the figure
types asked for and reports the files written and, one line each, what it had no data for.

Figures are `matplotlib.figure.Figure` objects rendered by the Agg canvas: no display, no pyplot state.
Fields are drawn in Hertzian coordinates x/b, y/a, where the Hertz ellipse is the unit circle: face gear
ellipses are 35-58 times longer than wide and would be a line at true scale.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math
from pathlib import Path
from typing import Callable, Mapping, Sequence

from matplotlib.axes import Axes
from matplotlib import colormaps
from matplotlib.colors import LightSource, Normalize
from matplotlib.figure import Figure
from matplotlib.ticker import FormatStrFormatter, LogLocator, MaxNLocator, NullFormatter, NullLocator
import numpy as np
from scipy.interpolate import RegularGridInterpolator

from facegear_tehl.results import PointResult, Result, read_result
from facegear_tehl.schema import CaseError
from facegear_tehl.solution import Field

FIGURE_TYPES = ("fields", "trends", "friction", "heat", "contact", "convergence")
FORMATS = ("png", "pdf", "svg")
CONTOUR_LEVELS = 40
FILM_COLOUR_LIMIT = 1.6  # film maps and surfaces show h up to this multiple of h_c (the inlet gap is much larger)
SIGNED_CMAP = "RdBu_r"  # fields of both signs: blue below zero, white at zero, red above
MANY_POINTS = 8  # above this many points, trend axes show the path coordinate without point names


@dataclass
class PlotReport:
    """Files written, and one line per figure (type or point) not drawn, saying why."""

    written: list[Path] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class _Output:
    folder: Path
    fmt: str
    dpi: int
    report: PlotReport

    def save(self, figure: Figure, stem: str) -> None:
        path = self.folder / f"{stem}.{self.fmt}"
        self.folder.mkdir(parents=True, exist_ok=True)
        figure.savefig(path, dpi=self.dpi)
        self.report.written.append(path)

    def skip(self, what: str, reason: str) -> None:
        self.report.skipped.append(f"skipped {what}: {reason}")


def plot_file(path: str | Path, folder: str | Path, **options) -> PlotReport:
    """Read the result file at `path` and draw its figures into `folder` (options as `plot_result`)."""
    return plot_result(read_result(path), folder, **options)


def plot_result(
    result: Result,
    folder: str | Path,
    what: Sequence[str] = FIGURE_TYPES,
    points: Sequence[str] | None = None,
    fmt: str = "png",
    dpi: int = 150,
) -> PlotReport:
    """Draw the figure types `what` (see FIGURE_TYPES) of `result` into `folder`.

    points: the points whose fields and convergence are drawn (default all). Bad `what`, `points`, `fmt`
    or `dpi` raise CaseError naming the command-line option.
    """
    check_options(result, what, points, fmt, dpi)
    out = _Output(Path(folder), fmt, dpi, PlotReport())
    selected = [result.points[name] for name in (points or result.points)]
    drawers: dict[str, Callable[[], None]] = {
        "fields": lambda: _draw_fields(result, selected, out),
        "trends": lambda: _draw_trends(result, out),
        "friction": lambda: _draw_friction(result, out),
        "heat": lambda: _draw_heat(result, out),
        "contact": lambda: _draw_contact(result, out),
        "convergence": lambda: _draw_convergence(result, selected, out),
    }
    for name in FIGURE_TYPES:
        if name in what:
            drawers[name]()
    return out.report


def figure_types(option: str) -> tuple[str, ...]:
    """The figure types of a comma-separated --what ('all' for every type); CaseError for an unknown one."""
    names = [name.strip() for name in option.split(",") if name.strip()]
    if not names:
        raise CaseError("--what", option, "figure types among: all, " + ", ".join(FIGURE_TYPES))
    return FIGURE_TYPES if "all" in names else tuple(dict.fromkeys(names))


def check_options(result: Result, what: Sequence[str], points: Sequence[str] | None, fmt: str, dpi: int) -> None:
    """CaseError for an unknown figure type, point name or format, or a non-positive dpi."""
    for name in what:
        if name not in FIGURE_TYPES:
            raise CaseError("--what", name, "figure types among: all, " + ", ".join(FIGURE_TYPES))
    for name in points or ():
        if name not in result.points:
            raise CaseError("--point", name, "point names of the file among: " + ", ".join(result.points))
    if fmt not in FORMATS:
        raise CaseError("--format", fmt, "one of " + ", ".join(FORMATS))
    if dpi <= 0:
        raise CaseError("--dpi", dpi, "a positive number of dots per inch")


# ----------------------------------------------------------------------------------------- common


def _title(result: Result, subject: str, point: PointResult | None = None) -> str:
    where = f", {point.name}" if point is not None else ""
    state = "" if point is None or point.converged else " (not converged)"
    return f"{result.case_name}{where}: {subject}{state}"


def _figure(width: float = 7.5, height: float = 5.0) -> Figure:
    return Figure(figsize=(width, height), layout="constrained")


def _legend(ax: Axes, **options) -> None:
    """A legend when the axes hold labelled artists."""
    if ax.get_legend_handles_labels()[0]:
        ax.legend(**options)


def _body_names(result: Result) -> tuple[str, str]:
    """Bodies 1 and 2: pinion and face gear in a gear case (one with a /contact path)."""
    return ("pinion", "face gear") if result.contact else ("body 1", "body 2")


# ----------------------------------------------------------------------------------------- fields


@dataclass(frozen=True)
class _Style:
    """How one kind of field is drawn: file-name stem, quantity (axis label), group (fields sharing a profile
    panel), colour map, colour of overlaid lines."""

    stem: str
    quantity: str
    group: str
    cmap: str
    ink: str


# SI units -> (factor, offset, units shown) for field values.
_SHOWN = {
    "Pa": (1e-6, 0.0, "MPa"),
    "m": (1e6, 0.0, "µm"),
    "K": (1.0, -273.15, "°C"),
    "W/m^2": (1e-6, 0.0, "MW/m²"),
    "W/m2": (1e-6, 0.0, "MW/m²"),
}


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
    units: str
    style: _Style
    vmin: float
    vmax: float

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
    factor, offset, units = _SHOWN.get(data.units, (1.0, 0.0, data.units))
    values = np.asarray(data.values, dtype=float) * factor + offset
    vmin, vmax = float(values.min()), float(values.max())
    if style.group == "pressure":
        vmin = 0.0
    if style.group == "film" and "h_c" in point.scalars:
        vmax = min(vmax, FILM_COLOUR_LIMIT * point.scalars["h_c"] * factor)
    if vmin < 0.0 < vmax:
        vmax = max(-vmin, vmax)
        vmin = -vmax
    return _Map(
        label=data.description or name.replace("_", " "),
        X=point.axes["x"].values / point.scalars["b"],
        Y=point.axes["y"].values / point.scalars["a"],
        values=values,
        units=units,
        style=style,
        vmin=vmin,
        vmax=vmax,
    )


def _draw_fields(result: Result, points: Sequence[PointResult], out: _Output) -> None:
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
    fig = _figure(height=5.6)
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
    ax.set_title(_title(result, m.label + clipped, point))
    _legend(ax, loc="upper left", fontsize="small", framealpha=0.8)
    return fig


def _hertz_axis_labels(ax: Axes, point: PointResult) -> None:
    ax.set_xlabel(f"x / b   (b = {point.scalars['b'] * 1e3:.3g} mm, minor axis)")
    ax.set_ylabel(f"y / a   (a = {point.scalars['a'] * 1e3:.3g} mm, major axis)")


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
    fig = _figure(height=5.6)
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
    ax.set_title(_title(result, m.label + clipped, point))
    _legend(ax, loc="upper left", fontsize="small")
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
    fig = _figure(width=10.0, height=2.6 * len(groups) + 0.8)
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
    fig.suptitle(_title(result, "centre-line profiles", point))
    return fig


def _decorate_profile(ax: Axes, point: PointResult, group: str, members: Sequence[_Map]) -> None:
    m = members[0]
    ax.set_ylabel(m.axis_label)
    for edge in (-1.0, 1.0):
        ax.axvline(edge, color="grey", linewidth=0.6, linestyle=":")
    if group == "pressure" and "p_hertz" in point.scalars:
        t = np.linspace(-1.0, 1.0, 201)
        ax.plot(t, point.scalars["p_hertz"] * 1e-6 * np.sqrt(1.0 - t**2), "--", color="grey",
                linewidth=0.8, label="dry Hertz")
    if group == "film":
        ax.set_ylim(0.0, m.vmax)
    ax.grid(alpha=0.3)
    _legend(ax, fontsize="small")


# ----------------------------------------------------------------------------------------- over points


def _per_point(result: Result, key: str) -> dict[str, float]:
    """A quantity per point, from the point scalars or else from a /heat column of that name."""
    values = {name: float(p.scalars[key]) for name, p in result.points.items() if key in p.scalars}
    if not values and key in result.heat:
        values = dict(zip(_heat_point_names(result), np.asarray(result.heat[key].values, dtype=float)))
    return values


def _heat_point_names(result: Result) -> list[str]:
    """The point names of the /heat rows: its text column, else the file's points in order."""
    for column in result.heat.values():
        if np.asarray(column.values).dtype.kind in "US":
            return [str(v) for v in column.values]
    rows = len(next(iter(result.heat.values())).values)
    names = list(result.points)
    return names if len(names) == rows else [f"row {i + 1}" for i in range(rows)]


def _point_axis(result: Result, names: Sequence[str]) -> tuple[dict[str, float], Callable[[Axes], None]]:
    """x position per point name (path coordinate in mm when every point has one), and the axis labeller."""
    coordinates = [result.points[n].scalars.get("path_coordinate") if n in result.points else None for n in names]
    if None not in coordinates and len(set(coordinates)) == len(names) > 1:
        positions = {n: 1e3 * float(s) for n, s in zip(names, coordinates)}

        def label_path(ax: Axes) -> None:
            if len(names) <= MANY_POINTS:
                ax.set_xticks(list(positions.values()), [f"{n}\n{s:.1f}" for n, s in positions.items()])
            ax.set_xlabel("meshing point, path coordinate s (mm)")

        return positions, label_path
    positions = {n: float(i) for i, n in enumerate(names)}

    def label_names(ax: Axes) -> None:
        ax.set_xticks(list(positions.values()), list(names))
        ax.set_xlabel("meshing point")
        ax.set_xlim(-0.5, len(names) - 0.5)

    return positions, label_names


def _plot_series(ax: Axes, result: Result, positions: Mapping[str, float], values: Mapping[str, float],
                 label: str, style: str = "o-") -> None:
    """A quantity over the points; open markers for points that did not converge."""
    names = [n for n in positions if n in values]
    x = [positions[n] for n in names]
    (line,) = ax.plot(x, [values[n] for n in names], style, label=label)
    open_names = [n for n in names if n in result.points and not result.points[n].converged]
    if open_names:
        ax.plot([positions[n] for n in open_names], [values[n] for n in open_names], "o", color="white",
                markeredgecolor=line.get_color(), markersize=7)


def _not_converged_note(ax: Axes, result: Result) -> None:
    if not all(p.converged for p in result.points.values()):
        ax.plot([], [], "o", color="white", markeredgecolor="black", label="open marker: not converged")


_SWEEP_FILE = "a sweep file holds one point on several grids (see sweep_error)"
# (key, label, factor from SI, linestyle) per trend panel: (title, y label, series...)
_TRENDS = (
    ("maximum pressure", "pressure (MPa)",
     (("p_max", "p_max (EHL)", 1e-6, "o-"), ("p_hertz", "p_h (dry Hertz)", 1e-6, "s--"))),
    ("film thickness", "film thickness (µm)",
     (("h_c", "h_c (central)", 1e6, "o-"), ("h_min", "h_min (minimum)", 1e6, "s-"))),
    ("maximum temperature rise", "ΔT_max (°C)", (("dT_max", "ΔT_max", 1.0, "o-"),)),
)


def _draw_trends(result: Result, out: _Output) -> None:
    """p_max, h_c, h_min and ΔT_max over the meshing points (Fig. 13)."""
    if result.sweep:
        out.skip("trends", _SWEEP_FILE)
        return
    names = [n for n, p in result.points.items() if p.scalars.keys() - {"path_coordinate"}]
    if len(names) < 2:
        out.skip("trends", f"results at {len(names)} point(s); trends need two or more")
        return
    panels = [(t, y, [s for s in series if _per_point(result, s[0])]) for t, y, series in _TRENDS]
    panels = [panel for panel in panels if panel[2]]
    if not any(s[0] == "dT_max" for *_, series in panels for s in series):
        out.skip("trends ΔT_max", "no dT_max scalar in the file (written by the thermal model)")
    positions, label_axis = _point_axis(result, names)
    fig = _figure(height=2.5 * len(panels) + 0.8)
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (title, y_label, series) in zip(axes, panels):
        for key, label, factor, style in series:
            values = {n: v * factor for n, v in _per_point(result, key).items()}
            _plot_series(ax, result, positions, values, label, style)
        ax.set_title(title)
        ax.set_ylabel(y_label)
        ax.grid(alpha=0.3)
        _legend(ax, fontsize="small")
    _not_converged_note(axes[0], result)
    _legend(axes[0], fontsize="small")
    label_axis(axes[-1])
    missing = [n for n in result.points if n not in names]
    suffix = f" (no results: {', '.join(missing)})" if missing else ""
    fig.suptitle(_title(result, "film characteristics over the meshing points" + suffix))
    out.save(fig, "trends")


# Friction coefficients: scalar or /heat column name -> legend label.
_FRICTION_LABELS = {"mu": "Ree–Eyring (thermal EHL)", "mu_xu": "Xu et al. (2007), empirical",
                    "mu_iso": "ISO/TR 14179-2"}


def _friction_keys(result: Result) -> list[str]:
    keys = {k for p in result.points.values() for k in p.scalars} | set(result.heat)
    return [k for k in _FRICTION_LABELS if k in keys]


def _draw_friction(result: Result, out: _Output) -> None:
    """Friction coefficients over the meshing points (Fig. 14, 15)."""
    keys = _friction_keys(result)
    if result.sweep:
        out.skip("friction", _SWEEP_FILE)
        return
    if not keys:
        out.skip("friction", "no friction coefficients in the file (point scalars or /heat columns mu, mu_xu)")
        return
    for key in ("mu", "mu_xu"):
        if key not in keys:
            out.skip(f"friction {key}", f"no {key} ({_FRICTION_LABELS[key]}) in the file")
    series = {key: _per_point(result, key) for key in keys}
    names = [n for n in dict.fromkeys(n for values in series.values() for n in values)]
    positions, label_axis = _point_axis(result, names)
    fig = _figure(height=4.5)
    ax = fig.add_subplot()
    for key, values in series.items():
        _plot_series(ax, result, positions, values, _FRICTION_LABELS.get(key, key))
    _not_converged_note(ax, result)
    ax.set_ylabel("friction coefficient μ (–)")
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    _legend(ax)
    label_axis(ax)
    ax.set_title(_title(result, "friction coefficient over the meshing points"))
    out.save(fig, "friction")


def _heat_columns(result: Result, units: str) -> dict[str, np.ndarray]:
    return {name: np.asarray(c.values, dtype=float) for name, c in result.heat.items() if c.units == units}


def _column_label(result: Result, name: str) -> str:
    """'friction_power_1' -> 'friction power, pinion' (body 1/2 of a plain contact)."""
    body_1, body_2 = _body_names(result)
    for suffix, body in (("_1", body_1), ("_2", body_2)):
        if name.endswith(suffix):
            return f"{name[: -len(suffix)].replace('_', ' ')}, {body}"
    return name.replace("_", " ")


def _draw_heat(result: Result, out: _Output) -> None:
    """Frictional heat power per gear, steady-state power (Fig. 17) and heat per meshing point (Fig. 20, 21)."""
    if not result.heat:
        out.skip("heat", "no /heat table in the file (written by the heat budget)")
        return
    names = _heat_point_names(result)
    powers = _heat_columns(result, "W")
    if powers:
        panels = [
            ("instantaneous frictional heat power", {k: v for k, v in powers.items() if "steady" not in k}),
            ("steady-state frictional heat power", {k: v for k, v in powers.items() if "steady" in k}),
        ]
        panels = [(title, columns) for title, columns in panels if columns]
        fig = _figure(height=2.8 * len(panels) + 0.8)
        axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
        for ax, (title, columns) in zip(axes, panels):
            _bars(ax, result, names, columns, log=False)
            ax.set_title(title)
            ax.set_ylabel("heat power (W)")
        axes[-1].set_xlabel("meshing point")
        fig.suptitle(_title(result, "frictional heat power"))
        out.save(fig, "heat_power")
    else:
        out.skip("heat power", "no heat power columns (units W) in /heat")
    energies = {k: v for k, v in _heat_columns(result, "J").items() if np.any(v > 0.0)}
    if not energies:
        out.skip("heat energy", "no heat columns (units J) in /heat")
        return
    fig = _figure(height=4.5)
    ax = fig.add_subplot()
    _bars(ax, result, names, energies, log=True)
    _annotate_oil_share(ax, energies)
    ax.set_ylabel("heat per meshing (J, log scale)")
    ax.set_xlabel("meshing point")
    ax.set_title(_title(result, "frictional heat and heat absorbed by the oil film"))
    out.save(fig, "heat_oil_film")


def _bars(ax: Axes, result: Result, names: Sequence[str], columns: Mapping[str, np.ndarray], log: bool) -> None:
    """Grouped bars, one group per point; on a log axis only positive values are drawn."""
    width = 0.8 / len(columns)
    x = np.arange(len(names))
    for i, (name, values) in enumerate(columns.items()):
        shown = np.where(values > 0.0, values, np.nan) if log else values
        ax.bar(x + (i - (len(columns) - 1) / 2) * width, shown, width, label=_column_label(result, name))
    if log:
        ax.set_yscale("log")
    ax.set_xticks(x, list(names))
    ax.grid(axis="y", alpha=0.3)
    _legend(ax, fontsize="small")


def _annotate_oil_share(ax: Axes, energies: Mapping[str, np.ndarray]) -> None:
    """Q_oil / Q_f in % above each group, when the columns say which is which."""
    oil = [v for k, v in energies.items() if "oil" in k]
    friction = [v for k, v in energies.items() if "friction" in k]
    if len(oil) != 1 or len(friction) != 1:
        return
    with np.errstate(divide="ignore", invalid="ignore"):
        share = 100.0 * oil[0] / friction[0]
    top = np.fmax(oil[0], friction[0])
    for i, (value, height) in enumerate(zip(share, top)):
        if np.isfinite(value) and height > 0.0:
            ax.annotate(f"{value:.2g} %", (i, height), textcoords="offset points", xytext=(0, 4),
                        ha="center", fontsize="small")
    ax.plot([], [], " ", label="n %: oil-film heat / frictional heat")
    ax.set_ylim(top=30.0 * float(np.nanmax(top)))
    _legend(ax, fontsize="small", loc="upper right")


# ----------------------------------------------------------------------------------------- contact path


def _draw_contact(result: Result, out: _Output) -> None:
    """The /contact path table (Fig. 2, 4, 6, 8), with the meshing points of the file marked."""
    if not result.contact:
        out.skip("contact", "no /contact path table in the file (plain contact case)")
        return
    table = result.contact
    if "s" not in table:
        out.skip("contact", "the /contact table has no path coordinate s")
        return
    for stem, figure in (("contact_path", _path_figure), ("contact_curvatures", _curvature_figure),
                         ("contact_speeds", _speed_figure), ("contact_load", _load_figure)):
        missing = [c for c in _CONTACT_COLUMNS[stem] if c not in table]
        if missing:
            out.skip(stem, f"/contact lacks {', '.join(missing)}")
        else:
            out.save(figure(result), stem)


_CONTACT_COLUMNS = {
    "contact_path": ("face_gear_radius", "pinion_profile_radius"),
    "contact_curvatures": ("pinion_curvature", "face_gear_curvature_1", "face_gear_curvature_2", "Rx", "Ry"),
    "contact_speeds": ("u1", "u2", "entrainment_speed", "sliding_speed", "srr", "entrainment_angle"),
    "contact_load": ("load", "p_h", "a", "b"),
}


def _path_mm(result: Result) -> np.ndarray:
    return 1e3 * np.asarray(result.contact["s"].values)


def _column(result: Result, name: str, factor: float = 1.0) -> np.ndarray:
    return factor * np.asarray(result.contact[name].values, dtype=float)


def _mark_points(axes: Sequence[Axes], result: Result) -> None:
    """Vertical lines at the meshing points of the file, named on the top panel."""
    marks = {n: 1e3 * p.scalars["path_coordinate"] for n, p in result.points.items() if "path_coordinate" in p.scalars}
    for ax in axes:
        for s in marks.values():
            ax.axvline(s, color="grey", linewidth=0.7, linestyle=":")
        ax.grid(alpha=0.3)
    top = axes[0]
    for name, s in marks.items():
        top.annotate(name, (s, 1.0), xycoords=("data", "axes fraction"), xytext=(0, 3),
                     textcoords="offset points", ha="center", va="bottom", fontsize="small")


def _path_panels(result: Result, count: int, subject: str) -> tuple[Figure, np.ndarray]:
    fig = _figure(height=2.5 * count + 1.0)
    axes = fig.subplots(count, 1, sharex=True, squeeze=False)[:, 0]
    axes[-1].set_xlabel("path coordinate s (mm; − meshing in, + meshing out)")
    fig.suptitle(_title(result, subject))
    return fig, axes


def _curve(ax: Axes, s: np.ndarray, values: np.ndarray, y_label: str, title: str, colour: str) -> None:
    """One quantity along the path; the top panel's title leaves room for the point names above it."""
    ax.plot(s, values, color=colour)
    ax.set_ylabel(y_label)
    ax.set_title(title, fontsize="medium", pad=14 if ax.get_subplotspec().is_first_row() else None)


def _finish_path(axes: Sequence[Axes], result: Result) -> None:
    _mark_points(axes, result)
    for ax in axes:
        _legend(ax, fontsize="small")


def _path_figure(result: Result) -> Figure:
    """Where the contact lies on both teeth along the path (Fig. 2)."""
    s = _path_mm(result)
    fig, axes = _path_panels(result, 2, "contact path on the teeth")
    _curve(axes[0], s, _column(result, "face_gear_radius", 1e3), "face gear radius (mm)",
           "on the face gear: radius across the face width", "tab:blue")
    _curve(axes[1], s, _column(result, "pinion_profile_radius", 1e3), "ρ₁ (mm)",
           "on the pinion: involute profile radius of curvature (root → tip)", "tab:orange")
    _finish_path(axes, result)
    return fig


def _curvature_figure(result: Result) -> Figure:
    """Principal curvatures of both tooth surfaces and the reduced radii (Fig. 4)."""
    s = _path_mm(result)
    fig, axes = _path_panels(result, 3, "curvature along the contact path")
    ax = axes[0]
    ax.plot(s, _column(result, "pinion_curvature"), label="pinion, along the profile")
    ax.plot(s, np.zeros_like(s), "--", label="pinion, along the axis (0)")
    ax.plot(s, _column(result, "face_gear_curvature_1"), label="face gear, principal 1")
    ax.plot(s, _column(result, "face_gear_curvature_2"), label="face gear, principal 2")
    ax.set_ylabel("curvature (1/m)")
    ax.set_title("principal curvatures (convex +)", fontsize="medium", pad=14)
    ax.legend(fontsize="small", ncols=2)
    _curve(axes[1], s, _column(result, "Rx", 1e3), "R_x (mm)", "reduced radius along the minor axis", "tab:purple")
    _curve(axes[2], s, _column(result, "Ry"), "R_y (m)", "reduced radius along the major axis", "tab:brown")
    _finish_path(axes, result)
    return fig


def _speed_figure(result: Result) -> Figure:
    """Surface, rolling and sliding speeds, slide-to-roll ratio and entrainment angle (Fig. 6)."""
    s = _path_mm(result)
    body_1, body_2 = _body_names(result)
    fig, axes = _path_panels(result, 3, "speeds along the contact path")
    ax = axes[0]
    ax.plot(s, np.hypot(*_column(result, "u1").T), label=f"{body_1} surface |u₁|")
    ax.plot(s, np.hypot(*_column(result, "u2").T), label=f"{body_2} surface |u₂|")
    ax.plot(s, _column(result, "entrainment_speed"), linewidth=2, label="rolling (entrainment) |U_e|")
    ax.plot(s, _column(result, "sliding_speed"), linewidth=2, label="sliding |V_s|")
    ax.set_ylabel("speed (m/s)")
    ax.set_title("speeds relative to the contact point", fontsize="medium", pad=14)
    _curve(axes[1], s, _column(result, "srr"), "SRR (–)", "slide-to-roll ratio, signed by V_s · U_e", "tab:red")
    axes[1].axhline(0.0, color="black", linewidth=0.6)
    _curve(axes[2], s, _column(result, "entrainment_angle"), "ψ (deg)", "entrainment angle to the minor axis x",
           "tab:green")
    _finish_path(axes, result)
    return fig


def _load_figure(result: Result) -> Figure:
    """Normal load with its share, Hertz pressure and semi-axes (Fig. 8)."""
    s = _path_mm(result)
    fig, axes = _path_panels(result, 3, "load along the contact path")
    _curve(axes[0], s, _column(result, "load"), "normal load (N)", "normal load on the tooth pair", "tab:blue")
    total = result.contact_scalars.get("normal_load")
    if total:
        share = axes[0].secondary_yaxis("right", functions=(lambda f: f / total, lambda k: k * total))
        share.set_ylabel("load share (–)")
    _curve(axes[1], s, _column(result, "p_h", 1e-6), "p_h (MPa)", "maximum Hertz pressure", "tab:red")
    axes[2].plot(s, _column(result, "a", 1e3), label="a, major semi-axis (left)")
    axes[2].set_ylabel("a (mm)")
    right = axes[2].twinx()
    right.plot(s, _column(result, "b", 1e3), color="tab:orange", label="b, minor semi-axis (right)")
    right.set_ylabel("b (mm)")
    axes[2].set_title("Hertz semi-axes", fontsize="medium")
    axes[2].legend(handles=[*axes[2].get_lines(), *right.get_lines()], fontsize="small", loc="lower center")
    _mark_points(axes, result)
    return fig


# ----------------------------------------------------------------------------------------- convergence


def _draw_convergence(result: Result, points: Sequence[PointResult], out: _Output) -> None:
    """Per-cycle histories of every point and the film on the multigrid levels; the /sweep table if any."""
    histories = list(dict.fromkeys(k for p in points for k in p.history if k.endswith("_history")))
    levels = [p for p in points if {"level_nodes", "level_h_c"} <= p.history.keys()]
    if histories or levels:
        out.save(_convergence_figure(result, points, histories, levels), "convergence")
    else:
        out.skip("convergence", "no per-cycle histories in the file")
    sweep = result.sweep
    if not sweep:
        out.skip("convergence sweep", "no /sweep table in the file (written by tehl sweep)")
    elif "grid" not in sweep or not _sweep_errors(sweep):
        out.skip("convergence sweep", "the /sweep table has no grid column or no finite *_error column")
    else:
        out.save(_sweep_figure(result, sweep), "sweep_error")


def _convergence_figure(result: Result, points: Sequence[PointResult], histories: Sequence[str],
                        levels: Sequence[PointResult]) -> Figure:
    count = len(histories) + bool(levels)
    columns = 2 if count > 1 else 1
    rows = math.ceil(count / columns)
    fig = _figure(width=5.0 * columns + 0.5, height=3.4 * rows + 0.6)
    axes = fig.subplots(rows, columns, squeeze=False).ravel()
    for ax, key in zip(axes, histories):
        _history_panel(ax, points, key)
    if levels:
        _levels_panel(axes[len(histories)], levels)
    for ax in axes[count:]:
        ax.remove()
    fig.suptitle(_title(result, "convergence per cycle"))
    return fig


def _history_panel(ax: Axes, points: Sequence[PointResult], key: str) -> None:
    """One per-cycle history of every point: errors and changes as magnitudes on a log axis, films in µm."""
    first = next(p.history[key] for p in points if key in p.history)
    film = first.units == "m"
    name = key.removesuffix("_history").replace("_", " ")
    for p in points:
        if key in p.history:
            values = np.asarray(p.history[key].values, dtype=float)
            if film:
                ax.plot(np.arange(len(values)), 1e6 * values, "o-", markersize=3, label=p.name)
            else:
                values = np.abs(values)
                ax.semilogy(np.arange(len(values)), np.where(values > 0.0, values, np.nan), "o-", markersize=3,
                            label=p.name)
    units = "µm" if film else first.units
    ax.set_ylabel(f"{name} ({units})" if film else f"|{name}|" + ("" if units in ("", "1") else f" ({units})"))
    ax.set_title(first.description or name, fontsize="medium", wrap=True)
    ax.set_xlabel("outer iteration" if "outer iteration" in first.description else "cycle")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.grid(alpha=0.3, which="both")
    _legend(ax, fontsize="small", ncols=2)


def _levels_panel(ax: Axes, points: Sequence[PointResult]) -> None:
    """h_c on each full-multigrid level relative to the finest: the discretisation error at a glance."""
    for p in points:
        nodes = np.asarray(p.history["level_nodes"].values)
        h_c = np.asarray(p.history["level_h_c"].values)
        ax.plot(nodes, 100.0 * (h_c / h_c[-1] - 1.0), "o-", markersize=3, label=p.name)
    ax.set_xscale("log", base=2)
    ax.set_xticks(nodes, [f"{n:.0f}" for n in nodes])
    ax.xaxis.set_minor_locator(NullLocator())
    ax.axhline(0.0, color="black", linewidth=0.6)
    ax.set_title(points[0].history["level_h_c"].description or "central film on the multigrid levels",
                 fontsize="medium", wrap=True)
    ax.set_xlabel("nodes per side")
    ax.set_ylabel("h_c / h_c(finest) − 1 (%)")
    ax.grid(alpha=0.3)
    _legend(ax, fontsize="small", ncols=2)


def _sweep_errors(sweep: Mapping[str, Field]) -> dict[str, np.ndarray]:
    """|relative error| per grid of each swept quantity (columns `<quantity>_error`; NaN where undefined)."""
    errors = {
        name.removesuffix("_error"): np.abs(np.asarray(column.values, dtype=float))
        for name, column in sweep.items()
        if name.endswith("_error") and np.asarray(column.values).dtype.kind == "f"
    }
    return {name: error for name, error in errors.items() if np.any(np.isfinite(error) & (error > 0.0))}


def _sweep_figure(result: Result, sweep: Mapping[str, Field]) -> Figure:
    """Error vs grid and error vs wall time, log-log (work-precision)."""
    errors = _sweep_errors(sweep)
    grids = np.asarray(sweep["grid"].values, dtype=float)
    abscissae = [("grid", "nodes per side")] + ([("wall_time", "wall time (s)")] if "wall_time" in sweep else [])
    fig = _figure(width=5.0 * len(abscissae) + 0.5, height=4.2)
    axes = fig.subplots(1, len(abscissae), squeeze=False)[0]
    for ax, (key, label) in zip(axes, abscissae):
        x = np.asarray(sweep[key].values, dtype=float)
        for name, error in errors.items():
            keep = np.isfinite(error) & (error > 0.0)
            ax.plot(x[keep], 100.0 * error[keep], "o-", label=name)
        ax.set_yscale("log")
        if key == "grid":
            ax.set_xscale("log", base=2)
            ax.set_xticks(x, [f"{n:.0f}" for n in x])
            ax.xaxis.set_minor_locator(NullLocator())
        else:
            ax.set_xscale("log")
            ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
            ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
            ax.xaxis.set_minor_formatter(NullFormatter())
            _label_grids(ax, x, grids, errors)
        ax.set_xlabel(label)
        ax.set_ylabel("|error| vs extrapolated value (%)")
        ax.grid(alpha=0.3, which="both")
        _legend(ax, fontsize="small")
    fig.suptitle(_title(result, "grid sweep: error vs grid and vs cost"))
    return fig


def _label_grids(ax: Axes, x: np.ndarray, grids: np.ndarray, errors: Mapping[str, np.ndarray]) -> None:
    """Name the grid of each point of the first error curve (on the cost axis the grids are not in order)."""
    error = 100.0 * next(iter(errors.values()))
    for xi, yi, n in zip(x, error, grids):
        if np.isfinite(yi) and yi > 0.0:
            ax.annotate(f"{n:.0f}²", (xi, yi), textcoords="offset points", xytext=(5, 4), fontsize="small")
