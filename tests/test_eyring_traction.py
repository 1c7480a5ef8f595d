"""Friction of the Ree-Eyring film in its stress-limited range against the Eyring traction of the Hertz zone.

Reference (docs/accuracy.md, "Published thermal validation"): with the Ree-Eyring law (Ree & Eyring 1955; Johnson &
Tevaarwerk 1977) a Couette film of thickness h sheared at u_s carries tau = tau_0 asinh(eta(p) u_s/(h tau_0)); over
the Hertz ellipse (p = p_h sqrt(1 - r^2), dA = 2 pi a b r dr) with the central film of Nijenbanning, Venner & Moes
(1994) for h, mu = (2 pi a b/W) int_0^1 tau(p(r)) r dr. It neglects the film's variation over the Hertz zone, the
Poiseuille part of the shear and the departure of the pressure from Hertz's: 5 % (docs/accuracy.md)."""

import math

import numpy as np
import pytest

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.film_formulas import nijenbanning_central
from facegear_tehl.hertz import hertz_contact
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.materials import Solid, reduced_modulus
from facegear_tehl.settings import SolverSettings

STEEL = Solid(elastic_modulus=2.0e11, poisson_ratio=0.3)
RADIUS = 0.01  # m: a 20 mm ball on a flat
P_HERTZ, SPEED = 1.0e9, 2.0  # Pa, m/s: Moes M = 78, L = 14
OIL = Lubricant(viscosity=0.04, pressure_viscosity=2.2e-8, rheology="ree_eyring", eyring_stress=1.0e7)
RINGS = 4000  # midpoint rule over r in (0, 1): the integrand's sqrt edge at r = 1 costs < 1e-5 relative


def hertz_zone_traction(load: float, sliding: float, film: float) -> float:
    """mu of the Couette Ree-Eyring film of thickness `film` over the Hertz ellipse of `load` (isothermal)."""
    e_prime = reduced_modulus(STEEL, STEEL)
    hertz = hertz_contact(RADIUS, RADIUS, load, e_prime)
    r = (np.arange(RINGS) + 0.5) / RINGS
    pressure = hertz.p_max * np.sqrt(1.0 - r * r)
    eta = OIL.viscosity_at(pressure)
    tau = OIL.eyring_stress * np.arcsinh(eta * sliding / (film * OIL.eyring_stress))
    return 2.0 * math.pi * hertz.a * hertz.b * float(np.sum(tau * r)) / RINGS / load


@pytest.mark.parametrize("srr", [0.2, 0.5, 1.0])
def test_eyring_friction_is_that_of_the_hertz_zone(srr):
    e_prime = reduced_modulus(STEEL, STEEL)
    load = 1000.0 * (P_HERTZ / hertz_contact(RADIUS, RADIUS, 1000.0, e_prime).p_max) ** 3
    point = ContactPoint.from_rolling_sliding("ball", RADIUS, RADIUS, load, SPEED, srr, 0.0, STEEL, STEEL)
    solution = solve_point(point, OIL, SolverSettings(grid=129, thermal="off"))
    assert solution.converged
    u = OIL.viscosity * SPEED / (e_prime * RADIUS)
    w = load / (e_prime * RADIUS**2)
    g = OIL.pressure_viscosity * e_prime
    moes_m, moes_l = w * (2.0 * u) ** -0.75, g * (2.0 * u) ** 0.25
    film = nijenbanning_central(moes_m, moes_l, 1.0) * RADIUS * math.sqrt(2.0 * u)
    reference = hertz_zone_traction(load, srr * SPEED, film)
    assert reference > 0.08  # deep in the stress-limited range (mean stress > 5 tau_0): asinh, not the Newtonian line
    assert solution.scalar("mu") == pytest.approx(reference, rel=0.05)
