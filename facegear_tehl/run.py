"""Running a case: contact points from the case, one EHL solve per point, a `RunResult` (the Python API
behind `tehl run`, for notebooks and scripts)."""

from __future__ import annotations

from dataclasses import replace
import math
from typing import Callable, Sequence

from facegear_tehl.case import Case
from facegear_tehl.ehl.solve import solve_point
from facegear_tehl.contact import ContactPoint
from facegear_tehl.points import contact_analysis, select_points
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
    analysis = contact_analysis(case)
    selected = list(analysis.points)
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
        solution = _with_path_coordinate(solution, point)
        solutions.append(solution)
        if progress is not None:
            progress(solution, done, len(selected))
    return RunResult(
        case=case,
        points=tuple(solutions),
        failed=tuple(failed),
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
