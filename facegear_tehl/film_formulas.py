"""Published film-thickness formulas for elliptical EHL contacts (isothermal, Newtonian, fully flooded).

Dimensionless groups (Hamrock & Dowson 1977), built on the radius R in the entrainment direction:
    U = eta_0 u_e/(E' R), G = alpha E', W = w/(E' R^2), k = a/b;  Moes: M = W (2U)^(-3/4), L = G (2U)^(1/4).
Used as the solver's initial guess and as references in the validation report; their scatter against
full numerical solutions is ~10-30 % (Nijenbanning et al. 1994 fit theirs within ~10-15 %; Hamrock-Dowson's h_min
is ~30 % below measurement, Koye & Winer 1981, J. Lubr. Technol. 103:284), so they never tune the solver.
"""

from __future__ import annotations

import math


def hamrock_dowson_central(u: float, g: float, w: float, k: float) -> float:
    """h_c/R = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k)) (Hamrock & Dowson 1977, Part III)."""
    return 2.69 * u**0.67 * g**0.53 * w**-0.067 * (1.0 - 0.61 * math.exp(-0.73 * k))


def hamrock_dowson_minimum(u: float, g: float, w: float, k: float) -> float:
    """h_min/R = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k)) (Hamrock & Dowson 1977, Part III)."""
    return 3.63 * u**0.68 * g**0.49 * w**-0.073 * (1.0 - math.exp(-0.68 * k))


def nijenbanning_central(moes_m: float, moes_l: float, d: float) -> float:
    """Central film in Moes' scaling, H_c = (h_c/R_x)(2U)^(-1/2), all four regimes, D = R_x/R_y
    (Nijenbanning, Venner & Moes 1994, Wear 176:217)."""
    common = 1.0 + 0.006 * math.log(d) + 0.63 * d ** (4.0 / 7.0)
    h_ri = 145.0 * (1.0 + 0.796 * d ** (14.0 / 15.0)) ** (-15.0 / 7.0) / d / moes_m**2
    h_ei = 3.18 * common ** (-14.0 / 25.0) * d ** (-1.0 / 15.0) * moes_m ** (-2.0 / 15.0)
    h_rp = 1.29 * (1.0 + 0.691 * d) ** (-2.0 / 3.0) * moes_l ** (2.0 / 3.0)
    h_ep = 1.48 * common ** (-7.0 / 20.0) * d ** (-1.0 / 24.0) * moes_m ** (-1.0 / 12.0) * moes_l**0.75
    s = 1.5 * (1.0 + math.exp(-1.2 * h_ei / h_ri))
    h_00 = 1.8 / d
    rigid = (h_ri**1.5 + (h_ei**-4 + h_00**-4) ** -0.375) ** (2.0 * s / 3.0)
    piezo = (h_rp**-8 + h_ep**-8) ** (-s / 8.0)
    return (rigid + piezo) ** (1.0 / s)


def chittenden_radii(radius_x: float, radius_y: float, angle: float) -> tuple[float, float]:
    """(R_e, R_s): radii in the entrainment and side-leakage directions for entrainment at `angle` (rad)
    to the minor axis x (Chittenden, Dowson, Dunn & Taylor 1985)."""
    r_e = 1.0 / (math.cos(angle) ** 2 / radius_x + math.sin(angle) ** 2 / radius_y)
    r_s = 1.0 / (math.sin(angle) ** 2 / radius_x + math.cos(angle) ** 2 / radius_y)
    return r_e, r_s


def chittenden_central(u: float, g: float, w: float, r_s_over_r_e: float) -> float:
    """h_c/R = 4.31 U^0.68 G^0.49 W^-0.073 [1 - exp(-1.23 (R_s/R_e)^(2/3))] (Chittenden et al. 1985)."""
    return 4.31 * u**0.68 * g**0.49 * w**-0.073 * (1.0 - math.exp(-1.23 * r_s_over_r_e ** (2.0 / 3.0)))


def chittenden_minimum(u: float, g: float, w: float, r_s_over_r_e: float) -> float:
    """h_min/R = 3.68 U^0.68 G^0.49 W^-0.073 [1 - exp(-0.67 (R_s/R_e)^(2/3))] (Chittenden et al. 1985)."""
    return 3.68 * u**0.68 * g**0.49 * w**-0.073 * (1.0 - math.exp(-0.67 * r_s_over_r_e ** (2.0 / 3.0)))
