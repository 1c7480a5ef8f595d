"""The seeded start of a point solve on a path of contacts (the meshing cycle by continuation, docs/cycle.md).

A thermal point whose plan has a coarse stage (plan.py) can start from its solved neighbour on the path instead of
the full-multigrid start and the seed stage: the neighbour's pressure P = p/p_h and film state (temperatures,
ln eta*/eta per layer) at the same Hertzian coordinates X = x/b, Y = y/a are interpolated bilinearly onto this
point's grid below its finest (outside the neighbour's domain: its edge values; the pressure zero on the boundary),
and H_0 is set so that the central film is this point's Hamrock & Dowson (1977) prediction times the neighbour's
ratio of solved to predicted central film (a predictor along the path). The coarse stage, the finest grid, the
outlet stage, their convergence tests and the error estimates (the coarse stage's summary against the finest grid's,
report.py) are those of the cold start. The record's stages say `seeded start` with the neighbour's name; a seeded
solve that fails is solved again from the cold start, with all of the retry policy, and the record says so.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math
from typing import Sequence

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.domain import predicted_central_film
from facegear_tehl.ehl.plan import PlannedStage, SolvePlan
from facegear_tehl.ehl.report import summarise
from facegear_tehl.ehl.retry import POLICY
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.ehl.staged import (
    RUN_AWAY_ARITHMETIC,
    STAGED,
    UNBOUNDED,
    StagedSolver,
    WarmChecked,
    noted_retry,
    retry_options,
)
from facegear_tehl.ehl.stopwatch import spent_on
from facegear_tehl.ehl.thermal import FilmState
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.ehl.y_check import CoarseStart
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.record import Action, Reason, RetryRecord, Stage
from facegear_tehl.settings import SolverSettings, ThermalMode
from facegear_tehl.solution import PointSolution, Status


@dataclass(frozen=True)
class Seed:
    """A solved point's pressure and film state on the grid it was reported on, in its Hertzian frame."""

    source: str  # the point's name
    x: np.ndarray  # X = x/b of the nodes
    y: np.ndarray  # Y = y/a of the nodes
    pressure: np.ndarray  # P = p/p_h, (ny, nx)
    film_ratio: float  # solved central film over Hamrock & Dowson's prediction
    state: FilmState  # temperatures (K) and eta*/eta per layer, (nz, ny, nx)
    # the finest grid's converged pressure, temperatures and ln(eta*/eta) minus the interpolation of the coarse
    # stage's (None: not a thermal full multigrid solve, or reported below its finest grid)
    correction: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None


def resample(values: np.ndarray, x: np.ndarray, y: np.ndarray, to_x: np.ndarray, to_y: np.ndarray) -> np.ndarray:
    """values[..., j, i] on the ascending axes (x, y) interpolated bilinearly at the nodes of the axes (to_x, to_y);
    beyond the axes the edge values."""
    fx = np.interp(to_x, x, np.arange(len(x), dtype=float))
    fy = np.interp(to_y, y, np.arange(len(y), dtype=float))
    i = np.minimum(fx.astype(int), len(x) - 2)
    j = np.minimum(fy.astype(int), len(y) - 2)
    tx, ty = fx - i, (fy - j)[:, None]
    near, far = values[..., j, :], values[..., j + 1, :]
    return np.ascontiguousarray((1.0 - ty) * ((1.0 - tx) * near[..., i] + tx * near[..., i + 1])
                                + ty * ((1.0 - tx) * far[..., i] + tx * far[..., i + 1]))


def seeded_plan(plan: SolvePlan, source: str) -> SolvePlan:
    """`plan` with the seeded start from point `source` on the coarse stage's grid in place of the full-multigrid
    start and the seed stage."""
    coarse = next(planned for planned in plan.stages if planned.stage is Stage.COARSE)
    seeded = PlannedStage(Stage.SEEDED, coarse.nx, coarse.ny, f"from {source}: its pressure, central film and film "
                                                                f"state in this contact's Hertzian frame")
    return SolvePlan((seeded,) + tuple(p for p in plan.stages if p.stage not in (Stage.START, Stage.SEED)))


class SeededSolve(PointSolve):
    """A point solve that starts from `seed` (the module docstring) when its plan has a coarse stage, else cold; it
    keeps the level and film state it reports, to seed the next point (`seed_for_next`)."""

    def __init__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings, seed: Seed | None,
                 attempt: int = 1, **options: object):
        """`attempt`: of the retry policy (retry.ATTEMPTS), whose relaxation this solve uses from the start; `options`:
        PointSolve's others (a retry's: staged.retry_options)."""
        super().__init__(point, lubricant, settings, attempt=attempt,
                         escalate_start=POLICY.escalates_start(attempt), **options)
        self.seed = seed if seed is not None and self.plan.has(Stage.COARSE) else None
        if self.seed is not None:
            self.plan = seeded_plan(self.plan, self.seed.source)
        self.reported: tuple[int, FilmState | None] | None = None
        self.coarse_pressure: np.ndarray | None = None  # the coarse stage's converged pressure (_start_fine_grid) ...
        self.fine_index = -1  # ... and the level of the finest uniform grid (an outlet stage adds patches above it)

    def begin(self) -> PointSolution | PointSolve:
        """The seeded start and the coarse stage (self, to be finished), or the cold start's `begin`."""
        if self.seed is None:
            return super().begin()
        index = len(self.solver.levels) - 2
        mark = self._mark()
        frozen = self._seeded_level(index)
        status = self.cycle(index, TUNING.cycles_per_thermal_update)
        self.summaries.append(summarise(self.solver.levels[index]))  # as the full-multigrid start's last level
        self._stage_done(Stage.SEEDED, index, status, mark)
        state = None
        if not status.diverged:
            mark = self._mark()
            state, status = self.couple(index, frozen)
            self._stage_done(Stage.COARSE, index, status, mark)
        if state is None or status.diverged or self.coarse_stage_stalled():
            return self.report(index, status, state)
        self.coarse_state = state
        self.elapsed = self._clock.spent()  # paused between stages, as PointSolve.begin
        return self

    def _seeded_level(self, index: int) -> FilmState:
        """Level `index` set from the seed: pressure, H_0 and the frozen film state (returned)."""
        seed, solver = self.seed, self.solver
        level = solver.levels[index]
        solver.reset_rhs(level)
        level.pressure = np.maximum(resample(seed.pressure, seed.x, seed.y, level.x, level.y), 0.0)
        level.pressure[0, :] = level.pressure[-1, :] = 0.0
        level.pressure[:, 0] = level.pressure[:, -1] = 0.0
        temperature = resample(seed.state.temperature, seed.x, seed.y, level.x, level.y)
        factor = np.exp(resample(np.log(seed.state.viscosity_factor), seed.x, seed.y, level.x, level.y))
        solver.h0 = 0.0
        solver.update_film(level)
        central = predicted_central_film(self.scaling) / self.scaling.film_scale * seed.film_ratio
        solver.h0 = central - solver.central_film(level)
        solver.set_film_state(index, temperature, factor)
        return replace(seed.state, temperature=temperature, viscosity_factor=factor)

    def _start_fine_grid(self, index: int) -> tuple[FilmState, Status]:
        """The finest grid from the coarse stage (PointSolve._start_fine_grid); a seeded `full` solve adds the
        neighbour's correction of its own coarse stage's interpolation (`Seed.correction`) to the interpolated
        pressure, temperatures and ln(eta*/eta). Keeps the converged coarse pressure for the next point's seed."""
        self.coarse_pressure, self.fine_index = self.solver.levels[index - 1].pressure.copy(), index
        seed = self.seed
        if seed is None or seed.correction is None or self.mode is not ThermalMode.FULL:
            return super()._start_fine_grid(index)
        solver = self.solver
        solver.interpolate_up(index)
        level = solver.levels[index]
        pressure, temperature, log_factor = (resample(c, seed.x, seed.y, level.x, level.y) for c in seed.correction)
        level.pressure = np.maximum(level.pressure + pressure, 0.0)
        level.pressure[0, :] = level.pressure[-1, :] = 0.0
        level.pressure[:, 0] = level.pressure[:, -1] = 0.0
        temperature += solver.prolong_layers(index, self.coarse_state.temperature)
        factor = np.exp(log_factor + solver.prolong_layers(index, np.log(self.coarse_state.viscosity_factor)))
        solver.set_film_state(index, temperature, factor)
        frozen = replace(self.coarse_state, temperature=temperature, viscosity_factor=factor)
        return frozen, self.cycle(index, TUNING.cycles_per_thermal_update)

    def warm_check(self) -> WarmChecked | None:
        """The error bounds' check started from this seeded solve's converged coarse stage (staged.WarmChecked, as a
        cold start's check starts from its own), None without a seeded `full` coarse stage. Without a seed stage
        below it, the check's steady-h_c test has no h_c one grid coarser in x: the strict test
        (convergence.h_c_steady without the error share)."""
        if self.seed is None or self.coarse_state is None or self.mode is not ThermalMode.FULL:
            return None
        level = self.solver.levels[-2]
        return WarmChecked(CoarseStart(level.x, level.y, level.pressure.copy(), self.solver.h0, self.coarse_state,
                                       math.nan))

    def report(self, index: int, status: Status, state: FilmState | None) -> PointSolution:
        self.reported = (index, state)
        return super().report(index, status, state)

    def seed_for_next(self) -> Seed | None:
        """This solve's reported level and film state as the next point's seed (None without a film state)."""
        if self.reported is None or self.reported[1] is None or not self.plan.has(Stage.COARSE):
            return None
        index, state = self.reported
        solver = self.solver
        level = solver.levels[index]
        predicted = predicted_central_film(self.scaling) / self.scaling.film_scale
        correction = None
        if index == self.fine_index and self.mode is ThermalMode.FULL:
            coarse = self.coarse_state
            correction = (level.pressure - solver.transfers[index].prolong_cubic(self.coarse_pressure),
                          state.temperature - solver.prolong_layers(index, coarse.temperature),
                          np.log(state.viscosity_factor) - solver.prolong_layers(index,
                                                                                 np.log(coarse.viscosity_factor)))
        return Seed(self.point.name, level.x, level.y, level.pressure.copy(), summarise(level).h_c / predicted,
                    state, correction)


class CheckPath:
    """The error bounds' checks of a path's points (error_bounds.y_estimates: the same point on half the rows), each
    solved like its point: seeded from the check of the point before (`solve_seeded`, unbounded; the first cold), and
    with the relaxation of the retry policy's attempt that converged that check (the checks of neighbours run away on
    the same attempts; not the rescue: RetryPolicy.carries). `source` and `attempt` say how the last check started
    ('': with no seed; 1: the first attempt)."""

    def __init__(self) -> None:
        self.seed: Seed | None = None
        self.following = 1  # the attempt the next check starts with
        self.source, self.attempt = "", 1

    def __call__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
        seed = None if self.seed is None else replace(self.seed, correction=None)
        solution, following = solve_seeded(point, lubricant, settings, seed, solver=UNBOUNDED, attempt=self.following,
                                           whole_policy=False)
        record = solution.record
        as_led = record is not None and not any(r.reason is Reason.SEEDED_START_FAILED for r in record.retries)
        seeded = as_led and seed is not None and record.stages[:1] != () and record.stages[0].stage is Stage.SEEDED
        self.source = self.seed.source if seeded else ""
        self.attempt = self.following if as_led else 1
        self.seed = following
        carried = solution.converged and POLICY.carries(record.attempt)
        self.following = record.attempt if carried else 1
        return solution


def solve_seeded(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings, seed: Seed | None,
                 check: CheckPath | None = None, solver: StagedSolver = STAGED, attempt: int = 1,
                 whole_policy: bool = True, retry_seeds: bool = False) -> tuple[PointSolution, Seed | None]:
    """One point of a path from `seed` (None: the cold start) with the relaxation of the retry policy's `attempt`, and
    the seed for the next point (None after a failure); `check`: its error bounds' check solved on the path of checks
    (else cold); `solver`: STAGED, or UNBOUNDED for a check. A solve so led (a seed, or an attempt after the first)
    that the retry policy would retry is solved again from the cold start (`solver`, its check cold), recorded as
    such: with every attempt of the policy (`whole_policy`), else with those after the one that failed (a check: the
    attempt it failed on ran away from the neighbour's state, and does so from the cold start where the neighbours'
    checks needed the next one); a cold start that fails goes on with the policy's retries, which give the seed of the
    attempt reported where `retry_seeds` (a refinement's: SeededRefinement; else None)."""
    solve = SeededSolve(point, lubricant, settings, seed, attempt)
    if check is not None:
        check.source, check.attempt = "", 1  # until this point's check says how it started
    with np.errstate(**RUN_AWAY_ARITHMETIC):
        begun = solve.begin()
    # with its error bounds as every solve of the staged solver; a seeded refinement's check from its coarse stage
    warm = begun.warm_check() if check is None and isinstance(begun, SeededSolve) else None
    solution = solver.finish(begun, check or warm) if isinstance(begun, PointSolve) else solver.bound(
        begun, point, lubricant, settings, check=check)
    if not solver.needs_retry(solution):
        if check is not None and solution.record is not None:
            record = replace(solution.record, check_seed=check.source, check_attempt=check.attempt)
            solution = replace(solution, record=record)
        return solution, solve.seed_for_next()
    if solve.seed is None and attempt == 1:
        if retry_seeds:
            return retried_with_seed(solution, point, lubricant, settings, solver)
        return solver.retried(solution, point, lubricant, settings), None
    following = None
    if whole_policy:
        cold, following = solve_seeded(point, lubricant, settings, None, solver=solver, retry_seeds=retry_seeds)
        spent = spent_on(solution) + spent_on(cold)
    else:  # the retries count the failed attempt's time
        cold = solver.retried(solution, point, lubricant, settings)
        spent = spent_on(cold)
    led = f"seeded from {solve.seed.source}" if solve.seed is not None else f"begun at attempt {attempt}"
    retry = RetryRecord(Reason.SEEDED_START_FAILED, Action.COLD_START, 1, f"{led}: {solution.message}")
    record = cold.record.with_retry(retry)
    return replace(cold, record=record, models={**cold.models, "solver": record.render()},
                   scalars={**cold.scalars, **spent.scalars()}), following if retry_seeds else None


def retried_with_seed(first: PointSolution, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
                      solver: StagedSolver) -> tuple[PointSolution, Seed | None]:
    """`solver.retried` of the cold start's failed `first` attempt, each retry a SeededSolve from the cold start (the
    same solve as staged.StagedSolver.begin's), and the seed of the attempt reported where a retry is (None where the
    first attempt is kept)."""
    solution, seed = first, None
    while solver.needs_retry(solution):
        attempt, options = retry_options(solution)
        solve = noted_retry(SeededSolve(point, lubricant, settings, None, attempt, **options), solution, attempt)
        with np.errstate(**RUN_AWAY_ARITHMETIC):
            begun = solve.begin()
        solution = solver.finish(begun) if isinstance(begun, PointSolve) else solver.bound(begun, point, lubricant,
                                                                                             settings)
        seed = solve.seed_for_next()
    if solution is first:
        return first, None
    return solver.with_retry(first, solution), seed if POLICY.better(first, solution) else None


def solve_path(tasks: Sequence[tuple[ContactPoint, Lubricant, SolverSettings]]) -> list[PointSolution]:
    """Neighbouring points of a path in order, each seeded from the one before it (the first cold; after a failure
    the next cold again)."""
    solutions, seed, check = [], None, CheckPath()
    for point, lubricant, settings in tasks:
        solution, seed = solve_seeded(point, lubricant, settings, seed, check)
        solutions.append(solution)
    return solutions


class SeededRefinement:
    """The accuracy target's solver (accuracy_target.py): a point on a finer grid seeded from its own last converged
    solve in the same model (`solve_seeded`: the seeded start on the finer grid's coarse stage, with the same stages,
    convergence tests and error bounds as the cold start, and the relaxation of the policy's first attempt, whatever
    attempt converged the coarser grid: a finer grid's V-cycles converge more easily, and a damped relaxation carried
    up costs more than it saves; a seeded solve that fails is solved again from the cold start, with every attempt of
    the policy). The first grid of a point is solved cold. It keeps the last seed of each point and model in the
    process that solves them: the target refines a point within one worker."""

    def __init__(self) -> None:
        self.seeds: dict[tuple, Seed] = {}  # (point, model) -> the last converged seed

    def __call__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
        key = (point.radius_x, point.radius_y, point.load, point.velocity_1, point.velocity_2,
               lubricant.rheology, settings.thermal, settings.thermal_layers)
        solution, following = solve_seeded(point, lubricant, settings, self.seeds.get(key), retry_seeds=True)
        if solution.converged and following is not None:
            self.seeds[key] = replace(following, correction=None)
        return solution
