"""Which Gauss-Seidel / Jacobi-distributive switch an attempt relaxes with (retry.RetryPolicy.attempt): Venner's
eps/h^2 > 0.3 (Venner & Lubrecht 2000) first on grids with fewer than venner_first_nodes X nodes across the Hertzian
width 2b, the ellipse-scaled switch first on finer ones; and a level's switch is the solver's current relaxation's,
so that a finest grid solved again with the next attempt's relaxation (staged.finest_again) relaxes with its switch."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from facegear_tehl.case import load_case
from facegear_tehl.ehl.relaxation import Relaxation
from facegear_tehl.ehl.retry import POLICY
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.ehl.staged import UNBOUNDED
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.points import contact_analysis, select_points

ROOT = Path(__file__).resolve().parent.parent
VENNER_SWITCH = 0.3  # eps/h^2 above which a node is relaxed Gauss-Seidel (Venner & Lubrecht 2000, circular contact)


def _case_point(name: str):
    case = load_case(ROOT / "cases" / "facegear_110.yaml")
    return case, select_points(contact_analysis(case).points, [name])[0]


def test_a_levels_switch_is_the_current_relaxations():
    """The finest level of S1 on 257 x 65: the ellipse-scaled switch is Venner's times the level's factor (> 1 for
    an ellipse of a/b ~ 40); with Venner's relaxation set on the same solver, Venner's 0.3 on the same level (a
    switch fixed when the level was made kept the scaled one for an attempt named Venner's)."""
    case, point = _case_point("S1")
    solve = PointSolve(point, case.lubricant, replace(case.solver, grid=257, grid_y=65))
    solver = solve.solver
    level = solver.levels[-1]
    assert solver.relaxation.scale_switch
    assert solver.switch(level) > 10 * VENNER_SWITCH
    solver.relaxation = Relaxation(scale_switch=False)
    assert solver.switch(level) == VENNER_SWITCH


def test_the_first_attempt_follows_the_nodes_across_the_contact():
    """S3 asked on 129 x 33 is solved at an X spacing of 2b/42.7 (fewer than venner_first_nodes across 2b): Venner's
    switch first, the scaled one second; on 257 x 65 (2b/85.3) the scaled switch first, Venner's second; the damped
    attempts do not depend on the grid."""
    case, point = _case_point("S3")
    coarse = PointSolve(point, case.lubricant, replace(case.solver, grid=129, grid_y=33))
    fine = PointSolve(point, case.lubricant, replace(case.solver, grid=257, grid_y=65))
    assert 2.0 / coarse.spacing < TUNING.venner_first_nodes < 2.0 / fine.spacing
    assert not coarse.solver.relaxation.scale_switch and fine.solver.relaxation.scale_switch
    assert POLICY.attempt(2, coarse.spacing).relaxation.scale_switch
    assert not POLICY.attempt(2, fine.spacing).relaxation.scale_switch
    for attempt in (3, 4):
        assert POLICY.attempt(attempt, coarse.spacing) == POLICY.attempt(attempt, fine.spacing)


def test_the_pitch_points_coarse_check_converges_on_its_first_attempt():
    """The error bound's check of the shipped S3 on 129 x 33 (thermal full, Ree-Eyring) is solved on 129 x 17: the
    pitch-point film, cooled as much as heated, whose coupled loop under the ellipse-scaled switch stalled at 4-7 K
    for 40 outer iterations on 129 x 17 and converged only on a retry. Converged on the first attempt, its record
    naming Venner's switch."""
    case, point = _case_point("S3")
    solution = UNBOUNDED(point, case.lubricant, replace(case.solver, grid=129, grid_y=17))
    assert solution.converged, solution.message
    assert solution.scalar("attempts") == 1
    assert solution.record.relaxation == "Venner's switch"


def test_the_finest_grid_again_never_repeats_the_failed_relaxation():
    """A finest grid that ran away after a converged coarse stage is solved again from that stage with a relaxation
    other than the one it failed with: the same relaxation from the same state repeats the same (deterministic)
    iteration. After the undamped attempts, whichever grid and switch, that is the damped one on the kept switch,
    numbered as the damped attempt; after the damped attempt of a light contact (no load continuation), none."""
    from facegear_tehl.record import SolveRecord, Stage, StageRecord
    from facegear_tehl.solution import Outcome, PointSolution

    def ran_away(attempt: int) -> PointSolution:
        stages = (StageRecord(Stage.COARSE, 129, 33, 10, 5, Outcome.CONVERGED, 0.1),
                  StageRecord(Stage.FINEST, 257, 65, 3, 1, Outcome.DIVERGED, 0.1))
        return PointSolution("S3", Outcome.DIVERGED, "diverged", {"attempts": (attempt, "-"), "moes_m": (100.0, "-")},
                             {}, {}, record=SolveRecord(stages=stages, attempt=attempt))

    for spacing in (2.0 / 42.7, 2.0 / 85.3):  # either side of venner_first_nodes
        for attempt in (1, 2):
            for switch in (True, False):  # the coarse stage's, kept
                failed = replace(POLICY.attempt(attempt, spacing).relaxation, scale_switch=switch)
                again = POLICY.finest_again(ran_away(attempt), failed, spacing)
                assert again is not None
                number, relaxation = again
                assert relaxation != failed and relaxation.scale_switch == switch
                assert number == TUNING.damped_attempt
                assert relaxation.under_gs < failed.under_gs
        damped = POLICY.attempt(TUNING.damped_attempt, spacing).relaxation
        assert POLICY.finest_again(ran_away(TUNING.damped_attempt), damped, spacing) is None
