"""Running a case: contact points from the case, one EHL solve per point, a `RunResult` (the Python API
behind `tehl run`, for notebooks and scripts)."""

from __future__ import annotations

from dataclasses import dataclass, replace
import math
from typing import Sequence

from facegear_tehl.accuracy_target import solve_to_accuracy, three_grid_checked
from facegear_tehl.case import Case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.cycle import MeshCycle, mesh_cycle, with_film_parameter
from facegear_tehl.ehl.closure import closed_on_the_centre_line, unresolvable
from facegear_tehl.ehl.domain import inlet_note, side_note, solution_domain
from facegear_tehl.ehl.retry import POLICY, estimates
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.ehl.stopwatch import Spent, spent_on
from facegear_tehl.ehl.tuning import TUNING, convergence_bands
from facegear_tehl.heat_budget import heat_budget
from facegear_tehl.parallel import PathSolver, Progress, Solver, SolveTask, StagedSolver, solve_all
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.record import Action, Reason, RetryRecord, SolveRecord
from facegear_tehl.results import RunResult
from facegear_tehl.settings import SolverSettings, ThermalMode
from facegear_tehl.solution import Outcome, PointSolution


def ehl_solver() -> StagedSolver:
    """The EHL solver (imported on first use: its Numba kernels are only needed once the input is checked)."""
    from facegear_tehl.ehl.staged import STAGED

    return STAGED


def ehl_checks() -> StagedSolver:
    """The EHL solver without error bounds: the accuracy target's model checks read only their figures."""
    from facegear_tehl.ehl.staged import UNBOUNDED

    return UNBOUNDED


def ehl_refining() -> Solver:
    """The EHL solver of the accuracy target: each finer grid of a point seeded from its coarser converged solve (a
    new one per run: it keeps the seeds of the points it solved)."""
    from facegear_tehl.ehl.seeded import SeededRefinement

    return SeededRefinement()


def solved_to_accuracy(tasks: Sequence[SolveTask], solver: Solver | StagedSolver | None, jobs: int | None,
                        progress: Progress | None) -> list[PointSolution]:
    """The tasks solved to their accuracy target, by the EHL solver seeding each finer grid from the coarser one
    (`ehl_refining`) and the model checks by the EHL solver without error bounds, unless a stand-in `solver` is given
    (it solves them too)."""
    checks = None if solver else ehl_checks()
    return solve_to_accuracy(tasks, solver or ehl_refining(), checks=checks, jobs=jobs, progress=progress)


def path_solver(case: Case) -> StagedSolver | PathSolver:
    """The EHL solver for the points of `case`: by continuation along the path (PathSolver over ehl.seeded.solve_path,
    chunks of continuation_chunk points) for a thermal face gear case of evenly spaced points (`gear.points: n`,
    neighbours close enough to seed each other); else point by point (ehl_solver)."""
    if case.gear is None or not isinstance(case.gear.points, int) or case.solver.thermal == ThermalMode.OFF:
        return ehl_solver()
    from facegear_tehl.ehl.seeded import solve_path

    return PathSolver(solve_path, TUNING.continuation_chunk)


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
    if case.solver.accuracy is None:
        solver = solver or (path_solver(case) if points is None else ehl_solver())
        solved, failed, refined = solve_refining(tasks, solver, jobs=jobs, progress=progress)
    else:  # the grid and models the accuracy target chooses, each point's record holding them
        solved, refined = solved_to_accuracy(tasks, solver, jobs, progress), {}
        failed = tuple(i for i, s in enumerate(solved) if s.outcome is Outcome.FAILED)
        overrides["accuracy"] = case.solver.accuracy
    by_name = {s.name: s for s in solved}
    warnings = analysis.warnings + tuple(refinement_note(name, refinement, by_name[name])
                                         for name, refinement in refined.items()) + _model_notes(tasks, solved)
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
        convergence_bands=convergence_bands(),
    )


def _model_notes(tasks: Sequence[SolveTask], solved: Sequence[PointSolution]) -> tuple[str, ...]:
    """Warnings on the converged solves whose film is not the one their error bounds stand for: an inlet short of its
    target (domain.inlet_note: where the solver chose the domain, or starved beyond the bounds where the case gave
    it), sides short of theirs (domain.side_note)."""
    notes = [inlet_note(s.name, s.scalar("inlet_gap_ratio"), chosen=task.settings.domain_x is None)
              for task, s in zip(tasks, solved) if s.converged and "inlet_gap_ratio" in s.scalars]
    notes += [side_note(s.name, s.scalar("side_pressure_ratio")) for s in solved
              if s.converged and "side_pressure_ratio" in s.scalars]
    return tuple(note for note in notes if note)


@dataclass(frozen=True)
class Refinement:
    """What the solver did about a point whose grid asked for did not resolve its film (grids as "nx x ny")."""

    asked: str  # the grid asked for
    grid: str  # the grid of the reported solution
    reason: str  # why a converged solve was not enough ("" for a solve that failed: `_coarse_reason`)
    tried: str = ""  # a finer grid whose solve did not converge, the coarser converged solution kept ("" if none)
    outcome: str = ""  # how the solve on `tried` ended
    stopped: str = ""  # the finer grid not started: it would have passed the point's time budget ("" if none)
    unresolvable: str = ""  # why no grid within the caps opens its closed film (closure.Unresolvable; "" if not so)


def solve_refining(tasks: Sequence[SolveTask], solver: Solver | StagedSolver | PathSolver, *, jobs: int | None = None,
                   progress: Progress | None = None
                   ) -> tuple[list[PointSolution], tuple[int, ...], dict[str, Refinement]]:
    """`parallel.solve_all`, then every point whose grid could not resolve its film (RetryPolicy.unresolved, or
    converged with an error estimate above coarse_estimate, RetryPolicy.coarse, unless asked on a trial grid) solved
    again on grids twice as fine until it can, the grid would pass the largest refined grid or the time budget, or
    its film closed where no grid within the caps resolves the film predicted (`_closed_for_good`). A finer solve
    that does not converge after a converged one ends the refinement of that point with the converged one; one that
    converges after a converged one has its bounds checked against it where it is the third grid
    (accuracy_target.three_grid_checked). Returns the solutions in task order (a refined point's wall time counts
    its coarser attempts), the indices of those that raised, and per refined point what the solver did."""
    tasks = list(tasks)
    solved, failed = solve_all(tasks, solver, jobs=jobs, progress=progress)
    refined: dict[str, Refinement] = {}
    asked = {task.point.name: _shape(task.settings) for task in tasks}
    # points whose converged solution stays as it is: asked on a trial grid, or a finer grid failed after it
    kept = {i for i, task in enumerate(tasks) if task.settings.grid < TUNING.min_lengthened_nodes}
    closed_for_good: set[int] = set()  # points whose closed film no grid within the caps opens (`_closed_for_good`)
    while True:
        next_grids = {i: _next_grid(tasks[i], s) for i, s in enumerate(solved)
                      if (POLICY.unresolved(s) or (POLICY.coarse(s) and i not in kept)) and i not in closed_for_good}
        for i, name in [(i, tasks[i].point.name) for i in next_grids]:  # a closed film no grid opens stays closed
            stop = _closed_for_good(tasks[i], solved[i], refined.get(name, Refinement(asked[name], asked[name], "")))
            if stop is not None:
                (solved[i], refined[name]), _ = stop, next_grids.pop(i)
                closed_for_good.add(i)
        for i in [i for i, settings in next_grids.items() if settings is not None and _over_budget(tasks[i], settings,
                                                                                                   solved[i])]:
            name = tasks[i].point.name
            first = refined.get(name, Refinement(asked[name], asked[name], _coarse_reason(solved[i])))
            refined[name] = replace(first, stopped=_shape(next_grids.pop(i)))
            kept.add(i)
            solved[i] = _budget_spent(tasks[i], solved[i], refined[name])
        closed = [i for i, settings in next_grids.items() if settings is not None]
        if not closed:
            return solved, failed, refined
        finer = [replace(tasks[i], settings=next_grids[i]) for i in closed]
        # the refined points are not neighbours on the path: each from its own start
        again, _ = solve_all(finer, ehl_solver() if isinstance(solver, PathSolver) else solver, jobs=jobs,
                             progress=progress)
        for i, task, solution in zip(closed, finer, again):
            name, previous = task.point.name, solved[i]
            first = refined.get(name, Refinement(asked[name], asked[name], _coarse_reason(previous)))
            spent = spent_on(previous) + spent_on(solution)
            if previous.converged and not solution.converged:
                kept.add(i)
                refined[name] = replace(first, tried=_shape(task.settings), outcome=solution.outcome.value)
                solved[i] = _kept_coarser(previous, refined[name], spent)
                continue
            tasks[i] = task
            refined[name] = replace(first, grid=_shape(task.settings))
            if previous.converged:  # the grid refined from: the third grid of the finer solve's x-estimates
                solution = three_grid_checked(previous, solution, task.lubricant.inlet_temperature)
            reason = Reason.COARSE_ESTIMATE if first.reason else Reason.UNRESOLVED
            why = f": {first.reason}" if first.reason else ""
            detail = f"{asked[name]}{why}; {_shape(task.settings)} chosen by the solver"
            earlier = () if previous.record is None else tuple(
                r for r in previous.record.retries if r.action is Action.FINER_GRID)  # this point's refinement so far
            solved[i] = _noted(solution, RetryRecord(reason, Action.FINER_GRID, 0, detail), earlier,
                               scalars={**solution.scalars, **spent.scalars()})


def _budget_spent(task: SolveTask, solution: PointSolution, refinement: Refinement) -> PointSolution:
    """The solution of a point whose next grid (`refinement.stopped`) would pass its time budget, noted so."""
    reason = Reason.UNRESOLVED if POLICY.unresolved(solution) else Reason.COARSE_ESTIMATE
    return _noted(solution, RetryRecord(reason, Action.BUDGET_SPENT, 0, f"{refinement.stopped}: time budget "
                                                                      f"{task.settings.time_budget:g} s"))


def _closed_for_good(task: SolveTask, solution: PointSolution,
                     refinement: Refinement) -> tuple[PointSolution, Refinement] | None:
    """A point whose film closed where no grid within the caps resolves the film Hamrock & Dowson predict
    (closure.unresolvable): the solution with why in its message and record, and the refinement with it; else None."""
    if solution.outcome is not Outcome.FILM_CLOSED or not closed_on_the_centre_line(solution, task.point,
                                                                                   task.lubricant):
        return None
    found = unresolvable(task.point, task.lubricant, task.settings, POLICY.largest_grid(solution))
    if found is None:
        return None
    retry = RetryRecord(Reason.FILM_CLOSED, Action.NOT_RESOLVABLE, 0, found.words())
    return (_noted(solution, retry, message=f"{solution.message}; {found.words()}"),
            replace(refinement, unresolvable=found.words()))


def _kept_coarser(previous: PointSolution, refinement: Refinement, spent: Spent) -> PointSolution:
    """The converged coarser solution after a finer grid did not converge, noted in its message and record."""
    note = (f"grid {refinement.tried} tried by the solver ended {refinement.outcome}; the result is the "
            f"converged {refinement.grid} solution" + (f" ({_coarse_reason(previous)})" if POLICY.coarse(previous)
                                                       else ""))
    retry = RetryRecord(Reason.FINER_GRID_FAILED, Action.KEPT_COARSER, 0,
                        f"{refinement.tried} ended {refinement.outcome}")
    return _noted(previous, retry, message=note, scalars={**previous.scalars, **spent.scalars()})


def _noted(solution: PointSolution, retry: RetryRecord, earlier: tuple[RetryRecord, ...] = (),
           **changes: object) -> PointSolution:
    """`solution` with the `earlier` retries and `retry` in its record (a new record for a stand-in solver's solution
    without one; the models' solver words rendered again) and `changes`."""
    record = solution.record or SolveRecord()
    for each in (*earlier, retry):
        record = record.with_retry(each)
    return replace(solution, record=record, models={**solution.models, "solver": record.render()}, **changes)


def _over_budget(task: SolveTask, finer: SolverSettings, solution: PointSolution) -> bool:
    """Solving the point on `finer` would pass its time budget: the CPU time spent on it so far (s; ehl/stopwatch.py)
    and that time again times the ratio of the finer grid's nodes to the last one's (multigrid work grows with the
    nodes) exceed `solver.time_budget`."""
    spent = spent_on(solution).cpu
    ratio = (finer.grid * finer.nodes_y) / (task.settings.grid * task.settings.nodes_y)
    return spent * (1.0 + ratio) > task.settings.time_budget


def refinement_note(name: str, refinement: Refinement, solution: PointSolution) -> str:
    """What the solver did about a grid that did not resolve the film of point `name`, and how it ended."""
    if refinement.unresolvable:
        done = f"not refined: {refinement.unresolvable}; the result is the {refinement.grid} solution, " \
               f"{solution.outcome.value}"
    elif refinement.stopped:
        done = (f"{refinement.stopped} not started: it would have passed the point's time budget "
                f"(solver.time_budget); the result is the {refinement.grid} solution, {solution.outcome.value}")
    elif refinement.tried:
        done = f"{refinement.tried} ended {refinement.outcome}; the result is the converged {refinement.grid} solution"
    elif POLICY.unresolved(solution):
        done = f"finer grids up to {refinement.grid} did not resolve it either ({solution.outcome.value})"
    else:
        done = f"solved on {refinement.grid}"
    if POLICY.coarse(solution):
        done += f", {_coarse_reason(solution)}"
    why = f" ({refinement.reason})" if refinement.reason else ""
    return f"{name}: the {refinement.asked} grid did not resolve the film{why}; {done} (chosen by the solver)"


def _coarse_reason(solution: PointSolution) -> str:
    """The error estimates of a converged solve, against coarse_estimate, or that it has none after a load
    continuation ("" for a solve that did not converge)."""
    if not solution.converged:
        return ""
    if POLICY.unestimated(solution):
        return "converged from a load continuation raised on its finest grid, without an error estimate"
    h_c, h_min = (100 * e for e in estimates(solution))
    bound = 100 * TUNING.coarse_estimate
    return f"converged with h_c estimated {h_c:.2g} % and h_min {h_min:.2g} % off, bound {bound:.0f} %"


def _next_grid(task: SolveTask, solution: PointSolution) -> SolverSettings | None:
    """RetryPolicy.finer_settings of the task, unless the nodes its solve would have (the inlet lengthened at their
    spacing, ehl.domain) pass the largest refined grid."""
    finer = POLICY.finer_settings(task.settings, solution)
    if finer is None:
        return None
    domain = solution_domain(scaling_for(task.point, task.lubricant), finer)
    return finer if max(domain.nx, domain.ny) <= POLICY.largest_grid(solution) else None


def _shape(settings: SolverSettings) -> str:
    return f"{settings.grid} x {settings.nodes_y}"


def _with_path_coordinate(solution: PointSolution, point: ContactPoint) -> PointSolution:
    """Adds the point's place s on the contact path (gear cases) to its scalars, for plots along the path."""
    if math.isnan(point.path_coordinate) or "path_coordinate" in solution.scalars:
        return solution
    return replace(solution, scalars={**solution.scalars, "path_coordinate": (point.path_coordinate, "m")})
