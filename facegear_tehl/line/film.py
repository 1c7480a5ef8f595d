r"""Flow coefficients of the line-contact film: isothermal Newtonian, and the generalized film across z.

Isothermal Newtonian (Reynolds 1886): q = -rho h^3/(12 eta) dp/dx + rho u_e h, i.e. in Hertzian units
(`reynolds.py`)  e = rho_bar/(eta_bar lambda),  r = rho_bar,  lambda = 12 eta_0 u_e R^2/(b^3 p_h).

The lubricant laws (viscosity eta(p, T), density rho(p, T)) are the project's `facegear_tehl.lubricant`.
Their pressure derivatives, needed by the Newton Jacobian, are central differences with the step
PRESSURE_STEP (relative to p_h).
"""

from __future__ import annotations

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
