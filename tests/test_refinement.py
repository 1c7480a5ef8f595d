"""The run's refinement policy (run.solve_refining): a converged point whose own error estimate of h_min or h_c
exceeds run.COARSE_ESTIMATE is solved again on the next grid, the finer result kept if it converges, else the
coarser converged one with the reason; what the solver chose is in the run's warnings, the point's message and
models and the overrides. The policy's unit behaviour runs on a stand-in solver; a real contact shows that the
refined film is the better one."""

from __future__ import annotations

from dataclasses import replace

import pytest

from facegear_tehl.parallel import SolveTask
from facegear_tehl.points import contact_analysis
from facegear_tehl.run import COARSE_ESTIMATE, refinement_note, solve_refining
from facegear_tehl.solution import Outcome, PointSolution

import synthetic


def _task(grid: int = 33) -> SolveTask:
    case = synthetic.ball_on_disc()
    settings = replace(case.solver, grid=grid, grid_y=grid)
    return SolveTask(contact_analysis(case).points[0], case.lubricant, settings)


class StandIn:
    """A solver whose outcome and h_min estimate depend on the grid: {nx: (outcome, estimate of h_min)}."""

    def __init__(self, by_grid: dict[int, tuple[Outcome, float]]):
        self.by_grid, self.grids = by_grid, []

    def __call__(self, point, lubricant, settings) -> PointSolution:
        self.grids.append(settings.grid)
        outcome, estimate = self.by_grid[settings.grid]
        solution = synthetic.solution(point, nx=settings.grid, ny=settings.nodes_y)
        message = "" if outcome is Outcome.CONVERGED else "not converged after 40 cycles"
        return replace(solution, outcome=outcome, message=message, scalars={
            **solution.scalars, "grid": (settings.grid, "1"), "grid_y": (settings.nodes_y, "1"),
            "error_estimate_h_c": (0.01, "1"), "error_estimate_h_min": (estimate, "1"), "wall_time": (1.0, "s")})


def test_a_converged_point_within_the_bound_is_left_alone():
    solver = StandIn({33: (Outcome.CONVERGED, 0.5 * COARSE_ESTIMATE)})
    solved, failed, refined = solve_refining([_task()], solver, jobs=1)
    assert solver.grids == [33] and refined == {} and failed == ()
    assert solved[0].message == ""


def test_a_converged_point_beyond_the_bound_is_solved_again_until_within_it():
    solver = StandIn({33: (Outcome.CONVERGED, 2.6), 65: (Outcome.CONVERGED, -0.14), 129: (Outcome.CONVERGED, 0.04),
                      257: (Outcome.CONVERGED, 0.0)})
    (solution,), _, refined = solve_refining([_task()], solver, jobs=1)
    assert solver.grids == [33, 65, 129]
    assert solution.scalar("grid") == 129 and solution.converged and solution.message == ""
    assert solution.scalar("wall_time") == 3.0  # all grids counted
    refinement = refined["contact"]
    assert (refinement.asked, refinement.grid, refinement.tried) == ("33 x 33", "129 x 129", "")
    note = refinement_note("contact", refinement, solution)
    assert note == ("contact: the 33 x 33 grid did not resolve the film (converged with h_c estimated 1 % and h_min "
                    "2.6e+02 % off, bound 10 %); solved on 129 x 129 (chosen by the solver)")
    assert "grid 129 x 129 chosen by the solver (33 x 33 did not resolve the film: converged with" in \
        solution.models["solver"]


@pytest.mark.parametrize("outcome", [Outcome.NOT_CONVERGED, Outcome.DIVERGED, Outcome.FILM_CLOSED])
def test_the_coarser_converged_point_is_kept_when_the_finer_grid_fails(outcome):
    solver = StandIn({33: (Outcome.CONVERGED, 0.3), 65: (Outcome.CONVERGED, 0.2), 129: (outcome, 0.01)})
    (solution,), _, refined = solve_refining([_task()], solver, jobs=1)
    assert solver.grids == [33, 65, 129]  # 129 failed: the refinement of this point ends there
    assert solution.converged and solution.scalar("grid") == 65 and solution.scalar("wall_time") == 3.0
    assert solution.message == (f"grid 129 x 129 tried by the solver ended {outcome.value}; the result is the "
                                "converged 65 x 65 solution (converged with h_c estimated 1 % and h_min 20 % off, "
                                "bound 10 %)")
    assert solution.message in solution.models["solver"]
    refinement = refined["contact"]
    assert (refinement.grid, refinement.tried, refinement.outcome) == ("65 x 65", "129 x 129", outcome.value)
    assert refinement_note("contact", refinement, solution).endswith(
        f"129 x 129 ended {outcome.value}; the result is the converged 65 x 65 solution, converged with h_c "
        "estimated 1 % and h_min 20 % off, bound 10 % (chosen by the solver)")


def test_the_asked_grid_is_kept_when_its_first_refinement_fails():
    solver = StandIn({33: (Outcome.CONVERGED, 0.3), 65: (Outcome.DIVERGED, 0.0)})
    (solution,), _, refined = solve_refining([_task()], solver, jobs=1)
    assert solver.grids == [33, 65] and solution.converged and solution.scalar("grid") == 33
    assert refined["contact"].grid == "33 x 33" and refined["contact"].tried == "65 x 65"


def test_a_point_that_fails_is_refined_as_before_and_then_held_to_the_bound():
    """A failure goes to the next grid (run._unresolved); once converged there, the bound applies as to any."""
    solver = StandIn({33: (Outcome.DIVERGED, 0.0), 65: (Outcome.CONVERGED, 0.5), 129: (Outcome.NOT_CONVERGED, 0.5)})
    solver.by_grid[33] = (Outcome.FILM_CLOSED, 0.0)
    (solution,), _, refined = solve_refining([_task()], _Closing(solver), jobs=1)
    assert solver.grids == [33, 65, 129]
    assert solution.converged and solution.scalar("grid") == 65
    note = refinement_note("contact", refined["contact"], solution)
    assert note.startswith("contact: the 33 x 33 grid did not resolve the film; 129 x 129 ended not converged; "
                           "the result is the converged 65 x 65 solution, converged with h_c estimated 1 % and h_min "
                           "50 % off")


class _Closing:
    """The stand-in, with no film reported where it closes (as the EHL solver reports a closed film)."""

    def __init__(self, solver: StandIn):
        self.solver = solver

    def __call__(self, point, lubricant, settings) -> PointSolution:
        solution = self.solver(point, lubricant, settings)
        if solution.outcome is Outcome.FILM_CLOSED:
            scalars = {k: v for k, v in solution.scalars.items() if k not in ("h_min", "h_c")}
            solution = replace(solution, scalars=scalars)
        return solution
