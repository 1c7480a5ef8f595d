"""Friction and heat budget of each meshing point (seed paper §3.3-3.5; formulas in heat.py, docs/method.md §6).

From a solved point (the thermal / Ree-Eyring film's friction coefficient mu, temperatures and stresses):
- Xu et al. (2007) empirical friction coefficient, next to the computed one;
- frictional heat power P = mu F |v_s|, its Blok/Jaeger partition gamma_i between the bodies, P_i = gamma_i P;
- the distribution of P over the contact in proportion to the pressure (seed paper) and to the local shear
  power tau . v_s (tau: mean of the two surface stresses), with the share of P they place differently,
  1/2 sum |q_p - q_s| dA / P;
- gear cases: steady-state heat power per gear P_ss,i = P_i t_c/T with the duty ratio t_c/T = b/(pi r_i);
- Blok's flash temperature (semi-elliptical flux), next to the largest surface temperature rise solved;
- dwell t_c = 2b/|U_e|, and the frictional heat of the meshing point three ways: as the seed paper defines it
  (§3.5), Q_f,seed = mu F |v_s| t_c (the sliding's friction power: zero at the pitch point, where v_s = 0); the
  film's own dissipation inside the Hertz ellipse, Q_f,ellipse = P_film,ellipse t_c (sliding and rolling
  traction: non-zero at the pitch point); and over the whole domain, Q_f = P_film t_c (it includes the heat
  dissipated in the inlet's back flow, so it grows with the inlet length); the heat held by the oil film in the
  Hertz ellipse Q_oil = sum c rho h dT_mean dA (and over the whole domain), and the ratios of Q_oil to each
  Q_f. The in-ellipse figures are the ones the seed's ratio (about 1 %) can be compared with. On the default
  case (257 x 65) Q_oil/Q_f,ellipse is 5.9 / 7.0 / 10.3 / 9.3 / 14.9 % at S1..S5 and Q_oil/Q_f,seed 6.2 / 8.5 /
  - / 15.0 / 20.4 %. Lengthening the inlet from 4.5 b to 10.5 b at equal spacing (513 x 65) changes
  Q_oil/Q_f,ellipse by +4.0 % at S1 and +8.7 % at S5 (Q_oil/Q_f,seed +4.3 %, +14 %; the whole-domain Q_oil/Q_f
  by -8 % and -33 %): at S5 the film in the ellipse itself changes with the inlet (mu -20 %, h_c +4.3 %,
  dT_max -8.5 %; the energy equation before issue 19 showed the same, mu -17 %), which no definition of the
  ratio removes.
"""

from __future__ import annotations

from dataclasses import replace
import math

import numpy as np

from facegear_tehl import heat
from facegear_tehl.contact import ContactPoint
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.solution import Field, PointSolution

# The seed's Q_f = mu F |v_s| t_c counts as zero below this share of the film's own in-ellipse heat: at the pitch
# point |v_s| is a round-off residue (Q_f,seed/Q_f,ellipse = 6e-17 at S3 of the default case), and Q_oil/Q_f,seed
# would be a meaningless 1e15; the smallest share of a sliding point there is 0.62 (S4).
SEED_HEAT_FLOOR = 1e-6

# /heat table columns: name -> (units, description)
COLUMNS = {
    "mu": ("1", "friction coefficient of the solved film (Ree-Eyring, thermal)"),
    "mu_xu": ("1", "empirical friction coefficient, Xu, Kahraman, Anderson & Maddock (2007)"),
    "sliding_speed": ("m/s", "|u_1 - u_2|"),
    "friction_power": ("W", "frictional heat power P = mu F |v_s|"),
    "partition_1": ("1", "share of P into body 1 (pinion), Blok/Jaeger gamma_1"),
    "partition_2": ("1", "share of P into body 2 (face gear), gamma_2"),
    "friction_power_1": ("W", "frictional heat power into body 1, gamma_1 P"),
    "friction_power_2": ("W", "frictional heat power into body 2, gamma_2 P"),
    "duty_ratio_1": ("1", "t_c/T = b/(pi r_1) of body 1"),
    "duty_ratio_2": ("1", "t_c/T = b/(pi r_2) of body 2"),
    "steady_power_1": ("W", "steady-state heat power of body 1, P_1 b/(pi r_1)"),
    "steady_power_2": ("W", "steady-state heat power of body 2, P_2 b/(pi r_2)"),
    "flash_temperature": ("K", "Blok flash temperature, semi-elliptical flux on the centre line"),
    "surface_rise_max": ("K", "largest surface temperature rise of the solved film, either body"),
    "dissipated_power": ("W", "power dissipated by shear in the solved film (sliding and rolling traction)"),
    "dissipated_power_ellipse": ("W", "power dissipated by shear in the solved film inside the Hertz ellipse"),
    "dwell_time": ("s", "t_c = 2b/|U_e|"),
    "frictional_heat": ("J", "frictional heat of the meshing point Q_f = P_film t_c (film dissipation over the "
                             "whole domain, inlet included)"),
    "frictional_heat_seed": ("J", "frictional heat as the seed paper defines it, Q_f,seed = mu F |v_s| t_c "
                                  "(zero at the pitch point)"),
    "frictional_heat_ellipse": ("J", "the film's own frictional heat in the Hertz ellipse, Q_f,ellipse = "
                                     "P_film,ellipse t_c"),
    "oil_film_heat": ("J", "heat held by the oil film in the Hertz ellipse, Q_oil = sum c rho h dT dA"),
    "oil_film_heat_domain": ("J", "the same summed over the whole computational domain (inlet included)"),
    "oil_to_friction_ratio": ("1", "Q_oil/Q_f (Q_f over the whole domain)"),
    "oil_to_seed_friction_ratio": ("1", "Q_oil/Q_f,seed (left out where there is no sliding: Q_f,seed = 0)"),
    "oil_to_ellipse_friction_ratio": ("1", "Q_oil/Q_f,ellipse: oil-film heat and film dissipation in the same "
                                           "Hertz ellipse"),
    "distribution_difference": ("1", "share of P placed differently by the pressure and shear-power distributions"),
}


def point_budget(point: ContactPoint, solution: PointSolution, lubricant: Lubricant
                 ) -> tuple[dict[str, float], dict[str, Field]]:
    """The budget of one solved point: (values of COLUMNS, SI; heat flux fields). Needs `mu` and the film state
    (fields temperature_mean and dissipation_column)."""
    values = _friction_values(point, solution, lubricant)
    values.update(_film_heat(point, solution, lubricant))
    difference, fields = _heat_distributions(point, solution, values["friction_power"])
    values["distribution_difference"] = difference
    return values, fields


def _friction_values(point: ContactPoint, solution: PointSolution, lubricant: Lubricant) -> dict[str, float]:
    """Friction (the film's mu and Xu et al.'s), its power, its partition between the solids, their duty ratios and
    steady-state powers, Blok's flash temperature and the largest solved surface temperature rise."""
    sc = solution.scalars
    mu = sc["mu"][0]
    b, a = sc["b"][0], sc["a"][0]
    u1, u2 = float(np.hypot(*point.velocity_1)), float(np.hypot(*point.velocity_2))
    roughness = math.hypot(point.body_1.roughness, point.body_2.roughness)
    values = {
        "mu": mu,
        "mu_xu": heat.xu_friction(abs(point.slide_roll_ratio), sc["p_hertz"][0], lubricant.viscosity,
                                  point.entrainment_speed, point.radius_x, roughness),
        "sliding_speed": point.sliding_speed,
    }
    power = heat.friction_power(mu, point.load, point.sliding_speed)
    share = heat.heat_partition(point.body_1, point.body_2, u1, u2)
    values.update({
        "friction_power": power,
        "partition_1": share.gamma_1,
        "partition_2": share.gamma_2,
        "friction_power_1": share.gamma_1 * power,
        "friction_power_2": share.gamma_2 * power,
    })
    for body, radius in ((1, point.rotation_radius_1), (2, point.rotation_radius_2)):
        if math.isfinite(radius):
            values[f"duty_ratio_{body}"] = heat.duty_ratio(b, radius)
            values[f"steady_power_{body}"] = heat.steady_state_power(values[f"friction_power_{body}"], b, radius)
    values["flash_temperature"] = heat.blok_flash_temperature(
        mu, point.load, point.sliding_speed, b, a,
        point.body_1.thermal_effusivity_speed(u1), point.body_2.thermal_effusivity_speed(u2))
    if "dT_surface_1_max" in sc and "dT_surface_2_max" in sc:  # (a thermal model's: an isothermal film has none)
        values["surface_rise_max"] = max(sc["dT_surface_1_max"][0], sc["dT_surface_2_max"][0])
    return values


def _film_heat(point: ContactPoint, solution: PointSolution, lubricant: Lubricant) -> dict[str, float]:
    """The heat the film dissipates during the dwell time 2b/u_e (over the domain, the Hertz ellipse, and the
    seed's mu F v_s), the heat the oil film holds, and their ratios."""
    sc, f = solution.scalars, solution.fields
    mu, b, a = sc["mu"][0], sc["b"][0], sc["a"][0]
    x, y = solution.axes["x"].values, solution.axes["y"].values
    dx, dy = float(x[1] - x[0]), float(y[1] - y[0])
    pressure, film = f["pressure"].values, f["film_thickness"].values
    t_mean = f["temperature_mean"].values
    rho_c = lubricant.density_at(pressure, t_mean) * lubricant.specific_heat
    dwell = 2.0 * b / point.entrainment_speed
    dissipated = sc["dissipated_power"][0]
    q_f = heat.frictional_heat(dissipated, dwell)
    rise = t_mean - lubricant.inlet_temperature
    inside = heat.in_hertz_ellipse(x, y, a, b)
    film = np.maximum(film, 0.0)
    q_oil = heat.oil_film_heat(rho_c, film * inside, rise, dx, dy)
    dissipated_ellipse = heat.power_in_region(f["dissipation_column"].values, inside, dx, dy)
    q_f_ellipse = heat.frictional_heat(dissipated_ellipse, dwell)
    q_f_seed = heat.seed_frictional_heat(mu, point.load, point.sliding_speed, dwell)
    values = {"dissipated_power": dissipated, "dissipated_power_ellipse": dissipated_ellipse,
              "dwell_time": dwell, "frictional_heat": q_f, "frictional_heat_seed": q_f_seed,
              "frictional_heat_ellipse": q_f_ellipse, "oil_film_heat": q_oil,
              "oil_film_heat_domain": heat.oil_film_heat(rho_c, film, rise, dx, dy),
              "oil_to_friction_ratio": q_oil / q_f, "oil_to_ellipse_friction_ratio": q_oil / q_f_ellipse}
    if q_f_seed > SEED_HEAT_FLOOR * q_f_ellipse:  # the seed's ratio is undefined without sliding
        values["oil_to_seed_friction_ratio"] = q_oil / q_f_seed
    return values


def _heat_distributions(point: ContactPoint, solution: PointSolution, power: float) -> tuple[float, dict[str, Field]]:
    """The friction power `power` (W) distributed over the grid in proportion to the pressure and to the shear power
    tau . v_s: (half the L1 difference of the two relative to the power, the two heat flux fields)."""
    x, y = solution.axes["x"].values, solution.axes["y"].values
    dx, dy = float(x[1] - x[0]), float(y[1] - y[0])
    f = solution.fields
    by_pressure = heat.distribute_by_pressure(power, f["pressure"].values)
    sliding = point.sliding  # u_1 - u_2; the film stress eta* du/dz does positive work on -sliding
    tau_x = -0.5 * (f["shear_stress_1_x"].values + f["shear_stress_2_x"].values)
    tau_y = -0.5 * (f["shear_stress_1_y"].values + f["shear_stress_2_y"].values)
    by_shear = np.maximum(heat.distribute_by_shear_power(tau_x, tau_y, sliding[0], sliding[1], dx, dy), 0.0)
    by_shear = by_shear * (power / by_shear.sum()) if by_shear.sum() > 0.0 else np.zeros_like(by_shear)
    difference = 0.5 * float(np.abs(by_pressure - by_shear).sum()) / power if power > 0.0 else 0.0
    fields = {
        "heat_flux_by_pressure": Field(by_pressure / (dx * dy), "W/m^2",
                                       "frictional heat flux, P distributed in proportion to the pressure"),
        "heat_flux_by_shear": Field(by_shear / (dx * dy), "W/m^2",
                                    "frictional heat flux, P distributed in proportion to the shear power tau . v_s"),
    }
    return difference, fields


def heat_budget(points: list[ContactPoint], solutions: list[PointSolution], lubricant: Lubricant
                ) -> tuple[list[PointSolution], dict[str, Field]]:
    """Budget of every converged point that has a solved film state: its solution gains the budget's scalars and heat
    flux fields; the /heat table has one row per such point (empty when none has)."""
    rows: list[tuple[str, dict[str, float]]] = []
    out = []
    for point, solution in zip(points, solutions):
        if (solution is None or not solution.converged or "mu" not in solution.scalars
                or "temperature_mean" not in solution.fields or "dissipation_column" not in solution.fields):
            out.append(solution)
            continue
        values, fields = point_budget(point, solution, lubricant)
        rows.append((point.name, values))
        scalars = {**solution.scalars, **{k: (v, COLUMNS[k][0]) for k, v in values.items() if k != "mu"}}
        out.append(replace(solution, scalars=scalars, fields={**solution.fields, **fields}))
    if not rows:
        return out, {}
    names = [name for name, _ in rows]
    table = {"point": Field(np.array(names), "-", "meshing point (a name: no unit)")}
    for column, (units, description) in COLUMNS.items():
        if all(column in values for _, values in rows):
            table[column] = Field(np.array([values[column] for _, values in rows]), units, description)
    return out, table
