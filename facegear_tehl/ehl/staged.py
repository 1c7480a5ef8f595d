"""The EHL solver as the runner uses it: a point solve's attempts (retry.POLICY) around its stages, which may run in
different worker processes with the same result (`begin`, `finish`)."""

from __future__ import annotations

from dataclasses import dataclass, replace
import pickle

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.error_bounds import CoarseStage, Solve, coarse_stage, with_error_bounds
from facegear_tehl.ehl.retry import POLICY
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.ehl.stopwatch import spent_on
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.ehl.y_check import CoarseStart, WarmCheck
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.record import Action, RetryRecord
from facegear_tehl.settings import SolverSettings, ThermalMode
from facegear_tehl.solution import PointSolution

# numpy's floating-point warnings inside a solve: an iterate that runs away overflows before the solver's own
# finiteness checks stop the attempt, report it and retry; the warning would only repeat that on the terminal.
RUN_AWAY_ARITHMETIC = {"over": "ignore", "invalid": "ignore", "divide": "ignore"}


def retry_options(retry_after: PointSolution) -> tuple[int, dict]:
    """The retry policy's next attempt after the failed `retry_after`, and the options of its PointSolve besides the
    attempt's relaxation and escalating start: its wall time counts the earlier attempts', a longer inlet, the load
    continuation where the attempt has it."""
    attempt = POLICY.next_attempt(retry_after)
    return attempt, {"elapsed": spent_on(retry_after), "max_doublings": TUNING.retry_inlet_doublings,
                     "load_continuation": POLICY.numbered(attempt).load_continuation}


def noted_retry(solve: PointSolve, retry_after: PointSolution, attempt: int) -> PointSolve:
    """`solve`, the retry `attempt` after `retry_after`, with the earlier retries and this one in its record."""
    solve.retries.extend(() if retry_after.record is None else retry_after.record.retries)
    failed = int(retry_after.scalar("attempts"))  # not attempt - 1: a stall of attempt 1 goes on to the damped 3
    solve.retries.append(RetryRecord(POLICY.reason(retry_after), Action.NEXT_RELAXATION, attempt,
                                     f"attempt {failed}: {retry_after.message}"))
    return solve


def finest_again(stage: PointSolve, solution: PointSolution, kept: PointSolve) -> tuple[PointSolve, PointSolution]:
    """After `stage.finish()` gave `solution`: where its finest grid failed after a converged coarse stage
    (RetryPolicy.finest_again), the finest grid solved again from that coarse stage (`kept`, a copy taken before the
    finest grid ran) with the first next attempt's under-relaxation that differs from the failed one's, on the switch
    the coarse stage converged with (the shipped S3 on 1025 x 129 converges so, damped on the ellipse-scaled switch,
    and runs away damped on Venner's).
    Returns the solve and solution to report: the new ones if
    that converged, else the first with the time of both and the try in its record (the policy's next attempt
    follows as before)."""
    chosen = POLICY.finest_again(solution, kept.solver.relaxation, kept.spacing)
    if chosen is None:
        return stage, solution
    attempt, kept.solver.relaxation = chosen
    kept.retries.append(RetryRecord(POLICY.reason(solution), Action.FINEST_AGAIN, attempt,
                                    f"attempt {kept.attempt}: {solution.message}"))
    kept.attempt, kept.elapsed = attempt, spent_on(solution)
    with np.errstate(**RUN_AWAY_ARITHMETIC):
        again = kept.finish()
    if again.converged:
        return kept, again
    record = solution.record.with_retry(RetryRecord(POLICY.reason(again), Action.FINEST_AGAIN, attempt,
                                                    f"ended: {again.message}"))
    return stage, replace(solution, scalars={**solution.scalars, **spent_on(again).scalars()},
                          models={**solution.models, "solver": record.render()}, record=record)


def _completed(solver: StagedSolver, begun: PointSolution | PointSolve) -> PointSolution:
    """A begun solve finished in this process."""
    return solver.finish(begun) if isinstance(begun, PointSolve) else begun


@dataclass(frozen=True)
class StagedSolver:
    """The EHL solver: whole (`__call__`), or in stages that may run in different processes with the same result
    (`begin`, `finish`, `needs_retry`, `with_retry`). An attempt that fails as retry.POLICY.next_attempt says is
    solved again with the next attempt; the first attempt is reported if no retry did better, with the retries
    recorded either way. `bounded`: every finished solution carries its error bounds (error_bounds.py; the checks
    those need are solved by this solver unbounded)."""

    bounded: bool = True

    def __call__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
        return self.retried(_completed(self, self.begin(point, lubricant, settings)), point, lubricant, settings)

    def retried(self, first: PointSolution, point: ContactPoint, lubricant: Lubricant,
                settings: SolverSettings) -> PointSolution:
        """The first attempt's solution `first`, solved again with the policy's next attempts while it says so."""
        solution = first
        while self.needs_retry(solution):
            solution = _completed(self, self.begin(point, lubricant, settings, solution))
        return first if solution is first else self.with_retry(first, solution)

    def begin(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
              retry_after: PointSolution | None = None) -> PointSolution | PointSolve:
        """The first stage (PointSolve.begin). `retry_after`: the last attempt, which failed: this one is the next
        attempt of the policy, with an escalating start, and its wall time counts the earlier attempts'."""
        if retry_after is None:
            solve = PointSolve(point, lubricant, settings)
        else:
            attempt, options = retry_options(retry_after)
            solve = noted_retry(PointSolve(point, lubricant, settings,
                                           escalate_start=POLICY.escalates_start(attempt), attempt=attempt, **options),
                                retry_after, attempt)
        with np.errstate(**RUN_AWAY_ARITHMETIC):
            begun = solve.begin()
        if isinstance(begun, PointSolve):
            return begun
        return self.bound(begun, point, lubricant, settings)

    def finish(self, stage: PointSolve, check: Solve | None = None) -> PointSolution:
        """The second stage (PointSolve.finish), with its error bounds (e_y from its coarse stage in a `full` solve,
        the check started from that stage: y_check.py; the check of a `reduced` one is reduced too, its finest figures
        then alike); `check`, when given, solves the bounds' check instead (as in `bound`)."""
        start = CoarseStart.of(stage) if stage.mode is ThermalMode.FULL else None
        kept = pickle.loads(pickle.dumps(stage))  # the converged coarse stage, for the finest grid again
        with np.errstate(**RUN_AWAY_ARITHMETIC):
            solution = stage.finish()
        stage, solution = finest_again(stage, solution, kept)
        coarse = None  # a reduced solve's finest figures are one film-state evaluation, its coarse stage's coupled
        if stage.mode is ThermalMode.FULL and len(stage.summaries) >= 2 and len(stage.solver.levels) >= 2:
            coarse = coarse_stage(stage.summaries[-2], stage.solver.levels[-2].ny, stage.scaling)
        if check is None and start is not None and coarse is not None:  # nx x (ny + 1)/2 is another grid's: cold
            check = WarmChecked(start)
        return self.bound(solution, stage.point, stage.lubricant, stage.asked, coarse, check)

    def bound(self, solution: PointSolution, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
              coarse: CoarseStage | None = None, check: Solve | None = None) -> PointSolution:
        """The solution with its error bounds (error_bounds.with_error_bounds), as it is when not `bounded`; `check`
        solves the bounds' check (default: UNBOUNDED, from the cold start; from the solve's coarse stage: WarmChecked;
        a path's checks: seeded.CheckPath)."""
        if not self.bounded:
            return solution
        with np.errstate(**RUN_AWAY_ARITHMETIC):
            return with_error_bounds(solution, point, lubricant, settings, check or UNBOUNDED, coarse)

    def needs_retry(self, solution: PointSolution) -> bool:
        """The policy has a next attempt for this one (retry.RetryPolicy.next_attempt)."""
        return POLICY.next_attempt(solution) is not None

    def with_retry(self, first: PointSolution, retry: PointSolution) -> PointSolution:
        """The last retry's solution if it did better than the first attempt (RetryPolicy.better); else the first
        attempt's, with the time and count of all attempts, what the retries did in its record and where its film
        closed on the finest grid an attempt reached (RetryPolicy.closure_place)."""
        if POLICY.better(first, retry):
            return retry
        last = RetryRecord(POLICY.reason(retry), Action.FIRST_KEPT, int(retry.scalar("attempts")),
                           f"attempt {int(retry.scalar('attempts'))}: {retry.message}")
        record = replace(retry.record, stages=first.record.stages, attempt=first.record.attempt,
                         relaxation=first.record.relaxation, iteration=first.record.iteration,
                         notes=first.record.notes).with_retry(last)
        return replace(first, scalars={**first.scalars, **POLICY.closure_place(first, retry),
                                       **spent_on(retry).scalars(), "attempts": retry.scalars["attempts"]},
                       models={**first.models, "solver": record.render()}, record=record)


STAGED = StagedSolver()
UNBOUNDED = StagedSolver(bounded=False)  # the solver of the error bounds' checks


@dataclass(frozen=True)
class WarmChecked:
    """The error bounds' check solve started from the solved point's coarse stage (y_check.WarmCheck), unbounded; one
    that the retry policy would retry is solved again cold by UNBOUNDED, with all its retries."""

    start: CoarseStart

    def __call__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
        with np.errstate(**RUN_AWAY_ARITHMETIC):
            begun = WarmCheck(point, lubricant, settings, self.start).begin()
        solution = _completed(UNBOUNDED, begun)
        return UNBOUNDED(point, lubricant, settings) if UNBOUNDED.needs_retry(solution) else solution


def solve_point(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
    """Solve the EHL problem of one contact point (thermal model and rheology as the settings say), retrying a
    solve that runs away or stalls as retry.POLICY says."""
    return STAGED(point, lubricant, settings)
