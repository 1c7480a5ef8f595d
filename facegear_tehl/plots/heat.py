"""The heat budget per meshing point on linear axes: frictional heat power per gear and its time average at a
point of the tooth surface (Fig. 17 of the seed paper), frictional heat generated per meshing and heat held by the
oil film (Fig. 20, 21) on separate axes (a heat generated and a heat held at one instant are different quantities);
columns that are zero to round-off at every point are left out with one line."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from matplotlib.axes import Axes
import numpy as np

from facegear_tehl.plots.common import Output, body_names, figure, legend_outside, title
from facegear_tehl.plots.field_data import round_off_names
from facegear_tehl.plots.over_points import heat_point_names
from facegear_tehl.results import Result
from facegear_tehl.units import display

STEADY_TITLE = ("time average at one point of the tooth surface (heated for b/(πr) of a revolution);\n"
                "not the gear's heat load, which is the mesh power loss of tehl run")
# The energy panels: one kind of heat per axis, the domain's held heat apart (it grows with the inlet length).
ENERGY_PANELS = (
    ("frictional heat generated per meshing", ("frictional_heat", "frictional_heat_ellipse", "frictional_heat_seed")),
    ("heat held by the oil film in the Hertz ellipse at the solved instant", ("oil_film_heat",)),
    ("heat held by the oil film over the whole solver domain at the solved instant\n"
     "(grows with the lengthened inlet; not a share of the heat generated)", ("oil_film_heat_domain",)),
)


def _labels(result: Result) -> dict[str, str]:
    """Legend labels of the /heat columns the heat budget writes."""
    body_1, body_2 = body_names(result)
    return {
        "friction_power": r"$P = \mu F |v_s|$, both bodies",
        "friction_power_1": rf"$\gamma_1 P$ into the {body_1}",
        "friction_power_2": rf"$\gamma_2 P$ into the {body_2}",
        "dissipated_power": "$P_{film}$: film dissipation, whole domain",
        "dissipated_power_ellipse": "$P_{film}$ in the Hertz ellipse",
        "steady_power_1": rf"$P_{{ss,1}} = \gamma_1 P\, b/(\pi r_1)$, {body_1}",
        "steady_power_2": rf"$P_{{ss,2}} = \gamma_2 P\, b/(\pi r_2)$, {body_2}",
        "frictional_heat": "$Q_f$: film dissipation, whole domain",
        "frictional_heat_ellipse": "$Q_{f,ellipse}$: film dissipation in the Hertz ellipse",
        "frictional_heat_seed": r"$Q_{f,seed} = \mu F |v_s| t_c$ (seed paper)",
        "oil_film_heat": "$Q_{oil}$: held by the oil film in the Hertz ellipse",
        "oil_film_heat_domain": "$Q_{oil}$: held by the oil film, whole domain",
    }


def _column_label(result: Result, name: str) -> str:
    """The label of a /heat column; 'x_y_1' -> 'x y, pinion' for a column the heat budget does not write."""
    labels = _labels(result)
    if name in labels:
        return labels[name]
    for suffix, body in zip(("_1", "_2"), body_names(result)):
        if name.endswith(suffix):
            return f"{name[: -len(suffix)].replace('_', ' ')}, {body}"
    return name.replace("_", " ")


def _heat_columns(result: Result, units: str, out: Output) -> dict[str, np.ndarray]:
    """The /heat columns in `units` that are not zero to round-off at every point (one line for those)."""
    columns = {name: c for name, c in result.heat.items() if c.units == units}
    zero = round_off_names(columns)
    if zero:
        out.skip(f"heat {', '.join(zero)}", "zero to round-off at every point")
    return {name: np.asarray(c.values, dtype=float) for name, c in columns.items() if name not in zero}


def draw_heat(result: Result, out: Output) -> None:
    """Frictional heat power per gear, steady-state power (Fig. 17) and heat per meshing point (Fig. 20, 21)."""
    if not result.heat:
        out.skip("heat", "no /heat table in the file (written by the heat budget)")
        return
    names = heat_point_names(result)
    powers = _heat_columns(result, "W", out)
    if powers:
        panels = [
            ("instantaneous frictional heat power", {k: v for k, v in powers.items() if "steady" not in k}),
            (STEADY_TITLE,
             {k: v for k, v in powers.items() if "steady" in k}),
        ]
        _panel_bars(result, names, panels, 2.8, "heat power (W)", "frictional heat power", "heat_power", out)
    else:
        out.skip("heat power", "no heat power columns (units W) in /heat")
    energies = _heat_columns(result, "J", out)
    if not energies:
        out.skip("heat energy", "no heat columns (units J) in /heat")
        return
    unit = display("J")
    panels = [(panel_title, {k: unit(energies[k]) for k in keys if k in energies})
              for panel_title, keys in _energy_panels(energies)]
    _panel_bars(result, names, panels, 2.4, f"heat ({unit.label})", "frictional heat and heat held by the oil film",
                "heat_oil_film", out)


def _panel_bars(result: Result, names: Sequence[str], panels: list[tuple[str, dict]], height: float, ylabel: str,
                what: str, stem: str, out: Output) -> None:
    """One bar panel per (title, columns) that has columns, stacked over the meshing points (`height` inches each),
    saved as `stem`."""
    panels = [(panel_title, columns) for panel_title, columns in panels if columns]
    fig = figure(width=9.0, height=height * len(panels) + 0.8)
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (panel_title, columns) in zip(axes, panels):
        _bars(ax, result, names, columns)
        ax.set_title(panel_title, fontsize="medium")
        ax.set_ylabel(ylabel)
    axes[-1].set_xlabel("meshing point")
    fig.suptitle(title(result, what))
    out.save(fig, stem)


def _energy_panels(energies: Mapping[str, np.ndarray]) -> list[tuple[str, tuple[str, ...]]]:
    """ENERGY_PANELS, and a panel of its own for each /heat column in J the heat budget does not write."""
    known = {key for _, keys in ENERGY_PANELS for key in keys}
    return [*ENERGY_PANELS, *((name.replace("_", " "), (name,)) for name in energies if name not in known)]


def _bars(ax: Axes, result: Result, names: Sequence[str], columns: Mapping[str, np.ndarray]) -> None:
    """Grouped bars on a linear axis from 0, one group per point; the legend beside the axes."""
    width = 0.8 / len(columns)
    x = np.arange(len(names))
    for i, (name, values) in enumerate(columns.items()):
        ax.bar(x + (i - (len(columns) - 1) / 2) * width, values, width, label=_column_label(result, name))
    ax.set_xticks(x, list(names))
    ax.grid(axis="y", alpha=0.3)
    legend_outside(ax)
