"""Running a case: contact points from the case, one EHL solve per point, a `RunResult` (the Python API
behind `tehl run`, for notebooks and scripts)."""

from __future__ import annotations

from dataclasses import replace
import math
from typing import Sequence

from facegear_tehl.case import Case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.heat_budget import heat_budget
from facegear_tehl.parallel import Progress, Solver, SolveTask, StagedSolver, solve_all
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.results import RunResult
from facegear_tehl.solution import PointSolution


def ehl_solver() -> StagedSolver:
    """The EHL solver (imported on first use: its Numba kernels are only needed once the input is checked)."""
    from facegear_tehl.ehl.solve import STAGED

    return STAGED


def run_case(
    case: Case,
    *,
    grid: int | None = None,
    points: Sequence[str] | None = None,
    progress: Progress | None = None,
    jobs: int | None = None,
    solver: Solver | StagedSolver | None = None,
) -> RunResult:
    """Solve the contact points of `case` (all, or those named in `points`), optionally on another grid.

    The points are independent: they are solved on up to `jobs` worker processes (None: all cores; 1: in
    this process). `progress` sees them in the order they finish; the result holds them in the case's
    order, with arrays bit-identical to a serial run. A point whose solve raises an error is recorded as
    failed (the error as message) and the remaining points are still solved. Bad `grid`, `points` or `jobs`
    raise CaseError. `solver`: the EHL solver unless a stand-in is given.
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
    solved, failed = solve_all(tasks, solver or ehl_solver(), jobs=jobs, progress=progress)
    solutions, heat_table = heat_budget(selected, [_with_path_coordinate(s, p) for s, p in zip(solved, selected)],
                                        case.lubricant)
    return RunResult(
        case=case,
        points=tuple(solutions),
        heat=heat_table,
        failed=tuple(selected[index].name for index in failed),
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
