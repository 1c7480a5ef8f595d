"""Whether a finer grid can open a film that closed: run.solve_refining asks before it refines a closed film.

A smooth film is open at any load (Hamrock & Dowson 1977, solve.FILM_CLOSED_MESSAGE): an iterate whose film closes is
a grid that does not resolve the film, or an iteration that failed. How thin a film a grid can hold follows from the
deflection it discretises. Across a Hertzian contact of half-width b the pressure p_h sqrt(1 - X^2) (X = x/b) makes
the surfaces parallel; past its edge the half-plane's surface slope leaves the gap rising as dh/dx = sqrt(x^2 - b^2)/R_x
(the principal value of the Hertz pressure's deflection integral, Johnson 1985, Contact Mechanics, ch. 2 and 4), so in
Venner & Lubrecht's H = h R_x/b^2, with xi = X - 1 past the edge,

    H(xi) = integral from 1 to 1 + xi of sqrt(T^2 - 1) dT = (2 sqrt(2)/3) xi^(3/2) (1 + O(xi)).

A film H_min therefore lies in an outlet constriction about w = (3 H_min/(2 sqrt 2))^(2/3) semi-axes b wide (the side
lobes' constriction alike: docs/envelope.md), which a grid of X spacing dX holds on w/dX + 1 nodes. Where the film
Hamrock & Dowson (1977) predict spans fewer than TUNING.closure_nodes nodes even on the finest grid along x that the
refinement may reach (the largest refined grid over the point's domain), no grid within the caps resolves it: the
refinement of a closed film stops there (`unresolvable`). The formula is the only film available for a film that
closed; it is an estimate (10-30 % from full solutions, film_formulas.py), and a contact near TUNING.closure_nodes
may go either way (docs/tuning.md). The rule reads the X spacing and the outlet past the Hertzian edge along x: it
applies to entrainment along x and a film closed near the centre line (`closed_on_the_centre_line`); a film closed in
a side lobe is refined in its rows (retry.RetryPolicy.finer_settings), which the rule does not read.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.domain import solution_domain
from facegear_tehl.ehl.retry import in_side_lobe
from facegear_tehl.ehl.scaling import Scaling, scaling_for
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.film_formulas import hamrock_dowson_minimum
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import PointSolution

EDGE_GAP = 2.0 * math.sqrt(2.0) / 3.0  # H = EDGE_GAP xi^(3/2) just past the Hertzian edge (the module's derivation)


def predicted_minimum_film(point: ContactPoint, lubricant: Lubricant) -> float:
    """Hamrock & Dowson's (1977) isothermal minimum film of the point, m (an estimate, not a solved film)."""
    s = scaling_for(point, lubricant)
    return hamrock_dowson_minimum(s.hamrock_u, s.hamrock_g, s.hamrock_w, s.ellipticity) * s.hertz.radius_x


def constriction_width(film: float) -> float:
    """Width (semi-axes b) of the constriction past the Hertzian edge in which a film H (in h R_x/b^2) lies."""
    return (max(film, 0.0) / EDGE_GAP) ** (2.0 / 3.0)


def closed_on_the_centre_line(solution: PointSolution, point: ContactPoint, lubricant: Lubricant) -> bool:
    """The film closed within side_lobe semi-axes a of the centre line, the entrainment leaving the domain along x:
    the outlet constriction the rule reads (module docstring)."""
    scaling = scaling_for(point, lubricant)
    return abs(scaling.wedge_x) >= abs(scaling.wedge_y) and not in_side_lobe(solution)


def finest_spacing(scaling: Scaling, settings: SolverSettings, largest: int) -> tuple[float, int]:
    """The X spacing (semi-axes b) of the finest grid along x the refinement may reach from `settings` (x doubled as
    long as the point's domain keeps at most `largest` nodes along x, ehl.domain), and that grid's nodes along x."""
    grid, domain = settings.grid, solution_domain(scaling, settings)
    while True:
        finer = solution_domain(scaling, replace(settings, grid=2 * grid - 1))
        if finer.nx > largest or finer.nx <= domain.nx:  # past the cap, or the lengthened axis no longer grows
            break
        grid, domain = 2 * grid - 1, finer
    return (domain.x[1] - domain.x[0]) / (domain.nx - 1), domain.nx


@dataclass(frozen=True)
class Unresolvable:
    """A film no grid within the caps resolves: Hamrock & Dowson's h_min (m), the finest grid's nodes along x and X
    spacing, and the nodes the constriction of that film spans there."""

    film: float
    nx: int
    spacing: float
    nodes: float

    def words(self) -> str:
        return (f"Hamrock & Dowson's (1977) minimum film, {1e9 * self.film:.3g} nm (the formula's estimate), would "
                f"span {self.nodes:.1f} nodes across its outlet constriction on the finest grid the solver may refine "
                f"to ({self.nx} nodes along x, spacing {self.spacing:.3g} b), fewer than the "
                f"{TUNING.closure_nodes} a film needs to be resolved: no grid within the caps opens it")


def constriction_nodes(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
                       largest: int) -> Unresolvable:
    """Hamrock & Dowson's film of the point, the finest grid along x within `largest` nodes and its spacing, and the
    nodes that film's outlet constriction spans there (module docstring)."""
    scaling = scaling_for(point, lubricant)
    film = predicted_minimum_film(point, lubricant)
    spacing, nx = finest_spacing(scaling, settings, largest)
    return Unresolvable(film, nx, spacing, constriction_width(film / scaling.film_scale) / spacing + 1.0)


def unresolvable(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
                 largest: int) -> Unresolvable | None:
    """The evidence that no grid up to `largest` nodes resolves the point's film (module docstring), or None."""
    found = constriction_nodes(point, lubricant, settings, largest)
    if not math.isfinite(found.nodes) or found.nodes >= TUNING.closure_nodes:
        return None
    return found
