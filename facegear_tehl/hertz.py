"""Exact elliptical Hertz contact and the relative curvature of two bodies.

Notation (Hamrock & Dowson 1977; Johnson, *Contact Mechanics*, 1985, ch. 4):
reduced radii R_x <= R_y, curvature sum 1/R = 1/R_x + 1/R_y, radius ratio alpha_r = R_y/R_x >= 1,
ellipticity k = a/b >= 1 (a: major semi-axis along y, b: minor semi-axis along x),
elliptic parameter m = e^2 = 1 - 1/k^2, K(m) and E(m) the complete elliptic integrals.

    alpha_r = (k^2 E - K) / (K - E)                     (ellipticity equation, solved for k)
    a = (6 k^2 E W R / (pi E'))^(1/3),  b = (6 E W R / (pi k E'))^(1/3)
    p_max = 3 W / (2 pi a b),  delta = K [9/(2 E R) (W/(pi k E'))^2]^(1/3)

K and E by the arithmetic-geometric mean of 1 and sqrt(1 - m) = 1/k (Abramowitz & Stegun 1964, 17.6.1-17.6.4:
K = pi/(2 AGM), E = K (1 - sum_n 2^(n-1) c_n^2), c_0^2 = m), which keeps full precision for radius ratios up to
several thousand (k of a few hundred): within 3e-15 of SciPy's ellipkm1/ellipe for k = 1..3000. (Not SciPy's:
scipy.special costs reading a case about 0.15 s of imports.)
"""

from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from facegear_tehl.roots import brentq


@dataclass(frozen=True)
class HertzContact:
    """Dry Hertz contact of an elliptical point contact (SI units)."""

    a: float  # m, major semi-axis (along y)
    b: float  # m, minor semi-axis (along x)
    p_max: float  # Pa, maximum (central) pressure
    approach: float  # m, mutual approach of distant points
    ellipticity: float  # k = a/b
    elliptic_k: float  # complete elliptic integral of the first kind K(m)
    elliptic_e: float  # complete elliptic integral of the second kind E(m)
    radius_x: float  # m
    radius_y: float  # m
    load: float  # N
    reduced_modulus: float  # Pa, E'

    @property
    def p_mean(self) -> float:
        """Mean pressure W/(pi a b) = 2/3 p_max, Pa."""
        return 2.0 * self.p_max / 3.0

    @property
    def area(self) -> float:
        """Contact area pi a b, m^2."""
        return math.pi * self.a * self.b


AGM_TOLERANCE = 2.3e-16  # relative |a_n - b_n|/2 at which the AGM has converged: about one ulp (quadratic
# convergence: 4-6 steps for the face gear's k = 50-60)
AGM_MAX_STEPS = 40  # far beyond the 6 steps k = 3000 takes


def _elliptic_integrals(k: float) -> tuple[float, float]:
    """K(m), E(m) for ellipticity k >= 1, m = 1 - 1/k^2 (AGM; Abramowitz & Stegun 1964, 17.6.1-17.6.4)."""
    p = 1.0 / (k * k)  # 1 - m
    a, b = 1.0, math.sqrt(p)
    total, power = 0.5 * (1.0 - p), 0.5  # sum of 2^(n-1) c_n^2 from c_0^2 = m
    for _ in range(AGM_MAX_STEPS):
        c = 0.5 * (a - b)
        if c <= AGM_TOLERANCE * a:
            break
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        power *= 2.0
        total += power * c * c
    elliptic_k = math.pi / (2.0 * a)
    return elliptic_k, elliptic_k * (1.0 - total)


def _radius_ratio_of(k: float) -> float:
    """alpha_r(k) = (k^2 E - K)/(K - E); tends to 1 as k -> 1."""
    kk, ee = _elliptic_integrals(k)
    return (k * k * ee - kk) / (kk - ee)


def ellipticity(radius_ratio: float) -> tuple[float, float, float]:
    """Solve the ellipticity equation for k = a/b given alpha_r = R_y/R_x >= 1.

    Returns (k, K, E). Exact to machine precision (root of the elliptic-integral equation).
    """
    if not np.isfinite(radius_ratio) or radius_ratio < 1.0:
        raise ValueError(f"radius ratio R_y/R_x must be >= 1, got {radius_ratio}")
    if radius_ratio - 1.0 < 1e-12:
        return 1.0, math.pi / 2.0, math.pi / 2.0
    # Near k = 1 the formula is 0/0; alpha_r - 1 ~ (3/2)(k^2 - 1) for small e (Johnson 1985, §4.2),
    # so bracket in log k from just above 1 up to a generous upper bound (k ~ alpha_r^(2/3) asymptotically).
    def f(log_k: float) -> float:
        return math.log(_radius_ratio_of(math.exp(log_k))) - math.log(radius_ratio)

    lo = 1e-7
    hi = max(1.0, math.log(2.0 * radius_ratio))
    log_k = brentq(f, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
    k = math.exp(log_k)
    kk, ee = _elliptic_integrals(k)
    return k, kk, ee


def hertz_contact(radius_x: float, radius_y: float, load: float, reduced_modulus: float) -> HertzContact:
    """Exact Hertz solution for an elliptical contact with reduced radii R_x <= R_y (m), load W (N), E' (Pa)."""
    if radius_y < radius_x:
        raise ValueError(f"radius_y ({radius_y}) must be >= radius_x ({radius_x})")
    k, kk, ee = ellipticity(radius_y / radius_x)
    r_sum = 1.0 / (1.0 / radius_x + 1.0 / radius_y)
    a = (6.0 * k * k * ee * load * r_sum / (math.pi * reduced_modulus)) ** (1.0 / 3.0)
    b = (6.0 * ee * load * r_sum / (math.pi * k * reduced_modulus)) ** (1.0 / 3.0)
    p_max = 3.0 * load / (2.0 * math.pi * a * b)
    approach = kk * (9.0 / (2.0 * ee * r_sum) * (load / (math.pi * k * reduced_modulus)) ** 2) ** (1.0 / 3.0)
    return HertzContact(
        a=a,
        b=b,
        p_max=p_max,
        approach=approach,
        ellipticity=k,
        elliptic_k=kk,
        elliptic_e=ee,
        radius_x=radius_x,
        radius_y=radius_y,
        load=load,
        reduced_modulus=reduced_modulus,
    )


@dataclass(frozen=True)
class RelativeCurvature:
    """Relative curvature of two bodies: gap h = A x'^2 + B y'^2 in the principal frame (B >= A).

    radius_x = 1/(2B) (minor-axis direction x'), radius_y = 1/(2A) (major-axis direction y').
    angle: angle (rad) from body 1's first principal direction to the x' axis (direction of B).
    """

    A: float  # 1/m
    B: float  # 1/m
    angle: float  # rad

    @property
    def radius_x(self) -> float:
        return 1.0 / (2.0 * self.B)

    @property
    def radius_y(self) -> float:
        return math.inf if self.A <= 0.0 else 1.0 / (2.0 * self.A)


def relative_curvature(
    kappa1_1: float, kappa1_2: float, kappa2_1: float, kappa2_2: float, alpha: float
) -> RelativeCurvature:
    """Relative curvature of two bodies whose principal planes are at an angle alpha (rad).

    kappa1_1, kappa1_2: principal curvatures of body 1 (1/m, convex positive);
    kappa2_1, kappa2_2: of body 2; alpha: angle between the planes of kappa1_1 and kappa2_1.
    Johnson (1985) §4.1:
        A + B = (k1' + k1'' + k2' + k2'')/2
        B - A = 1/2 sqrt((k1'-k1'')^2 + (k2'-k2'')^2 + 2 (k1'-k1'')(k2'-k2'') cos 2 alpha)
    The angle of the principal frame follows from the half-eigenvectors of K1 + Rot(alpha) K2 Rot(alpha)^T.
    """
    d1 = kappa1_1 - kappa1_2
    d2 = kappa2_1 - kappa2_2
    s = 0.5 * (kappa1_1 + kappa1_2 + kappa2_1 + kappa2_2)
    diff = 0.5 * math.sqrt(max(d1 * d1 + d2 * d2 + 2.0 * d1 * d2 * math.cos(2.0 * alpha), 0.0))
    a_coef = 0.5 * (s - diff)
    b_coef = 0.5 * (s + diff)
    # Orientation of the larger curvature B: the summed tensor's off-diagonal angle (Mohr's circle).
    angle = 0.5 * math.atan2(d2 * math.sin(2.0 * alpha), d1 + d2 * math.cos(2.0 * alpha))
    return RelativeCurvature(A=a_coef, B=b_coef, angle=angle)
