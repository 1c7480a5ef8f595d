"""An explicit snapshot of a point solve's solution arrays and iteration state, to go back to after a failed stage.

It holds copies of every array and number of each level of the multigrid solver (pressure, right-hand sides, film,
flow coefficients, frozen film state), the solver's H_0 and counters, the history and the pressure iteration's
state; the grid operators (deflection kernels, transfers) are shared, as they never change.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from facegear_tehl.ehl.convergence import History
from facegear_tehl.ehl.multigrid import MultigridSolver
from facegear_tehl.ehl.pressure import PressureIteration

_VALUES = (np.ndarray, float, int, bool, type(None))


class Snapshotted(Protocol):
    solver: MultigridSolver
    pressure: PressureIteration


@dataclass(frozen=True)
class SolveSnapshot:
    """The solver (the object itself: a stage may swap in another over it), copies of its levels' and its own values,
    of the history and of the pressure iteration's state."""

    solver: MultigridSolver
    own: dict[str, object]
    levels: tuple[dict[str, object], ...]
    history: History
    iteration: dict[str, object]


def _values(obj: object) -> dict[str, object]:
    """Copies of the arrays and numbers among an object's attributes."""
    return {name: value.copy(order="K") if isinstance(value, np.ndarray) else value
            for name, value in vars(obj).items() if isinstance(value, _VALUES)}


def take_snapshot(solve: Snapshotted) -> SolveSnapshot:
    solver, iteration = solve.solver, solve.pressure
    state = {name: value for name, value in vars(iteration).items() if name not in ("solver", "settings", "history")}
    return SolveSnapshot(solver, _values(solver), tuple(_values(level) for level in solver.levels),
                         copy.deepcopy(iteration.history), state)


def restore_snapshot(solve: Snapshotted, snapshot: SolveSnapshot) -> None:
    """The solve back at `snapshot`, keeping the count of the work done since (V-cycles, outer iterations, work
    units)."""
    history, work = solve.pressure.history, solve.solver.work_units
    solver = snapshot.solver
    for name, value in snapshot.own.items():
        setattr(solver, name, value.copy(order="K") if isinstance(value, np.ndarray) else value)
    for level, values in zip(solver.levels, snapshot.levels, strict=True):
        for name, value in values.items():
            setattr(level, name, value.copy(order="K") if isinstance(value, np.ndarray) else value)
    restored = copy.deepcopy(snapshot.history)
    restored.outer, restored.cycles = history.outer, history.cycles
    solve.solver = solver
    solve.pressure.history = restored
    for name, value in snapshot.iteration.items():
        setattr(solve.pressure, name, value)
    solver.work_units = work
