"""Brent's root finder (roots.py) and the AGM elliptic integrals of hertz.py against known values."""

import math

import pytest

from facegear_tehl.hertz import _elliptic_integrals
from facegear_tehl.roots import brentq


@pytest.mark.parametrize("function, low, high, root", [
    (lambda x: x * x - 2.0, 0.0, 2.0, math.sqrt(2.0)),
    (lambda x: math.cos(x) - x, 0.0, 1.0, 0.7390851332151607),  # the Dottie number
    (lambda x: x**3 - 2.0 * x - 5.0, 2.0, 3.0, 2.0945514815423265),  # Wallis's cubic (Newton's example)
    (lambda x: math.exp(x) - 1e6, 0.0, 20.0, math.log(1e6)),
    (lambda x: math.log(x) + 30.0, 1e-20, 1.0, math.exp(-30.0)),
])
def test_brentq_finds_known_roots_to_its_tolerance(function, low, high, root):
    assert brentq(function, low, high, xtol=1e-15) == pytest.approx(root, rel=1e-14, abs=1e-15)


def test_brentq_refuses_a_bracket_without_a_sign_change_and_stops_at_maxiter():
    with pytest.raises(ValueError, match="opposite signs"):
        brentq(lambda x: x * x + 1.0, -1.0, 1.0)
    with pytest.raises(RuntimeError, match="did not converge"):
        brentq(lambda x: x**3 - 0.3, 0.0, 1.0, xtol=0.0, rtol=0.0, maxiter=3)


def test_elliptic_integrals_match_tabulated_values_and_limits():
    # m = 1/2 (k = sqrt 2): K = 1.854074677301372, E = 1.350643881047675 (Abramowitz & Stegun 1964, table 17.1)
    k_half, e_half = _elliptic_integrals(math.sqrt(2.0))
    assert k_half == pytest.approx(1.854074677301372, rel=1e-15)
    assert e_half == pytest.approx(1.350643881047675, rel=1e-15)
    assert _elliptic_integrals(1.0) == (pytest.approx(math.pi / 2, rel=1e-16), pytest.approx(math.pi / 2, rel=1e-16))
    # m -> 1 (k = 1e4): K ~ ln(4/k') + (k'^2/4)(ln(4/k') - 1), E ~ 1 + (k'^2/2)(ln(4/k') - 1/2), k' = 1/k (A&S 17.3.26,
    # 17.3.36)
    kp = 1e-4
    big_k, big_e = _elliptic_integrals(1.0 / kp)
    assert big_k == pytest.approx(math.log(4 / kp) + kp * kp / 4 * (math.log(4 / kp) - 1), rel=1e-14)
    assert big_e == pytest.approx(1 + kp * kp / 2 * (math.log(4 / kp) - 0.5), rel=1e-14)
