"""Convergence (no figure of the paper): per-cycle histories of every point, the film on the multigrid levels
and, for a sweep file, the error against the extrapolated value per grid and per wall time."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
import math

from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import FormatStrFormatter, LogLocator, MaxNLocator, NullFormatter, NullLocator
import numpy as np

from facegear_tehl.plots.case_values import CaseValues
from facegear_tehl.plots.common import Output, figure, legend, plain, title
from facegear_tehl.results import PointResult, Result
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import Field
from facegear_tehl.units import PERCENT, display


def draw_convergence(result: Result, points: Sequence[PointResult], case: CaseValues | None, out: Output) -> None:
    """Per-cycle histories of every point with the tolerances, the film on the multigrid levels; the /sweep
    table if any."""
    histories = list(dict.fromkeys(k for p in points for k in p.history if k.endswith("_history")))
    levels = [p for p in points if {"level_nodes", "level_h_c"} <= p.history.keys()]
    if histories or levels:
        out.save(_convergence_figure(result, points, histories, levels, case), "convergence")
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
                        levels: Sequence[PointResult], case: CaseValues | None) -> Figure:
    """One panel per history, then the levels panel, two columns."""
    count = len(histories) + bool(levels)
    columns = 2 if count > 1 else 1
    rows = math.ceil(count / columns)
    fig = figure(width=5.0 * columns + 0.5, height=3.4 * rows + 0.6)
    axes = fig.subplots(rows, columns, squeeze=False).ravel()
    for ax, key in zip(axes, histories):
        _history_panel(ax, points, key, result.convergence_bands)
        if case is not None:
            _tolerances(ax, points, key, case.solver, result.convergence_bands)
    if levels:
        _levels_panel(axes[len(histories)], levels)
    for ax in axes[count:]:
        ax.remove()
    _name_restarts(fig, points, histories)
    fig.suptitle(title(result, "convergence per cycle"))
    return fig


# histories of counts, drawn as they are on a linear axis: their y label
_COUNTS = {"cycle_nodes_history": "nodes along x"}
# the reported figures (sweep.QUANTITIES) as every panel names them
_FIGURES = {"p_max": "$p_{max}$", "h_c": "$h_c$", "h_min": "$h_{min}$", "dT_max": r"$\Delta T_{max}$", "mu": r"$\mu$"}
_NAMES = {"thermal_h_c_history": _FIGURES["h_c"], "cycle_h_c_history": _FIGURES["h_c"],
          "cycle_h_min_history": _FIGURES["h_min"],
          "thermal_change_history": "temperature change",
          "viscosity_change_history": r"change of ln($\eta^*/\eta$)"}


def _history_panel(ax: Axes, points: Sequence[PointResult], key: str, bands: Mapping[str, float]) -> None:
    """One per-cycle history of every point: errors and changes as magnitudes on a log axis, films in µm, counts (a
    cycle's nodes) as they are; the
    temperature change relative to each point's rise (one tolerance line for all points); the first iterate of each
    later stage of the solve record marked as a restart."""
    first = next(p.history[key] for p in points if key in p.history)
    film, counts = first.units == "m", key in _COUNTS
    shown = display(first.units)
    name = _NAMES.get(key, key.removesuffix("_history").replace("_", " "))
    relative = key == "thermal_change_history"
    for p in points:
        if key in p.history:
            values = np.asarray(p.history[key].values, dtype=float)
            if film or counts:
                values = shown(values)
                line = ax.plot(np.arange(len(values)), values, "o-", markersize=3, label=plain(p.name))[0]
            else:
                values = np.abs(values) / (_rise(p, bands) if relative else 1.0)
                values = np.where(values > 0.0, values, np.nan)
                line = ax.semilogy(np.arange(len(values)), values, "o-", markersize=3, label=plain(p.name))[0]
            _mark_restarts(ax, p, first.description, values, line.get_color())
    units = shown.label if film else first.units
    if film:
        ax.ticklabel_format(axis="y", useOffset=False)  # a film that settles in its 5th digit: values, not an offset
    if counts:
        _count_ticks(ax, points, key)
        ax.set_ylabel(_COUNTS[key])
    elif relative:
        ax.set_ylabel(r"|temperature change| / $\Delta T_{max}$")
    else:
        ax.set_ylabel(f"{name} ({units})" if film else f"|{name}|" + ("" if units in ("", "1") else f" ({units})"))
    ax.set_title(first.description or name, fontsize="medium", wrap=True)
    ax.set_xlabel("outer iteration" if "outer iteration" in first.description else "cycle")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.yaxis.set_minor_locator(NullLocator())  # decades suffice; minor ticks of 5 log panels cost a second
    ax.grid(alpha=0.3)
    legend(ax, fontsize="small", ncols=2)


def _count_ticks(ax: Axes, points: Sequence[PointResult], key: str) -> None:
    """A count history on a linear axis ticked at the counts it takes (a level's nodes: 65, 129, 257, ...)."""
    taken = sorted({int(v) for p in points if key in p.history for v in p.history[key].values if np.isfinite(v)})
    ax.set_yticks(taken)
    ax.yaxis.set_major_formatter(FormatStrFormatter("%d"))


def _rise(point: PointResult, bands: Mapping[str, float]) -> float:
    """The rise the thermal loop's tolerance is scaled by (ehl.solve): ΔT_max, at least `min_rise` (K)."""
    return max(float(point.scalars.get("dT_max", 1.0)), bands.get("min_rise", 0.0))


def restart_indices(point: PointResult, description: str, length: int) -> list[int]:
    """Where each stage after the first begins in a history of `length` entries: the solve record's place of the
    stage's first entry in the per-cycle or the per-outer-iteration histories (StageRecord.first_cycle,
    first_outer); none for a file without a record or a stage not in the reported history."""
    if point.record is None:
        return []
    per_outer = "outer iteration" in description
    starts = [stage.first_outer if per_outer else stage.first_cycle for stage in point.record.stages]
    return sorted({start for start in starts if 0 < start < length})


def _mark_restarts(ax: Axes, point: PointResult, description: str, values: np.ndarray, colour: str) -> None:
    """Open squares on the first iterate of each later stage: the solve began again on a finer grid (or the outlet
    patch), a restart rather than divergence."""
    starts = restart_indices(point, description, len(values))
    if starts:
        ax.plot(starts, values[starts], "s", color=colour, markersize=8, markerfacecolor="none",
                label="_nolegend_")


def _tolerances(ax: Axes, points: Sequence[PointResult], key: str, solver: SolverSettings,
                bands: Mapping[str, float]) -> None:
    """The tolerance a history is judged by (ehl.solve): the pressure change and the load error below their
    tolerances, or the pressure change settled below `pressure_floor_band` times it; the temperature change per
    outer iteration below thermal_tolerance times the rise (at least `min_rise`), or settled below
    `thermal_floor_fraction` of it, lines per point in its colour. The bands are the file's (`convergence_bands`);
    a file without them gets the tolerances alone."""
    if key == "pressure_change_history":
        ax.axhline(solver.tolerance, color="black", linestyle="--", linewidth=1.0,
                   label=f"tolerance {solver.tolerance:.0e}")
        if "pressure_floor_band" in bands:
            bound = bands["pressure_floor_band"] * solver.tolerance
            ax.axhline(bound, color="black", linestyle=":", linewidth=1.0, label=f"settled-floor bound {bound:.0e}")
    elif key == "load_error_history":
        ax.axhline(solver.load_tolerance, color="black", linestyle="--", linewidth=1.0,
                   label=f"tolerance {solver.load_tolerance:.0e}")
    elif key == "viscosity_change_history":
        ax.axhline(solver.eyring_tolerance, color="black", linestyle="--", linewidth=1.0,
                   label=f"tolerance {solver.eyring_tolerance:.0e}")
    elif key == "thermal_change_history":
        _thermal_tolerances(ax, points, key, solver, bands)
    legend(ax, fontsize="small", ncols=2)


def _thermal_tolerances(ax: Axes, points: Sequence[PointResult], key: str, solver: SolverSettings,
                        bands: Mapping[str, float]) -> None:
    """The thermal loop's tolerance (and settled-floor bound, if the file has it) as fractions of each point's rise,
    the axis the changes are drawn on."""
    ax.axhline(solver.thermal_tolerance, color="black", linestyle="--", linewidth=1.0,
               label=f"tolerance {solver.thermal_tolerance:.0e}")
    if "thermal_floor_fraction" in bands:
        floor = bands["thermal_floor_fraction"]
        ax.axhline(floor, color="black", linestyle=":", linewidth=1.0, label=f"settled-floor bound {floor:.0e}")


def _name_restarts(fig: Figure, points: Sequence[PointResult], histories: Sequence[str]) -> None:
    """The open squares named once for the figure, below the panels, when any panel has them."""
    if any(restart_indices(p, p.history[key].description, len(p.history[key].values))
           for key in histories for p in points if key in p.history):
        fig.supxlabel("□ open squares: the first iterate of a later stage of the solve (a finer grid or an outlet "
                      "patch): a restart, not divergence", fontsize="small")


def _levels_panel(ax: Axes, points: Sequence[PointResult]) -> None:
    """h_c on each full-multigrid level relative to the finest: the discretisation error at a glance."""
    for p in points:
        nodes = np.asarray(p.history["level_nodes"].values)
        h_c = np.asarray(p.history["level_h_c"].values)
        ax.plot(nodes, PERCENT(h_c / h_c[-1] - 1.0), "o-", markersize=3, label=plain(p.name))
    ax.set_xscale("log", base=2)
    ax.set_xticks(nodes, [f"{n:.0f}" for n in nodes])
    ax.xaxis.set_minor_locator(NullLocator())
    ax.axhline(0.0, color="black", linewidth=0.6)
    ax.set_title(points[0].history["level_h_c"].description or "central film on the multigrid levels",
                 fontsize="medium", wrap=True)
    ax.set_xlabel("nodes per side")
    ax.set_ylabel(f"$h_c / h_c$(finest) − 1 ({PERCENT.label})")
    ax.grid(alpha=0.3)
    legend(ax, fontsize="small", ncols=2)


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
    fig = figure(width=5.0 * len(abscissae) + 0.5, height=4.2)
    axes = fig.subplots(1, len(abscissae), squeeze=False)[0]
    for ax, (key, label) in zip(axes, abscissae):
        x = np.asarray(sweep[key].values, dtype=float)
        for name, error in errors.items():
            keep = np.isfinite(error) & (error > 0.0)
            ax.plot(x[keep], PERCENT(error[keep]), "o-", label=_FIGURES.get(name, name))
        ax.set_yscale("log")
        ax.yaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))  # 0.5, 1, 2, 5 rather than 6×10⁰
        ax.yaxis.set_major_formatter(FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(NullFormatter())
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
        ax.set_ylabel(f"|error| vs extrapolated value ({PERCENT.label})")
        ax.grid(alpha=0.3, which="both")
        legend(ax, fontsize="small")
    fig.suptitle(title(result, "grid sweep: error vs grid and vs cost"))
    return fig


def _label_grids(ax: Axes, x: np.ndarray, grids: np.ndarray, errors: Mapping[str, np.ndarray]) -> None:
    """Name the grid of each point of the first error curve (on the cost axis the grids are not in order)."""
    error = PERCENT(next(iter(errors.values())))
    for xi, yi, n in zip(x, error, grids):
        if np.isfinite(yi) and yi > 0.0:
            ax.annotate(f"{n:.0f}²", (xi, yi), textcoords="offset points", xytext=(5, 4), fontsize="small")
