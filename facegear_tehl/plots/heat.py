"""The heat budget per meshing point: frictional heat power per gear and its steady-state value (Fig. 17),
frictional heat and heat absorbed by the oil film (Fig. 20, 21)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from matplotlib.axes import Axes
import numpy as np

from facegear_tehl.plots.common import Output, body_names, figure, legend, title
from facegear_tehl.plots.over_points import heat_point_names
from facegear_tehl.results import Result


def _heat_columns(result: Result, units: str) -> dict[str, np.ndarray]:
    """The /heat columns in `units`, by name."""
    return {name: np.asarray(c.values, dtype=float) for name, c in result.heat.items() if c.units == units}


def _column_label(result: Result, name: str) -> str:
    """'friction_power_1' -> 'friction power, pinion' (body 1/2 of a plain contact)."""
    body_1, body_2 = body_names(result)
    for suffix, body in (("_1", body_1), ("_2", body_2)):
        if name.endswith(suffix):
            return f"{name[: -len(suffix)].replace('_', ' ')}, {body}"
    return name.replace("_", " ")


def draw_heat(result: Result, out: Output) -> None:
    """Frictional heat power per gear, steady-state power (Fig. 17) and heat per meshing point (Fig. 20, 21)."""
    if not result.heat:
        out.skip("heat", "no /heat table in the file (written by the heat budget)")
        return
    names = heat_point_names(result)
    powers = _heat_columns(result, "W")
    if powers:
        panels = [
            ("instantaneous frictional heat power", {k: v for k, v in powers.items() if "steady" not in k}),
            ("steady-state frictional heat power", {k: v for k, v in powers.items() if "steady" in k}),
        ]
        panels = [(panel_title, columns) for panel_title, columns in panels if columns]
        fig = figure(height=2.8 * len(panels) + 0.8)
        axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
        for ax, (panel_title, columns) in zip(axes, panels):
            _bars(ax, result, names, columns, log=False)
            ax.set_title(panel_title)
            ax.set_ylabel("heat power (W)")
        axes[-1].set_xlabel("meshing point")
        fig.suptitle(title(result, "frictional heat power"))
        out.save(fig, "heat_power")
    else:
        out.skip("heat power", "no heat power columns (units W) in /heat")
    energies = {k: v for k, v in _heat_columns(result, "J").items() if np.any(v > 0.0)}
    if not energies:
        out.skip("heat energy", "no heat columns (units J) in /heat")
        return
    fig = figure(height=4.5)
    ax = fig.add_subplot()
    _bars(ax, result, names, energies, log=True)
    _annotate_oil_share(ax, energies)
    ax.set_ylabel("heat per meshing (J, log scale)")
    ax.set_xlabel("meshing point")
    ax.set_title(title(result, "frictional heat and heat absorbed by the oil film"))
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
    legend(ax, fontsize="small")


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
    legend(ax, fontsize="small", loc="upper right")
