"""Exact Hertz theory (Johnson 1985, Contact Mechanics, ch. 4) against published and independently computed
values and closed forms."""

import math

import numpy as np
import pytest

from facegear_tehl.hertz import ellipticity, hertz_contact, relative_curvature
from facegear_tehl.materials import Solid, reduced_modulus


def steel(e=206e9):
    return Solid(elastic_modulus=e, poisson_ratio=0.3)


def within_quoted(value, quoted, decimals):
    """The reference is quoted to `decimals` places: agree to half a unit of its last digit."""
    assert abs(value - quoted) <= 0.5 * 10.0 ** (-decimals) * (1 + 1e-9), (value, quoted)


def test_two_steel_balls_stachowiak():
    # Stachowiak & Batchelor, Engineering Tribology, p. 291 example: R = 10 and 15 mm -> R_x = R_y = 6 mm, W = 5 N.
    e_prime = reduced_modulus(steel(210e9), steel(210e9))
    within_quoted(e_prime / 1e11, 2.30769, 5)
    h = hertz_contact(6e-3, 6e-3, 5.0, e_prime)
    within_quoted(h.a * 1e6, 57.989, 3)
    within_quoted(h.p_max / 1e6, 709.94, 2)
    within_quoted(h.p_mean / 1e6, 473.29, 2)
    within_quoted(h.approach * 1e9, 560.45, 2)


def test_elliptical_steel_contact():
    # Worked example (computed independently): R_x = 10 mm, R_y = 50 mm, W = 1000 N, E = 206 GPa.
    h = hertz_contact(10e-3, 50e-3, 1000.0, reduced_modulus(steel(), steel()))
    within_quoted(h.ellipticity, 2.89018, 5)
    within_quoted(h.elliptic_k, 2.49374, 5)
    within_quoted(h.elliptic_e, 1.12052, 5)
    within_quoted(h.a * 1e6, 869.804, 3)
    within_quoted(h.b * 1e6, 300.951, 3)
    within_quoted(h.p_max / 1e9, 1.8240, 4)
    within_quoted(h.approach * 1e6, 12.094, 3)


@pytest.mark.parametrize(
    "r_y, a_um, b_um, p_gpa, delta_um",
    [(20e-3, 262.064, 165.256, 1.1025, 3.0824), (10e-3, 186.626, 186.626, 1.3709, 3.4829)],
)
def test_crossed_cylinders(r_y, a_um, b_um, p_gpa, delta_um):
    # Worked examples (computed independently): crossed cylinders R1 = 10 mm, R2 = 20 (or 10) mm, W = 100 N, E = 210
    # GPa.
    h = hertz_contact(10e-3, r_y, 100.0, reduced_modulus(steel(210e9), steel(210e9)))
    within_quoted(h.a * 1e6, a_um, 3)
    within_quoted(h.b * 1e6, b_um, 3)
    within_quoted(h.p_max / 1e9, p_gpa, 4)
    within_quoted(h.approach * 1e6, delta_um, 4)


@pytest.mark.parametrize(
    "ratio, k, e, kk",
    [(1, 1.0, 1.57080, 1.57080), (1.5, 1.31010, 1.39114, 1.78977), (2, 1.58580, 1.29715, 1.95211),
     (3, 2.07199, 1.20018, 2.18827), (5, 2.89018, 1.12052, 2.49374), (10, 4.49945, 1.05988, 2.91420),
     (20, 6.92868, 1.02958, 3.33419), (50, 12.07115, 1.01161, 3.88207), (100, 18.18710, 1.00573, 4.28950)],
)
def test_ellipticity_table(ratio, k, e, kk):
    # Exact k, K(m), E(m) computed independently (Brewe & Hamrock 1977 tabulate the same comparison).
    k_num, kk_num, e_num = ellipticity(ratio)
    within_quoted(k_num, k, 5)
    within_quoted(e_num, e, 5)
    within_quoted(kk_num, kk, 5)


@pytest.mark.parametrize("ratio", [1.0001, 7.3, 300.0, 800.0, 2000.0])
def test_ellipticity_solves_its_equation(ratio):
    # alpha_r = (k^2 E - K)/(K - E) must hold to 1e-9 up to the face-gear ratios (300-800, docs/accuracy.md).
    k, kk, e = ellipticity(ratio)
    assert (k * k * e - kk) / (kk - e) == pytest.approx(ratio, rel=1e-9)


def test_circular_limit_is_exact():
    # k = 1: a = (3 W R_s/(4 E*))^(1/3), delta = (9 W^2/(16 R_s E*^2))^(1/3) (Johnson 1985, §4.2).
    e_star = 1.1e11
    h = hertz_contact(0.02, 0.02, 250.0, 2 * e_star)
    assert h.a == pytest.approx((3 * 250.0 * 0.02 / (4 * e_star)) ** (1 / 3), rel=1e-12)
    assert h.approach == pytest.approx((9 * 250.0**2 / (16 * 0.02 * e_star**2)) ** (1 / 3), rel=1e-12)


def test_facegear_hertz_check():
    # Worked check of the independent gear implementation (docs/accuracy.md): F = 1000 N, E' = 226.37 GPa -> a =
    # 2.1040 mm, b = 0.1992 mm, p0 = 1139 MPa.
    # The values hold for R_x = 10 mm and R_y = 400 mm (the text's "R_y = 40" drops a zero: with 40 mm,
    # a = 0.786 mm). a, b and p0 scale as F^(1/3).
    e_prime = 226.37e9
    h1 = hertz_contact(10e-3, 0.4, 1000.0, e_prime)
    within_quoted(h1.a * 1e3, 2.1040, 4)
    within_quoted(h1.b * 1e3, 0.1992, 4)
    within_quoted(h1.p_max / 1e6, 1139.0, 0)
    h8 = hertz_contact(10e-3, 0.4, 8000.0, e_prime)
    assert (h8.a / h1.a, h8.b / h1.b, h8.p_max / h1.p_max) == pytest.approx((2.0, 2.0, 2.0), rel=1e-12)


@pytest.mark.parametrize(
    "alpha, a_coef, b_coef, rx_mm, ry_mm",
    [(0, 13.3333, 21.6667, 23.0769, 37.500), (30, 8.7997, 26.2003, 19.0838, 56.820),
     (60, 3.6306, 31.3694, 15.9391, 137.72), (90, 1.6667, 33.3333, 15.000, 300.00)],
)
def test_relative_curvature_table(alpha, a_coef, b_coef, rx_mm, ry_mm):
    # Johnson (1985) §4.1 relative curvature, worked case: pinion R' = 20, R'' = 100 mm; face gear R' = -150, R'' =
    # +60 mm (hyperbolic point).
    rc = relative_curvature(1 / 20e-3, 1 / 100e-3, -1 / 150e-3, 1 / 60e-3, math.radians(alpha))
    within_quoted(rc.A, a_coef, 4)
    within_quoted(rc.B, b_coef, 4)
    assert rc.radius_x * 1e3 == pytest.approx(rx_mm, abs=6e-4 * rx_mm)
    assert rc.radius_y * 1e3 == pytest.approx(ry_mm, abs=6e-4 * ry_mm)


def test_relative_curvature_equals_tensor_eigenvalues():
    # Johnson's closed form = half-eigenvalues of K1 + Rot(alpha) K2 Rot(alpha)^T, with the eigenvector angle.
    rng = np.random.default_rng(7)
    for _ in range(50):
        k1 = rng.uniform(-50, 80, 2)
        k2 = rng.uniform(-50, 80, 2)
        alpha = rng.uniform(0, math.pi)
        rot = np.array([[math.cos(alpha), -math.sin(alpha)], [math.sin(alpha), math.cos(alpha)]])
        total = np.diag(k1) + rot @ np.diag(k2) @ rot.T
        values, vectors = np.linalg.eigh(total)
        rc = relative_curvature(k1[0], k1[1], k2[0], k2[1], alpha)
        assert rc.A == pytest.approx(values[0] / 2, abs=1e-9)
        assert rc.B == pytest.approx(values[1] / 2, abs=1e-9)
        direction = np.array([math.cos(rc.angle), math.sin(rc.angle)])
        assert abs(abs(direction @ vectors[:, 1]) - 1.0) < 1e-9
