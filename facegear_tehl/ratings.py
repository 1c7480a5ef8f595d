"""The gear standards' scuffing and micropitting ratings of a face gear run (docs/verdict.md, "Scuffing by the
standards", "Micropitting"): ISO/TS 6336-20 (flash temperature), ISO/TS 6336-21 (integral temperature) and
ISO/TS 6336-22 method B (scuffing.py, micropitting.py) applied point by point over the contact analysis' path
samples, each beside the same quantity from the solved TEHL points (bulk + solved surface temperature rise; the
solved h_min). Returns verdict scalars (SI, name -> (value, units)) and the reasons a rating was left out."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
import math

import numpy as np

from facegear_tehl import fzg, micropitting, scuffing
from facegear_tehl.case import Case
from facegear_tehl.heat import GAUSSIAN_RA_PER_RQ
from facegear_tehl.lubricant import KELVIN
from facegear_tehl.materials import reduced_modulus
from facegear_tehl.solution import Field

Scalars = dict[str, tuple[float, str]]
# A solved point this close to the end of the path (in base pitches) is at the pinion tip (cycle.PATH_END_TOLERANCE).
PATH_END = 1e-9


@dataclass(frozen=True)
class PathValues:
    """The contact analysis' path samples (SI arrays in path order) the standards are applied to."""

    s: np.ndarray  # m
    radius: np.ndarray  # R_x, m: the relative radius across the contact (the standards' rho_rel, rho_n)
    unit_load: np.ndarray  # w = pi p_h b/2 = 3F/(4a), N/m: the load per length of the Hertz ellipse's centre line
    half_width: np.ndarray  # b, m: Hertz semi-axis across the contact
    pressure: np.ndarray  # p_h, Pa
    speed_1: np.ndarray  # |u_1|, m/s
    speed_2: np.ndarray  # |u_2|, m/s
    load: np.ndarray  # N
    sliding: np.ndarray  # |u_1 - u_2|, m/s

    @classmethod
    def of(cls, contact: Mapping[str, Field]) -> PathValues:
        order = np.argsort(contact["s"].values)
        col = {name: np.asarray(contact[name].values, dtype=float)[order] for name in
               ("s", "Rx", "load", "a", "b", "p_h", "u1", "u2", "sliding_speed")}
        return cls(s=col["s"], radius=col["Rx"], unit_load=0.75 * col["load"] / col["a"], half_width=col["b"],
                   pressure=col["p_h"], speed_1=np.hypot(*col["u1"].T), speed_2=np.hypot(*col["u2"].T),
                   load=col["load"], sliding=col["sliding_speed"])

    def at_pitch(self, values: np.ndarray) -> float:
        """`values` at the pitch point s = 0 (point C of the standards), interpolated."""
        return float(np.interp(0.0, self.s, values))


def rate(case: Case, contact: Mapping[str, Field], contact_scalars: Mapping[str, tuple[float, str]],
         cycle: Mapping[str, Field]) -> tuple[Scalars, tuple[str, ...]]:
    """The standards' verdict scalars of a gear run and the notes on what was not rated (and why)."""
    lubricant = case.lubricant
    if case.gear is None or "s" not in contact:
        return {}, ()
    notes = []
    path = PathValues.of(contact)
    scalars: Scalars = {}
    oil_factor = scuffing.LUBRICANT_FACTOR.get(lubricant.oil_type)
    ra = GAUSSIAN_RA_PER_RQ * 0.5 * (case.materials.body_1.roughness + case.materials.body_2.roughness)
    if lubricant.fzg_scuffing_stage is None:
        notes.append("scuffing by ISO/TS 6336-20/-21: no lubricant.fzg_scuffing_stage (FZG A/8.3/90) given")
    elif oil_factor is None:
        notes.append(f"scuffing by ISO/TS 6336-20/-21: no lubricant factor X_L for oil_type {lubricant.oil_type}")
    elif ra <= 0.0:
        notes.append("scuffing by ISO/TS 6336-20/-21: the flanks need a roughness (the mean friction reads R_a)")
    else:
        scalars.update(_flash_method(case, path, contact_scalars, cycle, oil_factor, ra))
        scalars.update(_integral_method(case, path, contact_scalars, cycle, oil_factor, ra))
    if lubricant.micropitting_test_film is None and lubricant.micropitting_stage is None:
        notes.append("micropitting by ISO/TS 6336-22: no lubricant.micropitting_stage (FZG GF-C/8.3/90) given")
    elif oil_factor is None or ra <= 0.0:
        notes.append("micropitting by ISO/TS 6336-22: needs a roughness and a lubricant factor X_L for the oil")
    else:
        scalars.update(_micropitting(case, path, contact_scalars, cycle, oil_factor, ra))
    return scalars, tuple(notes)


def _at(law, temperature: float) -> float:
    """A lubricant law (Lubricant.viscosity_at, density_at) at p = 0 and `temperature` (K), as a float."""
    return float(np.ravel(law(0.0, temperature))[0])


def _contact_coefficients(case: Case) -> tuple[float, float]:
    """B_M,i = sqrt(k rho c) of the two flanks, W s^0.5/(m^2 K)."""
    return tuple(math.sqrt(b.thermal_conductivity * b.density * b.specific_heat)
                 for b in (case.materials.body_1, case.materials.body_2))


def _flash(path: PathValues, mu: float, coefficients: tuple[float, float], factor: np.ndarray | float = 1.0
           ) -> np.ndarray:
    """Blok's flash temperature (scuffing.flash_temperature) at every path sample, K."""
    return np.array([scuffing.flash_temperature(mu, w, v1, v2, b, *coefficients) for w, v1, v2, b in zip(
        path.unit_load, path.speed_1, path.speed_2, path.half_width)]) * factor


def _solved_rise(case: Case, cycle: Mapping[str, Field]) -> tuple[np.ndarray, np.ndarray] | None:
    """(s, the larger solved surface temperature rise of the two flanks) at the solved points of a thermal solve, or
    None (as cycle.py's solved contact temperatures)."""
    if case.solver.thermal == "off" or not all(name in cycle for name in ("s", "dT_surface_1_max",
                                                                          "dT_surface_2_max")):
        return None
    return cycle["s"].values, np.maximum(cycle["dT_surface_1_max"].values, cycle["dT_surface_2_max"].values)


def _flash_method(case: Case, path: PathValues, contact_scalars: Mapping[str, tuple[float, str]],
                  cycle: Mapping[str, Field], oil_factor: float, ra: float) -> Scalars:
    """ISO/TS 6336-20 along the path: mu_m at the pitch point, theta_fl(s) with X_J, theta_M, theta_B,max, theta_S
    and S_B; beside them S_B with the solved surface rise on the same theta_M."""
    lub = case.lubricant
    mu = scuffing.mean_friction_flash(path.at_pitch(path.unit_load), path.at_pitch(path.speed_1 + path.speed_2),
                                      path.at_pitch(path.radius), lub.viscosity, ra, oil_factor)
    x_j = scuffing.approach_factor(path.s, contact_scalars["path_start"][0], contact_scalars["path_end"][0],
                                   path.at_pitch(path.unit_load))
    flash = _flash(path, mu, _contact_coefficients(case), x_j)
    bulk = scuffing.flash_bulk_temperature(lub.inlet_temperature, scuffing.path_mean(path.s, flash), lub.lubrication)
    theta_s = scuffing.scuffing_temperature(lub.fzg_scuffing_stage, oil_factor, lub.viscosity)
    found: Scalars = {"mu_flash_method": (mu, "1"), "bulk_temperature_flash": (bulk, "K"),
                      "contact_temperature_flash_max": (bulk + float(flash.max()), "K"),
                      "contact_temperature_flash_max_s": (float(path.s[np.argmax(flash)]), "m"),
                      "scuffing_temperature_fzg": (theta_s, "K")}
    safety = scuffing.flash_safety(theta_s, lub.inlet_temperature, bulk + float(flash.max()))
    if safety is not None:
        found["scuffing_safety_flash"] = (safety, "1")
    solved = _solved_rise(case, cycle)
    if solved is not None:
        hottest = bulk + float(solved[1].max())
        found["contact_temperature_flash_solved_max"] = (hottest, "K")
        safety = scuffing.flash_safety(theta_s, lub.inlet_temperature, hottest)
        if safety is not None:
            found["scuffing_safety_flash_solved"] = (safety, "1")
    return found


def _integral_method(case: Case, path: PathValues, contact_scalars: Mapping[str, tuple[float, str]],
                     cycle: Mapping[str, Field], oil_factor: float, ra: float) -> Scalars:
    """ISO/TS 6336-21 along the path: mu_mC, theta_flaE at the pinion tip (the path's end) under the pair's whole load,
    theta_fla,int = theta_flaE X_eps/X_Q, theta_int, theta_intS, S_intS; beside them the same with the solved surface
    rise at the solved point at the path's end (S5) in place of theta_flaE, both brought to the whole load by the
    standard's w^0.75 (the tip carries the share K of it)."""
    lub = case.lubricant
    mu = scuffing.mean_friction_integral(path.at_pitch(path.unit_load), path.at_pitch(path.speed_1 + path.speed_2),
                                         path.at_pitch(path.radius), lub.viscosity, ra, oil_factor)
    base_pitch, normal_load = contact_scalars["base_pitch"][0], contact_scalars["normal_load"][0]
    weight = (scuffing.contact_ratio_factor(float(path.s[-1]) / base_pitch, -float(path.s[0]) / base_pitch)
              / scuffing.approach_recess_factor(float(path.s[0]), float(path.s[-1])))
    tip = _flash(path, mu, _contact_coefficients(case))[-1] * (normal_load / path.load[-1]) ** 0.75
    nu_40 = _at(lub.viscosity_at, 40.0 + KELVIN) / _at(lub.density_at, 40.0 + KELVIN)
    theta_int_s = scuffing.integral_scuffing_temperature(lub.fzg_scuffing_stage, oil_factor, nu_40)
    _, theta_int = scuffing.integral_temperature(lub.inlet_temperature, tip * weight, lub.lubrication)
    found: Scalars = {"mu_integral_method": (mu, "1"), "tip_flash_temperature": (tip, "K"),
                      "integral_flash_temperature": (tip * weight, "K"),
                      "integral_temperature": (theta_int, "K"), "scuffing_integral_temperature": (theta_int_s, "K"),
                      "scuffing_safety_integral": (scuffing.integral_safety(theta_int_s, theta_int), "1")}
    solved = _solved_rise(case, cycle)
    if solved is not None and abs(solved[0][-1] - path.s[-1]) <= PATH_END * base_pitch:  # the tip is solved
        tip_solved = float(solved[1][-1]) / float(cycle["load_share"].values[-1]) ** 0.75
        _, theta_solved = scuffing.integral_temperature(lub.inlet_temperature, tip_solved * weight, lub.lubrication)
        found["integral_temperature_solved"] = (theta_solved, "K")
        found["scuffing_safety_integral_solved"] = (scuffing.integral_safety(theta_int_s, theta_solved), "1")
    return found


def _test_film(case: Case, oil_factor: float) -> float:
    """lambda_GFT: given, or of the FZG C-type gear at the oil's GF-C/8.3/90 failure stage (fzg.failure_film) with
    the case's viscosity law and alpha_38 = alpha(T_0) scaled by ISO/TR 15144-1 Formula (8)."""
    lub = case.lubricant
    if lub.micropitting_test_film is not None:
        return lub.micropitting_test_film
    alpha_38 = lub.pressure_viscosity * micropitting.alpha_ratio(micropitting.ALPHA_REFERENCE, lub.inlet_temperature)
    return fzg.failure_film(lub.micropitting_stage, lambda t: _at(lub.viscosity_at, t), alpha_38, oil_factor)


def _micropitting(case: Case, path: PathValues, contact_scalars: Mapping[str, tuple[float, str]],
                  cycle: Mapping[str, Field], oil_factor: float, ra: float) -> Scalars:
    """ISO/TS 6336-22 method B along the path: lambda_GF(s) = h_Y/Ra, its minimum and where, lambda_GFP, S_lambda;
    beside them lambda from the solved h_min (over the solved points) against the same lambda_GFP."""
    lub, gear = case.lubricant, case.gear
    mu = scuffing.mean_friction_integral(path.at_pitch(path.unit_load), path.at_pitch(path.speed_1 + path.speed_2),
                                         path.at_pitch(path.radius), lub.viscosity, ra, oil_factor, min_load=0.0)
    loss = mu * float(np.trapezoid(path.load * path.sliding, path.s)) / contact_scalars["base_pitch"][0]
    centre_distance = gear.module * gear.pinion_teeth / 2.0 + contact_scalars["face_gear_pitch_radius"][0]
    bulk = micropitting.bulk_temperature(lub.inlet_temperature, loss, centre_distance,
                                         gear.outer_radius - gear.inner_radius,
                                         scuffing.LUBRICATION_FACTOR[lub.lubrication])
    e_r = reduced_modulus(case.materials.body_1, case.materials.body_2)
    alpha_bulk = lub.pressure_viscosity * micropitting.alpha_ratio(bulk, lub.inlet_temperature)
    eta_bulk = _at(lub.viscosity_at, bulk)
    coefficients = _contact_coefficients(case)
    films = []
    for i in range(len(path.s)):
        rise = micropitting.flash_temperature(mu, path.pressure[i], path.speed_1[i], path.speed_2[i],
                                              path.half_width[i], *coefficients)
        sliding = micropitting.sliding_parameter(alpha_bulk * micropitting.alpha_ratio(bulk + rise, bulk),
                                                 _at(lub.viscosity_at, bulk + rise), alpha_bulk, eta_bulk)
        films.append(micropitting.film_thickness(path.radius[i], path.speed_1[i] + path.speed_2[i], path.pressure[i],
                                                 e_r, alpha_bulk, eta_bulk, sliding))
    lambdas = np.array(films) / ra
    permissible = micropitting.permissible_film(_test_film(case, oil_factor))
    found: Scalars = {"mu_micropitting": (mu, "1"), "bulk_temperature_micropitting": (bulk, "K"),
                      "lambda_gf_min": (float(lambdas.min()), "1"), "lambda_gf_min_s": (float(path.s[np.argmin(
                          lambdas)]), "m"), "lambda_gfp": (permissible, "1"),
                      "micropitting_safety": (float(lambdas.min()) / permissible, "1")}
    if "h_min" in cycle:
        solved = float(np.min(cycle["h_min"].values)) / ra
        found["lambda_gf_min_solved"] = (solved, "1")
        found["micropitting_safety_solved"] = (solved / permissible, "1")
    return found
