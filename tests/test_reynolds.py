"""The discrete Reynolds operator (ehl/reynolds.py) against a manufactured solution.

Smooth P(X, Y) and H(X, Y) are chosen, eps and the Couette fluxes follow from them through a Barus viscosity and
a Dowson-Higginson-type density, and the continuous operator of the dimensionless Reynolds equation (scaling.py)

    L(P) = d/dX(eps dP/dX) + k^-2 d/dY(eps dP/dY) - s_x dq_x/dX - s_y dq_y/dY,   q = |c| rho H

is evaluated from derivatives written out by hand below (product and chain rules), not by the code under test.
The truncation error L_h(P) - L(P) on grids of 33, 65 and 129 nodes must fall at the order of each part of the
scheme: second for the Poiseuille (diffusion) term with arithmetic-mean face coefficients, third for the
upwind-biased wedge difference (2, 3, -6, 1)/6 inside the domain and first on the line next to the upstream
boundary, where the kernel falls back to the two-point difference (Venner & Lubrecht 2000, ch. 5 and 8).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from facegear_tehl.ehl import reynolds

GRIDS = (33, 65, 129)
DOMAIN_X = (-4.5, 1.5)  # Venner & Lubrecht's inlet-heavy X range
DOMAIN_Y = (-2.0, 2.0)  # narrower than X: h_y != h_x, so the two axes' factors cannot be swapped unnoticed
K = 2.0  # ellipticity: the Y Poiseuille factor is 1/k^2 = 0.25 (MultigridSolver._args)
LAM = 0.5  # lambda in eps = rho H^3/(eta lambda)
ALPHA = 2.0  # dimensionless Barus coefficient: eta = exp(ALPHA P), eps varies by e^2 over the domain
RHO_A, RHO_B = 0.6, 1.7  # rho = 1 + A P/(1 + B P)
PSI = math.radians(-30.0)  # entrainment angle: s_x = +1, s_y = -1, both upwind orientations exercised
CX, CY = math.cos(PSI), math.sin(PSI) / K  # wedge factors cos(psi), kappa sin(psi) (scaling.py)
SX, SY = int(np.sign(CX)), int(np.sign(CY))


# ------------------------------------------------------------------------- the manufactured solution

def pressure(x, y):
    """P = E (1 + 0.1 X), E = exp(-X^2/4 - Y^2/2), with (P, P_X, P_Y, P_XX, P_YY)."""
    e = np.exp(-(x**2) / 4.0 - y**2 / 2.0)
    e_x, e_y = -x / 2.0 * e, -y * e
    e_xx, e_yy = (x**2 / 4.0 - 0.5) * e, (y**2 - 1.0) * e
    g = 1.0 + 0.1 * x
    return e * g, e_x * g + 0.1 * e, e_y * g, e_xx * g + 0.2 * e_x, e_yy * g


def film(x, y):
    """H = 1 + X^2/2 + 0.3 Y^2 + 0.2 sin X cos Y (> 0.8), with (H, H_X, H_Y)."""
    h = 1.0 + 0.5 * x**2 + 0.3 * y**2 + 0.2 * np.sin(x) * np.cos(y)
    return h, x + 0.2 * np.cos(x) * np.cos(y), 0.6 * y - 0.2 * np.sin(x) * np.sin(y)


def density(p):
    """rho(P) = 1 + A P/(1 + B P) and rho'(P)."""
    return 1.0 + RHO_A * p / (1.0 + RHO_B * p), RHO_A / (1.0 + RHO_B * p) ** 2


def exact_parts(x, y):
    """(P, eps, q_x, q_y, Poiseuille part, wedge part) of L(P) = Poiseuille - wedge, analytically."""
    p, p_x, p_y, p_xx, p_yy = pressure(x, y)
    h, h_x, h_y = film(x, y)
    rho, rho_p = density(p)
    viscous = np.exp(-ALPHA * p) / LAM  # 1/(eta lambda)
    eps = rho * h**3 * viscous
    eps_p = (rho_p - ALPHA * rho) * h**3 * viscous  # d eps/dP at fixed H
    eps_h = 3.0 * rho * h**2 * viscous  # d eps/dH at fixed P
    eps_x, eps_y = eps_p * p_x + eps_h * h_x, eps_p * p_y + eps_h * h_y
    poiseuille = (eps_x * p_x + eps * p_xx) + (eps_y * p_y + eps * p_yy) / K**2
    # q = |c| rho H (flow.isothermal_coefficients: f = rho |c|); the kernel differences it along s
    q_x, q_y = abs(CX) * rho * h, abs(CY) * rho * h
    dq_x = abs(CX) * (rho_p * p_x * h + rho * h_x)
    dq_y = abs(CY) * (rho_p * p_y * h + rho * h_y)
    wedge = SX * dq_x + SY * dq_y
    return p, eps, q_x, q_y, poiseuille, wedge


def grid(n):
    x = np.linspace(*DOMAIN_X, n)
    y = np.linspace(*DOMAIN_Y, n)
    xx, yy = np.meshgrid(x, y)  # (ny, nx), i along X
    return x[1] - x[0], y[1] - y[0], xx, yy


def discrete(n, *, poiseuille=True, wedge=True):
    """(L_h(P), L(P)) on the n x n grid, with the Poiseuille and/or the wedge part."""
    hx, hy, xx, yy = grid(n)
    p, eps, q_x, q_y, exact_poiseuille, exact_wedge = exact_parts(xx, yy)
    if not poiseuille:
        eps = np.zeros_like(eps)
    sx, sy = (SX, SY) if wedge else (0, 0)
    out = np.empty_like(p)
    reynolds.apply_operator(p, q_x, q_y, eps, hx, hy, 1.0, 1.0 / K**2, sx, sy, out)
    exact = (exact_poiseuille if poiseuille else 0.0) - (exact_wedge if wedge else 0.0)
    return out, exact


def orders(errors):
    """Observed orders log2(e_h/e_h/2) between successive grids."""
    return [math.log2(coarse / fine) for coarse, fine in itertools.pairwise(errors)]


def upstream_lines(n):
    """Masks of the interior nodes whose wedge difference is first order (the line next to the upstream
    boundary in X, and in Y) and of the other interior nodes."""
    first = np.zeros((n, n), dtype=bool)
    first[1:-1, 1 if SX > 0 else n - 2] = True
    first[1 if SY > 0 else n - 2, 1:-1] = True
    inner = np.zeros((n, n), dtype=bool)
    inner[1:-1, 1:-1] = True
    return first & inner, inner & ~first


# --------------------------------------------------------------------------------------------- tests

def test_the_analytic_derivatives_match_central_differences():
    """A check of the hand-written derivatives themselves (not of the scheme): the Poiseuille and wedge parts
    against fourth-order central differences of eps P_X, eps P_Y, q_x, q_y at a few points, step 1e-3."""
    d = 1e-3

    def central(f, x, y, axis):
        sx, sy = (d, 0.0) if axis == 0 else (0.0, d)
        return (-f(x + 2 * sx, y + 2 * sy) + 8.0 * f(x + sx, y + sy) - 8.0 * f(x - sx, y - sy)
                + f(x - 2 * sx, y - 2 * sy)) / (12.0 * d)

    def flux(axis):
        def f(x, y):
            eps = exact_parts(x, y)[1]
            return eps * pressure(x, y)[1 + axis]
        return f

    def qx(x, y):
        return exact_parts(x, y)[2]

    def qy(x, y):
        return exact_parts(x, y)[3]

    for x, y in [(-1.3, 0.4), (0.2, -0.9), (-3.0, 1.5)]:
        _, _, _, _, poiseuille, wedge = exact_parts(np.array(x), np.array(y))
        numeric = central(flux(0), x, y, 0) + central(flux(1), x, y, 1) / K**2
        # differences: O(d^4) ~ 1e-12 truncation and ~1e-13 round-off; a wrong term would be off by O(0.1-1)
        assert poiseuille == pytest.approx(numeric, rel=1e-8, abs=1e-10)
        numeric_wedge = SX * central(qx, x, y, 0) + SY * central(qy, x, y, 1)
        assert wedge == pytest.approx(numeric_wedge, rel=1e-8, abs=1e-10)


def test_poiseuille_term_is_second_order():
    errors = []
    for n in GRIDS:
        discrete_value, exact = discrete(n, wedge=False)
        errors.append(np.abs(discrete_value - exact)[1:-1, 1:-1].max())
    observed = orders(errors)
    # the 5-point stencil with arithmetic-mean eps at the faces is second order: 2 +- 0.2 (pre-asymptotic slack)
    assert all(1.8 < p < 2.2 for p in observed), (errors, observed)


def test_wedge_term_is_third_order_inside_and_first_order_next_to_the_upstream_boundary():
    inner_errors, first_errors = [], []
    for n in GRIDS:
        discrete_value, exact = discrete(n, poiseuille=False)
        first, inner = upstream_lines(n)
        error = np.abs(discrete_value - exact)
        inner_errors.append(error[inner].max())
        first_errors.append(error[first].max())
    # (2, 3, -6, 1)/6 is third order: 3 +- 0.2; the two-point fallback next to the inlet is first order: 1 +- 0.2
    assert all(2.8 < p < 3.2 for p in orders(inner_errors)), (inner_errors, orders(inner_errors))
    assert all(0.8 < p < 1.2 for p in orders(first_errors)), (first_errors, orders(first_errors))


def test_full_operator_and_residual():
    """With f = L(P): residual = f - L_h(P) at nodes with P > 0, zero on cavitated nodes and on the boundary;
    it falls at second order away from the upstream lines, first order on them."""
    inner_errors, first_errors = [], []
    for n in GRIDS:
        hx, hy, xx, yy = grid(n)
        p, eps, q_x, q_y, poiseuille, wedge = exact_parts(xx, yy)
        f = poiseuille - wedge
        args = (hx, hy, 1.0, 1.0 / K**2, SX, SY)
        operator = np.empty_like(p)
        reynolds.apply_operator(p, q_x, q_y, eps, *args, operator)
        assert (operator[0, :] == 0.0).all() and (operator[:, 0] == 0.0).all()
        assert (operator[-1, :] == 0.0).all() and (operator[:, -1] == 0.0).all()
        out = np.empty_like(p)
        reynolds.residual(p, q_x, q_y, eps, f, *args, out)
        first, inner = upstream_lines(n)
        assert np.array_equal(out[inner | first], (f - operator)[inner | first])
        inner_errors.append(np.abs(out[inner]).max())
        first_errors.append(np.abs(out[first]).max())
        # cavitated nodes (P = 0) carry no residual: the complementarity P >= 0, residual 0 where P = 0
        cavitated = p.copy()
        cavitated[:, : n // 4] = 0.0
        reynolds.residual(cavitated, q_x, q_y, eps, f, *args, out)
        assert (out[:, : n // 4] == 0.0).all() and (out[1:-1, n // 4 : -1] != 0.0).all()
    # second order overall where the wedge has its full stencil (the Poiseuille term dominates): > 1.8
    assert all(p > 1.8 for p in orders(inner_errors)), (inner_errors, orders(inner_errors))
    # on the upstream lines the first-order wedge error mixes with the second-order Poiseuille error (1.6, then
    # 1.5 towards 1 on these grids): at least first order, > 0.8
    assert all(p > 0.8 for p in orders(first_errors)), (first_errors, orders(first_errors))
