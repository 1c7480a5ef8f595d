"""Pressure-dependent thermal conductivity of the lubricant (issue 4): the Larsson et al.
(2000) law against hand values, its case keys, the energy kernel against the conduction solution of a uniformly
heated film, and its effect on a small thermal solve. The defaults (a = b = 0) keep the constant k_0 bit for bit."""

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from facegear_tehl.case import load_case, parse_case
from facegear_tehl.ehl import energy
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.lubricant import KELVIN, Lubricant
from facegear_tehl.lubricant_laws import conductivity_ratio, conductivity_ratio_at
from facegear_tehl.points import contact_analysis
from facegear_tehl.schema import CaseError

SLIDING = Path(__file__).resolve().parents[1] / "cases" / "ball_on_disc_sliding.yaml"
PAOB = dict(thermal_conductivity=0.154, conductivity_pressure_coefficient=1.40, conductivity_pressure_saturation=0.34)
# k/k_0 = 1 + 1.4 p/(1 + 0.34 p) by hand: p = 0.5 GPa: 1 + 0.7/1.17 = 187/117; p = 1 GPa: 1 + 1.4/1.34 = 137/67
HAND = [(0.0, 1.0), (0.5, 187.0 / 117.0), (1.0, 137.0 / 67.0)]


def oil(**kw):
    return Lubricant(viscosity=0.04, inlet_temperature=40.0 + KELVIN, pressure_viscosity=2.2e-8, density=870.0, **kw)


@pytest.mark.parametrize("p_gpa, ratio", HAND)
def test_larsson_law_against_hand_values(p_gpa, ratio):
    assert conductivity_ratio_at(p_gpa * 1e9, 1.40, 0.34) == pytest.approx(ratio, rel=1e-14)
    assert oil(**PAOB).conductivity_at(p_gpa * 1e9) == pytest.approx(0.154 * ratio, rel=1e-14)
    assert {0.0: 0.154, 0.5: 0.246137, 1.0: 0.314896}[p_gpa] == pytest.approx(0.154 * ratio, abs=5e-7)


def test_larsson_law_on_arrays_clips_negative_pressure_and_saturates():
    p = np.array([[-1e8, 0.0], [0.5e9, 1e9]])
    k = oil(**PAOB).conductivity_at(p)
    assert k.shape == (2, 2)
    np.testing.assert_allclose(k, 0.154 * np.array([[1.0, 1.0], [187.0 / 117.0, 137.0 / 67.0]]), rtol=1e-14)
    assert conductivity_ratio(np.array([1e15]), 1.40, 0.34)[0] == pytest.approx(1.0 + 1.40 / 0.34, rel=1e-5)


def test_default_conductivity_is_exactly_k0():
    p = np.linspace(-1e9, 5e9, 1001)
    assert np.array_equal(oil().conductivity_at(p), np.full(p.shape, 0.13))
    lub = load_case(SLIDING).lubricant
    assert (lub.conductivity_pressure_coefficient, lub.conductivity_pressure_saturation) == (0.0, 0.0)
    assert np.array_equal(lub.conductivity_at(p), np.full(p.shape, 0.14))


def test_uniformly_heated_film_without_convection_has_the_conduction_solution_with_k_of_p():
    # Film at rest, uniform heating Q, both walls at T_w: T - T_w = Q z (h - z)/(2 k), the mid-film excess
    # Q h^2/(8 k(p)) with k at each column's pressure, and Q h/2 into each wall whatever k is. The layer
    # scheme is exact for this quadratic.
    nz, q, h, t_wall = 9, 5e13, 4e-7, 350.0
    pressures = np.array([[0.0, 0.5e9, 1.0e9]])
    shape = (nz,) + pressures.shape
    temperature = np.full(shape, t_wall)
    zero = np.zeros(shape)
    film = np.full(pressures.shape, h)
    conductivity = oil(**PAOB).conductivity_at(pressures)
    energy.sweep_film_temperature(temperature, zero, zero.copy(), np.full(shape, q), zero.copy(), zero.copy(),
                                  np.full(shape, 1.7e6), conductivity, film, 1e-6, 1e-6, t_wall, 2, 0.0)
    k_hand = 0.154 * np.array([1.0, 187.0 / 117.0, 137.0 / 67.0])
    np.testing.assert_allclose(temperature[nz // 2, 0] - t_wall, q * h**2 / (8.0 * k_hand), rtol=1e-9)
    assert q * h**2 / (8.0 * 0.154) == pytest.approx(6.4935, rel=1e-4)  # K, at p = 0
    z = np.linspace(0.0, h, nz)[:, None]
    np.testing.assert_allclose(temperature[:, 0] - t_wall, q * z * (h - z) / (2.0 * k_hand), rtol=1e-9, atol=1e-12)
    q1, q2 = energy.wall_heat_flux(temperature, film, conductivity)
    np.testing.assert_allclose(q1, q * h / 2.0, rtol=1e-9)
    np.testing.assert_allclose(q2, q * h / 2.0, rtol=1e-9)


def _sliding_lubricant_text(extra: str) -> str:
    return SLIDING.read_text().replace("  specific_heat: 2000.0", extra + "\n  specific_heat: 2000.0")


def test_case_keys_are_read_in_per_gpa():
    lub = parse_case(_sliding_lubricant_text("  conductivity_pressure_coefficient: 1.40\n"
                                             "  conductivity_pressure_saturation: 0.34")).lubricant
    assert (lub.conductivity_pressure_coefficient, lub.conductivity_pressure_saturation) == (1.40, 0.34)
    assert lub.conductivity_at(1e9) == pytest.approx(0.14 * 137.0 / 67.0, rel=1e-14)


@pytest.mark.parametrize("key", ["conductivity_pressure_coefficient", "conductivity_pressure_saturation"])
@pytest.mark.parametrize("value, expected", [("-0.5", "a number >= 0 in 1/GPa"), (".inf", "a finite number in 1/GPa"),
                                             (".nan", "a finite number in 1/GPa"), ("high", "a finite number in 1/GPa"),
                                             ("1.0e3", "a number <= 100 in 1/GPa")])
def test_bad_conductivity_keys_are_named(key, value, expected):
    with pytest.raises(CaseError) as error:
        parse_case(_sliding_lubricant_text(f"  {key}: {value}"))
    assert str(error.value).startswith(f"lubricant.{key}: got ")
    assert expected in str(error.value)


def test_misspelt_conductivity_key_gets_a_hint():
    with pytest.raises(CaseError, match=r"lubricant.conductivity_pressure_coeficient: .*did you mean "
                                        r"'conductivity_pressure_coefficient'"):
        parse_case(_sliding_lubricant_text("  conductivity_pressure_coeficient: 1.4"))


def test_higher_conductivity_under_pressure_cools_the_film_and_the_energy_balance_still_closes():
    # Ball on disc, SRR = 1, p_h = 0.45 GPa, 33^2: k rises to 1.14 k_0 at p_h with the PAOB coefficients.
    case = load_case(SLIDING)
    point = contact_analysis(case).points[0]
    settings = dataclasses.replace(case.solver, grid=33, thermal="full")
    larsson = dataclasses.replace(case.lubricant, conductivity_pressure_coefficient=1.40,
                                  conductivity_pressure_saturation=0.34)
    constant = solve_point(point, case.lubricant, settings)
    cooled = solve_point(point, larsson, settings)
    assert constant.converged and cooled.converged
    assert cooled.scalar("dT_max") < 0.9 * constant.scalar("dT_max")
    assert cooled.models["conductivity"].startswith("larsson") and constant.models["conductivity"] == "constant"
    generated = cooled.scalar("heat_generated")
    assert generated > 0.0
    assert abs(cooled.scalar("heat_conducted") + cooled.scalar("heat_convected") - generated) < 0.02 * generated
