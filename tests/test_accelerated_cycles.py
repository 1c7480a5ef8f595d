"""The pressure iteration (ehl/pressure.py) accelerated by Anderson's method on the V-cycle map, against the exact
fixed point of an affine map whose plain iteration never converges.

The "V-cycle" of the stand-in solver is x -> x* + A (x - x*) on (P, H_0) with A's eigenvalues -1 (a period-2 limit
cycle, the mode of the heavy ellipses' coarse grids), 1.04 (a slowly growing mode, as on w08's outlet rim on 513^2)
and 0.3 (the modes a V-cycle damps). The plain iteration cycles and diverges; Anderson's iterates on an affine map are
GMRES's (Walker & Ni 2011, theorem 2.2), which finds the fixed point of a map with three distinct eigenvalues in
three steps of its Krylov space: the accelerated loop must stop converged, on x* to the loop's tolerance.
"""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import numpy as np

from facegear_tehl.ehl import pressure as pressure_module
from facegear_tehl.ehl.convergence import History
from facegear_tehl.ehl.multigrid import Iterate
from facegear_tehl.ehl.pressure import PressureIteration
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import Outcome

SHAPE = (6, 8)
H0_STAR = 0.3  # the fixed point's H_0


class AffineCycles:
    """A stand-in MultigridSolver of one level whose V-cycle is an affine map of (P, H_0) with a known fixed point:
    the load error is H_0 - H_0* (zero at the fixed point), the Reynolds residual zero."""

    def __init__(self, eigenvalues: np.ndarray, seed: int = 5):
        rng = np.random.default_rng(seed)
        size = SHAPE[0] * SHAPE[1] + 1
        basis, _ = np.linalg.qr(rng.standard_normal((size, size)))
        self.matrix = basis @ np.diag(eigenvalues) @ basis.T
        self.star = np.append(1.0 + rng.random(size - 1), H0_STAR)  # positive pressure: no projection at x*
        self.problem = SimpleNamespace(load_integral=1.0)
        start = self.star + 1e-2 * rng.standard_normal(size)
        self.levels = [SimpleNamespace(pressure=start[:-1].reshape(SHAPE), film=np.ones(SHAPE), eps=np.ones(SHAPE),
                                       nx=SHAPE[1])]
        self.h0 = float(start[-1])
        self.truncated = False

    def state(self) -> np.ndarray:
        return np.append(self.levels[0].pressure.ravel(), self.h0)

    def cycle(self, index: int) -> None:
        new = self.star + self.matrix @ (self.state() - self.star)
        self.levels[index].pressure = new[:-1].reshape(SHAPE)
        self.h0 = float(new[-1])

    def pressure_change(self, level, previous: np.ndarray) -> float:
        return float(np.abs(level.pressure - previous).sum() / np.abs(level.pressure).sum())

    def central_film(self, level) -> float:
        return 1.0

    def force_error(self, level) -> float:
        return self.h0 - H0_STAR

    def residual(self, level) -> np.ndarray:
        return np.zeros(SHAPE)

    def snapshot(self, index: int) -> Iterate:
        return Iterate(self.levels[index].pressure.copy(), self.h0)

    def restore(self, index: int, iterate: Iterate) -> None:
        self.levels[index].pressure, self.h0 = iterate.pressure.copy(), iterate.h0


def _iterate(monkeypatch, depth: int) -> tuple[AffineCycles, Outcome]:
    monkeypatch.setattr(pressure_module, "TUNING", replace(pressure_module.TUNING, pressure_anderson_depth=depth))
    eigenvalues = np.full(SHAPE[0] * SHAPE[1] + 1, 0.3)
    eigenvalues[:2] = -1.0, 1.04
    solver = AffineCycles(eigenvalues)
    settings = SolverSettings(tolerance=1e-8, load_tolerance=1e-8)
    status = PressureIteration(solver, settings, History(cycles=0)).cycle(0, max_cycles=60)
    return solver, status.outcome


def test_anderson_on_the_v_cycle_map_converges_where_the_plain_cycles_cycle_and_diverge(monkeypatch):
    solver, outcome = _iterate(monkeypatch, depth=3)
    assert outcome is Outcome.CONVERGED
    # the stopping test is the last plain cycle's change (1e-8): the error it leaves is of that order
    assert np.abs(solver.state() - solver.star).max() < 1e-6


def test_the_bare_cycles_of_the_same_map_do_not_converge(monkeypatch):
    """The map is a fair test: its plain V-cycles (depth 0) end unconverged, away from x*."""
    solver, outcome = _iterate(monkeypatch, depth=0)
    assert outcome is not Outcome.CONVERGED
    assert np.abs(solver.state() - solver.star).max() > 1e-3


def test_a_call_whose_bare_cycles_contract_is_not_accelerated(monkeypatch):
    """Every mode damped (eigenvalues 0.3): the bare cycles contract, the accelerated loop never engages and ends on
    the very iterate of the bare one."""
    eigenvalues = np.full(SHAPE[0] * SHAPE[1] + 1, 0.3)
    ends = []
    for depth in (5, 0):
        monkeypatch.setattr(pressure_module, "TUNING", replace(pressure_module.TUNING, pressure_anderson_depth=depth))
        solver = AffineCycles(eigenvalues)
        status = PressureIteration(solver, SolverSettings(tolerance=1e-8, load_tolerance=1e-8),
                                   History(cycles=0)).cycle(0, max_cycles=60)
        assert status.outcome is Outcome.CONVERGED
        ends.append(solver.state())
    assert np.array_equal(ends[0], ends[1])
