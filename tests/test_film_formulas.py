"""Film-thickness formulas (Hamrock & Dowson 1977; Nijenbanning et al. 1994; Chittenden et al. 1985)
against worked numbers computed independently from the published formulas."""

import math

import pytest

from facegear_tehl import film_formulas as ff
from facegear_tehl.hertz import ellipticity

# Worked case: R_x = 10 mm, R_y = 50 mm, F = 1000 N, E' = 226.37 GPa, eta_0 = 0.03 Pa s, alpha = 15/GPa, u = 5 m/s
U, G, W = 6.6262e-11, 3395.6, 4.4175e-5
K = 1.03 * 5.0**0.64  # Hamrock-Dowson's ellipticity approximation, as in their fit


def test_hamrock_dowson_worked_example():
    assert ff.hamrock_dowson_central(U, G, W, K) * 0.01 == pytest.approx(549.3e-9, rel=1e-3)
    assert ff.hamrock_dowson_minimum(U, G, W, K) * 0.01 == pytest.approx(417.7e-9, rel=1e-3)


def test_chittenden_worked_example_and_zero_angle():
    r_e, r_s = ff.chittenden_radii(0.01, 0.05, 0.0)
    assert (r_e, r_s) == pytest.approx((0.01, 0.05))
    assert ff.chittenden_central(U, G, W, r_s / r_e) * 0.01 == pytest.approx(560.9e-9, rel=1e-3)
    assert ff.chittenden_minimum(U, G, W, r_s / r_e) * 0.01 == pytest.approx(423.0e-9, rel=1e-3)


def test_nijenbanning_worked_example():
    # M = 1130.97, L = 11.521, D = 0.2 -> h_c = 617.0 nm with h = H_c R_x (2U)^(1/2)
    h = ff.nijenbanning_central(1130.97, 11.521, 0.2) * 0.01 * math.sqrt(2 * U)
    assert h == pytest.approx(617.0e-9, rel=1e-3)


@pytest.mark.parametrize("m, moes_l, h", [(10, 10, 4.8324), (20, 10, 4.7081), (50, 5, 3.1540), (100, 10, 4.4965),
                                     (200, 10, 4.3803), (500, 20, 6.5504), (1000, 10, 4.0346)])
def test_nijenbanning_circular_table(m, moes_l, h):
    assert ff.nijenbanning_central(m, moes_l, 1.0) == pytest.approx(h, rel=2e-4)


@pytest.mark.parametrize("d, h", [(0.5, 5.1459), (0.2, 5.7295), (0.1, 6.0538)])
def test_nijenbanning_elliptical_table(d, h):
    assert ff.nijenbanning_central(100, 10, d) == pytest.approx(h, rel=2e-4)


def test_exact_ellipticity_is_close_to_hamrock_dowson_fit():
    assert ellipticity(5.0)[0] == pytest.approx(K, rel=0.01)
