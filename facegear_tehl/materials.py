"""Elastic and thermal properties of the two solids in contact (SI units)."""

from __future__ import annotations

from dataclasses import dataclass
import math


@dataclass(frozen=True)
class Solid:
    """An isotropic solid body.

    elastic_modulus: Young's modulus E, Pa.
    poisson_ratio: nu, -.
    density: rho, kg/m^3.
    thermal_conductivity: k, W/(m K).
    specific_heat: c, J/(kg K).
    roughness: RMS surface roughness R_q, m (the empirical friction of heat.py, the film parameter of cycle.py);
        0: not given (a smooth surface).
    """

    elastic_modulus: float
    poisson_ratio: float
    density: float = 7850.0
    thermal_conductivity: float = 46.0
    specific_heat: float = 470.0
    roughness: float = 0.0

    @property
    def thermal_diffusivity(self) -> float:
        """kappa = k / (rho c), m^2/s."""
        return self.thermal_conductivity / (self.density * self.specific_heat)

    def thermal_effusivity_speed(self, speed: float) -> float:
        """B = sqrt(k rho c u), W s^0.5/(m^2 K) * (m/s)^0.5: Jaeger's moving-source coefficient."""
        return math.sqrt(self.thermal_conductivity * self.density * self.specific_heat * abs(speed))


def reduced_modulus(body_1: Solid, body_2: Solid) -> float:
    """E' = 2 / [(1 - nu1^2)/E1 + (1 - nu2^2)/E2], Pa (Hamrock & Dowson convention; Johnson's E* = E'/2)."""
    compliance = (1.0 - body_1.poisson_ratio**2) / body_1.elastic_modulus + (
        1.0 - body_2.poisson_ratio**2
    ) / body_2.elastic_modulus
    return 2.0 / compliance
