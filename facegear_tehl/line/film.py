r"""Flow coefficients of the line-contact film: isothermal Newtonian, and the generalized film across z.

Isothermal Newtonian (Reynolds 1886): q = -rho h^3/(12 eta) dp/dx + rho u_e h, i.e. in Hertzian units
(`reynolds.py`)  e = rho_bar/(eta_bar lambda),  r = rho_bar,  lambda = 12 eta_0 u_e R^2/(b^3 p_h).

The lubricant laws (viscosity eta(p, T), density rho(p, T)) are the project's `facegear_tehl.lubricant`.
Their pressure derivatives, needed by the Newton Jacobian, are central differences with the step
PRESSURE_STEP (relative to p_h).
"""

from __future__ import annotations

import math

import numpy as np

from facegear_tehl.line.reynolds import FilmCoefficients
from facegear_tehl.lubricant import Lubricant

# Central-difference step of dP for d(eta, rho)/dP, relative to p_h: alpha p_h dP ~ 1e-6 for alpha p_h ~ 30, so
# the truncation error (dP^2) and the rounding error (1e-16/dP) of the derivative are both below 1e-8.
PRESSURE_STEP = 1e-7


class IsothermalNewtonian:
    """e(P) = rho_bar/(eta_bar^s lambda), r(P) = rho_bar at the inlet temperature.

    s = `viscosity_exponent` is 1 for the physical film; s < 1 softens the piezoviscous law (ln eta scaled by s)
    for the continuation of `solve.py` from an almost isoviscous film."""

    def __init__(self, lubricant: Lubricant, p_h: float, lam: float, viscosity_exponent: float = 1.0):
        self.lubricant = lubricant
        self.p_h = p_h
        self.lam = lam
        self.viscosity_exponent = viscosity_exponent

    def _laws(self, p_bar: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        p = p_bar * self.p_h
        lub = self.lubricant
        eta = (lub.viscosity_at(p) / lub.viscosity) ** self.viscosity_exponent
        return eta, lub.density_at(p) / lub.density

    def with_exponent(self, viscosity_exponent: float) -> IsothermalNewtonian:
        return IsothermalNewtonian(self.lubricant, self.p_h, self.lam, viscosity_exponent)

    def __call__(self, p_bar: np.ndarray) -> FilmCoefficients:
        eta, rho = self._laws(p_bar)
        eta_up, rho_up = self._laws(p_bar + PRESSURE_STEP)
        eta_dn, rho_dn = self._laws(p_bar - PRESSURE_STEP)
        e = rho / (eta * self.lam)
        e_up = rho_up / (eta_up * self.lam)
        e_dn = rho_dn / (eta_dn * self.lam)
        return FilmCoefficients(
            e=e,
            de=(e_up - e_dn) / (2.0 * PRESSURE_STEP),
            r=rho,
            dr=(rho_up - rho_dn) / (2.0 * PRESSURE_STEP),
        )


# --- generalized film: viscosity varying across z (Yang & Wen 1990) ---------------------------------------------

class CrossFilmIntegrals:
    r"""Integrals across the film of one state, on `layers` equal cells per node (cell centres z_k = (k + 1/2)/m
    as fractions of h), with eta* and rho constant in each cell:

        G(zeta) = int_0^zeta dz'/eta*,   G1(zeta) = int_0^zeta z' dz'/eta*     (zeta = z/h)
        u(zeta) = u_a + tau_a h G(zeta) + p_x h^2 G1(zeta),   tau_a = (du - p_x h^2 G1(1))/(h G(1)),  du = u_b - u_a
        IG_k = int_cell G, IG1_k = int_cell G1 (exact for the piecewise-constant 1/eta*)

    (the velocity of a film whose shear stress tau = tau_a + p_x z drives du/dz = tau/eta*; Yang & Wen 1990). The
    layer mass fluxes per unit width split into a Couette part and a Poiseuille part per unit p_x:

        m_k = mC_k + p_x mP_k,   mC_k = h rho_k (u_a d + du IG_k/G(1)),
        mP_k = h^3 rho_k (IG1_k - G1(1) IG_k/G(1)),   sum_k mC_k = h B,  sum_k mP_k = h^3 A

    so that the film's flux is q = A h^3 dp/dx + B h: the generalized Reynolds equation of Yang & Wen (1990)
    (for a Newtonian isothermal film A = -rho/(12 eta), B = rho u_e exactly)."""

    def __init__(self, eta_star: np.ndarray, rho: np.ndarray, u_a: float, u_b: float):
        n, m = eta_star.shape
        d = 1.0 / m
        z_lo = np.arange(m) * d
        z_hi = z_lo + d
        f = 1.0 / eta_star
        g_hi = np.cumsum(f * d, axis=1)
        g_lo = g_hi - f * d
        g1_cell = f * 0.5 * (z_hi**2 - z_lo**2)
        g1_lo = np.cumsum(g1_cell, axis=1) - g1_cell
        self.d = d
        self.z = 0.5 * (z_lo + z_hi)
        self.f = f
        self.rho = rho
        self.u_a, self.du = u_a, u_b - u_a
        self.g_total = g_hi[:, -1]
        self.g1_total = g1_cell.sum(axis=1)
        self.ig = 0.5 * d * (g_lo + g_hi)
        self.ig1 = d * g1_lo + 0.5 * f * ((z_hi**3 - z_lo**3) / 3.0 - z_lo**2 * d)
        ratio = (self.g1_total / self.g_total)[:, None]
        self.couette_shape = rho * (u_a * d + self.du * self.ig / self.g_total[:, None])  # mC_k / h
        self.poiseuille_shape = rho * (self.ig1 - ratio * self.ig)  # mP_k / h^3

    @property
    def a(self) -> np.ndarray:
        """A = sum_k rho_k (IG1_k - G1(1) IG_k/G(1)) (< 0), kg/(m^3 Pa s)."""
        return self.poiseuille_shape.sum(axis=1)

    @property
    def b(self) -> np.ndarray:
        """B = sum_k rho_k (u_a d + du IG_k/G(1)), kg/(m^2 s)."""
        return self.couette_shape.sum(axis=1)

    def wall_stress(self, h: np.ndarray, p_x: np.ndarray) -> np.ndarray:
        """tau_a = (du - p_x h^2 G1(1))/(h G(1)), Pa: the shear stress on the surface z = 0."""
        return (self.du - p_x * h * h * self.g1_total) / (h * self.g_total)

    def dissipation(self, h: np.ndarray, p_x: np.ndarray) -> np.ndarray:
        """int over each cell of tau du/dz dz = h f_k int (tau_a + p_x h zeta)^2 dzeta, W/m^2 (n, m), exact."""
        tau_a = self.wall_stress(h, p_x)[:, None]
        slope = (p_x * h)[:, None]
        d = self.d
        z_lo = self.z - 0.5 * d
        z_hi = self.z + 0.5 * d
        integral = tau_a**2 * d + tau_a * slope * (z_hi**2 - z_lo**2) + slope**2 * (z_hi**3 - z_lo**3) / 3.0
        return h[:, None] * self.f * integral


class GeneralizedFilm:
    """Flow coefficients e(P), r(P) of the generalized Reynolds equation (Yang & Wen 1990) at a frozen
    temperature field T (n, m) and, for a Ree-Eyring film, a frozen shear rate |du/dz| of every layer (n, m):

        e = -A b^3 p_h/(rho_0 u_e R^2),   r = B/(rho_0 u_e)        (CrossFilmIntegrals; Hertzian units)
        eta* = tau_0 asinh(eta |du/dz|/tau_0)/|du/dz|              (Ree-Eyring; eta* = eta when Newtonian)

    The viscosity eta(p, T) and density rho(p, T) of every layer follow the node pressure (their P-derivatives
    by central differences). Freezing the shear rate rather than eta*/eta gives eta* the stress-limited pressure
    response of the Ree-Eyring fluid (eta* ~ ln(eta)/rate), which the Couette-dominated Hertz zone needs for
    the outer iteration of `solve.py` (it updates T and the rates) to converge."""

    def __init__(self, lubricant: Lubricant, p_h: float, b: float, radius: float, u_a: float, u_b: float,
                 temperature: np.ndarray, shear_rate: np.ndarray | None = None,
                 eyring_stress: float = math.inf):
        self.lubricant = lubricant
        self.p_h = p_h
        self.u_a, self.u_b = u_a, u_b
        self.u_e = 0.5 * (u_a + u_b)
        self.e_scale = b**3 * p_h / (lubricant.density * self.u_e * radius**2)
        self.temperature = temperature
        self.shear_rate = shear_rate
        self.eyring_stress = eyring_stress

    def layer_laws(self, p_bar: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(eta, eta*, rho) of every layer (n, m) at node pressures p_bar."""
        p = np.broadcast_to((p_bar * self.p_h)[:, None], self.temperature.shape)
        eta = self.lubricant.viscosity_at(p, self.temperature)
        rho = self.lubricant.density_at(p, self.temperature)
        if self.shear_rate is None or not math.isfinite(self.eyring_stress):
            return eta, eta, rho
        rate = self.shear_rate
        x = eta * rate / self.eyring_stress
        small = x < 1e-8
        eta_star = np.where(small, eta, eta * np.arcsinh(x) / np.where(small, 1.0, x))
        return eta, eta_star, rho

    def integrals(self, p_bar: np.ndarray) -> CrossFilmIntegrals:
        _, eta_star, rho = self.layer_laws(p_bar)
        return CrossFilmIntegrals(eta_star, rho, self.u_a, self.u_b)

    def _er(self, p_bar: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        c = self.integrals(p_bar)
        return -c.a * self.e_scale, c.b / (self.lubricant.density * self.u_e)

    def __call__(self, p_bar: np.ndarray) -> FilmCoefficients:
        e, r = self._er(p_bar)
        e_up, r_up = self._er(p_bar + PRESSURE_STEP)
        e_dn, r_dn = self._er(p_bar - PRESSURE_STEP)
        return FilmCoefficients(e=e, de=(e_up - e_dn) / (2.0 * PRESSURE_STEP),
                                r=r, dr=(r_up - r_dn) / (2.0 * PRESSURE_STEP))
