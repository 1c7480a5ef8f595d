"""The solution domain of a contact point, in Hertzian units (X = x/b, Y = y/a), and its nodes.

The start is Venner & Lubrecht's (2000) square of +-3 semi-axes shifted 1.5 upstream (along x: X in [-4.5, 1.5],
Y in [-3, 3]). Its inlet starves thick films: the pressure is held at zero where the inlet meets the domain's edge,
so the hydrodynamic pressure the real inlet builds further upstream is missing. In the far inlet the film is the
rigid gap g = x^2/(2 R_x) and Reynolds' equation gives dq/dx ~ 6 eta_0 u_e/g^2, so the missing reduced pressure
q(-L) ~ 8 eta_0 u_e R_x^2/L^3 ~ G^(-3/2), with G = g(-L)/h_c the inlet gap ratio. The measured h_c error follows
that law: on the face gear points (isothermal Newtonian, fixed spacing) it is 140-200 G^(-3/2) percent
(docs/accuracy.md, domain size; 6.5 % at G = 7.5, 0.57 % at G = 38).

When the case gives no `solver.domain`, the domain is therefore lengthened upstream along the axis through which
the entrainment line leaves it, doubling that length together with its node count (the spacing of the grid asked
for is kept, and the grid stays 2^n + 1; from TUNING.min_lengthened_nodes up), until the inlet gap ratio predicted with
Hamrock & Dowson's (1977) central film reaches inlet_gap_target (at most max_inlet_doublings times). The isothermal
formula over-predicts a heated film, so the ratio of the solved film is larger still (a conservative choice).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math

import numpy as np

from facegear_tehl.ehl.scaling import Scaling
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.film_formulas import hamrock_dowson_central
from facegear_tehl.settings import SolverSettings


@dataclass(frozen=True)
class Domain:
    """The domain of one solve (Hertzian units) and its finest grid's nodes."""

    x: tuple[float, float]
    y: tuple[float, float]
    nx: int
    ny: int
    doublings: int  # times the inlet was lengthened (0: the domain of the settings, or the default one)
    predicted_gap_ratio: float  # inlet gap ratio with the Hamrock & Dowson central film (nan: domain given)
    capped: bool = False  # the lengthened axis kept max_lengthened_nodes nodes, fewer than the spacing asked needs

    def settings(self, settings: SolverSettings) -> SolverSettings:
        """`settings` with this domain and its nodes."""
        return replace(settings, grid=self.nx, grid_y=self.ny, domain_x=self.x, domain_y=self.y)

    def note(self, asked: SolverSettings) -> str:
        """What the lengthening did, for the result's solver description ('' if nothing)."""
        if self.doublings == 0:
            return ""
        capped = f" (capped at {TUNING.max_lengthened_nodes} nodes: a coarser spacing)" if self.capped else ""
        return (f"inlet lengthened by the solver to X in [{self.x[0]:g}, {self.x[1]:g}], Y in [{self.y[0]:g}, "
                f"{self.y[1]:g}] on {self.nx} x {self.ny} nodes at the spacing of {asked.grid} x {asked.nodes_y}"
                f"{capped} (predicted inlet gap ratio {self.predicted_gap_ratio:.0f}, "
                f"target {TUNING.inlet_gap_target:g})")


def venner_lubrecht_domain(scaling: Scaling) -> tuple[tuple[float, float], tuple[float, float]]:
    """[-3, 3]^2 shifted 1.5 against the entrainment direction (in Hertzian units): 4.5 upstream, 1.5 downstream.

    For entrainment along x this is Venner & Lubrecht's X in [-4.5, 1.5], Y in [-3, 3].
    """
    dx, dy = scaling.wedge_x, scaling.wedge_y
    norm = math.hypot(dx, dy)
    shift, half = TUNING.domain_upstream_shift, TUNING.domain_half_width
    cx, cy = -shift * dx / norm, -shift * dy / norm
    return (cx - half, cx + half), (cy - half, cy + half)


def inlet_exit(x: tuple[float, float], y: tuple[float, float], scaling: Scaling) -> tuple[str, float, float]:
    """Where the entrainment line through the centre leaves the domain upstream: the axis ("x" or "y") of the
    boundary it crosses and the exit point (X, Y) in Hertzian units. The line runs along (cos psi, kappa sin psi)
    in Hertzian units (scaling.wedge_x, wedge_y): X = -s wedge_x, Y = -s wedge_y upstream for s > 0."""
    exits = []
    for axis, bounds, component in (("x", x, scaling.wedge_x), ("y", y, scaling.wedge_y)):
        if component != 0.0:
            exits += [(-bound / component, axis) for bound in bounds if -bound / component > 0.0]
    s, axis = min(exits)
    return axis, -s * scaling.wedge_x, -s * scaling.wedge_y


def rigid_gap_ratio(x: tuple[float, float], y: tuple[float, float], scaling: Scaling, radius_x: float,
                    radius_y: float, h_c: float) -> float:
    """Rigid gap x^2/(2 R_x) + y^2/(2 R_y) where the entrainment line leaves the domain upstream, over h_c (radii
    and h_c in m): how far the inlet reaches, in central films."""
    _, exit_x, exit_y = inlet_exit(x, y, scaling)
    return ((exit_x * scaling.b) ** 2 / (2.0 * radius_x) + (exit_y * scaling.a) ** 2 / (2.0 * radius_y)) / h_c


def side_pressure_ratio(pressure: np.ndarray, x: np.ndarray, y: np.ndarray, scaling: Scaling) -> float:
    """The largest pressure on the nodes within SIDE_BAND of the domain's width from its sides (the boundaries along
    the entrainment, across the axis the inlet leaves by; at least the first interior row or column, the sides' own
    held at zero), over the largest pressure (pressure on the (ny, nx) nodes x, y in Hertzian units). An elastic
    film's pressure is confined to the Hertzian ellipse and its inlet; a light load's film spreads along the contact
    line up to the sides, whose zero pressure then cuts it short as a short inlet cuts its inflow."""
    axis, _, _ = inlet_exit((float(x[0]), float(x[-1])), (float(y[0]), float(y[-1])), scaling)
    nodes = y.size if axis == "x" else x.size
    band = max(1, math.floor(SIDE_BAND * (nodes - 1)))  # the nodes within the band's width, 1 at least
    near = np.zeros(nodes, dtype=bool)
    near[: band + 1] = near[nodes - 1 - band:] = True
    side = pressure[near, :] if axis == "x" else pressure[:, near]
    return float(side.max() / max(float(pressure.max()), 1e-300))


def predicted_central_film(scaling: Scaling) -> float:
    """Hamrock & Dowson's (1977) isothermal central film of the point, m."""
    s = scaling
    return hamrock_dowson_central(s.hamrock_u, s.hamrock_g, s.hamrock_w, s.ellipticity) * s.hertz.radius_x


def solution_domain(scaling: Scaling, settings: SolverSettings,
                    max_doublings: int = TUNING.max_inlet_doublings) -> Domain:
    """The domain the point is solved on: the settings' own if they give one, else Venner & Lubrecht's with its
    inlet lengthened (module docstring), at most `max_doublings` times."""
    if settings.domain_x is not None and settings.domain_y is not None:
        return Domain(settings.domain_x, settings.domain_y, settings.grid, settings.nodes_y, 0, math.nan)
    x, y = venner_lubrecht_domain(scaling)
    nx, ny, doublings, capped = settings.grid, settings.nodes_y, 0, False
    radii, h_c = (scaling.hertz.radius_x, scaling.hertz.radius_y), predicted_central_film(scaling)
    ratio = rigid_gap_ratio(x, y, scaling, *radii, h_c)
    while ratio < TUNING.inlet_gap_target and doublings < max_doublings:
        axis, _, _ = inlet_exit(x, y, scaling)
        if (nx if axis == "x" else ny) < TUNING.min_lengthened_nodes:
            break
        nodes = 2 * (nx if axis == "x" else ny) - 1
        capped = capped or nodes > TUNING.max_lengthened_nodes
        if axis == "x":
            x, nx = _lengthened(x, scaling.wedge_x), min(nodes, TUNING.max_lengthened_nodes)
        else:
            y, ny = _lengthened(y, scaling.wedge_y), min(nodes, TUNING.max_lengthened_nodes)
        doublings += 1
        ratio = rigid_gap_ratio(x, y, scaling, *radii, h_c)
    return Domain(x, y, nx, ny, doublings, ratio, capped)


def _lengthened(bounds: tuple[float, float], component: float) -> tuple[float, float]:
    """`bounds` twice as long, lengthened upstream (against the entrainment component along the axis)."""
    low, high = bounds
    length = high - low
    return (low - length, high) if component > 0.0 else (low, high + length)


# the truncated inlet's h_c error, 140-200 G^-3/2 percent (docs/accuracy.md, domain size): its coefficients as fractions
STARVED_FILM_ERROR = (1.4, 2.0)


def starved_inlet(gap_ratio: float) -> bool:
    """Whether a film solved over an inlet of gap ratio G (`inlet_gap_ratio`) is starved beyond what its figures' bounds
    stand for: G below TUNING.min_inlet_gap_ratio."""
    return gap_ratio < TUNING.min_inlet_gap_ratio


def inlet_note(name: str, gap_ratio: float, chosen: bool) -> str:
    """A warning for point `name` whose inlet reaches G central films ("" otherwise): below inlet_gap_target where the
    solver `chosen` the domain (it could not lengthen the inlet enough), below min_inlet_gap_ratio where the case gave
    it (a domain chosen short, as Venner & Lubrecht's, is the case's to choose until its figures lose their bounds):
    h_c starved by 140-200 G^-3/2 percent, and whether its figures are then unresolved (`starved_inlet`)."""
    if not gap_ratio < (TUNING.inlet_gap_target if chosen else TUNING.min_inlet_gap_ratio):
        return ""
    low, high = (100.0 * c * gap_ratio**-1.5 for c in STARVED_FILM_ERROR)
    amount = f"by about {low:.2g}-{high:.2g} %" if high < 100.0 else f"by {low:.0f} % or more"
    if starved_inlet(gap_ratio):
        starved = f"{amount}, so no figure is bounded"
    else:
        starved = f"{amount}, which its error bounds (grid and iteration) do not include"
    return (f"{name}: its inlet reaches {gap_ratio:.3g} central films (inlet_gap_ratio; target "
            f"{TUNING.inlet_gap_target:g}): the truncated inlet starves h_c {starved} (docs/accuracy.md, domain size)")


# the band of the domain's width next to each side read by `side_pressure_ratio`: the outer sixth of each half
SIDE_BAND = 1.0 / 12.0


def starved_sides(pressure_ratio: float) -> bool:
    """Whether a film whose pressure near its sides is `pressure_ratio` of its peak (`side_pressure_ratio`) is cut
    short by them beyond what its figures' bounds stand for: above TUNING.max_side_pressure."""
    return pressure_ratio > TUNING.max_side_pressure


def side_note(name: str, pressure_ratio: float) -> str:
    """A warning for point `name` whose sides starve its film (`starved_sides`; "" otherwise). The solver does not
    widen the domain: a film whose footprint reaches that far along a gear tooth depends on the flank's face width and
    its ends, which the local contact of two paraboloids does not hold; a plain contact's case may give a wider
    `solver.domain`."""
    if not starved_sides(pressure_ratio):
        return ""
    return (f"{name}: its pressure near the domain's sides is {100.0 * pressure_ratio:.3g} % of its peak "
            f"(side_pressure_ratio, above {100.0 * TUNING.max_side_pressure:g} %): the sides cut the film short, "
            f"thinning h_c by a few to tens of per cent (docs/accuracy.md, domain size: the sides), so no figure is "
            f"bounded")
