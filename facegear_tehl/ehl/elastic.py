r"""Elastic deflection of the contacting half-spaces by FFT convolution (O(N log N)).

In Hertzian units (X = x/b, Y = y/a, P = p/p_h, H = h R_x / b^2) the deflection of two elastic half-spaces
(Boussinesq; Johnson 1985, §3.2) is

    H_d(X, Y) = C_d \iint P(S, T) / sqrt((X - S)^2 + k^2 (Y - T)^2) dS dT,   C_d = 2 p_h a R_x / (pi E' b^2),

with k = a/b. P is taken constant on each cell of size h_x x h_y around a node; the integral over a cell
is the closed form of Venner & Lubrecht (2000, eq. 8.6) for 1/r over a rectangle, here stretched by k in Y:

    K(d_i, d_j) = (1/k) R(d_i h_x - h_x/2, d_i h_x + h_x/2; k (d_j h_y - h_y/2), k (d_j h_y + h_y/2)),
    R(x1, x2; y1, y2) = F(x2, y2) - F(x1, y2) - F(x2, y1) + F(x1, y1),   F(x, y) = x asinh(y/|x|) + y asinh(x/|y|).

The discrete convolution W_ij = sum K(|i - i'|, |j - j'|) P_i'j' is evaluated with real FFTs on a grid padded
to m = `scipy.fft.next_fast_len(2 n - 2)` nodes per axis: a circular convolution of period m >= 2 n - 2 is the
linear one on the grid's n nodes because K is even (offsets d and -d, the only ones of |d| <= n - 1 that share a
residue modulo 2 n - 2, carry the same K(n - 1)); for the grids of 2^k + 1 nodes m = 2^(k+1), against the 2^(k+1) + 1
of a general kernel, whose fast sizes (1080 for 1025) cost 1.2-2x more. The even kernel's transform is real (its
imaginary part is round-off, below 1e-16 of its largest value, and is dropped). The two-dimensional transforms are
taken one axis at a time, so that the rows of zeros the padding adds are never transformed along X and only the
rows of the grid are transformed back (a pruned FFT).
A grid of at most DENSE_NODES nodes (the coarsest) is multiplied by the dense matrix of K instead.
"""

from __future__ import annotations

import numpy as np
from scipy import fft


def _f(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """F(x, y) = x asinh(y/|x|) + y asinh(x/|y|): d^2F/dx dy = 1/sqrt(x^2 + y^2) in every quadrant
    (F = 0 on the axes)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        fx = np.where(x != 0.0, x * np.arcsinh(y / np.where(x != 0.0, np.abs(x), 1.0)), 0.0)
        fy = np.where(y != 0.0, y * np.arcsinh(x / np.where(y != 0.0, np.abs(y), 1.0)), 0.0)
    return fx + fy


def influence_coefficients(nx: int, ny: int, hx: float, hy: float, ellipticity: float) -> np.ndarray:
    """K[d_j, d_i] for d_i in 0..nx-1, d_j in 0..ny-1 (shape (ny, nx)), without the factor C_d."""
    di = np.arange(nx, dtype=np.float64)[None, :]
    dj = np.arange(ny, dtype=np.float64)[:, None]
    x1, x2 = di * hx - 0.5 * hx, di * hx + 0.5 * hx
    y1, y2 = ellipticity * (dj * hy - 0.5 * hy), ellipticity * (dj * hy + 0.5 * hy)
    rect = _f(x2, y2) - _f(x1, y2) - _f(x2, y1) + _f(x1, y1)
    return rect / ellipticity


# Grids of at most this many nodes (the coarsest, 17 x 17 by default) convolve by the dense matrix of K: there the
# transforms' cost is their calls' overhead (docs/tuning.md, pressure cycles)
DENSE_NODES = 400


class DeflectionOperator:
    """W = K * P on an (ny, nx) grid by zero-padded real FFTs (by the dense matrix of K on at most DENSE_NODES
    nodes); `coefficients` keeps K[d_j, d_i]."""

    def __init__(self, nx: int, ny: int, hx: float, hy: float, ellipticity: float):
        self.nx, self.ny = nx, ny
        self.coefficients = influence_coefficients(nx, ny, hx, hy, ellipticity)
        self._matrix = None
        if nx * ny <= DENSE_NODES:
            j, i = np.divmod(np.arange(nx * ny), nx)
            self._matrix = self.coefficients[np.abs(j[:, None] - j[None, :]), np.abs(i[:, None] - i[None, :])]
            return
        self.shape = (fft.next_fast_len(2 * ny - 2, real=True), fft.next_fast_len(2 * nx - 2, real=True))
        full = np.zeros(self.shape)
        k = self.coefficients
        # Place K(|d|) at circular offsets d and -d so that the product of transforms is a linear convolution (for
        # m = 2 n - 2 both write K(n - 1) at offset n - 1).
        full[:ny, :nx] = k
        full[:ny, -(nx - 1):] = k[:, :0:-1]
        full[-(ny - 1):, :nx] = k[:0:-1, :]
        full[-(ny - 1):, -(nx - 1):] = k[:0:-1, :0:-1]
        # An even kernel's transform is real: its imaginary part (round-off) is set to zero; kept complex, as the
        # product of a complex array with a real one costs NumPy a cast of the real one (1.6x the complex product).
        self._kernel_hat = fft.rfft2(full).real.astype(complex)
        self._inverse_size = 1.0 / (self.shape[0] * self.shape[1])  # the inverse transform's normalisation
        self._padded = np.zeros((ny, self.shape[1]))  # the pressure's rows padded along X (the padding stays zero)

    def apply(self, pressure: np.ndarray) -> np.ndarray:
        """W_ij = sum_{i'j'} K(|i - i'|, |j - j'|) P_{i'j'}; pressure shape (ny, nx). The transform of the padded
        pressure one axis at a time: along X its ny rows alone (the padding's rows transform to zero), along Y
        every column; back along Y every column, along X the ny rows kept, the normalisation 1/(m_y m_x) applied once
        at the end as the two-dimensional inverse applies it (a heavy hard case's 513^2 solve, M = 5000, closed its
        film with the normalisation applied per axis). The rows are padded in a work array kept with the operator (a
        padding by `rfft(n=...)` cost up to 3x the transform of 1025 x 129 pressures on 2048 nodes). 1.05 -> 0.90 ms on
        513 x 65 (transforms of 1080 x 135 -> 1024 x 128 nodes), 5.3 -> 4.3 ms on 1025 x 129, 65 -> 54 ms on 1025^2
        (`python scripts/bench_deflection.py --before DIR`, medians of 5, one machine)."""
        if self._matrix is not None:
            return (self._matrix @ pressure.ravel()).reshape(self.ny, self.nx)
        self._padded[:, : self.nx] = pressure
        rows = fft.rfft(self._padded, axis=1)
        spectrum = fft.fft(rows, n=self.shape[0], axis=0, overwrite_x=True)
        spectrum *= self._kernel_hat
        rows = fft.ifft(spectrum, axis=0, norm="forward", overwrite_x=True)[: self.ny]
        deflection = fft.irfft(rows, n=self.shape[1], axis=1, norm="forward")[:, : self.nx]
        deflection *= self._inverse_size
        return deflection
