"""Film characteristics over the meshing points (Fig. 13 of the seed paper): p_max with the dry Hertz p_h,
h_c and h_min, ΔT_max and ΔT_min, with the solver's error bounds as error bars and no line across the
jumps of the tooth load."""

from __future__ import annotations

from collections.abc import Sequence

from matplotlib.axes import Axes
import numpy as np

from facegear_tehl.plots.common import Output, figure, legend_outside, title
from facegear_tehl.plots.field_data import KELVIN_RISE
from facegear_tehl.plots.over_points import (
    SWEEP_FILE,
    bars_note,
    error_bars,
    jump_note,
    not_converged_note,
    on_path,
    per_point,
    plot_series,
    point_axis,
)
from facegear_tehl.results import Result
from facegear_tehl.units import MILLIMETRE, Unit, display

# Per panel: title, quantity on the y axis, its display unit, then (key, label, style) per series.
_TRENDS = (
    ("maximum pressure", "pressure $p$", display("Pa"),
     (("p_max", "$p_{max}$ (EHL)", "o-"), ("p_hertz", "$p_h$ (dry Hertz)", "s--"))),
    ("film thickness", "film thickness $h$", display("m"),
     (("h_c", "$h_c$ (central)", "o-"), ("h_min", "$h_{min}$ (minimum)", "s-"))),
    ("temperature rise over the inlet", r"$\Delta T$", KELVIN_RISE,
     (("dT_max", r"$\Delta T_{max}$", "o-"), ("dT_min", r"$\Delta T_{min}$", "v-"))),
)


def draw_trends(result: Result, out: Output) -> None:
    """p_max, h_c, h_min, ΔT_max and ΔT_min over the meshing points (Fig. 13)."""
    if result.sweep:
        out.skip("trends", SWEEP_FILE)
        return
    names = [n for n, p in result.points.items() if p.scalars.keys() - {"path_coordinate"}]
    if len(names) < 2:
        out.skip("trends", f"results at {len(names)} point(s); trends need two or more")
        return
    panels = [(t, q, u, [s for s in series if per_point(result, s[0])]) for t, q, u, series in _TRENDS]
    panels = [panel for panel in panels if panel[3]]
    if not any(s[0] == "dT_max" for *_, series in panels for s in series):
        out.skip("trends ΔT", "no dT_max scalar in the file (written by the thermal model)")
    positions, label_axis = point_axis(result, names)
    fig = figure(width=8.5, height=2.4 * len(panels) + 0.9)
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (panel_title, quantity, unit, series) in zip(axes, panels):
        for key, label, style in series:
            values = {n: unit(v) for n, v in per_point(result, key).items()}
            plot_series(ax, result, positions, values, label, style, *error_bars(result, key, values))
        if series[0][0] == "p_max":
            _path_hertz_pressure(ax, result, names, unit)
        if series[0][0] == "dT_max":
            ax.axhline(0.0, color="black", linewidth=0.6)
        ax.set_title(panel_title, fontsize="medium")
        ax.set_ylabel(f"{quantity} ({unit.label})")
        ax.grid(alpha=0.3)
    not_converged_note(axes[0], result)
    jump_note(axes[0], result, names)
    bars_note(axes[0], result)
    for ax in axes:
        legend_outside(ax)
    label_axis(axes[-1])
    missing = [n for n in result.points if n not in names]
    suffix = f" (no results: {', '.join(missing)})" if missing else ""
    fig.suptitle(title(result, "film characteristics over the meshing points" + suffix))
    out.save(fig, "trends")


def _path_hertz_pressure(ax: Axes, result: Result, names: Sequence[str], unit: Unit) -> None:
    """The dry Hertz pressure along the whole /contact path, with its jumps, behind the points."""
    table = result.contact
    if {"s", "p_h"} <= table.keys() and on_path(result, names):
        ax.plot(MILLIMETRE(np.asarray(table["s"].values)), unit(np.asarray(table["p_h"].values)), color="grey",
                linewidth=0.8, alpha=0.7, label="$p_h$ along the path", zorder=0)
