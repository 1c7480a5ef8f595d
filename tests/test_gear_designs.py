"""The random face gear designs of facegear_tehl/suites/gear_designs.py (run by scripts/gear_designs.py): drawn
inside their ranges, turned into valid cases on their usable face width, speed and torque by hand; a design the
checks reject is a row, not a crash. Nothing is solved here (the suite itself is run by hand: docs/envelope.md)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from facegear_tehl.case import parse_case
from facegear_tehl.schema import CaseError
from facegear_tehl.suites import gear_designs as designs_module

CASE = (Path(__file__).resolve().parents[1] / "cases" / "facegear_110.yaml").read_text()


@pytest.fixture(scope="module")
def designs():
    return designs_module.random_designs(40, 1)


def test_designs_are_drawn_inside_their_ranges_and_repeat_with_the_seed(designs):
    m = designs_module
    assert designs == m.random_designs(40, 1) and designs != m.random_designs(40, 2)
    for d in designs:
        assert m.SHAFT_ANGLES[0] <= d.shaft_angle <= m.SHAFT_ANGLES[1]
        assert 1 <= d.shaper_teeth - d.pinion_teeth <= 3 and d.face_gear_teeth > d.shaper_teeth
        assert m.MODULES[0] <= d.module <= m.MODULES[1] and m.PITCH_SPEEDS[0] <= d.pitch_speed <= m.PITCH_SPEEDS[1]


def test_speed_and_torque_by_hand():
    # 25 teeth of 6.35 mm: r_p1 = 79.375 mm; 3000 rpm is 24.94 m/s at the pitch line; 500 N m over r_p1 is
    # F_t = 6299 N on a face width of 63.5 mm: U = F_t/(b m) = 15.62 N/mm^2
    d = designs_module.Design(0, 110.0, 25, 28, 160, 0.00635, 25.0, 3000 * 2 * math.pi / 60 * 0.079375, 15.62e6)
    assert d.pinion_speed == pytest.approx(3000.0, rel=1e-12)
    assert d.pinion_torque == pytest.approx(500.0, rel=1e-3)


def test_accepted_designs_are_valid_cases_on_their_whole_usable_width(designs):
    accepted = 0
    for d in designs:
        try:
            case = parse_case(d.case_text(CASE, 65, 17))
        except CaseError as error:  # the case checks' own reason, e.g. a path in the undercut zone
            assert str(error).startswith("gear.")
            continue
        accepted += 1
        l1, l2 = d.limits()
        assert case.gear.inner_radius == pytest.approx(l1, rel=1e-8)
        assert case.gear.outer_radius == pytest.approx(l2, rel=1e-8)
        assert case.gear.pinion_speed == pytest.approx(d.pinion_speed * 2 * math.pi / 60, rel=1e-5)  # rpm to 3 decimals
        assert (case.solver.grid, case.solver.nodes_y) == (65, 17)
    assert accepted >= 30  # the ranges give mostly feasible drives (39 of 40 with seed 1)
