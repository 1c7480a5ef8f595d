"""The error bounds' y-check started from the solve's coarse stage (ehl/y_check.py): it solves the same discrete
problem as the check from the Hertz pressure (a converged solution does not depend on its start), so its figures
agree with that cold check's to the size of the loop's own tolerance; and it runs on the check's grid alone (no
full-multigrid start, no coarse stage of its own), in fewer outer iterations."""

from dataclasses import replace
from pathlib import Path

import pytest

from facegear_tehl.case import load_case
from facegear_tehl.ehl.staged import UNBOUNDED, WarmChecked
from facegear_tehl.ehl.y_check import CoarseStart
from facegear_tehl.points import contact_analysis
from facegear_tehl.record import Stage
from facegear_tehl.solution import Outcome

CASE = Path(__file__).resolve().parent.parent / "cases" / "facegear_110.yaml"


@pytest.fixture(scope="module")
def s5_begun():
    """S5 of the default case, thermal full on 257 x 33 asked (513 x 33 solved: seed, coarse and finest stages),
    begun up to its coarse stage."""
    case = load_case(CASE)
    point = next(p for p in contact_analysis(case).points if p.name == "S5")
    settings = replace(case.solver, grid=257, grid_y=33)
    return point, case.lubricant, settings, UNBOUNDED.begin(point, case.lubricant, settings)


def test_the_warm_check_solves_the_cold_checks_problem_on_its_grid_alone(s5_begun):
    point, lubricant, settings, begun = s5_begun
    start = CoarseStart.of(begun)
    assert start is not None and start.pressure.shape == (33, 257)
    solution = UNBOUNDED.finish(begun)
    x, y = solution.axes["x"].values, solution.axes["y"].values
    a, b = solution.scalar("a"), solution.scalar("b")
    check = replace(settings, grid=257, grid_y=17, domain_x=(x[0] / b, x[-1] / b), domain_y=(y[0] / a, y[-1] / a),
                    outlet_refinement="never")
    warm, cold = WarmChecked(start)(point, lubricant, check), UNBOUNDED(point, lubricant, check)
    assert warm.outcome is Outcome.CONVERGED and cold.outcome is Outcome.CONVERGED
    assert [s.stage for s in warm.record.stages] == [Stage.FINEST]
    assert Stage.START in [s.stage for s in cold.record.stages]
    # both loops stop on a last change below the thermal tolerance (of the rise): what each leaves is of its size
    for name in ("h_c", "h_min", "dT_max", "mu"):
        assert abs(warm.scalar(name) / cold.scalar(name) - 1.0) <= settings.thermal_tolerance, name
    assert warm.history["thermal_change_history"].values.size < cold.history["thermal_change_history"].values.size
