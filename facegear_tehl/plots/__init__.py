"""Figures from a result file: oil-film fields, trends over the meshing points, friction, heat budget,
the face gear contact path and convergence (matplotlib; the seed paper's figure numbers in the docstrings).

Everything is read through `results.read_result`; nothing is solved again. `plot_result` draws the figure
types asked for and reports the files written and, one line each, what it had no data for. One module per
figure family: `fields`, `trends`, `friction`, `heat`, `contact`, `convergence`, `cycle`; `common` and `over_points`
hold what they share. Values are shown in the display units of `facegear_tehl.units`.

Figures are `matplotlib.figure.Figure` objects rendered by the Agg canvas: no display, no pyplot state.
Fields are drawn in Hertzian coordinates x/b, y/a, where the Hertz ellipse is the unit circle: face gear
ellipses are 35-58 times longer than wide and would be a line at true scale.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

from facegear_tehl.plots.common import Output, PlotReport
from facegear_tehl.plots.contact import draw_contact
from facegear_tehl.plots.convergence import draw_convergence
from facegear_tehl.plots.cycle import draw_cycle
from facegear_tehl.plots.fields import draw_fields
from facegear_tehl.plots.friction import draw_friction
from facegear_tehl.plots.heat import draw_heat
from facegear_tehl.plots.trends import draw_trends
from facegear_tehl.results import Result, read_result
from facegear_tehl.schema import CaseError

__all__ = ["FIGURE_TYPES", "FORMATS", "PlotReport", "check_options", "figure_types", "plot_file", "plot_result"]

FIGURE_TYPES = ("fields", "trends", "friction", "heat", "contact", "convergence", "cycle")
FORMATS = ("png", "pdf", "svg")


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
    out = Output(Path(folder), fmt, dpi, PlotReport())
    selected = [result.points[name] for name in (points or result.points)]
    drawers: dict[str, Callable[[], None]] = {
        "fields": lambda: draw_fields(result, selected, out),
        "trends": lambda: draw_trends(result, out),
        "friction": lambda: draw_friction(result, out),
        "heat": lambda: draw_heat(result, out),
        "contact": lambda: draw_contact(result, out),
        "convergence": lambda: draw_convergence(result, selected, out),
        "cycle": lambda: draw_cycle(result, out),
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
