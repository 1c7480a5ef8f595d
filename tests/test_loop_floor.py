"""A coupled loop at its floor: judged on the full step, it ends "converged at its floor" only once the full step no
longer contracts at the smallest relaxation, and the amplitude it is left with enters each figure's iteration error
(coupled.CoupledLoop, error_bounds.floor_error).

The stand-in loop has a known limit cycle: its film-state map F(T) = T* + L (T - T*) + A (-1)^k, whose evaluation
alternates by A about the contraction's fixed point T* whatever the iterate (as an inexact inner solve leaves a noise
floor), and a central film h(T) = h* (1 - s (T - T*)). The distance of the iterate from T* never falls below the
relaxed share of A, so no tolerance below A is ever met; judged on the relaxed step, a relaxation halved to 1/8
"met" a tolerance eight times looser and reported the error of the last relaxed change."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from facegear_tehl.ehl import coupled
from facegear_tehl.ehl.convergence import History
from facegear_tehl.ehl.error_bounds import bounds, iteration_error
from facegear_tehl.ehl.film_state import FilmState
from facegear_tehl.ehl.relaxation import Relaxation
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import CONVERGED, Field, PointSolution

T_IN, T_FIXED, CONTRACTION, SENSITIVITY, H_FIXED = 300.0, 400.0, 0.5, 2e-3, 2.0e-7  # K, K, 1, 1/K, m
TOLERANCE = 2e-3  # of the rise, the thermal loop's default


class _Pressure:
    """A pressure that converges on every frozen film state."""

    settings = SolverSettings()
    solver = SimpleNamespace(relaxation=Relaxation())

    def cycle(self, index: int, max_cycles: int):
        return CONVERGED

    def settled_pressure(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        return np.ones(3), np.ones(3)  # an open film


class _LimitCycle:
    """The stand-in target: the map above with amplitude `amplitude` (K) and film sensitivity `sensitivity` (1/K);
    it ends on its tolerance, as the uniform grid's target does, once the loop's change falls below TOLERANCE of the
    rise. `films`: its central film after each update (m)."""

    index = 0
    model = SimpleNamespace(solve_energy=True)

    def __init__(self, amplitude: float, sensitivity: float):
        self.amplitude, self.sensitivity, self.k = amplitude, sensitivity, 0
        self.temperature, self.films = None, []

    def evaluate(self, temperature: np.ndarray, forcing: float) -> FilmState:
        self.k += 1
        mapped = T_FIXED + CONTRACTION * (temperature - T_FIXED) + self.amplitude * (-1.0) ** self.k
        ones = np.ones(temperature.shape)
        return FilmState(temperature=mapped, viscosity_factor=ones, dissipation=ones, velocity_x=None,
                         velocity_y=None, stress_1=ones[:2], stress_2=ones[:2], heat_flux_1=None, heat_flux_2=None,
                         compression=None, change=0.0)

    def constrain(self, temperature: np.ndarray) -> None:
        pass

    def freeze(self, state: FilmState) -> None:
        self.temperature = state.temperature

    def central_film(self) -> float:
        self.films.append(H_FIXED * (1.0 - self.sensitivity * (float(self.temperature.mean()) - T_FIXED)))
        return self.films[-1]

    def judge(self, loop, status, rise):
        if loop.outer > 0 and loop.changes[-1] < TOLERANCE * rise:
            return coupled.Ending.TOLERANCE, CONVERGED
        return coupled.Ending.GOING, status


def _run(amplitude: float, sensitivity: float = SENSITIVITY):
    """The loop's end and the solution it reports (its rise, h_c and their histories), its last iterate's true rise
    and h_c."""
    target, history = _LimitCycle(amplitude, sensitivity), History(cycles=2)
    start = np.full((3, 4, 5), T_IN + 10.0)
    end = coupled.CoupledLoop(target, _Pressure(), history, 40, T_IN).run(start, np.ones(start.shape))
    rise, h_c = float(end.state.temperature.max()) - T_IN, target.films[-1]
    scalars = {"a": 1.0, "b": 1.0, "h_c": h_c, "h_min": h_c, "dT_max": rise, "thermal_floor": history.thermal_floor,
               "error_estimate_h_c": 1e-3, "error_estimate_h_min": 1e-3, "error_estimate_dT_max": 1e-3}
    recorded = {"thermal_change_history": Field(np.array(history.thermal_changes), "K", ""),
                "thermal_h_c_history": Field(np.array(target.films), "m", "")}
    axes = {"x": Field(np.linspace(-1.0, 1.0, 257), "m", ""), "y": Field(np.linspace(-1.0, 1.0, 257), "m", "")}
    solution = PointSolution("P", end.status.outcome, "", {k: (v, "1") for k, v in scalars.items()}, {}, axes,
                             recorded)
    return end, solution


@pytest.mark.parametrize("amplitude", [0.5, 2.0])
def test_a_loop_at_a_limit_cycle_ends_at_its_floor_with_the_amplitude_in_its_bound(amplitude):
    """The full step never falls below the map's amplitude: the loop halves its relaxation to min_relaxation_scale,
    stalls there, and ends at its floor (not on a tolerance a 1/8 step met); the iteration errors of the rise and of
    h_c bound their true errors against the fixed point."""
    end, solution = _run(amplitude)
    assert end.ending is coupled.Ending.FLOOR and end.status.converged
    rise, h_c = solution.scalar("dT_max"), solution.scalar("h_c")
    assert iteration_error(solution, "dT_max") >= abs(rise - (T_FIXED - T_IN)) / rise
    assert iteration_error(solution, "h_c") >= abs(h_c - H_FIXED) / h_c
    assert solution.scalar("thermal_floor") >= TUNING.thermal_relaxation * amplitude


def test_a_figure_the_floors_amplitude_leaves_above_the_limit_is_unresolved():
    """A floor whose amplitude carried into h_c exceeds max_iteration_error leaves h_c unresolved, its iteration
    error in the file as the reason, while the rise, whose share of the amplitude is small, stays bounded."""
    end, solution = _run(10.0, sensitivity=0.2)
    assert end.ending is coupled.Ending.FLOOR
    out = bounds(solution, {"h_c": 0.0, "h_min": 0.0, "dT_max": 0.0})
    assert out["unresolved_h_c"][0] == 1.0 and "error_bound_h_c" not in out
    assert out["iteration_error_h_c"][0] > TUNING.max_iteration_error
    assert out["unresolved_dT_max"][0] == 0.0
    assert out["error_bound_dT_max"][0] >= out["iteration_error_dT_max"][0] > 0.0
