"""The meshing cycle along the contact path (/cycle): load share and p_h; h_min with the film parameter as a second
scale; ΔT_max and the surface rises; the contact temperatures solved and by Blok's flash formula; μ and the sliding
power; S1–S5 marked, the efficiency in the title. A panel with two y-axes names the axis of each series in its
legend."""

from __future__ import annotations

from collections.abc import Mapping

from matplotlib.axes import Axes
import numpy as np

from facegear_tehl.plots.common import Output, body_names, figure, title
from facegear_tehl.plots.over_points import continuous_runs
from facegear_tehl.results import Result
from facegear_tehl.solution import Field
from facegear_tehl.units import CELSIUS, MILLIMETRE, PERCENT, Unit, display

MESHING_POINTS = ("S1", "S2", "S3", "S4", "S5")
# Per panel: (key, label, style, unit) on the left axis, then on the right axis (none: one axis); a key the file
# lacks is left out. One quantity per axis; where a panel has two, each legend entry names its axis.
_PANELS = (
    ((("load_share", "load share of the pair", "o-", Unit("–")),),
     (("p_h", "$p_h$ (dry Hertz)", "s--", display("Pa")),)),
    ((("h_min", "h_min", "o-", display("m")),), ()),
    ((("dT_max", "ΔT_max (film)", "o-", Unit("K")), ("dT_surface_1_max", "surface rise, {0}", "^-", Unit("K")),
      ("dT_surface_2_max", "surface rise, {1}", "v-", Unit("K"))), ()),
    ((("contact_temperature_1", "θ_B solved, {0}", "^-", CELSIUS),
      ("contact_temperature_2", "θ_B solved, {1}", "v-", CELSIUS),
      ("contact_temperature_blok_1", "θ_B Blok (1937) flash, {0}", "D:", CELSIUS),
      ("contact_temperature_blok_2", "θ_B Blok (1937) flash, {1}", "x:", CELSIUS)), ()),
    ((("mu", "μ (film)", "o-", Unit("–")), ("mu_xu", "μ Xu et al. (2007) [c]", "s-", Unit("–"))),
     (("sliding_power", "P = μF|v_s| (film)", "o--", Unit("W")),
      ("sliding_power_xu", "P with Xu's μ [c]", "s--", Unit("W")))),
)
_LEFT_LABELS = ("load share of the pair (–)", "h_min ({0})", "temperature rise over the inlet (K)",
                "contact temperature θ_B (°C)", "friction coefficient μ (–)")
_RIGHT_LABELS = ("$p_h$ ({0})", "", "", "", "sliding power (W)")
_FILM_PANEL = 1  # the panel of h_min, with λ = h_min/σ as a second scale of the same curve
_FRICTION_PANEL = 4


def draw_cycle(result: Result, out: Output) -> None:
    """Along-path panels of the /cycle group, one figure 'cycle'."""
    cycle = result.cycle
    if not cycle or len(cycle["s"].values) < 2:
        out.skip("cycle", "no /cycle group with two or more points (written by tehl run for a face gear pair)")
        return
    s = MILLIMETRE(np.asarray(cycle["s"].values, dtype=float))
    names = [str(n) for n in cycle["point"].values]
    open_points = np.array([n in result.points and not result.points[n].converged for n in names])
    bodies = body_names(result)
    runs = [[names.index(n) for n in run] for run in continuous_runs(result, names)]
    fig = figure(height=13.0)
    axes = fig.subplots(len(_PANELS), 1, sharex=True)
    for i, (ax, (left, right)) in enumerate(zip(axes, _PANELS)):
        sides = " (left axis)" if right else ""
        handles = _series(ax, cycle, s, left, bodies, open_points, runs, "C0", sides)
        ax.set_ylabel(_LEFT_LABELS[i].format(left[0][3].label))
        if right:
            twin = ax.twinx()
            handles += _series(twin, cycle, s, right, bodies, open_points, runs, "C3", " (right axis)")
            twin.set_ylabel(_RIGHT_LABELS[i].format(right[0][3].label))
        if i == _FILM_PANEL:
            _film_parameter_scale(ax, cycle)
        if i == _FRICTION_PANEL and "mu_iso" in result.cycle_scalars:
            handles.append(ax.axhline(result.cycle_scalars["mu_iso"], color="C2", linestyle="-.",
                                      label="μ ISO/TR 14179-2 (mean) [c] (left axis)"))
        ax.grid(alpha=0.3)
        if handles:
            ax.legend(handles=handles, fontsize="x-small", loc="upper left", bbox_to_anchor=(1.12, 1.0))
        _mark_meshing_points(ax, result, label=i == 0)
    axes[-1].set_xlabel(f"path coordinate s ({MILLIMETRE.label}); [c] cylindrical-gear correlation")
    fig.suptitle(title(result, "meshing cycle, " + _efficiency_text(result)), fontsize="medium")
    out.save(fig, "cycle")


def _film_parameter_scale(ax: Axes, cycle: Mapping[str, Field]) -> None:
    """λ = h_min/σ as a right-hand scale of the h_min curve (σ the composite roughness, the ratio of the two columns
    the file holds): one curve, two scales, rather than two coinciding curves."""
    if "film_parameter" not in cycle or "h_min" not in cycle:
        return
    h_min = display("m")(np.asarray(cycle["h_min"].values, dtype=float))
    lam = np.asarray(cycle["film_parameter"].values, dtype=float)
    sigma = float(np.median(h_min / lam))
    scale = ax.secondary_yaxis("right", functions=(lambda h: h / sigma, lambda x: x * sigma))
    scale.set_ylabel(f"λ = h_min/σ (σ {sigma:.3g} {display('m').label})")


def _series(ax: Axes, cycle: Mapping[str, Field], s: np.ndarray, series: tuple, bodies: tuple[str, str],
            open_points: np.ndarray, runs: list[list[int]], color: str, side: str) -> list:
    """The series of one axis that the file holds, a line through each run of points between two jumps of the
    tooth load (over_points.continuous_runs: no trend drawn across a jump); open markers where a point did not
    converge; `side` (the axis a series is read on) ends each legend label."""
    handles = []
    for k, (key, label, style, unit) in enumerate(series):
        if key not in cycle:
            continue
        values = unit(np.asarray(cycle[key].values, dtype=float))
        size = 6 if style[0] in "Dx" else 3  # Blok's markers larger than the solved ones they often coincide with
        colour = f"C{(int(color[1]) + k) % 10}"
        name = label.format(*bodies) + side
        segments = [ax.plot(s[run], values[run], style, color=colour, markersize=size,
                            label=name if r == 0 else "_nolegend_")[0] for r, run in enumerate(runs)]
        line = segments[0]
        if open_points.any():
            ax.plot(s[open_points], values[open_points], "o", color="white", markeredgecolor=line.get_color(),
                    markersize=5)
        handles.append(line)
    return handles


def _mark_meshing_points(ax: Axes, result: Result, label: bool) -> None:
    """Dotted vertical lines at S1..S5 (the /cycle attrs s_S1..s_S5), named on the top panel."""
    for name in MESHING_POINTS:
        key = f"s_{name}"
        if key in result.cycle_scalars:
            x = MILLIMETRE(result.cycle_scalars[key])
            ax.axvline(x, color="grey", linestyle=":", linewidth=0.8)
            if label:
                ax.annotate(name, (x, 1.0), xycoords=("data", "axes fraction"), ha="center", va="bottom",
                            fontsize="small")


def _efficiency_text(result: Result) -> str:
    """'η = 99.77 % (Xu [c] 99.90 %, ISO/TR 14179-2 [c] 99.90 %)' from the /cycle attrs, or why there is none."""
    scalars = result.cycle_scalars
    if "mesh_efficiency" not in scalars:
        return "no mesh efficiency (see the file's warnings)"
    others = [f"{label} {PERCENT(scalars[key]):.2f} %" for key, label in
              (("mesh_efficiency_xu", "Xu [c]"), ("mesh_efficiency_iso", "ISO/TR 14179-2 [c]")) if key in scalars]
    text = f"mesh efficiency η = {PERCENT(scalars['mesh_efficiency']):.2f} %"
    return text + (f" ({', '.join(others)})" if others else "")
