"""Whether a wide-envelope contact's film closes physically or on its grid (issue 47): the contact solved
isothermal Newtonian on each grid given, and per grid the finest level's film as it is, open or closed.

The contact (facegear_tehl/suites/wide_envelope.py) is solved with `thermal: off` and Newtonian rheology by one
attempt of the point solve (retry.ATTEMPTS, no retry, no refinement) on square grids over the solver's domain. Per
grid the script prints the outcome, the lowest film H_min = h_min R_x/b^2 (negative: closed) and where it lies
(Hertzian units X = x/b, Y = y/a), the central film H_c, the nodes with H <= 0 and the V-cycles' last pressure
change; then Hamrock & Dowson's (1977) and Chittenden, Dowson, Dunn & Taylor's (1985) films of the contact (the latter
with the groups on the radius along the entrainment, R_e) in the same units, and, from the last three grids, the
observed order of H_c and of H_min and their Richardson extrapolations (Roache 1998, "Verification and Validation in
Computational Science and Engineering", ch. 5): the film the grids converge to, open or closed. A lowest film that
moves between grids is not one quantity: the extrapolation is printed with where each grid puts it.

    python scripts/film_closure.py w08 [--grids 129,257,513] [--attempt 1]
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from dataclasses import dataclass, replace
import math
import sys

import numpy as np

from facegear_tehl.ehl.retry import ATTEMPTS
from facegear_tehl.ehl.scaling import Scaling
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.film_formulas import (
    chittenden_central,
    chittenden_minimum,
    chittenden_radii,
    hamrock_dowson_central,
    hamrock_dowson_minimum,
)
from facegear_tehl.suites.envelope import EnvelopeCase
from facegear_tehl.suites.wide_envelope import wide_envelope_contact


@dataclass(frozen=True)
class GridFilm:
    """The finest level's film of one solve (Hertzian units)."""

    nodes: int
    outcome: str
    h_min: float
    x_min: float
    y_min: float
    h_c: float
    closed_nodes: int
    message: str


def solved_film(case: EnvelopeCase, nodes: int, attempt: int) -> GridFilm:
    """`case` isothermal Newtonian on `nodes` x `nodes` by attempt `attempt` alone: its finest level's film."""
    solve = PointSolve(case.point(), case.lubricant(), case.settings(nodes, nodes), ATTEMPTS[attempt - 1].relaxation,
                       attempt=attempt)
    solution = solve.begin()
    level = solve.solver.levels[-1]
    film = level.film
    j, i = np.unravel_index(np.argmin(film), film.shape)
    centre = solve.solver.central_film(level)
    return GridFilm(nodes, solution.outcome.value, float(film.min()), float(level.x[i]), float(level.y[j]),
                    float(centre), int((film <= 0.0).sum()), solution.message)


def formula_films(case: EnvelopeCase, scaling: Scaling) -> dict[str, tuple[float, float]]:
    """(H_c, H_min) of Hamrock & Dowson (1977) and of Chittenden et al. (1985), in Hertzian units."""
    s, hertz = scaling, scaling.hertz
    to_h = hertz.radius_x / s.film_scale
    hamrock = (hamrock_dowson_central(s.hamrock_u, s.hamrock_g, s.hamrock_w, s.ellipticity) * to_h,
               hamrock_dowson_minimum(s.hamrock_u, s.hamrock_g, s.hamrock_w, s.ellipticity) * to_h)
    r_e, r_s = chittenden_radii(hertz.radius_x, hertz.radius_y, math.radians(case.skew))
    ratio = hertz.radius_x / r_e  # U ~ 1/R, W ~ 1/R^2 (film_formulas: groups on the radius R)
    u, w = s.hamrock_u * ratio, s.hamrock_w * ratio**2
    to_h = r_e / s.film_scale
    chittenden = (chittenden_central(u, s.hamrock_g, w, r_s / r_e) * to_h,
                  chittenden_minimum(u, s.hamrock_g, w, r_s / r_e) * to_h)
    return {"Hamrock & Dowson (1977)": hamrock, "Chittenden et al. (1985)": chittenden}


def extrapolated(values: Sequence[float]) -> tuple[float, float]:
    """The observed order p of three values on grids each twice as fine, and the Richardson extrapolation of the last
    two with it: (p, value); nan where the differences do not fall."""
    first, second = values[-2] - values[-3], values[-1] - values[-2]
    if second == 0.0 or first / second <= 1.0:
        return math.nan, math.nan
    order = math.log2(first / second)
    return order, values[-1] + second / (2.0**order - 1.0)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", type=wide_envelope_contact, help="a wide-envelope contact's name or its prefix (w08)")
    parser.add_argument("--grids", default="129,257,513", help="comma-separated nodes per axis, each twice as fine")
    parser.add_argument("--attempt", type=int, default=1, help="the relaxation of this attempt (retry.ATTEMPTS)")
    args = parser.parse_args(argv)
    case = args.case
    case = replace(case, thermal=False)
    films = []
    for nodes in (int(n) for n in args.grids.split(",")):
        film = solved_film(case, nodes, args.attempt)
        films.append(film)
        print(f"{nodes} x {nodes}: {film.outcome}, H_min {film.h_min:.5f} at X {film.x_min:.3f} Y {film.y_min:.3f}, "
              f"H_c {film.h_c:.5f}, {film.closed_nodes} nodes closed; {film.message.split('; ')[-1]}", flush=True)
    solve = PointSolve(case.point(), case.lubricant(), case.settings(films[0].nodes, films[0].nodes))
    for name, (h_c, h_min) in formula_films(case, solve.scaling).items():
        print(f"{name}: H_c {h_c:.5f}, H_min {h_min:.5f}")
    print(f"film scale R_x/b^2 = {solve.scaling.film_scale:.4g} m per unit H")
    if len(films) >= 3:
        for key in ("h_c", "h_min"):
            order, value = extrapolated([getattr(f, key) for f in films])
            print(f"{key}: observed order {order:.2f}, extrapolated {value:.5f} (the last three grids)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
