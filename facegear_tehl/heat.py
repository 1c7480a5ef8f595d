"""Friction and heat budget of one meshing point: friction formulas, frictional heat power, its partition
between the two bodies, flash temperature, steady-state duty ratio and oil-film heat (SI units).

Formulas (docs/method.md §6):
  Xu, Kahraman, Anderson & Maddock (2007):  mu = exp(f) P_h^b2 |SR|^b3 V_e^b6 nu_0^b7 R^b8,
      f = b1 + b4 |SR| P_h log10(nu_0) + b5 exp(-|SR| P_h log10(nu_0)) + b9 exp(S)
  ISO/TR 14179-2 (Schlenk 1994):  mu_mz = 0.048 (F_bt/b / (v_sum rho_red))^0.2 eta^-0.05 R_a^0.25 X_L
  friction power P = mu F v_s;  Blok/Jaeger partition gamma_i = B_i/(B_1 + B_2), B_i = sqrt(k_i rho_i c_i u_i)
  Blok (1937) flash temperature dT_f = C q_0 sqrt(b)/(B_1 + B_2) with Jaeger's (1942) high-Péclet kernel
  Tian & Kennedy (1994) circular source;  Péclet number Pe = u b/(2 kappa)
  duty ratio t_c/T = b/(pi r) with t_c = 2b/v_t, T = 60/n;  Q_oil = sum c rho h dT dx dy;  Q_f = P t_c
  (the seed paper's Q_f = mu F |v_s| t_c; the film's own dissipation over the Hertz ellipse, P_film t_c)
"""

from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from facegear_tehl.materials import Solid

# Xu, Kahraman, Anderson & Maddock (2007), J. Mech. Des. 129(1):58-68: regression coefficients b1..b9
# (the published magnitudes with their signs applied).
XU_COEFFICIENTS = (
    -8.916465,  # b1
    1.03303,  # b2, exponent of P_h (GPa)
    1.036077,  # b3, exponent of |SR|
    -0.354068,  # b4
    2.812084,  # b5
    -0.100601,  # b6, exponent of V_e (m/s)
    0.752755,  # b7, exponent of nu_0 (mPa s)
    -0.390958,  # b8, exponent of R (m)
    0.620305,  # b9, factor of exp(S), S in micrometres
)

# ISO/TR 14179-2 (Schlenk 1994) oil-type factor X_L as used by Fernandes' GEARpie `CONTACT.py`
# (Fernandes et al. 2015, Tribol. Int. 88:309-316); ISO/TR's own table has 1.0 for mineral oil and lower values
# for synthetics.
ISO_TR_14179_OIL_FACTOR = {"mineral": 0.846, "pao": 0.65, "ester": 0.65, "pag": 0.585}
# R_a / R_q of a surface with Gaussian heights: the mean absolute deviation of a normal distribution, sqrt(2/pi) of
# its standard deviation (Thomas 1999, Rough Surfaces, 2nd ed.: R_a ~ 0.8 R_q); turns the case's RMS roughness R_q
# into the arithmetic mean roughness R_a that ISO/TR 14179-2 asks for.
GAUSSIAN_RA_PER_RQ = math.sqrt(2.0 / math.pi)

# Maximum of Jaeger's (1942) high-Péclet kernel over a band of half-width b, in units of q0 sqrt(b)/B
# (Jaeger 1942, Proc. R. Soc. N.S.W. 76:203-224): uniform flux q0 -> 2 sqrt(2/pi) at the trailing edge
# (closed form);
# semi-elliptical flux q0 sqrt(1 - x^2/b^2) -> 1.2346198 at x = +0.6522 b (quadrature; quoted 1.23462).
FLASH_PEAK_COEFFICIENT = {"semi_elliptical": 1.2346198, "uniform": 2.0 * math.sqrt(2.0 / math.pi)}
# Blok (1937) line-contact coefficient with a semi-elliptical flux, p0 = 2w'/(pi b): 1.2346198 * 2/pi
# = 0.7860 (Blok 1937, Proc. Gen. Disc. Lubrication, IMechE 2:222-235); times sqrt(2) it is Blok's classical
# 1.11 for the full width 2b.
BLOK_LINE_COEFFICIENT = FLASH_PEAK_COEFFICIENT["semi_elliptical"] * 2.0 / math.pi
BLOK_SAME_MATERIAL_COEFFICIENT = BLOK_LINE_COEFFICIENT * math.sqrt(2.0)

# Tian & Kennedy (1994), J. Tribol. 116:167-174, uniform circular source: constants of the
# Péclet-number fits of the maximum and mean surface temperature (constants as usually quoted; their Pe -> 0
# and Pe -> inf limits are checked against the exact values in tests/test_heat.py).
TIAN_KENNEDY_MAX_OFFSET = 1.273
TIAN_KENNEDY_MEAN_FACTOR = 1.22
TIAN_KENNEDY_MEAN_OFFSET = 0.6575


def xu_friction(
    srr: float, p_h: float, viscosity: float, entrainment_speed: float, radius: float, roughness: float
) -> float:
    """Friction coefficient of Xu, Kahraman, Anderson & Maddock (2007), -.

    mu = exp(f) P_h^b2 |SR|^b3 V_e^b6 nu_0^b7 R^b8,
    f  = b1 + b4 |SR| P_h log10(nu_0) + b5 exp(-|SR| P_h log10(nu_0)) + b9 exp(S)

    Arguments in SI; the regression's own units are applied inside:
    srr: slide-to-roll ratio SR = |u1 - u2| / ((u1 + u2)/2), -.
    p_h: maximum Hertz pressure, Pa (formula: GPa).
    viscosity: dynamic viscosity at the inlet temperature, Pa s (formula: nu_0 in mPa s).
    entrainment_speed: V_e = (u1 + u2)/2, m/s.
    radius: effective radius of curvature R, m (formula: m).
    roughness: composite RMS roughness S, m (formula: micrometres).
    """
    if p_h <= 0.0 or viscosity <= 0.0 or entrainment_speed <= 0.0 or radius <= 0.0 or roughness < 0.0:
        raise ValueError("Xu friction needs positive p_h, viscosity, entrainment speed, radius and roughness >= 0")
    b1, b2, b3, b4, b5, b6, b7, b8, b9 = XU_COEFFICIENTS
    sr = abs(srr)
    p_gpa = p_h * 1e-9
    nu_mpas = viscosity * 1e3
    s_um = roughness * 1e6
    group = sr * p_gpa * math.log10(nu_mpas)
    f = b1 + b4 * group + b5 * math.exp(-group) + b9 * math.exp(s_um)
    return (
        math.exp(f) * p_gpa**b2 * sr**b3 * entrainment_speed**b6 * nu_mpas**b7 * radius**b8
    )


def iso_tr_14179_friction(
    load_per_width: float,
    sum_velocity: float,
    reduced_radius: float,
    viscosity: float,
    roughness: float,
    oil_factor: float,
) -> float:
    """Mean gear friction coefficient of ISO/TR 14179-2 (Schlenk 1994), -; a plausibility cross-check.

    mu_mz = 0.048 (F_bt/b / (v_sum rho_red))^0.2 eta_oil^-0.05 R_a^0.25 X_L, with the formula's units
    F_bt/b in N/mm, v_sum in m/s, rho_red in mm, eta_oil in mPa s, R_a in micrometres.
    Arguments in SI, converted inside:
    load_per_width: transverse tangential load per face width F_bt/b, N/m.
    sum_velocity: sum of the tangential velocities at the pitch point v_sum, m/s.
    reduced_radius: reduced radius of curvature at the pitch point rho_red, m.
    viscosity: dynamic viscosity at the oil temperature, Pa s.
    roughness: mean arithmetic roughness R_a, m.
    oil_factor: lubricant factor X_L, - (see ISO_TR_14179_OIL_FACTOR).
    It is a mesh-averaged value for a whole gear pair, not a local one: compare it with the mean of
    the per-point coefficients along the path of contact.
    """
    if min(load_per_width, sum_velocity, reduced_radius, viscosity, oil_factor) <= 0.0 or roughness < 0.0:
        raise ValueError("ISO/TR 14179-2 friction needs positive inputs (roughness >= 0)")
    load_n_per_mm = load_per_width * 1e-3
    radius_mm = reduced_radius * 1e3
    return (
        0.048
        * (load_n_per_mm / (sum_velocity * radius_mm)) ** 0.2
        * (viscosity * 1e3) ** -0.05
        * (roughness * 1e6) ** 0.25
        * oil_factor
    )


@dataclass(frozen=True)
class HeatPartition:
    """Share of the frictional heat entering each body (Blok 1937; Jaeger 1942, high Péclet number)."""

    gamma_1: float  # -, share of body 1
    gamma_2: float  # -, share of body 2, 1 - gamma_1
    effusivity_1: float  # B_1 = sqrt(k_1 rho_1 c_1 |u_1|), W s^0.5/(m^2 K) (m/s)^0.5
    effusivity_2: float  # B_2


def heat_partition(body_1: Solid, body_2: Solid, u1: float, u2: float) -> HeatPartition:
    """Blok/Jaeger partition gamma_i = B_i / (B_1 + B_2), B_i = sqrt(k_i rho_i c_i |u_i|).

    It makes the maximum flash temperatures of both surfaces equal when both see the same flux shape.
    u1, u2: surface speeds relative to the contact along the direction of motion, m/s.
    For equal materials gamma_1 = 1/(1 + sqrt(u2/u1)).
    """
    effusivity_1 = body_1.thermal_effusivity_speed(u1)
    effusivity_2 = body_2.thermal_effusivity_speed(u2)
    total = effusivity_1 + effusivity_2
    if total <= 0.0:
        raise ValueError("heat partition undefined: both surfaces are at rest relative to the contact")
    gamma_1 = effusivity_1 / total
    return HeatPartition(gamma_1=gamma_1, gamma_2=effusivity_2 / total, effusivity_1=effusivity_1,
                         effusivity_2=effusivity_2)


def blok_flash_temperature_line(
    mu: float,
    load_per_length: float,
    sliding_speed: float,
    b: float,
    effusivity_1: float,
    effusivity_2: float,
    flux_shape: str = "semi_elliptical",
) -> float:
    """Blok (1937) flash temperature of a line contact, K: dT_f = C q_0 sqrt(b) / (B_1 + B_2).

    Semi-elliptical flux q_0 sqrt(1 - x^2/b^2), q_0 = mu p_0 |v_s|, p_0 = 2 w'/(pi b): C = 1.2346, so
    dT_f = 0.7860 mu w' |v_s| / (sqrt(b) (B_1 + B_2)).  Uniform flux carrying the same heat,
    q = mu w' |v_s| / (2b): C = 1.5958.  C is the maximum of Jaeger's (1942) high-Péclet kernel.
    load_per_length: w', N/m; sliding_speed: v_s = u1 - u2, m/s; b: Hertz half-width along the
    motion, m; effusivity_i: B_i = sqrt(k_i rho_i c_i |u_i|) (`HeatPartition`).
    """
    if flux_shape not in FLASH_PEAK_COEFFICIENT:
        raise ValueError(f"flux_shape must be one of {sorted(FLASH_PEAK_COEFFICIENT)}, got {flux_shape!r}")
    heat_per_length = mu * load_per_length * abs(sliding_speed)  # W/m
    if flux_shape == "semi_elliptical":
        peak_flux = 2.0 * heat_per_length / (math.pi * b)
    else:
        peak_flux = heat_per_length / (2.0 * b)
    return FLASH_PEAK_COEFFICIENT[flux_shape] * peak_flux * math.sqrt(b) / (effusivity_1 + effusivity_2)


def blok_flash_temperature(
    mu: float,
    load: float,
    sliding_speed: float,
    b: float,
    a: float,
    effusivity_1: float,
    effusivity_2: float,
    flux_shape: str = "semi_elliptical",
) -> float:
    """Blok flash temperature of an elliptical point contact on its centre line (y = 0), K.

    p_0 = 3W/(2 pi a b), so the centre line carries the equivalent line load w' = pi p_0 b/2 = 3W/(4a);
    dT_f = C q_0 sqrt(b)/(B_1 + B_2) with q_0 = mu p_0 |v_s| and C = 1.2346 (semi-elliptical flux), or
    the uniform flux of the same centre-line heat with C = 1.5958 (`blok_flash_temperature_line`).
    load: W, N; b: semi-axis along the motion, m; a: the other semi-axis, m.
    """
    return blok_flash_temperature_line(
        mu, 3.0 * load / (4.0 * a), sliding_speed, b, effusivity_1, effusivity_2, flux_shape
    )


def blok_flash_temperature_same_material(
    mu: float, load_per_length: float, u1: float, u2: float, b: float, solid: Solid
) -> float:
    """Blok's (1937) classical form for two bodies of one material, line contact, K.

    dT_f = 1.11 mu w' |sqrt(u1) - sqrt(u2)| / (beta sqrt(2b)),  beta = sqrt(k rho c),
    with 1.11 = 0.7860 sqrt(2) (BLOK_SAME_MATERIAL_COEFFICIENT) and 2b the full Hertzian width.
    u1, u2: surface speeds relative to the contact, m/s (same sign).
    """
    beta = math.sqrt(solid.thermal_conductivity * solid.density * solid.specific_heat)
    root_difference = abs(math.sqrt(abs(u1)) - math.sqrt(abs(u2)))
    return BLOK_SAME_MATERIAL_COEFFICIENT * mu * load_per_length * root_difference / (beta * math.sqrt(2.0 * b))


def peclet_number(u: float, b: float, solid: Solid) -> float:
    """Pe = |u| b / (2 kappa), kappa = k/(rho c) (Jaeger 1942; Tian & Kennedy 1994), -.

    u: surface speed relative to the contact, m/s; b: half-width along the motion, m.
    """
    return abs(u) * b / (2.0 * solid.thermal_diffusivity)


def friction_power(mu: float, load: float, sliding_speed: float) -> float:
    """Instantaneous frictional heat power P = mu F |v_s|, W."""
    return mu * load * abs(sliding_speed)


def distribute_by_pressure(power: float, pressure: np.ndarray) -> np.ndarray:
    """Heat power per grid cell P p_ij / sum(p), W, in proportion to the local pressure (seed paper §3.4)."""
    pressure = np.asarray(pressure, dtype=float)
    total = pressure.sum()
    if not total > 0.0:
        raise ValueError("pressure field carries no load")
    return power * (pressure / total)


def distribute_by_shear_power(
    tau_x: np.ndarray,
    tau_y: np.ndarray,
    sliding_x: float | np.ndarray,
    sliding_y: float | np.ndarray,
    dx: float,
    dy: float,
) -> np.ndarray:
    """Heat power per grid cell from the local shear-stress power (tau_x v_x + tau_y v_y) dx dy, W.

    tau_x, tau_y: film shear stress, Pa, signed so that it does positive work on the sliding velocity
    (Couette shear: tau = eta (u1 - u2)/h with sliding = u1 - u2); sliding_x, sliding_y: u1 - u2, m/s,
    scalars or fields; dx, dy: grid spacing, m.  Its sum is the film's friction power mu_film F v_s.
    """
    flux = np.asarray(tau_x, dtype=float) * sliding_x + np.asarray(tau_y, dtype=float) * sliding_y
    return flux * (dx * dy)


@dataclass(frozen=True)
class DutyCycle:
    """Contact dwell and rotation period of a gear surface point (seed paper §3.4; docs/method.md §6)."""

    tangential_speed: float  # v_t = omega r, m/s
    dwell: float  # t_c = 2b / v_t, s
    period: float  # T = 60 / n, s

    @property
    def ratio(self) -> float:
        """t_c / T, - (equals b/(pi r))."""
        return self.dwell / self.period


def duty_cycle(b: float, radius: float, speed_rpm: float) -> DutyCycle:
    """Dwell t_c = 2b/v_t of a surface point in the contact and the period T = 60/n of its gear.

    b: contact half-width along the tangential motion, m; radius: r of the point, m; speed_rpm: n, 1/min.
    """
    if b <= 0.0 or radius <= 0.0 or speed_rpm <= 0.0:
        raise ValueError("duty cycle needs positive b, radius and speed")
    tangential_speed = 2.0 * math.pi * speed_rpm / 60.0 * radius
    return DutyCycle(tangential_speed=tangential_speed, dwell=2.0 * b / tangential_speed, period=60.0 / speed_rpm)


def duty_ratio(b: float, radius: float) -> float:
    """t_c / T = b / (pi r), -: independent of the speed (t_c = 2b/(omega r), T = 2 pi/omega)."""
    return b / (math.pi * radius)


def steady_state_power(power: float, b: float, radius: float) -> float:
    """Time-averaged heat power of a gear, P_ss = P_i t_c/T = P_i b/(pi r), W (P_i its share, W)."""
    return power * duty_ratio(b, radius)


def oil_film_heat(
    rho_c: float | np.ndarray, film: np.ndarray, temperature_rise: np.ndarray, dx: float, dy: float
) -> float:
    """Heat absorbed by the oil film Q_oil = sum_ij c rho_ij h_ij dT_ij dx dy, J.

    rho_c: volumetric heat capacity rho c, J/(m^3 K), scalar or field; film: h, m;
    temperature_rise: film temperature above the inlet, K; dx, dy: grid spacing, m.
    """
    return float(np.sum(np.asarray(rho_c, dtype=float) * film * temperature_rise) * dx * dy)


def frictional_heat(power: float, dwell: float) -> float:
    """Frictional heat of one meshing point Q_f = P t_c, J (power P in W, dwell t_c in s)."""
    return power * dwell


def seed_frictional_heat(mu: float, load: float, sliding_speed: float, dwell: float) -> float:
    """Frictional heat of one meshing point as the seed paper defines it (§3.5), Q_f = mu F |v_s| t_c, J:
    the friction power of the sliding alone, zero at the pitch point (v_s = 0). mu: friction coefficient;
    load F, N; sliding_speed v_s, m/s; dwell t_c, s."""
    return frictional_heat(friction_power(mu, load, sliding_speed), dwell)


def in_hertz_ellipse(x: np.ndarray, y: np.ndarray, a: float, b: float) -> np.ndarray:
    """Nodes (ny, nx) of a grid with node coordinates x (nx,) and y (ny,), m, on or inside the Hertz ellipse
    (x/b)^2 + (y/a)^2 <= 1 centred on the contact (b: semi-axis along x, a: along y, m)."""
    return (np.asarray(x)[None, :] / b) ** 2 + (np.asarray(y)[:, None] / a) ** 2 <= 1.0


def power_in_region(power_density: np.ndarray, region: np.ndarray, dx: float, dy: float) -> float:
    """Power of a density per unit area (W/m^2, (ny, nx)) summed over the nodes of `region` (a boolean mask
    of the same shape), each node standing for its cell dx dy (m^2), W."""
    return float(np.sum(np.asarray(power_density, dtype=float) * region) * dx * dy)


@dataclass(frozen=True)
class CircularSourceTemperature:
    """Surface temperature rise under a uniform circular heat source, K."""

    maximum: float
    mean: float


def tian_kennedy_circular(q: float, a: float, k: float, pe: float) -> CircularSourceTemperature:
    """Tian & Kennedy (1994) fits for a uniform circular source of radius a moving at any Péclet number.

    theta_max = 2 q a / (k sqrt(pi (1.273 + Pe))),  theta_mean = 1.22 q a / (k sqrt(pi (0.6575 + Pe)))
    q: flux, W/m^2; a: radius, m; k: conductivity of the solid, W/(m K); pe: u a/(2 kappa), -.
    Limits: Pe -> 0 gives q a/k and 8/(3 pi) q a/k (stationary disc); Pe -> inf the 1-D high-Péclet values.
    """
    if pe < 0.0:
        raise ValueError(f"Péclet number must be >= 0, got {pe}")
    scale = q * a / k
    maximum = 2.0 * scale / math.sqrt(math.pi * (TIAN_KENNEDY_MAX_OFFSET + pe))
    mean = TIAN_KENNEDY_MEAN_FACTOR * scale / math.sqrt(math.pi * (TIAN_KENNEDY_MEAN_OFFSET + pe))
    return CircularSourceTemperature(maximum=maximum, mean=mean)
