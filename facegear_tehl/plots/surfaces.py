"""3-D surfaces of every field of a point, on request (`--what surfaces`), over their contour map on the
floor of the box (Fig. 12, 18 of the seed paper)."""

from __future__ import annotations

from collections.abc import Sequence
import math

from matplotlib import colormaps
from matplotlib.colors import LightSource, Normalize
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
import numpy as np

from facegear_tehl.plots.common import Output, figure, legend, title
from facegear_tehl.plots.field_data import FieldMap
from facegear_tehl.plots.maps import levels
from facegear_tehl.results import PointResult, Result

ACTIVE_FRACTION = 0.005  # a surface shows the box where the field differs from its rest value by this share


def draw_surfaces(result: Result, rows: Sequence[tuple[PointResult, dict[str, FieldMap]]], out: Output) -> None:
    """A 3-D surface per point and field, `<point>_<field>_surface`."""
    for point, maps in rows:
        for m in maps.values():
            stem = "film" if m.name == "film_thickness" else m.name
            out.save(surface_figure(result, point, m), f"{point.name}_{stem}_surface")


def surface_figure(result: Result, point: PointResult, m: FieldMap) -> Figure:
    """3-D surface over the region where the field is in its colour range (pressure above 0.5 % of its
    maximum, film clipped at FILM_COLOUR_LIMIT h_c), lit so the pressure spike stands out, over its contour
    map on the floor of the box with the Hertz ellipse."""
    fig = figure(height=5.6)
    ax = fig.add_subplot(projection="3d", computed_zorder=False)
    rows, columns = _active_region(m)
    X, Y, values = m.X[columns], m.Y[rows], np.clip(m.values[rows, columns], m.vmin, m.vmax)
    XX, YY = np.meshgrid(X, Y)
    floor = m.vmin - 0.6 * (m.vmax - m.vmin)
    ax.contourf(XX, YY, values, levels=levels(m), cmap=m.cmap, zdir="z", offset=floor, zorder=0)
    angle = np.linspace(0.0, 2.0 * math.pi, 361)
    ax.plot(np.cos(angle), np.sin(angle), zs=floor, zdir="z", color="tab:cyan", linewidth=1.5,
            label="Hertz ellipse (on the floor map)", zorder=1)
    norm, cmap = Normalize(m.vmin, m.vmax), colormaps[m.cmap]
    # Lit from above to show the shape, except a signed field, whose white zero level lighting would grey.
    colours = cmap(norm(values)) if m.signed else LightSource(azdeg=315, altdeg=50).shade(
        values, cmap=cmap, norm=norm, blend_mode="soft")
    if m.group == "pressure":  # left out where there is no pressure, so the floor map shows there
        values = np.where(values <= 0.01 * m.vmax, np.nan, values)
    ax.plot_surface(XX, YY, values, facecolors=colours, rcount=min(len(Y), 160),
                    ccount=min(len(X), 257), linewidth=0, antialiased=False, shade=False, zorder=2)
    ax.set_zlim(floor, m.vmax)
    ticks = MaxNLocator(6).tick_values(m.vmin, m.vmax)
    ax.set_zticks(ticks[(ticks >= m.vmin) & (ticks <= m.vmax)])
    ax.xaxis.set_major_locator(MaxNLocator(6))
    ax.yaxis.set_major_locator(MaxNLocator(6))
    ax.set_xlabel("$x/b$  (outlet +)")
    ax.set_ylabel("$y/a$")
    ax.set_zlabel(m.axis_label)
    ax.set_box_aspect((1.3, 1.3, 0.9), zoom=0.85)
    ax.view_init(elev=28, azim=-65)
    clipped = f", clipped at {m.vmax:.3g} {m.unit.label}" if m.clipped else ""
    ax.set_title(m.label + clipped, fontsize="medium")
    fig.suptitle(title(result, "surface", point))
    legend(ax, loc="upper left", fontsize="small")
    return fig


def _active_region(m: FieldMap) -> tuple[slice, slice]:
    """Index ranges (rows, columns) of the box around the drawn part of a field, two nodes of margin,
    never smaller than the Hertz ellipse."""
    if m.group == "film":
        active = m.values <= m.vmax
    else:
        rest = 0.0 if m.signed else m.vmin
        active = np.abs(m.values - rest) >= ACTIVE_FRACTION * (m.vmax - m.vmin)
    active |= (np.abs(m.X)[None, :] <= 1.0) & (np.abs(m.Y)[:, None] <= 1.0)
    rows, columns = np.nonzero(active)
    return (slice(max(rows.min() - 2, 0), rows.max() + 3), slice(max(columns.min() - 2, 0), columns.max() + 3))
