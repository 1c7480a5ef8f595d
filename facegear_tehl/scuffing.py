"""Scuffing of gear flanks by the flash-temperature method (ISO/TS 6336-20, formerly ISO/TR 13989-1:2000 and
DIN 3990-4) and the integral-temperature method (ISO/TS 6336-21, formerly ISO/TR 13989-2:2000), written with the
local values of one contact point so that they apply point by point along a face gear's path (docs/verdict.md,
"Scuffing by the standards"). SI inside; the standards' own units are applied where their empirical constants need
them (loads in N/mm, radii in mm, viscosities in mPa s, temperatures in degC). Equation numbers are those of
ISO/TR 13989-1:2000 ("Part 1") and ISO/TR 13989-2:2000 ("Part 2").

  flash temperature   theta_fl = 1.11 mu X_J w |v_1 - v_2| / ((B_M1 sqrt v_1 + B_M2 sqrt v_2) sqrt(2 b))   (Blok 1937;
                      Part 1 Eq. (5) before its involute parametrisation, Eq. (A.5): mu X_M X_J X_G (X_G w)^0.75 ...)
  mean friction       mu_m  = 0.060 (w/(v_sum rho))^0.2 X_L X_R,  X_L = X_L0 eta^-0.05,  X_R = Ra^0.5   (Part 1
                      Eq. (25), (27), (28))
                      mu_mC = 0.045 (w/(v_sum rho))^0.2 eta^-0.05 X_L0 X_R,  X_R = 2.2 (Ra/rho)^0.25  (Part 2 Eq. (1),
                      (7): Ra in um, rho in mm);
                      w >= 150 N/mm (Part 2, 5.1); v_sum <= 50 m/s
  approach factor     X_J = 1 + (C_eff - C_a)/50 um (-s/(s_E - s_A))^3 in the approach (s < 0), else 1 (Part 1
                      Eq. (45)-(46), Gamma/(Gamma_E - Gamma_A) = s/(s_E - s_A) on the line of action)
  bulk temperature    theta_M = theta_oil + 0.47 X_S X_mp theta_fl,m          (Part 1 Eq. (22))
                      theta_M = theta_oil + 0.70 X_S X_mp theta_fla,int       (Part 2 Eq. (20))
  integral temp.      theta_int = theta_M + 1.5 theta_fla,int,  theta_fla,int = theta_flaE X_eps/X_Q  (Part 2 Eq. (17),
                      (18), (19) with X_E = X_Ca = 1: run in, no tip relief); theta_flaE the flash temperature at the
                      pinion tip under the pair's whole load; X_eps of the addendum contact ratios (Eq. (39)-(44))
  scuffing temp.      theta_S = 80 degC + (0.85 + 1.4 X_W) X_L S_FZG^2 K      (Part 1 Eq. (99), FZG A/8.3/90 stage)
                      theta_intS = theta_MT + 1.5 X_W theta_flaintT, theta_MT = 80 degC + 0.23 T_1T X_L0,
                      theta_flaintT = 0.2 T_1T (100/nu_40)^0.02 X_L0, T_1T = 3.726 S_FZG^2 N m  (Part 2 Eq. (94)-(97))
  safety factors      S_B = (theta_S - theta_oil)/(theta_B,max - theta_oil)   (Part 1 Eq. (100))
                      S_intS = theta_intS/theta_int  (degC)                   (Part 2 Eq. (14))
"""

from __future__ import annotations

from collections.abc import Sequence
import math

import numpy as np

from facegear_tehl.lubricant import KELVIN

# Blok (1937) band-contact coefficient on the full Hertz width 2b, as the standards carry it (Part 1 Eq. (5));
# Jaeger's (1942) semi-elliptical source gives 1.1116 (heat.BLOK_SAME_MATERIAL_COEFFICIENT).
BLOK_STANDARD = 1.11
# Lubricant factor X_L0 of the base oil (Part 1 Eq. (27); Part 2, 5.1): mineral 1.0, polyalphaolefin 0.8,
# non-water-soluble polyglycol 0.7. Synthetic esters have no entry (the tables' 1.3 is for phosphate esters).
LUBRICANT_FACTOR = {"mineral": 1.0, "pao": 0.8, "pag": 0.7}
# Lubrication factor X_S (Part 1 Eq. (22), Part 2 Eq. (20)): dip lubrication 1.0, spray 1.2.
LUBRICATION_FACTOR = {"dip": 1.0, "spray": 1.2}
LUBRICATION_METHODS = tuple(LUBRICATION_FACTOR)
# Part 1 Eq. (22) and Part 2 Eq. (20), (17): bulk-temperature and integral-temperature weights.
FLASH_BULK_WEIGHT = 0.47
INTEGRAL_BULK_WEIGHT = 0.70  # C_1
INTEGRAL_WEIGHT = 1.5  # C_2
# Part 1 Eq. (25) and Part 2 Eq. (1) constants, and their range limits (Part 2, 5.1).
FLASH_FRICTION = 0.060
INTEGRAL_FRICTION = 0.045
INTEGRAL_ROUGHNESS = 2.2
MIN_UNIT_LOAD = 150.0  # N/mm
MAX_SUM_VELOCITY = 50.0  # m/s
# Part 1 Eq. (46): the approach factor's stiffness scale, 50 um; ISO 6336-1 mesh stiffness of steel spur gears
# c_gamma = 20 N/(mm um) for the effective tip relief C_eff = w/c_gamma of an unmodified profile.
APPROACH_RELIEF_SCALE = 50.0  # um
MESH_STIFFNESS = 20.0  # N/(mm um)
# FZG A/8.3/90 (ISO 14635-1): pinion torque of load stage S, T_1T = 3.726 S^2 N m (Part 2 Eq. (97));
# the scuffing-temperature constants of Part 1 Eq. (99) and Part 2 Eq. (95)-(96).
FZG_TORQUE_PER_STAGE2 = 3.726  # N m
SCUFFING_BASE = 80.0  # degC
FZG_STAGES = (1, 14)  # the stages of the A/8.3/90 test (stage 12 passed: "> 12"; 14 the highest run)


def mean_friction_flash(unit_load: float, sum_velocity: float, radius: float, viscosity: float, roughness_ra: float,
                        oil_factor: float) -> float:
    """mu_m of Part 1 Eq. (25), -: unit load w in N/m, v_sum in m/s, the relative radius rho in m, the oil's dynamic
    viscosity in Pa s at theta_oil, the mean arithmetic roughness Ra in m, X_L0 of `LUBRICANT_FACTOR`."""
    w, v, rho = unit_load * 1e-3, min(sum_velocity, MAX_SUM_VELOCITY), radius * 1e3
    return (FLASH_FRICTION * (w / (v * rho)) ** 0.2 * oil_factor * (viscosity * 1e3) ** -0.05
            * math.sqrt(roughness_ra * 1e6))


def mean_friction_integral(unit_load: float, sum_velocity: float, radius: float, viscosity: float,
                           roughness_ra: float, oil_factor: float, min_load: float = MIN_UNIT_LOAD) -> float:
    """mu_mC of Part 2 Eq. (1), -, in the arguments of `mean_friction_flash`; w at least `min_load` N/mm (Part 2,
    5.1: 150; ISO/TR 15144-1 Formula (86), the same law, sets none: 0)."""
    w, v, rho = max(unit_load * 1e-3, min_load), min(sum_velocity, MAX_SUM_VELOCITY), radius * 1e3
    roughness_factor = INTEGRAL_ROUGHNESS * (roughness_ra * 1e6 / rho) ** 0.25  # Ra in um over rho in mm
    return INTEGRAL_FRICTION * (w / (v * rho)) ** 0.2 * (viscosity * 1e3) ** -0.05 * roughness_factor * oil_factor


def flash_temperature(mu: float, unit_load: float, speed_1: float, speed_2: float, half_width: float,
                      contact_coefficient_1: float, contact_coefficient_2: float) -> float:
    """Blok's flash temperature as the standards write it, K: 1.11 mu w |v_1 - v_2| / ((B_1 sqrt v_1 + B_2 sqrt v_2)
    sqrt(2 b)); w in N/m, the flanks' speeds v_i in m/s relative to the contact, the Hertz semi-width b in m along the
    motion, B_i = sqrt(k rho c) in W s^0.5/(m^2 K). Zero where the flanks roll without sliding or carry no load."""
    v1, v2 = abs(speed_1), abs(speed_2)
    denominator = (contact_coefficient_1 * math.sqrt(v1) + contact_coefficient_2 * math.sqrt(v2)) * math.sqrt(
        2.0 * half_width)
    if unit_load <= 0.0 or denominator <= 0.0:
        return 0.0
    return BLOK_STANDARD * mu * unit_load * abs(v1 - v2) / denominator


def approach_factor(s: np.ndarray, s_start: float, s_end: float, unit_load: float, tip_relief: float = 0.0
                    ) -> np.ndarray:
    """X_J along the path (Part 1 Eq. (45)-(46), the pinion driving): 1 + (C_eff - C_a)/50 um (-s/(s_E - s_A))^3 for
    s < 0, 1 in the recess and never below 1; C_eff = w/c_gamma in um (w in N/m), C_a the tip relief in m."""
    relief = unit_load * 1e-3 / MESH_STIFFNESS - tip_relief * 1e6
    position = np.clip(-np.asarray(s, dtype=float) / (s_end - s_start), 0.0, None)
    return np.maximum(1.0 + relief / APPROACH_RELIEF_SCALE * position**3, 1.0)


def contact_ratio_factor(eps_1: float, eps_2: float) -> float:
    """X_eps of Part 2 Eq. (39)-(44), -: the mean flash temperature along the path over the one at the pinion tip,
    from the addendum contact ratios eps_1 (pinion tip side) and eps_2 (eps_alpha = eps_1 + eps_2 < 3)."""
    eps = eps_1 + eps_2
    if eps < 1.0:
        terms = eps_1**2 + eps_2**2
    elif eps < 2.0 and eps_1 < 1.0 and eps_2 < 1.0:
        terms = 0.70 * (eps_1**2 + eps_2**2) - 0.22 * eps + 0.52 - 0.60 * eps_1 * eps_2
    elif eps < 2.0 and eps_2 < 1.0:
        terms = 0.18 * eps_1**2 + 0.70 * eps_2**2 + 0.82 * eps_1 - 0.52 * eps_2 - 0.30 * eps_1 * eps_2
    elif eps < 2.0:
        terms = 0.70 * eps_1**2 + 0.18 * eps_2**2 - 0.52 * eps_1 + 0.82 * eps_2 - 0.30 * eps_1 * eps_2
    elif eps_1 >= eps_2:
        terms = 0.44 * eps_1**2 + 0.59 * eps_2**2 + 0.30 * eps_1 - 0.30 * eps_2 - 0.15 * eps_1 * eps_2
    else:
        terms = 0.59 * eps_1**2 + 0.44 * eps_2**2 - 0.30 * eps_1 + 0.30 * eps_2 - 0.15 * eps_1 * eps_2
    return terms / (2.0 * eps * eps_1)


def path_mean(s: Sequence[float], values: Sequence[float]) -> float:
    """The mean of `values` over the path s (trapezoidal rule in s, any order): Part 1 Eq. (24)'s theta_fl,m."""
    order = np.argsort(s)
    x, y = np.asarray(s, dtype=float)[order], np.asarray(values, dtype=float)[order]
    span = x[-1] - x[0]
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)) / span) if span > 0.0 else float(np.mean(y))


def flash_bulk_temperature(oil_temperature: float, mean_flash: float, lubrication: str = "dip") -> float:
    """theta_M = theta_oil + 0.47 X_S theta_fl,m, K (Part 1 Eq. (22), X_mp = 1: one mating gear)."""
    return oil_temperature + FLASH_BULK_WEIGHT * LUBRICATION_FACTOR[lubrication] * mean_flash


def integral_temperature(oil_temperature: float, integral_flash: float, lubrication: str = "dip"
                         ) -> tuple[float, float]:
    """(theta_M, theta_int), K: theta_M = theta_oil + 0.70 X_S theta_fla,int, theta_int = theta_M + 1.5
    theta_fla,int (Part 2 Eq. (20), (17); X_mp = 1)."""
    bulk = oil_temperature + INTEGRAL_BULK_WEIGHT * LUBRICATION_FACTOR[lubrication] * integral_flash
    return bulk, bulk + INTEGRAL_WEIGHT * integral_flash


def approach_recess_factor(s_start: float, s_end: float) -> float:
    """X_Q of Part 2 Eq. (25)-(29) from the approach and recess lengths of the path (s < 0 approach, pinion
    driving): 1 for eps_f/eps_a <= 1.5, 1.40 - 4/15 eps_f/eps_a up to 3, 0.60 beyond."""
    ratio = -s_start / s_end if s_end > 0.0 else math.inf
    return 1.0 if ratio <= 1.5 else (0.60 if ratio >= 3.0 else 1.40 - 4.0 / 15.0 * ratio)


def scuffing_temperature(stage: float, oil_factor: float, viscosity: float, structural_factor: float = 1.0) -> float:
    """theta_S of the FZG A/8.3/90 failure load stage S_FZG, K: 80 degC + (0.85 + 1.4 X_W) X_L S^2 with X_L = X_L0
    eta^-0.05 (eta in Pa s at theta_oil; Part 1 Eq. (99), (27))."""
    factor = oil_factor * (viscosity * 1e3) ** -0.05
    return SCUFFING_BASE + KELVIN + (0.85 + 1.4 * structural_factor) * factor * stage**2


def integral_scuffing_temperature(stage: float, oil_factor: float, nu_40: float, structural_factor: float = 1.0
                                  ) -> float:
    """theta_intS of the FZG A/8.3/90 failure load stage, K (Part 2 Eq. (94)-(97)); nu_40 in m^2/s."""
    torque = FZG_TORQUE_PER_STAGE2 * stage**2
    bulk = SCUFFING_BASE + 0.23 * torque * oil_factor
    flash = 0.2 * torque * (100.0 / (nu_40 * 1e6)) ** 0.02 * oil_factor
    return bulk + structural_factor * INTEGRAL_WEIGHT * flash + KELVIN


def flash_safety(scuffing_temperature: float, oil_temperature: float, contact_temperature: float) -> float | None:
    """S_B = (theta_S - theta_oil)/(theta_B - theta_oil), -; None when theta_B does not rise above the oil."""
    if contact_temperature <= oil_temperature:
        return None
    return (scuffing_temperature - oil_temperature) / (contact_temperature - oil_temperature)


def integral_safety(scuffing_temperature: float, integral: float) -> float:
    """S_intS = theta_intS/theta_int with both in degC (Part 2 Eq. (14)); temperatures given in K."""
    return (scuffing_temperature - KELVIN) / (integral - KELVIN)
