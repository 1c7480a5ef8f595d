"""Quadrature across the film on equally spaced layer nodes zeta_k = k/(nz - 1), k = 0 .. nz - 1 (nz odd).

Fourth-order rules only: the viscosity of a hot sheared film varies by an order of magnitude across it (in the
face gear case 1/eta* grows ~25-fold from the walls to mid-film), and the second-order trapezoidal rule left
h_c 0.9 % and mu 1.8 % off on the default nine layers (S1 of cases/facegear_110.yaml against 33 layers).
"""

from __future__ import annotations

from numba import njit
import numpy as np


@njit(cache=True, inline="always")
def simpson_weight(k: int, nz: int) -> float:
    """Weight of node k in Simpson's rule for \\int_0^1 g d zeta on nz (odd) nodes."""
    dz = 1.0 / (nz - 1)
    if k == 0 or k == nz - 1:
        return dz / 3.0
    return 4.0 * dz / 3.0 if k % 2 == 1 else 2.0 * dz / 3.0


def simpson_weights(nz: int) -> np.ndarray:
    """All nz weights of `simpson_weight` (NumPy; Numba kernels call `simpson_weight`)."""
    w = np.full(nz, 2.0)
    w[1::2] = 4.0
    w[0] = w[-1] = 1.0
    return w / (3.0 * (nz - 1))


@njit(cache=True, inline="always")
def cumulative_stencil(k: int, nz: int):
    """Nodes and weights (times dz) of \\int over [zeta_k-1, zeta_k]: (first node, w0, w1, w2, w3) for
    sum_m w_m g_first+m. The cubic through the four nearest nodes, (-1, 13, 13, -1)/24, one-sided
    (9, 19, -5, 1)/24 at the ends; the quadratic on three nodes. Summed, the running integral \\int_0^zeta g is
    fourth-order accurate."""
    if nz == 3:
        if k == 1:
            return 0, 5.0 / 12.0, 8.0 / 12.0, -1.0 / 12.0, 0.0
        return 0, -1.0 / 12.0, 8.0 / 12.0, 5.0 / 12.0, 0.0
    if k == 1:
        return 0, 9.0 / 24.0, 19.0 / 24.0, -5.0 / 24.0, 1.0 / 24.0
    if k == nz - 1:
        return k - 3, 1.0 / 24.0, -5.0 / 24.0, 19.0 / 24.0, 9.0 / 24.0
    return k - 2, -1.0 / 24.0, 13.0 / 24.0, 13.0 / 24.0, -1.0 / 24.0


@njit(cache=True, inline="always")
def cumulative_step(g: np.ndarray, k: int, dz: float) -> float:
    """\\int over [zeta_k-1, zeta_k] of g given on equally spaced nodes (spacing dz; `cumulative_stencil`)."""
    first, w0, w1, w2, w3 = cumulative_stencil(k, g.size)
    total = w0 * g[first] + w1 * g[first + 1] + w2 * g[first + 2]
    total += w3 * g[min(first + 3, g.size - 1)] if w3 != 0.0 else 0.0
    return dz * total
