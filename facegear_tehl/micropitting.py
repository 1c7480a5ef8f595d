"""Micropitting by ISO/TS 6336-22 method B (formerly ISO/TR 15144-1:2014), written with the local values of one
contact point so that it applies point by point along a face gear's path (docs/verdict.md, "Micropitting"). SI
inside; Formula numbers are those of ISO/TR 15144-1:2014.

  specific film        lambda_GF,Y = h_Y / Ra,  Ra = (Ra_1 + Ra_2)/2                             (Formulae (2), (3))
  film thickness       h_Y = 1.6 rho_n G^0.6 U^0.7 W^-0.13 S_GF^0.22                           (Formula (4), Dowson &
                       G = alpha_M E_r, U = eta_M v_sum/(2 E_r rho_n), W = 2 pi p_dyn^2/E_r^2    Higginson line contact)
                       S_GF = alpha_B eta_B/(alpha_M eta_M)  (properties at theta_B and at theta_M, Formula (27))
  alpha(T)             alpha_38 [1 + 516 K (1/T - 1/311 K)]                                   (Formulae (8), (28))
  contact temperature  theta_B = theta_M + theta_fl,  theta_fl = sqrt(pi/2) mu_m p_dyn |v_s| sqrt(b)/(B_M1 sqrt v_1
                       + B_M2 sqrt v_2)  (Formula (80) with b_H = 4 rho_n p_dyn/E_r the Hertz semi-width)
  bulk temperature     theta_M = theta_oil + 7400 K (P_VZP/(a b))^0.72 X_S/(1.2 X_Ca),  P_VZP = P mu_m H_V in kW, a and
                       b in mm                                                                 (Formula (84))
  permissible          lambda_GFP = 1.4 W_W lambda_GFT                                          (Annex A, from the test)
  safety               S_lambda = lambda_GF,min / lambda_GFP                                    (Formula (1))
"""

from __future__ import annotations

import math

ALPHA_TEMPERATURE_CONSTANT = 516.0  # K, Formula (8)
ALPHA_REFERENCE = 311.0  # K (38 degC as the standard rounds it), Formula (8)
FLASH_COEFFICIENT = math.sqrt(math.pi / 2.0)  # Formula (80): sqrt(pi)/2 on sqrt(2 b_H)
BULK_COEFFICIENT = 7400.0  # K, Formula (84)
BULK_EXPONENT = 0.72
BULK_REFERENCE_LUBRICATION = 1.2  # the X_S of spray lubrication the coefficient belongs to, Formula (84)
PERMISSIBLE_FACTOR = 1.4  # Annex A: lambda_GFP from the test gear's lambda_GFT
# Material factor W_W: 1.0 for case-carburized steel, the test gears' material (ISO/TR 15144-1 Annex A).
MATERIAL_FACTOR_CARBURIZED = 1.0


def alpha_ratio(temperature: float, reference: float) -> float:
    """alpha(T)/alpha(T_ref) of Formula (8); temperatures in K."""
    def factor(t: float) -> float:
        return 1.0 + ALPHA_TEMPERATURE_CONSTANT * (1.0 / t - 1.0 / ALPHA_REFERENCE)
    return factor(temperature) / factor(reference)


def film_thickness(radius: float, sum_velocity: float, pressure: float, reduced_modulus: float, alpha_bulk: float,
                   eta_bulk: float, sliding_parameter: float) -> float:
    """h_Y of Formula (4), m: rho_n in m, v_sum = v_1 + v_2 in m/s, p_dyn in Pa, E_r in Pa (2/((1-nu1^2)/E1 + ...)),
    alpha and eta at the bulk temperature (1/Pa, Pa s), S_GF of `sliding_parameter`."""
    g = alpha_bulk * reduced_modulus
    u = eta_bulk * sum_velocity / (2.0 * reduced_modulus * radius)
    w = 2.0 * math.pi * pressure**2 / reduced_modulus**2
    return 1.6 * radius * g**0.6 * u**0.7 * w**-0.13 * sliding_parameter**0.22


def sliding_parameter(alpha_contact: float, eta_contact: float, alpha_bulk: float, eta_bulk: float) -> float:
    """S_GF = alpha_B eta_B/(alpha_M eta_M), - (Formula (27)): the film's loss of viscosity at the contact
    temperature against the bulk temperature."""
    return alpha_contact * eta_contact / (alpha_bulk * eta_bulk)


def flash_temperature(mu: float, pressure: float, speed_1: float, speed_2: float, half_width: float,
                      contact_coefficient_1: float, contact_coefficient_2: float) -> float:
    """theta_fl of Formula (80), K: sqrt(pi/2) mu p_dyn |v_1 - v_2| sqrt(b)/(B_1 sqrt v_1 + B_2 sqrt v_2); p_dyn in
    Pa, speeds in m/s, the Hertz semi-width b in m, B_i = sqrt(k rho c) in W s^0.5/(m^2 K)."""
    v1, v2 = abs(speed_1), abs(speed_2)
    denominator = contact_coefficient_1 * math.sqrt(v1) + contact_coefficient_2 * math.sqrt(v2)
    if denominator <= 0.0:
        return 0.0
    return FLASH_COEFFICIENT * mu * pressure * abs(v1 - v2) * math.sqrt(half_width) / denominator


def bulk_temperature(oil_temperature: float, loss_power: float, centre_distance: float, face_width: float,
                     lubrication_factor: float, tip_relief_factor: float = 1.0) -> float:
    """theta_M of Formula (84), K: theta_oil + 7400 (P_VZP/(a b))^0.72 X_S/(1.2 X_Ca); P_VZP = P mu_m H_V in W, a and
    b in m (the formula's kW and mm applied inside)."""
    group = (loss_power * 1e-3) / (centre_distance * 1e3 * face_width * 1e3)
    return oil_temperature + BULK_COEFFICIENT * group**BULK_EXPONENT * lubrication_factor / (
        BULK_REFERENCE_LUBRICATION * tip_relief_factor)


def permissible_film(test_film: float, material_factor: float = MATERIAL_FACTOR_CARBURIZED) -> float:
    """lambda_GFP = 1.4 W_W lambda_GFT, - (ISO/TR 15144-1 Annex A); lambda_GFT of the oil's FZG GF-C/8.3/90 test."""
    return PERMISSIBLE_FACTOR * material_factor * test_film
