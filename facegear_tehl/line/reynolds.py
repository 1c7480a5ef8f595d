r"""Finite-volume Reynolds equation of a line contact, its complementarity form and its exact Jacobian.

Steady 1-D Reynolds equation in Hertzian units (X = x/b, P = p/p_h, H = h R/b^2; `elastic.py`), written as
conservation of the mass flux per unit length, made dimensionless with rho_0 u_e b^2/R:

    Q(X) = -eps dP/dX + c,      dQ/dX = 0  where P > 0,
    eps = e(P) H^3,  c = r(P) H.

Isothermal Newtonian film (Reynolds 1886; Dowson & Higginson 1966):  e = rho_bar/(eta_bar lambda), r = rho_bar,
lambda = 12 eta_0 u_e R^2/(b^3 p_h).  The generalized (thermal, non-Newtonian) film of Yang & Wen (1990)
has the same form with e and r from integrals across the film (`film.py`).

Discretisation on any increasing node set X_0 .. X_{n-1} (P_0 = P_{n-1} = 0): control volume i is
[X_{i-1/2}, X_{i+1/2}] (face midpoints), and its net outflow is

    R_i = Q_{i+1/2} - Q_{i-1/2},
    Q_{f} = -(eps_f + eps_{f+1})/2 (P_{f+1} - P_f)/D_f + C_f,      D_f = X_{f+1} - X_f,
    C_f = c_f + (c_f - c_{f-1}) D_f/(2 D_{f-1})    (second-order upwind extrapolation to the face;
                                                    first order, C_0 = c_0, on the first face).

On a uniform grid the Couette part of R_i/D is (3 c_i - 4 c_{i-1} + c_{i-2})/(2 D), the second-order upstream
difference.  R_i is the flux balance of the cell, not divided by its width: the complementarity pairs P_i
(order 1) with a flux difference (order D), which keeps the Newton merit function ||F||^2 from being dominated
by the few cells of the inlet and the pressure spike where dQ/dX is large while the iterate is still far off
(on the 801-node grid this halved the Newton steps and removed the need for continuation).

Cavitation (Reynolds/Swift-Stieber condition as a complementarity problem; Christopherson 1941 gave the
pressure form, the Fischer (1992) function makes it a semismooth equation solved by Newton):

    P_i >= 0,  R_i >= 0,  P_i R_i = 0   <=>   phi(P_i, R_i) = P_i + R_i - sqrt(P_i^2 + R_i^2) = 0.

R_i > 0 with P_i = 0 is film rupture (more Couette flux leaves the cell than enters).  No pressure is clipped.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class FilmCoefficients:
    """Per-node coefficients of the flux: eps = e H^3, c = r H, and their derivatives in P at fixed H."""

    e: np.ndarray
    de: np.ndarray
    r: np.ndarray
    dr: np.ndarray


class ReynoldsSystem:
    """Residual and Jacobian of the discrete complementarity Reynolds problem with the load balance.

    Unknowns u = (P_1 .. P_{n-2}, H_0); equations: phi(P_i, R_i) for the interior nodes and
    (int P dX - pi/2)/(pi/2) for the load. `kernel` is the influence matrix (`elastic.influence_matrix`),
    `weights` the load quadrature (`elastic.load_weights`).
    """

    def __init__(self, nodes: np.ndarray, kernel: np.ndarray, weights: np.ndarray, second_order: bool = True):
        self.x = np.asarray(nodes, dtype=np.float64)
        self.n = self.x.size
        self.kernel = kernel
        self.weights = weights
        self.d = np.diff(self.x)  # face spacings D_f, f = 0 .. n-2
        # upwind extrapolation weight of face f: C_f = c_f + w_f (c_f - c_{f-1}); w_0 = 0 (first order)
        self.upwind = np.zeros(self.n - 1)
        if second_order:
            self.upwind[1:] = self.d[1:] / (2.0 * self.d[:-1])
        self.geometry = 0.5 * self.x**2
        self.interior = np.arange(1, self.n - 1)
        self.volume = 0.5 * (self.x[2:] - self.x[:-2])  # control-volume widths V_i, i = 1 .. n-2
        self.scale = np.ones(self.n - 2)  # row scaling of the balances (set_row_scale)

    # --- state -----------------------------------------------------------------------------------------
    def pressure(self, u: np.ndarray) -> np.ndarray:
        """Nodal P (zeros at both ends) from the unknowns."""
        p = np.zeros(self.n)
        p[1:-1] = u[:-1]
        return p

    def film(self, p: np.ndarray, h0: float) -> np.ndarray:
        """H = H_0 + X^2/2 + K P."""
        return h0 + self.geometry + self.kernel @ p

    # --- fluxes ----------------------------------------------------------------------------------------
    def face_fluxes(self, p: np.ndarray, h: np.ndarray, coef: FilmCoefficients) -> tuple[np.ndarray, np.ndarray]:
        """(Poiseuille part, Couette part) of Q at the n-1 faces."""
        eps = coef.e * h**3
        c = coef.r * h
        grad = np.diff(p) / self.d
        poiseuille = -0.5 * (eps[:-1] + eps[1:]) * grad
        couette = c[:-1].copy()
        couette[1:] += self.upwind[1:] * (c[1:-1] - c[:-2])
        return poiseuille, couette

    def flux_residual(self, p: np.ndarray, h: np.ndarray, coef: FilmCoefficients) -> np.ndarray:
        """R_i = Q_{i+1/2} - Q_{i-1/2} at the interior nodes."""
        poiseuille, couette = self.face_fluxes(p, h, coef)
        q = poiseuille + couette
        return np.diff(q)

    def set_row_scale(self, u: np.ndarray, coef: FilmCoefficients) -> None:
        """Fix s_i = 1 + eps_i/V_i at the state u (a constant diagonal scaling of the balances for one Newton
        solve): R_i/s_i is of the order of a pressure change both where Couette flow dominates (s ~ 1) and
        where Poiseuille flow does (R_i ~ eps dP/V, up to 1e14 in a rigid-isoviscous inlet). It is frozen
        because a scale that followed eps(H) would make any film H -> infinity look like a solution."""
        h = self.film(self.pressure(u), u[-1])
        self.scale = 1.0 + coef.e[1:-1] * h[1:-1] ** 3 / self.volume

    def residual(self, u: np.ndarray, coef: FilmCoefficients) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(F, R/s, H): the complementarity residual with the load row, the scaled flux balance and the film."""
        p = self.pressure(u)
        h = self.film(p, u[-1])
        r = self.flux_residual(p, h, coef) / self.scale
        a = u[:-1]
        f = np.empty(u.size)
        f[:-1] = a + r - np.hypot(a, r)
        f[-1] = (self.weights @ p - 0.5 * np.pi) / (0.5 * np.pi)
        return f, r, h

    def jacobian(self, u: np.ndarray, coef: FilmCoefficients, r: np.ndarray, h: np.ndarray) -> np.ndarray:
        """dF/du (dense, (n-1) x (n-1)), exact for the discretisation at fixed e(P), r(P) laws."""
        n = self.n
        m = u.size  # n - 2 pressures + H_0
        p = self.pressure(u)
        # dH/du: columns of K for the interior pressures, ones for H_0
        dh = np.empty((n, m))
        dh[:, :-1] = self.kernel[:, 1:-1]
        dh[:, -1] = 1.0
        # d eps/du and d c/du (local P-dependence on the diagonal of the pressure columns)
        deps = (3.0 * coef.e * h**2)[:, None] * dh
        dc = coef.r[:, None] * dh
        deps[self.interior, self.interior - 1] += coef.de[1:-1] * h[1:-1] ** 3
        dc[self.interior, self.interior - 1] += coef.dr[1:-1] * h[1:-1]
        eps = coef.e * h**3
        grad = np.diff(p) / self.d
        # face Poiseuille flux: -(eps_f + eps_f+1)/2 grad_f
        dq = -0.5 * grad[:, None] * (deps[:-1] + deps[1:])
        eps_face = 0.5 * (eps[:-1] + eps[1:]) / self.d
        # direct dependence on P_f+1 - P_f (interior pressure columns only)
        f_idx = np.arange(n - 1)
        right = f_idx + 1  # node f+1
        left = f_idx
        mask_r = (right >= 1) & (right <= n - 2)
        mask_l = (left >= 1) & (left <= n - 2)
        dq[f_idx[mask_r], right[mask_r] - 1] -= eps_face[mask_r]
        dq[f_idx[mask_l], left[mask_l] - 1] += eps_face[mask_l]
        # face Couette flux
        dq += dc[:-1]
        dq[1:] += self.upwind[1:, None] * (dc[1:-1] - dc[:-2])
        dr = (dq[1:] - dq[:-1]) / self.scale[:, None]
        # complementarity
        a = u[:-1]
        rho = np.hypot(a, r)
        safe = np.where(rho > 0.0, rho, 1.0)
        da = np.where(rho > 0.0, 1.0 - a / safe, 1.0 - np.sqrt(0.5))
        db = np.where(rho > 0.0, 1.0 - r / safe, 1.0 - np.sqrt(0.5))
        jac = np.empty((m, m))
        jac[:-1] = db[:, None] * dr
        jac[np.arange(m - 1), np.arange(m - 1)] += da
        jac[-1, :-1] = self.weights[1:-1] / (0.5 * np.pi)
        jac[-1, -1] = 0.0
        return jac
