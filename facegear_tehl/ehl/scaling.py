r"""Hertzian scaling of an elliptical EHL contact: the dimensionless variables of the solver, defined once.

Dimensional problem (steady, isothermal, Newtonian; x along the minor axis b, y along the major axis a):
    d/dx(rho h^3/(12 eta) dp/dx) + d/dy(rho h^3/(12 eta) dp/dy) = u_ex d(rho h)/dx + u_ey d(rho h)/dy
    h = h_0 + x^2/(2 R_x) + y^2/(2 R_y) + (2/(pi E')) \iint p/r ds dt,       \iint p dx dy = w

Dimensionless variables (Venner & Lubrecht 2000, stretched to the ellipse):
    X = x/b,  Y = y/a,  P = p/p_h,  H = h R_x/b^2,  rho_bar = rho/rho_0,  eta_bar = eta/eta_0
    k = a/b (ellipticity), kappa = b/a, D = R_x/R_y, U_e = |u_e| (cos psi, sin psi)

Dimensionless problem:
    d/dX(eps dP/dX) + kappa^2 d/dY(eps dP/dY) - cos(psi) d(rho_bar H)/dX - kappa sin(psi) d(rho_bar H)/dY = 0
    eps = rho_bar H^3/(eta_bar lambda),   lambda = 12 eta_0 |u_e| R_x^2/(p_h b^3)
    H = H_0 + X^2/2 + k^2 D Y^2/2 + C_d \iint P/sqrt((X-S)^2 + k^2 (Y-T)^2) dS dT,  C_d = 2 p_h a R_x/(pi E' b^2)
    \iint P dX dY = 2 pi/3
For a circle (k = D = 1): lambda = 6 eta_0 u_s R^2/(a^3 p_h) and C_d = 2/pi^2, exactly Venner & Lubrecht's form.

Groups reported with results: Moes M = W (2U)^(-3/4), L = G (2U)^(1/4) and Hamrock-Dowson U, G, W, all built on
R_x with U = eta_0 |u_e|/(E' R_x), W = w/(E' R_x^2), G = alpha E' (alpha: the low-pressure pressure-viscosity
coefficient of the chosen viscosity law).
"""

from __future__ import annotations

from dataclasses import dataclass
import math

from facegear_tehl.contact import ContactPoint
from facegear_tehl.hertz import HertzContact
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.materials import Solid, reduced_modulus


@dataclass(frozen=True)
class Scaling:
    hertz: HertzContact
    lam: float  # lambda, 12 eta_0 |u_e| R_x^2/(p_h b^3)
    deflection_coefficient: float  # C_d
    wedge_x: float  # cos(psi)
    wedge_y: float  # kappa sin(psi)
    moes_m: float
    moes_l: float
    hamrock_u: float
    hamrock_g: float
    hamrock_w: float

    @property
    def b(self) -> float:
        return self.hertz.b

    @property
    def a(self) -> float:
        return self.hertz.a

    @property
    def p_h(self) -> float:
        return self.hertz.p_max

    @property
    def ellipticity(self) -> float:
        return self.hertz.ellipticity

    @property
    def kappa(self) -> float:
        return 1.0 / self.hertz.ellipticity

    @property
    def geometry_y(self) -> float:
        """Coefficient of Y^2/2 in the gap: k^2 R_x/R_y."""
        return self.hertz.ellipticity**2 * self.hertz.radius_x / self.hertz.radius_y

    @property
    def film_scale(self) -> float:
        """h = H * b^2/R_x, m."""
        return self.hertz.b**2 / self.hertz.radius_x


def scaling_for(point: ContactPoint, lubricant: Lubricant) -> Scaling:
    """The Hertzian scaling of one contact point."""
    hertz = point.hertz
    e_prime = point.reduced_modulus
    ue = point.entrainment
    speed = point.entrainment_speed
    if speed <= 0.0:
        raise ValueError(f"contact point {point.name}: entrainment speed must be positive, got {speed}")
    r_x = point.radius_x
    b, a, p_h = hertz.b, hertz.a, hertz.p_max
    lam = 12.0 * lubricant.viscosity * speed * r_x**2 / (p_h * b**3)
    c_d = 2.0 * p_h * a * r_x / (math.pi * e_prime * b**2)
    u = lubricant.viscosity * speed / (e_prime * r_x)
    w = point.load / (e_prime * r_x**2)
    g = lubricant.effective_alpha * e_prime
    return Scaling(
        hertz=hertz,
        lam=lam,
        deflection_coefficient=c_d,
        wedge_x=float(ue[0]) / speed,
        wedge_y=(b / a) * float(ue[1]) / speed,
        moes_m=w * (2.0 * u) ** -0.75,
        moes_l=g * (2.0 * u) ** 0.25,
        hamrock_u=u,
        hamrock_g=g,
        hamrock_w=w,
    )


# Reference solids and oil of the Venner & Lubrecht (2000) benchmarks (docs/benchmarks.md): steel E = 200 GPa,
# nu = 0.3 (E' = 2.198e11 Pa), eta_0 = 0.04 Pa s, alpha = 2.2e-8 1/Pa, R_x = 12.7 mm.
_BENCH_STEEL = Solid(elastic_modulus=2.0e11, poisson_ratio=0.3)
_BENCH_RADIUS = 0.0127  # m
_BENCH_VISCOSITY = 0.04  # Pa s
_BENCH_ALPHA = 2.2e-8  # 1/Pa


def contact_from_moes(
    moes_m: float,
    moes_l: float,
    radius_ratio_d: float = 1.0,
    *,
    entrainment_angle: float = 0.0,
    slide_roll_ratio: float = 0.0,
    viscosity_model: str = "barus",
    density_model: str = "incompressible",
) -> tuple[ContactPoint, Lubricant]:
    """A physical contact with given Moes M, L and D = R_x/R_y (steel, the benchmark oil and R_x = 12.7 mm).

    Inverts L = alpha E' (2U)^(1/4) for the speed and M = W (2U)^(-3/4) for the load.
    """
    e_prime = reduced_modulus(_BENCH_STEEL, _BENCH_STEEL)
    two_u = (moes_l / (_BENCH_ALPHA * e_prime)) ** 4
    w = moes_m * two_u**0.75
    speed = 0.5 * two_u * e_prime * _BENCH_RADIUS / _BENCH_VISCOSITY
    point = ContactPoint.from_rolling_sliding(
        name="contact",
        radius_x=_BENCH_RADIUS,
        radius_y=_BENCH_RADIUS / radius_ratio_d,
        load=w * e_prime * _BENCH_RADIUS**2,
        entrainment_speed=speed,
        slide_roll_ratio=slide_roll_ratio,
        entrainment_angle_deg=entrainment_angle,
        body_1=_BENCH_STEEL,
        body_2=_BENCH_STEEL,
    )
    lubricant = Lubricant(
        viscosity=_BENCH_VISCOSITY,
        inlet_temperature=313.15,
        pressure_viscosity=_BENCH_ALPHA,
        density=870.0,
        viscosity_model=viscosity_model,
        density_model=density_model,
    )
    return point, lubricant
