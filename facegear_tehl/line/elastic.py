r"""Elastic deflection of a line contact and the dry (Hertz) line-contact solution.

Plane strain, two elastic half-spaces (Johnson, *Contact Mechanics*, 1985, ch. 2): a pressure p(s) on the
strip gives the combined normal surface displacement, up to a constant,

    v(x) = -(4/(pi E')) \int p(s) ln|x - s| ds,      E' = 2/[(1 - nu1^2)/E1 + (1 - nu2^2)/E2]

and the gap h(x) = h_0 + x^2/(2R) + v(x).  Scaled with the Hertz half-width b and maximum pressure p_h of the
same load per unit length w' (Johnson 1985, eqs. 4.43-4.45, written with E' = 2E*):

    b = sqrt(8 w' R/(pi E')),   p_h = 2 w'/(pi b) = sqrt(w' E'/(2 pi R)) = E' b/(4R)

(in Johnson's E* = E'/2: b = sqrt(4 w' R/(pi E*)), p_h = sqrt(w' E*/(pi R))),

X = x/b, P = p/p_h, H = h R/b^2, the gap is H(X) = H_0 + X^2/2 - (1/pi) \int P(S) ln|X - S| dS, and the load
balance is \int P dX = pi/2.  The factor 4 p_h R/(E' b) = 1 makes the kernel coefficient exactly 1/pi.

Discretisation (this module): P piecewise linear between the nodes (hat functions, on any node spacing),
integrated exactly against the logarithm, so that K @ P is the deflection of the interpolated pressure, not a
quadrature of it.  For the Hertz semi-ellipse the classical identity (a semi-elliptical pressure flattens the
parabolic gap: the Hertz line contact, Johnson 1985, ch. 4)

    -(1/pi) \int_{-1}^{1} sqrt(1 - S^2) ln|X - S| dS = -X^2/2 + (1 + 2 ln 2)/4,    |X| <= 1

makes the gap exactly flat over the contact; `tests/test_line_contact.py` checks K against it.
"""

from __future__ import annotations

import math

import numpy as np


def hertz_line(load_per_length: float, radius: float, reduced_modulus: float) -> tuple[float, float]:
    """(b, p_h) of a dry line contact: b = sqrt(8 w' R/(pi E')), p_h = 2 w'/(pi b) = sqrt(w' E'/(2 pi R)), m and
    Pa (Johnson 1985, eqs. 4.43-4.45 with E* = E'/2; Hamrock et al. 2004, eqs. 17.37 and 17.40)."""
    b = math.sqrt(8.0 * load_per_length * radius / (math.pi * reduced_modulus))
    p_h = 2.0 * load_per_length / (math.pi * b)
    return b, p_h


def hertz_deflection(x: np.ndarray) -> np.ndarray:
    """-(1/pi) int_{-1}^{1} sqrt(1 - S^2) ln|X - S| dS for |X| <= 1 (closed form, see module docstring)."""
    return -0.5 * np.asarray(x) ** 2 + 0.25 * (1.0 + 2.0 * math.log(2.0))


def _f0(t: np.ndarray) -> np.ndarray:
    """Antiderivative of ln|t|: t ln|t| - t (0 at t = 0)."""
    at = np.abs(t)
    safe = np.where(at > 0.0, at, 1.0)
    return np.where(at > 0.0, t * np.log(safe) - t, 0.0)


def _f1(t: np.ndarray) -> np.ndarray:
    """Antiderivative of t ln|t|: t^2 ln|t|/2 - t^2/4 (0 at t = 0)."""
    at = np.abs(t)
    safe = np.where(at > 0.0, at, 1.0)
    return np.where(at > 0.0, 0.5 * t * t * np.log(safe) - 0.25 * t * t, 0.0)


def _segment_integrals(x: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For targets x (column) and segments [lo, hi] (row): I0 = int ln|x - s| ds and
    I1 = int (s - lo) ln|x - s| ds over the segment, exactly (substitution t = s - x)."""
    ta = lo[None, :] - x[:, None]
    tb = hi[None, :] - x[:, None]
    i0 = _f0(tb) - _f0(ta)
    # s - lo = t - ta:  int (t - ta) ln|t| dt
    i1 = (_f1(tb) - _f1(ta)) - ta * i0
    return i0, i1


def influence_matrix(nodes: np.ndarray) -> np.ndarray:
    """K with (K @ P)_i = -(1/pi) int P(S) ln|X_i - S| dS for P piecewise linear on `nodes` (increasing),
    exact integrals of the hat functions (dimensionless; see module docstring). Shape (n, n)."""
    x = np.asarray(nodes, dtype=np.float64)
    lo, hi = x[:-1], x[1:]
    width = hi - lo
    i0, i1 = _segment_integrals(x, lo, hi)
    rising = i1 / width[None, :]  # hat of the right node of each segment: (s - lo)/width
    falling = i0 - rising  # hat of the left node: 1 - (s - lo)/width
    k = np.zeros((x.size, x.size))
    k[:, 1:] += rising
    k[:, :-1] += falling
    return -k / math.pi


def load_weights(nodes: np.ndarray) -> np.ndarray:
    """Weights w with w @ P = int P dX for P piecewise linear on `nodes` (the trapezoidal rule, exact)."""
    x = np.asarray(nodes, dtype=np.float64)
    w = np.zeros(x.size)
    d = np.diff(x)
    w[:-1] += 0.5 * d
    w[1:] += 0.5 * d
    return w
