"""What every figure family shares: the report of files written and figures skipped, the output folder,
figures, titles and legends."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from facegear_tehl.results import PointResult, Result

PNG_COMPRESSION = 3  # zlib level: 55-75 % of the encoding time of the default 6, files 5-15 % larger


@dataclass
class PlotReport:
    """Files written, and one line per figure (type or point) not drawn, saying why."""

    written: list[Path] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class Output:
    """Where and how figures are saved, and the report of what was written or skipped."""

    folder: Path
    fmt: str
    dpi: int
    report: PlotReport

    def save(self, figure: Figure, stem: str) -> None:
        path = self.folder / f"{stem}.{self.fmt}"
        self.folder.mkdir(parents=True, exist_ok=True)
        options = {"pil_kwargs": {"compress_level": PNG_COMPRESSION}} if self.fmt == "png" else {}
        figure.savefig(path, dpi=self.dpi, **options)
        self.report.written.append(path)

    def skip(self, what: str, reason: str) -> None:
        self.report.skipped.append(f"skipped {what}: {reason}")


def plain(text: str) -> str:
    """`text` from a file (a case or point name, a varied value) drawn as written: each `$`, which would open
    matplotlib's mathtext, escaped (`name: "q$x^{$q"` would otherwise fail to parse and stop the plot)."""
    return text.replace("$", r"\$")


def title(result: Result, subject: str, point: PointResult | None = None) -> str:
    """'<case>, <point>: <subject>', flagged when the point did not converge; the names drawn as written."""
    where = f", {plain(point.name)}" if point is not None else ""
    state = "" if point is None or point.converged else " (not converged)"
    return f"{plain(result.case_name)}{where}: {subject}{state}"


def figure(width: float = 7.5, height: float = 5.0) -> Figure:
    """A figure with constrained layout, rendered by the Agg canvas (no pyplot state)."""
    return Figure(figsize=(width, height), layout="constrained")


def legend(ax: Axes, **options) -> None:
    """A legend when the axes hold labelled artists."""
    if ax.get_legend_handles_labels()[0]:
        ax.legend(**options)


def legend_outside(ax: Axes, handles: list | None = None) -> None:
    """A legend to the right of the axes (never over the data), when there is something to list."""
    handles = handles if handles is not None else ax.get_legend_handles_labels()[0]
    handles = sorted(handles, key=_is_note)  # notes (entries without a line or marker) after the data
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                  fontsize="small")


def _is_note(handle: object) -> bool:
    return isinstance(handle, Line2D) and handle.get_linestyle() == "None" and handle.get_marker() in ("None", " ", "")


def body_names(result: Result) -> tuple[str, str]:
    """Bodies 1 and 2: pinion and face gear in a gear case (one with a /contact path)."""
    return ("pinion", "face gear") if result.contact else ("body 1", "body 2")
