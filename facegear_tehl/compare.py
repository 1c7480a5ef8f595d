"""`tehl compare A.h5 B.h5 [...]`: two or more designs side by side, point by point, each difference judged against
the solver's error estimates.

Per meshing point present in every file, and per quantity, the value of each file, the difference of each file to
the first and the combined estimate e = sqrt(e_1^2 + e_2^2) of the two values' grid errors (each e_i the file's
relative estimate times its value: Richardson's, ehl/report.py). A difference no larger than e is marked not
significant: the grids cannot tell the designs apart there. A quantity without an estimate is compared without a
verdict; a point that did not converge in a file is not compared (its values are an iterate's, not a film's) and
not drawn. The figure overlays the quantities along the contact path with their estimates as error bars.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum
import math
from pathlib import Path

from matplotlib.axes import Axes
from matplotlib.figure import Figure
import numpy as np

from facegear_tehl.plots.common import Output, PlotReport, figure
from facegear_tehl.plots.over_points import continuous_runs
from facegear_tehl.results import PointResult, Result
from facegear_tehl.tables import error_bound, format_table, scalar_unit
from facegear_tehl.units import MILLIMETRE

# Quantity, the scalar holding its relative error estimate (λ = h_min/σ carries h_min's; None: no estimate).
QUANTITIES = (("h_c", "error_estimate_h_c"), ("h_min", "error_estimate_h_min"),
              ("film_parameter", "error_estimate_h_min"), ("p_max", "error_estimate_p_max"),
              ("dT_max", "error_estimate_dT_max"), ("mu", "error_estimate_mu"))
PLOTTED = ("h_min", "p_max", "dT_max", "mu")  # the quantities drawn along the path


class Significance(Enum):
    """Whether a difference exceeds the combined error estimate of the two values."""

    SIGNIFICANT = "yes"
    NOT_SIGNIFICANT = "no (within the estimates)"
    UNKNOWN = "no estimate"
    NOT_CONVERGED = "not compared (not converged)"


@dataclass(frozen=True)
class Difference:
    """One quantity of one point in two files: both values (SI), the difference b - a, the combined estimate (SI;
    NaN without one) and its significance."""

    point: str
    quantity: str
    units: str
    a: float
    b: float
    estimate: float
    significance: Significance

    @property
    def difference(self) -> float:
        return self.b - self.a


def common_points(results: Sequence[Result]) -> list[str]:
    """The point names every file holds, in the first file's order."""
    return [name for name in results[0].points if all(name in r.points for r in results[1:])]


def absolute_estimate(point: PointResult, quantity: str, estimate: str | None) -> float:
    """The grid-error estimate of a scalar in its units: its figure's error bound times |value| (NaN where unresolved);
    in a file without bounds a relative estimate (units "1", as ehl/report.py writes them) times |value|, an
    estimate in the scalar's own units as it is; NaN without one."""
    if estimate is None or quantity not in point.scalars:
        return math.nan
    bound = error_bound(point.scalars, estimate.removeprefix("error_estimate_"))
    if bound is not None:  # the error bound (ehl/error_bounds.py): none where the solve cannot give one
        return math.nan if isinstance(bound, str) else bound * abs(point.scalars[quantity])
    if estimate not in point.scalars:
        return math.nan
    absolute = point.units.get(estimate, "1") != "1" and point.units.get(estimate) == point.units[quantity]
    return abs(point.scalars[estimate]) * (1.0 if absolute else abs(point.scalars[quantity]))


def differences(a: Result, b: Result) -> list[Difference]:
    """Every QUANTITY of every point the two files share."""
    found = []
    for name in common_points([a, b]):
        pa, pb = a.points[name], b.points[name]
        for quantity, estimate in QUANTITIES:
            if quantity not in pa.scalars or quantity not in pb.scalars:
                continue
            combined = math.hypot(absolute_estimate(pa, quantity, estimate), absolute_estimate(pb, quantity, estimate))
            va, vb = float(pa.scalars[quantity]), float(pb.scalars[quantity])
            if not (pa.converged and pb.converged):
                va, vb = (v if p.converged else math.nan for v, p in ((va, pa), (vb, pb)))
                combined, significance = math.nan, Significance.NOT_CONVERGED
            elif math.isnan(combined):
                significance = Significance.UNKNOWN
            else:
                significance = Significance.SIGNIFICANT if abs(vb - va) > combined else Significance.NOT_SIGNIFICANT
            found.append(Difference(name, quantity, pa.units[quantity], va, vb, combined, significance))
    return found


def comparison_table(results: Sequence[Result], labels: Sequence[str]) -> str:
    """Per point and quantity: each file's value, and for each file after the first its difference to the first, the
    combined estimate and the significance; in engineering units."""
    rows = []
    pairs = [differences(results[0], other) for other in results[1:]]
    for first in pairs[0]:
        unit = scalar_unit(first.quantity, first.units)
        cells = [first.point, first.quantity, unit.label, _number(unit(first.a))]
        for pair in pairs:
            match = next((d for d in pair if (d.point, d.quantity) == (first.point, first.quantity)), None)
            cells += ["-"] * 4 if match is None else [
                _number(unit(match.b)),
                "-" if math.isnan(match.difference) else _number(unit(match.difference) - unit(0.0)),
                "-" if math.isnan(match.estimate) else _number(unit(match.estimate) - unit(0.0)),
                match.significance.value]
        rows.append(cells)
    headers = ["point", "quantity", "unit", labels[0]]
    for label in labels[1:]:
        headers += [label, f"{label} - {labels[0]}", "± estimate", "significant"]
    return format_table(headers, rows)


def _number(value: float) -> str:
    return "not converged" if math.isnan(value) else f"{value:.4g}"


def comparison_figure(results: Sequence[Result], labels: Sequence[str]) -> Figure:
    """PLOTTED along the path coordinate s of each point, one series per file with the estimates as error bars, no
    line across a jump of the tooth load (over_points.continuous_runs); a white-filled marker where a file's value
    is within the combined estimates of the first file's."""
    fig = figure(width=8.0, height=2.4 * len(PLOTTED) + 0.8)
    axes = fig.subplots(len(PLOTTED), 1, sharex=True)
    along_path = any("path_coordinate" in p.scalars for result in results for p in result.points.values())
    for ax, quantity in zip(axes, PLOTTED):
        if along_path:
            for k, (result, label) in enumerate(zip(results, labels)):
                _series(ax, results[0], result, quantity, label, f"C{k}", k == 0)
        else:
            _by_file(ax, results, labels, quantity)
        ax.grid(alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize="small")
    axes[-1].set_xlabel(f"path coordinate s ({MILLIMETRE.label}); error bars: the solver's grid-error estimates; "
                        "white: within them of the first file" if along_path else
                        "file; error bars: the solver's grid-error estimates")
    fig.suptitle("comparison: " + " vs ".join(labels), fontsize="medium")
    return fig


def _by_file(ax: Axes, results: Sequence[Result], labels: Sequence[str], quantity: str) -> None:
    """Plain contacts (no contact path): each shared point's `quantity` over the files, with its estimates as error
    bars."""
    for k, name in enumerate(common_points(results)):
        points = [result.points[name] for result in results]
        if not all(quantity in p.scalars and p.converged for p in points):
            continue
        unit = scalar_unit(quantity, points[0].units[quantity])
        values = [unit(p.scalars[quantity]) for p in points]
        errors = [abs(unit(np.nan_to_num(absolute_estimate(p, quantity, dict(QUANTITIES)[quantity]))) - unit(0.0))
                  for p in points]
        ax.errorbar(range(len(points)), values, yerr=errors, fmt="o-", markersize=4, capsize=3, color=f"C{k}",
                    label=name)
        ax.set_ylabel(f"{quantity} ({unit.label})" if unit.label != "-" else quantity)
    ax.set_xticks(range(len(results)), labels)


def _series(ax: Axes, first: Result, result: Result, quantity: str, label: str, colour: str, first_file: bool
            ) -> None:
    """One file's `quantity` along the path: lines per continuous run, error bars, open markers where the difference
    to the first file is not significant."""
    points = [p for p in result.points.values()
              if p.converged and quantity in p.scalars and "path_coordinate" in p.scalars]
    if not points:
        return
    unit = scalar_unit(quantity, points[0].units[quantity])
    at = {p.name: (MILLIMETRE(p.scalars["path_coordinate"]), unit(p.scalars[quantity])) for p in points}
    errors = [abs(unit(np.nan_to_num(absolute_estimate(p, quantity, dict(QUANTITIES)[quantity]))) - unit(0.0))
              for p in points]
    ax.errorbar([at[p.name][0] for p in points], [at[p.name][1] for p in points], yerr=errors, fmt="o",
                markersize=4, capsize=3, color=colour, label=label)
    for run in continuous_runs(result, [p.name for p in points]):
        ax.plot([at[n][0] for n in run], [at[n][1] for n in run], "-", color=colour)
    if not first_file:
        same = [d.point for d in differences(first, result)
                if d.quantity == quantity and d.significance is Significance.NOT_SIGNIFICANT and d.point in at]
        ax.plot([at[n][0] for n in same], [at[n][1] for n in same], "o", markersize=4, color="white",
                markeredgecolor=colour)
    ax.set_ylabel(f"{quantity} ({unit.label})" if unit.label != "-" else quantity)


def labels_of(paths: Sequence[Path]) -> list[str]:
    """File stems, or the paths themselves when two stems coincide."""
    stems = [p.stem for p in paths]
    return stems if len(set(stems)) == len(stems) else [str(p) for p in paths]


def save_figure(results: Sequence[Result], labels: Sequence[str], target: Path) -> PlotReport:
    """Draw the comparison figure into `target` (its suffix the format: png, pdf or svg)."""
    out = Output(target.parent, target.suffix.lstrip(".") or "png", 150, PlotReport())
    out.save(comparison_figure(results, labels), target.stem)
    return out.report
