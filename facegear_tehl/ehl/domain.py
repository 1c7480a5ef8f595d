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
for is kept, and the grid stays 2^n + 1; from MIN_LENGTHENED_NODES up), until the inlet gap ratio predicted with
Hamrock & Dowson's (1977) central film reaches INLET_GAP_TARGET (at most MAX_INLET_DOUBLINGS times). The isothermal
formula over-predicts a heated film, so the ratio of the solved film is larger still (a conservative choice).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math

from facegear_tehl.ehl.scaling import Scaling
from facegear_tehl.film_formulas import hamrock_dowson_central
from facegear_tehl.settings import SolverSettings

DOMAIN_HALF_WIDTH = 3.0  # default domain: a square of +-3 semi-axes (Venner & Lubrecht 2000) ...
DOMAIN_UPSTREAM_SHIFT = 1.5  # ... shifted 1.5 semi-axes upstream: 4.5 upstream, 1.5 downstream of the centre
# Inlet gap ratio the lengthened domain must reach: 140-200 G^(-3/2) percent (module docstring) is 0.55-0.8 % of h_c
# at G = 40 for an isothermal film and less for a heated one (the face gear S5, thermal: 0.34 % at its solved
# G = 50); the next doubling (G = 160) would cost twice the nodes again for another 0.4 %.
INLET_GAP_TARGET = 40.0
# Smallest node count along an axis from which it is lengthened: trial grids are left as they are, their own error
# is as large as the inlet's (S1 of the face gear case: h_c -1.5 % on 65 x 17, -5.8 % on 33 x 17 against the
# extrapolated value, docs/accuracy.md), and on 129 x 17 (65 x 17 lengthened) S2 ends on a period-2 load flicker.
MIN_LENGTHENED_NODES = 129
# Doublings at most: a light load (Moes M ~ 3-20, a circle or an a/b = 5 ellipse at 0.3 GPa, 2 m/s) needs two (an inlet
# of 22.5 semi-axes, 4x the nodes) to reach the target; a third has not been needed in the envelope suite.
MAX_INLET_DOUBLINGS = 2
# Doublings of a retry after a solve ran away: an a/b = 100 ellipse at 0.3 GPa, 30 m/s, eta_0 = 0.1 Pa s (a 10 µm
# film, G = 19 even at 22.5 b) runs away in the full-multigrid start on 22.5 b from every coarsest grid and converges
# on 10.5 b (h_c 9.80 µm; 4.76 µm on 4.5 b).
RETRY_INLET_DOUBLINGS = 1
# Largest node count of a lengthened axis: beyond it the lengthened domain keeps this many nodes (a coarser spacing
# than asked, said in the note), so that its length never depends on the grid (tehl sweep, solver-chosen grids).
MAX_LENGTHENED_NODES = 2049


@dataclass(frozen=True)
class Domain:
    """The domain of one solve (Hertzian units) and its finest grid's nodes."""

    x: tuple[float, float]
    y: tuple[float, float]
    nx: int
    ny: int
    doublings: int  # times the inlet was lengthened (0: the domain of the settings, or the default one)
    predicted_gap_ratio: float  # inlet gap ratio with the Hamrock & Dowson central film (nan: domain given)
    capped: bool = False  # the lengthened axis kept MAX_LENGTHENED_NODES nodes, fewer than the spacing asked needs

    def settings(self, settings: SolverSettings) -> SolverSettings:
        """`settings` with this domain and its nodes."""
        return replace(settings, grid=self.nx, grid_y=self.ny, domain_x=self.x, domain_y=self.y)

    def note(self, asked: SolverSettings) -> str:
        """What the lengthening did, for the result's solver description ('' if nothing)."""
        if self.doublings == 0:
            return ""
        capped = f" (capped at {MAX_LENGTHENED_NODES} nodes: a coarser spacing)" if self.capped else ""
        return (f"inlet lengthened by the solver to X in [{self.x[0]:g}, {self.x[1]:g}], Y in [{self.y[0]:g}, "
                f"{self.y[1]:g}] on {self.nx} x {self.ny} nodes at the spacing of {asked.grid} x {asked.nodes_y}"
                f"{capped} (predicted inlet gap ratio {self.predicted_gap_ratio:.0f}, target {INLET_GAP_TARGET:g})")


def venner_lubrecht_domain(scaling: Scaling) -> tuple[tuple[float, float], tuple[float, float]]:
    """[-3, 3]^2 shifted 1.5 against the entrainment direction (in Hertzian units): 4.5 upstream, 1.5 downstream.

    For entrainment along x this is Venner & Lubrecht's X in [-4.5, 1.5], Y in [-3, 3].
    """
    dx, dy = scaling.wedge_x, scaling.wedge_y
    norm = math.hypot(dx, dy)
    cx, cy = -DOMAIN_UPSTREAM_SHIFT * dx / norm, -DOMAIN_UPSTREAM_SHIFT * dy / norm
    return (cx - DOMAIN_HALF_WIDTH, cx + DOMAIN_HALF_WIDTH), (cy - DOMAIN_HALF_WIDTH, cy + DOMAIN_HALF_WIDTH)


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


def predicted_central_film(scaling: Scaling) -> float:
    """Hamrock & Dowson's (1977) isothermal central film of the point, m."""
    s = scaling
    return hamrock_dowson_central(s.hamrock_u, s.hamrock_g, s.hamrock_w, s.ellipticity) * s.hertz.radius_x


def solution_domain(scaling: Scaling, settings: SolverSettings, max_doublings: int = MAX_INLET_DOUBLINGS) -> Domain:
    """The domain the point is solved on: the settings' own if they give one, else Venner & Lubrecht's with its
    inlet lengthened (module docstring), at most `max_doublings` times."""
    if settings.domain_x is not None and settings.domain_y is not None:
        return Domain(settings.domain_x, settings.domain_y, settings.grid, settings.nodes_y, 0, math.nan)
    x, y = venner_lubrecht_domain(scaling)
    nx, ny, doublings, capped = settings.grid, settings.nodes_y, 0, False
    radii, h_c = (scaling.hertz.radius_x, scaling.hertz.radius_y), predicted_central_film(scaling)
    ratio = rigid_gap_ratio(x, y, scaling, *radii, h_c)
    while ratio < INLET_GAP_TARGET and doublings < max_doublings:
        axis, _, _ = inlet_exit(x, y, scaling)
        if (nx if axis == "x" else ny) < MIN_LENGTHENED_NODES:
            break
        nodes = 2 * (nx if axis == "x" else ny) - 1
        capped = capped or nodes > MAX_LENGTHENED_NODES
        if axis == "x":
            x, nx = _lengthened(x, scaling.wedge_x), min(nodes, MAX_LENGTHENED_NODES)
        else:
            y, ny = _lengthened(y, scaling.wedge_y), min(nodes, MAX_LENGTHENED_NODES)
        doublings += 1
        ratio = rigid_gap_ratio(x, y, scaling, *radii, h_c)
    return Domain(x, y, nx, ny, doublings, ratio, capped)


def _lengthened(bounds: tuple[float, float], component: float) -> tuple[float, float]:
    """`bounds` twice as long, lengthened upstream (against the entrainment component along the axis)."""
    low, high = bounds
    length = high - low
    return (low - length, high) if component > 0.0 else (low, high + length)
