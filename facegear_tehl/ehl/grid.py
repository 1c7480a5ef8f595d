"""Nested uniform grids and the transfer operators between them (arrays indexed [j, i], i along X).

Level l has (2^l m + 1) nodes per side; coarse node (jc, ic) coincides with fine node (2 jc, 2 ic), or with
fine node (jc, 2 ic) where only X is coarsened (semi-coarsening: `SEMI_X`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np


def hierarchy_sizes(finest: int, coarsest: int) -> list[int]:
    """Node counts per side from coarsest to finest, e.g. (257, 17) -> [17, 33, 65, 129, 257]."""
    sizes = [finest]
    while sizes[-1] > coarsest:
        sizes.append((sizes[-1] - 1) // 2 + 1)
    return sizes[::-1]


def hierarchy_shapes(finest_x: int, finest_y: int, coarsest: int) -> list[tuple[int, int]]:
    """(nx, ny) per level, coarsest first: nx halves alone while it is larger than ny (semi-coarsening), then
    both halve together until the smaller reaches `coarsest`, e.g. (257, 65, 17) -> [(17, 17), (33, 33),
    (65, 65), (129, 65), (257, 65)]; (65, 257, 17) -> [(17, 65), (33, 129), (65, 257)].

    The coarse grids of a grid refined along X are those of the square grid: a coarsest grid with 65 or more
    nodes along X (the rolling direction) runs away from the Hertz start with the default relaxation (so does a
    65^2 coarsest grid; with Venner's switch, the second attempt of solve.ATTEMPTS, about ten heavy contacts of the
    envelope suite start from 65^2).
    """
    x_only = []
    while finest_x > finest_y:
        x_only.insert(0, (finest_x, finest_y))
        finest_x = (finest_x - 1) // 2 + 1
    xs, ys = hierarchy_sizes(finest_x, coarsest), hierarchy_sizes(finest_y, coarsest)
    levels = min(len(xs), len(ys))
    return list(zip(xs[-levels:], ys[-levels:])) + x_only


def restrict_full_weighting(fine: np.ndarray) -> np.ndarray:
    """(1 2 1; 2 4 2; 1 2 1)/16 weighting at interior coarse nodes; boundary nodes 0."""
    nyc, nxc = (fine.shape[0] - 1) // 2 + 1, (fine.shape[1] - 1) // 2 + 1
    out = np.zeros((nyc, nxc))
    c = fine[2:-1:2, 2:-1:2]
    e = fine[2:-1:2, 3::2]
    w = fine[2:-1:2, 1:-2:2]
    n = fine[3::2, 2:-1:2]
    s = fine[1:-2:2, 2:-1:2]
    ne = fine[3::2, 3::2]
    nw = fine[3::2, 1:-2:2]
    se = fine[1:-2:2, 3::2]
    sw = fine[1:-2:2, 1:-2:2]
    out[1:-1, 1:-1] = (4.0 * c + 2.0 * (e + w + n + s) + ne + nw + se + sw) / 16.0
    return out


def restrict_pressure(fine: np.ndarray) -> np.ndarray:
    """Full weighting, but injection where any of the 9 fine nodes is cavitated (P = 0): keeps the free
    boundary sharp on the coarse grid (Venner & Lubrecht 2000)."""
    out = restrict_full_weighting(fine)
    injected = fine[::2, ::2]
    zero = fine <= 0.0
    near_zero = np.zeros(out.shape, dtype=bool)
    for dj in (-1, 0, 1):
        for di in (-1, 0, 1):
            near_zero[1:-1, 1:-1] |= zero[2 + dj : fine.shape[0] - 1 + dj : 2, 2 + di : fine.shape[1] - 1 + di : 2]
    out[near_zero] = injected[near_zero]
    out[0, :] = out[-1, :] = 0.0
    out[:, 0] = out[:, -1] = 0.0
    return out


def inject(fine: np.ndarray) -> np.ndarray:
    return fine[::2, ::2].copy()


def prolong_linear_x(coarse: np.ndarray) -> np.ndarray:
    """Linear interpolation along X only, to the grid with twice the X resolution."""
    nyc, nxc = coarse.shape
    out = np.zeros((nyc, 2 * nxc - 1))
    out[:, ::2] = coarse
    out[:, 1::2] = 0.5 * (coarse[:, :-1] + coarse[:, 1:])
    return out


def prolong_bilinear(coarse: np.ndarray) -> np.ndarray:
    """Bilinear interpolation of a coarse-grid array to the next finer grid."""
    along_x = prolong_linear_x(coarse)
    out = np.zeros((2 * coarse.shape[0] - 1, along_x.shape[1]))
    out[::2, :] = along_x
    out[1::2, :] = 0.5 * (out[:-1:2, :] + out[2::2, :])
    return out


def _cubic_axis(a: np.ndarray) -> np.ndarray:
    """Fourth-order interpolation along the last axis: mid-points by (-1, 9, 9, -1)/16,
    one-sided (5, 15, -5, 1)/16 next to the ends."""
    n = a.shape[-1]
    out = np.zeros(a.shape[:-1] + (2 * n - 1,))
    out[..., ::2] = a
    if n < 4:
        out[..., 1::2] = 0.5 * (a[..., :-1] + a[..., 1:])
        return out
    out[..., 1] = (5.0 * a[..., 0] + 15.0 * a[..., 1] - 5.0 * a[..., 2] + a[..., 3]) / 16.0
    out[..., 3:-3:2] = (-a[..., :-3] + 9.0 * a[..., 1:-2] + 9.0 * a[..., 2:-1] - a[..., 3:]) / 16.0
    out[..., -2] = (5.0 * a[..., -1] + 15.0 * a[..., -2] - 5.0 * a[..., -3] + a[..., -4]) / 16.0
    return out


def prolong_cubic(coarse: np.ndarray) -> np.ndarray:
    """Bicubic (fourth-order) interpolation of a converged coarse solution: the full-multigrid start."""
    return _cubic_axis(_cubic_axis(coarse).T).T


def restrict_full_weighting_x(fine: np.ndarray) -> np.ndarray:
    """(1 2 1)/4 weighting along X at interior coarse nodes (Y not coarsened); boundary nodes 0."""
    out = np.zeros((fine.shape[0], (fine.shape[1] - 1) // 2 + 1))
    out[1:-1, 1:-1] = (2.0 * fine[1:-1, 2:-1:2] + fine[1:-1, 1:-2:2] + fine[1:-1, 3::2]) / 4.0
    return out


def restrict_pressure_x(fine: np.ndarray) -> np.ndarray:
    """restrict_pressure along X only: injection where any of the 3 fine nodes is cavitated."""
    out = restrict_full_weighting_x(fine)
    zero = fine <= 0.0
    near_zero = np.zeros(out.shape, dtype=bool)
    near_zero[1:-1, 1:-1] = zero[1:-1, 1:-2:2] | zero[1:-1, 2:-1:2] | zero[1:-1, 3::2]
    out[near_zero] = fine[:, ::2][near_zero]
    return out


def inject_x(fine: np.ndarray) -> np.ndarray:
    return fine[:, ::2].copy()


@dataclass(frozen=True)
class Transfer:
    """The transfer operators between a grid and the next finer one."""

    restrict: Callable[[np.ndarray], np.ndarray]  # full weighting (residuals)
    restrict_pressure: Callable[[np.ndarray], np.ndarray]
    inject: Callable[[np.ndarray], np.ndarray]
    prolong: Callable[[np.ndarray], np.ndarray]  # (bi)linear: coarse-grid corrections, film state
    prolong_cubic: Callable[[np.ndarray], np.ndarray]  # the full-multigrid start


STANDARD = Transfer(restrict_full_weighting, restrict_pressure, inject, prolong_bilinear, prolong_cubic)
SEMI_X = Transfer(restrict_full_weighting_x, restrict_pressure_x, inject_x, prolong_linear_x, _cubic_axis)


def transfer(fine_shape: tuple[int, int], coarse_shape: tuple[int, int]) -> Transfer:
    """The operators between grids of (nx, ny) `fine_shape` and `coarse_shape` (hierarchy_shapes)."""
    return SEMI_X if fine_shape[1] == coarse_shape[1] else STANDARD


def bilinear_at(values: np.ndarray, x: np.ndarray, y: np.ndarray, x0: float, y0: float) -> float:
    """Bilinear interpolation of values[j, i] on the uniform axes x, y at (x0, y0)."""
    fx = (x0 - x[0]) / (x[1] - x[0])
    fy = (y0 - y[0]) / (y[1] - y[0])
    i = int(np.clip(np.floor(fx), 0, len(x) - 2))
    j = int(np.clip(np.floor(fy), 0, len(y) - 2))
    tx, ty = fx - i, fy - j
    return float(
        (1 - ty) * ((1 - tx) * values[j, i] + tx * values[j, i + 1])
        + ty * ((1 - tx) * values[j + 1, i] + tx * values[j + 1, i + 1])
    )
