"""Lubricant inputs in engineering units: an ISO 3448 grade or kinematic viscosities in mm^2/s turned into the
SI properties of `Lubricant` at the inlet temperature (docs/verdict.md, "Oil inputs").

  grade             nu_40 = the ISO 3448 midpoint of the grade, mm^2/s (ISO 3448:1992, VG 22 .. VG 1000)
  viscosity index   VI = 100 (L - U)/(L - H) for U >= H, else VI = 100 + (10^N - 1)/0.00715, N = log(H/U)/log(Y)
                    (ASTM D2270-10 Procedures A and B; U = nu_40, Y = nu_100, L and H the nu_40 of the VI 0 and
                    VI 100 reference oils of the same nu_100 by the quadratics of its Appendix X2, Table X2.1);
                    nu_100 not given = the Y at which the given or the oil type's assumed VI is reached
  rho_15 not given  the oil type's typical density at 15 degC (ASSUMED_DENSITY_15, from gear oils' data sheets)
  viscosity-temp.   log10 log10(nu + 0.7) = A - B log10 T   (ASTM D341, Walther; nu in mm^2/s >= 2, T in K),
                    A and B through (313.15 K, nu_40) and (373.15 K, nu_100)
  density           rho(t) = rho_15 exp[-a_15 dt (1 + 0.8 a_15 dt)],  a_15 = K_1/rho_15,  dt = t - 15 degC
                    (API MPMS 11.1 (1980) / ASTM D1250, Table 54D lubricating oils: K_0 = 0, K_1 = 0.6278 kg/(m^3 K))
  dynamic visc.     eta_0 = nu(T_0) rho(T_0)
  beta              -d ln(eta)/dT at T_0 = B (nu + 0.7) ln(nu + 0.7)/(nu T) - d ln(rho)/dT  (Walther, differentiated)
  thermal exp.      eps_T = -d ln(rho)/dT at T_0 = a_15 (1 + 1.6 a_15 dt)
  alpha             alpha_38 = C eta_38^X (eta_38 in Pa s, alpha in 1/Pa): mineral 2.657e-8, 0.1348; PAO 1.466e-8,
                    0.0507; PAG 1.392e-8, 0.1572; alpha(T) = alpha_38 [1 + 516 K (1/T - 1/311 K)]
                    (ISO/TR 15144-1:2014 Formulae (8)-(11): AGMA 925-A03's alpha = k eta^s in SI units; none for
                    esters). It lies 9-39 % below the measured coefficients it is checked against (docs/verdict.md)
  conductivity      k = 0.1172 (1 - 5.4e-4 t)/s_15 W/(m K)        (Cragoe 1929, US Bureau of Standards Misc.
  heat capacity     c = (1685 + 3.39 t)/sqrt(s_15) J/(kg K)         Publ. 97; petroleum oils; s_15 = rho_15/1000)

Each derived value is recorded with its source (`OilDerivation.provenance`); a value the case gives itself wins.
"""

from __future__ import annotations

from dataclasses import dataclass
import math

from facegear_tehl.lubricant import KELVIN
from facegear_tehl.micropitting import ALPHA_REFERENCE, alpha_ratio

# ISO 3448:1992 viscosity grades: the grade number is the midpoint kinematic viscosity at 40 degC in mm^2/s
# (limits +-10 %); VG 22 to VG 1000 are the gear and bearing oils.
ISO_VG_GRADES = (22, 32, 46, 68, 100, 150, 220, 320, 460, 680, 1000)
NU40_TEMPERATURE = 40.0 + KELVIN  # K, ISO 3448 reference temperature
NU100_TEMPERATURE = 100.0 + KELVIN  # K, the second point of ASTM D341 as datasheets give it
# ASTM D341: Z = nu + 0.7 holds for nu >= 2 mm^2/s (below it the standard adds terms of its own).
WALTHER_SHIFT = 0.7  # mm^2/s
WALTHER_LOWEST = 2.0  # mm^2/s
# API MPMS 11.1 (1980) / ASTM D1250 Table 54D (lubricating oils): a_15 = K_0/rho_15^2 + K_1/rho_15, K_0 = 0.
API_LUBE_K1 = 0.6278  # kg/(m^3 K)
DENSITY_REFERENCE = 15.0  # degC
# ISO/TR 15144-1:2014 Formulae (9)-(11), the pressure-viscosity coefficient at 38 degC by base oil: alpha_38 = C
# eta_38^X, (C in 1/Pa at eta_38 = 1 Pa s, X); its temperature factor is micropitting.alpha_ratio (Formula (8)).
# They are AGMA 925-A03's alpha = k eta^s (k in mm^2/N, eta in mPa s) restated: C = k 1e-6 1000^X (test_oils.py).
PRESSURE_VISCOSITY_38 = {"mineral": (2.657e-8, 0.1348), "pao": (1.466e-8, 0.0507), "pag": (1.392e-8, 0.1572)}
ALPHA_REFERENCE_TEMPERATURE = 38.0 + KELVIN  # K, where eta_38 is read
# Cragoe (1929), US Bureau of Standards Misc. Publ. 97, for petroleum oils (t in degC, s_15 specific gravity):
CRAGOE_CONDUCTIVITY = 0.1172  # W/(m K): 0.813 Btu in/(h ft^2 degF)
CRAGOE_CONDUCTIVITY_SLOPE = 5.4e-4  # 1/degC: 0.0003 per degF
CRAGOE_HEAT_CAPACITY = 1685.0  # J/(kg K): 0.4024 Btu/(lb degF) at 0 degC
CRAGOE_HEAT_CAPACITY_SLOPE = 3.39  # J/(kg K degC): 0.00045 Btu/(lb degF^2)
WATER_DENSITY = 1000.0  # kg/m^3, to turn rho_15 into the specific gravity s_15 of Cragoe's formulas
# ASTM D2270-10, Appendix X2, Table X2.1: the nu_40 of the reference oils of VI 0 (L) and VI 100 (H) having the
# oil's nu_100 = Y (mm^2/s), L = a Y^2 + b Y + c and H = d Y^2 + e Y + f from Y = the row's first number up to the
# next row's (the last row, Y > 70, is the standard's own formula for L and H above its Table 1). The quadratics
# reproduce Table 1 within 0.1 % (tests/test_oils.py).
D2270_REFERENCE_OILS = (
    (2.0, 1.14673, 1.7576, -0.109, 0.84155, 1.5521, -0.077),
    (3.8, 3.38095, -15.4952, 33.196, 0.78571, 1.7929, -0.183),
    (4.4, 2.5, -7.2143, 13.812, 0.82143, 1.5679, 0.119),
    (5.0, 0.101, 16.635, -45.469, 0.04985, 9.1613, -18.557),
    (6.4, 3.35714, -23.5643, 78.466, 0.22619, 7.7369, -16.656),
    (7.0, 0.01191, 21.475, -72.87, 0.79762, -0.7321, 14.61),
    (7.7, 0.41858, 16.1558, -56.04, 0.05794, 10.5156, -28.24),
    (9.0, 0.88779, 7.5527, -16.6, 0.26665, 6.7015, -10.81),
    (12.0, 0.7672, 10.7972, -38.18, 0.20073, 8.4658, -22.49),
    (15.0, 0.97305, 5.3135, -2.2, 0.28889, 5.9741, -4.93),
    (18.0, 0.97256, 5.25, -0.98, 0.24504, 7.416, -16.73),
    (22.0, 0.91413, 7.4759, -21.82, 0.20323, 9.1267, -34.23),
    (28.0, 0.87031, 9.7157, -50.77, 0.18411, 10.1015, -46.75),
    (40.0, 0.84703, 12.6752, -133.31, 0.17029, 11.4866, -80.62),
    (55.0, 0.85921, 11.1009, -83.19, 0.1713, 11.368, -76.94),
    (70.0, 0.83531, 14.6731, -216.246, 0.16841, 11.8493, -96.947),
)
D2270_HIGH_INDEX = 0.00715  # ASTM D2270-10 Procedure B: VI = 100 + (antilog N - 1)/0.00715
# The viscosity index assumed for a grade given without nu_100, the typical VI printed on the data sheets of gear
# oils of the base oil (docs/verdict.md, "Oil inputs"): mineral ISO 12925-1 CKD oils 95-98 (ExxonMobil Mobilgear
# 600 XP series: 97), PAO 150-155, PAG 200-220 (Shell Omala S4 WE 220: 203). Esters range too widely (about
# 120-200) for one value: nu100 is required for them.
ASSUMED_VISCOSITY_INDEX = {"mineral": 97.0, "pao": 150.0, "pag": 200.0}
# The density at 15 degC assumed for a grade given without density_15 (kg/m^3), the middle of the data sheets'
# values: mineral gear oils 880-900 (Mobilgear 600 XP 100: 880, 220: 890), PAO 850-870 (Mobil SHC 630: 866),
# PAG 1000-1080 (Shell Omala S4 WE 220: 1074).
ASSUMED_DENSITY_15 = {"mineral": 890.0, "pao": 860.0, "pag": 1060.0}


def grade_viscosity(grade: int) -> float:
    """nu_40 of an ISO 3448 grade, mm^2/s (its midpoint, the grade number); ValueError for another number."""
    if grade not in ISO_VG_GRADES:
        raise ValueError(f"ISO VG {grade} is not one of the grades {ISO_VG_GRADES}")
    return float(grade)


def reference_oils(nu_100: float) -> tuple[float, float]:
    """(L, H): nu_40 of the VI 0 and VI 100 reference oils of this nu_100, mm^2/s (ASTM D2270-10, Table X2.1)."""
    row = next(r for r in reversed(D2270_REFERENCE_OILS) if nu_100 >= r[0])
    _, a, b, c, d, e, f = row
    return a * nu_100**2 + b * nu_100 + c, d * nu_100**2 + e * nu_100 + f


def viscosity_index(nu_40: float, nu_100: float) -> float:
    """ASTM D2270-10 viscosity index of an oil of nu_40, nu_100 (mm^2/s, nu_100 >= 2): Procedure A,
    100 (L - U)/(L - H), where U = nu_40 >= H; Procedure B, 100 + (10^N - 1)/0.00715 with N = log(H/U)/log(nu_100)."""
    low, high = reference_oils(nu_100)
    if nu_40 >= high:
        return 100.0 * (low - nu_40) / (low - high)
    return 100.0 + (10.0 ** (math.log10(high / nu_40) / math.log10(nu_100)) - 1.0) / D2270_HIGH_INDEX


def nu100_for_index(nu_40: float, index: float) -> float:
    """The nu_100 (mm^2/s) at which an oil of nu_40 has the viscosity index `index` (ASTM D2270-10 inverted by
    bisection on log nu_100; the index rises with nu_100 at fixed nu_40). ValueError if it lies below 2 mm^2/s."""
    low, high = math.log(WALTHER_LOWEST), math.log(nu_40)
    if viscosity_index(nu_40, WALTHER_LOWEST) > index:
        raise ValueError(f"an oil of nu_40 = {nu_40:g} mm^2/s and VI {index:g} has nu_100 below "
                         f"{WALTHER_LOWEST:g} mm^2/s, where ASTM D2270 defines no index")
    for _ in range(60):  # 60 halvings of the interval: below 1e-15 relative
        middle = 0.5 * (low + high)
        low, high = (middle, high) if viscosity_index(nu_40, math.exp(middle)) < index else (low, middle)
    return math.exp(0.5 * (low + high))


@dataclass(frozen=True)
class Walther:
    """ASTM D341 viscosity-temperature line log10 log10(nu + 0.7) = a - b log10 T (nu in mm^2/s, T in K)."""

    a: float
    b: float

    @classmethod
    def through(cls, nu_40: float, nu_100: float) -> Walther:
        """The line through nu_40 at 40 degC and nu_100 at 100 degC (mm^2/s, nu_40 > nu_100 >= 2)."""
        w40, w100 = (math.log10(math.log10(nu + WALTHER_SHIFT)) for nu in (nu_40, nu_100))
        b = (w40 - w100) / math.log10(NU100_TEMPERATURE / NU40_TEMPERATURE)
        return cls(w40 + b * math.log10(NU40_TEMPERATURE), b)

    def viscosity(self, temperature: float) -> float:
        """nu(T), mm^2/s; T in K."""
        return 10.0 ** (10.0 ** (self.a - self.b * math.log10(temperature))) - WALTHER_SHIFT

    def log_slope(self, temperature: float) -> float:
        """-d ln(nu)/dT = b (nu + 0.7) ln(nu + 0.7)/(nu T), 1/K; T in K."""
        nu = self.viscosity(temperature)
        return self.b * (nu + WALTHER_SHIFT) * math.log(nu + WALTHER_SHIFT) / (nu * temperature)


def expansion_15(density_15: float) -> float:
    """a_15 = K_1/rho_15, 1/K (API MPMS 11.1 Table 54D, lubricating oils); rho_15 in kg/m^3."""
    return API_LUBE_K1 / density_15


def density_at(density_15: float, temperature: float) -> float:
    """rho(T) = rho_15 exp[-a_15 dt (1 + 0.8 a_15 dt)], kg/m^3; dt = T - 15 degC, T in K."""
    a15, dt = expansion_15(density_15), temperature - KELVIN - DENSITY_REFERENCE
    return density_15 * math.exp(-a15 * dt * (1.0 + 0.8 * a15 * dt))


def thermal_expansion_at(density_15: float, temperature: float) -> float:
    """eps_T = -d ln(rho)/dT = a_15 (1 + 1.6 a_15 dt), 1/K, of `density_at`; T in K."""
    a15, dt = expansion_15(density_15), temperature - KELVIN - DENSITY_REFERENCE
    return a15 * (1.0 + 1.6 * a15 * dt)


def pressure_viscosity(eta_38: float, temperature: float, oil_type: str = "mineral") -> float:
    """alpha(T) = C eta_38^X [1 + 516 K (1/T - 1/311 K)], 1/Pa (ISO/TR 15144-1:2014 Formulae (8)-(11), C and X of
    `PRESSURE_VISCOSITY_38`); eta_38 the dynamic viscosity at 38 degC in Pa s, T in K."""
    coefficient, exponent = PRESSURE_VISCOSITY_38[oil_type]
    return coefficient * eta_38**exponent * alpha_ratio(temperature, ALPHA_REFERENCE)


def cragoe_conductivity(density_15: float, temperature: float) -> float:
    """k = 0.1172 (1 - 5.4e-4 t)/s_15, W/(m K) (Cragoe 1929; petroleum oils); t in degC from T in K."""
    return CRAGOE_CONDUCTIVITY * (1.0 - CRAGOE_CONDUCTIVITY_SLOPE * (temperature - KELVIN)) / (
        density_15 / WATER_DENSITY)


def cragoe_heat_capacity(density_15: float, temperature: float) -> float:
    """c = (1685 + 3.39 t)/sqrt(s_15), J/(kg K) (Cragoe 1929; petroleum oils); t in degC from T in K."""
    return (CRAGOE_HEAT_CAPACITY + CRAGOE_HEAT_CAPACITY_SLOPE * (temperature - KELVIN)) / math.sqrt(
        density_15 / WATER_DENSITY)


@dataclass(frozen=True)
class OilDerivation:
    """The `Lubricant` values derived from nu_40, nu_100 and rho_15 at the inlet temperature (SI), each with the
    line that says where it came from (`provenance`). `pressure_viscosity`, `thermal_conductivity` and
    `specific_heat` are None where no correlation for the oil type is used."""

    viscosity: float  # eta_0, Pa s
    density: float  # rho_0, kg/m^3
    temperature_viscosity: float  # beta, 1/K
    thermal_expansion: float  # eps_T, 1/K
    pressure_viscosity: float | None  # alpha, 1/Pa
    thermal_conductivity: float | None  # W/(m K)
    specific_heat: float | None  # J/(kg K)
    provenance: tuple[str, ...]


def derive(nu_40: float, nu_100: float, density_15: float, temperature: float, oil_type: str,
           source: str, density: float | None = None) -> OilDerivation:
    """The SI inputs of an oil of nu_40, nu_100 (mm^2/s) and rho_15 (kg/m^3) at the inlet temperature T (K);
    `source` says where nu_40 came from (e.g. "ISO VG 100 midpoint"); `density` (kg/m^3 at T) replaces the one
    derived from rho_15 where given. Mineral, PAO and PAG oils get alpha (ISO/TR 15144-1), mineral oils k, c (Cragoe
    1929); esters none of the three."""
    line = Walther.through(nu_40, nu_100)
    nu = line.viscosity(temperature)
    rho = density_at(density_15, temperature) if density is None else density
    eps = thermal_expansion_at(density_15, temperature)
    celsius = temperature - KELVIN
    walther = f"ASTM D341 (Walther) through nu_40 = {nu_40:g} ({source}) and nu_100 = {nu_100:g} mm^2/s"
    provenance = [
        f"viscosity = {nu * 1e-6 * rho:.4g} Pa s: nu = {nu:.4g} mm^2/s at {celsius:g} degC by {walther} "
        f"(B = {line.b:.4g}), times the density",
        f"density = {rho:.4g} kg/m^3 at {celsius:g} degC from rho_15 = {density_15:g} kg/m^3 "
        "(API MPMS 11.1 / ASTM D1250 Table 54D, lubricating oils)",
        f"temperature_viscosity = {line.log_slope(temperature) + eps:.4g} 1/K: -d ln(eta)/dT at {celsius:g} degC "
        "of the Walther line and the density",
        f"thermal_expansion = {eps:.4g} 1/K: -d ln(rho)/dT at {celsius:g} degC (API MPMS 11.1 Table 54D)",
    ]
    alpha = conductivity = heat_capacity = None
    if oil_type in PRESSURE_VISCOSITY_38:
        eta_38 = line.viscosity(ALPHA_REFERENCE_TEMPERATURE) * 1e-6 * density_at(density_15,
                                                                                ALPHA_REFERENCE_TEMPERATURE)
        alpha = pressure_viscosity(eta_38, temperature, oil_type)
        provenance.append(f"pressure_viscosity = {alpha:.4g} 1/Pa: ISO/TR 15144-1 ({oil_type} oils) at eta_38 = "
                          f"{eta_38:.4g} Pa s and {celsius:g} degC")
    if oil_type == "mineral":
        conductivity = cragoe_conductivity(density_15, temperature)
        heat_capacity = cragoe_heat_capacity(density_15, temperature)
        provenance += [
            f"thermal_conductivity = {conductivity:.4g} W/(m K): Cragoe (1929), petroleum oils",
            f"specific_heat = {heat_capacity:.4g} J/(kg K): Cragoe (1929), petroleum oils",
        ]
    beta = line.log_slope(temperature) + eps
    return OilDerivation(viscosity=nu * 1e-6 * rho, density=rho, temperature_viscosity=beta, thermal_expansion=eps,
                         pressure_viscosity=alpha, thermal_conductivity=conductivity, specific_heat=heat_capacity,
                         provenance=tuple(provenance))
