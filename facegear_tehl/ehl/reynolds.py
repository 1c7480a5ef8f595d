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


@njit(cache=True, inline="always")
def _wedge(qx, qy, j, i, sx, sy, rhx, rhy):
    """Upwind divergence of the Couette mass flux: sx d(qx)/dX + sy d(qy)/dY (qx, qy signed by sx, sy)."""
    ny, nx = qx.shape
    w = 0.0
    if sx != 0:
        cp, c0, c1, c2 = _upwind(i, sx, nx)
        wx = c0 * qx[j, i] + c1 * qx[j, i - sx]
        if cp != 0.0:
            wx += cp * qx[j, i + sx]
        if c2 != 0.0:
            wx += c2 * qx[j, i - 2 * sx]
        w += rhx * wx
    if sy != 0:
        cp, c0, c1, c2 = _upwind(j, sy, ny)
        wy = c0 * qy[j, i] + c1 * qy[j - sy, i]
        if cp != 0.0:
            wy += cp * qy[j + sy, i]
        if c2 != 0.0:
            wy += c2 * qy[j - 2 * sy, i]
        w += rhy * wy
    return w


@njit(cache=True, inline="always")
def _poiseuille(p, j, i, xe, xw, xn, xs, xsum):
    """The Poiseuille part of L(P) at node (j, i) from its coefficients (`_coefficients`; xsum their sum)."""
    return xe * p[j, i + 1] + xw * p[j, i - 1] + xn * p[j + 1, i] + xs * p[j - 1, i] - xsum * p[j, i]


@njit(cache=True, inline="always")
def _operator(p, qx, qy, eps, j, i, rhx, rhy, rhx2, rhy2k, sx, sy):
    xe, xw, xn, xs = _coefficients(eps, j, i, rhx2, rhy2k)
    return _poiseuille(p, j, i, xe, xw, xn, xs, xe + xw + xn + xs) - _wedge(qx, qy, j, i, sx, sy, rhx, rhy)


@njit(cache=True)
def apply_operator(p, qx, qy, eps, hx, hy, px, py, sx, sy, out):
    """out = L(P) at interior nodes (0 on the boundary); px, py: factors of the x and y Poiseuille terms
    (1 and kappa^2 in the ellipse frame)."""
    ny, nx = p.shape
    rhx, rhy = 1.0 / hx, 1.0 / hy
    rhx2, rhy2k = px * rhx * rhx, py * rhy * rhy
    out[:, :] = 0.0
    for j in range(1, ny - 1):
        for i in range(1, nx - 1):
            out[j, i] = _operator(p, qx, qy, eps, j, i, rhx, rhy, rhx2, rhy2k, sx, sy)


@njit(cache=True)
def residual(p, qx, qy, eps, f, hx, hy, px, py, sx, sy, out):
    """out = f - L(P) at interior nodes where P > 0 (cavitated nodes satisfy the complementarity), else 0."""
    ny, nx = p.shape
    rhx, rhy = 1.0 / hx, 1.0 / hy
    rhx2, rhy2k = px * rhx * rhx, py * rhy * rhy
    out[:, :] = 0.0
    for j in range(1, ny - 1):
        for i in range(1, nx - 1):
            if p[j, i] > 0.0:
                out[j, i] = f[j, i] - _operator(p, qx, qy, eps, j, i, rhx, rhy, rhx2, rhy2k, sx, sy)


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
def _solve_band(a, rhs, x, n, ml, mu):
    """Solve a banded system in place by Gaussian elimination with partial pivoting.

    Row r holds A[r, c] at a[r, c - r + ml] for c - r in [-ml, mu + ml] (the upper band is widened by ml
    for the fill-in of row interchanges).
    """
    width = 2 * ml + mu + 1
    for i in range(n):
        # pivot among rows i..i+ml in column i
        piv = i
        best = abs(a[i, ml])
        for r in range(i + 1, min(i + ml + 1, n)):
            v = abs(a[r, i - r + ml])
            if v > best:
                best = v
                piv = r
        if piv != i:
            for c in range(i, min(i + ml + mu + 1, n)):
                ci = c - i + ml
                cp = c - piv + ml
                t = a[i, ci]
                a[i, ci] = a[piv, cp]
                a[piv, cp] = t
            t = rhs[i]
            rhs[i] = rhs[piv]
            rhs[piv] = t
        d = a[i, ml]
        if d == 0.0:
            d = 1e-300
            a[i, ml] = d
        for r in range(i + 1, min(i + ml + 1, n)):
            factor = a[r, i - r + ml] / d
            if factor != 0.0:
                for c in range(i, min(i + ml + mu + 1, n)):
                    cr = c - r + ml
                    if cr < width:
                        a[r, cr] -= factor * a[i, c - i + ml]
                rhs[r] -= factor * rhs[i]
    for i in range(n - 1, -1, -1):
        s = rhs[i]
        for c in range(i + 1, min(i + ml + mu + 1, n)):
            s -= a[i, c - i + ml] * x[c]
        x[i] = s / a[i, ml]


@njit(cache=True)
def relax_lines(p, qx, qy, fx, fy, eps, f, hx, hy, px, py, sx, sy, e_gs, e_jd, wx, wy, xi_switch, ur_gs, ur_jd):
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
            rhs[r] = f[j, i] - (poiseuille - _wedge(qx, qy, j, i, sx, sy, rhx, rhy))
            # Does the node couple to its line neighbours? (not across a cavitation boundary)
            coupled = pj[j, i] > 0.0
            for m in range(-2, 3):
                ii = i + m
                if ii >= 0 and ii <= nx - 1 and pj[j, ii] <= 0.0 and m != 0 and ii >= 1 and ii <= nx - 2:
                    coupled = False
            cxp, cx0, cx1, cx2 = _upwind(i, sx, nx)
            cyp, cy0, cy1, cy2 = _upwind(j, sy, ny)
            for m in range(-ml, mu + 1):
                k = i + m
                if k < 1 or k > nx - 2:
                    continue
                if m != 0 and not coupled:
                    continue
                q = 0 if gs[j, k] else 1  # the pattern of column k: patterns[q] (an index, not an array)
                # elastic part: -d(wedge)/d(delta_k)
                el = 0.0
                if sx != 0:
                    if cxp != 0.0:
                        el += cxp * fx[j, i + sx] * patterns[q, 0, i + sx - k + reach]
                    el += cx0 * fx[j, i] * patterns[q, 0, i - k + reach]
                    el += cx1 * fx[j, i - sx] * patterns[q, 0, i - sx - k + reach]
                    if cx2 != 0.0:
                        el += cx2 * fx[j, i - 2 * sx] * patterns[q, 0, i - 2 * sx - k + reach]
                    el *= rhx
                if sy != 0:
                    ey = (cy0 * fy[j, i] * patterns[q, 0, i - k + reach]
                          + cy1 * fy[j - sy, i] * patterns[q, 1, i - k + reach])
                    if cyp != 0.0:
                        ey += cyp * fy[j + sy, i] * patterns[q, 1, i - k + reach]
                    if cy2 != 0.0:
                        ey += cy2 * fy[j - 2 * sy, i] * patterns[q, 2, i - k + reach]
                    el += rhy * ey
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
        _solve_band(a, rhs, x, n, ml, mu)
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
