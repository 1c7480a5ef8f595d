"""Figures from a result file: the centre line of each point, an overview sheet of the film maps, trends
over the meshing points, friction, heat budget, the face gear contact path and convergence by default;
contour maps and 3-D surfaces of every field on request (matplotlib; the seed paper's figure numbers in
the docstrings).

Everything is read through `results.read_result`; nothing is solved again. `plot_result` draws the figure
types asked for and reports the files written and, one line each, what it had no data for. One module per
figure family: `centreline`, `overview`, `maps`, `surfaces`, `trends`, `friction`, `heat`, `contact`,
`convergence`, `cycle`; `common`, `field_data`, `over_points` and `case_values` hold what they share. Values are
shown in the display units of `facegear_tehl.units`, temperatures as the rise over the inlet ΔT in K.

Figures are `matplotlib.figure.Figure` objects rendered by the Agg canvas: no display, no pyplot state.
Fields are drawn in Hertzian coordinates x/b, y/a, where the Hertz ellipse is the unit circle: face gear
ellipses are 35-58 times longer than wide and would be a line at true scale.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

from facegear_tehl.plots.case_values import case_values
from facegear_tehl.plots.centreline import draw_centreline
from facegear_tehl.plots.common import Output, PlotReport
from facegear_tehl.plots.contact import draw_contact
from facegear_tehl.plots.convergence import draw_convergence
from facegear_tehl.plots.cycle import draw_cycle
from facegear_tehl.plots.field_data import point_fields
from facegear_tehl.plots.friction import draw_friction
from facegear_tehl.plots.heat import draw_heat
from facegear_tehl.plots.maps import draw_maps
from facegear_tehl.plots.overview import draw_overview
from facegear_tehl.plots.surfaces import draw_surfaces
from facegear_tehl.plots.trends import draw_trends
from facegear_tehl.results import Result, read_result
from facegear_tehl.schema import CaseError

__all__ = ["DEFAULT_TYPES", "FIGURE_TYPES", "FORMATS", "PlotReport", "check_options", "figure_types", "plot_file",
           "plot_result"]

DEFAULT_TYPES = ("centreline", "overview", "trends", "friction", "heat", "contact", "convergence", "cycle")
FIGURE_TYPES = (*DEFAULT_TYPES, "maps", "surfaces")  # maps and surfaces (a file per point and field) on request
FIELD_TYPES = ("centreline", "overview", "maps", "surfaces")  # the types drawn from the point fields
_EXPECTED = "figure types among: default, all, " + ", ".join(FIGURE_TYPES)
FORMATS = ("png", "pdf", "svg")


def plot_file(path: str | Path, folder: str | Path, **options) -> PlotReport:
    """Read the result file at `path` and draw its figures into `folder` (options as `plot_result`)."""
    return plot_result(read_result(path), folder, **options)


def plot_result(
    result: Result,
    folder: str | Path,
    what: Sequence[str] = DEFAULT_TYPES,
    points: Sequence[str] | None = None,
    fmt: str = "png",
    dpi: int = 150,
) -> PlotReport:
    """Draw the figure types `what` (see FIGURE_TYPES) of `result` into `folder`.

    points: the points whose fields and convergence are drawn (default all). Bad `what`, `points`, `fmt`
    or `dpi` raise CaseError naming the command-line option.
    """
    check_options(result, what, points, fmt, dpi)
    out = Output(Path(folder), fmt, dpi, PlotReport())
    selected = [result.points[name] for name in (points or result.points)]
    case = case_values(result)
    rows = point_fields(result, selected, case, out) if set(FIELD_TYPES) & set(what) else []
    drawers: dict[str, Callable[[], None]] = {
        "centreline": lambda: draw_centreline(result, rows, out),
        "overview": lambda: draw_overview(result, rows, out),
        "maps": lambda: draw_maps(result, rows, out),
        "surfaces": lambda: draw_surfaces(result, rows, out),
        "trends": lambda: draw_trends(result, out),
        "friction": lambda: draw_friction(result, out),
        "heat": lambda: draw_heat(result, out),
        "contact": lambda: draw_contact(result, out),
        "convergence": lambda: draw_convergence(result, selected, case, out),
        "cycle": lambda: draw_cycle(result, out),
    }
    for name in FIGURE_TYPES:
        if name in what:
            drawers[name]()
    return out.report


def figure_types(option: str) -> tuple[str, ...]:
    """The figure types of a comma-separated --what ('default' for DEFAULT_TYPES, 'all' for every type);
    CaseError for an unknown one."""
    names = [name.strip() for name in option.split(",") if name.strip()]
    if not names:
        raise CaseError("--what", option, _EXPECTED)
    if "all" in names:
        return FIGURE_TYPES
    return tuple(dict.fromkeys(n for name in names for n in (DEFAULT_TYPES if name == "default" else (name,))))


def check_options(result: Result, what: Sequence[str], points: Sequence[str] | None, fmt: str, dpi: int) -> None:
    """CaseError for an unknown figure type, point name or format, or a non-positive dpi."""
    for name in what:
        if name not in FIGURE_TYPES:
            raise CaseError("--what", name, _EXPECTED)
    for name in points or ():
        if name not in result.points:
            raise CaseError("--point", name, "point names of the file among: " + ", ".join(result.points))
    if fmt not in FORMATS:
        raise CaseError("--format", fmt, "one of " + ", ".join(FORMATS))
    if dpi <= 0:
        raise CaseError("--dpi", dpi, "a positive number of dots per inch")
