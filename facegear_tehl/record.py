"""The typed record of a point solve: what was planned, what ran, what was retried and why.

A `SolveRecord` travels with the `PointSolution`, is written to the result file (results.py, /points/<P>/solve) and
shown by `tehl info`. Human sentences are rendered from it (`render`); no decision is ever taken by reading them back.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from enum import Enum

from facegear_tehl.outcome import Outcome


class Stage(Enum):
    """A stage of a point solve (plan.py orders them)."""

    START = "full-multigrid start"  # from the Hertz pressure on the coarsest grid (Venner & Lubrecht 2000)
    SEED = "seed stage"  # the coupled problem two grids below the finest
    COARSE = "coarse stage"  # the coupled problem one grid below the finest
    FINEST = "finest grid"  # the pressure (and the coupled loop) on the finest grid
    OUTLET = "outlet patch"  # a patch at half the x spacing over the outlet spike (outlet.py)
    SEEDED = "seeded start"  # from the solved neighbour on the path, in place of START and SEED (seeded.py)


class Reason(Enum):
    """A typed failure that leads to a retry (retry.py maps each to its next attempt)."""

    RAN_AWAY = "ran away"
    STALLED = "stalled short of its tolerances"
    FILM_CLOSED = "the film closed"
    START_RAN_AWAY = "the full-multigrid start ran away"
    SEED_RAN_AWAY = "the seed stage ran away"
    SEED_FILM_CLOSED = "the seed stage's film closed"
    COARSE_STAGE_RAN_AWAY = "the coarse stage ran away"
    COARSE_STAGE_FILM_CLOSED = "the coarse stage's film closed"
    STAGE_FAILED = "an outlet stage failed"
    UNRESOLVED = "the grid did not resolve the film"
    COARSE_ESTIMATE = "the error estimate exceeds its bound"
    FINER_GRID_FAILED = "a finer grid did not converge"
    SEEDED_START_FAILED = "the solve seeded from its neighbour failed"


class Action(Enum):
    """What the retry policy did about a failure."""

    NEXT_RELAXATION = "solved again with the next relaxation"
    FINER_COARSEST_GRID = "the start begun again from a finer coarsest grid"
    COARSEST_TO_ITS_LOAD = "the start's coarsest grid cycled until it carries its load, the start climbed again"
    COARSEST_GRID_AGAIN = "the coarse stage begun again from the coarsest grid"
    COUPLED_ON_FINEST = "coupled on the finest grid alone from its isothermal solution"
    FINEST_AGAIN = "the finest grid solved again from the converged coarse stage with the next relaxation"
    DROPPED = "dropped: the solution below it is reported"
    MORE_COARSE_CYCLES = "solved again with more V-cycles of the grid below per patch correction"
    STAGES_AGAIN = "back to where the outlet stages began, the stages below it solved again, each to convergence"
    FINER_GRID = "solved again on a finer grid"
    KEPT_COARSER = "the converged coarser solution kept"
    FIRST_KEPT = "no retry did better: the first attempt reported"
    COLD_START = "solved again from the cold start"
    BUDGET_SPENT = "not refined: the next grid would pass the point's time budget, the best solution so far kept"
    NOT_RESOLVABLE = "not refined: no grid within the caps resolves the film the formula predicts"


@dataclass(frozen=True)
class StageRecord:
    """One stage that ran: on which grid (nodes in x, y), its V-cycles on that grid (the full-multigrid start's cycles
    on the grids below it are in its work), outer iterations, how it ended, its wall time (s) and work units; where its
    first entry sits in the reported per-cycle and per-outer-iteration histories (-1: not in them, the history was
    begun again after the stage, or a file without the index)."""

    stage: Stage
    nx: int
    ny: int
    cycles: int
    outer: int
    outcome: Outcome
    seconds: float
    work: float = 0.0  # work units (the finest grid's relaxation sweeps' worth, Venner & Lubrecht 2000)
    first_cycle: int = -1
    first_outer: int = -1


@dataclass(frozen=True)
class RetryRecord:
    """One retry: the typed reason, what was done, on which attempt (1-based) or grid, and the failure's words."""

    reason: Reason
    action: Action
    attempt: int
    detail: str = ""


@dataclass(frozen=True)
class SolveRecord:
    """The record of a point solve: the planned stages (as `plan.SolvePlan.describe` words), the stages that ran, the
    retries with their reasons, the attempt reported and its relaxation, the outcome of the iteration itself
    (before a closed film is reported as such), fixed notes (the domain, the load continuation), and how the error
    bounds' check began (error_bounds.py; a path's checks, seeded.CheckPath): `check_seed` the point whose check
    seeded it ('': none did), `check_attempt` the retry policy's attempt whose relaxation it began with."""

    plan: tuple[str, ...] = ()
    stages: tuple[StageRecord, ...] = ()
    retries: tuple[RetryRecord, ...] = ()
    attempt: int = 1
    relaxation: str = ""
    iteration: Outcome = Outcome.CONVERGED
    notes: tuple[str, ...] = field(default=())
    check_seed: str = ""
    check_attempt: int = 1

    def with_retry(self, retry: RetryRecord) -> SolveRecord:
        return replace(self, retries=self.retries + (retry,))

    def render(self) -> str:
        """The record in words: the method, the notes, then each retry."""
        words = ["FAS multigrid, line GS / Jacobi distributive (Venner & Lubrecht 2000), FFT deflection"]
        words += list(self.notes)
        for retry in self.retries:
            where = f" ({retry.detail})" if retry.detail else ""
            words.append(f"{retry.reason.value}{where}: {retry.action.value}")
        return "; ".join(words)


def record_to_dict(record: SolveRecord) -> dict[str, object]:
    """The record as plain data (enums by their words), for the result file and `tehl info --json`."""
    return {
        "plan": list(record.plan),
        "stages": [{"stage": s.stage.value, "nx": s.nx, "ny": s.ny, "cycles": s.cycles, "outer": s.outer,
                    "outcome": s.outcome.value, "seconds": s.seconds, "work": s.work, "first_cycle": s.first_cycle,
                    "first_outer": s.first_outer} for s in record.stages],
        "retries": [{"reason": r.reason.value, "action": r.action.value, "attempt": r.attempt, "detail": r.detail}
                    for r in record.retries],
        "attempt": record.attempt,
        "relaxation": record.relaxation,
        "iteration": record.iteration.value,
        "notes": list(record.notes),
        "check_seed": record.check_seed,
        "check_attempt": record.check_attempt,
    }


def record_from_dict(data: dict[str, object]) -> SolveRecord:
    """The record from `record_to_dict`'s plain data."""
    stages = tuple(StageRecord(Stage(s["stage"]), int(s["nx"]), int(s["ny"]), int(s["cycles"]), int(s["outer"]),
                               Outcome(s["outcome"]), float(s["seconds"]), float(s.get("work", 0.0)),
                               int(s.get("first_cycle", -1)), int(s.get("first_outer", -1)))
                   for s in data["stages"])
    retries = tuple(RetryRecord(Reason(r["reason"]), Action(r["action"]), int(r["attempt"]), str(r["detail"]))
                    for r in data["retries"])
    return SolveRecord(tuple(data["plan"]), stages, retries, int(data["attempt"]), str(data["relaxation"]),
                       Outcome(data["iteration"]), tuple(data["notes"]), str(data.get("check_seed", "")),
                       int(data.get("check_attempt", 1)))


def record_lines(name: str, record: SolveRecord) -> list[str]:
    """The record of point `name` for `tehl info`: the plan, each stage that ran (grid, V-cycles, outer iterations,
    outcome, wall time), each retry with its reason, and the notes."""
    lines = [f"solve of {name}: attempt {record.attempt} ({record.relaxation}), iteration {record.iteration.value}"]
    lines += [f"  planned  {step}" for step in record.plan]
    lines += [f"  ran      {s.stage.value} on {s.nx} x {s.ny}: {s.cycles} V-cycles, {s.outer} outer iterations, "
              f"{s.work:.1f} work units, {s.outcome.value}, {s.seconds:.2f} s" for s in record.stages]
    lines += [f"  retry    {r.reason.value}" + (f" ({r.detail})" if r.detail else "") + f": {r.action.value}"
              for r in record.retries]
    lines += [f"  note     {note}" for note in record.notes]
    if record.check_seed or record.check_attempt > 1:
        seeded = f"seeded from {record.check_seed}'s check" if record.check_seed else "from its cold start"
        lines.append(f"  check    the error bounds' check {seeded}, begun with attempt {record.check_attempt}")
    return lines
