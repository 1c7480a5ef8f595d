"""The lubrication regime of each solved point from its film parameter (docs/verdict.md, "Film regime").

  lambda_min = h_min / sigma,  lambda_c = h_c / sigma,  sigma = sqrt(R_q1^2 + R_q2^2)   (Tallian 1967)

with R_q the RMS roughness of each flank (materials.body_i.roughness; an arithmetic-mean R_a converts as
R_q ~ 1.25 R_a for a Gaussian surface). Regimes by lambda_min (Hamrock, Schmid & Jacobson 2004, Fundamentals of
Fluid Film Lubrication, 2nd ed., ch. 1; Tallian 1967):

  full film   lambda >= 3       asperities separated: the smooth-surface TEHL model applies
  mixed       1 <= lambda < 3   the film carries most of the load, asperity contacts occur
  boundary    lambda < 1        asperities carry a large share of the load: outside the smooth-film model
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from enum import Enum

from facegear_tehl.solution import Field, PointSolution

FULL_FILM_LAMBDA = 3.0  # Hamrock, Schmid & Jacobson (2004): full-film EHL from lambda = 3
BOUNDARY_LAMBDA = 1.0  # below it boundary lubrication (Hamrock, Schmid & Jacobson 2004; Tallian 1967)


class Regime(Enum):
    """The lubrication regime of a contact by its film parameter."""

    FULL_FILM = "full film"
    MIXED = "mixed"
    BOUNDARY = "boundary"


def regime(film_parameter: float) -> Regime:
    """The regime of lambda = h_min/sigma (FULL_FILM_LAMBDA and BOUNDARY_LAMBDA)."""
    if film_parameter >= FULL_FILM_LAMBDA:
        return Regime.FULL_FILM
    if film_parameter >= BOUNDARY_LAMBDA:
        return Regime.MIXED
    return Regime.BOUNDARY


def with_central_film_parameter(solution: PointSolution, sigma: float) -> PointSolution:
    """The solution with `film_parameter_central` = h_c/sigma beside its `film_parameter` (h_min/sigma), when it
    has a film and sigma > 0 (m)."""
    if sigma <= 0.0 or "h_c" not in solution.scalars:
        return solution
    value = (solution.scalar("h_c") / sigma, "1")
    return replace(solution, scalars={**solution.scalars, "film_parameter_central": value})


def central_column(cycle: Mapping[str, Field], sigma: float) -> dict[str, Field]:
    """The /cycle columns with `film_parameter_central` = h_c/sigma added (when it has h_c and sigma > 0)."""
    if sigma <= 0.0 or "h_c" not in cycle:
        return dict(cycle)
    return {**cycle, "film_parameter_central": Field(cycle["h_c"].values / sigma, "1",
                                                     "film parameter at the centre lambda_c = h_c / sqrt(R_q1^2 + "
                                                     "R_q2^2)")}


def regime_warning(film_parameters: Mapping[str, float]) -> str | None:
    """One warning naming the points (name -> lambda_min) below BOUNDARY_LAMBDA, or None if there are none."""
    low = {name: value for name, value in film_parameters.items() if value < BOUNDARY_LAMBDA}
    if not low:
        return None
    listed = ", ".join(f"{name} {value:.2f}" for name, value in low.items())
    return (f"film parameter lambda = h_min/sigma below {BOUNDARY_LAMBDA:g} at {listed}: boundary lubrication, the "
            "asperities carry part of the load; the smooth-film results there (film, pressure, friction, "
            "temperature) are outside the model (docs/verdict.md)")
