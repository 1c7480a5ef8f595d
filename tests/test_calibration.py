"""The calibration of the error bounds (suites/calibration.py) on a subset: every resolved figure's bound holds
against the Richardson-extrapolated reference of twice the nodes along x and y, or the figure is unresolved."""

from pathlib import Path

import pytest

from facegear_tehl.ehl.staged import STAGED, UNBOUNDED
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
    """The quick subset's every third point (the isothermal envelope core at 2 m/s and four thermal core contacts on
    129 x 33, the gear cases' S3 on 65 x 17 and 129 x 33): no resolved figure understated more than twofold, and at
    least 95 % bounded (the acceptance of issue 46)."""
    points = calibration_points(True, ROOT / "cases")[::3]
    comparisons = [c for p in points for c in compare(p, STAGED, UNBOUNDED)]
    assert len(comparisons) >= 20
    resolved = [c for c in comparisons if not c.unresolved]
    assert not [c for c in resolved if c.understated]
    assert sum(c.bounded for c in resolved) >= 0.95 * len(resolved), [c for c in resolved if not c.bounded]


@pytest.mark.slow
def test_the_side_lobe_minimum_of_the_orthogonal_face_gear_is_unresolved_or_bounded():
    """S2 of cases/facegear_90.yaml (a = 6.3 mm) asked on 129 x 33: the lowest film lies where the y grid cannot
    resolve it (issue 46: once reported +-6.6 % for a -52 % error). Against the same model with twice the nodes
    along x and y, Richardson-extrapolated, h_min is unresolved or its bound holds; so are h_c, dT_max and mu."""
    point = next(p for p in calibration_points(False, ROOT / "cases", designs=0)
                 if p.name == "facegear_90 S2 129x33")
    comparisons = compare(point, STAGED, UNBOUNDED)
    assert {c.quantity for c in comparisons} >= {"h_c", "h_min", "dT_max", "mu"}
    assert all(c.unresolved or c.bounded for c in comparisons), comparisons


@pytest.mark.slow
def test_the_rise_of_a_rolling_film_held_by_its_compression_is_unresolved_or_bounded():
    """S3 of random design 6 (seed 46; pure rolling; 129 x 33 asked, 257 x 33 solved): its hot spot, 16.1 K in
    mid-film at x = -0.61 b, is its compression in the inlet, with the outlet spike's flank 1.2 % cooler; on the grid
    twice as fine along x and y the flank is the hot spot, 11 % hotter, while the estimates against the coarse stage
    and the y-check said 1.5 % and -0.1 % (a bound of 4.9 % once). Against that grid, Richardson-extrapolated, dT_max
    is unresolved or its bound holds (error_bounds.compression_held); so are h_c, h_min and mu."""
    point = next(p for p in calibration_points(False, ROOT / "cases") if p.name == "design6 S3 129x33")
    comparisons = compare(point, STAGED, UNBOUNDED)
    assert {c.quantity for c in comparisons} >= {"h_c", "h_min", "dT_max", "mu"}
    assert all(c.unresolved or c.bounded for c in comparisons), comparisons
