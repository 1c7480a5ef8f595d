"""Moving heat source: surface temperature rise of a solid sliding under a surface heat flux.

High-Péclet kernel (Jaeger 1942; Carslaw & Jaeger 1959, §10.7): a surface moving at speed u toward +x
under a flux q(x) (W/m^2) that conducts only across its depth heats up as

    dT(x) = 1/(sqrt(pi) B) * integral_{x_in}^{x} q(s) (x - s)^(-1/2) ds,     B = sqrt(k rho c u)

(Jaeger 1942, Proc. R. Soc. N.S.W. 76:203-224). It holds for Pe = u b/(2 kappa) >> 1;
`band_source_temperature` gives Jaeger's exact finite-Péclet solution of a uniform band source, against
which its error is 4 % at Pe = 5 and 2.4 % at Pe = 10.

Discretisation: q is taken piecewise linear between the nodes of a uniform grid and the weight
(x - s)^(-1/2) is integrated analytically over every interval (product integration), so the kernel
is exact for piecewise-linear flux and has no trouble with the singularity at s = x. With
a_m = sqrt(m), c_m = sqrt(m - 1) and node spacing h, the interval that lies m intervals upstream of
the evaluation node contributes

    sqrt(h) * [ q_left  * (2/3) (a_m - c_m)^2 (a_m + 2 c_m)
              + q_right * (2/3) (a_m - c_m)^2 (2 a_m + c_m) ],     a_m - c_m = 1/(a_m + c_m),

i.e. the integrals of (1 - t) and t against (m - t)^(-1/2) over t in [0, 1], written without
cancellation. The influence matrix is lower triangular and Toeplitz except for the first column
(the inlet node has no interval upstream of it).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import fft  # the exact band source's quad, brentq and k0e are imported where used (start-up time)


def _kernel_weights(nx: int) -> tuple[np.ndarray, np.ndarray]:
    """The dimensionless weights of `influence_matrix` (without sqrt(dx/pi)): its Toeplitz column w(d) for nodes
    j >= 1 at d = i - j = 0 .. nx - 1 intervals upstream, and the inlet node's column `left` (rows 1 .. nx - 1)."""
    m = np.arange(1, nx, dtype=float)  # intervals upstream of the evaluation node: 1 .. nx-1
    a = np.sqrt(m)
    c = np.sqrt(m - 1.0)
    gap_sq = (1.0 / (a + c)) ** 2
    left = (2.0 / 3.0) * gap_sq * (a + 2.0 * c)  # weight of the interval's upstream node
    right = (2.0 / 3.0) * gap_sq * (2.0 * a + c)  # weight of the interval's downstream node
    # Node j at distance d = i - j >= 0 downstream gets `left` from interval m = d (if d >= 1) and
    # `right` from interval m = d + 1 (if j >= 1, which holds for every d <= nx - 2 off column 0).
    column = np.empty(nx)
    column[0] = right[0]
    column[1:] = left
    column[1:-1] += right[1:]
    return column, left


def influence_matrix(nx: int, dx: float) -> np.ndarray:
    """Geometric influence matrix G (nx, nx), m^0.5, of the high-Péclet kernel on a uniform grid.

    dT = (G @ q) / B for a flux q (W/m^2) at the nodes of one grid line, surface moving toward +x
    (inlet at node 0), B = sqrt(k rho c u) (`Solid.thermal_effusivity_speed`). G depends only on
    the node count and the spacing dx (m): build it once per grid and reuse it for every row.
    G[i, j] = sqrt(dx/pi) * w(i - j) for j >= 1, lower triangular; G[0, 0] = 0.
    """
    return influence_block(nx, dx, slice(0, nx), slice(0, nx))


def influence_block(nx: int, dx: float, rows: slice | np.ndarray, columns: slice | np.ndarray) -> np.ndarray:
    """The block G[rows, columns] of `influence_matrix(nx, dx)` (m^0.5; rows and columns: slices or node indices),
    built without the whole matrix (the whole x axis of an outlet patch at an eighth of the spacing has 4097 nodes:
    134 MB)."""
    _check(nx, dx)
    column, left = _kernel_weights(nx)
    i = np.arange(nx)[rows][:, None]
    j = np.arange(nx)[columns][None, :]
    distance = i - j
    block = np.where(distance >= 0, column[np.clip(distance, 0, nx - 1)], 0.0)
    block = np.where((j == 0) & (i >= 1), left[np.clip(i - 1, 0, nx - 2)], block)  # the inlet node's own column
    block[(i == 0) & (j == 0)] = 0.0
    return math.sqrt(dx / math.pi) * block


def convolved_rise(flux: np.ndarray, dx: float) -> np.ndarray:
    """flux @ influence_matrix(nx, dx).T along the last axis (m^0.5 W/m^2; over B it is the rise in K) by a
    real FFT convolution: n log n per row instead of the n^2 of the matrix product (equal to round-off)."""
    flux = np.asarray(flux, dtype=float)
    nx = flux.shape[-1]
    _check(nx, dx)
    column, left = _kernel_weights(nx)
    size = fft.next_fast_len(2 * nx - 1, real=True)
    interior = flux.copy()
    interior[..., 0] = 0.0  # the inlet node enters through its own column
    product = fft.irfft(fft.rfft(interior, size) * fft.rfft(column, size), size)[..., :nx]
    product[..., 1:] += flux[..., :1] * left
    product[..., 0] = 0.0
    return math.sqrt(dx / math.pi) * product


def _check(nx: int, dx: float) -> None:
    if nx < 2:
        raise ValueError(f"need at least 2 nodes, got {nx}")
    if not dx > 0.0:
        raise ValueError(f"grid spacing must be positive, got {dx}")


def surface_temperature_rise(
    flux: np.ndarray,
    dx: float,
    effusivity: float | np.ndarray,
    *,
    matrix: np.ndarray | None = None,
    reverse: bool = False,
) -> np.ndarray:
    """Surface temperature rise dT (K) of a surface moving along x under the nodal flux `flux`.

    flux: W/m^2, shape (nx,) or (ny, nx); the kernel integrates along the last axis.
    dx: node spacing along x, m.
    effusivity: B = sqrt(k rho c |u|), W s^0.5/(m^2 K) * (m/s)^0.5; a scalar or an array that
        broadcasts against the rows, e.g. shape (ny, 1) when the speed varies from row to row.
    matrix: a prebuilt `influence_matrix(nx, dx)` to reuse.
    reverse: the surface moves toward -x (inlet at the last node) instead of +x.
    A surface at rest (B = 0) is outside the kernel's validity (Pe = 0) and raises ValueError.
    """
    effusivity = np.asarray(effusivity, dtype=float)
    if not np.all(effusivity > 0.0):
        raise ValueError("the high-Péclet kernel needs a moving surface (effusivity B = sqrt(k rho c |u|) > 0)")
    flux = np.asarray(flux, dtype=float)
    nx = flux.shape[-1]
    if matrix is None:
        matrix = influence_matrix(nx, dx)
    elif matrix.shape != (nx, nx):
        raise ValueError(f"influence matrix has shape {matrix.shape}, flux rows have {nx} nodes")
    upstream_first = flux[..., ::-1] if reverse else flux
    rise = upstream_first @ matrix.T
    if reverse:
        rise = rise[..., ::-1]
    return rise / effusivity


def _source_weight(u: float) -> float:
    """exp(-u) K0(|u|), written with the scaled Bessel function k0e(z) = exp(z) K0(z) (no overflow)."""
    from scipy import special

    if u < 0.0:
        return float(special.k0e(-u))
    return math.exp(-2.0 * u) * float(special.k0e(u))


def band_source_temperature(position: float, peclet: float) -> float:
    """Exact steady temperature rise of a surface under a uniform band source, theta k/(q l), dimensionless.

    Jaeger (1942), band of half-width l with uniform flux q over a half-space moving toward +x at
    speed V relative to the source (Carslaw & Jaeger 1959, §10.7):

        theta k/(q l) = 1/(pi L) * integral_{X-L}^{X+L} exp(-u) K0(|u|) du,    X = -L x/l,  L = Pe = V l/(2 kappa)

    position: x/l (the source spans -1..1; the wake lies at x/l > 1, as in `surface_temperature_rise`).
    The log singularity of K0 at u = 0 is split out as an integration break point.
    """
    from scipy import integrate

    if not peclet > 0.0:
        raise ValueError(f"Péclet number must be positive, got {peclet}")
    centre = -peclet * position
    lower, upper = centre - peclet, centre + peclet
    options = {"limit": 200, "epsabs": 1e-13, "epsrel": 1e-12}
    if lower < 0.0 < upper:
        total = integrate.quad(_source_weight, lower, 0.0, **options)[0]
        total += integrate.quad(_source_weight, 0.0, upper, **options)[0]
    else:
        total = integrate.quad(_source_weight, lower, upper, **options)[0]
    return total / (math.pi * peclet)


def band_source_maximum(peclet: float) -> tuple[float, float]:
    """Position x/l and value theta k/(q l) of the maximum of `band_source_temperature`.

    The maximum is where d theta/dX = exp(-(X+L)) K0(|X+L|) - exp(-(X-L)) K0(|X-L|) vanishes; the
    derivative runs from +inf at X = -L to -inf at X = +L, so one bracketed root finds it.
    """
    if not peclet > 0.0:
        raise ValueError(f"Péclet number must be positive, got {peclet}")

    def slope(centre: float) -> float:
        return _source_weight(centre + peclet) - _source_weight(centre - peclet)

    from scipy import optimize

    edge = peclet * (1.0 - 1e-12)
    centre = optimize.brentq(slope, -edge, edge, xtol=1e-14 * max(1.0, peclet))
    position = -centre / peclet
    return position, band_source_temperature(position, peclet)
