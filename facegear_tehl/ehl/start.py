"""The full-multigrid start of a point solve (Venner & Lubrecht 2000, ch. 5.6): the Hertz pressure on the coarsest
grid with H_0 set for the Hamrock & Dowson (1977) central film, then each finer grid from the bicubic interpolation
of the one below with `cycles_per_level` V-cycles.

Two remedies of the retry policy (retry.py) act here: a start that runs away is begun again from a coarsest grid
twice as fine (`escalate_start`), and the last attempt at a heavily loaded point starts at a fraction of its load
and raises it step by step on the start's last level, each step held only where the pressure iteration converges it
(load continuation), on a hierarchy coarsened along the strongly coupled axes alone (`continued_shapes`).
"""

from __future__ import annotations

from dataclasses import replace
import math
from typing import Protocol

from facegear_tehl.ehl import grid
from facegear_tehl.ehl.convergence import History, finite
from facegear_tehl.ehl.coupled import film_closed
from facegear_tehl.ehl.domain import predicted_central_film
from facegear_tehl.ehl.multigrid import Level, MultigridSolver, Problem, at_load_fraction
from facegear_tehl.ehl.pressure import PressureIteration
from facegear_tehl.ehl.report import LevelSummary, summarise
from facegear_tehl.ehl.scaling import Scaling
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.record import Action, Reason, RetryRecord
from facegear_tehl.settings import SolverSettings, ThermalMode
from facegear_tehl.solution import CONVERGED, Outcome, Status

# H = h R_x/b^2 of the central film against the load at fixed radii: h_c ~ W^-0.067 (Hamrock & Dowson 1977) and
# b^2 ~ W^(2/3) (Hertz): each load step moves H_0 by the central film's predicted change.
FILM_LOAD_EXPONENT = -0.067 - 2.0 / 3.0


def continued_shapes(nx: int, ny: int, problem: Problem, columns: int) -> list[tuple[int, int]]:
    """(nx, ny) per level, coarsest first, of a hierarchy coarsened along x down to `columns` columns and along y only
    where the rows are coupled at least row_coupling times as strongly as the columns: the Reynolds operator's
    coefficients along Y and X stand as (h_x/(k h_y))^2 (k = a/b; reynolds.py), and an axis whose coupling is weak is
    not coarsened (semi-coarsening of anisotropic problems: Brandt 1977; Trottenberg, Oosterlee & Schüller 2001,
    §5.1). A circle's hierarchy is the one coarsened along both axes (grid.hierarchy_shapes); a long ellipse's keeps
    every row, e.g. a/b = 74.5 on (257, 65): [(33, 65), (65, 65), (129, 65), (257, 65)]."""
    length_x = problem.domain_x[1] - problem.domain_x[0]
    length_y = problem.domain_y[1] - problem.domain_y[0]
    shapes = [(nx, ny)]
    while nx > columns:
        coupling = (length_x / (nx - 1) / (problem.ellipticity * length_y / (ny - 1))) ** 2
        ny = (ny - 1) // 2 + 1 if coupling >= TUNING.row_coupling and ny > columns else ny
        nx = (nx - 1) // 2 + 1
        shapes.insert(0, (nx, ny))
    return shapes


class Starting(Protocol):
    """What the start needs of a point solve (solve.PointSolve)."""

    solver: MultigridSolver
    history: History
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

    def hierarchy(self, coarsest: int) -> list[tuple[int, int]]: ...


def start(solve: Starting, below_top: int) -> tuple[int, Status]:
    """Full multigrid from the Hertz start up to `below_top` levels below the finest. With `escalate_start`, a start
    that runs away is begun again from a coarsest grid twice as fine, as long as the hierarchy keeps the levels
    asked for (a heavy load's film and spike are not resolved by coarse grids); from the last coarsest grid the
    hierarchy allows, a first step that runs away has the coarsest grid cycled to its load first (`_balanced`).
    Returns the finest level that stayed sound (a level that runs away is undone) and the status."""
    settings = solve.settings
    while True:
        finer = 2 * solve.coarsest - 1
        shapes = solve.hierarchy(finer)
        last = finer > min(settings.grid, settings.nodes_y) or len(shapes) <= below_top
        index, status = _full_multigrid(solve, len(solve.solver.levels) - 1 - below_top,
                                        balance=solve.escalate_start and last)
        if not (status.diverged and solve.escalate_start) or last:
            return index, status
        solve.new_hierarchy(shapes)
        solve.retries.append(RetryRecord(Reason.START_RAN_AWAY, Action.FINER_COARSEST_GRID, solve.attempt,
                                         f"from {solve.coarsest} x {solve.coarsest}: {status.message}"))
        solve.coarsest = finer


def hierarchy_shapes(settings: SolverSettings, coarsest: int, problem: Problem,
                     continued: bool) -> list[tuple[int, int]]:
    """The grids of a point solve, coarsest first: coarsened along both axes down to `coarsest` nodes on the shorter
    side (grid.hierarchy_shapes), or, for a solve `continued` from a fraction of the load, along the axes whose
    coupling is strong down to `coarsest` columns, semi_coarsest_columns at least (`continued_shapes`)."""
    if continued:
        return continued_shapes(settings.grid, settings.nodes_y, problem, max(coarsest, TUNING.semi_coarsest_columns))
    return grid.hierarchy_shapes(settings.grid, settings.nodes_y, coarsest)


def _full_multigrid(solve: Starting, last: int, balance: bool = False) -> tuple[int, Status]:
    """Full multigrid from the Hertz start on the coarsest grid up to level `last`; appends a summary per level.
    With `balance`, a first step that runs away is taken again from the coarsest grid cycled to its load
    (`_climbed_balanced`). With a start_load_fraction below 1, level `last` is started at that fraction of the load
    and its load raised to the full load (_continued; `balance` does not apply there)."""
    if solve.start_load_fraction < 1.0:
        return _continued(solve, last)
    solver, index = solve.solver, 0
    solve.load_reached = 1.0
    try:
        _hertz_start(solver, solve.scaling, solve.settings.cycles_per_level, 1.0)
        solve.summaries.append(summarise(solver.levels[0]))
        index, status = _climb(solve, 1, last)
        if balance and status.diverged and index == 0:
            index, status = _climbed_balanced(solve, last, status)
    finally:
        solver.update_film(solver.levels[index])
    return index, status


def _climbed_balanced(solve: Starting, last: int, failed: Status) -> tuple[int, Status]:
    """The start climbed again from the coarsest grid cycled to its load (`_balanced`) after its first step ran away
    (`failed`); the coarsest grid as it was, and `failed`, where the cycles do not carry the load."""
    solver = solve.solver
    saved = solver.snapshot(0)
    if not _balanced(solver):
        solver.restore(0, saved)
        return 0, failed
    solve.retries.append(RetryRecord(Reason.START_RAN_AWAY, Action.COARSEST_TO_ITS_LOAD, solve.attempt, failed.message))
    solve.summaries[-1] = summarise(solver.levels[0])
    return _climb(solve, 1, last)


def _hertz_start(solver: MultigridSolver, scaling: Scaling, cycles: int, fraction: float) -> None:
    """The coarsest grid of `solver` from the Hertz pressure at `fraction` of the load (H_0 for the predicted central
    film there) and `cycles` V-cycles on it; `solver.problem` is that load's."""
    central = predicted_central_film(scaling) / scaling.film_scale
    solver.start_from_hertz(central * fraction ** FILM_LOAD_EXPONENT)
    for _ in range(cycles):
        solver.cycle(0)


def _balanced(solver: MultigridSolver) -> bool:
    """The coarsest grid (made the finest again) cycled on until it carries its load, |g| within start_balance_error
    of it, in at most start_balance_cycles V-cycles; whether it does. For a start whose first full-multigrid step ran
    away: the predicted central film that set H_0 was far from the film of the domain solved. Hamrock & Dowson's
    (1977) fit holds in the elastic-piezoviscous regime; a light load's rigid-isoviscous film over a lengthened inlet
    is several times thicker (docs/tuning.md), and the start's few cycles per level cannot move H_0 that far before
    the next level is judged to run away."""
    level = solver.levels[0]
    bound = TUNING.start_balance_error * solver.problem.load_integral
    for _ in range(TUNING.start_balance_cycles):
        if not finite(level) or abs(solver.force_error(level)) <= bound:
            break
        solver.cycle(0)
    return finite(level) and abs(solver.force_error(level)) <= bound


def _continued(solve: Starting, last: int) -> tuple[int, Status]:
    """Full multigrid at start_load_fraction of the load up to the level below `last`, its load raised there to the
    full load (_raise_load), then the full-multigrid step to `last` (_climb); where a level does not carry the full
    load, the raise goes on from the load it reached on the next finer one, up to `last` (a solution raised on `last`
    has no level one grid coarser at the full load to estimate its error against: retry.RetryPolicy.coarse sends it
    to a finer grid). The solve's hierarchy is coarsened along the strongly coupled axes alone
    (`continued_shapes`): the coarse grids coarsened along both axes do not carry a heavy long ellipse, their V-cycles
    fall into a period-2 limit cycle at the end of the major axis, where the rows are coupled through the deflection
    alone, or run away from its converged start (docs/envelope.md); those that keep every row converge there."""
    solver, problem, fraction = solve.solver, solve.solver.problem, solve.start_load_fraction
    iteration = PressureIteration(solver, _step_settings(solve.settings), History(cycles=0))
    index = max(last - 1, 0)
    solver.problem = at_load_fraction(problem, fraction)
    try:
        _hertz_start(solver, solve.scaling, solve.settings.cycles_per_level, fraction)
        _interpolated(solver, 1, index, solve.settings.cycles_per_level)
        while True:
            fraction, status = _raise_load(iteration, index, problem, fraction)
            if status.converged or index == last:
                break
            index += 1
            solver.problem = at_load_fraction(problem, fraction)
            _interpolated(solver, index, index, solve.settings.cycles_per_level)
    finally:
        solver.problem = problem
        solver.update_film(solver.levels[index])
    solve.load_reached = fraction
    solve.history.cycles += iteration.history.cycles
    solve.summaries.append(_at_load(summarise(solver.levels[index]), fraction))
    return _climb(solve, index + 1, last) if status.converged else (index, status)


def _interpolated(solver: MultigridSolver, first: int, last: int, cycles: int) -> None:
    """Full-multigrid steps from level `first - 1` up to level `last`, `cycles` V-cycles each (a level that runs away
    is the load steps' to judge)."""
    for index in range(first, last + 1):
        solver.interpolate_up(index)
        for _ in range(cycles):
            solver.cycle(index)


def _step_settings(settings: SolverSettings) -> SolverSettings:
    """The tolerances a load step's V-cycles must meet (continuation_tolerance, of the pressure change and the load
    error) within cycles_per_load_step cycles."""
    return replace(settings, tolerance=TUNING.continuation_tolerance, load_tolerance=TUNING.continuation_tolerance,
                   max_cycles=TUNING.cycles_per_load_step)


def _climb(solve: Starting, first: int, last: int) -> tuple[int, Status]:
    """Full-multigrid steps from level `first - 1` (solved) up to level `last`; returns the finest sound level and
    the status."""
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
        solve.summaries.append(summarise(level))
    return max(last, first - 1), CONVERGED


def _ran_away(solver: MultigridSolver, level: Level) -> bool:
    """A level not finite, or whose load error after its cycles exceeds diverged_load_error of the load."""
    bound = TUNING.diverged_load_error * solver.problem.load_integral
    return not finite(level) or abs(solver.force_error(level)) > bound


def _raise_load(iteration: PressureIteration, index: int, problem: Problem, fraction: float) -> tuple[float, Status]:
    """Raise the load of level `index` of `iteration`'s solver from `fraction` to the full load of `problem` under
    step control by the convergence monitor: each step multiplies the load by the current factor (load_step at most),
    moves H_0 by the predicted change of the central film (FILM_LOAD_EXPONENT) and cycles the pressure
    (pressure.PressureIteration: phase means and Anderson's acceleration where the V-cycles stall) to the step's
    tolerances (_step_settings). A step whose cycles do not converge, run away, or leave the film closed (h_min <= 0:
    not a film of the smooth-film equations, which is open at any load) is taken back and the logarithm of its factor
    halved; one that holds doubles it again, up to load_step. Returns the fraction reached and the status: how the
    last step failed when the factor falls below min_load_step (the grid does not carry a heavier load, or does not
    resolve its film), diverged at once when the level's start ran away."""
    solver = iteration.solver
    level, step = solver.levels[index], TUNING.load_step
    if _ran_away(solver, level):
        return fraction, Status(Outcome.DIVERGED, f"diverged during the full-multigrid start at {fraction:.3g} of the "
                                                  f"load on the {level.nx} x {level.ny} grid")
    while fraction < 1.0:
        saved, previous = solver.snapshot(index), fraction
        fraction = min(step * fraction, 1.0)
        h_c = solver.central_film(level)
        solver.problem = at_load_fraction(problem, fraction)
        solver.h0 += h_c * ((fraction / previous) ** FILM_LOAD_EXPONENT - 1.0)
        solver.update_film(level)
        failure = _failed_step(level, iteration.cycle(index, TUNING.cycles_per_load_step))
        if failure is None:
            step = min(step * step, TUNING.load_step)
            continue
        solver.problem = at_load_fraction(problem, previous)
        solver.restore(index, saved)
        fraction, step = previous, math.sqrt(step)
        if step < TUNING.min_load_step:
            return fraction, Status(failure, f"{STEP_FAILURES[failure]} raising the load of the full-multigrid start "
                                             f"past {fraction:.3g} on the {level.nx} x {level.ny} grid")
    return fraction, CONVERGED


STEP_FAILURES = {Outcome.DIVERGED: "diverged", Outcome.FILM_CLOSED: "the film closes",
                 Outcome.NOT_CONVERGED: "the V-cycles do not converge"}


def _failed_step(level: Level, status: Status) -> Outcome | None:
    """How a load step failed: its V-cycles ran away or did not converge (`status`), or its film closed (h_min <= 0,
    the film of the iterate after its cycles); None when it holds."""
    if not status.converged:
        return status.outcome
    return Outcome.FILM_CLOSED if film_closed(level.film) else None


def _at_load(summary: LevelSummary, fraction: float) -> LevelSummary:
    """A level summary solved at `fraction` of the load in the full load's Hertzian units: H = h R_x/b^2 and
    P = p/p_h with b^2 and p_h scaling as f^(2/3) and f^(1/3) (multigrid.at_load_fraction)."""
    if fraction == 1.0:
        return summary
    return replace(summary, h_c=summary.h_c * fraction ** (2.0 / 3.0), h_min=summary.h_min * fraction ** (2.0 / 3.0),
                   p_max=summary.p_max * fraction ** (1.0 / 3.0))
