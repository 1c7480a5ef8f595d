"""An isothermal Ree-Eyring film under Barus's exponential viscosity: the outer loop's first film-state update, made at
the Newtonian pressure of the full-multigrid start, wants eta*/eta orders of magnitude below its fixed point, and the
damped attempt moves ln(eta*/eta) by a bounded step per update (Relaxation.film_step, docs/tuning.md)."""

from dataclasses import replace
import math
from pathlib import Path

import numpy as np
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.ehl import coupled
from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.film_state import FilmState
from facegear_tehl.ehl.retry import DAMPED, POLICY
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.film_formulas import hamrock_dowson_central, nijenbanning_central
from facegear_tehl.points import contact_analysis

ROOT = Path(__file__).resolve().parents[1]


def _update(factor: np.ndarray) -> FilmState:
    """An isothermal film state whose eta*/eta is `factor`."""
    ones = np.ones(factor.shape)
    return FilmState(temperature=313.15 * ones, viscosity_factor=factor, dissipation=ones, velocity_x=None,
                     velocity_y=None, stress_1=ones[:2], stress_2=ones[:2], heat_flux_1=None, heat_flux_2=None,
                     compression=None, change=0.0)


@pytest.mark.parametrize("rise", [None, 10.0])  # the isothermal Ree-Eyring loop, the thermal loop
def test_a_bounded_film_step_limits_the_change_of_ln_eta_star(rise):
    """An update 10 e-folds below a Newtonian film (S1 of the face gear case under Barus: 11.4 at the first update)
    moves ln(eta*/eta) by the relaxed step unbounded and by at most film_step bounded."""
    shape = (3, 4, 5)
    temperature, factor = np.full(shape, 313.15), np.ones(shape)
    update = _update(np.full(shape, math.exp(-10.0)))
    relaxation = TUNING.eyring_relaxation if rise is None else TUNING.viscosity_relaxation
    free = coupled.next_film_state(Anderson(3), temperature, factor, update, 1.0, rise)[1]
    assert np.log(free) == pytest.approx(np.full(shape, -10.0 * relaxation))
    bounded = coupled.next_film_state(Anderson(3), temperature, factor, update, 1.0, rise, 2.0)[1]
    assert np.log(bounded) == pytest.approx(np.full(shape, -2.0))


def test_only_the_damped_attempts_bound_the_film_step():
    """The first two attempts are as they were (every point that converges there unchanged); the damped ones bound."""
    steps = [attempt.relaxation.film_step for attempt in POLICY.attempts]
    assert steps[:TUNING.damped_attempt - 1] == [math.inf] * (TUNING.damped_attempt - 1)
    assert steps[TUNING.damped_attempt - 1:] == [TUNING.damped_film_step] * (len(steps) - TUNING.damped_attempt + 1)
    assert DAMPED.film_step == TUNING.damped_film_step


def test_barus_ree_eyring_s1_converges_between_the_published_central_films():
    """S1 of cases/facegear_110.yaml (p_h 556 MPa, a/b = 58) with Barus's viscosity, isothermal Ree-Eyring, on 257 x 17
    (513 x 17 solved): every attempt ran away before the bound (the first update took ln(eta*/eta) to -9 against -5.5
    at the fixed point, and the pressure's V-cycle overflowed exp(alpha p) on the coarse grids). It converges, with an
    open film whose central value lies between Hamrock & Dowson's (1977) and Nijenbanning, Venner & Moes's (1994)
    central films (measured 1.413 um between 1.208 and 1.633 um; the Newtonian film under Barus on 513 x 33 is
    1.405 um: the inlet that sets h_c is Newtonian)."""
    case = load_case(ROOT / "cases" / "facegear_110.yaml")
    lubricant = replace(case.lubricant, viscosity_model="barus")
    point = next(p for p in contact_analysis(case).points if p.name == "S1")
    solution = solve_point(point, lubricant, replace(case.solver, grid=257, grid_y=17, thermal="off"))
    assert solution.converged, solution.message
    h_c = solution.scalar("h_c")
    assert 0.0 < solution.scalar("h_min") < h_c
    sc = scaling_for(point, lubricant)
    hamrock_dowson = hamrock_dowson_central(sc.hamrock_u, sc.hamrock_g, sc.hamrock_w, sc.ellipticity) * point.radius_x
    nvm = (nijenbanning_central(sc.moes_m, sc.moes_l, point.radius_x / point.radius_y) * point.radius_x
           * math.sqrt(2.0 * sc.hamrock_u))
    assert hamrock_dowson < h_c < nvm
