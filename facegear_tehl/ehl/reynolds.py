"""Discrete Reynolds operator and its line relaxation (Numba kernels).

Discretisation on a uniform (ny, nx) grid (arrays indexed [j, i], i along X), see `scaling.py`:
    L(P)_ij = xi_e (P_i+1 - P_i) - xi_w (P_i - P_i-1) + xi_n (P_j+1 - P_j) - xi_s (P_j - P_j-1)
              - s_x D_x(q_x) - s_y D_y(q_y),      q_x = f_x H, q_y = f_y H
    xi_e = (eps_i + eps_i+1)/(2 h_x^2),  xi_n = kappa^2 (eps_j + eps_j+1)/(2 h_y^2)  (and w, s alike)
    D(q) = (2 q_+1 + 3 q_0 - 6 q_-1 + q_-2)/(6 h), the third-order upwind-biased difference oriented by the
    entrainment component on that axis (second-order upstream, then first order, next to the boundary).
The wedge term thus follows the entrainment direction in both axes (skewed entrainment). f_x, f_y are the
Couette mass-flux factors (rho_bar cos(psi) and rho_bar kappa sin(psi) for an isothermal Newtonian film;
see `flow.py` for the general form) signed by s_x, s_y so that the upwind difference acts on s q.

Relaxation (Venner & Lubrecht 2000, ch. 8): lines of constant Y are solved together with a banded
approximation of the Jacobian, including the elastic coupling through the influence coefficients.
Where xi = eps/h^2 is large (inlet, outlet) the line is relaxed Gauss-Seidel; where it is small (the
Hertzian region, where the equation is an integral equation of the first kind) the changes are distributed
Jacobi-wise, delta_ij - w_x (delta_i-1 + delta_i+1) - w_y (delta_j-1 + delta_j+1), with the weights of a
physical Laplacian (w_x : w_y = 1/h_x^2 : 1/(k h_y)^2, 2 w_x + 2 w_y = 1): for a circle this is Venner's
1/4 pattern; for a long ellipse (k >> 1) it tends to the line-contact pattern 1/2 along X.
"""

from __future__ import annotations

from numba import njit
import numpy as np

BAND = 3  # half-width of the banded line Jacobian (columns i-3 .. i+3)
PATTERN_REACH = 2 * BAND  # |d| range of the pattern-effect kernels (wedge reaches i - 2 and band 3, +1 spread)


@njit(cache=True, inline="always")
def _upwind(i: int, s: int, n: int):
    """Coefficients (c_+1, c_0, c_-1, c_-2) of q_i+s, q_i, q_i-s, q_i-2s in the upwind difference (times 1/h).

    Third-order upwind-biased (2, 3, -6, 1)/6 where the stencil fits, else second-order upstream
    (0, 1.5, -2, 0.5), else first order (0, 1, -1, 0); s = 0: no entrainment on this axis.
    """
    if s == 0:
        return 0.0, 0.0, 0.0, 0.0
    has_next = i + s >= 0 and i + s <= n - 1
    has_second = i - 2 * s >= 0 and i - 2 * s <= n - 1
    if has_next and has_second:
        return 1.0 / 3.0, 0.5, -1.0, 1.0 / 6.0
    if has_second:
        return 0.0, 1.5, -2.0, 0.5
    return 0.0, 1.0, -1.0, 0.0


@njit(cache=True, inline="always")
def _coefficients(eps, j, i, rhx2, rhy2k):
    e0 = eps[j, i]
    xe = 0.5 * (eps[j, i + 1] + e0) * rhx2
    xw = 0.5 * (eps[j, i - 1] + e0) * rhx2
    xn = 0.5 * (eps[j + 1, i] + e0) * rhy2k
    xs = 0.5 * (eps[j - 1, i] + e0) * rhy2k
    return xe, xw, xn, xs


@njit(cache=True)
def upwind_table(s: int, n: int) -> np.ndarray:
    """`_upwind` of every index 0..n-1 of an axis (rows (c_+1, c_0, c_-1, c_-2)), taken once per sweep."""
    table = np.zeros((n, 4))
    for i in range(n):
        table[i, 0], table[i, 1], table[i, 2], table[i, 3] = _upwind(i, s, n)
    return table


@njit(cache=True, inline="always")
def _clamp(i: int, n: int) -> int:
    return min(max(i, 0), n - 1)


@njit(cache=True, inline="always")
def _wedge(qx, qy, j, i, sx, sy, rhx, rhy, tx, ty):
    """Upwind divergence of the Couette mass flux: sx d(qx)/dX + sy d(qy)/dY (qx, qy signed by sx, sy), with the
    coefficients of `upwind_table` (tx along X, ty along Y). A term whose coefficient is zero is read at a clamped
    index and selected away (a branch per term here made the residual 5x slower)."""
    ny, nx = qx.shape
    cp, c0, c1, c2 = tx[i, 0], tx[i, 1], tx[i, 2], tx[i, 3]
    wx = c0 * qx[j, i] + c1 * qx[j, _clamp(i - sx, nx)]
    wx += cp * qx[j, _clamp(i + sx, nx)] if cp != 0.0 else 0.0
    wx += c2 * qx[j, _clamp(i - 2 * sx, nx)] if c2 != 0.0 else 0.0
    cp, c0, c1, c2 = ty[j, 0], ty[j, 1], ty[j, 2], ty[j, 3]
    wy = c0 * qy[j, i] + c1 * qy[_clamp(j - sy, ny), i]
    wy += cp * qy[_clamp(j + sy, ny), i] if cp != 0.0 else 0.0
    wy += c2 * qy[_clamp(j - 2 * sy, ny), i] if c2 != 0.0 else 0.0
    return rhx * wx + rhy * wy


@njit(cache=True, inline="always")
def _poiseuille(p, j, i, xe, xw, xn, xs, xsum):
    """The Poiseuille part of L(P) at node (j, i) from its coefficients (`_coefficients`; xsum their sum)."""
    return xe * p[j, i + 1] + xw * p[j, i - 1] + xn * p[j + 1, i] + xs * p[j - 1, i] - xsum * p[j, i]


@njit(cache=True, inline="always")
def _operator(p, qx, qy, eps, j, i, rhx, rhy, rhx2, rhy2k, sx, sy, tx, ty):
    xe, xw, xn, xs = _coefficients(eps, j, i, rhx2, rhy2k)
    return _poiseuille(p, j, i, xe, xw, xn, xs, xe + xw + xn + xs) - _wedge(qx, qy, j, i, sx, sy, rhx, rhy, tx, ty)


@njit(cache=True)
def apply_operator(p, qx, qy, eps, hx, hy, px, py, sx, sy, out):
    """out = L(P) at interior nodes (0 on the boundary); px, py: factors of the x and y Poiseuille terms
    (1 and kappa^2 in the ellipse frame)."""
    ny, nx = p.shape
    rhx, rhy = 1.0 / hx, 1.0 / hy
    rhx2, rhy2k = px * rhx * rhx, py * rhy * rhy
    tx, ty = upwind_table(sx, nx), upwind_table(sy, ny)
    out[:, :] = 0.0
    for j in range(1, ny - 1):
        for i in range(1, nx - 1):
            out[j, i] = _operator(p, qx, qy, eps, j, i, rhx, rhy, rhx2, rhy2k, sx, sy, tx, ty)


@njit(cache=True)
def residual(p, qx, qy, eps, f, hx, hy, px, py, sx, sy, out):
    """out = f - L(P) at interior nodes where P > 0 (cavitated nodes satisfy the complementarity), else 0."""
    ny, nx = p.shape
    rhx, rhy = 1.0 / hx, 1.0 / hy
    rhx2, rhy2k = px * rhx * rhx, py * rhy * rhy
    tx, ty = upwind_table(sx, nx), upwind_table(sy, ny)
    out[:, :] = 0.0
    for j in range(1, ny - 1):
        for i in range(1, nx - 1):
            if p[j, i] > 0.0:
                out[j, i] = f[j, i] - _operator(p, qx, qy, eps, j, i, rhx, rhy, rhx2, rhy2k, sx, sy, tx, ty)


def pattern_kernels(k: np.ndarray, deflection_coefficient: float, wx: float, wy: float):
    """Effect on H of a unit change at a node, by row offset e = 0..2 and column offset d = -6..6.

    Returns (E_gs, E_jd), each shape (3, 2*PATTERN_REACH + 1): E_gs for a point change (C_d K), E_jd for the
    distributed change delta - w_x (delta_i-1 + delta_i+1) - w_y (delta_j-1 + delta_j+1).
    k: influence coefficients K[d_j, d_i] (shape (ny, nx), at least 4 x (PATTERN_REACH + 2)).
    """
    reach = PATTERN_REACH

    def kk(dj: int, di: int) -> float:
        return k[abs(dj), abs(di)]

    e_gs = np.zeros((3, 2 * reach + 1))
    e_jd = np.zeros((3, 2 * reach + 1))
    for e in range(3):
        for d in range(-reach, reach + 1):
            e_gs[e, d + reach] = kk(e, d)
            e_jd[e, d + reach] = kk(e, d) - wx * (kk(e, d - 1) + kk(e, d + 1)) - wy * (kk(e - 1, d) + kk(e + 1, d))
    return deflection_coefficient * e_gs, deflection_coefficient * e_jd


@njit(cache=True)
def _solve_band(a, rhs, x, n):
    """Solve a banded system of n rows in place by Gaussian elimination with partial pivoting.

    Row r holds A[r, c] at a[r, c - r + BAND] for c - r in [-BAND, 2 BAND] (the upper band of half-width BAND is
    widened by BAND for the fill-in of row interchanges). The loops run over the whole band of a row, whose entries
    beyond the last column are zero (the same numbers as loops cut at n, 0.3 ms less per sweep on 513 x 65).
    """
    lo = BAND
    span = 3 * BAND + 1
    for i in range(n):
        # pivot among rows i..i+BAND in column i
        piv = i
        best = abs(a[i, lo])
        last = min(i + lo, n - 1)
        for r in range(i + 1, last + 1):
            v = abs(a[r, i - r + lo])
            if v > best:
                best = v
                piv = r
        if piv != i:
            shift = piv - i
            for ci in range(lo, span):
                t = a[i, ci]
                a[i, ci] = a[piv, ci - shift]
                a[piv, ci - shift] = t
            t = rhs[i]
            rhs[i] = rhs[piv]
            rhs[piv] = t
        d = a[i, lo]
        if d == 0.0:
            d = 1e-300
            a[i, lo] = d
        for r in range(i + 1, last + 1):
            shift = r - i
            factor = a[r, lo - shift] / d
            if factor != 0.0:
                for ci in range(lo, span):
                    a[r, ci - shift] -= factor * a[i, ci]
                rhs[r] -= factor * rhs[i]
    for i in range(n - 1, -1, -1):
        s = rhs[i]
        for c in range(i + 1, min(i + 2 * BAND + 1, n)):
            s -= a[i, c - i + lo] * x[c]
        x[i] = s / a[i, lo]


# A Numba kernel (exempt from the complexity limit): its branches are the discretisation's cases, inline for speed.
@njit(cache=True)
def relax_lines(p, qx, qy, fx, fy, eps, f, hx, hy, px, py, sx, sy, e_gs, e_jd, wx, wy, xi_switch, ur_gs, ur_jd):  # noqa: C901
    """One sweep of line relaxation over lines of constant Y (in place on p); returns the L1 norm of changes.

    H (through qx = fx H, qy = fy H), the Couette factors fx, fy and eps are frozen during the sweep
    (recomputed by the caller afterwards); dq/dP is approximated by f dH/dP.
    Gauss-Seidel nodes see the already updated neighbours; Jacobi-distributive nodes see the pressures at
    the start of the sweep.
    """
    ny, nx = p.shape
    rhx, rhy = 1.0 / hx, 1.0 / hy
    rhx2, rhy2k = px * rhx * rhx, py * rhy * rhy
    ml = BAND
    mu = BAND
    reach = PATTERN_REACH
    n = nx - 2
    a = np.zeros((n, 2 * ml + mu + 1))
    rhs = np.zeros(n)
    x = np.zeros(n)
    pj = p.copy()
    patterns = np.stack((e_gs, e_jd))
    tx, ty = upwind_table(sx, nx), upwind_table(sy, ny)
    gs = np.zeros((ny, nx), dtype=np.bool_)
    for j in range(1, ny - 1):
        for i in range(1, nx - 1):
            xe, xw, xn, xs = _coefficients(eps, j, i, rhx2, rhy2k)
            gs[j, i] = max(max(xe, xw), max(xn, xs)) > xi_switch
    change = 0.0
    for j in range(1, ny - 1):
        a[:, :] = 0.0
        for i in range(1, nx - 1):
            r = i - 1
            xe, xw, xn, xs = _coefficients(eps, j, i, rhx2, rhy2k)
            xsum = xe + xw + xn + xs
            # (one call per array: choosing an array, `src = pj if ... else p`, costs Numba a reference count per
            # node, and with the pattern below made the sweep 1.8x slower)
            if gs[j, i]:
                poiseuille = _poiseuille(pj, j, i, xe, xw, xn, xs, xsum)
            else:
                poiseuille = _poiseuille(p, j, i, xe, xw, xn, xs, xsum)
            rhs[r] = f[j, i] - (poiseuille - _wedge(qx, qy, j, i, sx, sy, rhx, rhy, tx, ty))
            # Does the node couple to its line neighbours? (not across a cavitation boundary)
            coupled = pj[j, i] > 0.0
            for m in range(-2, 3):
                ii = i + m
                if ii >= 0 and ii <= nx - 1 and pj[j, ii] <= 0.0 and m != 0 and ii >= 1 and ii <= nx - 2:
                    coupled = False
            # The wedge's coefficients times the Couette factors of the nodes they read (zero where the upwind
            # difference has no such term, read at a clamped index).
            ax_p = tx[i, 0] * fx[j, _clamp(i + sx, nx)]
            ax_0 = tx[i, 1] * fx[j, i]
            ax_1 = tx[i, 2] * fx[j, _clamp(i - sx, nx)]
            ax_2 = tx[i, 3] * fx[j, _clamp(i - 2 * sx, nx)]
            ay_p = ty[j, 0] * fy[_clamp(j + sy, ny), i]
            ay_0 = ty[j, 1] * fy[j, i]
            ay_1 = ty[j, 2] * fy[_clamp(j - sy, ny), i]
            ay_2 = ty[j, 3] * fy[_clamp(j - 2 * sy, ny), i]
            for m in range(-ml, mu + 1):
                k = i + m
                if k < 1 or k > nx - 2 or (m != 0 and not coupled):
                    continue
                q = 0 if gs[j, k] else 1  # the pattern of column k: patterns[q] (an index, not an array)
                d = reach - m  # patterns[q, e, d + o]: the effect on H at offset o from node i of column k
                # elastic part: -d(wedge)/d(delta_k)
                el = (ax_p * patterns[q, 0, d + sx] + ax_0 * patterns[q, 0, d] + ax_1 * patterns[q, 0, d - sx]
                      + ax_2 * patterns[q, 0, d - 2 * sx]) * rhx
                el += rhy * (ay_0 * patterns[q, 0, d] + ay_1 * patterns[q, 1, d] + ay_p * patterns[q, 1, d]
                             + ay_2 * patterns[q, 2, d])
                # Poiseuille part, for the pattern of column k
                po = 0.0
                if gs[j, k]:
                    if m == 0:
                        po = -xsum
                    elif m == 1:
                        po = xe
                    elif m == -1:
                        po = xw
                else:
                    if m == 0:
                        po = -xsum - wx * (xe + xw) - wy * (xn + xs)
                    elif m == 1:
                        po = xe + wx * xsum
                    elif m == -1:
                        po = xw + wx * xsum
                    elif m == 2:
                        po = -wx * xe
                    elif m == -2:
                        po = -wx * xw
                a[r, m + ml] = po - el
        _solve_band(a, rhs, x, n)
        for i in range(1, nx - 1):
            delta = x[i - 1]
            old = pj[j, i]
            if gs[j, i]:
                new = old + ur_gs * delta
                if new < 0.0:
                    new = 0.0
                pj[j, i] = new
                change += abs(new - old)
            else:
                new = old + ur_jd * delta
                if new < 0.0:
                    new = 0.0
                pj[j, i] = new
                d0 = new - old
                change += abs(d0)
                if (new > 0.0 and pj[j, i - 1] > 0.0 and pj[j, i + 1] > 0.0 and pj[j - 1, i] > 0.0
                        and pj[j + 1, i] > 0.0):
                    if i > 1:
                        pj[j, i - 1] = max(pj[j, i - 1] - wx * d0, 0.0)
                    if i < nx - 2:
                        pj[j, i + 1] = max(pj[j, i + 1] - wx * d0, 0.0)
                    if j > 1:
                        pj[j - 1, i] = max(pj[j - 1, i] - wy * d0, 0.0)
                    if j < ny - 2:
                        pj[j + 1, i] = max(pj[j + 1, i] - wy * d0, 0.0)
    p[:, :] = pj
    return change
