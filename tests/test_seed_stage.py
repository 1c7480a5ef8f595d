"""The seed stage of a `full` thermal solve (solve.PointSolve._seed_stage) evaluates a film state on a converged
isothermal pressure only: the typed status of its pressure cycles decides, not a message."""

from __future__ import annotations

import dataclasses

from facegear_tehl.case import load_case
from facegear_tehl.ehl import solve
from facegear_tehl.points import contact_analysis
from facegear_tehl.record import Reason
from facegear_tehl.settings import ThermalMode
from facegear_tehl.solution import Outcome


def test_a_seed_stage_whose_pressure_does_not_converge_evaluates_no_film_state(monkeypatch):
    """S1 of the default case on 513 x 65 (`full`: a seed stage on 129 x 65) with one pressure cycle allowed and a
    tolerance no cycle meets: the seed stage's isothermal pressure ends NOT_CONVERGED, so no film state is evaluated
    on its grid (a film state on an unconverged pressure was the first step of w10's runaway, docs/envelope.md); the
    stage is dropped with Reason.SEED_NOT_CONVERGED and the solver begun again from the coarsest grid."""
    case = load_case("cases/facegear_110.yaml")
    point = next(p for p in contact_analysis(case).points if p.name == "S1")
    settings = dataclasses.replace(case.solver, thermal=ThermalMode.FULL, max_cycles=1, tolerance=1e-12,
                                   load_tolerance=1e-12)
    coupled_on = []

    def recorded(self, index, *args, **kwargs):
        coupled_on.append(self.solver.levels[index].nx)
        return None, solve.Status(Outcome.DIVERGED, "not reached")

    monkeypatch.setattr(solve.PointSolve, "couple", recorded)
    point_solve = solve.PointSolve(point, case.lubricant, settings)
    assert point_solve.settings.grid == 513 and point_solve.plan.has(solve.Stage.SEED)
    assert point_solve._seed_stage() is None
    assert coupled_on == []
    assert [r.reason for r in point_solve.retries] == [Reason.SEED_NOT_CONVERGED]
    assert len(point_solve.solver.levels[-3].x) == 129  # the hierarchy begun again
