"""Running a case: contact points from the case, one EHL solve per point, a `RunResult` (the Python API
behind `tehl run`, for notebooks and scripts)."""

from __future__ import annotations

from contextlib import closing
from dataclasses import replace
import math
from typing import Callable, Sequence

from facegear_tehl.case import Case
from facegear_tehl.ehl.solve import solve_point
from facegear_tehl.heat_budget import heat_budget
from facegear_tehl.contact import ContactPoint
from facegear_tehl.parallel import SolveTask, solve_each, stages_of
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.results import RunResult
from facegear_tehl.solution import PointSolution

Progress = Callable[[PointSolution, int, int], None]
"""Called as each point finishes with (solution, points done, points in the run)."""


def run_case(
    case: Case,
    *,
    grid: int | None = None,
    points: Sequence[str] | None = None,
    progress: Progress | None = None,
    jobs: int | None = None,
) -> RunResult:
    """Solve the contact points of `case` (all, or those named in `points`), optionally on another grid.

    The points are independent: they are solved on up to `jobs` worker processes (None: all cores; 1: in
    this process). `progress` sees them in the order they finish; the result holds them in the case's
    order, with arrays bit-identical to a serial run. A point whose solve raises an error is recorded as
    failed (converged = False, the error as message) and the remaining points are still solved. Bad
    `grid`, `points` or `jobs` raise CaseError.
    """
    overrides: dict[str, object] = {}
    if grid is not None:
        case = case.with_grid(grid)
        overrides["grid"] = grid
    analysis = contact_analysis(case)
    selected = list(analysis.points)
    if points is not None:
        selected = select_points(selected, points)
        overrides["points"] = [p.name for p in selected]
    tasks = [SolveTask(point, case.lubricant, case.solver) for point in selected]
    solutions: list[PointSolution | None] = [None] * len(tasks)
    failed: set[int] = set()
    # solve_point is looked up here, at call time, so that tests can stand in for the solver.
    # closing: an exception in this loop (Ctrl-C while reporting progress) stops the workers now, not when
    # the generator is collected (the traceback keeps it alive until the interpreter exits)
    with closing(solve_each(tasks, solve=solve_point, jobs=jobs, stages=stages_of(solve_point))) as outcomes:
        for done, (index, outcome) in enumerate(outcomes, start=1):
            solution = _with_path_coordinate(outcome.solution, selected[index])
            solutions[index] = solution
            if outcome.failed:
                failed.add(index)
            if progress is not None:
                progress(solution, done, len(tasks))
    solutions, heat_table = heat_budget(selected, solutions, case.lubricant)
    return RunResult(
        case=case,
        points=tuple(solutions),
        heat=heat_table,
        failed=tuple(selected[index].name for index in sorted(failed)),
        contact=analysis.path,
        contact_scalars=analysis.scalars,
        warnings=analysis.warnings,
        overrides=overrides,
    )


def _with_path_coordinate(solution: PointSolution, point: ContactPoint) -> PointSolution:
    """Adds the point's place s on the contact path (gear cases) to its scalars, for plots along the path."""
    if math.isnan(point.path_coordinate) or "path_coordinate" in solution.scalars:
        return solution
    return replace(solution, scalars={**solution.scalars, "path_coordinate": (point.path_coordinate, "m")})
