"""Root finding for the geometry, contact and Hertz modules: Brent's method (Brent 1973, *Algorithms for
Minimization without Derivatives*, ch. 4; in the form of Forsythe, Malcolm & Moler 1977, `zeroin`).

Written here rather than taken from `scipy.optimize`, which pulls in scipy.linalg and scipy.sparse: about 0.3 s of
CPU that every command reading a gear case (`tehl validate`, `tehl contact`) paid. The tolerance has SciPy's
meaning: the root is found to within xtol + rtol |x|.
"""

from __future__ import annotations

from typing import Callable

EPS = 2.220446049250313e-16  # IEEE 754 double machine epsilon
DEFAULT_XTOL = 2e-12  # absolute tolerance when not given (scipy.optimize.brentq's default)
DEFAULT_RTOL = 4.0 * EPS  # relative tolerance when not given: the smallest SciPy accepts
DEFAULT_MAXITER = 100  # iterations when not given (bisection alone halves a bracket 100 times: 2^-100)


def brentq(function: Callable[[float], float], low: float, high: float, xtol: float = DEFAULT_XTOL,
           rtol: float = DEFAULT_RTOL, maxiter: int = DEFAULT_MAXITER) -> float:
    """The root of `function` in the bracket [low, high] (function(low) and function(high) of opposite signs, or
    one of them zero) to within xtol + rtol |x|: inverse quadratic interpolation or the secant where it makes
    progress, else bisection, so the bracket at least halves every two steps (Brent 1973, ch. 4).

    Raises ValueError for a bracket without a sign change and RuntimeError after `maxiter` iterations."""
    a, b = float(low), float(high)
    fa, fb = function(a), function(b)
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if (fa > 0.0) == (fb > 0.0):
        raise ValueError(f"f({a}) = {fa} and f({b}) = {fb} must have opposite signs")
    c, fc = a, fa
    step = previous = b - a
    for _ in range(maxiter):
        if (fb > 0.0) == (fc > 0.0):  # the root lies between a and b: c takes a's place
            c, fc = a, fa
            step = previous = b - a
        if abs(fc) < abs(fb):  # b is the best estimate
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tolerance = 0.5 * (xtol + rtol * abs(b))
        half = 0.5 * (c - b)
        if fb == 0.0 or abs(half) <= tolerance:
            return b
        if abs(previous) >= tolerance and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:  # secant
                p, q = 2.0 * half * s, 1.0 - s
            else:  # inverse quadratic interpolation through a, b, c
                q, r = fa / fc, fb / fc
                p = s * (2.0 * half * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0.0:
                q = -q
            else:
                p = -p
            if 2.0 * p < min(3.0 * half * q - abs(tolerance * q), abs(previous * q)):  # accept the interpolation
                previous, step = step, p / q
            else:
                previous = step = half
        else:
            previous = step = half
        a, fa = b, fb
        b += step if abs(step) > tolerance else (tolerance if half > 0.0 else -tolerance)
        fb = function(b)
    raise RuntimeError(f"Brent's method did not converge in {maxiter} iterations (bracket [{b}, {c}])")
