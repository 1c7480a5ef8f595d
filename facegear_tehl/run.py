"""Running a case: contact points from the case, one EHL solve per point, a `RunResult` (the Python API
behind `tehl run`, for notebooks and scripts)."""

from __future__ import annotations

from dataclasses import dataclass, replace
import math
from typing import Sequence

from facegear_tehl.case import Case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.cycle import MeshCycle, mesh_cycle, with_film_parameter
from facegear_tehl.ehl.domain import MIN_LENGTHENED_NODES, solution_domain
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.heat_budget import heat_budget
from facegear_tehl.parallel import Progress, Solver, SolveTask, StagedSolver, solve_all
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.results import RunResult
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import Outcome, PointSolution

# A film too thin for the grid it was asked on closes there (h_min <= 0), or the solve stalls with an h_min
# whose own error estimate exceeds UNRESOLVED_H_MIN: the point is solved again on a finer grid, up to
# MAX_REFINED_GRID nodes along either axis (the hard cases of Moes M = 5000 close their film on 129^2 and
# 257^2, or stall there with h_min = 7 nm estimated 46 % off, and converge on 513^2; a 1025 x 1025 solve takes
# about a minute here). Stalled thermal loops estimate their h_min within 0.1-0.4 %: they are not refined.
MAX_REFINED_GRID = 1025
# A thermal point is refined up to 513 nodes along either axis: in the operating-envelope suite (97 contacts) no
# thermal point that 513 nodes left unresolved converged on 1025, and each such attempt cost 2-6 minutes here
# (a/b = 30, 1.5 GPa, 0.5 m/s, SRR 0.5: 495 s in all up to 1025 x 1025).
MAX_REFINED_THERMAL_GRID = 513
UNRESOLVED_H_MIN = 0.1
# A converged point whose own error estimate of h_min or h_c (Richardson, from the grid below: ehl.report) exceeds
# COARSE_ESTIMATE is solved again on the next grid as a failure is (`_next_grid`, same caps); the finer solution is
# kept if it converges, else the coarser converged one with the reason. Why 10 %: the estimate is (f_h - f_2h)/3, so
# beyond it the two grids differ by more than 30 %, outside the asymptotic range the estimate assumes (its own
# error is then of its size: a/b = 5, 1.5 GPa, 0.5 m/s estimates 260 % on 257^2 and h_min rises by 38 % to 513^2).
# Below it sit the films the grid asked for resolves (the operating-envelope suite's 0.01-9.6 % on 257 x 65, the
# default face gear case's about 0.1 %): they are left alone. So are trial grids, fewer than MIN_LENGTHENED_NODES
# along x (not lengthened either, ehl.domain): asked for a quick look, their error is expected to be large (the
# default face gear case on 65 x 17: h_c 1.5 % low); they are refined only when they fail.
COARSE_ESTIMATE = 0.1
# Where the film is lowest decides the direction: in the side lobes (|y| > SIDE_LOBE a) the film's narrow
# constriction runs along x and is resolved by rows, so a grid with fewer rows than columns doubles its rows
# alone (an a/b = 5 ellipse at p_h = 1.5 GPa, 0.5 m/s, Moes M = 8.5e3, closes its film at y = 0.94 a on 257 x 65
# and 257 x 129 and converges on 257 x 257; on 513 x 129 it runs away); elsewhere (the outlet constriction and
# the pressure spike along the centre rows) both axes are doubled.
SIDE_LOBE = 0.5


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
    solved, failed, refined = solve_refining(tasks, solver or ehl_solver(), jobs=jobs, progress=progress)
    by_name = {s.name: s for s in solved}
    warnings = analysis.warnings + tuple(refinement_note(name, refinement, by_name[name])
                                         for name, refinement in refined.items())
    if refined:
        overrides["refined_grid"] = {name: refinement.grid for name, refinement in refined.items()}
    solutions, heat_table = heat_budget(selected, [_with_path_coordinate(s, p) for s, p in zip(solved, selected)],
                                        case.lubricant)
    solutions = [with_film_parameter(s, p) for s, p in zip(solutions, selected)]
    cycle = MeshCycle({}, {}, {})
    if case.gear is not None:
        cycle = mesh_cycle(case, selected, solutions, analysis.path, analysis.scalars)
        solutions = [replace(s, scalars={**s.scalars, **cycle.point_scalars.get(s.name, {})}) for s in solutions]
        warnings += cycle.notes
    return RunResult(
        case=case,
        points=tuple(solutions),
        heat=heat_table,
        failed=tuple(selected[index].name for index in failed),
        contact=analysis.path,
        contact_scalars=analysis.scalars,
        cycle=cycle.columns,
        cycle_scalars=cycle.scalars,
        warnings=warnings,
        overrides=overrides,
    )


@dataclass(frozen=True)
class Refinement:
    """What the solver did about a point whose grid asked for did not resolve its film (grids as "nx x ny")."""

    asked: str  # the grid asked for
    grid: str  # the grid of the reported solution
    reason: str  # why a converged solve was not enough ("" for a solve that failed: `_coarse_reason`)
    tried: str = ""  # a finer grid whose solve did not converge, the coarser converged solution kept ("" if none)
    outcome: str = ""  # how the solve on `tried` ended


def solve_refining(tasks: Sequence[SolveTask], solver: Solver | StagedSolver, *, jobs: int | None = None,
                   progress: Progress | None = None
                   ) -> tuple[list[PointSolution], tuple[int, ...], dict[str, Refinement]]:
    """`parallel.solve_all`, then every point whose grid could not resolve its film (`_unresolved`, or converged with
    an error estimate above COARSE_ESTIMATE, `_coarse`, unless asked on a trial grid) solved again on grids twice as
    fine until it can or the grid would pass MAX_REFINED_GRID (a finer grid also lets the retry's start begin on a
    finer coarsest grid). A finer solve that does not converge after a converged one ends the refinement of that
    point with the converged one (the finer outcome in its message). Returns the solutions in task order (a refined
    point's wall time counts its coarser attempts), the indices of those that raised, and per refined point what the
    solver did."""
    tasks = list(tasks)
    solved, failed = solve_all(tasks, solver, jobs=jobs, progress=progress)
    refined: dict[str, Refinement] = {}
    asked = {task.point.name: _shape(task.settings) for task in tasks}
    # points whose converged solution stays as it is: asked on a trial grid, or a finer grid failed after it
    kept = {i for i, task in enumerate(tasks) if task.settings.grid < MIN_LENGTHENED_NODES}
    while True:
        next_grids = {i: _next_grid(tasks[i], s) for i, s in enumerate(solved)
                      if _unresolved(s) or (_coarse(s) and i not in kept)}
        closed = [i for i, settings in next_grids.items() if settings is not None]
        if not closed:
            return solved, failed, refined
        finer = [replace(tasks[i], settings=next_grids[i]) for i in closed]
        again, _ = solve_all(finer, solver, jobs=jobs, progress=progress)
        for i, task, solution in zip(closed, finer, again):
            name, previous = task.point.name, solved[i]
            first = refined.get(name, Refinement(asked[name], asked[name], _coarse_reason(previous)))
            spent = previous.scalars.get("wall_time", (0.0, "s"))[0] + solution.scalars.get("wall_time", (0.0, "s"))[0]
            if previous.converged and not solution.converged:
                kept.add(i)
                refinement = replace(first, tried=_shape(task.settings), outcome=solution.outcome.value)
                note = (f"grid {refinement.tried} tried by the solver ended {refinement.outcome}; the result is the "
                        f"converged {refinement.grid} solution" + (f" ({_coarse_reason(previous)})" if _coarse(previous)
                                                                   else ""))
                solver_note = previous.models.get("solver", "") + "; " + note
                solved[i] = replace(previous, message=note, scalars={**previous.scalars, "wall_time": (spent, "s")},
                                    models={**previous.models, "solver": solver_note})
                refined[name] = refinement
                continue
            tasks[i] = task
            note = (f"grid {_shape(task.settings)} chosen by the solver ({asked[name]} did not resolve the film"
                    + (f": {first.reason})" if first.reason else ")"))
            solved[i] = replace(solution, scalars={**solution.scalars, "wall_time": (spent, "s")},
                                models={**solution.models, "solver": solution.models.get("solver", "") + "; " + note})
            refined[name] = replace(first, grid=_shape(task.settings))


def refinement_note(name: str, refinement: Refinement, solution: PointSolution) -> str:
    """What the solver did about a grid that did not resolve the film of point `name`, and how it ended."""
    if refinement.tried:
        done = f"{refinement.tried} ended {refinement.outcome}; the result is the converged {refinement.grid} solution"
    elif _unresolved(solution):
        done = f"finer grids up to {refinement.grid} did not resolve it either ({solution.outcome.value})"
    else:
        done = f"solved on {refinement.grid}"
    if _coarse(solution):
        done += f", {_coarse_reason(solution)}"
    why = f" ({refinement.reason})" if refinement.reason else ""
    return f"{name}: the {refinement.asked} grid did not resolve the film{why}; {done} (chosen by the solver)"


def _coarse_reason(solution: PointSolution) -> str:
    """The error estimates of a converged solve, against COARSE_ESTIMATE ("" for a solve that did not converge)."""
    if not solution.converged:
        return ""
    h_c, h_min = (100 * e for e in _estimates(solution))
    return f"converged with h_c estimated {h_c:.2g} % and h_min {h_min:.2g} % off, bound {100 * COARSE_ESTIMATE:.0f} %"


def _coarse(solution: PointSolution) -> bool:
    """The solve converged, but estimates its own h_min or h_c error above COARSE_ESTIMATE (NaN: no estimate)."""
    return solution.converged and any(abs(e) > COARSE_ESTIMATE for e in _estimates(solution))


def _estimates(solution: PointSolution) -> tuple[float, float]:
    """The solve's own relative error estimates of h_c and h_min (0 where it has none)."""
    return tuple(solution.scalars.get(f"error_estimate_{key}", (0.0, "1"))[0] for key in ("h_c", "h_min"))


def _unresolved(solution: PointSolution) -> bool:
    """The solve's grid could not resolve its film: no film was reported (it closed, or the solve ran away with
    it closed), or the solve did not converge and estimates its own h_min error above UNRESOLVED_H_MIN."""
    if solution.outcome in (Outcome.FILM_CLOSED, Outcome.DIVERGED) and "h_min" not in solution.scalars:
        return True
    estimate = solution.scalars.get("error_estimate_h_min", (0.0, "1"))[0]
    return solution.outcome is Outcome.NOT_CONVERGED and abs(estimate) > UNRESOLVED_H_MIN


def _next_grid(task: SolveTask, solution: PointSolution) -> SolverSettings | None:
    """`_refined` settings of the task, unless the nodes its solve would have (the inlet lengthened at their spacing,
    ehl.domain) pass the largest refined grid."""
    finer = _refined(task.settings, solution)
    if finer is None:
        return None
    domain = solution_domain(scaling_for(task.point, task.lubricant), finer)
    return finer if max(domain.nx, domain.ny) <= _largest_grid(solution) else None


def _largest_grid(solution: PointSolution) -> int:
    """MAX_REFINED_GRID, or MAX_REFINED_THERMAL_GRID for a thermal solve."""
    return MAX_REFINED_GRID if solution.models.get("thermal", "off") == "off" else MAX_REFINED_THERMAL_GRID


def _refined(settings: SolverSettings, solution: PointSolution) -> SolverSettings | None:
    """The settings on the next finer grid for a film that `solution` did not resolve: twice the rows alone when its
    lowest film lies in the side lobes and the grid has fewer rows than columns, else twice as fine along each
    axis (SIDE_LOBE); None beyond MAX_REFINED_GRID (MAX_REFINED_THERMAL_GRID for a thermal solve)."""
    largest = _largest_grid(solution)
    if _in_side_lobe(solution) and settings.nodes_y < settings.grid and 2 * settings.nodes_y - 1 <= largest:
        return replace(settings, grid_y=2 * settings.nodes_y - 1)
    if 2 * max(settings.grid, settings.nodes_y) - 1 > largest:
        return None
    grid_y = None if settings.grid_y is None else 2 * settings.grid_y - 1
    return replace(settings, grid=2 * settings.grid - 1, grid_y=grid_y)


def _in_side_lobe(solution: PointSolution) -> bool:
    """The lowest film of the solve (or where it closed) lies beyond SIDE_LOBE semi-axes a from the centre line."""
    scalars = solution.scalars
    y = scalars.get("y_h_min", scalars.get("y_film_closed", (math.nan, "m")))[0]
    a = scalars.get("a", (math.nan, "m"))[0]
    return abs(y) > SIDE_LOBE * a


def _shape(settings: SolverSettings) -> str:
    return f"{settings.grid} x {settings.nodes_y}"


def _with_path_coordinate(solution: PointSolution, point: ContactPoint) -> PointSolution:
    """Adds the point's place s on the contact path (gear cases) to its scalars, for plots along the path."""
    if math.isnan(point.path_coordinate) or "path_coordinate" in solution.scalars:
        return solution
    return replace(solution, scalars={**solution.scalars, "path_coordinate": (point.path_coordinate, "m")})
