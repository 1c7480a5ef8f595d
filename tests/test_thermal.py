"""Thermal, non-Newtonian EHL (issue 4): limits, conservation and the face gear trends."""

import dataclasses
import json
import math

from click.testing import CliRunner
import numpy as np
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.cli import summary_table, tehl
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import plan, solve
from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.coupled import next_film_state
from facegear_tehl.ehl.energy import energy_budget
from facegear_tehl.ehl.flow import temperature_factors
from facegear_tehl.ehl.staged import StagedSolver, solve_point
from facegear_tehl.ehl.thermal import (
    FilmState,
    FilmThermalModel,
    layer_viscosity,
    relaxed_steps,
)
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.lubricant_laws import viscosity_ratio_at, viscosity_temperature_coefficient_at
from facegear_tehl.results import read_result
from facegear_tehl.solution import Outcome

SLIDING = "cases/ball_on_disc_sliding.yaml"


def plain(path, grid=65, **changes):
    case = load_case(path)
    c = dataclasses.replace(case.contact, **changes)
    point = ContactPoint.from_rolling_sliding("contact", c.radius_x, c.radius_y, c.load, c.entrainment_speed,
                                             c.slide_roll_ratio, c.entrainment_angle, case.materials.body_1,
                                             case.materials.body_2)
    return point, case.lubricant, dataclasses.replace(case.solver, grid=grid)


def test_pure_rolling_at_low_speed_equals_isothermal():
    # Heating is negligible in pure rolling at low speed (little shear heating):
    # full thermal h_c within 1 %.
    point, lub, settings = plain(SLIDING, slide_roll_ratio=0.0, entrainment_speed=0.3)
    newtonian = dataclasses.replace(lub, rheology="newtonian")
    hot = solve_point(point, newtonian, dataclasses.replace(settings, thermal="full"))
    cold = solve_point(point, newtonian, dataclasses.replace(settings, thermal="off"))
    assert hot.converged and cold.converged
    assert hot.scalar("h_c") == pytest.approx(cold.scalar("h_c"), rel=0.01)
    assert hot.scalar("dT_max") < 1.0


def test_energy_balance_on_a_sliding_case():
    # Heat generated in the film (+ the heat of the mass the full-film velocities do not conserve, energy.py) =
    # conducted into both solids + convected out of the domain, within 1 % (issue 19; it was 2 % without the
    # convection across the layers and without the mass defect).
    point, lub, settings = plain(SLIDING)
    sol = solve_point(point, lub, dataclasses.replace(settings, thermal="full"))
    assert sol.converged
    generated = sol.scalar("heat_generated")
    assert generated > 0.0
    closure = generated + sol.scalar("heat_mass_defect") - sol.scalar("heat_conducted") - sol.scalar("heat_convected")
    assert abs(closure) < 0.01 * generated
    assert sol.scalar("energy_balance_error") == pytest.approx(closure / generated, rel=1e-9, abs=1e-15)
    assert abs(sol.scalar("heat_mass_defect")) < 0.05 * generated


def test_ree_eyring_tends_to_newtonian():
    point, lub, settings = plain(SLIDING)
    off = dataclasses.replace(settings, thermal="off")
    newtonian = solve_point(point, dataclasses.replace(lub, rheology="newtonian"), off)
    eyring = solve_point(point, dataclasses.replace(lub, eyring_stress=1e13), off)
    for key in ("h_c", "h_min", "p_max"):
        assert eyring.scalar(key) == pytest.approx(newtonian.scalar(key), rel=2e-3)
    # and with a realistic tau_0 the film is shear-thinned: lower traction than the Newtonian film
    thinned = solve_point(point, lub, off)
    assert thinned.scalar("mu") < eyring.scalar("mu")


def test_isothermal_ree_eyring_dissipation_equals_the_work_of_the_wall_tractions():
    """Energy conservation of the isothermal film (thermal off, Ree-Eyring, SRR 1): the power dissipated by shear,
    iiint tau . gamma_dot dV, equals the work the surfaces do on the film, -(F_1 . u_1 + F_2 . u_2), with F_i the
    traction on body i (the pressure work, int p div(q) dA, vanishes for an incompressible film and is small for
    Dowson-Higginson). Measured: 0.11 % at 65^2, 0.04 % at 129^2 (it falls with the grid); 0.5 % bound."""
    point, lub, settings = plain(SLIDING)
    sol = solve_point(point, lub, dataclasses.replace(settings, thermal="off"))
    assert sol.converged
    x, y = sol.axes["x"].values, sol.axes["y"].values
    area = (x[1] - x[0]) * (y[1] - y[0])
    f = sol.fields
    traction_1 = np.array([f["shear_stress_1_x"].values.sum(), f["shear_stress_1_y"].values.sum()]) * area
    traction_2 = -np.array([f["shear_stress_2_x"].values.sum(), f["shear_stress_2_y"].values.sum()]) * area
    work = -(traction_1 @ np.asarray(point.velocity_1) + traction_2 @ np.asarray(point.velocity_2))
    assert work > 0.0
    assert sol.scalar("dissipated_power") == pytest.approx(work, rel=5e-3)


def test_hard_thermal_case_converges_or_says_why_never_nan():
    # Slide-to-roll ratio 2 (surface 2 at rest) at p_h ~ 2 GPa.
    point, lub, settings = plain(SLIDING, slide_roll_ratio=2.0, load=551.0)
    sol = solve_point(point, lub, dataclasses.replace(settings, thermal="full", max_thermal_iterations=10))
    assert sol.scalar("p_hertz") == pytest.approx(2.0e9, rel=0.02)
    for f in sol.fields.values():
        assert np.isfinite(f.values).all()
    assert all(math.isfinite(v) for v, _ in sol.scalars.values())
    # converged: an open film and no message; else the message names the reason, and a closed film as such,
    # without a film (a negative film is never reported as a result)
    if sol.converged:
        assert sol.message == "" and sol.scalar("h_min") > 0.0
    else:
        assert sol.message.startswith(("thermal loop not converged", "not converged", "diverged", "the film closes"))
        closed = "film closes" in sol.message
        assert closed == (sol.outcome is Outcome.FILM_CLOSED or "h_min" not in sol.scalars)
        assert closed == (not sol.fields) and (closed or sol.scalar("h_min") > 0.0)


@pytest.mark.xfail(strict=True, reason="SRR 2 at p_h 2 GPa on 65^2: the outer thermal loop stalls with a 35 K change "
                                       "per iteration (still after 100 iterations) and the iterate's film closes "
                                       "(h_min about -77 nm)")
def test_hard_thermal_case_converges_with_an_open_film():
    point, lub, settings = plain(SLIDING, slide_roll_ratio=2.0, load=551.0)
    sol = solve_point(point, lub, dataclasses.replace(settings, thermal="full", max_thermal_iterations=10))
    assert sol.converged, sol.message
    assert 0.0 < sol.scalar("h_min") < sol.scalar("h_c")


@pytest.fixture
def face_gear_points(facegear_run):
    """The default face gear case on --grid 65 (65 x 17), solved once per session (conftest.py), by point."""
    return {p.name: p for p in facegear_run.points}


def test_face_gear_temperature_and_friction_are_smallest_at_the_pitch_point(face_gear_points):
    sols = face_gear_points
    assert all(s.converged for s in sols.values())
    rise = {k: s.scalar("dT_max") for k, s in sols.items()}
    mu = {k: s.scalar("mu") for k, s in sols.items()}
    assert min(rise, key=rise.get) == "S3"
    assert min(mu, key=mu.get) == "S3"
    # the hottest point is the one with the most sliding (S1: SRR 0.57)
    srr = {k: abs(s.scalar("slide_roll_ratio")) for k, s in sols.items()}
    assert max(rise, key=rise.get) == max(srr, key=srr.get)
    for name in ("S1", "S2", "S4"):  # sliding points under full or 2/3 load
        assert 0.005 < mu[name] < 0.1


def test_thermal_film_reduction_and_heating_grow_with_sliding():
    # Fixed load and entrainment speed; only the slide-to-roll ratio changes (the thermal film reduction grows with
    # sliding).
    ratios, rises = [], []
    for srr in (0.0, 0.5, 1.5):
        point, lub, settings = plain(SLIDING, slide_roll_ratio=srr)
        full = solve_point(point, lub, dataclasses.replace(settings, thermal="full"))
        off = solve_point(point, lub, dataclasses.replace(settings, thermal="off"))
        ratios.append(full.scalar("h_c") / off.scalar("h_c"))
        rises.append(full.scalar("dT_max"))
    assert ratios[2] < ratios[1] <= ratios[0] + 0.005
    assert rises[0] < rises[1] < rises[2]


def test_thermal_floor_is_a_stalled_small_change_with_a_steady_film():
    """The outer loop's algebraic floor (solve._at_thermal_floor): a period-2 flicker that stopped falling,
    below 1 % of the rise, with h_c steady to 5e-4 or to half its grid error if larger, is accepted; a change
    still falling, a large flicker or a drifting film is not."""
    from facegear_tehl.ehl.convergence import at_thermal_floor as _at_thermal_floor

    flicker = [0.45, 0.42, 0.45, 0.42, 0.44, 0.43, 0.45, 0.42]
    steady = [1.2669e-6] * 8
    assert _at_thermal_floor(flicker, steady, bound=0.01 * 98.0)
    assert not _at_thermal_floor(flicker[:7], steady[:7], bound=0.01 * 98.0)  # too few iterations to judge
    falling = [0.45 * 0.5**k for k in range(8)]
    assert not _at_thermal_floor(falling, steady, bound=0.01 * 98.0)
    # 4.5 K of a 98 K rise: too large
    assert not _at_thermal_floor([10 * c for c in flicker], steady, bound=0.01 * 98.0)
    drifting = [1.9887e-7 * (1 + 0.002 * k) for k in range(8)]
    assert not _at_thermal_floor(flicker, drifting, bound=0.01 * 142.0)
    # a film flickering by 5.4e-4 (S3 on 257 x 65): steady only against a grid error of h_c above 1.1e-3
    alternating = [1.55154e-6, 1.55070e-6] * 4
    assert not _at_thermal_floor(flicker, alternating, bound=0.01 * 98.0)
    assert not _at_thermal_floor(flicker, alternating, bound=0.01 * 98.0, h_c_error=1.0e-3)
    assert _at_thermal_floor(flicker, alternating, bound=0.01 * 98.0, h_c_error=1.7e-3)


def test_the_tolerance_stop_needs_a_steady_film():
    """convergence.h_c_steady, asked by the loop's tolerance stop over its last steady_updates updates: the spread of
    h_c within 5e-4 of the last value, or half its error estimate if larger. By hand: the 513^2 S1 updates that ended
    early (1.20504, 1.20419, 1.20482 um: spread 8.5e-4 / 1.20482 = 7.1e-4) are not steady at an error of 1e-3, are at
    2e-3 (half: 1e-3); the settled ones (1.20558, 1.20564, 1.20560 um: 5.0e-5) are."""
    from facegear_tehl.ehl.convergence import h_c_steady as _h_c_steady

    assert TUNING.steady_updates >= 2  # one update has no spread to judge
    moving, settled = [1.20504, 1.20419, 1.20482], [1.20558, 1.20564, 1.20560]
    assert not _h_c_steady(moving) and not _h_c_steady(moving, h_c_error=1.0e-3)
    assert _h_c_steady(moving, h_c_error=2.0e-3)
    assert _h_c_steady(settled)
    assert not _h_c_steady([])


def test_energy_sweeps_are_forced_loosely_in_a_transient_and_tighter_as_the_loop_converges():
    """solve.energy_forcing is Eisenstat & Walker's (1996) choice 2, gamma (c_k/c_k-1)^2 with gamma 0.3, kept within
    [0.1, 0.3]: by hand, a loop whose changes stay (the temperature continuation's 35 K steps) or grow keeps 0.3, one
    falling by 0.8 per update gets 0.3 x 0.64 = 0.192, one halving its change the floor 0.1 (0.075 by the formula)."""
    from facegear_tehl.ehl.coupled import energy_forcing

    assert energy_forcing([]) == energy_forcing([2.3]) == 0.3
    assert energy_forcing([35.0, 35.0]) == energy_forcing([0.5, 0.9]) == 0.3
    assert energy_forcing([1.0, 0.8]) == pytest.approx(0.192, rel=1e-12)
    assert energy_forcing([1.0, 0.5]) == 0.1
    assert energy_forcing([0.0, 0.0]) == 0.3  # no change to judge a ratio by


def test_a_flickering_pressure_feeds_the_film_state_the_mean_of_its_two_phases():
    """On a period-2 flicker of the pressure (the change per cycle stalled below 10x the tolerance) the outer
    loop evaluates the film state at the mean of the last two iterates and ends on it (solve.PointSolve
    .settled_pressure, .settle): the film is affine in (P, H_0), so the mean film handed to the energy equation
    is the film the solver computes for the mean iterate; a pressure still converging is used as it is."""
    from facegear_tehl.ehl.multigrid import Iterate
    from facegear_tehl.ehl.solve import PointSolve

    point, lubricant, settings = plain(SLIDING, grid=33)
    solve = PointSolve(point, lubricant, settings)
    solver, top = solve.solver, len(solve.solver.levels) - 1
    level = solver.levels[top]
    xx, yy = np.meshgrid(level.x, level.y)
    phase_a = np.sqrt(np.maximum(1.0 - xx**2 - yy**2, 0.0))
    phase_b = phase_a * (1.0 + 0.02 * np.exp(-((xx - 0.9) / 0.2) ** 2))  # the outlet side raised
    solver.restore(top, Iterate(phase_b, 0.30))
    solve.pressure.before_cycle = (solver.snapshot(top), level.film.copy())
    solver.restore(top, Iterate(phase_a, 0.32))
    solve.history.changes = [math.nan, 2.9e-4, 2.8e-4, 2.9e-4]
    pressure, film = solve.pressure.settled_pressure(top)
    assert np.allclose(pressure, 0.5 * (phase_a + phase_b))
    solve.pressure.settle(top)
    assert solver.h0 == pytest.approx(0.31)
    assert np.allclose(level.pressure, pressure) and np.allclose(level.film, film, rtol=1e-12, atol=1e-14)
    solve.history.changes = [math.nan, 2.9e-4, 1.5e-4, 0.9e-4]  # still falling: no flicker
    pressure, film = solve.pressure.settled_pressure(top)
    assert pressure is level.pressure and film is level.film


def test_error_estimates_of_dT_max_and_mu_come_from_the_coarse_thermal_stage():
    """error_estimate_dT_max = (f_h - f_2h)/(2^1 - 1)/f_h (first order: the maximum sits at the pressure spike),
    error_estimate_mu the same (mu's observed order along x is 0.7-1.7), from the coarse stage's figures; NaN
    without that stage."""
    from types import SimpleNamespace

    from facegear_tehl.ehl.report import ORDER_DT_MAX, ORDER_MU, LevelSummary, estimate

    coarse = LevelSummary(n=65, h_c=1.0, h_min=0.8, p_max=1.1, dT_max=95.0, mu=0.0132)
    fine = LevelSummary(n=129, h_c=1.0, h_min=0.8, p_max=1.1)
    level = SimpleNamespace(nx=129)
    assert (ORDER_DT_MAX, ORDER_MU) == (1, 1)
    assert estimate([coarse, fine], level, 97.0, "dT_max", ORDER_DT_MAX) == pytest.approx(2.0 / 97.0)
    assert estimate([coarse, fine], level, 0.0130, "mu", ORDER_MU) == pytest.approx(-0.0002 / 0.0130)
    assert math.isnan(estimate([fine], level, 97.0, "dT_max", 1))
    assert math.isnan(estimate([LevelSummary(n=65, h_c=1.0, h_min=0.8, p_max=1.1), fine], level, 97.0, "dT_max", 1))


@pytest.mark.slow
def test_error_estimates_hold_against_a_converged_reference():
    """The estimates of dT_max and mu are differences against the coarse thermal stage, which stops at
    TUNING.coarse_stage_tolerance times the thermal tolerance, at most TUNING.coarse_stage_limit of the rise: its
    iteration error must stay well below that difference, or the estimate measures the iteration and not the grid.
    S1 of the default case (the point whose mu estimate a coarse stage stopped at 1e-2 of the rise made 4.9e-4
    against 4.2e-3), at thermal tolerances of 1e-3 and 2e-3 (the default): each of the four estimates is within
    30 % of the same solve's converged to 3e-5 of the rise (both stages' iteration errors then negligible), and each
    figure within a quarter of that estimate of the converged one."""
    from facegear_tehl.points import contact_analysis

    case = load_case("cases/facegear_110.yaml")
    point = next(p for p in contact_analysis(case).points if p.name == "S1")
    reference = solve_point(point, case.lubricant, dataclasses.replace(case.solver, thermal_tolerance=3e-5))
    assert reference.converged
    for tolerance in (1e-3, 2e-3):
        solved = solve_point(point, case.lubricant, dataclasses.replace(case.solver, thermal_tolerance=tolerance))
        assert solved.converged
        assert reference.scalar("thermal_iterations") > solved.scalar("thermal_iterations")
        for name in ("h_c", "h_min", "dT_max", "mu"):
            estimate, converged = solved.scalar(f"error_estimate_{name}"), reference.scalar(f"error_estimate_{name}")
            assert abs(estimate) == pytest.approx(abs(converged), rel=0.3), (tolerance, name)
            assert abs(solved.scalar(name) / reference.scalar(name) - 1.0) < 0.25 * abs(converged), (tolerance, name)


def test_the_coarse_stage_seeded_two_grids_down_reaches_the_same_film(monkeypatch):
    """S1 of the default case (513 x 65): the coupled problem is solved first on 129 x 65 to TUNING.seed_stage_limit
    of the rise and the coarse stage (257 x 65) starts from its interpolated state instead of the inlet temperature.
    The loop's fixed point does not depend on where it starts: h_c, h_min, dT_max and mu within a quarter of their
    error estimates of the solve whose coarse stage starts from the inlet temperature, at a fraction of the coarse
    stage's updates. A seed stage that runs away is dropped and the coarse stage begun again from the coarsest grid:
    the solve is then the unseeded one."""
    from facegear_tehl.points import contact_analysis
    from facegear_tehl.solution import Status

    case = load_case("cases/facegear_110.yaml")
    point = next(p for p in contact_analysis(case).points if p.name == "S1")
    couple, seed_stage = solve.PointSolve.couple, solve.PointSolve._seed_stage
    per_grid = {}  # outer iterations per grid of the last solve

    def counted(self, index, *args, **kwargs):
        before = self.history.outer
        out = couple(self, index, *args, **kwargs)
        per_grid[self.solver.levels[index].nx] = self.history.outer - before
        return out

    monkeypatch.setattr(solve.PointSolve, "couple", counted)
    alone = StagedSolver(bounded=False)  # the solve alone: the error bounds' check solves would be counted too
    seeded = alone(point, case.lubricant, case.solver)
    seeded_grids = dict(per_grid)
    per_grid.clear()
    with monkeypatch.context() as m:
        m.setattr(plan, "TUNING", dataclasses.replace(plan.TUNING, min_seed_stage_grid=10**6))
        unseeded = alone(point, case.lubricant, case.solver)
    unseeded_grids = dict(per_grid)
    assert seeded.converged and unseeded.converged
    assert set(seeded_grids) == {129, 257, 513} and set(unseeded_grids) == {257, 513}
    assert seeded_grids[257] < unseeded_grids[257]
    for name in ("h_c", "h_min", "dT_max", "mu"):
        estimate = abs(unseeded.scalar(f"error_estimate_{name}"))
        assert abs(seeded.scalar(name) / unseeded.scalar(name) - 1.0) < 0.25 * estimate, name
        assert abs(seeded.scalar(f"error_estimate_{name}")) == pytest.approx(estimate, rel=0.3), name

    def running_away(self, index, *args, **kwargs):
        if index == len(self.solver.levels) - 3:  # the seed stage's grid
            return None, Status(Outcome.DIVERGED, "a seed stage that runs away")
        return couple(self, index, *args, **kwargs)

    seeds = []

    def recorded(self):
        seeds.append(seed_stage(self))
        return seeds[-1]

    monkeypatch.setattr(solve.PointSolve, "couple", running_away)
    monkeypatch.setattr(solve.PointSolve, "_seed_stage", recorded)
    fallen_back = alone(point, case.lubricant, case.solver)
    assert seeds == [None]
    for name in ("h_c", "h_min", "dT_max", "mu", "thermal_iterations"):
        assert fallen_back.scalar(name) == unseeded.scalar(name), name


def test_coldest_film_temperature_is_reported_with_its_place(face_gear_points, facegear_file):
    """dT_min (issue 19): the coldest layer temperature relative to the inlet and where it lies. No film is
    colder than the inlet's oil without cooling, and the surfaces enter the domain at the inlet temperature, so
    dT_min <= 0 everywhere. At the pitch point (pure rolling) the oil cools by expansion where the pressure falls
    in the outlet (beta_T T u dp/dx < 0): the coldest place is downstream of the centre, in mid-film, and colder
    than the inlet by several kelvin, but by less than adiabatic expansion from the largest pressure would give,
    beta_T T p_max/(rho c) (about 80 K here, for T at its hottest: the oil is not adiabatic)."""
    case = load_case("cases/facegear_110.yaml")
    lub = case.lubricant
    for name, sol in face_gear_points.items():
        assert [sol.scalars[k][1] for k in ("dT_min", "x_dT_min", "y_dT_min")] == ["K", "m", "m"]
        assert sol.scalar("dT_min") <= 0.0, name
        x, y = sol.axes["x"].values, sol.axes["y"].values
        assert x[0] <= sol.scalar("x_dT_min") <= x[-1] and y[0] <= sol.scalar("y_dT_min") <= y[-1]
    s3 = face_gear_points["S3"]
    cold, b = s3.scalar("dT_min"), s3.scalar("b")
    hottest = lub.inlet_temperature + s3.scalar("dT_max")
    adiabatic = lub.thermal_expansion * hottest * s3.scalar("p_max") / (lub.density * lub.specific_heat)
    assert -adiabatic < cold < -5.0
    assert 0.0 < s3.scalar("x_dT_min") < 1.5 * b
    mid = s3.fields["temperature_mid"].values  # the coldest layer is mid-film: the walls are warmer
    assert mid.min() - lub.inlet_temperature == pytest.approx(cold, abs=1e-9)
    j, i = np.unravel_index(np.argmin(mid), mid.shape)
    assert (s3.axes["x"].values[i], s3.axes["y"].values[j]) == (s3.scalar("x_dT_min"), s3.scalar("y_dT_min"))
    # in the written file: tehl info --json and the run table
    info = CliRunner().invoke(tehl, ["info", str(facegear_file), "--json"])
    assert info.exit_code == 0
    points = json.loads(info.output)["points"]
    assert points["S3"]["dT_min"] == pytest.approx(cold, rel=1e-12)
    rows = CliRunner().invoke(tehl, ["info", str(facegear_file)]).output.splitlines()
    assert any(row.split()[:2] == ["dT_min", "K"] for row in rows if row.strip())
    # the run summary: a dT_min column next to dT_max
    header = summary_table(read_result(facegear_file).points.values()).splitlines()[0]
    assert "dT_max K  dT_min K" in header


@pytest.mark.slow
def test_the_outlet_hot_spot_is_the_adiabatic_compression_through_the_pressure_spike():
    """Where the film's largest temperature rise comes from at a sliding point below full load (S2 of the default
    case, its default grid): on the row of dT_max, between the lowest pressure downstream of the centre and the hot
    node at the spike's rising flank, the mid-film temperature rises by the adiabatic compression of the oil,
    dT = \\int beta_T T/(rho c) dp (beta_T = eps_T/(1 - eps_T (T - T_0)) of the density law), plus a little shear
    heating: the flank is crossed in ~1 µs, far faster than heat crosses the film (h^2 rho c/k ~ 30 µs). So dT_max
    at S2 and S4 converges with the grid as the sampled spike does (docs/accuracy.md)."""
    from facegear_tehl.run import run_case

    case = load_case("cases/facegear_110.yaml")
    sol = run_case(case, points=["S2"], jobs=1).points[0]
    assert sol.converged, sol.message
    lub = case.lubricant
    p, t = sol.fields["pressure"].values, sol.fields["temperature_mid"].values
    x = sol.axes["x"].values
    j, i = np.unravel_index(np.argmax(t), t.shape)
    assert t[j, i] - lub.inlet_temperature == pytest.approx(sol.scalar("dT_max"), rel=1e-9)
    centre = int(np.searchsorted(x, 0.0))
    assert i > centre  # in the outlet half
    k = centre + int(np.argmin(p[j, centre:i + 1]))
    pressure, temperature = p[j, k:i + 1], t[j, k:i + 1]
    beta = lub.thermal_expansion / (1.0 - lub.thermal_expansion * (temperature - lub.inlet_temperature))
    integrand = beta * temperature / (lub.density_at(pressure, temperature) * lub.specific_heat)
    adiabatic = float(np.sum(0.5 * (integrand[1:] + integrand[:-1]) * np.diff(pressure)))
    assert pressure[-1] - pressure[0] > 0.15 * sol.scalar("p_hertz")  # the spike's rising flank
    assert 1.0 < (temperature[-1] - temperature[0]) / adiabatic < 1.25


def _hertzian_film():
    """The sliding contact's point and lubricant, a 33 x 17 grid (x, y in m) around its Hertz ellipse, the Hertz
    pressure (Pa) and a 100 nm film plus the gap of its radii (m): a film state's inputs for the update's own tests."""
    point, lub, _ = plain(SLIDING)
    a, b = point.hertz.a, point.hertz.b
    x, y = np.linspace(-3.0 * b, 1.5 * b, 33), np.linspace(-2.0 * a, 2.0 * a, 17)
    xx, yy = np.meshgrid(x, y)
    pressure = point.hertz.p_max * np.sqrt(np.maximum(1.0 - (xx / b) ** 2 - (yy / a) ** 2, 0.0))
    film = 1e-7 + xx**2 / (2.0 * point.hertz.radius_x) + yy**2 / (2.0 * point.hertz.radius_y)
    return point, lub, x, y, pressure, film


def test_deferred_wall_fluxes_are_the_updates_own_and_close_its_energy_budget():
    # An outer loop's updates leave out their wall heat fluxes (they cost a sweep) and `completed` adds them for the
    # state the loop ends on: the fluxes an update computes itself, and with them its discrete energy budget closes
    # (energy.energy_budget: generated + mass defect = conducted + convected, to the sweeps' tolerance).
    point, lub, x, y, pressure, film = _hertzian_film()

    def model():
        return FilmThermalModel(x, y, 7, lub, point, solve_energy=True)

    entry = model().initial_temperature()
    whole = model().update(pressure, film, entry)
    deferring = model()
    first = deferring.update(pressure, film, entry, wall_fluxes=False)
    assert first.heat_flux_1 is None and first.heat_flux_2 is None
    later = [deferring.update(pressure, film, first.temperature, wall_fluxes=False) for _ in range(2)]
    completed = deferring.completed(dataclasses.replace(later[0], temperature=later[0].temperature + 1.0))
    assert completed.heat_flux_1 is not None  # the update before the last one: kept for a loop that runs away
    with pytest.raises(ValueError):
        deferring.completed(first)  # three updates back: no longer kept
    state = model().completed(whole)  # a state with its fluxes stays as it is
    assert state is whole
    again, temperature = model(), entry
    for _ in range(30):  # the updates' fixed point at this pressure: the state an outer loop ends on
        state = again.update(pressure, film, temperature, wall_fluxes=False)
        temperature = state.temperature
    assert state.change < 1e-6 * (temperature.max() - lub.inlet_temperature)
    state = again.completed(state)
    exact = model().update(pressure, film, temperature)  # the same fixed point, its fluxes computed by the update
    assert np.allclose(state.heat_flux_1, exact.heat_flux_1, rtol=1e-9, atol=0.0)
    budget = energy_budget(state, film, x[1] - x[0], y[1] - y[0], lub.inlet_temperature)
    assert budget["heat_conducted"] > 0.0
    assert abs(budget["energy_balance_error"]) < 1e-6
    fresh = model()
    deferred = fresh.completed(fresh.update(pressure, film, entry, wall_fluxes=False))
    assert np.array_equal(deferred.heat_flux_1, whole.heat_flux_1)
    assert np.array_equal(deferred.heat_flux_2, whole.heat_flux_2)


def test_an_isothermal_films_deferred_wall_fluxes_are_those_of_its_temperatures():
    # Without the energy equation an update's wall fluxes are the conduction of the temperatures it was given
    # (energy.wall_heat_flux); deferred, `completed` gives the same numbers. A temperature linear across the film
    # conducts k dT/dh through either wall (the one-sided differences are exact for it).
    point, lub, x, y, pressure, film = _hertzian_film()
    nz, rise = 9, 4.0  # K from surface 1 to surface 2
    temperature = lub.inlet_temperature + rise * np.linspace(0.0, 1.0, nz)[:, None, None] * np.ones(film.shape)

    def model():
        return FilmThermalModel(x, y, nz, lub, point, solve_energy=False)

    whole = model().update(pressure, film, temperature)
    deferring = model()
    state = deferring.update(pressure, film, temperature, wall_fluxes=False)
    assert state.heat_flux_1 is None and state.heat_flux_2 is None
    state = deferring.completed(state)
    assert np.array_equal(state.heat_flux_1, whole.heat_flux_1)
    assert np.array_equal(state.heat_flux_2, whole.heat_flux_2)
    conducted = lub.conductivity_at(pressure) * rise / film
    assert np.allclose(state.heat_flux_1, conducted, rtol=1e-9)
    assert np.allclose(state.heat_flux_2, -conducted, rtol=1e-9)


def test_accelerated_temperatures_move_by_at_most_the_continuation_step():
    # A hot film's updates held at the continuation limit give nearly equal steps, which Anderson's secant
    # extrapolates far beyond the limit; the outer loop takes no more than the limit per update.
    shape = (3, 4, 5)
    t_in = 313.0

    def update(temperature: np.ndarray, rise: float) -> FilmState:
        ones = np.ones(shape)
        return FilmState(temperature=temperature + rise, viscosity_factor=ones, dissipation=ones, velocity_x=None,
                         velocity_y=None, stress_1=ones[:2], stress_2=ones[:2], heat_flux_1=None, heat_flux_2=None,
                         compression=None, change=rise)

    def steps(limited: bool) -> list[float]:
        accelerator, temperature, factor, jumps = Anderson(3), np.full(shape, t_in), np.ones(shape), []
        step = TUNING.max_temperature_step
        for held in (step, 0.99 * step):  # the updates, each at (or by) the limit
            if limited:
                new, _, _, _ = next_film_state(accelerator, temperature, factor, update(temperature, held), 1.0,
                                                      max(float(temperature.max()) - t_in, 1.0))
            else:  # the accelerator alone, as next_film_state weighs it
                rise = max(float(temperature.max()) - t_in, 1.0)
                x = accelerator.step(np.concatenate([temperature.ravel(), np.zeros(temperature.size)]),
                                     np.concatenate([np.full(temperature.size, TUNING.thermal_relaxation * held),
                                                     np.zeros(temperature.size)]),
                                     (1.0 / rise, 1.0))
                new = x[:temperature.size].reshape(shape)
            jumps.append(float(np.abs(new - temperature).max()))
            temperature = new
        return jumps

    free, limited = steps(False), steps(True)
    # no history yet
    assert free[0] == limited[0] == pytest.approx(TUNING.thermal_relaxation * TUNING.max_temperature_step)
    assert free[1] > 10.0 * TUNING.max_temperature_step  # the secant through two nearly equal steps
    assert limited[1] == pytest.approx(TUNING.max_temperature_step)


@pytest.mark.parametrize("law", ["roelands", "barus"])
def test_layer_viscosity_is_the_node_by_node_law_with_or_without_the_temperature_factors_given(law):
    # thermal.layer_viscosity factors the Roelands pressure term once per column and takes the temperature factors
    # the film state's pressure cycles evaluated (flow.temperature_factors) when given: every node equals
    # lubricant_laws.viscosity_ratio_at and viscosity_temperature_coefficient_at; Barus takes no factors.
    lubricant = dataclasses.replace(load_case(SLIDING).lubricant, viscosity_model=law)
    parameters = lubricant.law_parameters()
    rng = np.random.default_rng(5)
    pressure = rng.uniform(-1e7, 1.5e9, (4, 6))
    temperature = rng.uniform(300.0, 420.0, (5, 4, 6))
    temperature[2] = temperature[1]  # a layer at the temperature of the one below it
    expected_ratio = np.empty_like(temperature)
    expected_beta = np.empty_like(temperature)
    for (k, j, i), t in np.ndenumerate(temperature):
        expected_ratio[k, j, i] = viscosity_ratio_at(pressure[j, i], t, parameters)
        expected_beta[k, j, i] = viscosity_temperature_coefficient_at(pressure[j, i], t, parameters)
    for given in (np.empty((0, 0, 0)), temperature_factors(temperature, parameters)):
        ratio, beta = layer_viscosity(pressure, temperature, parameters, True, given)
        assert np.array_equal(ratio, expected_ratio) and np.array_equal(beta, expected_beta)


def test_relaxed_steps_are_the_numpy_expressions_of_the_outer_loop_step():
    # thermal.relaxed_steps forms the outer loop's iterate (T, ln(eta*/eta)) and its relaxed plain step in one pass:
    # the same numbers as the NumPy expressions, the largest |step| of each half, NaN when one of its steps is.
    rng = np.random.default_rng(11)
    shape = (3, 4, 5)
    temperature, updated = rng.uniform(310.0, 400.0, shape), rng.uniform(310.0, 400.0, shape)
    factor, updated_factor = rng.uniform(0.1, 1.0, shape), rng.uniform(0.1, 1.0, shape)
    size = temperature.size
    x, f = np.empty(2 * size), np.empty(2 * size)
    np.log(factor.ravel(), out=x[size:])
    np.log(updated_factor.ravel(), out=f[size:])
    largest_t, largest_f = relaxed_steps(temperature, updated, 0.7, 0.4, x, f)
    step_t = 0.7 * (updated - temperature)
    step_f = 0.4 * (np.log(updated_factor) - np.log(factor))
    assert np.array_equal(x, np.concatenate([temperature.ravel(), np.log(factor).ravel()]))
    assert np.array_equal(f, np.concatenate([step_t.ravel(), step_f.ravel()]))
    assert (largest_t, largest_f) == (np.abs(step_t).max(), np.abs(step_f).max())
    updated[1, 2, 3] = np.nan
    np.log(updated_factor.ravel(), out=f[size:])
    largest_t, largest_f = relaxed_steps(temperature, updated, 0.7, 0.4, x, f)
    assert math.isnan(largest_t) and largest_f == np.abs(step_f).max()
