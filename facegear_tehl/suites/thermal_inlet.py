r"""Thermal inlet-zone analysis of a rolling line contact: the film lost to inlet shear heating under the
assumptions of the published inlet analyses, solved here from scratch (it imports nothing else of facegear_tehl:
an independent reference).

Assumptions (those Wilson & Sheu 1983 and Murch & Wilson 1975 state for their inlet analyses): Grubin's (1949)
inlet, i.e. rigid surfaces with the dry Hertzian gap up to the edge of the contact, where the pressure becomes
infinite; pure rolling at u (both surfaces), Newtonian incompressible oil with eta = eta_0 exp(alpha p - beta dT);
a local energy balance (heat conducted across the film only, none carried along it) with both walls at the inlet
temperature. With X = x/b, H = h/h_0 (h_0: the parallel film of the contact) and t = z/h - 1/2:

    gap          H = 1 + kappa G(X),  kappa = b^2/(2 R h_0),  G = |X| sqrt(X^2 - 1) - ln(|X| + sqrt(X^2 - 1))
                 (the gap outside a Hertz line contact: -(1/pi) int sqrt(1 - S^2) ln|X - S| dS + X^2/2 + const)
    flux         q = u h - p_x h^3 exp(-alpha p) phi/(12 eta_0) = u h_0,   phi = 12 int_{-1/2}^{1/2} t^2 e^theta dt
                 (pure rolling: the shear is the Poiseuille part tau = p_x (z - h/2) only; phi = 1 isothermal)
    energy       k d^2T/dz^2 = -tau^2/eta, T = T_0 at both walls; in theta = beta dT:
                 theta'' = -(lambda_0/phi^2) t^2 e^theta,   lambda_0 = 144 L exp(alpha p) (1 - 1/H)^2,
                 L = eta_0 beta u^2/k_f (the thermal loading of Wilson & Sheu 1983, eq. 6)
    pressure     S = 1 - exp(-alpha p):  dS/dX = 12 eta_0 u alpha b (H - 1)/(h_0^2 H^3 phi),
                 S(-inf) = 0 and S(-1) = 1 (Grubin's condition) fix h_0.

The cross-film problem has one universal solution: with s = nu^(1/4) t (nu = lambda_0 e^theta_m/phi^2, theta_m
the mid-film value), psi = theta - theta_m obeys Psi'' = -s^2 e^Psi, Psi(0) = Psi'(0) = 0, and the walls sit at
s_w = nu^(1/4)/2 where theta_m = -Psi(s_w); then phi = 3 e^theta_m (-Psi'(s_w))/s_w^3 and lambda_0 =
16 s_w^4 e^-theta_m phi^2 (small lambda_0: theta_m = lambda_0/192, phi = 1 + lambda_0/336). One integration of
Psi tabulates phi(lambda_0); past the table (the contact edge, where exp(alpha p) -> inf) phi follows the power
law of its last points. C = h_0(L)/h_0(L = 0) is the thermal correction factor of the published analyses.

Checks (tests/test_thermal_validation.py): at L = 0 the film is Ertel & Grubin's h_0 = 1.95 R (U G)^(8/11)
W^(-1/11); at L = 10 and 20, where the published fits were made, C is Wilson & Sheu's eq. 8 and Murch & Wilson's
within 2 %; the gap G against a quadrature of the Hertz deflection.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
import math

import numpy as np
from scipy import integrate, optimize

INLET_START = -20.0  # X where the inlet integral starts: its tail beyond adds ~1/(3 kappa^2 |X|^3) ~ 1e-5 of S
TABLE_END = 30.0  # largest mid-film theta tabulated (e^30: far past any physical rise; the power law continues)
TABLE_POINTS = 400  # tabulated cross-film solutions, log-spaced in the wall position s_w
# first wall position tabulated: lambda_0 = 0.13, where the first-order phi = 1 + lambda_0/336 is within 4e-5 of
# phi - 1 (it is used below)
TABLE_START = 0.3
ODE_TOLERANCE = 1e-9  # relative tolerance of both integrations: far below the 1e-4 reported on C
# absolute tolerances: Psi and S are O(1) (Psi down to -TABLE_END), so these floors never bind before the relative one
PSI_ATOL, S_ATOL = 1e-14, 1e-12
EDGE_GAP = 1e-12  # X distance kept from the Hertz edge (sqrt(X^2 - 1) stays real); G there is ~1e-18


def hertz_gap(x: np.ndarray | float) -> np.ndarray:
    """G(X) = |X| sqrt(X^2 - 1) - ln(|X| + sqrt(X^2 - 1)) for |X| >= 1: the dry gap outside a Hertz line contact
    in units of b^2/(2R) (Grubin 1949; the closed form of the Hertz deflection integral)."""
    a = np.abs(np.asarray(x, dtype=float))
    root = np.sqrt(np.clip(a * a - 1.0, 0.0, None))
    return a * root - np.log(a + root)


@lru_cache(maxsize=1)
def _cross_film_table() -> tuple[np.ndarray, np.ndarray, float]:
    """(ln lambda_0, ln(phi - 1), large-lambda_0 exponent of phi) of the universal cross-film solution."""
    def rhs(s, y):
        return [y[1], -s * s * math.exp(y[0])]

    def deep(s, y):  # stop once the mid-film rise theta_m = -Psi exceeds the table
        return y[0] + TABLE_END
    deep.terminal = True
    # s_w grows like theta_m/I(inf) once the wall region is cold: 1e3 is far beyond TABLE_END, which ends the run
    solution = integrate.solve_ivp(rhs, (0.0, 1e3), [0.0, 0.0], rtol=ODE_TOLERANCE, atol=PSI_ATOL, dense_output=True,
                                   events=deep)
    s = np.geomspace(TABLE_START, solution.t[-1], TABLE_POINTS)
    psi, slope = solution.sol(s)
    theta_m = -psi
    phi = 3.0 * np.exp(theta_m) * (-slope) / s**3
    lam = 16.0 * s**4 * np.exp(-theta_m) * phi**2
    exponent = math.log(phi[-1] / phi[-2]) / math.log(lam[-1] / lam[-2])
    return np.log(lam), np.log(phi - 1.0), exponent


def poiseuille_factor(lam0: float) -> float:
    """phi(lambda_0) = 12 int t^2 e^theta dt of the cross-film solution (1 when isothermal): the first-order
    1 + lambda_0/336 below the table, the table's power law above it."""
    log_lam, log_excess, exponent = _cross_film_table()
    if lam0 <= math.exp(log_lam[0]):
        return 1.0 + lam0 / 336.0
    x = math.log(lam0)
    if x >= log_lam[-1]:
        top = 1.0 + math.exp(log_excess[-1])
        return top * math.exp(exponent * (x - log_lam[-1]))
    return 1.0 + math.exp(float(np.interp(x, log_lam, log_excess)))


def ertel_grubin(radius: float, half_width: float, speed: float, viscosity: float, pressure_viscosity: float
                 ) -> float:
    """Ertel & Grubin's isothermal film h_0 = 1.95 R (U G)^(8/11) W^(-1/11) (Grubin 1949), m, with U G =
    eta_0 u alpha/R and W = w'/(E' R) = pi b^2/(8 R^2) (b = sqrt(8 w' R/(pi E')))."""
    ug = viscosity * speed * pressure_viscosity / radius
    w = math.pi * half_width**2 / (8.0 * radius**2)
    return 1.95 * radius * ug ** (8.0 / 11.0) * w ** (-1.0 / 11.0)


@dataclass(frozen=True)
class RollingInlet:
    """A rolling line contact for the inlet analysis, SI: reduced radius R (m), Hertz half-width b (m), entrainment
    speed u (m/s), eta_0 (Pa s), alpha (1/Pa)."""

    radius: float
    half_width: float
    speed: float
    viscosity: float
    pressure_viscosity: float

    def edge_reduced_pressure(self, h0: float, loading: float) -> float:
        """S at the Hertz edge X = -1 for a parallel film h0 (m); where S reaches 1 before the edge (only with
        heating), 1 + the X distance left, so that the result grows monotonically as h0 falls."""
        kappa = self.half_width**2 / (2.0 * self.radius * h0)
        scale = 12.0 * self.viscosity * self.speed * self.pressure_viscosity * self.half_width / h0**2

        def rhs(x, y):
            ratio = 1.0 + kappa * float(hertz_gap(min(x, -1.0 - EDGE_GAP)))
            phi = 1.0
            if loading > 0.0:
                # S < 1 until the event ends the run; the floor keeps a trial step past it finite
                lam0 = 144.0 * loading * (1.0 - 1.0 / ratio) ** 2 / max(1.0 - y[0], 1e-300)
                phi = poiseuille_factor(lam0)
            return [scale * (ratio - 1.0) / (ratio**3 * phi)]

        def full(x, y):
            return y[0] - 1.0
        full.terminal = True
        # max_step: the gap's curvature is resolved near the edge (steps of 0.1 b at most)
        solution = integrate.solve_ivp(rhs, (INLET_START, -1.0), [0.0], rtol=ODE_TOLERANCE, atol=S_ATOL,
                                       events=full if loading > 0.0 else None, max_step=0.1)
        if loading > 0.0 and solution.t[-1] < -1.0 - EDGE_GAP:
            return 1.0 + (-1.0 - solution.t[-1])
        return float(solution.y[0, -1])

    def film(self, loading: float) -> float:
        """h_0 (m) meeting Grubin's condition S(-1) = 1 at thermal loading `loading`, searched within a factor 20
        of Ertel & Grubin's isothermal h_0 = 1.95 R (U G)^(8/11) W^(-1/11), U G = eta_0 u alpha/R,
        W = w'/(E' R) = pi b^2/(8 R^2) (Grubin 1949)."""
        guess = ertel_grubin(self.radius, self.half_width, self.speed, self.viscosity, self.pressure_viscosity)
        return math.exp(optimize.brentq(lambda g: self.edge_reduced_pressure(math.exp(g), loading) - 1.0,
                                        math.log(guess / 20.0), math.log(20.0 * guess), xtol=1e-12))

    def correction(self, loading: float) -> float:
        """C = h_0(L)/h_0(0): the thermal correction factor of the central film."""
        return self.film(loading) / self.film(0.0)
