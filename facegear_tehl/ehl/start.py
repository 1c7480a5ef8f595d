"""The full-multigrid start of a point solve (Venner & Lubrecht 2000, ch. 5.6): the Hertz pressure on the coarsest
grid with H_0 set for the Hamrock & Dowson (1977) central film, then each finer grid from the bicubic interpolation
of the one below with `cycles_per_level` V-cycles.

Two remedies of the retry policy (retry.py) act here: a start that runs away is begun again from a coarsest grid
twice as fine (`escalate_start`), and the last attempt at a heavily loaded point starts at a fraction of its load
and raises it step by step one grid below the finest (load continuation).
"""

from __future__ import annotations

from dataclasses import replace
import math
from typing import Protocol

from facegear_tehl.ehl import grid
from facegear_tehl.ehl.convergence import finite
from facegear_tehl.ehl.coupled import film_closed
from facegear_tehl.ehl.domain import predicted_central_film
from facegear_tehl.ehl.multigrid import Level, MultigridSolver, Problem, at_load_fraction
from facegear_tehl.ehl.report import LevelSummary, summarise
from facegear_tehl.ehl.scaling import Scaling
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.record import Action, Reason, RetryRecord
from facegear_tehl.settings import SolverSettings, ThermalMode
from facegear_tehl.solution import CONVERGED, Outcome, Status

# H = h R_x/b^2 of the central film against the load at fixed radii: h_c ~ W^-0.067 (Hamrock & Dowson 1977) and
# b^2 ~ W^(2/3) (Hertz): each load step moves H_0 by the central film's predicted change.
FILM_LOAD_EXPONENT = -0.067 - 2.0 / 3.0


class Starting(Protocol):
    """What the start needs of a point solve (solve.PointSolve)."""

    solver: MultigridSolver
    settings: SolverSettings
    scaling: Scaling
    summaries: list[LevelSummary]
    coarsest: int
    escalate_start: bool
    start_load_fraction: float
    load_reached: float  # the fraction of the load the start's last level carries (1 unless a continuation failed)
    mode: ThermalMode
    coupled: bool
    attempt: int
    retries: list[RetryRecord]

    def new_hierarchy(self, shapes: list[tuple[int, int]]) -> None: ...


def start(solve: Starting, below_top: int) -> tuple[int, Status]:
    """Full multigrid from the Hertz start up to `below_top` levels below the finest. With `escalate_start`, a start
    that runs away is begun again from a coarsest grid twice as fine, as long as the hierarchy keeps the levels
    asked for (a heavy load's film and spike are not resolved by coarse grids). Returns the finest level that
    stayed sound (a level that runs away is undone) and the status."""
    settings = solve.settings
    while True:
        index, status = _full_multigrid(solve, len(solve.solver.levels) - 1 - below_top)
        finer = 2 * solve.coarsest - 1
        shapes = grid.hierarchy_shapes(settings.grid, settings.nodes_y, finer)
        if (not (status.diverged and solve.escalate_start) or finer > min(settings.grid, settings.nodes_y)
                or len(shapes) <= below_top):
            return index, status
        solve.new_hierarchy(shapes)
        solve.retries.append(RetryRecord(Reason.START_RAN_AWAY, Action.FINER_COARSEST_GRID, solve.attempt,
                                         f"from {solve.coarsest} x {solve.coarsest}: {status.message}"))
        solve.coarsest = min(shapes[0])


def _full_multigrid(solve: Starting, last: int) -> tuple[int, Status]:
    """Full multigrid from the Hertz start on the coarsest grid up to level `last`; appends a summary per level.
    With a start_load_fraction below 1 the levels up to the one below `last` are solved at that fraction of the
    load, raised to the full load there or, where a grid does not carry it, on the finer ones (_continued)."""
    solver, problem, fraction = solve.solver, solve.solver.problem, solve.start_load_fraction
    ramp = max(last - 1, 0) if fraction < 1.0 else last  # the level whose load is raised
    solver.problem = at_load_fraction(problem, fraction)
    solve.load_reached, index = fraction, 0
    try:
        central = predicted_central_film(solve.scaling) / solve.scaling.film_scale
        solver.start_from_hertz(central * fraction ** FILM_LOAD_EXPONENT)
        for _ in range(solve.settings.cycles_per_level):
            solver.cycle(0)
        solve.summaries.append(_at_load(summarise(solver.levels[0]), fraction))
        index, status = _climb(solve, 1, ramp, fraction)
        if status.converged and fraction < 1.0:
            index, status = _continued(solve, index, last, problem, fraction)
    finally:
        solver.problem = problem
        solver.update_film(solver.levels[index])
    return index, status


def _continued(solve: Starting, index: int, last: int, problem: Problem, fraction: float) -> tuple[int, Status]:
    """Raise the load of level `index` from `fraction` (_raise_load); where that grid does not carry a heavier load,
    go on from the fraction it reached on the next finer level, up to `last` (the summaries of the levels below are
    then at other loads than the finer ones': dropped, so that no error estimate compares them), then climb to
    `last` at the full load."""
    solver = solve.solver
    while True:
        fraction, status = _raise_load(solver, index, problem, fraction, open_film=index == last)
        solve.load_reached = fraction
        if status.converged:
            solve.summaries[-1] = summarise(solver.levels[index])
            return _climb(solve, index + 1, last, 1.0)
        if index >= last:
            return index, status
        solve.summaries.clear()
        solver.problem = at_load_fraction(problem, fraction)
        index, status = _climb(solve, index + 1, index + 1, fraction)
        if not status.converged:
            return index, status


def _climb(solve: Starting, first: int, last: int, fraction: float) -> tuple[int, Status]:
    """Full-multigrid steps from level `first - 1` (solved) up to level `last` at `fraction` of the load (the
    solver's problem); returns the finest sound level and the status."""
    solver = solve.solver
    saved = solver.snapshot(first - 1)
    for index in range(first, last + 1):
        solver.interpolate_up(index)
        # the finest grid of an isothermal Ree-Eyring film: its outer loop follows at once
        eyring_top = index == len(solver.levels) - 1 and solve.mode is ThermalMode.OFF and solve.coupled
        for _ in range(TUNING.eyring_start_cycles if eyring_top else solve.settings.cycles_per_level):
            solver.cycle(index)
        level = solver.levels[index]
        if _ran_away(solver, level):
            solver.restore(index - 1, saved)
            message = f"diverged during the full-multigrid start on the {level.nx} x {level.ny} grid"
            return index - 1, Status(Outcome.DIVERGED, message)
        saved = solver.snapshot(index)
        solve.summaries.append(_at_load(summarise(level), fraction))
    return max(last, first - 1), CONVERGED


def _ran_away(solver: MultigridSolver, level: Level) -> bool:
    """A level not finite, or whose load error after its cycles exceeds diverged_load_error of the load."""
    bound = TUNING.diverged_load_error * solver.problem.load_integral
    return not finite(level) or abs(solver.force_error(level)) > bound


def _raise_load(solver: MultigridSolver, index: int, problem: Problem, fraction: float,
                open_film: bool) -> tuple[float, Status]:
    """Raise the load of level `index` from `fraction` to the full load of `problem` under step control: each step
    multiplies the load by the current factor (load_step at most), moves H_0 by the predicted change of the central
    film (FILM_LOAD_EXPONENT) and takes cycles_per_load_step V-cycles. A step that runs away (`_ran_away`), or with
    `open_film` (the finest level of the start, whose film is the result's) one whose film closes (h_min <= 0: not a
    film of the smooth-film equations, which is open at any load), is taken back and the logarithm of its factor
    halved; one that holds doubles it again, up to load_step. Returns the fraction reached and the status: diverged,
    or film closed, when the factor falls below min_load_step (the grid does not carry a heavier load, or does not
    resolve its film). A coarser level's closed film goes on: it is that grid's, and the finer grids, which start
    from it, may resolve it (docs/envelope.md, ab1_ph2.5_u0.5_eta0.01_iso and w08)."""
    level, step = solver.levels[index], TUNING.load_step
    while fraction < 1.0:
        saved, previous = solver.snapshot(index), fraction
        fraction = min(step * fraction, 1.0)
        h_c = solver.central_film(level)
        solver.problem = at_load_fraction(problem, fraction)
        solver.h0 += h_c * ((fraction / previous) ** FILM_LOAD_EXPONENT - 1.0)
        solver.update_film(level)
        for _ in range(TUNING.cycles_per_load_step):
            solver.cycle(index)
        failure = _failed_step(solver, level, open_film)
        if failure is None:
            step = min(step * step, TUNING.load_step)
            continue
        solver.problem = at_load_fraction(problem, previous)
        solver.restore(index, saved)
        fraction, step = previous, math.sqrt(step)
        if step < TUNING.min_load_step:
            what = "diverged" if failure is Outcome.DIVERGED else "the film closes"
            return fraction, Status(failure, f"{what} raising the load of the full-multigrid start past "
                                             f"{fraction:.3g} on the {level.nx} x {level.ny} grid")
    return fraction, CONVERGED


def _failed_step(solver: MultigridSolver, level: Level, open_film: bool) -> Outcome | None:
    """How a load step failed: it ran away (`_ran_away`), or, with `open_film`, its film closed (h_min <= 0, the film
    of the iterate after its cycles); None when it holds."""
    if _ran_away(solver, level):
        return Outcome.DIVERGED
    if not open_film:
        return None
    solver.update_film(level)
    return Outcome.FILM_CLOSED if film_closed(level.film) else None


def _at_load(summary: LevelSummary, fraction: float) -> LevelSummary:
    """A level summary solved at `fraction` of the load in the full load's Hertzian units: H = h R_x/b^2 and
    P = p/p_h with b^2 and p_h scaling as f^(2/3) and f^(1/3) (multigrid.at_load_fraction)."""
    if fraction == 1.0:
        return summary
    return replace(summary, h_c=summary.h_c * fraction ** (2.0 / 3.0), h_min=summary.h_min * fraction ** (2.0 / 3.0),
                   p_max=summary.p_max * fraction ** (1.0 / 3.0))
