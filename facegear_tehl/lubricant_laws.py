"""The viscosity, density and conductivity laws of lubricant.py as Numba kernels (SI units; the law parameters
from `Lubricant.law_parameters`; their constants from lubricant_constants.py). Apart from the Lubricant dataclass,
which imports them on first use, so that reading a case does not import Numba (`tehl validate`: Numba takes about
0.15 s to import)."""

from __future__ import annotations

import math

from numba import njit
import numpy as np

from facegear_tehl.lubricant_constants import (
    DH_P1,
    DH_RATIO,
    DOWSON_HIGGINSON,
    ROELANDS,
    ROELANDS_PRESSURE,
    ROELANDS_T_INF,
)


@njit(cache=True)
def roelands_pressure_factor_at(p, law):
    """(1 + p/p_r)^z of the Roelands law, p in Pa clipped at 0."""
    return (1.0 + max(p, 0.0) / ROELANDS_PRESSURE) ** law[2]


@njit(cache=True)
def roelands_temperature_factor_at(t, law):
    """((T - T_inf)/(T_0 - T_inf))^(-S_0) of the Roelands law (1 for Barus)."""
    if law[0] == ROELANDS:
        return ((t - ROELANDS_T_INF) / (law[6] - ROELANDS_T_INF)) ** (-law[4])
    return 1.0


@njit(cache=True)
def roelands_ratio(pressure_factor, temperature_factor, law):
    """eta/eta_0 = exp(ln-term ((1 + p/p_r)^z ((T - T_inf)/(T_0 - T_inf))^(-S_0) - 1)) from its two factors."""
    return math.exp(law[3] * (pressure_factor * temperature_factor - 1.0))


@njit(cache=True)
def viscosity_ratio_at(p, t, law):
    """eta/eta_0 at one pressure p (Pa, clipped at 0) and temperature t (K); law from `law_parameters`."""
    if law[0] == ROELANDS:
        return roelands_ratio(roelands_pressure_factor_at(p, law), roelands_temperature_factor_at(t, law), law)
    return math.exp(law[1] * max(p, 0.0) - law[5] * (t - law[6]))


@njit(cache=True)
def roelands_temperature_coefficient(pressure_factor, temperature_factor, t, law):
    """beta = -d ln(eta)/dT (1/K) of the Roelands law at temperature t (K) from its two factors:
    ln-term S_0 (1 + p/p_r)^z ((T - T_inf)/(T_0 - T_inf))^(-S_0)/(T - T_inf)."""
    return law[3] * law[4] * pressure_factor * temperature_factor / (t - ROELANDS_T_INF)


@njit(cache=True)
def viscosity_temperature_coefficient_at(p, t, law):
    """beta = -d ln(eta)/dT (1/K) at pressure p (Pa) and temperature t (K) of the viscosity law."""
    if law[0] == ROELANDS:
        return roelands_temperature_coefficient(roelands_pressure_factor_at(p, law),
                                                roelands_temperature_factor_at(t, law), t, law)
    return law[5]


@njit(cache=True)
def density_ratio_at(p, t, law):
    """rho/rho_0 at one pressure p (Pa, clipped at 0) and temperature t (K)."""
    return density_pressure_factor_at(p, law) * density_thermal_factor_at(t, law)


@njit(cache=True)
def density_pressure_factor_at(p, law):
    """The pressure factor of rho/rho_0 (Dowson & Higginson 1966; 1 for an incompressible oil), p in Pa clipped at 0."""
    if law[7] == DOWSON_HIGGINSON:
        p = max(p, 0.0)
        return (DH_P1 + DH_RATIO * p) / (DH_P1 + p)
    return 1.0


@njit(cache=True)
def density_thermal_factor_at(t, law):
    """The temperature factor of rho/rho_0, 1 - eps_T (T - T_0), t in K."""
    return 1.0 - law[8] * (t - law[6])


@njit(cache=True)
def conductivity_ratio_at(p, a, b):
    """k/k_0 at one pressure p (Pa, clipped at 0) of the pressure-dependent thermal conductivity of
    Larsson, Larsson, Eriksson, Sjoberg & Hoglund (2000), Proc. IMechE J 214:17-27, fit for the PAO 'PAOB':

        k/k_0 = 1 + a p/(1 + b p),   p in GPa, a and b in 1/GPa

    (PAOB: a = 1.40, b = 0.34, k_0 = 0.154 W/(m K); fitted up to 1.1 GPa, beyond which it is extrapolated,
    saturating towards 1 + a/b). a = b = 0 gives exactly 1."""
    p_gpa = max(p, 0.0) * 1e-9
    return 1.0 + a * p_gpa / (1.0 + b * p_gpa)


@njit(cache=True)
def conductivity_ratio(pressure, a, b):
    """k/k_0 on an array of pressure (Pa), flattened; a, b in 1/GPa (`conductivity_ratio_at`)."""
    p_flat = pressure.ravel()
    out = np.empty(p_flat.size)
    for n in range(p_flat.size):
        out[n] = conductivity_ratio_at(p_flat[n], a, b)
    return out


@njit(cache=True)
def viscosity_ratio(pressure, temperature, law):
    """eta/eta_0 on arrays of pressure (Pa) and temperature (K), flattened."""
    p_flat = pressure.ravel()
    t_flat = temperature.ravel()
    out = np.empty(p_flat.size)
    for n in range(p_flat.size):
        out[n] = viscosity_ratio_at(p_flat[n], t_flat[n], law)
    return out


@njit(cache=True)
def density_ratio(pressure, temperature, law):
    """rho/rho_0 on arrays of pressure (Pa) and temperature (K), flattened."""
    p_flat = pressure.ravel()
    t_flat = temperature.ravel()
    out = np.empty(p_flat.size)
    for n in range(p_flat.size):
        out[n] = density_ratio_at(p_flat[n], t_flat[n], law)
    return out


@njit(cache=True)
def temperature_coefficient(pressure, temperature, law):
    """beta = -d ln(eta)/dT (1/K) on arrays of pressure (Pa) and temperature (K), flattened."""
    p_flat = pressure.ravel()
    t_flat = temperature.ravel()
    out = np.empty(p_flat.size)
    for n in range(p_flat.size):
        out[n] = viscosity_temperature_coefficient_at(p_flat[n], t_flat[n], law)
    return out
