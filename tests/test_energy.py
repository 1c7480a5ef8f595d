"""The film's energy equation with the convection across the layers (energy.py): a manufactured solution whose
velocity field satisfies continuity, the exact discrete energy balance on a synthetic film with reversed flow,
the fourth-order wall heat flux of thermal Couette flow, and the layer widths."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from facegear_tehl.ehl import energy, rheology

# Manufactured film (SI): length L along x, film h(x) = H0 (1 + x/(2L)), heat capacity rho c = CV, conductivity
# K. The heat-capacity flux per unit of zeta, h rho c u = Q (1 + eps(x) g(zeta)) with \int_0^1 g = 0: the column
# carries Q at every x (continuity of the column), and the flux across the layers is c W = -Q eps'(x) G(zeta),
# G = \int_0^zeta g, zero on both walls. T = T_IN + AMP phi(x) psi(zeta) with phi(0) = phi'(0) = 0 (the oil
# enters at T_IN) and the source S = rho c u dT/dx + (c W/h) dT/dzeta - (k/h^2) d^2T/dzeta^2 by hand. With these
# numbers the three terms are of one order (cross-film Péclet Q eps' h/k ~ 0.9).
L, H0, CV, K, Q, EPS, T_IN, AMP = 2e-4, 1e-6, 1.8e6, 0.13, 9.0, 0.8, 313.0, 20.0
DY = 1e-5  # m, spacing of the three identical rows along y (no flow along y)


def _h(x):
    return H0 * (1.0 + 0.5 * x / L)


def _eps(x):
    return EPS * np.sin(np.pi * x / L)


def _deps(x):
    return EPS * np.pi / L * np.cos(np.pi * x / L)


def _g(z):
    return 1.0 - 6.0 * z * (1.0 - z)


def _big_g(z):
    return z * (1.0 - z) * (1.0 - 2.0 * z)


def _phi(x):
    return 0.5 * (1.0 - np.cos(np.pi * x / L))


def _dphi(x):
    return 0.5 * np.pi / L * np.sin(np.pi * x / L)


def _psi(z):
    return 0.5 + np.sin(np.pi * z) + 0.3 * z


def _dpsi(z):
    return np.pi * np.cos(np.pi * z) + 0.3


def _d2psi(z):
    return -np.pi**2 * np.sin(np.pi * z)


def _source(x, z):
    h = _h(x)
    u = Q * (1.0 + _eps(x) * _g(z)) / (h * CV)
    cross = -Q * _deps(x) * _big_g(z)
    return (CV * u * AMP * _dphi(x) * _psi(z) + cross / h * AMP * _phi(x) * _dpsi(z)
            - K / h**2 * AMP * _phi(x) * _d2psi(z))


def _exact_budget():
    """Generated, conducted and convected heat of the manufactured film (W) by quadrature of the closed forms."""
    from scipy import integrate

    width = 3 * DY
    generated = integrate.dblquad(lambda z, x: _source(x, z) * _h(x), 0.0, L, 0.0, 1.0, epsabs=1e-13)[0]
    conducted = integrate.quad(lambda x: K / _h(x) * AMP * _phi(x) * (_dpsi(0.0) - _dpsi(1.0)), 0.0, L)[0]
    convected = integrate.quad(lambda z: Q * (1.0 + _eps(L) * _g(z)) * AMP * _phi(L) * _psi(z), 0.0, 1.0)[0]
    return generated * width, conducted * width, convected * width


def _manufactured(nx, nz):
    """The film solved on nx cells along x and nz layer nodes: (largest error / AMP, budget)."""
    dx = L / nx
    x = (np.arange(nx) + 0.5) * dx  # cell centres: the faces of the domain at 0 (inflow) and L (outflow)
    z = np.linspace(0.0, 1.0, nz)
    xs, zs = np.meshgrid(x, z)
    shape = (nz, 3, nx)

    def rows(a):
        return np.ascontiguousarray(np.broadcast_to(a[:, None, :], shape))

    film = np.ascontiguousarray(np.broadcast_to(_h(x), (3, nx)))
    velocity = rows(Q * (1.0 + _eps(xs) * _g(zs)) / (_h(xs) * CV))
    source = rows(_source(xs, zs))
    exact = rows(T_IN + AMP * _phi(xs) * _psi(zs))
    temperature = np.full(shape, T_IN)
    temperature[0], temperature[-1] = exact[0], exact[-1]  # the walls: Dirichlet
    zero = np.zeros(shape)
    heat_capacity = np.full(shape, CV)
    _, change, q1, q2 = energy.solve_film_temperature(temperature, velocity, zero, source, zero, zero, heat_capacity,
                                                      np.full((3, nx), K), film, dx, DY, T_IN, 20000, 1e-11)
    assert change < 1e-11
    state = SimpleNamespace(temperature=temperature, velocity_x=velocity, velocity_y=zero,
                            heat_capacity=heat_capacity, dissipation=source, compression=zero, heat_flux_1=q1,
                            heat_flux_2=q2)
    return float(np.abs(temperature - exact).max()) / AMP, energy.energy_budget(state, film, dx, DY, T_IN)


def test_manufactured_film_with_flow_across_the_layers_converges_at_second_order():
    """The velocity across the layers from continuity is part of the equation: the scheme converges to the
    manufactured field at second order (measured 1.2e-3, 3.3e-4, 8.6e-5 of AMP; the energy equation without the
    cross-film term, as before this change, stalls at 1.7e-2 on all three grids), and its budget terms to the
    closed-form integrals, which balance exactly (generated = conducted + convected, no mass defect)."""
    errors, budgets = [], []
    for nx, nz in ((32, 9), (64, 17), (128, 33)):
        error, budget = _manufactured(nx, nz)
        errors.append(error)
        budgets.append(budget)
    assert errors[1] < 5e-4
    for coarse, fine in zip(errors, errors[1:]):
        assert math.log2(coarse / fine) > 1.7, errors
    generated, conducted, convected = _exact_budget()
    assert generated == pytest.approx(conducted + convected, rel=1e-9)  # the closed forms balance
    for key, exact in (("heat_generated", generated), ("heat_conducted", conducted), ("heat_convected", convected)):
        misses = [abs(b[key] / exact - 1.0) for b in budgets]
        assert misses[1] < 1e-3 and misses[2] < misses[0], (key, misses)
    for budget in budgets:
        assert abs(budget["heat_mass_defect"]) < 1e-12 * generated  # the column carries Q everywhere
        assert abs(budget["energy_balance_error"]) < 1e-9


def _synthetic_film(nz=7, ny=9, nx=17):
    """A small film with what the face gear films have: reversed flow in mid-film, flow along y, a column flux
    that is not divergence-free (a mass defect), compression heating and expansion cooling, heating that falls
    with temperature (sensitivity), k varying per column, walls at given temperatures."""
    x = np.linspace(-1.0, 1.0, nx)[None, None, :]
    y = np.linspace(-1.0, 1.0, ny)[None, :, None]
    z = np.linspace(0.0, 1.0, nz)[:, None, None]
    shape = (nz, ny, nx)
    film = (1e-6 * (1.0 + 0.6 * x**2 + 0.2 * y**2))[0]
    u = np.broadcast_to(2.0 + 3.0 * z - 40.0 * z * (1.0 - z) * np.exp(-4.0 * (x + 0.6) ** 2), shape).copy()
    v = np.broadcast_to(0.8 * y * (1.0 + z) - 0.3 * z * (1.0 - z) * x, shape).copy()
    rho_c = 1.7e6 * (1.0 + 0.1 * np.sin(3.0 * x + y) * (1.0 + z))
    source = np.broadcast_to(4e12 * np.exp(-3.0 * x**2 - y**2) * (1.0 + 2.0 * z * (1.0 - z)), shape).copy()
    sensitivity = 0.02 * source
    expansivity_grad = np.broadcast_to(8e9 * np.sin(2.5 * x) * np.cos(y), shape).copy()
    conductivity = (0.13 * (1.0 + 0.3 * np.exp(-x**2)))[0] * np.ones((ny, nx))
    t_inlet = 313.0
    temperature = np.full(shape, t_inlet)
    temperature[0] += (10.0 * np.exp(-(x - 0.3) ** 2) * (1.0 + 0.1 * y))[0]
    temperature[-1] += (6.0 * np.exp(-(x - 0.1) ** 2))[0]
    return dict(temperature=temperature, velocity_x=u, velocity_y=v, source=source, sensitivity=sensitivity,
                expansivity_grad=expansivity_grad, rho_c=np.broadcast_to(rho_c, shape).copy(),
                conductivity=conductivity, film=film, dx=2.0e-5, dy=4.0e-4, t_inlet=t_inlet)


def test_discrete_energy_balance_closes_to_round_off_on_a_film_with_reversed_flow():
    """Conservation of the discrete scheme, proved by hand in energy.py (`wall_fluxes`, `energy_budget`): on a
    converged solution, generated + mass defect = conducted into the walls + convected out of the domain to
    round-off, for any velocity field; each term is not small (measured: generated 2.16 W, conducted 2.37 W,
    convected 0.25 W, mass defect 0.47 W; closure 3e-15)."""
    f = _synthetic_film()
    reference = f["temperature"].copy()
    _, change, q1, q2 = energy.solve_film_temperature(
        f["temperature"], f["velocity_x"], f["velocity_y"], f["source"], f["sensitivity"], f["expansivity_grad"],
        f["rho_c"], f["conductivity"], f["film"], f["dx"], f["dy"], f["t_inlet"], 20000, 1e-12)
    assert change < 1e-12
    t = f["temperature"]
    assert t.max() > f["t_inlet"] + 5.0 and t.min() < f["t_inlet"]  # heated, and cooled by expansion
    # the heat source the scheme solved with: linearised about the entry temperatures
    state = SimpleNamespace(temperature=t, velocity_x=f["velocity_x"], velocity_y=f["velocity_y"],
                            heat_capacity=f["rho_c"], heat_flux_1=q1, heat_flux_2=q2,
                            dissipation=f["source"] - f["sensitivity"] * (t - reference),
                            compression=f["expansivity_grad"] * t)
    budget = energy.energy_budget(state, f["film"], f["dx"], f["dy"], f["t_inlet"])
    generated = budget["heat_generated"]
    assert abs(budget["energy_balance_error"]) < 1e-10, budget
    assert budget["heat_conducted"] > 0.3 * generated and abs(budget["heat_convected"]) > 0.05 * generated
    assert abs(budget["heat_mass_defect"]) > 0.05 * generated
    # the reversed flow leaves through the inlet side (x = x_0) in mid-film
    fx, _, fz, _ = energy.transport_fluxes(f["velocity_x"], f["velocity_y"], f["rho_c"], f["film"], f["dx"], f["dy"])
    assert (fx[:, :, 0] < 0.0).any() and (fx[:, :, 0] > 0.0).any()
    assert np.abs(fz).max() > 0.0 and (fz[0] == 0.0).all() and np.allclose(fz[-1], 0.0, atol=0.0)


def test_without_flow_along_the_film_nothing_crosses_the_layers():
    """A film of constant thickness with velocities uniform along x and y (any profile across it): the layers
    are parallel streams, no flux across them, no mass defect."""
    shape = (9, 5, 6)
    z = np.linspace(0.0, 1.0, 9)[:, None, None]
    u = np.broadcast_to(1.0 + 4.0 * z * (1.0 - z), shape).copy()
    v = np.broadcast_to(-0.5 * z, shape).copy()
    fx, fy, fz, divergence = energy.transport_fluxes(u, v, np.full(shape, 1.8e6), np.full((5, 6), 1e-6), 1e-5, 1e-5)
    assert np.abs(fz).max() < 1e-9 and np.abs(divergence).max() < 1e-9
    assert fx.shape == (9, 5, 7) and fy.shape == (9, 6, 6)


def _nahme_fluxes(nz, s=2.0, h=1e-6, k=0.13, eta0=0.03, beta=0.04, t_wall=350.0):
    """Plane Couette flow with eta = eta0 exp(-beta (T - T_w)), both walls at T_w (Nahme 1940; e.g. Pearson
    1985): each wall takes tau U/2, tau = sqrt(8 k eta0/beta) s/(h cosh s), U = sqrt(8 k/(beta eta0)) sinh s.
    The relative errors of the two wall fluxes of `solve_film_temperature`."""
    speed = math.sqrt(8.0 * k / (beta * eta0)) * math.sinh(s)
    tau = math.sqrt(8.0 * k * eta0 / beta) * s / (h * math.cosh(s))
    shape = (nz, 1, 1)
    temperature = np.full(shape, t_wall)
    zero2, film, conductivity = np.zeros((1, 1)), np.full((1, 1), h), np.full((1, 1), k)
    factor, dissipation, u, v, thinning = (np.empty(shape) for _ in range(5))
    stress_1, stress_2 = np.zeros((2, 1, 1)), np.zeros((2, 1, 1))
    q1 = q2 = None
    for outer in range(400):
        eta = eta0 * np.exp(-beta * (temperature - t_wall))
        rheology.shear_state(zero2, film, zero2, zero2, eta, np.zeros(2), np.array([speed, 0.0]), math.inf,
                             outer > 0, factor, dissipation, u, v, stress_1, stress_2, thinning)
        before = temperature.copy()
        # dx = dy = 1e30 m: no convection along the film
        _, _, q1, q2 = energy.solve_film_temperature(temperature, u, v, dissipation, beta * dissipation,
                                                     np.zeros(shape), np.full(shape, 1.8e6), conductivity, film,
                                                     1e30, 1e30, t_wall, 1, 0.0)
        if np.abs(temperature - before).max() < 1e-12:
            break
    exact = 0.5 * tau * speed
    return abs(q1[0, 0] / exact - 1.0), abs(q2[0, 0] / exact - 1.0)


def test_wall_heat_flux_consistent_with_the_scheme_is_fourth_order_on_thermal_couette_flow():
    """The flux the thermal model passes to the solids (`wall_fluxes`: from the compact scheme's balances) against
    Nahme's closed form: fourth order (measured 6.6e-4, 6.5e-5, 3.7e-6, 2.2e-7 on 9, 17, 33, 65 layers)."""
    assert max(_nahme_fluxes(9)) < 1e-3
    errors = [max(_nahme_fluxes(nz)) for nz in (17, 33, 65)]
    for coarse, fine in zip(errors, errors[1:]):
        assert math.log2(coarse / fine) > 3.5, errors


@pytest.mark.parametrize("nz", [3, 5, 7, 9, 17])
def test_layer_widths_sum_to_the_film_and_integrate_cubics_exactly(nz):
    """Gregory's end-corrected rule (9, 28, 23, 24, ...)/24: exact for cubics on nz >= 5; Simpson on 3."""
    w = energy.layer_weights(nz)
    z = np.linspace(0.0, 1.0, nz)
    assert w.sum() == pytest.approx(1.0, rel=1e-14)
    for power in range(4):
        assert (w * z**power).sum() == pytest.approx(1.0 / (power + 1), rel=1e-13), power
    if nz >= 7:
        assert np.allclose(w[:4] * 24 * (nz - 1), [9, 28, 23, 24])


def test_column_sweeps_after_the_first_solve_only_the_columns_next_to_one_that_moved():
    """A converged film whose heating rises in a few columns near its outlet: sweeping only the columns next to one
    that moved (energy.ACTIVE_SHARE) reaches the temperatures that sweeping every column reaches, to the sweeps'
    tolerance (the same fixed point), and solves fewer columns (measured on this 9 x 65 film: 5653 against 7605 in 13
    sweeps each, the temperatures within 4e-10 K; a face gear film spends most of its sweeps on the columns around
    the outlet spike)."""
    ny, nx, tolerance = 9, 65, 1e-8
    f = _synthetic_film(ny=ny, nx=nx)
    args = [f[name] for name in ("velocity_x", "velocity_y", "source", "sensitivity", "expansivity_grad", "rho_c",
                                 "conductivity", "film", "dx", "dy", "t_inlet")]
    energy.solve_film_temperature(f["temperature"], *args, 20000, 1e-12)
    source = args[2].copy()
    source[:, 4, 56:59] *= 1.5  # a local rise of the heating
    fx, fy, fz, _ = energy.transport_fluxes(f["velocity_x"], f["velocity_y"], f["rho_c"], f["film"], f["dx"], f["dy"])
    results = {}
    for share in (-1.0, energy.ACTIVE_SHARE):  # -1: every column passes its move on, every sweep solves them all
        temperature = f["temperature"].copy()
        fixed = energy.fixed_parts(fz, source, f["sensitivity"], temperature.copy(), f["expansivity_grad"],
                                   f["conductivity"], f["film"])
        done, change, solved = energy.sweep_columns(temperature, fx, fy, fz, *fixed, f["conductivity"], f["film"],
                                                    f["dx"], f["dy"], f["t_inlet"], 20000, tolerance, 0, 0, share)
        assert change < tolerance
        results[share] = temperature, done, solved
    (every, every_done, every_solved), (active, _, active_solved) = results[-1.0], results[energy.ACTIVE_SHARE]
    assert every_solved == every_done * ny * nx
    assert np.abs(active - f["temperature"]).max() > 0.5  # the heating moved the film
    assert np.abs(active - every).max() < 10.0 * tolerance
    assert active_solved < 0.85 * every_solved


def _muscl_face(temperature, k, j, i, dj, di, t_inlet):
    """The face value of van Leer's MUSCL scheme (van Leer 1979) from node (j, i), upwind, towards (j + dj, i + di),
    written out from its definition: T_up + 0.5 psi(r) (T_up - T_up2), psi(r) = (r + |r|)/(1 + |r|) with
    r = (T_down - T_up)/(T_up - T_up2); the inlet temperature outside the domain, the linear extrapolation on a
    boundary face the oil leaves by."""
    _, ny, nx = temperature.shape

    def value(jj, ii):
        return temperature[k, jj, ii] if 0 <= jj < ny and 0 <= ii < nx else t_inlet

    up, up2 = value(j, i), value(j - dj, i - di)
    if not (0 <= j + dj < ny and 0 <= i + di < nx):
        return up + 0.5 * (up - up2)
    if up == up2:
        return up
    r = (value(j + dj, i + di) - up) / (up - up2)
    return up + 0.5 * (r + abs(r)) / (1.0 + abs(r)) * (up - up2)


def test_convection_along_the_film_reads_the_stencil_as_the_muscl_face_values_do():
    """The convection along x and y of a node (energy._xy_form, through wall_convection's wall layers) on a random
    film with flow in and out through every face, at boundary columns (bounds-checked reads) and interior ones (read
    directly): a = sum of the inflows, b = sum over faces of the inflow times the face value, less the outflow times
    the face value's excess over the node, with the MUSCL face values written out from their definition."""
    rng = np.random.default_rng(7)
    nz, ny, nx, dx, dy, t_inlet = 5, 9, 10, 2e-6, 3e-6, 313.0
    temperature = t_inlet + 40.0 * rng.random((nz, ny, nx))
    film = 1e-6 * (1.0 + rng.random((ny, nx)))
    flux_x = rng.normal(size=(nz, ny, nx + 1))
    flux_y = rng.normal(size=(nz, ny + 1, nx))
    flux_x[:, 3, 4] = 0.0  # faces without flow
    walls = energy.wall_convection(temperature, flux_x, flux_y, film, dx, dy, t_inlet)
    for side, k in ((0, 0), (1, nz - 1)):
        for j in range(ny):
            for i in range(nx):
                t, a, b = temperature[k, j, i], 0.0, 0.0
                faces = ((flux_x[k, j, i + 1] / dx, 0, 1), (-flux_x[k, j, i] / dx, 0, -1),
                         (flux_y[k, j + 1, i] / dy, 1, 0), (-flux_y[k, j, i] / dy, -1, 0))
                for outward, dj, di in faces:
                    g = outward / film[j, i]
                    if g > 0.0:
                        b -= g * (_muscl_face(temperature, k, j, i, dj, di, t_inlet) - t)
                    elif g < 0.0:
                        a -= g
                        b -= g * _muscl_face(temperature, k, j + dj, i + di, -dj, -di, t_inlet)
                assert walls[side, 0, j, i] == pytest.approx(a, rel=1e-12, abs=1e-9)
                assert walls[side, 1, j, i] == pytest.approx(b, rel=1e-12, abs=1e-6)
