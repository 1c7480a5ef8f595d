"""A light load on a long ellipse (the shipped face gear at 5 N m): the start from a film prediction several times too
thin converges (ehl/start.py), and the domain's sides, which the film spreads beyond, are measured and flagged
(ehl/domain.py, side_pressure_ratio)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.ehl.domain import (
    predicted_central_film,
    side_note,
    side_pressure_ratio,
    starved_sides,
)
from facegear_tehl.ehl.error_bounds import unresolved_figure
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.ehl.unresolved import Why
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.record import Action


def _light_case(tmp_path: Path, torque: float):
    text = Path("cases/facegear_110.yaml").read_text()
    assert "pinion_torque: 500.0" in text
    path = tmp_path / "light.yaml"
    path.write_text(text.replace("pinion_torque: 500.0", f"pinion_torque: {torque}"))
    return load_case(str(path))


def test_a_light_loads_start_carries_its_load_where_the_predicted_film_is_several_times_too_thin(tmp_path):
    """S1 at 5 N m (Moes M 8.6, p_h 120 MPa), isothermal Newtonian: Hamrock & Dowson's (1977) central film, fitted in
    the elastic-piezoviscous regime, sets the start's H_0 at a fraction of the film the lengthened inlet carries; the
    start used to run away on every attempt. Now a retry's coarsest grid is cycled to its load and the start climbs
    on: converged, the pressure field carries the point's load (a conservation law, integrated here from the field)
    and the film is rigid-isoviscous, thicker than the fit predicts, with a pressure peak a few per cent of Hertz's."""
    case = _light_case(tmp_path, 5.0)
    point = select_points(list(contact_analysis(case).points), ["S1"])[0]
    lubricant = replace(case.lubricant, rheology="newtonian")
    solution = solve_point(point, lubricant, replace(case.solver, grid=257, grid_y=33, thermal="off"))
    assert solution.converged, solution.message
    pressure = solution.fields["pressure"].values
    x, y = solution.axes["x"].values, solution.axes["y"].values
    carried = np.trapezoid(np.trapezoid(pressure, x, axis=1), y)
    assert carried == pytest.approx(point.load, rel=2e-3)
    scaling = scaling_for(point, lubricant)
    assert solution.scalar("h_c") > 1.5 * predicted_central_film(scaling)
    assert Action.COARSEST_TO_ITS_LOAD in {retry.action for retry in solution.record.retries}
    assert solution.scalar("p_max") < 0.1 * solution.scalar("p_hertz")
    # the film spreads beyond the sides and the inlet: nothing is bounded, for both reasons
    assert starved_sides(solution.scalar("side_pressure_ratio"))
    assert solution.scalar("inlet_gap_ratio") < TUNING.min_inlet_gap_ratio
    assert unresolved_figure(solution, "h_c", 1e-3, 1e-3, 100) is Why.STARVED_INLET
    flooded_inlet = replace(solution, scalars={**solution.scalars, "inlet_gap_ratio": (40.0, "1")})
    assert unresolved_figure(flooded_inlet, "h_c", 1e-3, 1e-3, 100) is Why.STARVED_SIDES


def test_sides_that_starve_the_film_are_flagged_and_sides_four_times_as_far_are_not(tmp_path):
    """S1 at 50 N m (Moes M 86), isothermal Newtonian on X in [-22.5, 1.5] (257 nodes): sides at +-6 a (129 rows)
    against +-24 a (513 rows, the same spacing), where the film no longer feels them. The narrower domain's film is
    thinner by more than 1 %, and its pressure near the sides passes max_side_pressure: unresolved, with a warning;
    the wider one's does not."""
    case = _light_case(tmp_path, 50.0)
    point = select_points(list(contact_analysis(case).points), ["S1"])[0]
    lubricant = replace(case.lubricant, rheology="newtonian")
    films, ratios = [], []
    for half, rows in ((6.0, 129), (24.0, 513)):
        settings = replace(case.solver, grid=257, grid_y=rows, thermal="off", domain_x=(-22.5, 1.5),
                           domain_y=(-half, half))
        solution = solve_point(point, lubricant, settings)
        assert solution.converged, solution.message
        films.append(solution.scalar("h_c"))
        ratios.append(solution.scalar("side_pressure_ratio"))
    assert 1.0 - films[0] / films[1] > 0.01
    assert starved_sides(ratios[0]) and "no figure is bounded" in side_note("S1", ratios[0])
    assert not starved_sides(ratios[1]) and side_note("S1", ratios[1]) == ""


def test_the_side_pressure_ratio_reads_the_bands_next_to_the_sides():
    """A Hertzian pressure sqrt(1 - X^2 - Y^2) on Venner & Lubrecht's domain is zero beyond Y = 1: no side pressure.
    A pressure that is uniform along Y has its peak at the sides: the ratio is 1. Entrainment along x: the bands are
    the rows within 1/12 of the width from Y = -3 and Y = 3."""
    case = load_case("cases/facegear_110.yaml")
    point = select_points(list(contact_analysis(case).points), ["S3"])[0]
    scaling = scaling_for(point, case.lubricant)
    x, y = np.linspace(-4.5, 1.5, 97), np.linspace(-3.0, 3.0, 49)
    hertz = np.sqrt(np.clip(1.0 - x[None, :] ** 2 - y[:, None] ** 2, 0.0, None))
    assert side_pressure_ratio(hertz, x, y, scaling) == 0.0
    uniform = np.broadcast_to(np.exp(-x[None, :] ** 2), (y.size, x.size))
    assert side_pressure_ratio(uniform, x, y, scaling) == pytest.approx(1.0)
    half_way = hertz.copy()
    half_way[(np.abs(y) >= 2.5), 40] = 0.25  # in the bands: a quarter of the peak
    half_way[(np.abs(y) < 2.4), 40] = 0.25  # outside them: not read
    assert side_pressure_ratio(half_way, x, y, scaling) == pytest.approx(0.25)


def test_the_side_warning_says_nothing_is_bounded_and_gives_the_ratio_readably():
    assert side_note("S1", 0.9 * TUNING.max_side_pressure) == ""
    for ratio in (0.02, 0.5):  # the 5 N m face gear's points: 41-66 % (docs/accuracy.md)
        starved = side_note("S1", ratio)
        assert "no figure is bounded" in starved and starved_sides(ratio)
        assert "e+" not in starved and f"{100 * ratio:.3g} %" in starved


def test_the_sides_are_read_across_the_entrainment_and_on_interior_nodes_of_a_coarse_grid():
    """Entrainment along y (wedge_x = 0): the sides are the X boundaries. On 9 nodes the band holds the first
    interior node next to each side (the sides' own are held at zero)."""
    case = load_case("cases/facegear_110.yaml")
    point = select_points(list(contact_analysis(case).points), ["S3"])[0]
    along_y = replace(scaling_for(point, case.lubricant), wedge_x=0.0, wedge_y=1.0)
    x, y = np.linspace(-3.0, 3.0, 49), np.linspace(-4.5, 1.5, 97)
    spread_along_x = np.broadcast_to(np.exp(-((y[:, None] + 1.0) ** 2)), (y.size, x.size)).copy()
    spread_along_x[:, [0, -1]] = 0.0
    assert side_pressure_ratio(spread_along_x, x, y, along_y) == pytest.approx(1.0)
    coarse_x, coarse_y = np.linspace(-4.5, 1.5, 17), np.linspace(-3.0, 3.0, 9)
    uniform_along_y = np.broadcast_to(np.exp(-coarse_x[None, :] ** 2), (9, 17)).copy()
    uniform_along_y[[0, -1], :] = 0.0
    scaling = scaling_for(point, case.lubricant)
    assert side_pressure_ratio(uniform_along_y, coarse_x, coarse_y, scaling) == pytest.approx(1.0)


def test_the_accuracy_target_does_not_refine_a_figure_the_domain_starves():
    """A finer grid keeps the domain: a figure unresolved because the inlet or the sides starve the film is not
    refined for (`solver.accuracy`); one unresolved for a grid reason is."""
    from facegear_tehl.accuracy_target import never_refined

    import synthetic

    case = load_case("cases/facegear_110.yaml")
    solution = synthetic.solution(select_points(list(contact_analysis(case).points), ["S1"])[0])
    for why, refined in ((Why.STARVED_SIDES, False), (Why.STARVED_INLET, False), (Why.NARROW_FEATURE, True)):
        flagged = replace(solution, scalars={**solution.scalars, "unresolved_h_c": (1.0, "1"),
                                             "unresolved_reason_h_c": (float(why), "1")})
        assert never_refined(flagged, "h_c") is not refined
