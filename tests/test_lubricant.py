"""Viscosity and density laws (Roelands 1966, Dowson & Higginson 1966, Yang & Wen 1990) against values
computed independently from the published formulas."""

import numpy as np
import pytest

from facegear_tehl.lubricant import KELVIN, Lubricant
from facegear_tehl.lubricant_laws import temperature_coefficient


def roelands(**kw):
    base = dict(viscosity=0.0294, inlet_temperature=40.0 + KELVIN, pressure_viscosity=2.131e-8, density=900.0,
                roelands_z=0.68)
    base.update(kw)
    return Lubricant(**base)


@pytest.mark.parametrize("p_gpa, ratio", [(0.1, 7.2989), (0.5, 4.4436e3), (1.0, 2.8743e6), (2.0, 1.3433e11)])
def test_roelands_pressure_table(p_gpa, ratio):
    lub = roelands()
    assert lub.viscosity_at(p_gpa * 1e9) / lub.viscosity == pytest.approx(ratio, rel=1e-4)


def test_roelands_limit_and_temperature_form():
    # eta_inf = exp(-9.67) Pa s; with S0 = 1.1 the temperature form gives 0.014763 Pa s at 60 degC, 0.0084744 at 80 degC
    lub = roelands()
    s0 = 1.1
    beta = s0 * lub.roelands_log_term / (lub.inlet_temperature - 138.0)
    hot = roelands(temperature_viscosity=beta)
    assert hot.s0 == pytest.approx(s0, rel=1e-12)
    assert hot.viscosity_at(0.0, 60.0 + KELVIN) == pytest.approx(0.014763, rel=1e-4)
    assert hot.viscosity_at(0.0, 80.0 + KELVIN) == pytest.approx(0.0084744, rel=1e-4)
    assert lub.roelands_log_term == pytest.approx(np.log(0.0294) + 9.67, rel=1e-12)


@pytest.mark.parametrize("p_gpa, ratio", [(0.5, 1.15596), (1.0, 1.21384), (2.0, 1.26255)])
def test_dowson_higginson_density(p_gpa, ratio):
    assert roelands().density_at(p_gpa * 1e9) / 900.0 == pytest.approx(ratio, rel=1e-5)


def test_temperature_coefficient_is_minus_dln_eta_dt():
    lub = roelands(temperature_viscosity=0.042)
    law = lub.law_parameters()
    p = np.array([0.0, 3e8, 1e9])
    t = np.array([313.15, 340.0, 380.0])
    beta = temperature_coefficient(p, t, law)
    dt = 1e-3
    numeric = -(np.log(lub.viscosity_at(p, t + dt)) - np.log(lub.viscosity_at(p, t - dt))) / (2 * dt)
    assert np.allclose(beta, numeric, rtol=1e-6)
    assert beta[0] == pytest.approx(0.042, rel=1e-12)  # the given beta at the inlet, p = 0
