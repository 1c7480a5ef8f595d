"""The meshing cycle of a face gear pair over its solved points: quantities along the contact path, the film
parameter, the contact temperature of each flank, and the mesh power loss and mechanical efficiency (SI units).

  film parameter        lambda = h_min / sigma,  sigma = sqrt(R_q1^2 + R_q2^2)  (Tallian 1967, ASLE Trans. 10:418)
  contact temperature   theta_B,i = theta_bulk,i + theta_fl  (Blok 1937): theta_fl Blok's flash temperature
                        (heat.blok_flash_temperature), or the solved surface temperature rise of flank i
  sliding power         P(s) = mu(s) F(s) |v_s(s)|,  F(s) = K(s) F_n
  mesh power loss       P_loss = (1/p_b) int_{s_min}^{s_max} P(s) ds
  efficiency            eta = 1 - P_loss / (T_1 omega_1)

The power loss is the mean over one base pitch of the summed loss of every pair in mesh: the path coordinate s is
the pinion's roll distance, s = r_b1 phi_1, so while the pinion turns by one base pitch the pair at s sweeps
[s, s + p_b) and the pairs one, two, ... base pitches ahead sweep the rest of the path; the sum of their time
means is (1/p_b) times the integral over the whole path (two pairs in the double-tooth zones, one in the single).
The integral is the trapezoidal rule over the solved points in path order (P linear in s between them).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
import math

import numpy as np

from facegear_tehl import heat
from facegear_tehl.case import Case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.gears.tca import meshing_points
from facegear_tehl.solution import Field, PointSolution

# A point this close to an end of the path (in base pitches) counts as at the end: the evenly spaced points and
# S1, S5 are placed at s_min and s_max by linspace and the path limits themselves (round-off only).
PATH_END_TOLERANCE = 1e-9
# Below this many points the cycle is a coarse sample of the path: on the default case (thermal off, 33 x 9) the five
# points S1..S5 put the mesh efficiency 0.056 percentage points above 81 points, 21 points 0.006 and 41 points 0.002
# (scripts/cycle_points.py, docs/cycle.md).
COARSE_POINT_COUNT = 21

# Along-path columns taken from the point scalars: column -> (scalar, units, description).
_FROM_POINTS = {
    "p_h": ("p_hertz", "Pa", "maximum Hertz pressure"),
    "p_max": ("p_max", "Pa", "largest film pressure"),
    "h_c": ("h_c", "m", "central film thickness"),
    "h_min": ("h_min", "m", "minimum film thickness"),
    "dT_max": ("dT_max", "K", "largest film temperature rise above the inlet"),
    "dT_min": ("dT_min", "K", "smallest film temperature rise above the inlet (negative: the film cools)"),
    "dT_surface_1_max": ("dT_surface_1_max", "K", "largest surface temperature rise of the pinion flank (solved)"),
    "dT_surface_2_max": ("dT_surface_2_max", "K", "largest surface temperature rise of the face-gear flank (solved)"),
    "mu": ("mu", "1", "friction coefficient of the solved film"),
    "mu_xu": ("mu_xu", "1", "friction coefficient of Xu et al. (2007), a cylindrical-gear correlation"),
    "dissipated_power": ("dissipated_power", "W", "power dissipated by shear in the solved film (whole domain)"),
    "flash_temperature": ("flash_temperature", "K", "Blok (1937) flash temperature with the film's mu"),
}
# The power-loss variants: attr suffix -> the column of the sliding (or dissipated) power they integrate; "_iso"
# (ISO/TR 14179-2's constant mu_mz times F |v_s|) is added when the case gives a roughness.
_LOSS_COLUMNS = {"": "sliding_power", "_xu": "sliding_power_xu", "_dissipated": "dissipated_power"}
# How the attrs power_loss* integrate their column (printed by tehl run and tehl info).
QUADRATURE = "(1/p_b) x trapezoidal rule in s over the solved points, every pair in mesh"


@dataclass(frozen=True)
class MeshCycle:
    """The /cycle group: columns along the path (name -> Field, in path order), attrs (name -> (value, units)),
    the scalars each point gains (point name -> name -> (value, units)) and remarks for the run's warnings."""

    columns: Mapping[str, Field]
    scalars: Mapping[str, tuple[float, str]]
    point_scalars: Mapping[str, Mapping[str, tuple[float, str]]]
    notes: tuple[str, ...] = ()


def composite_roughness(roughness_1: float, roughness_2: float) -> float:
    """sigma = sqrt(R_q1^2 + R_q2^2), m: the RMS roughness of the sum of the two surfaces (R_q in m)."""
    return math.hypot(roughness_1, roughness_2)


def film_parameter(h_min: float, roughness_1: float, roughness_2: float) -> float:
    """lambda = h_min / sqrt(R_q1^2 + R_q2^2), - (Tallian 1967); h_min and R_q in m, not both R_q zero."""
    return h_min / composite_roughness(roughness_1, roughness_2)


def with_film_parameter(solution: PointSolution, point: ContactPoint) -> PointSolution:
    """The solution with the scalar `film_parameter` when the case gives a roughness and the film an h_min."""
    if "h_min" not in solution.scalars or composite_roughness(point.body_1.roughness, point.body_2.roughness) == 0:
        return solution
    value = film_parameter(solution.scalar("h_min"), point.body_1.roughness, point.body_2.roughness)
    return replace(solution, scalars={**solution.scalars, "film_parameter": (value, "1")})


def mesh_power_loss(s: Sequence[float], power: Sequence[float], base_pitch: float) -> float:
    """P_loss = (1/p_b) int P ds, W, by the trapezoidal rule over the points (s in m, any order; P in W)."""
    order = np.argsort(s)
    s_sorted, p_sorted = np.asarray(s, dtype=float)[order], np.asarray(power, dtype=float)[order]
    return float(np.sum(0.5 * (p_sorted[1:] + p_sorted[:-1]) * np.diff(s_sorted)) / base_pitch)


def mesh_efficiency(power_loss: float, torque: float, speed: float) -> float:
    """eta = 1 - P_loss / (T_1 omega_1), -: P_loss in W, the pinion torque T_1 in N m and speed omega_1 in rad/s."""
    return 1.0 - power_loss / (torque * speed)


def iso_tr_14179_mean_friction(case: Case, normal_load: float, path: Mapping[str, Field]) -> float:
    """ISO/TR 14179-2's (Schlenk 1994) mean friction coefficient of the pair, -, with the inputs a cylindrical gear
    would give it (heat.iso_tr_14179_friction): F_bt/b the normal load over the face-gear face width, the sum
    velocity 2|U_e| and the reduced radius R_x at the pitch point s = 0 (interpolated in the contact path), the
    oil's inlet viscosity, R_a = sqrt(2/pi) (R_q1 + R_q2)/2 and X_L of lubricant.oil_type."""
    gear, body_1, body_2 = case.gear, case.materials.body_1, case.materials.body_2
    s = path["s"].values
    at_pitch = {name: float(np.interp(0.0, s, path[name].values)) for name in ("entrainment_speed", "Rx")}
    roughness = heat.GAUSSIAN_RA_PER_RQ * 0.5 * (body_1.roughness + body_2.roughness)
    return heat.iso_tr_14179_friction(normal_load / (gear.outer_radius - gear.inner_radius),
                                      2.0 * at_pitch["entrainment_speed"], at_pitch["Rx"], case.lubricant.viscosity,
                                      roughness, heat.ISO_TR_14179_OIL_FACTOR[case.lubricant.oil_type])


def mesh_cycle(case: Case, points: Sequence[ContactPoint], solutions: Sequence[PointSolution],
               path: Mapping[str, Field], geometry: Mapping[str, tuple[float, str]]) -> MeshCycle:
    """The cycle of a gear case over the points whose film was solved (converged, with an h_min), in path order.

    path: the contact path table (gears/analysis.py); geometry: its scalars (base_pitch, normal_load,
    pinion_base_radius, path_start, path_end). The power loss and efficiency are given when the points span the
    whole path (both ends solved); the ISO/TR 14179-2 variant when the case gives a roughness."""
    solved = sorted(((p, sol) for p, sol in zip(points, solutions) if _has_film(sol)),
                    key=lambda pair: pair[0].path_coordinate)
    if not solved:  # the points' own messages say why
        return MeshCycle({}, {}, {})
    base_pitch = geometry["base_pitch"][0]
    s = np.array([p.path_coordinate for p, _ in solved])
    sigma = composite_roughness(case.materials.body_1.roughness, case.materials.body_2.roughness)
    columns = _columns(case, solved, geometry, sigma)
    scalars: dict[str, tuple[float, str]] = {
        "point_count": (len(solved), "1"),
        "base_pitch": (base_pitch, "m"),
        "input_power": (case.gear.pinion_torque * case.gear.pinion_speed, "W"),
        **{f"bulk_temperature_{body}": (t, "K") for body, t in enumerate(_bulk_temperatures(case), start=1)},
        **{f"s_{name}": (value, "m") for name, value in
           meshing_points(geometry["path_start"][0], geometry["path_end"][0], base_pitch).items()},
    }
    notes = []
    spans = (abs(s[0] - geometry["path_start"][0]) <= PATH_END_TOLERANCE * base_pitch
             and abs(s[-1] - geometry["path_end"][0]) <= PATH_END_TOLERANCE * base_pitch)
    left_out = [p.name for p, sol in zip(points, solutions) if not _has_film(sol)]
    if left_out:
        notes.append(f"cycle: {', '.join(left_out)} left out (not converged)")
    if not spans or len(solved) < 2:
        notes.append("cycle: the solved points do not span the contact path from end to end; "
                     "no mesh power loss or efficiency")
    else:
        notes.extend(_power_losses(case, s, columns, sigma, geometry, path, scalars))
    return MeshCycle(columns, scalars, _point_scalars(columns), tuple(notes))


def _bulk_temperatures(case: Case) -> tuple[float, float]:
    """The bulk temperatures of the two flanks (K): the case's, else the oil's inlet temperature."""
    return tuple(case.lubricant.inlet_temperature if t is None else t
                 for t in (case.gear.pinion_bulk_temperature, case.gear.face_gear_bulk_temperature))


def _columns(case: Case, solved: Sequence[tuple[ContactPoint, PointSolution]],
             geometry: Mapping[str, tuple[float, str]], sigma: float) -> dict[str, Field]:
    """The cycle table over the solved points (path order): position, load, sliding, the points' scalars present
    at every point, the sliding power, the film parameter (roughness `sigma` > 0, m) and the contact temperatures."""
    s = np.array([p.path_coordinate for p, _ in solved])
    load = np.array([p.load for p, _ in solved])
    values = {name: np.array([sol.scalars[key][0] if key in sol.scalars else math.nan for _, sol in solved])
              for name, (key, _, _) in _FROM_POINTS.items()}
    columns = {
        "point": Field(np.array([p.name for p, _ in solved]), "-", "meshing point (a name: no unit)"),
        "s": Field(s, "m", "path coordinate: pinion roll distance from the pitch position"),
        "roll_angle": Field(s / geometry["pinion_base_radius"][0], "rad",
                            "pinion roll angle from the pitch position, s / r_b1"),
        "load_share": Field(load / geometry["normal_load"][0], "1", "share K of the normal load carried by the pair"),
        "load": Field(load, "N", "normal load of the pair, K F_n"),
        "sliding_speed": Field(np.array([p.sliding_speed for p, _ in solved]), "m/s", "sliding speed |u_1 - u_2|"),
    }
    columns.update({name: Field(values[name], units, description)
                    for name, (_, units, description) in _FROM_POINTS.items() if np.isfinite(values[name]).all()})
    sliding = load * columns["sliding_speed"].values
    if "mu" in columns:
        columns["sliding_power"] = Field(values["mu"] * sliding, "W", "sliding power P = mu F |v_s| of the solved "
                                         "film; the attr power_loss is its " + QUADRATURE)
    if "mu_xu" in columns:
        columns["sliding_power_xu"] = Field(values["mu_xu"] * sliding, "W", "P = mu F |v_s| with Xu et al.'s mu")
    if sigma > 0.0:
        columns["film_parameter"] = Field(values["h_min"] / sigma, "1",
                                          "film parameter lambda = h_min / sqrt(R_q1^2 + R_q2^2)")
    columns.update(_contact_temperatures(case, columns, values))
    return columns


def _contact_temperatures(case: Case, columns: Mapping[str, Field],
                          values: Mapping[str, np.ndarray]) -> dict[str, Field]:
    """Each flank's contact temperature (K): its bulk temperature plus Blok's flash temperature, and plus its
    solved surface temperature rise (a thermal solve), where the points give them."""
    bulk = _bulk_temperatures(case)
    temperatures = {}
    for body in (1, 2):
        if "flash_temperature" in columns:
            temperatures[f"contact_temperature_blok_{body}"] = Field(
                bulk[body - 1] + values["flash_temperature"], "K",
                f"contact temperature of flank {body}: its bulk temperature + Blok's flash temperature")
        if case.solver.thermal != "off" and f"dT_surface_{body}_max" in columns:
            temperatures[f"contact_temperature_{body}"] = Field(
                bulk[body - 1] + values[f"dT_surface_{body}_max"], "K",
                f"contact temperature of flank {body}: its bulk temperature + its solved surface temperature rise")
    return temperatures


def _power_losses(case: Case, s: np.ndarray, columns: Mapping[str, Field], sigma: float,
                  geometry: Mapping[str, tuple[float, str]], path: Mapping[str, Field],
                  scalars: dict[str, tuple[float, str]]) -> list[str]:
    """The mesh power loss and efficiency of each sliding power the table has (and of ISO/TR 14179-2's mean
    friction with a roughness `sigma` > 0) into `scalars`, for points spanning the path; returns the notes."""
    gear, base_pitch, normal_load = case.gear, geometry["base_pitch"][0], geometry["normal_load"][0]
    notes = []
    variants = {suffix: columns[name].values for suffix, name in _LOSS_COLUMNS.items() if name in columns}
    if "" not in variants:
        notes.append("cycle: not every point has the film's friction coefficient; no mesh power loss from it")
    if sigma > 0.0:
        mu_iso = iso_tr_14179_mean_friction(case, normal_load, path)
        scalars["mu_iso"] = (mu_iso, "1")
        variants["_iso"] = mu_iso * (columns["load"].values * columns["sliding_speed"].values)
    for suffix, power in variants.items():
        loss = mesh_power_loss(s, power, base_pitch)
        scalars[f"power_loss{suffix}"] = (loss, "W")
        scalars[f"mesh_efficiency{suffix}"] = (mesh_efficiency(loss, gear.pinion_torque, gear.pinion_speed), "1")
    return notes


def _has_film(solution: PointSolution | None) -> bool:
    """A converged solve with a film: the figures a point that did not converge carries are of its last iterate
    or coarser grid, not a result."""
    return solution is not None and solution.converged and "h_min" in solution.scalars


# Columns the points gain as scalars (the others they already hold).
_NEW_POINT_SCALARS = ("roll_angle", "load_share", "sliding_power", "sliding_power_xu", "contact_temperature_1",
                      "contact_temperature_2", "contact_temperature_blok_1", "contact_temperature_blok_2")


def _point_scalars(columns: Mapping[str, Field]) -> dict[str, dict[str, tuple[float, str]]]:
    names = [str(name) for name in columns["point"].values]
    return {name: {key: (float(columns[key].values[i]), columns[key].units)
                   for key in _NEW_POINT_SCALARS if key in columns} for i, name in enumerate(names)}
