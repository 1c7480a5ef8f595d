"""Friction coefficients over the meshing points (Fig. 14, 15)."""

from __future__ import annotations

from facegear_tehl.plots.common import Output, figure, legend_outside, title
from facegear_tehl.plots.over_points import (
    SWEEP_FILE,
    bars_note,
    error_bars,
    jump_note,
    not_converged_note,
    per_point,
    plot_series,
    point_axis,
)
from facegear_tehl.results import Result

# Friction coefficients: scalar or /heat column name -> legend label.
_FRICTION_LABELS = {"mu": r"$\mu$ of the solved film",
                    "mu_xu": r"$\mu$, Xu et al. (2007), empirical"}


def _friction_keys(result: Result) -> list[str]:
    """The friction coefficients the file holds, as point scalars or /heat columns."""
    keys = {k for p in result.points.values() for k in p.scalars} | set(result.heat)
    return [k for k in _FRICTION_LABELS if k in keys]


def draw_friction(result: Result, out: Output) -> None:
    """Friction coefficients over the meshing points (Fig. 14, 15)."""
    keys = _friction_keys(result)
    if result.sweep:
        out.skip("friction", SWEEP_FILE)
        return
    if not keys:
        out.skip("friction", "no friction coefficients in the file (point scalars or /heat columns mu, mu_xu)")
        return
    for key in ("mu", "mu_xu"):
        if key not in keys:
            out.skip(f"friction {key}", f"no {key} ({_FRICTION_LABELS[key]}) in the file")
    series = {key: per_point(result, key) for key in keys}
    names = [n for n in dict.fromkeys(n for values in series.values() for n in values)]
    positions, label_axis = point_axis(result, names)
    fig = figure(width=8.5, height=4.2)
    ax = fig.add_subplot()
    for key, values in series.items():
        errors, unresolved = error_bars(result, key, values)
        plot_series(ax, result, positions, values, _FRICTION_LABELS.get(key, key), errors=errors,
                    unresolved=unresolved)
    not_converged_note(ax, result)
    jump_note(ax, result, names)
    if "mu" in keys:
        bars_note(ax, result)
    ax.set_ylabel(r"friction coefficient $\mu$ (–)")
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    legend_outside(ax)
    label_axis(ax)
    ax.set_title(title(result, "friction coefficient over the meshing points"))
    out.save(fig, "friction")
