"""Moving heat source kernels (Jaeger 1942; Carslaw & Jaeger 1959) against closed forms and values computed
independently by quadrature of the exact solutions."""

import math

import numpy as np
import pytest
from scipy import integrate

from facegear_tehl.ehl.jaeger import (
    band_source_maximum,
    band_source_temperature,
    convolved_rise,
    influence_block,
    influence_matrix,
    surface_temperature_rise,
)
from facegear_tehl.materials import Solid

STEEL = Solid(elastic_modulus=206e9, poisson_ratio=0.3)  # k = 46, rho = 7850, c = 470 (handbook steel)
HALF_WIDTH = 0.3e-3  # m


def band_grid(nx, half_width=HALF_WIDTH, extent=2.0):
    """Uniform grid over [-extent b, extent b] with nodes on the band edges +-b."""
    x = np.linspace(-extent * half_width, extent * half_width, nx)
    return x, x[1] - x[0]


def uniform_band_flux(x, half_width=HALF_WIDTH):
    """Unit step flux on |x| <= b as nodal values: edge nodes carry 1/2, so the piecewise-linear
    interpolant carries the band's exact heat (the step itself is not piecewise linear)."""
    flux = (np.abs(x) <= half_width * (1 + 1e-12)).astype(float)
    flux[np.isclose(np.abs(x), half_width, rtol=1e-9)] = 0.5
    return flux


def semi_elliptical_flux(x, half_width=HALF_WIDTH):
    return np.sqrt(np.clip(1.0 - (x / half_width) ** 2, 0.0, None))


def semi_elliptical_exact(x):
    """(1/sqrt(pi)) int_{-1}^{min(x,1)} sqrt(1 - s^2) (x - s)^-1/2 ds for b = 1, by QUADPACK with the
    algebraic endpoint weights taken out of the integrand."""
    if x <= -1.0:
        return 0.0
    if x <= 1.0:
        value = integrate.quad(lambda s: math.sqrt(1 - s), -1, x, weight="alg", wvar=(0.5, -0.5), epsabs=1e-13)[0]
    else:
        value = integrate.quad(lambda s: 1 / math.sqrt(x - s), -1, 1, weight="alg", wvar=(0.5, 0.5), epsabs=1e-13)[0]
    return value / math.sqrt(math.pi)


def test_uniform_band_maximum_and_mean():
    # Jaeger (1942), uniform flux: max 2 sqrt(2/pi) = 1.59577 q sqrt(b)/B at the trailing edge, mean over the band
    # 1.0638.
    u, q = 10.0, 1e9
    effusivity = STEEL.thermal_effusivity_speed(u)
    x, dx = band_grid(257)
    rise = surface_temperature_rise(q * uniform_band_flux(x), dx, effusivity)
    unit = q * math.sqrt(HALF_WIDTH) / effusivity
    assert rise.max() / unit == pytest.approx(1.59577, rel=0.01)
    assert abs(x[np.argmax(rise)] - HALF_WIDTH) <= dx
    band = np.abs(x) <= HALF_WIDTH * (1 + 1e-9)
    mean = integrate.trapezoid(rise[band], x[band]) / (2 * HALF_WIDTH)
    assert mean / unit == pytest.approx(1.0638, rel=0.01)


def test_semi_elliptical_maximum_and_its_position():
    # Jaeger (1942), semi-elliptical flux (quadrature): max 1.23462 q0 sqrt(b)/B at x = +0.652 b.
    x, dx = band_grid(257)
    rise = surface_temperature_rise(semi_elliptical_flux(x), dx, 1.0)
    assert rise.max() / math.sqrt(HALF_WIDTH) == pytest.approx(1.23462, rel=0.01)
    assert x[np.argmax(rise)] / HALF_WIDTH == pytest.approx(0.652, rel=0.01)


def test_exact_for_piecewise_linear_flux():
    # Closed forms: int_{x0}^{x} (x - s)^-1/2 ds = 2 sqrt(x - x0), int (s - x0)(x - s)^-1/2 ds = 4/3 (x - x0)^1.5.
    x = np.linspace(0.0, 2.0, 41)
    dx = x[1] - x[0]
    alpha, beta = 3.0, -1.25
    exact = (2 * alpha * np.sqrt(x) + 4 / 3 * beta * x**1.5) / math.sqrt(math.pi)
    np.testing.assert_allclose(surface_temperature_rise(alpha + beta * x, dx, 1.0), exact, rtol=1e-12, atol=1e-14)
    # A tent with its kink on a node: superpose two ramps starting at x0 = 0 and x0 = 1.
    tent = np.where(x <= 1.0, x, 2.0 - x)
    ramp = lambda start: 4 / 3 * np.clip(x - start, 0, None) ** 1.5 / math.sqrt(math.pi)  # noqa: E731
    np.testing.assert_allclose(surface_temperature_rise(tent, dx, 1.0), ramp(0.0) - 2 * ramp(1.0), atol=1e-13)



def test_fft_convolution_and_blocks_are_the_product_integration():
    # The FFT convolution along the axis and a block of the matrix built on its own (the outlet patch's whole axis of
    # 4097 nodes) against the closed forms of a piecewise-linear flux above (exact for the product integration).
    x = np.linspace(0.0, 2.0, 41)
    dx = x[1] - x[0]
    alpha, beta = 3.0, -1.25
    exact = (2 * alpha * np.sqrt(x) + 4 / 3 * beta * x**1.5) / math.sqrt(math.pi)
    rows = np.stack([alpha + beta * x, 2.0 * (alpha + beta * x)])
    np.testing.assert_allclose(convolved_rise(rows, dx), np.stack([exact, 2.0 * exact]), rtol=1e-12, atol=1e-13)
    whole = influence_matrix(41, dx)
    np.testing.assert_array_equal(influence_block(41, dx, slice(5, 30), slice(0, 41)), whole[5:30])
    np.testing.assert_array_equal(influence_block(41, dx, np.array([40, 3, 0]), np.array([0, 2, 39])),
                                  whole[np.ix_([40, 3, 0], [0, 2, 39])])
    # the rise at nodes 5..29 from the flux at nodes 10..40 alone: the kernel looks upstream only
    block = influence_block(41, dx, slice(5, 30), slice(10, 41))
    flux = np.where(np.arange(41) >= 10, alpha + beta * x, 0.0)
    np.testing.assert_allclose(block @ flux[10:], convolved_rise(flux, dx)[5:30], rtol=1e-12, atol=1e-13)
    assert np.all(block[:5] == 0.0)
    with pytest.raises(ValueError):
        convolved_rise(np.ones(1), dx)


def test_grid_convergence_semi_elliptical():
    # Against quadrature. The nodal flux cannot follow sqrt(1 - x^2)'s infinite slope at x = b, so the
    # largest error sits at the trailing edge and falls like dx (first order); the peak converges faster.
    field_errors, peak_errors = [], []
    for nx in (33, 65, 129, 257, 513):
        x = np.linspace(-2.0, 2.0, nx)
        computed = influence_matrix(nx, x[1] - x[0]) @ semi_elliptical_flux(x, 1.0)
        exact = np.array([semi_elliptical_exact(value) for value in x])
        field_errors.append(np.max(np.abs(computed - exact)) / 1.23462)
        peak_errors.append(abs(computed.max() / 1.23462 - 1.0))
    orders = np.log2(np.array(field_errors[:-1]) / np.array(field_errors[1:]))
    assert np.all(orders > 0.95), orders
    assert all(fine < coarse for coarse, fine in zip(peak_errors, peak_errors[1:])), peak_errors
    assert field_errors[-1] < 2.5e-3 and peak_errors[-1] < 2e-4


def test_grid_convergence_uniform_band():
    # Exact solution inside the band: (2/sqrt(pi)) sqrt(x + b); the step costs O(dx^0.5) near its edges.
    errors = []
    for nx in (65, 129, 257, 513, 1025):
        x, dx = band_grid(nx, 1.0)
        rise = influence_matrix(nx, dx) @ uniform_band_flux(x, 1.0)
        errors.append(abs(rise.max() - 2 * math.sqrt(2 / math.pi)))
    assert all(fine < coarse for coarse, fine in zip(errors, errors[1:])), errors


def test_rows_speeds_and_direction():
    nx, ny = 129, 5
    x, dx = band_grid(nx)
    scales = np.linspace(0.5, 2.0, ny)[:, None]
    flux = scales * semi_elliptical_flux(x)[None, :]
    effusivity = np.linspace(1e4, 3e4, ny)[:, None]
    matrix = influence_matrix(nx, dx)
    field = surface_temperature_rise(flux, dx, effusivity, matrix=matrix)
    for row in range(ny):
        single = surface_temperature_rise(flux[row], dx, effusivity[row, 0])
        np.testing.assert_allclose(field[row], single, rtol=1e-13)
    # A surface moving toward -x sees the mirror image.
    mirrored = surface_temperature_rise(flux[:, ::-1], dx, effusivity, matrix=matrix, reverse=True)
    np.testing.assert_allclose(mirrored, field[:, ::-1], rtol=1e-13)
    with pytest.raises(ValueError):
        surface_temperature_rise(flux, dx, 1.0, matrix=influence_matrix(nx - 1, dx))


def test_disc_source_mean_two_dimensional():
    # Uniform flux on a disc of radius a, kernel applied row by row: the high-Pe disc average is
    # 0.6886 q a/(k sqrt(Pe)) (disc average of the 1-D solution); with B = k sqrt(2 Pe/a) that is 0.6886 sqrt(2) q
    # sqrt(a)/B.
    nx = 257
    x = np.linspace(-1.25, 1.25, nx)
    xx, yy = np.meshgrid(x, x)
    disc = (xx**2 + yy**2 <= 1.0).astype(float)
    rise = surface_temperature_rise(disc, x[1] - x[0], 1.0)
    assert rise[disc > 0].mean() / math.sqrt(2) == pytest.approx(0.6886, rel=0.01)


@pytest.mark.parametrize(
    "pe, exact_max",
    [(0.1, 2.2003), (0.5, 1.3042), (1, 0.99185), (2, 0.73680), (5, 0.48464), (10, 0.34850),
     (20, 0.24891), (50, 0.15856), (100, 0.11244)],
)
def test_jaeger_band_exact_table(pe, exact_max):
    # Jaeger (1942), computed independently by quadrature: maximum theta k/(q l) of the exact finite-Péclet band
    # solution.
    position, value = band_source_maximum(pe)
    assert value == pytest.approx(exact_max, rel=1e-3)
    assert 0.0 < position < 1.0  # the peak lies inside the source, toward the trailing edge
    assert band_source_temperature(position, pe) >= band_source_temperature(position + 1e-3, pe)


def test_jaeger_band_exact_mean_at_high_peclet():
    # Jaeger (1942), quadrature: the mean over the source is 0.07536 at Pe = 100 (0.7523/sqrt(L) asymptotically).
    mean = integrate.quad(lambda xi: band_source_temperature(xi, 100.0), -1, 1, epsabs=1e-10)[0] / 2
    assert mean == pytest.approx(0.07536, rel=1e-3)


@pytest.mark.parametrize("pe, tolerance", [(5, 0.05), (10, 0.024), (20, 0.024), (50, 0.024), (100, 0.024)])
def test_high_peclet_kernel_against_exact_band(pe, tolerance):
    # The high-Pe kernel is within 5 % of the exact band solution for Pe >= 5, 2.4 % for Pe >= 10.
    u = 2.0 * pe * STEEL.thermal_diffusivity / HALF_WIDTH  # Pe = u b / (2 kappa)
    q = 1e9
    x, dx = band_grid(513)
    rise = surface_temperature_rise(q * uniform_band_flux(x), dx, STEEL.thermal_effusivity_speed(u))
    kernel_max = rise.max() * STEEL.thermal_conductivity / (q * HALF_WIDTH)
    exact_max = band_source_maximum(pe)[1]
    assert kernel_max > exact_max  # neglecting conduction along x overestimates the peak
    assert kernel_max / exact_max - 1.0 < tolerance


def test_invalid_arguments():
    with pytest.raises(ValueError):
        influence_matrix(1, 1e-6)
    with pytest.raises(ValueError):
        influence_matrix(17, 0.0)
    with pytest.raises(ValueError):
        band_source_temperature(0.0, 0.0)
    with pytest.raises(ValueError):
        surface_temperature_rise(np.ones(9), 1e-6, np.array([[1e4], [0.0]]))
