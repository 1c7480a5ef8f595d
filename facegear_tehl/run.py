"""Running a case: contact points from the case, one EHL solve per point, a `RunResult` (the Python API
behind `tehl run`, for notebooks and scripts)."""

from __future__ import annotations

from typing import Callable, Sequence

from facegear_tehl.case import Case
from facegear_tehl.ehl.solve import solve_point
from facegear_tehl.points import contact_points, select_points
from facegear_tehl.results import RunResult
from facegear_tehl.solution import PointSolution

Progress = Callable[[PointSolution, int, int], None]
"""Called after each point with (solution, points done, points in the run)."""


def run_case(
    case: Case,
    *,
    grid: int | None = None,
    points: Sequence[str] | None = None,
    progress: Progress | None = None,
) -> RunResult:
    """Solve the contact points of `case` (all, or those named in `points`), optionally on another grid.

    A point whose solve raises an error is recorded as failed (converged = False, the error as message)
    and the remaining points are still solved. Bad `grid` or `points` raise CaseError.
    """
    overrides: dict[str, object] = {}
    if grid is not None:
        case = case.with_grid(grid)
        overrides["grid"] = grid
    selected = contact_points(case)
    if points is not None:
        selected = select_points(selected, points)
        overrides["points"] = [p.name for p in selected]
    solutions: list[PointSolution] = []
    failed: list[str] = []
    for done, point in enumerate(selected, start=1):
        try:
            solution = solve_point(point, case.lubricant, case.solver)
        except Exception as exc:  # one failing point must not lose the others; the error is recorded
            solution = PointSolution(
                name=point.name,
                converged=False,
                message=f"failed: {type(exc).__name__}: {exc}",
                scalars={},
                fields={},
                axes={},
            )
            failed.append(point.name)
        solutions.append(solution)
        if progress is not None:
            progress(solution, done, len(selected))
    return RunResult(case=case, points=tuple(solutions), failed=tuple(failed), overrides=overrides)
