"""The pressure iteration's judge on a frozen film state (pressure.PressureIteration): the algebraic floor is no
floor while the call's central film still drifts one way (its fixed point lies further on).

The stand-in multigrid solver below plays a prescribed sequence: its pressure changes per cycle by `changes[k]` and
its central film after cycle k is `films[k]`, with the load balanced, so that what the judge decides is all there is
to see."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from facegear_tehl.ehl.convergence import History
from facegear_tehl.ehl.multigrid import Iterate
from facegear_tehl.ehl.pressure import PressureIteration
from facegear_tehl.ehl.relaxation import Relaxation
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.settings import SolverSettings

SETTINGS = SolverSettings()


class _Solver:
    """A multigrid solver whose cycle k changes the pressure by changes[k] and leaves the central film films[k]."""

    def __init__(self, changes: np.ndarray, films: np.ndarray, relaxation: Relaxation = Relaxation()):
        self.changes, self.films, self.k = changes, films, 0
        self.relaxation, self.truncated, self.h0 = relaxation, False, 0.0
        self.problem = SimpleNamespace(load_integral=1.0)
        self.levels = [SimpleNamespace(pressure=np.ones(4), film=np.ones(4), eps=np.ones(4), nx=257)]

    def cycle(self, index: int) -> None:
        self.k += 1

    def pressure_change(self, level, previous) -> float:
        return float(self.changes[min(self.k, self.changes.size - 1)])

    def force_error(self, level) -> float:
        return 0.0

    def residual(self, level) -> np.ndarray:
        return np.zeros(4)

    def central_film(self, level) -> float:
        return float(self.films[min(self.k, self.films.size - 1)])

    def snapshot(self, index: int) -> Iterate:
        return Iterate(self.levels[index].pressure.copy(), self.h0)

    def restore(self, index: int, iterate: Iterate) -> None:
        self.levels[index].pressure = iterate.pressure


def _cycled(films: np.ndarray, change: float | np.ndarray):
    """The stand-in cycled to its tolerance or floor at most max_cycles times (`change`: per cycle, or constant)."""
    solver = _Solver(np.broadcast_to(change, films.shape), films)
    iteration = PressureIteration(solver, SETTINGS, History(cycles=0))
    status = iteration.cycle(0, SETTINGS.max_cycles)
    return status, solver.k, iteration.history


def test_a_drifting_film_is_cycled_on_to_its_fixed_point_not_accepted_at_the_floor():
    """The pressure change flickers below floor_band times the tolerance (the algebraic floor) while h_c still moves
    one way by 3 % per cycle, then settles at h*: the iteration goes on to h* (accepted once the drift is over), not
    at the fifth cycle with h_c 30 % off."""
    settle = 20
    k = np.arange(SETTINGS.max_cycles + 1)
    drift = 0.3 * 0.97 ** k * (k < settle)
    films = 2.0e-7 * (1.0 + drift)
    status, cycles, history = _cycled(films, 0.5 * TUNING.floor_band * SETTINGS.tolerance)
    assert status.converged and history.floor == pytest.approx(0.5 * TUNING.floor_band * SETTINGS.tolerance)
    assert settle < cycles < SETTINGS.max_cycles
    assert history.films[-1][1] == pytest.approx(2.0e-7)


def test_a_film_still_drifting_at_the_cap_ends_at_the_floor_for_the_bound_to_flag():
    """A film that drifts through the whole call ends at the cap on its floor (error_bounds.cycle_error then
    reports it unresolved), not earlier."""
    films = 2.0e-7 * (1.0 + 0.3 * 0.97 ** np.arange(SETTINGS.max_cycles + 1))
    status, cycles, _ = _cycled(films, 0.5 * TUNING.floor_band * SETTINGS.tolerance)
    assert status.converged and cycles == SETTINGS.max_cycles


def test_a_tolerance_met_while_the_film_drifts_is_no_stop():
    """The pressure change falls below the tolerance (at the eighth cycle, the load balanced) while h_c still rises
    3 % per cycle: the iteration goes on until the drift is over, not at the eighth cycle."""
    settle = 15
    k = np.arange(SETTINGS.max_cycles + 1)
    films = 2.0e-7 * (1.0 + 0.03 * np.minimum(k, settle))
    changes = np.where(k < 8, 30.0, 0.5) * SETTINGS.tolerance
    status, cycles, history = _cycled(films, changes)
    assert status.converged and settle < cycles < SETTINGS.max_cycles
    assert history.films[-1][1] == pytest.approx(2.0e-7 * (1.0 + 0.03 * settle))
