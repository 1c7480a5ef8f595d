"""An isothermal Ree-Eyring film under Barus's exponential viscosity: the outer loop's first film-state update, made at
the Newtonian pressure of the full-multigrid start, wants eta*/eta many e-folds below its fixed point, and every listed
attempt runs away in the V-cycles after it. The retry policy's rescue (retry.RESCUE) moves ln(eta*/eta) by a bounded
step per update (Relaxation.film_step, docs/tuning.md), on a path only such a failing solve takes."""

from __future__ import annotations

from dataclasses import replace
import math
from pathlib import Path

import numpy as np
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.ehl import coupled
from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.film_state import FilmState
from facegear_tehl.ehl.retry import ATTEMPTS, DAMPED, POLICY, RESCUE
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.film_formulas import hamrock_dowson_central, nijenbanning_central
from facegear_tehl.points import contact_analysis
from facegear_tehl.record import SolveRecord, Stage, StageRecord
from facegear_tehl.solution import Outcome, PointSolution

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


def _failed(attempt: int, outer: int, moes_m: float = 856.0, thermal: str = "off",
            outcome: Outcome = Outcome.DIVERGED) -> PointSolution:
    """A solve of `attempt` whose finest grid ended `outcome` after `outer` updates of its film state."""
    stages = (StageRecord(Stage.START, 513, 65, 0, 0, Outcome.CONVERGED, 0.1),
              StageRecord(Stage.FINEST, 513, 65, 1, outer, outcome, 0.1))
    return PointSolution("S1", outcome, "", {"attempts": (float(attempt), "1"), "moes_m": (moes_m, "1")}, {}, {}, {},
                         {"thermal": thermal}, record=SolveRecord(stages=stages, attempt=attempt, iteration=outcome))


@pytest.mark.parametrize(("solution", "expected"), [
    (_failed(1, 1), 2),  # the listed attempts first, as before
    (_failed(2, 1), 3),
    (_failed(3, 1), POLICY.rescue_attempt),  # the damped attempt ran away at its first update: the rescue
    (_failed(3, 2), POLICY.rescue_attempt),  # ... or at its second
    (_failed(3, 0), None),  # before its first: reported as before
    (_failed(3, 3), None),  # ... as after a later one
    (_failed(3, 1, thermal="full"), None),  # a thermal loop: as before
    (_failed(3, 1, moes_m=1e4), 4),  # a heavy point's continued start comes first ...
    (_failed(4, 1, moes_m=1e4), None),  # ... and is its last attempt
    (_failed(3, 1, outcome=Outcome.NOT_CONVERGED), None),
    (_failed(POLICY.rescue_attempt, 1), None),  # the rescue is the last
])
def test_the_rescue_follows_only_a_damped_attempt_that_ran_away_at_its_first_film_state_updates(solution, expected):
    assert POLICY.next_attempt(solution) == expected


def test_the_rescue_is_the_damped_relaxation_with_a_bounded_film_step_and_is_not_carried():
    assert all(math.isinf(attempt.relaxation.film_step) for attempt in ATTEMPTS)  # every listed attempt unbounded
    assert RESCUE.relaxation == replace(DAMPED, film_step=TUNING.rescue_film_step)
    assert not RESCUE.load_continuation
    assert POLICY.numbered(POLICY.rescue_attempt) is RESCUE and POLICY.numbered(3) is ATTEMPTS[2]
    assert POLICY.attempt(POLICY.rescue_attempt, 1e-3) is RESCUE
    assert [POLICY.carries(a) for a in range(1, POLICY.rescue_attempt + 1)] == [True, True, True, False, False]
    assert RESCUE.name == "Venner's switch, damped, the film state's step bounded"


def test_barus_ree_eyring_s1_converges_between_the_published_central_films():
    """S1 of cases/facegear_110.yaml (p_h 556 MPa, a/b = 58) with Barus's viscosity, isothermal Ree-Eyring, on 257 x 17
    (513 x 17 solved): every listed attempt runs away at its first film-state updates (the first takes ln(eta*/eta)
    to -9 against -5.5 at the fixed point, and the V-cycles after them overflow exp(alpha p)); the rescue converges,
    with an open film whose central value lies between Hamrock & Dowson's (1977) and Nijenbanning, Venner & Moes's
    (1994) central films (1.413 um between 1.208 and 1.633 um)."""
    case = load_case(ROOT / "cases" / "facegear_110.yaml")
    lubricant = replace(case.lubricant, viscosity_model="barus")
    point = next(p for p in contact_analysis(case).points if p.name == "S1")
    solution = solve_point(point, lubricant, replace(case.solver, grid=257, grid_y=17, thermal="off"))
    assert solution.converged, solution.message
    assert solution.record.attempt == POLICY.rescue_attempt
    h_c = solution.scalar("h_c")
    assert 0.0 < solution.scalar("h_min") < h_c
    sc = scaling_for(point, lubricant)
    hamrock_dowson = hamrock_dowson_central(sc.hamrock_u, sc.hamrock_g, sc.hamrock_w, sc.ellipticity) * point.radius_x
    nvm = (nijenbanning_central(sc.moes_m, sc.moes_l, point.radius_x / point.radius_y) * point.radius_x
           * math.sqrt(2.0 * sc.hamrock_u))
    assert hamrock_dowson < h_c < nvm
