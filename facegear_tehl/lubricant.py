"""Lubricant: pressure-temperature viscosity and density laws, thermal properties, rheology (SI units).

Viscosity (ratio to the inlet value eta_0 at p = 0, T = T_0):
  Roelands (1966), temperature form after Yang & Wen (1990):
      eta/eta_0 = exp{(ln eta_0 + 9.67) [(1 + p/p_r)^z ((T - 138)/(T_0 - 138))^(-S_0) - 1]},  p_r = 1.96e8 Pa
      with z = alpha p_r / (ln eta_0 + 9.67) unless given, S_0 = beta (T_0 - 138)/(ln eta_0 + 9.67)
  Barus (1893) with an exponential temperature term:  eta/eta_0 = exp(alpha p - beta (T - T_0))
Density (ratio to rho_0 at p = 0, T = T_0):
  Dowson & Higginson (1966), in the form of the Venner & Lubrecht (2000) code, multiplied by a linear
  thermal expansion term:  rho/rho_0 = (5.9e8 + 1.34 p)/(5.9e8 + p) * (1 - eps_T (T - T_0))
  incompressible: rho/rho_0 = 1 - eps_T (T - T_0)
Thermal conductivity (ratio to k_0 at p = 0):
  Larsson, Larsson, Eriksson, Sjoberg & Hoglund (2000):  k/k_0 = 1 + a p/(1 + b p),  p in GPa, a and b in 1/GPa
  (a = b = 0: constant k_0)
The laws' constants are in lubricant_constants.py; the laws themselves are Numba kernels in lubricant_laws.py,
imported on first use: reading a case (`tehl validate`) does not load Numba.
"""

from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from facegear_tehl.lubricant_constants import (
    BARUS,
    DOWSON_HIGGINSON,
    INCOMPRESSIBLE,
    ROELANDS,
    ROELANDS_LN_ETA_INF,
    ROELANDS_PRESSURE,
    ROELANDS_T_INF,
)

KELVIN = 273.15  # K at 0 degC

VISCOSITY_MODELS = ("roelands", "barus")
DENSITY_MODELS = ("dowson_higginson", "incompressible")
RHEOLOGY_MODELS = ("newtonian", "ree_eyring")
OIL_TYPES = ("mineral", "pao", "ester", "pag")  # base oils of ISO/TR 14179-2's oil factor X_L (heat.py)


@dataclass(frozen=True)
class Lubricant:
    """Lubricant properties; all values SI (temperatures in K), except the two conductivity coefficients,
    in 1/GPa as in the source (Larsson et al. 2000) and the case file."""

    viscosity: float  # eta_0, Pa s at p = 0 and the inlet temperature
    pressure_viscosity: float  # alpha, 1/Pa (Barus coefficient; sets Roelands z unless roelands_z is given)
    inlet_temperature: float = 40.0 + KELVIN  # T_0, K
    density: float = 870.0  # rho_0, kg/m^3 at p = 0 and T_0
    viscosity_model: str = "roelands"
    density_model: str = "dowson_higginson"
    rheology: str = "newtonian"
    eyring_stress: float = math.inf  # tau_0, Pa (Ree-Eyring reference stress)
    roelands_z: float | None = None  # Roelands pressure index; derived from alpha if None
    temperature_viscosity: float = 0.0  # beta = -d ln(eta)/dT at T_0, 1/K
    thermal_expansion: float = 0.0  # eps_T, 1/K
    thermal_conductivity: float = 0.13  # k_f = k_0, W/(m K) at p = 0
    conductivity_pressure_coefficient: float = 0.0  # a of k/k_0 = 1 + a p/(1 + b p), 1/GPa (0: constant k)
    conductivity_pressure_saturation: float = 0.0  # b, 1/GPa
    specific_heat: float = 2000.0  # c_f, J/(kg K)
    oil_type: str = "mineral"  # base oil, one of OIL_TYPES: only ISO/TR 14179-2's friction coefficient reads it
    scuffing_temperature: float | None = None  # theta_S, K, of the oil on the flanks (scuffing.py); None: not given
    fzg_scuffing_stage: float | None = None  # failure load stage of the FZG A/8.3/90 test (ISO 14635-1); None
    micropitting_stage: float | None = None  # failure load stage of the FZG GF-C/8.3/90 test (FVA 54/7); None
    micropitting_test_film: float | None = None  # its lambda_GFT (ISO/TS 6336-22) given instead of the stage; None
    lubrication: str = "dip"  # dip | spray: the standards' lubrication factor X_S (scuffing.py)

    @property
    def roelands_log_term(self) -> float:
        """ln(eta_0) + 9.67 (eta_0 in Pa s)."""
        return math.log(self.viscosity) - ROELANDS_LN_ETA_INF

    @property
    def z(self) -> float:
        """Roelands pressure-viscosity index z = alpha p_r / (ln eta_0 + 9.67) unless given."""
        if self.roelands_z is not None:
            return self.roelands_z
        return self.pressure_viscosity * ROELANDS_PRESSURE / self.roelands_log_term

    @property
    def s0(self) -> float:
        """Roelands temperature index S_0 = beta (T_0 - 138)/(ln eta_0 + 9.67)."""
        return self.temperature_viscosity * (self.inlet_temperature - ROELANDS_T_INF) / self.roelands_log_term

    @property
    def effective_alpha(self) -> float:
        """Pressure-viscosity coefficient at p = 0 of the chosen law, 1/Pa (Roelands: z (ln eta_0 + 9.67)/p_r)."""
        if self.viscosity_model == "barus":
            return self.pressure_viscosity
        return self.z * self.roelands_log_term / ROELANDS_PRESSURE

    def law_parameters(self) -> np.ndarray:
        """Parameters for the Numba kernels of lubricant_laws.py (`viscosity_ratio`, `density_ratio`, ...)."""
        return np.array(
            [
                ROELANDS if self.viscosity_model == "roelands" else BARUS,
                self.pressure_viscosity,
                self.z,
                self.roelands_log_term,
                self.s0,
                self.temperature_viscosity,
                self.inlet_temperature,
                DOWSON_HIGGINSON if self.density_model == "dowson_higginson" else INCOMPRESSIBLE,
                self.thermal_expansion,
            ],
            dtype=np.float64,
        )

    def viscosity_at(self, pressure, temperature=None) -> np.ndarray:
        """eta(p, T), Pa s; temperature in K (default: inlet)."""
        # imported here, not at the top, for start-up: reading a case (`tehl validate`) does not load Numba
        from facegear_tehl.lubricant_laws import viscosity_ratio

        p, t = _broadcast(pressure, temperature, self.inlet_temperature)
        return self.viscosity * viscosity_ratio(p, t, self.law_parameters()).reshape(np.shape(p))

    def density_at(self, pressure, temperature=None) -> np.ndarray:
        """rho(p, T), kg/m^3; temperature in K (default: inlet)."""
        # imported here, not at the top, for start-up: reading a case (`tehl validate`) does not load Numba
        from facegear_tehl.lubricant_laws import density_ratio

        p, t = _broadcast(pressure, temperature, self.inlet_temperature)
        return self.density * density_ratio(p, t, self.law_parameters()).reshape(np.shape(p))

    def conductivity_at(self, pressure) -> np.ndarray:
        """k(p), W/(m K) (Larsson et al. 2000; exactly k_0 everywhere when a = b = 0)."""
        # imported here, not at the top, for start-up: reading a case (`tehl validate`) does not load Numba
        from facegear_tehl.lubricant_laws import conductivity_ratio

        p = np.asarray(pressure, dtype=np.float64)
        ratio = conductivity_ratio(np.ascontiguousarray(p), self.conductivity_pressure_coefficient,
                                   self.conductivity_pressure_saturation)
        return self.thermal_conductivity * ratio.reshape(p.shape)


def _broadcast(pressure, temperature, default_t):
    p = np.asarray(pressure, dtype=np.float64)
    t = np.full_like(p, default_t) if temperature is None else np.broadcast_to(
        np.asarray(temperature, dtype=np.float64), p.shape
    ).copy()
    return np.ascontiguousarray(p), np.ascontiguousarray(t)
