"""The error bound's y-check of a thermal full multigrid solve, started from that solve's own coarse stage.

A `full` solve of nx x ny nodes takes e_y from its converged coarse stage on (nx + 1)/2 x ny and one check solve of
the same point and model on (nx + 1)/2 x (ny + 1)/2 (error_bounds.py), whose nodes are every other row of the coarse
stage's on the same domain. So instead of the full-multigrid start from the Hertz pressure and a coarse stage of its
own, the check starts on its grid from the solve's coarse stage injected onto its nodes (pressure, H_0, temperatures
and eta*/eta per layer), which differs from the check's solution by the y-error alone (a few tenths of a percent at
the default case's points: docs/accuracy.md), and runs the coupled loop on that grid to the finest grid's tolerance
(the converged solution does not depend on the start: tests/test_y_check.py). Its steady-h_c test
(convergence.h_c_steady) reads h_c one grid coarser in x from the solve's seed stage on (nx + 3)/4 x ny, the x nodes
of the cold check's own coarse stage. A solve without that stage (a seeded point of
the cycle: ehl/seeded.py) has its check solved cold. A warm check the retry policy would retry is solved again cold
(staged.UNBOUNDED).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.ehl.thermal import FilmState
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.record import Stage
from facegear_tehl.settings import SolverSettings, ThermalMode
from facegear_tehl.solution import PointSolution


@dataclass(frozen=True)
class CoarseStart:
    """A solve's converged coarse stage: its nodes X = x/b, Y = y/a, pressure P = p/p_h (ny, nx), H_0 and film
    state (nz, ny, nx); and the dimensionless h_c of its seed stage, one grid coarser in x."""

    x: np.ndarray
    y: np.ndarray
    pressure: np.ndarray
    h0: float
    state: FilmState
    coarser_h_c: float

    @classmethod
    def of(cls, solve: PointSolve) -> CoarseStart | None:
        """The coarse stage of a begun `full` solve (PointSolve.begin returned it), None without one or without the
        seed stage's summary below it."""
        levels, summaries = solve.solver.levels, solve.summaries
        if solve.coarse_state is None or len(levels) < 3 or len(summaries) < 2:
            return None
        level, seed = levels[-2], summaries[-2]
        if not (seed.n == levels[-3].nx and summaries[-1].n == level.nx and plan_has_seed(solve)):
            return None
        return cls(level.x, level.y, level.pressure.copy(), solve.solver.h0, solve.coarse_state, seed.h_c)


def plan_has_seed(solve: PointSolve) -> bool:
    """The solve's plan has the seed stage (Stage.SEED), which ran."""
    return solve.plan.has(Stage.SEED) and any(record.stage is Stage.SEED for record in solve.stages)


class WarmCheck(PointSolve):
    """The check solve (PointSolve) on its grid from `start` where the check's nodes are every other row of it (module
    docstring), else cold."""

    def __init__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings, start: CoarseStart):
        super().__init__(point, lubricant, settings)
        self.start_from = start

    def _coincide(self) -> bool:
        """The check's nodes are the start's columns and every other row of it (and the model is `full`)."""
        level, start = self.solver.levels[-1], self.start_from
        if self.mode is not ThermalMode.FULL or start.x.shape != level.x.shape or start.y[::2].shape != level.y.shape:
            return False
        scale = max(np.ptp(level.x), np.ptp(level.y))
        return bool(np.allclose(start.x, level.x, rtol=0.0, atol=1e-9 * scale)
                    and np.allclose(start.y[::2], level.y, rtol=0.0, atol=1e-9 * scale))

    def begin(self) -> PointSolution | PointSolve:
        """The coupled loop on the check's grid from the injected start (the solution), or the cold start's
        `begin`."""
        if not self._coincide():
            return super().begin()
        index, start, solver = len(self.solver.levels) - 1, self.start_from, self.solver
        mark = self._mark()
        level = solver.levels[index]
        solver.reset_rhs(level)
        level.pressure = np.ascontiguousarray(start.pressure[::2])
        solver.h0 = start.h0
        solver.update_film(level)
        frozen = replace(start.state, temperature=np.ascontiguousarray(start.state.temperature[:, ::2]),
                         viscosity_factor=np.ascontiguousarray(start.state.viscosity_factor[:, ::2]))
        solver.set_film_state(index, frozen.temperature, frozen.viscosity_factor)
        status = self.cycle(index, TUNING.cycles_per_thermal_update)
        state = None
        if not status.diverged:
            state, status = self.couple(index, frozen, start.coarser_h_c)
        self._stage_done(Stage.FINEST, index, status, mark)
        return self.report(index, status, state)
