"""A film that closes on its grid ends the coupled loop (coupled.CoupledLoop): no film state is evaluated on a closed
film, whose energy equation is undefined (no thickness to shear, conduct across or carry heat in).

The contact is w34 of the wide envelope (a/b 1.01, 1.31 GPa, 0.69 m/s, SRR 0.72, entrainment skewed 44.6 deg, thermal
Ree-Eyring). On 129 x 65 its pressure iterate closes over a band along the skewed side of the contact (H down to
-0.011 against H_c = 0.007), as its isothermal solve does on that grid: the smooth-film equations have an open film
at any load (Hamrock & Dowson 1977, H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k)) > 0), so the grid does not
resolve it. Evaluated there, the film temperatures moved by the 50 K cap per update from the second update on, above
and below the inlet temperature, until they were not finite, on every attempt (docs/envelope.md)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from facegear_tehl.ehl import coupled
from facegear_tehl.ehl.convergence import History
from facegear_tehl.ehl.retry import POLICY
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.ehl.thermal import FilmThermalModel
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.record import Reason
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import CONVERGED, Outcome, Status
from facegear_tehl.suites.wide_envelope import wide_cases


def test_a_film_closed_on_its_grid_is_reported_closed_without_a_film_state_evaluated_on_it(monkeypatch):
    case = next(c for c in wide_cases() if c.name.startswith("w34_"))
    films = []
    update = FilmThermalModel.update

    def watched(self, pressure, film, temperature, *args, **kwargs):
        films.append(float(film.min()))
        return update(self, pressure, film, temperature, *args, **kwargs)

    monkeypatch.setattr(FilmThermalModel, "update", watched)
    solution = solve_point(case.point(), case.lubricant(), case.settings(129, 65))
    assert solution.outcome is Outcome.FILM_CLOSED, solution.message
    assert "the film closes on the 129 x 65 grid" in solution.message
    assert "h_min" not in solution.scalars and not solution.fields  # a closed film is never a result
    assert all(h > 0.0 for h in films), films  # the energy equation only ever saw an open film
    # the first attempt's closed film goes to a finer grid: no relaxation is tried on a grid that does not resolve it
    assert POLICY.next_attempt(solution) is None and POLICY.unresolved(solution)
    reasons = [r.reason for r in solution.record.retries]
    assert Reason.RAN_AWAY not in reasons and Reason.COARSE_STAGE_RAN_AWAY not in reasons, reasons


class _Pressure:
    """A pressure iteration whose film is closed until cycled, when it becomes `cycled_film`."""

    settings = SolverSettings()

    def __init__(self, cycled_film: np.ndarray):
        self.film, self.cycled_film, self.cycles = np.array([[-1e-3, 1.0]]), cycled_film, 0

    def settled_pressure(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        return np.ones_like(self.film), self.film

    def cycle(self, index: int, max_cycles: int) -> Status:
        self.cycles += 1
        self.film = self.cycled_film
        return CONVERGED


def _loop(pressure: _Pressure) -> coupled.CoupledLoop:
    target = SimpleNamespace(index=0, model=SimpleNamespace(solve_energy=True))
    return coupled.CoupledLoop(target, pressure, History(cycles=2), 10, 313.15)


def test_a_closure_the_pressure_cycles_open_on_the_frozen_state_goes_on():
    """A transient closure of the iterate that cycling the pressure opens does not end the loop."""
    pressure = _Pressure(np.array([[1e-3, 1.0]]))
    assert _loop(pressure)._closed_film(0) is None and pressure.cycles == 1


def test_a_closure_that_stays_on_the_converged_frozen_state_ends_the_loop_closed():
    pressure = _Pressure(np.array([[-1e-3, 1.0]]))
    closed = _loop(pressure)._closed_film(3)
    assert closed.outcome is Outcome.FILM_CLOSED and "before outer iteration 4" in closed.message
    assert pressure.cycles == 1


def test_an_open_film_is_not_cycled():
    pressure = _Pressure(np.array([[1e-3, 1.0]]))
    pressure.film = np.array([[1e-6, 1.0]])
    assert _loop(pressure)._closed_film(0) is None and pressure.cycles == 0


@pytest.mark.parametrize(("attempt", "closed", "expected"), [
    (1, False, False), (TUNING.damped_attempt, False, True), (1, True, True)])
def test_a_coarse_stage_whose_film_closed_couples_on_the_finest_grid_at_once(attempt, closed, expected):
    assert POLICY.couples_on_finest(attempt, closed) is expected
