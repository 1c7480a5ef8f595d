"""The calibration of the error bounds (suites/calibration.py) on a subset: every resolved figure's bound holds
against the Richardson-extrapolated reference of twice the nodes along x and y, or the figure is unresolved."""

from pathlib import Path

import pytest

from facegear_tehl.ehl.staged import StagedSolver
from facegear_tehl.suites.calibration import Comparison, calibration_points, compare, summary

ROOT = Path(__file__).resolve().parent.parent


def test_a_comparison_is_bounded_understated_or_unresolved():
    assert Comparison("P", "h_c", -0.01, 0.02, False).bounded
    assert not Comparison("P", "h_c", -0.05, 0.02, False).bounded
    assert Comparison("P", "h_c", -0.05, 0.02, False).understated  # 2.5x above the bound
    assert not Comparison("P", "h_c", -0.5, float("nan"), True).bounded  # unresolved: neither, never small
    assert not Comparison("P", "h_c", -0.5, float("nan"), True).understated
    table = summary([Comparison("P", "h_c", -0.01, 0.02, False), Comparison("Q", "h_c", -0.5, float("nan"), True)])
    assert "| h_c | 2 | 1 | 1 | 100 % | 0 | 0.50 |" in table


@pytest.mark.slow
def test_the_quick_calibration_bounds_every_resolved_figure():
    """The quick subset's every third point (the isothermal envelope core at 2 m/s on 129 x 33 and 257 x 65, four
    thermal core contacts on 129 x 33, the shipped case's S3 on 65 x 17 and 129 x 33)."""
    points = calibration_points(True, ROOT / "cases" / "facegear_110.yaml")[::3]
    comparisons = [c for p in points for c in compare(p, StagedSolver(), StagedSolver(bounded=False))]
    assert len(comparisons) >= 20
    failed = [c for c in comparisons if not (c.unresolved or c.bounded)]
    assert not failed, failed
