"""Root finding for the geometry and contact modules, with SciPy imported on first use: `scipy.optimize` pulls in
scipy.linalg and costs about 0.2 s, which every command (`tehl validate`, `tehl info`) paid at start-up."""

from __future__ import annotations

from typing import Any, Callable


def brentq(function: Callable[[float], float], low: float, high: float, **options: Any) -> float:
    """The root of `function` bracketed by [low, high] (scipy.optimize.brentq, Brent 1973), options passed on."""
    from scipy.optimize import brentq as scipy_brentq

    return scipy_brentq(function, low, high, **options)
