"""The oil's micropitting test result as ISO/TS 6336-22 reads it: the specific film thickness lambda_GFT of the FZG
C-type test gear at the failure load stage of the test GF-C/8.3/90 (FVA 54/7: 8.3 m/s pitch line velocity, 90 degC
oil injected), by method B on the gear's involute path (ISO/TR 15144-1:2014 Formulae (4), (12)-(15), (22)-(25), (34)-
(48), (80)-(92); the local laws in micropitting.py). SI inside.

Test gear (Hoehn, Oster, Tobie & Michaelis 2008, Goriva i maziva 47(2):129, table 1): z 16/24, m 4.5 mm, alpha 20 deg,
a 91.5 mm, b 14 mm, x 0.1817/0.1715, tip diameters 82.46/118.36 mm (the table rounds them to 82.5/118.4),
16MnCr5 case carburized, ground to Ra 0.5 um;
pinion torque of load stage S: T_1 = 3.726 S^2 N m (ISO 14635-1, as ISO/TR 13989-2 Eq. (97) writes it).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
import math

import numpy as np

from facegear_tehl import micropitting, scuffing

PINION_TEETH, WHEEL_TEETH = 16, 24
MODULE = 4.5e-3  # m
PRESSURE_ANGLE = math.radians(20.0)
CENTRE_DISTANCE = 91.5e-3  # m
FACE_WIDTH = 14.0e-3  # m
TIP_DIAMETERS = (82.46e-3, 118.36e-3)  # m
ROUGHNESS_RA = 0.5e-6  # m, ground test flanks (ISO/TR 15144-1 Annex A)
PITCH_LINE_VELOCITY = 8.3  # m/s, at the reference circle
OIL_TEMPERATURE = 90.0 + 273.15  # K
TEST_LUBRICATION = "spray"  # injection lubrication: X_S = 1.2
STEEL_MODULUS, STEEL_POISSON = 206e9, 0.3  # Pa, - (ISO 6336-2 steel)
STEEL_CONTACT_COEFFICIENT = math.sqrt(45.0 * 7800.0 * 440.0)  # B_M = sqrt(k rho c), ISO/TR 15144-1 Table 2 steel
# The load stages of the GF-C/8.3/90 test: 5 to 10 (a pass at 10 reads "> 10"; FVA 54/7).
MICROPITTING_STAGES = (5, 10)
# ISO 1328-1 grade 5 of the test gears: Q = 7, the load share at the ends of the path (Q - 2)/15 = 1/3
# (ISO/TR 15144-1 Formulae (46)-(48)).
END_SHARE = (7 - 2) / 15.0


@dataclass(frozen=True)
class InvolutePoint:
    """One point Y of a spur pair's path of contact (SI): radii of curvature, tangential speeds, load share."""

    name: str
    rho_1: float
    rho_2: float
    speed_1: float
    speed_2: float
    share: float

    @property
    def radius(self) -> float:
        """rho_n,Y = rho_1 rho_2/(rho_1 + rho_2), m (spur: beta_b = 0)."""
        return self.rho_1 * self.rho_2 / (self.rho_1 + self.rho_2)


def path_points(pinion_speed: float) -> tuple[tuple[InvolutePoint, ...], float, float]:
    """Method B's points A, AB, B, C, D, DE, E of the test gear's path (ISO/TR 15144-1 Formulae (34)-(40)), the
    pinion driving at `pinion_speed` rad/s, and the addendum contact ratios eps_1, eps_2."""
    rb1, rb2 = (MODULE * z * math.cos(PRESSURE_ANGLE) / 2.0 for z in (PINION_TEETH, WHEEL_TEETH))
    alpha_w = math.acos((rb1 + rb2) / CENTRE_DISTANCE)
    tip_1, tip_2 = (math.sqrt((d / 2.0) ** 2 - rb**2) for d, rb in zip(TIP_DIAMETERS, (rb1, rb2)))
    line = CENTRE_DISTANCE * math.sin(alpha_w)
    length = tip_1 + tip_2 - line  # g_alpha
    pitch = math.pi * MODULE * math.cos(PRESSURE_ANGLE)  # p_et
    g_c = rb1 * math.tan(alpha_w) - tip_1 + length
    places = {"A": 0.0, "AB": (length - pitch) / 2.0, "B": length - pitch, "C": g_c, "D": pitch,
              "DE": (length - pitch) / 2.0 + pitch, "E": length}
    ratio = WHEEL_TEETH / PINION_TEETH
    points = []
    for name, g in places.items():
        if g < length - pitch:
            share = END_SHARE + (1.0 / 3.0) * g / (length - pitch)
        elif g <= pitch:
            share = 1.0
        else:
            share = END_SHARE + (1.0 / 3.0) * (length - g) / (length - pitch)
        rho_1 = tip_1 - length + g
        points.append(InvolutePoint(name, rho_1, line - rho_1, pinion_speed * rho_1,
                                    pinion_speed / ratio * (line - rho_1), share))
    return tuple(points), (tip_1 - rb1 * math.tan(alpha_w)) / pitch, (tip_2 - rb2 * math.tan(alpha_w)) / pitch


def load_loss_factor(eps_1: float, eps_2: float) -> float:
    """H_V = (eps_1^2 + eps_2^2 + 1 - eps_alpha)(1/z_1 + 1/z_2) pi, - (ISO/TR 15144-1 Formula (92), spur,
    eps_alpha < 2)."""
    return (eps_1**2 + eps_2**2 + 1.0 - eps_1 - eps_2) * (1.0 / PINION_TEETH + 1.0 / WHEEL_TEETH) * math.pi


def stage_torque(stage: float) -> float:
    """Pinion torque of an FZG load stage, N m: 3.726 S^2 (ISO/TR 13989-2 Eq. (97))."""
    return scuffing.FZG_TORQUE_PER_STAGE2 * stage**2


def failure_film(stage: float, viscosity: Callable[[float], float], alpha_38: float, oil_factor: float) -> float:
    """lambda_GFT: the smallest lambda_GF,Y = h_Y/Ra over the test gear's points A..E at the failure load stage
    (all load factors K = 1), for an oil of dynamic viscosity viscosity(T) (Pa s, T in K) and alpha_38 (1/Pa)."""
    speed = 2.0 * PITCH_LINE_VELOCITY / (MODULE * PINION_TEETH)  # rad/s
    points, eps_1, eps_2 = path_points(speed)
    pitch = next(p for p in points if p.name == "C")
    e_r = STEEL_MODULUS / (1.0 - STEEL_POISSON**2)  # 2/((1 - nu^2)/E + (1 - nu^2)/E)
    torque = stage_torque(stage)
    normal_load = torque / (MODULE * PINION_TEETH / 2.0) / math.cos(PRESSURE_ANGLE) / FACE_WIDTH  # N/m
    mu = scuffing.mean_friction_integral(normal_load, pitch.speed_1 + pitch.speed_2, pitch.radius,
                                         viscosity(OIL_TEMPERATURE), ROUGHNESS_RA, oil_factor, min_load=0.0)
    loss = torque * speed * mu * load_loss_factor(eps_1, eps_2)
    bulk = micropitting.bulk_temperature(OIL_TEMPERATURE, loss, CENTRE_DISTANCE, FACE_WIDTH,
                                         scuffing.LUBRICATION_FACTOR[TEST_LUBRICATION])
    alpha_bulk = alpha_38 * micropitting.alpha_ratio(bulk, micropitting.ALPHA_REFERENCE)
    films = []
    for p in points:
        pressure = math.sqrt(e_r * normal_load * p.share / (2.0 * math.pi * p.radius))
        half_width = 4.0 * p.radius * pressure / e_r
        rise = micropitting.flash_temperature(mu, pressure, p.speed_1, p.speed_2, half_width,
                                              STEEL_CONTACT_COEFFICIENT, STEEL_CONTACT_COEFFICIENT)
        sliding = micropitting.sliding_parameter(alpha_38 * micropitting.alpha_ratio(
            bulk + rise, micropitting.ALPHA_REFERENCE), viscosity(bulk + rise), alpha_bulk, viscosity(bulk))
        films.append(micropitting.film_thickness(p.radius, p.speed_1 + p.speed_2, pressure, e_r, alpha_bulk,
                                                 viscosity(bulk), sliding))
    return float(np.min(films)) / ROUGHNESS_RA
