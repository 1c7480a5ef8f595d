"""Deflection operator against the exact Hertz solution (Johnson 1985, §3.4 and §4.2)."""

import numpy as np
import pytest

from facegear_tehl.ehl.elastic import DENSE_NODES, DeflectionOperator, influence_coefficients
from facegear_tehl.ehl.scaling import contact_from_moes, scaling_for


@pytest.mark.parametrize("ratio", [1.0, 5.0, 100.0])
def test_hertz_pressure_gives_hertz_approach(ratio):
    # Inside a Hertz ellipse the elastic deflection equals the approach minus the quadratic gap:
    # C_d K*P + X^2/2 + k^2 D Y^2/2 = delta R_x/b^2 for P = sqrt(1 - X^2 - Y^2).
    point, lubricant = contact_from_moes(20.0, 10.0, 1.0 / ratio)
    sc = scaling_for(point, lubricant)
    n = 257
    x = np.linspace(-1.5, 1.5, n)
    operator = DeflectionOperator(n, n, x[1] - x[0], x[1] - x[0], sc.ellipticity)
    xx, yy = np.meshgrid(x, x)
    pressure = np.sqrt(np.maximum(1.0 - xx**2 - yy**2, 0.0))
    deflection = sc.deflection_coefficient * operator.apply(pressure)
    approach = sc.hertz.approach * point.radius_x / sc.b**2
    inside = xx**2 + yy**2 < 1.0
    error = np.abs(deflection + 0.5 * xx**2 + 0.5 * sc.geometry_y * yy**2 - approach)[inside].max()
    assert error < 0.005 * approach


@pytest.mark.parametrize("nx, ny", [(17, 21), (33, 21)])
def test_fft_convolution_is_the_direct_sum(nx, ny):
    # 17 x 21 = 357 nodes: the dense matrix (DENSE_NODES); 33 x 21: the transforms
    assert (nx * ny <= DENSE_NODES) == (nx == 17)
    rng = np.random.default_rng(3)
    operator = DeflectionOperator(nx, ny, 0.2, 0.15, 3.0)
    pressure = rng.random((ny, nx))
    k = operator.coefficients
    direct = np.zeros_like(pressure)
    for j in range(ny):
        for i in range(nx):
            dj = np.abs(np.arange(ny) - j)[:, None]
            di = np.abs(np.arange(nx) - i)[None, :]
            direct[j, i] = (k[dj, di] * pressure).sum()
    assert np.allclose(operator.apply(pressure), direct, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("nx, ny", [(129, 17), (65, 33), (30, 17)])
def test_the_even_kernel_period_is_the_linear_convolution(nx, ny):
    """Transforms of 2 n - 2 nodes (256 x 32, 128 x 64 for the grids of 2^k + 1 nodes; next_fast_len(58) x 32
    otherwise): the offsets n - 1 and -(n - 1) share one node of the period and the even kernel has the same K
    there, so the circular convolution is the direct sum to round-off, the farthest nodes' coupling included."""
    rng = np.random.default_rng(11)
    operator = DeflectionOperator(nx, ny, 0.023, 0.031, 0.4)
    assert operator.shape[0] < 2 * ny - 1 or operator.shape[1] < 2 * nx - 1
    pressure = np.maximum(rng.random((ny, nx)) - 0.3, 0.0)
    pressure[0, 0], pressure[-1, -1] = 1.0, 2.0  # the corners: offsets n - 1 along both axes
    k = operator.coefficients
    dj = np.abs(np.arange(ny)[:, None, None, None] - np.arange(ny)[None, None, :, None])
    di = np.abs(np.arange(nx)[None, :, None, None] - np.arange(nx)[None, None, None, :])
    direct = (k[dj, di] * pressure[None, None, :, :]).sum(axis=(2, 3))
    scale = np.abs(direct).max()
    assert np.abs(operator.apply(pressure) - direct).max() < 1e-13 * scale


def test_cell_integral_of_one_over_r():
    # Self-influence of a square cell of side h: 4 h asinh(1) (the integral of 1/r over the square).
    k = influence_coefficients(3, 3, 0.1, 0.1, 1.0)
    assert k[0, 0] == pytest.approx(4 * 0.1 * np.arcsinh(1.0), rel=1e-14)
