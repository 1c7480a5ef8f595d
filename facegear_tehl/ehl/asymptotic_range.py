"""Roache's asymptotic-range check of a grid-convergence estimate (Roache 1998, Verification and Validation in
Computational Science and Engineering, ch. 5; Celik et al. 2008, J. Fluids Eng. 130: 078001): three grids along x, a
figure's two successive Richardson estimates, the order they show and whether the safety factor of the bound
(TUNING.bound_safety) still covers it. error_bounds.py applies it to every reported figure with a third grid.
"""

from __future__ import annotations

from dataclasses import dataclass
import math

from facegear_tehl.ehl.tuning import TUNING


def lowest_order(order: int) -> float:
    """The lowest order q of a figure converging as C h^q at which F_s times its Richardson estimate at the assumed
    `order` p still bounds its error: F_s/(2^p - 1) >= 1/(2^q - 1), q = log2(1 + (2^p - 1)/F_s) (1 for p = 2, 0.415
    for p = 1 at F_s = 3)."""
    return math.log2(1.0 + (2.0**order - 1.0) / TUNING.bound_safety)


def observed_order(e_x: float, coarser: float) -> float:
    """The order q of f = f* + C h^q read from three grids along x (Roache 1998, ch. 5; Celik et al. 2008, J. Fluids
    Eng. 130: 078001, eq. 4 at the ratio 2): log2 of the ratio of the successive differences, from the x-estimates of
    the finer pair `e_x` and of the next coarser pair `coarser` (both Richardson-scaled at the same order and in units
    of the reported figure); NaN where the differences change sign (oscillatory convergence) or vanish."""
    if not (math.isfinite(e_x) and math.isfinite(coarser)) or e_x * coarser <= 0.0:
        return math.inf if e_x == 0.0 and coarser != 0.0 and math.isfinite(coarser) else math.nan
    return math.log2(coarser / e_x)


def three_grid_estimate(e_x: float, coarser: float, order: int, noise: float = 0.0) -> float:
    """|e_x| checked against the next coarser pair along x (`coarser`, NaN: no third grid, |e_x| as it is); inf where
    the three grids are outside the asymptotic range: the differences change sign, or do not fall at the observed order
    `lowest_order` of the assumed `order` asks (Roache's asymptotic-range check of the grid convergence index, 1998,
    ch. 5; the figures it concerns: docs/accuracy.md, error bounds), each beyond what the iterations' errors in the
    two estimates, `noise` (in e_x's units), can make of them: two estimates within it of zero have no sign nor order
    to read. Within it, the larger of |e_x| and the coarser pair's estimate carried one grid finer at the assumed order
    over F_s, |coarser|/(2^p F_s): under f = f* + C h^q F_s |e_x| bounds the error of the finest figure for q from
    lowest_order, |coarser|/2^p for q from p on; the second takes over where it exceeds the first (q above p + log2
    F_s), as where the finest pair's difference vanishes by chance (an error crossing zero between its grids)."""
    if not math.isfinite(coarser):
        return abs(e_x)
    oscillating = e_x * coarser < 0.0 and min(abs(e_x), abs(coarser)) > noise
    slow = abs(coarser) + noise < 2.0 ** lowest_order(order) * (abs(e_x) - noise)
    if oscillating or slow:
        return math.inf
    return max(abs(e_x), abs(coarser) / (2.0**order * TUNING.bound_safety))


@dataclass(frozen=True)
class CoarserPair:
    """The next coarser pair's x-estimate of a figure (Richardson-scaled as report.estimate, in units of the reported
    figure) and how far the iterations of its two grids can move it (same units)."""

    estimate: float
    noise: float = 0.0
