"""Film characteristics over the meshing points (Fig. 13): p_max, h_c, h_min and ΔT_max."""

from __future__ import annotations

from facegear_tehl.plots.common import Output, figure, legend, title
from facegear_tehl.plots.over_points import SWEEP_FILE, not_converged_note, per_point, plot_series, point_axis
from facegear_tehl.results import Result
from facegear_tehl.units import CELSIUS_RISE, display

# Per panel: title, quantity on the y axis, its display unit, then (key, label, linestyle) per series.
_TRENDS = (
    ("maximum pressure", "pressure", display("Pa"),
     (("p_max", "p_max (EHL)", "o-"), ("p_hertz", "p_h (dry Hertz)", "s--"))),
    ("film thickness", "film thickness", display("m"),
     (("h_c", "h_c (central)", "o-"), ("h_min", "h_min (minimum)", "s-"))),
    ("maximum temperature rise", "ΔT_max", CELSIUS_RISE, (("dT_max", "ΔT_max", "o-"),)),
)


def draw_trends(result: Result, out: Output) -> None:
    """p_max, h_c, h_min and ΔT_max over the meshing points (Fig. 13)."""
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
        out.skip("trends ΔT_max", "no dT_max scalar in the file (written by the thermal model)")
    positions, label_axis = point_axis(result, names)
    fig = figure(height=2.5 * len(panels) + 0.8)
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (panel_title, quantity, unit, series) in zip(axes, panels):
        for key, label, style in series:
            values = {n: unit(v) for n, v in per_point(result, key).items()}
            plot_series(ax, result, positions, values, label, style)
        ax.set_title(panel_title)
        ax.set_ylabel(f"{quantity} ({unit.label})")
        ax.grid(alpha=0.3)
        legend(ax, fontsize="small")
    not_converged_note(axes[0], result)
    legend(axes[0], fontsize="small")
    label_axis(axes[-1])
    missing = [n for n in result.points if n not in names]
    suffix = f" (no results: {', '.join(missing)})" if missing else ""
    fig.suptitle(title(result, "film characteristics over the meshing points" + suffix))
    out.save(fig, "trends")
