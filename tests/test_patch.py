"""The X-refined patch (ehl/patch.py) against the uniform grid of the patch's spacing.

Contact: the circle at Moes M = 20, L = 10 (Roelands, Dowson & Higginson; contact_from_moes), Venner & Lubrecht's
domain X in [-4.5, 1.5], Y in [-3, 3], 33 nodes along Y. Its outlet spike (X = 0.75) is resolved well enough that
129 and 257 nodes along X differ clearly in it (p_max 1.282 against 1.364 p_h, the spike one node upstream), so a
composite of 129 x 33 and a patch of half its X spacing must land on the 257 x 33 solution where the patch is,
against a yardstick the patch did not produce: the difference between the two uniform grids.
"""

from __future__ import annotations

from dataclasses import replace
import math
from pathlib import Path

import numpy as np
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.ehl import grid
from facegear_tehl.ehl.patch import PatchedSolver, patch_columns, trapezoid
from facegear_tehl.ehl.scaling import contact_from_moes
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.points import contact_analysis
from facegear_tehl.settings import SolverSettings

COARSE, FINE, FINEST = 129, 257, 513
NY = 33
OUTLET = 1.5  # the domain's outlet edge (X)
# Solver tolerances ten times tighter than the defaults: the differences asserted below (down to 1e-5 of p_h) must
# not be the iteration's
TOLERANCE = 1e-5
FACE_GEAR_CASE = Path(__file__).resolve().parents[1] / "cases" / "facegear_110.yaml"


def _settings(nx: int) -> SolverSettings:
    return SolverSettings(grid=nx, grid_y=NY, domain_x=(-4.5, OUTLET), domain_y=(-3.0, 3.0), max_cycles=60,
                          tolerance=TOLERANCE, load_tolerance=TOLERANCE)


def _point_solve(nx: int) -> PointSolve:
    point, lubricant = contact_from_moes(20.0, 10.0, viscosity_model="roelands", density_model="dowson_higginson")
    return PointSolve(point, lubricant, _settings(nx))


@pytest.fixture(scope="module")
def uniform():
    """The converged finest level of the uniform 129 x 33, 257 x 33 and 513 x 33 solves."""
    levels = {}
    for nx in (COARSE, FINE, FINEST):
        solve = _point_solve(nx)
        index, status = solve.start(below_top=0)
        assert status.converged
        assert solve.cycle(index, solve.settings.max_cycles).converged
        levels[nx] = solve.solver.levels[index]
    return levels


def _patched(start: float) -> PatchedSolver:
    """129 x 33 with a patch over [start, OUTLET]: full multigrid up to 129 x 33, the patch interpolated from it,
    composite V-cycles to the tolerances."""
    solve = _point_solve(COARSE)
    solve.solver = PatchedSolver(solve.solver.problem, grid.hierarchy_shapes(COARSE, NY, 17), (start, OUTLET))
    index, status = solve.start(below_top=1)
    assert status.converged
    solve.solver.interpolate_up(index + 1)
    assert solve.cycle(index + 1, solve.settings.max_cycles).converged
    return solve.solver


def _nested(start: float, nested_start: float) -> PatchedSolver:
    """_patched(start) with a second patch over [nested_start, OUTLET] on top (a quarter of 129 x 33's spacing),
    started from the first's interpolation and cycled to TOLERANCE. (Before the truncated coarse-grid correction,
    multigrid.corrected_nodes, its spike flickered with period two at 1.1e-4 per cycle and the composite was cycled
    to 1e-4 only; a stop at 1e-4 leaves p_max 3e-3 p_h from the converged composite.)"""
    solve = _point_solve(COARSE)
    solve.solver = _patched(start)
    solve.solver = PatchedSolver.over(solve.solver, (nested_start, OUTLET))
    top = len(solve.solver.levels) - 1
    solve.solver.interpolate_up(top)
    assert solve.cycle(top, solve.settings.max_cycles).converged
    return solve.solver


def _assert_the_same_solution(solver: PatchedSolver, uniform_level, tolerance: float) -> None:
    """The composite of patches over the whole domain against the uniform grid of the last one's spacing: h_c and h_min
    within 1e-4 relative, p_max and the pressure within `tolerance` (p_h)."""
    summary = solver.summary()
    h_c, h_min = _film_figures(uniform_level)
    p_max, _ = _spike(uniform_level)
    assert summary.h_c == pytest.approx(h_c, rel=1e-4)
    assert summary.h_min == pytest.approx(h_min, rel=1e-4)
    assert abs(summary.p_max - p_max) < tolerance
    assert np.abs(solver.patch.pressure - uniform_level.pressure).max() < tolerance


def _spike(level) -> tuple[float, float]:
    j, i = np.unravel_index(int(np.argmax(level.pressure)), level.pressure.shape)
    return float(level.pressure[j, i]), float(level.x[i])


def _film_figures(level) -> tuple[float, float]:
    return grid.bilinear_at(level.film, level.x, level.y, 0.0, 0.0), float(level.film.min())


def test_a_patch_over_the_whole_domain_is_the_uniform_fine_grid(uniform):
    """With the patch over every column the composite problem is the 257 x 33 one (its end columns are the
    domain's boundaries, the grid below only a coarse grid of the FAS): the solutions agree to the iterations'
    algebraic floor (both stop on a period-2 flicker of the spike's nodes, 6.5e-5 of the pressure per cycle for the
    uniform grid). Measured: h_c and h_min within 2.3e-5 relative, p_max within 3.3e-4 p_h, the pressure within
    4.1e-4 p_h; the two grids (129 and 257 nodes) differ by 0.08 p_h in p_max."""
    solver = _patched(-4.5)
    fine = uniform[FINE]
    assert (solver.first, solver.last) == (0, COARSE - 1)
    _assert_the_same_solution(solver, fine, 1e-3)


def test_an_outlet_patch_resolves_the_spike_as_the_fine_grid(uniform):
    """Patch over [-0.5, 1.5] b (the spike at 0.75 and half a semi-axis upstream of its rise). Measured: p_max
    1.3670 against 1.3640 on 257 x 33 and 1.2816 on 129 x 33; inside the patch the pressure differs from 257 x 33 by
    at most 0.011 p_h (129 x 33, interpolated: 0.36), outside from 257 x 33 by 1.16x what 129 x 33 does."""
    solver = _patched(-0.5)
    coarse, fine = uniform[COARSE], uniform[FINE]
    summary = solver.summary()
    p_coarse, x_coarse = _spike(coarse)
    p_fine, x_fine = _spike(fine)
    assert x_coarse != x_fine  # the yardstick: 129 x 33 puts the spike one node upstream
    assert summary.x_p_max == x_fine
    assert abs(summary.p_max - p_fine) < 0.1 * abs(p_coarse - p_fine)
    inside = np.abs(solver.patch.pressure - fine.pressure[:, solver.columns]).max()
    coarse_inside = np.abs(grid.SEMI_X.prolong_cubic(coarse.pressure) - fine.pressure)[:, solver.columns].max()
    assert inside < 0.1 * coarse_inside
    outside = np.ones(COARSE, dtype=bool)
    outside[solver.first:solver.last + 1] = False
    fine_nodes = fine.pressure[:, ::2]
    composite_error = np.abs(solver.below.pressure - fine_nodes)[:, outside].max()
    coarse_error = np.abs(coarse.pressure - fine_nodes)[:, outside].max()
    assert composite_error < 1.5 * coarse_error


def test_the_composite_pressure_carries_the_load():
    """\\iint P dX dY = 2 pi/3 (the Hertz load in these units), integrated here by numpy's trapezoid rule on each
    part: the grid below up to the patch, the patch from there."""
    solver = _patched(-0.5)
    below, patch = solver.below, solver.patch
    columns_y = np.trapezoid(below.pressure, below.y, axis=0)
    upstream = np.trapezoid(columns_y[:solver.first + 1], below.x[:solver.first + 1])
    downstream = np.trapezoid(columns_y[solver.last:], below.x[solver.last:])
    inside = np.trapezoid(np.trapezoid(patch.pressure, patch.y, axis=0), patch.x)
    load = upstream + inside + downstream
    assert abs(load - 2.0 * math.pi / 3.0) < 2.0 * TOLERANCE * 2.0 * math.pi / 3.0


def test_two_patches_over_the_whole_domain_are_the_uniform_grid_of_the_last(uniform):
    """Both patches over every column: the composite problem is the 513 x 33 one, solved through two partial levels
    of the FAS (the grids below only coarse grids). Measured: h_c and h_min within 3.5e-5 relative, p_max within
    3.3e-4 p_h, the pressure within 1.1e-3 p_h of 513 x 33 (257 x 33 misses its p_max by 0.073 p_h)."""
    solver = _nested(-4.5, -4.5)
    finest = uniform[FINEST]
    _assert_the_same_solution(solver, finest, 2e-3)


def test_a_patch_on_a_patch_resolves_the_spike_as_the_grid_of_its_spacing(uniform):
    """The first patch over [-1.5, 1.5] (the inlet side of the Hertzian zone at 257 x 33's spacing: the spike's
    height follows the film the inlet sets), the second on it over [-0.5, 1.5], against uniform 513 x 33, with what
    257 x 33 misses of it as the yardstick. Measured: p_max 1.4375 against 1.4370 (257 x 33: 1.3640); the pressure
    on the second patch within 0.0023 p_h of 513 x 33 (257 x 33 interpolated: 0.19). (With the first patch from -0.5,
    the inlet at 129 x 33's spacing, p_max is 1.416.)"""
    solver = _nested(-1.5, -0.5)
    fine, finest = uniform[FINE], uniform[FINEST]
    summary = solver.summary()
    p_fine, _ = _spike(fine)
    p_finest, x_finest = _spike(finest)
    inside = np.abs(solver.patch.pressure - finest.pressure[:, solver.columns]).max()
    fine_inside = np.abs(grid.SEMI_X.prolong_cubic(fine.pressure) - finest.pressure)[:, solver.columns].max()
    assert summary.x_p_max == pytest.approx(x_finest, abs=1e-9)
    assert abs(summary.p_max - p_finest) < 0.1 * abs(p_fine - p_finest)
    assert inside < 0.1 * fine_inside


def test_the_pressure_of_nested_patches_carries_the_load():
    """\\iint P dX dY = 2 pi/3 over the three parts of the composite (numpy's trapezoid rule on each): the grid
    below up to the first patch, the first patch up to the second, the second, and the rest of each after it."""
    solver = _nested(-0.5, 0.25)
    (uniform, own_u), (first, own_1), (second, _) = solver.parts()
    load = np.trapezoid(np.trapezoid(second.pressure, second.y, axis=0), second.x)
    for level, own in ((uniform, own_u), (first, own_1)):
        columns = np.trapezoid(level.pressure, level.y, axis=0)
        ends = np.flatnonzero(~own)[[0, -1]]  # the next patch's end columns
        load += np.trapezoid(columns[:ends[0] + 1], level.x[:ends[0] + 1])
        load += np.trapezoid(columns[ends[1]:], level.x[ends[1]:])
    assert abs(load - 2.0 * math.pi / 3.0) < 2.0 * TOLERANCE * 2.0 * math.pi / 3.0
    assert abs(solver.composite_integral() - load) < 1e-12


def test_a_patch_from_the_inlet_edge_of_the_hertz_zone_gives_the_fine_grid_films(uniform):
    """h_c and h_min are set where the pressure builds up at the inlet edge of the Hertzian zone (X ~ -1), not at
    the spike: an outlet patch from -0.5 leaves them at 129 x 33's values (h_c 0.42584 against 0.42570, 257 x 33:
    0.42712), one from -1 gives 257 x 33's (0.42713; h_min 0.28269 against 0.28267, 129 x 33: 0.28208)."""
    coarse, fine = uniform[COARSE], uniform[FINE]
    summary = _patched(-1.0).summary()
    (h_c_coarse, h_min_coarse), (h_c_fine, h_min_fine) = _film_figures(coarse), _film_figures(fine)
    assert abs(summary.h_c - h_c_fine) < 0.1 * abs(h_c_coarse - h_c_fine)
    assert abs(summary.h_min - h_min_fine) < 0.1 * abs(h_min_coarse - h_min_fine)


def test_patch_columns_enclose_the_span_and_refuse_a_patch_of_one_cell():
    x = np.linspace(-4.5, 1.5, 129)  # spacing 0.046875
    assert patch_columns(x, (-0.5, 1.5)) == (85, 128)  # x[85] = -0.515625 <= -0.5
    assert patch_columns(x, (-10.0, 10.0)) == (0, 128)
    with pytest.raises(ValueError, match="fewer than two cells"):
        patch_columns(x, (0.01, 0.04))


def test_trapezoid_integrates_a_quadratic_along_x_to_the_rule_error():
    """\\int_0^1 x^2 dx = 1/3; the trapezoid rule on n cells errs by h^2/6 (its error term -(b-a) h^2 f''/12)."""
    x = np.linspace(0.0, 1.0, 11)
    p = np.zeros((3, 11))
    p[1] = x**2
    h = 0.1
    assert trapezoid(p, h, 1.0) == pytest.approx(1.0 / 3.0 + h**2 / 6.0, rel=1e-12)


def _face_gear(name: str) -> tuple:
    """A point of the default face gear case, isothermal Newtonian, on the case's lengthened domain: its PointSolve
    arguments with the settings of its own grid (513 x 65), and the converged finest levels of the uniform 513 x 65
    and 1025 x 65 (the patch spacing) grids."""
    case = load_case(FACE_GEAR_CASE)
    point = next(p for p in contact_analysis(case).points if p.name == name)
    lubricant = replace(case.lubricant, rheology="newtonian")
    settings = replace(PointSolve(point, lubricant, replace(case.solver, thermal="off")).settings, max_cycles=60)
    levels = []
    for nx in (settings.grid, 2 * settings.grid - 1):
        solve = PointSolve(point, lubricant, replace(settings, grid=nx))
        index, status = solve.start(below_top=0)
        assert status.converged and solve.cycle(index, settings.max_cycles).converged
        levels.append(solve.solver.levels[index])
    return point, lubricant, settings, levels[0], levels[1]


def _face_gear_patched(point, lubricant, settings, start: float) -> PatchedSolver:
    """513 x 65 with a patch over [start, outlet], converged (as _patched)."""
    solve = PointSolve(point, lubricant, settings)
    shapes = grid.hierarchy_shapes(settings.grid, settings.nodes_y, settings.coarsest_grid)
    solve.solver = PatchedSolver(solve.solver.problem, shapes, (start, settings.domain_x[1]))
    index, status = solve.start(below_top=1)
    assert status.converged
    solve.solver.interpolate_up(index + 1)
    status = solve.cycle(index + 1, settings.max_cycles)
    assert status.converged, (point.name, start, status.message)
    return solve.solver


def test_the_face_gear_spike_on_an_outlet_patch_is_the_fine_grid_spike():
    """S2 (a/b = 45, p_h = 565 MPa): 513 x 65 with a patch over [-0.5 b, outlet] against the uniform 1025 x 65 grid
    of the patch spacing. Measured: p_max 1.5077 against 1.5080 (513 x 65: 1.3506), the spike at X = 0.6094 on
    both (513 x 65: one node upstream), the pressure on the patch within 0.012 p_h of 1025 x 65 (513 x 65: 0.38)."""
    point, lubricant, settings, coarse, fine = _face_gear("S2")
    solver = _face_gear_patched(point, lubricant, settings, -0.5)
    summary = solver.summary()
    p_coarse, x_coarse = _spike(coarse)
    p_fine, x_fine = _spike(fine)
    assert x_coarse != x_fine
    assert summary.x_p_max == pytest.approx(x_fine, abs=1e-9)
    assert abs(summary.p_max - p_fine) < 0.05 * abs(p_coarse - p_fine)
    inside = np.abs(solver.patch.pressure - fine.pressure[:, solver.columns]).max()
    coarse_inside = np.abs(grid.SEMI_X.prolong_cubic(coarse.pressure) - fine.pressure)[:, solver.columns].max()
    assert inside < 0.1 * coarse_inside


@pytest.mark.slow
@pytest.mark.parametrize("name", ["S2", "S4"])
def test_patches_ending_on_the_inlet_side_of_the_hertz_zone_converge(name):
    """Upstream ends X_a in [-1.1, -0.6] b cross the inlet side of the Hertzian zone, where one V-cycle of the grid
    below per coarse-grid correction ran away (patch_coarse_cycles): every one converges, with p_max within a tenth of
    what 513 x 65 misses of 1025 x 65's (measured: within 0.0027 p_h; 513 x 65 misses by 0.16 and 0.096 p_h)."""
    point, lubricant, settings, coarse, fine = _face_gear(name)
    p_coarse, _ = _spike(coarse)
    p_fine, x_fine = _spike(fine)
    for start in (-1.1, -1.0, -0.9, -0.8, -0.7, -0.6):
        summary = _face_gear_patched(point, lubricant, settings, start).summary()
        assert summary.x_p_max == pytest.approx(x_fine, abs=1e-9), start
        assert abs(summary.p_max - p_fine) < 0.1 * abs(p_coarse - p_fine), start
