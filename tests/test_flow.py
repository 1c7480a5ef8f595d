"""Generalised Reynolds coefficients (flow.py): limits with known closed forms."""

import numpy as np
import pytest

from facegear_tehl.ehl.flow import (
    column_integrals,
    frozen_layered_coefficients,
    frozen_shapes,
    isothermal_coefficients,
    isothermal_layered_coefficients,
    layer_integrals,
    temperature_factors,
)
from facegear_tehl.lubricant import Lubricant


def layered_coefficients(p, film, temperature, factors, viscosity_factor, law, lam, kappa, sx, sy, u1, u2, *out):
    """eps, f_x, f_y of a layered film at the pressure p (Pa) it is frozen at: the layer integrals themselves."""
    shapes = frozen_shapes(p, temperature, factors, viscosity_factor, law)
    frozen_layered_coefficients(p, film, shapes, temperature, factors, viscosity_factor, law, lam, kappa, sx, sy, u1,
                                u2, *out)


@pytest.mark.parametrize("nz", [3, 5, 9])
def test_constant_properties_are_exact(nz):
    # rho h^3/(12 eta) and rho h u_e: 12 (F1 R2/F0 - R1) = rho/eta, R2/F0 = rho/2.
    f0, f1, r0, r1, r2 = layer_integrals(np.full(nz, 2.0), np.full(nz, 1.5))
    assert 12 * (f1 * r2 / f0 - r1) == pytest.approx(0.75, rel=1e-14)
    assert r2 / f0 == pytest.approx(0.75, rel=1e-14)


def test_viscosity_linear_in_depth_against_quadrature():
    # Couette share R2/F0 for eta(z) = 1 + 3 z (exact by scipy quadrature), rho = 1.
    from scipy import integrate

    def eta(z):
        return 1.0 + 3.0 * z

    f0_exact = integrate.quad(lambda z: 1 / eta(z), 0, 1)[0]
    r2_exact = integrate.quad(lambda z: integrate.quad(lambda s: 1 / eta(s), 0, z)[0], 0, 1)[0]
    z = np.linspace(0, 1, 33)
    f0, _, _, _, r2 = layer_integrals(eta(z), np.ones_like(z))
    assert f0 == pytest.approx(f0_exact, rel=1e-3)
    assert r2 / f0 == pytest.approx(r2_exact / f0_exact, rel=1e-3)


def test_layered_isothermal_newtonian_equals_isothermal():
    lub = Lubricant(viscosity=0.03, inlet_temperature=313.15, pressure_viscosity=1.5e-8, density=880.0,
                    temperature_viscosity=0.04, thermal_expansion=7e-4)
    law = lub.law_parameters()
    rng = np.random.default_rng(1)
    p = rng.uniform(0, 1.5e9, (6, 7))
    film = rng.uniform(0.1, 2.0, (6, 7))
    a = [np.empty((6, 7)) for _ in range(3)]
    b = [np.empty((6, 7)) for _ in range(3)]
    cx, cy, kappa = 0.9, 0.02, 0.05
    isothermal_coefficients(p, film, law, 313.15, 0.7, cx, cy, *a)
    temperature = np.full((5, 6, 7), 313.15)
    # u1 + u2 = 2 (cos psi, sin psi); cy = kappa sin psi
    sin_psi = cy / kappa
    u1 = np.array([1.3 * cx, 0.6 * sin_psi])
    u2 = np.array([2 * cx - u1[0], 2 * sin_psi - u1[1]])
    layered_coefficients(p, film, temperature, temperature_factors(temperature, law), np.ones_like(temperature), law,
                         0.7, kappa, 1.0, 1.0, u1, u2, *b)
    for x, y in zip(a, b):
        assert np.allclose(x, y, rtol=1e-12, atol=0)


def _lubricant_law():
    lub = Lubricant(viscosity=0.03, inlet_temperature=313.15, pressure_viscosity=1.5e-8, density=880.0,
                    temperature_viscosity=0.04, thermal_expansion=7e-4)
    return lub.law_parameters()


def test_column_shapes_closed_form():
    # Fluidity eta/eta* = 1 + 3 zeta across the film (quadratic integrands: the fourth-order rules are exact):
    # a0 = 5/2, a1 = 3/2, b1 = \int (zeta^2/2 + zeta^3) = 5/12, b2 = \int (zeta + 3 zeta^2/2) = 1, so the shapes are
    # a1 b2/a0 - b1 = 11/60 and b2/a0 = 2/5; a Newtonian column (eta* = eta) gives 1/12 and 1/2.
    zeta = np.linspace(0.0, 1.0, 9)
    factor = np.empty((9, 2, 3))
    factor[:, 0, :] = (1.0 / (1.0 + 3.0 * zeta))[:, None]
    factor[:, 1, :] = 1.0
    shapes = column_integrals(factor)
    assert np.allclose(shapes[:, 0, :], np.array([11.0 / 60.0, 0.4])[:, None], rtol=1e-14, atol=0)
    assert np.allclose(shapes[:, 1, :], np.array([1.0 / 12.0, 0.5])[:, None], rtol=1e-14, atol=0)


def test_isothermal_layered_equals_layered():
    # One temperature per column (varying over the grid) and an Eyring profile eta*/eta varying across the film: the
    # column form equals the layer-by-layer integrals of the same film to rounding.
    law = _lubricant_law()
    rng = np.random.default_rng(2)
    shape = (9, 6, 7)
    p = rng.uniform(0, 1.5e9, shape[1:])
    film = rng.uniform(0.1, 2.0, shape[1:])
    column_t = rng.uniform(313.15, 360.0, shape[1:])
    temperature = np.ascontiguousarray(np.broadcast_to(column_t, shape))
    factor = np.exp(-rng.uniform(0.0, 6.0, shape))
    u1, u2, kappa = np.array([1.3, 0.01]), np.array([0.7, 0.03]), 0.05
    a = [np.empty(shape[1:]) for _ in range(3)]
    b = [np.empty(shape[1:]) for _ in range(3)]
    factors = temperature_factors(temperature, law)
    layered_coefficients(p, film, temperature, factors, factor, law, 0.7, kappa, 1.0, -1.0, u1, u2, *a)
    isothermal_layered_coefficients(p, film, column_t, factors[0], column_integrals(factor), law, 0.7, kappa, 1.0, -1.0,
                                    u1, u2, *b)
    for x, y in zip(a, b):
        assert np.allclose(x, y, rtol=1e-12, atol=0)


def test_isothermal_newtonian_column_is_closed_form():
    # eta* = eta: eps = rho H^3/(eta lambda) and f = s rho c, the closed-form Newtonian film (isothermal_coefficients).
    law = _lubricant_law()
    rng = np.random.default_rng(3)
    p = rng.uniform(0, 1.5e9, (6, 7))
    film = rng.uniform(0.1, 2.0, (6, 7))
    cx, cy, kappa = 0.9, 0.02, 0.05
    sin_psi = cy / kappa
    u1 = np.array([1.3 * cx, 0.6 * sin_psi])
    u2 = np.array([2 * cx - u1[0], 2 * sin_psi - u1[1]])
    a = [np.empty((6, 7)) for _ in range(3)]
    b = [np.empty((6, 7)) for _ in range(3)]
    isothermal_coefficients(p, film, law, 313.15, 0.7, cx, cy, *a)
    temperature = np.full((6, 7), 313.15)
    isothermal_layered_coefficients(p, film, temperature, temperature_factors(temperature, law),
                                    column_integrals(np.ones((5, 6, 7))), law, 0.7, kappa, 1.0, 1.0, u1, u2, *b)
    for x, y in zip(a, b):
        assert np.allclose(x, y, rtol=1e-12, atol=0)


def _layered_film(law_name, layered_temperature):
    """A film state of 9 layers on 6 x 7 columns: Eyring factors across the film, temperatures rising from the walls
    to mid-film (or one per column), pressures 0.2-1.2 GPa."""
    lub = Lubricant(viscosity=0.03, inlet_temperature=313.15, pressure_viscosity=1.5e-8, density=880.0,
                    temperature_viscosity=0.04, thermal_expansion=7e-4, viscosity_model=law_name)
    rng = np.random.default_rng(4)
    shape = (9, 6, 7)
    zeta = np.linspace(0.0, 1.0, shape[0])[:, None, None]
    column_t = rng.uniform(313.15, 340.0, shape[1:])
    rise = 4.0 * zeta * (1.0 - zeta) * rng.uniform(20.0, 60.0, shape[1:]) if layered_temperature else 0.0
    temperature = np.ascontiguousarray(column_t + rise + np.zeros(shape))
    factor = np.exp(-rng.uniform(0.0, 3.0, shape))
    return lub.law_parameters(), temperature, factor, rng.uniform(0.2e9, 1.2e9, shape[1:]), rng.uniform(0.5, 2.0,
                                                                                                       shape[1:])


def _frozen_against_exact(law, temperature, factor, p0, film, p1):
    """The largest relative difference of eps, f_x, f_y between the state frozen at p0 (Pa) evaluated at p1 and
    the layer integrals at p1."""
    u1, u2, kappa = np.array([1.3, 0.01]), np.array([0.7, 0.03]), 0.05
    factors = temperature_factors(temperature, law)
    frozen = [np.empty(film.shape) for _ in range(3)]
    exact = [np.empty(film.shape) for _ in range(3)]
    shapes = frozen_shapes(p0, temperature, factors, factor, law)
    refrozen = frozen_layered_coefficients(p1, film, shapes, temperature, factors, factor, law, 0.7, kappa, 1.0, -1.0,
                                           u1, u2, *frozen)
    assert refrozen == 0
    layered_coefficients(p1, film, temperature, factors, factor, law, 0.7, kappa, 1.0, -1.0, u1, u2, *exact)
    return max(float(np.abs(a / b - 1.0).max()) for a, b in zip(frozen, exact))


@pytest.mark.parametrize("law_name, layered", [("barus", True), ("roelands", False)])
def test_a_frozen_film_follows_the_pressure_exactly_where_its_layers_share_one_viscosity_law(law_name, layered):
    # Barus: ln(eta) moves by alpha dp in every layer; Roelands with one temperature per column: by ln-term S dv
    # with the same temperature factor S in every layer. The frozen shapes then scale exactly, the pressure moved by
    # up to +-0.4 GPa (the Eyring factors eta*/eta stay frozen in both).
    law, temperature, factor, p0, film = _layered_film(law_name, layered)
    p1 = p0 + np.random.default_rng(5).uniform(-0.4e9, 0.4e9, p0.shape)
    assert _frozen_against_exact(law, temperature, factor, p0, film, p1) < 1e-11


def test_a_frozen_layered_film_departs_from_its_integrals_at_second_order_in_the_pressure_change():
    # Roelands with temperatures rising by 20-60 K to mid-film: the layers' viscosities move with the pressure at
    # slopes that differ by their temperature factors; the frozen film moves its two shapes along their exact first
    # derivatives, so it departs from the layer integrals by O(dp^2): halving the pressure change quarters the
    # difference (a 20 MPa change: 5e-5).
    law, temperature, factor, p0, film = _layered_film("roelands", True)
    step = 0.02e9
    large = _frozen_against_exact(law, temperature, factor, p0, film, p0 + step)
    small = _frozen_against_exact(law, temperature, factor, p0, film, p0 + 0.5 * step)
    assert 1e-7 < large < 2e-4
    assert large / small == pytest.approx(4.0, rel=0.1)
