"""The Ree-Eyring film state of the outer loops (ehl/solve.py): its Newtonian columns, isothermal and thermal."""

from dataclasses import replace
import math

import numpy as np
import pytest

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import rheology, solve
from facegear_tehl.ehl.friction import friction_coefficients
from facegear_tehl.ehl.report import cell_area
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.materials import Solid
from facegear_tehl.settings import SolverSettings

STEEL = Solid(elastic_modulus=2.0e11, poisson_ratio=0.3)
OIL = Lubricant(viscosity=0.04, pressure_viscosity=2.2e-8, rheology="ree_eyring", eyring_stress=1.0e7)


def _bounded_and_full_updates(monkeypatch, mode: solve.ThermalMode):
    """A ball on a flat (p_h = 1.33 GPa, 5 m/s, SRR 0.5) solved isothermal Ree-Eyring on 65 x 65, and one update of the
    film model of `mode` at its converged pressure from the inlet temperature, with the columns below the Newtonian
    bound r_N = sqrt(6 share tolerance) taken as Newtonian and with every column solved: (solver, level, the two
    states, r_N)."""
    point = ContactPoint.from_rolling_sliding("ball", 0.01, 0.01, 100.0, 5.0, 0.5, 0.0, STEEL, STEEL)
    solver = solve.PointSolve(point, OIL, SolverSettings(grid=65, thermal="off"))
    assert solver.begin().converged
    level = solver.solver.levels[-1]
    pressure, film = level.pressure * solver.scaling.p_h, level.film * solver.scaling.film_scale
    solver.mode = mode
    bounded = solver._film_model(level)
    bound = math.sqrt(6.0 * TUNING.eyring_newtonian_share * solver.settings.eyring_tolerance)
    assert bounded.newtonian_below == pytest.approx(bound, rel=1e-12)
    assert bounded.solve_energy == (mode is not solve.ThermalMode.OFF)
    monkeypatch.setattr(solve, "TUNING", replace(TUNING, eyring_newtonian_share=0.0))
    full = solver._film_model(level)
    temperature = full.initial_temperature()
    return solver, level, [model.update(pressure, film, temperature) for model in (bounded, full)], bound


def _within_bound(states, bound: float, share: float) -> None:
    """More than `share` of the columns taken as Newtonian, none with every column solved, and ln(eta*/eta) within
    r_N^2/6 (sinh r/r <= exp(r^2/6)) and not the same."""
    newtonian = np.all(states[0].viscosity_factor == 1.0, axis=0)
    assert share < newtonian.mean() < 1.0 and not np.any(np.all(states[1].viscosity_factor == 1.0, axis=0))
    difference = np.abs(np.log(states[0].viscosity_factor) - np.log(states[1].viscosity_factor))
    assert 0.0 < difference.max() <= bound * bound / 6.0


def test_newtonian_columns_of_a_converged_eyring_film(monkeypatch):
    # the isothermal film: the bound takes effect (the inlet's columns are Newtonian), and the friction coefficient is
    # the same to 1e-6
    solver, level, states, bound = _bounded_and_full_updates(monkeypatch, solve.ThermalMode.OFF)
    _within_bound(states, bound, 0.3)
    mu = [friction_coefficients(state, level.pressure, cell_area(level, solver.scaling), solver.point.load)[0]
          for state in states]
    assert mu[0] == pytest.approx(mu[1], rel=1e-6)


def test_log_factor_change_is_the_logarithms_and_skips_newtonian_entries():
    # ln(eta*/eta) and its change toward an update, against NumPy's logarithms; entries at 1 in both give exact zeros
    rng = np.random.default_rng(21)
    factor = np.exp(-rng.uniform(0.0, 5.0, (9, 13, 31)))
    updated = np.exp(-rng.uniform(0.0, 5.0, factor.shape))
    newtonian = rng.random(factor.shape[1:]) < 0.8
    factor[:, newtonian] = updated[:, newtonian] = 1.0
    updated[4, 0, 0], factor[2, 1, 1] = 1.0, 1.0  # at 1 in one of the two only: a logarithm taken
    log_factor, change = np.full(factor.shape, np.nan), np.full(factor.shape, np.nan)
    largest = rheology.log_factor_change(factor, updated, log_factor, change)
    expected = np.log(updated) - np.log(factor)
    assert np.allclose(log_factor, np.log(factor), rtol=1e-15, atol=0.0)
    assert np.allclose(change, expected, rtol=1e-14, atol=1e-15)
    assert not log_factor[:, newtonian].any() and not change[:, newtonian].any()
    assert largest == pytest.approx(float(np.abs(expected).max()), rel=1e-15)


def test_newtonian_columns_of_a_thermal_film(monkeypatch):
    # The thermal film model takes the same Newtonian bound: its layered state differs in ln(eta*/eta) by no more than
    # r_N^2/6, and the temperatures the energy equation gives for the two by a small share of the rise.
    _, _, states, bound = _bounded_and_full_updates(monkeypatch, solve.ThermalMode.FULL)
    _within_bound(states, bound, 0.1)
    rise = float(states[1].temperature.max()) - OIL.inlet_temperature
    assert rise > 1.0
    assert np.abs(states[0].temperature - states[1].temperature).max() < 1e-3 * rise
