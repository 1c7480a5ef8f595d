"""Across-film discretisation (layers.py, rheology.py, energy.py) against closed-form solutions."""

import math

import numpy as np
import pytest

from facegear_tehl.ehl import energy, rheology
from facegear_tehl.ehl.flow import layer_integrals


def nahme_couette(nz, s=2.0, h=1e-6, k=0.13, eta0=0.03, beta=0.04, t_wall=350.0):
    """Plane Couette flow of a Newtonian oil with eta = eta0 exp(-beta (T - T_w)), both walls at T_w, solved
    with the film kernels (one column, no convection), and the closed form (Nahme 1940; e.g. Pearson 1985):
    beta (T - T_w) = 2 ln[cosh s / cosh(s (2 z/h - 1))], with the wall speed U = sqrt(8 k/(beta eta0)) sinh s
    fixing s, the shear stress tau = sqrt(8 k eta0/beta) s/(h cosh s), and tau U/2 into each wall.
    Returns (relative errors of the mid-film rise, of tau, of the wall heat fluxes)."""
    speed = math.sqrt(8.0 * k / (beta * eta0)) * math.sinh(s)
    tau = math.sqrt(8.0 * k * eta0 / beta) * s / (h * math.cosh(s))
    rise = 2.0 * math.log(math.cosh(s)) / beta
    shape = (nz, 1, 1)
    temperature = np.full(shape, t_wall)
    zero = np.zeros((1, 1))
    film = np.full((1, 1), h)
    conductivity = np.full((1, 1), k)
    factor, dissipation, u, v, thinning = (np.empty(shape) for _ in range(5))
    stress_1, stress_2 = np.zeros((2, 1, 1)), np.zeros((2, 1, 1))
    for outer in range(400):
        eta = eta0 * np.exp(-beta * (temperature - t_wall))
        rheology.shear_state(zero, film, zero, zero, eta, np.zeros(2), np.array([speed, 0.0]), math.inf, outer > 0,
                             factor, dissipation, u, v, stress_1, stress_2, thinning)
        before = temperature.copy()
        # dx = dy = 1e30 m: no convection along the film
        energy.sweep_film_temperature(temperature, u, v, dissipation, beta * dissipation, np.zeros(shape),
                                      np.full(shape, 1.8e6), conductivity, film, 1e30, 1e30, t_wall, 1, 0.0)
        if np.abs(temperature - before).max() < 1e-12:
            break
    q1, q2 = energy.wall_heat_flux(temperature, film, conductivity)
    return ((temperature[nz // 2, 0, 0] - t_wall - rise) / rise, (stress_1[0, 0, 0] - tau) / tau,
            (q1[0, 0] - 0.5 * tau * speed) / (0.5 * tau * speed), (q2[0, 0] - 0.5 * tau * speed) / (0.5 * tau * speed))


def test_thermal_couette_flow_has_nahmes_solution_at_fourth_order():
    # s = 2: the viscosity falls 14-fold from the walls to mid-film (the face gear case: ~25-fold)
    errors = {nz: np.abs(nahme_couette(nz)) for nz in (9, 17, 33)}
    # second order: 9e-3, 1e-2, 1.6e-2
    assert errors[9][0] < 1.5e-3 and errors[9][1] < 1e-3 and max(errors[9][2:]) < 5e-3
    for quantity in range(4):
        order = math.log2(errors[17][quantity] / errors[33][quantity])
        assert order > 3.5, (quantity, order)


@pytest.mark.parametrize("a", [1.0, 3.2])
def test_layer_integrals_of_an_exponential_viscosity_converge_at_fourth_order(a):
    # 1/eta = exp(a zeta), rho = 1: F0 = (e^a - 1)/a, F1 = e^a/a - (e^a - 1)/a^2, R2 = \int f0 = (F0 - 1)/a,
    # R1 = \int f1 by quadrature. a = 3.2: 1/eta grows 25-fold across the film (the trapezoidal rule: 1.3 % off
    # on nine nodes)
    from scipy import integrate
    f0_exact = math.expm1(a) / a
    f1_exact = math.exp(a) / a - math.expm1(a) / a**2
    r2_exact = (f0_exact - 1.0) / a
    r1_exact = integrate.quad(lambda z: math.exp(a * z) * z / a - math.expm1(a * z) / a**2, 0.0, 1.0,
                              epsabs=1e-14)[0]
    errors = []
    for nz in (9, 17, 33):
        z = np.linspace(0.0, 1.0, nz)
        f0, f1, r0, r1, r2 = layer_integrals(np.exp(-a * z), np.ones(nz))
        assert r0 == pytest.approx(1.0, rel=1e-14)
        errors.append(max(abs(f0 / f0_exact - 1), abs(f1 / f1_exact - 1), abs(r1 / r1_exact - 1),
                          abs(r2 / r2_exact - 1)))
    assert errors[0] < 5e-4
    assert math.log2(errors[1] / errors[2]) > 3.5


def test_eyring_couette_column_and_the_outputs_only_the_energy_equation_uses():
    # Plane Couette flow of a Ree-Eyring oil (no pressure gradient): tau = tau_0 asinh(eta u_s/(h tau_0)) in every
    # layer (Johnson & Tevaarwerk 1977), eta*/eta = r/sinh r, the thinning tanh(r)/r at r = tau/tau_0 and the velocity
    # linear across the film. Without thinning and velocity arrays (a film without the energy equation) every other
    # output is the same.
    nz, h, eta0, tau0, speed = 9, 1e-6, 0.5, 1e7, 2.0
    shape = (nz, 1, 1)
    zero, film, eta = np.zeros((1, 1)), np.full((1, 1), h), np.full(shape, eta0)
    outputs = []
    for layers in (shape, (0, 0, 0)):
        factor, dissipation, u, v, thinning = (np.empty(s) for s in (shape, shape, layers, layers, layers))
        stress_1, stress_2 = np.zeros((2, 1, 1)), np.zeros((2, 1, 1))
        rheology.shear_state(zero, film, zero, zero, eta, np.zeros(2), np.array([speed, 0.0]), tau0, False, factor,
                             dissipation, u, v, stress_1, stress_2, thinning)
        outputs.append((factor, dissipation, stress_1, stress_2, u, thinning))
    r = math.asinh(eta0 * speed / (h * tau0))
    factor, dissipation, stress_1, _, u, thinning = outputs[0]
    assert stress_1[0, 0, 0] == pytest.approx(tau0 * r, rel=1e-9)
    assert np.allclose(factor, r / math.sinh(r), rtol=1e-9, atol=0)
    assert np.allclose(thinning, math.tanh(r) / r, rtol=1e-9, atol=0)
    assert np.allclose(u[:, 0, 0], speed * np.linspace(0.0, 1.0, nz), rtol=1e-9, atol=1e-12)
    assert np.allclose(dissipation, tau0 * r * speed / h, rtol=1e-9, atol=0)
    for with_all, without in zip(outputs[0][:4], outputs[1][:4]):
        assert np.array_equal(with_all, without)


def eyring_column(newtonian_below, speed=0.05, gradient=2e9, eta0=0.05, h=2e-6, tau0=1e7):
    """One Ree-Eyring column with sliding and a pressure gradient (Pa/m), solved by rheology.shear_state: (eta*/eta,
    dissipation, stress at surface 1, thinning)."""
    nz = 9
    shape = (nz, 1, 1)
    film, eta, grad = np.full((1, 1), h), np.full(shape, eta0), np.full((1, 1), gradient)
    factor, dissipation, u, v, thinning = (np.empty(shape) for _ in range(5))
    stress_1, stress_2 = np.zeros((2, 1, 1)), np.zeros((2, 1, 1))
    rheology.shear_state(np.zeros((1, 1)), film, grad, np.zeros((1, 1)), eta, np.zeros(2), np.array([speed, 0.0]),
                         tau0, False, factor, dissipation, u, v, stress_1, stress_2, thinning, newtonian_below)
    return factor, dissipation, stress_1, thinning


def test_the_thinning_of_a_sheared_poiseuille_column_is_tanh_r_over_r_in_every_layer():
    # With a pressure gradient the stress varies across the film, tau_k = tau_s + z_k grad p: the thinning of each
    # layer (rheology.shear_state forms it from the shear rate's Jacobian, without tanh) is tanh(r_k)/r_k at
    # r_k = |tau_k|/tau_0: here 10 at both walls and 1e-4 at mid-film, where tau_k changes sign.
    speed, gradient, eta0, h, tau0 = 2.0, 2e14, 0.5, 1e-6, 1e7
    factor, _, stress_1, thinning = eyring_column(0.0, speed=speed, gradient=gradient, eta0=eta0, h=h, tau0=tau0)
    r = np.abs(stress_1[0, 0, 0] + gradient * h * np.linspace(0.0, 1.0, 9)) / tau0
    assert r.max() > 9.0 and r.min() < 1e-3
    expected = np.where(r > 0.0, np.tanh(r) / np.where(r > 0.0, r, 1.0), 1.0)
    assert np.allclose(thinning[:, 0, 0], expected, rtol=1e-12, atol=0)
    assert np.allclose(factor[:, 0, 0], np.where(r > 0.0, r / np.sinh(np.where(r > 0.0, r, 1.0)), 1.0), rtol=1e-9)


def test_a_column_below_the_newtonian_bound_takes_the_newtonian_state():
    # Couette and Poiseuille with eta = const: the Newtonian surface stress is eta u_s/h - h grad p/2 (from
    # \int (tau_s + z grad p)/eta dz = u_s), and the Eyring film departs from it by |ln(eta*/eta)| <= r^2/6 with r the
    # largest |tau|/tau_0 of the column (sinh r/r <= exp(r^2/6)). A column whose Newtonian wall stresses lie below
    # the bound takes that Newtonian state; one above it is solved in full as without the bound.
    speed, gradient, eta0, h, tau0 = 0.05, 2e9, 0.05, 2e-6, 1e7
    tau_s = eta0 * speed / h - h * gradient / 2.0
    r = max(abs(tau_s), abs(tau_s + h * gradient)) / tau0  # 1e-3: the wall stresses 10 kPa and 5 kPa
    factor, dissipation, stress_1, thinning = eyring_column(1.001 * r)
    assert np.all(factor == 1.0) and np.all(thinning == 1.0)
    assert stress_1[0, 0, 0] == pytest.approx(tau_s, rel=1e-12)
    tau = tau_s + gradient * h * np.linspace(0.0, 1.0, 9)
    assert np.allclose(dissipation[:, 0, 0], tau * tau / eta0, rtol=1e-12, atol=0)
    full = eyring_column(0.0)
    log_factor = np.log(full[0])
    assert 0.0 < np.abs(log_factor).max() <= r * r / 6.0  # the full solution departs, by no more than the bound
    assert stress_1[0, 0, 0] == pytest.approx(full[2][0, 0, 0], rel=r * r)
    above = eyring_column(0.999 * r)
    for with_bound, without in zip(above, full):
        assert np.array_equal(with_bound, without)
