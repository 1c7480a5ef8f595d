"""The oil-film fields of a point as the figures draw them: each field in display units on Hertzian
coordinates X = x/b, Y = y/a (the Hertz ellipse is the unit circle), temperatures as the rise over the inlet
ΔT = T − T_inlet (K), with its label, colour map and colour limits; fields that are zero to round-off are
left out with the reason; sections through the centre along and across the entrainment."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
import math

import numpy as np
from scipy.interpolate import RegularGridInterpolator

from facegear_tehl.plots.case_values import CaseValues
from facegear_tehl.plots.common import Output, body_names
from facegear_tehl.results import PointResult, Result
from facegear_tehl.units import Unit, display

FILM_COLOUR_LIMIT = 1.6  # film maps show h up to this multiple of h_c (at the domain edge h is 20-70 times h_c)
SIGNED_CMAP = "RdBu_r"  # temperature rises and fields of both signs: blue below zero, white at zero, red above
# A field whose largest |value| is below this fraction of the largest |value| of the point's fields in the same
# units is round-off of zero (e.g. the frictional heat fluxes mu F |v_s| at the pitch point, where |v_s| is
# ~1e-16 of the rolling speed): double-precision round-off sits near 1e-16 relative, a physical field that
# small relative to its siblings would be invisible anyway; 1e-12 leaves four decades on either side.
ROUND_OFF = 1e-12
KELVIN_RISE = display("K")  # temperature rises on figures, in K


@dataclass(frozen=True)
class _Kind:
    """How one kind of field is drawn: group (fields sharing an axis), colour map, colour of lines on it."""

    group: str
    cmap: str
    ink: str


_KINDS = {"pressure": _Kind("pressure", "inferno", "white"), "film": _Kind("film", "viridis", "black"),
          "temperature": _Kind("temperature", SIGNED_CMAP, "black"), "heat_flux": _Kind("heat_flux", "magma", "white")}


def field_label(result: Result, name: str, description: str = "") -> tuple[str, str] | None:
    """(group, label in mathtext) of a drawn field by its dataset name; None for fields not drawn."""
    body_1, body_2 = body_names(result)
    labels = {
        "pressure": ("pressure", "pressure $p$"),
        "film_thickness": ("film", "film thickness $h$"),
        "temperature_mean": ("temperature", r"film-averaged $\Delta T$"),
        "temperature_mid": ("temperature", r"mid-film $\Delta T$"),
        "temperature_surface_1": ("temperature", rf"$\Delta T$ of the {body_1} surface"),
        "temperature_surface_2": ("temperature", rf"$\Delta T$ of the {body_2} surface"),
        "heat_flux_1": ("heat_flux", f"heat flux $q$ into the {body_1}"),
        "heat_flux_2": ("heat_flux", f"heat flux $q$ into the {body_2}"),
        "heat_flux_by_pressure": ("heat_flux", r"frictional heat flux, $P = \mu F |v_s|$ spread as $p$"),
        "heat_flux_by_shear": ("heat_flux", r"frictional heat flux, $P$ spread as $\tau \cdot v_s$"),
    }
    if name in labels:
        return labels[name]
    for group in ("temperature", "heat_flux"):
        if name.startswith(group):
            return group, description or name.replace("_", " ")
    return None


@dataclass(frozen=True)
class FieldMap:
    """A field on Hertzian coordinates X = x/b (nx,), Y = y/a (ny,), values (ny, nx) in display units
    (temperatures as ΔT = T − T_inlet in K), colour limits vmin, vmax."""

    name: str
    label: str
    X: np.ndarray
    Y: np.ndarray
    values: np.ndarray
    unit: Unit
    kind: _Kind
    vmin: float
    vmax: float

    @property
    def group(self) -> str:
        return self.kind.group

    @property
    def clipped(self) -> bool:
        return self.vmax < float(self.values.max())

    @property
    def signed(self) -> bool:
        """Centred on zero: a temperature rise, or a field of both signs (a heat flux that reverses)."""
        return self.group == "temperature" or self.vmin < 0.0 < self.vmax

    @property
    def cmap(self) -> str:
        return SIGNED_CMAP if self.signed else self.kind.cmap

    @property
    def ink(self) -> str:
        return "black" if self.signed else self.kind.ink

    @property
    def axis_label(self) -> str:
        quantity = {"pressure": "pressure $p$", "film": "film thickness $h$", "temperature": r"$\Delta T$",
                    "heat_flux": "heat flux $q$"}[self.group]
        return f"{quantity} ({self.unit.label})"


def rise_values(point: PointResult, name: str, inlet: float) -> np.ndarray:
    """A temperature field of `point` as ΔT = T − T_inlet (K)."""
    return np.asarray(point.fields[name].values, dtype=float) - inlet


def temperature_limit(points: Iterable[PointResult], case: CaseValues | None) -> float:
    """The common colour limit L of the ΔT maps of `points` (drawn on [−L, L]): the largest |ΔT| of their
    temperature fields and of their dT_max / dT_min scalars; 0 without temperatures."""
    limit = 0.0
    for point in points:
        limit = max([limit] + [abs(float(point.scalars[k])) for k in ("dT_max", "dT_min") if k in point.scalars])
        if case is not None:
            for name in point.fields:
                if name.startswith("temperature"):
                    limit = max(limit, float(np.abs(rise_values(point, name, case.inlet_temperature)).max()))
    return limit


def interior_place(point: PointResult) -> tuple[float, float] | None:
    """(x/b, y/a) of ΔT_min when it lies below the inlet temperature and more than one node inside the domain; None
    when the file lacks the place, the film never cools below the inlet (ΔT_min = 0 is the inlet itself) or the
    minimum sits on the domain boundary (where the inlet oil enters: a boundary value, not a place in the film)."""
    s = point.scalars
    if not {"x_dT_min", "y_dT_min", "dT_min"} <= s.keys() or not {"x", "y"} <= point.axes.keys():
        return None
    x, y = (np.asarray(point.axes[k].values, dtype=float) for k in ("x", "y"))
    inside = all(axis[0] + (axis[1] - axis[0]) < place < axis[-1] - (axis[-1] - axis[-2])
                 for axis, place in ((x, s["x_dT_min"]), (y, s["y_dT_min"])))
    if s["dT_min"] >= 0.0 or not inside:
        return None
    return s["x_dT_min"] / s["b"], s["y_dT_min"] / s["a"]


def hertz_ready(point: PointResult) -> str | None:
    """Why the fields of `point` cannot be drawn in Hertzian coordinates, or None when they can."""
    if not point.fields:
        state = point.message or ("converged" if point.converged else "not converged")
        return f"no fields in the file ({state})"
    missing = [key for key in ("a", "b") if key not in point.scalars] + [
        axis for axis in ("x", "y") if axis not in point.axes]
    return f"fields without {', '.join(missing)}" if missing else None


def point_maps(result: Result, point: PointResult, case: CaseValues | None, dT_limit: float
               ) -> tuple[list[FieldMap], list[str]]:
    """The drawable fields of a point (temperatures as ΔT on [−dT_limit, dT_limit]), and one line for each
    reason a field is left out (round-off, uniform, no inlet temperature). Assumes `hertz_ready(point)`."""
    maps, uniform, no_inlet = [], [], []
    labelled = {name: field_label(result, name, data.description) for name, data in point.fields.items()}
    zero = round_off_names({name: point.fields[name] for name, label in labelled.items() if label is not None})
    for name, label in labelled.items():
        if label is None or name in zero:
            continue
        if label[0] == "temperature" and case is None:
            no_inlet.append(name)
            continue
        m = field_map(point, name, label, case, dT_limit)
        (maps if m.vmax > m.vmin else uniform).append(m)
    reasons = [f"{', '.join(zero)}: zero to round-off (|value| below {ROUND_OFF:.0e} of the largest field "
               "in the same units)"] if zero else []
    reasons += [f"{m.name} is uniform ({m.vmin:.4g} {m.unit.label})" for m in uniform]
    if no_inlet:
        reasons.append(f"{', '.join(no_inlet)}: no inlet temperature (the case text in the file does not parse)")
    return maps, reasons


def round_off_names(fields: dict) -> list[str]:
    """Names of the fields (name -> Field) that are zero to round-off: largest |value| below ROUND_OFF of
    the largest |value| of all fields in the same units."""
    largest = {name: float(np.abs(np.asarray(f.values, dtype=float)).max(initial=0.0)) for name, f in fields.items()}
    scale: dict[str, float] = {}
    for name, f in fields.items():
        scale[f.units] = max(scale.get(f.units, 0.0), largest[name])
    return [name for name, f in fields.items() if largest[name] < ROUND_OFF * scale[f.units]]


def field_map(point: PointResult, name: str, label: tuple[str, str], case: CaseValues | None,
              dT_limit: float) -> FieldMap:
    """One field as drawn; pressure from 0, film up to FILM_COLOUR_LIMIT h_c, ΔT on [−dT_limit, dT_limit],
    fields of both signs symmetric about 0."""
    group, text = label
    data = point.fields[name]
    if group == "temperature":
        unit, values = KELVIN_RISE, rise_values(point, name, case.inlet_temperature)
    else:
        unit = display(data.units)
        values = unit(np.asarray(data.values, dtype=float))
    vmin, vmax = float(values.min()), float(values.max())
    if group == "pressure":
        vmin = 0.0
    if group == "film" and "h_c" in point.scalars:
        vmax = min(vmax, FILM_COLOUR_LIMIT * unit(point.scalars["h_c"]))
    if group == "temperature":
        vmin, vmax = -dT_limit, dT_limit
    elif vmin < 0.0 < vmax:
        vmax = max(-vmin, vmax)
        vmin = -vmax
    return FieldMap(name=name, label=text, X=point.axes["x"].values / point.scalars["b"],
                    Y=point.axes["y"].values / point.scalars["a"], values=values, unit=unit, kind=_KINDS[group],
                    vmin=vmin, vmax=vmax)


def section_directions(point: PointResult) -> tuple[np.ndarray, np.ndarray]:
    """Unit vectors in Hertzian coordinates along the entrainment and across it.

    Along: the true entrainment direction (angle psi to x), mapped to (cos psi / b, sin psi / a).
    Across: perpendicular in Hertzian coordinates, i.e. the ellipse diameter conjugate to the entrainment;
    it runs from edge to edge of the ellipse, which the physical perpendicular does not in a skewed,
    elongated contact. Both cross the ellipse edge at +-1.
    """
    psi = math.radians(point.scalars.get("entrainment_angle", 0.0))
    along = np.array([math.cos(psi) / point.scalars["b"], math.sin(psi) / point.scalars["a"]])
    along /= np.hypot(*along)
    return along, np.array([-along[1], along[0]])


def section_length(point: PointResult, direction: np.ndarray) -> float:
    """The true length (m) of one Hertz radius along `direction` (Hertzian unit vector): |(d_x b, d_y a)|."""
    return float(np.hypot(direction[0] * point.scalars["b"], direction[1] * point.scalars["a"]))


def section(m: FieldMap, direction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Values along t * direction through the centre (t in Hertz radii), where the line is inside the grid."""
    step = 0.5 * min(m.X[1] - m.X[0], m.Y[1] - m.Y[0])
    reach = float(np.hypot(max(abs(m.X[0]), abs(m.X[-1])), max(abs(m.Y[0]), abs(m.Y[-1]))))
    t = np.arange(-reach, reach + step, step)
    X, Y = t * direction[0], t * direction[1]
    inside = (X >= m.X[0]) & (X <= m.X[-1]) & (Y >= m.Y[0]) & (Y <= m.Y[-1])
    interpolate = RegularGridInterpolator((m.Y, m.X), m.values)
    return t[inside], interpolate(np.column_stack([Y[inside], X[inside]]))


def point_fields(result: Result, points: Sequence[PointResult], case: CaseValues | None, out: Output
                 ) -> list[tuple[PointResult, dict[str, FieldMap]]]:
    """The drawable maps of each point that has fields (by field name, ΔT on the point's own scale [−L, L], L its
    largest |ΔT|: a shared scale leaves a point of small rises blank); one skip line per point and reason a field or
    a point is left out, and per thermal group no point has."""
    rows = []
    for point in points:
        dT_limit = temperature_limit([point], case)
        reason = hertz_ready(point)
        if reason is not None:
            out.skip(f"fields {point.name}", reason)
            continue
        maps, reasons = point_maps(result, point, case, dT_limit)
        for line in reasons:
            out.skip(f"fields {point.name}", line)
        rows.append((point, {m.name: m for m in maps}))
    if rows:
        for group in ("temperature", "heat_flux"):
            if not any(name.startswith(group) for point, _ in rows for name in point.fields):
                out.skip(f"fields {group}", f"no {group}* datasets in the file (written by the thermal model)")
    return rows
