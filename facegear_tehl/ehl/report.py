"""What a solve reports: film and pressure figures, error estimate, friction, temperatures and energy
budget of one contact point, assembled into the `PointSolution` that the results file stores (SI units)."""

from __future__ import annotations

from dataclasses import dataclass, replace
import math

import numpy as np

from facegear_tehl.ehl import grid
from facegear_tehl.ehl.layers import simpson_weights
from facegear_tehl.ehl.multigrid import Level
from facegear_tehl.ehl.thermal import FilmState, thermal_loading
from facegear_tehl.solution import Field, PointSolution

ORDER = 2  # formal order of the discretisation, for the Richardson-scaled error estimate
ORDER_DT_MAX = 1  # observed order of the largest temperature rise (it sits at the outlet pressure spike; README)


@dataclass(frozen=True)
class LevelSummary:
    """Film and pressure figures of one converged full-multigrid level (dimensionless)."""

    n: int
    h_c: float
    h_min: float
    p_max: float
    dT_max: float = math.nan  # K, with a film state (thermal full multigrid: the coarse stage)
    mu: float = math.nan


def summarise(level: Level) -> LevelSummary:
    return LevelSummary(
        n=level.nx,
        h_c=grid.bilinear_at(level.film, level.x, level.y, 0.0, 0.0),
        h_min=float(level.film.min()),
        p_max=float(level.pressure.max()),
    )


def with_film_state(summary: LevelSummary, level: Level, state: FilmState, scaling, load: float,
                    t_inlet: float) -> LevelSummary:
    """The summary of a level with its converged film state: largest temperature rise and friction coefficient."""
    mu = friction_coefficients(state, level.pressure, _cell_area(level, scaling), load)[0]
    return replace(summary, dT_max=float(state.temperature.max() - t_inlet), mu=mu)


def _cell_area(level: Level, scaling) -> float:
    """Area of one grid cell, m^2."""
    return (level.x[1] - level.x[0]) * scaling.b * (level.y[1] - level.y[0]) * scaling.a


def friction_coefficients(state: FilmState, pressure: np.ndarray, cell: float,
                          load: float) -> tuple[float, float, float]:
    """Friction coefficients from the shear stresses over the pressurised film: mu_i = |F_i|/W with the traction
    on body 1, F_1 = \\iint tau(z = 0) dA, and on body 2, F_2 = -\\iint tau(z = h) dA (Couette and Poiseuille
    parts); returns (mean of mu_1 and mu_2, mu_1, mu_2)."""
    wet = pressure > 0.0
    f1 = np.array([state.stress_1[0][wet].sum(), state.stress_1[1][wet].sum()]) * cell
    f2 = np.array([state.stress_2[0][wet].sum(), state.stress_2[1][wet].sum()]) * cell
    mu_1, mu_2 = float(np.hypot(*f1) / load), float(np.hypot(*f2) / load)
    return 0.5 * (mu_1 + mu_2), mu_1, mu_2


def energy_budget(state: FilmState, film: np.ndarray, dx: float, dy: float, rho_c: np.ndarray,
                  t_inlet: float) -> dict[str, float]:
    """Power dissipated by shear in the film, heat generated in it (dissipation + compression), conducted into
    the solids and convected out of the domain by the oil (enthalpy flux through its boundary), W; and the
    relative imbalance."""
    depth = simpson_weights(state.temperature.shape[0])[:, None, None] * film[None, :, :]
    dissipated = float((state.dissipation * depth).sum() * dx * dy)
    generated = float(((state.dissipation + state.compression) * depth).sum() * dx * dy)
    conducted = float((state.heat_flux_1 + state.heat_flux_2).sum() * dx * dy)
    excess = rho_c * (state.temperature - t_inlet) * depth
    out = (excess[:, :, -1] * state.velocity_x[:, :, -1]).sum() - (excess[:, :, 0] * state.velocity_x[:, :, 0]).sum()
    out = out * dy + ((excess[:, -1, :] * state.velocity_y[:, -1, :]).sum()
                      - (excess[:, 0, :] * state.velocity_y[:, 0, :]).sum()) * dx
    convected = float(out)
    imbalance = (generated - conducted - convected) / generated if generated > 0.0 else 0.0
    return {"dissipated_power": dissipated, "heat_generated": generated, "heat_conducted": conducted,
            "heat_convected": convected, "energy_balance_error": imbalance}


def richardson_error(fine: float, coarse: float, order: int) -> float:
    """Relative discretisation error of `fine` from the same figure one grid coarser, Richardson-scaled for
    `order`: (f_h - f_2h)/((2^order - 1) f_h)."""
    return (fine - coarse) / (2**order - 1) / fine


def _estimate(summaries: list, level: Level, fine: float, name: str, order: int) -> float:
    """`richardson_error` of `fine` against the summary one grid coarser (the thermal coarse stage); NaN
    without it."""
    if len(summaries) < 2 or summaries[-1].n != level.nx or fine == 0.0:
        return math.nan
    return richardson_error(fine, getattr(summaries[-2], name), order)


def _inlet_gap_ratio(level: Level, scaling, point, h_c: float) -> float:
    """Rigid gap x^2/(2 R_x) + y^2/(2 R_y) where the entrainment line through the centre leaves the domain
    upstream, over h_c: how far the inlet reaches, in central films. Measured on the face gear points
    (README, Accuracy: domain size): 9-25 at the default domain; against an inlet of 10.5 b, h_c is 2-6 %
    low at 7-16 and 0.3-1 % low at 20-43."""
    cos, sin = scaling.wedge_x, scaling.wedge_y
    exits = []
    for bound, component, semi_axis in ((level.x[0], cos, scaling.b), (level.x[-1], cos, scaling.b),
                                        (level.y[0], sin, scaling.a), (level.y[-1], sin, scaling.a)):
        if component != 0.0:
            t = -bound * semi_axis / component  # x = -t cos, y = -t sin: upstream
            if t > 0.0:
                exits.append(t)
    t = min(exits)
    gap = (t * cos) ** 2 / (2.0 * point.radius_x) + (t * sin) ** 2 / (2.0 * point.radius_y)
    return gap / h_c


def point_solution(point, lubricant, scaling, solver, level, summaries, converged, message, wall, history,
                   state, mode, reason) -> PointSolution:
    """The PointSolution of a finished solve: scalars with units, fields on the finest grid, histories, models."""
    film_scale = scaling.film_scale
    p_h = scaling.p_h
    fine = summarise(level)
    if len(summaries) >= 2 and summaries[-1].n == level.nx:
        coarse = summaries[-2]
        est_hc = (summaries[-1].h_c - coarse.h_c) / (2**ORDER - 1) / summaries[-1].h_c
        est_hmin = (summaries[-1].h_min - coarse.h_min) / (2**ORDER - 1) / summaries[-1].h_min
    else:
        est_hc = est_hmin = math.nan
    j_min, i_min = np.unravel_index(np.argmin(level.film), level.film.shape)
    load_error = solver.force_error(level) / solver.problem.load_integral
    scalars = {
        "h_c": (fine.h_c * film_scale, "m"),
        "h_min": (fine.h_min * film_scale, "m"),
        "x_h_min": (float(level.x[i_min]) * scaling.b, "m"),
        "y_h_min": (float(level.y[j_min]) * scaling.a, "m"),
        "p_max": (fine.p_max * p_h, "Pa"),
        "p_hertz": (p_h, "Pa"),
        "a": (scaling.a, "m"),
        "b": (scaling.b, "m"),
        "ellipticity": (scaling.ellipticity, "1"),
        "load": (point.load, "N"),
        "radius_x": (point.radius_x, "m"),
        "radius_y": (point.radius_y, "m"),
        "entrainment_speed": (point.entrainment_speed, "m/s"),
        "sliding_speed": (point.sliding_speed, "m/s"),
        "slide_roll_ratio": (point.slide_roll_ratio, "1"),
        "entrainment_angle": (point.entrainment_angle, "deg"),
        "moes_m": (scaling.moes_m, "1"),
        "moes_l": (scaling.moes_l, "1"),
        "thermal_loading": (thermal_loading(point, lubricant), "1"),
        "load_error": (load_error, "1"),
        "iterations": (float(history.cycles), "1"),
        "work_units": (solver.work_units, "1"),
        "wall_time": (wall, "s"),
        "error_estimate_h_c": (est_hc, "1"),
        "error_estimate_h_min": (est_hmin, "1"),
        "grid": (float(level.nx), "1"),
        "grid_y": (float(level.ny), "1"),
        "algebraic_floor": (history.floor, "1"),
        "inlet_gap_ratio": (_inlet_gap_ratio(level, scaling, point, fine.h_c * film_scale), "1"),
    }
    fields = {
        "pressure": Field(level.pressure * p_h, "Pa", "film pressure"),
        "film_thickness": Field(level.film * film_scale, "m", "film thickness"),
    }
    if state is not None:
        t_in = lubricant.inlet_temperature
        mu, mu_1, mu_2 = friction_coefficients(state, level.pressure, _cell_area(level, scaling), point.load)
        temperature = state.temperature
        scalars.update({
            "mu": (mu, "1"),
            "mu_1": (mu_1, "1"),
            "mu_2": (mu_2, "1"),
            "dT_max": (float(temperature.max() - t_in), "K"),
            "dT_mid_max": (float(temperature[temperature.shape[0] // 2].max() - t_in), "K"),
            "dT_surface_1_max": (float(temperature[0].max() - t_in), "K"),
            "dT_surface_2_max": (float(temperature[-1].max() - t_in), "K"),
            "thermal_iterations": (float(len(history.thermal_changes)), "1"),
            "error_estimate_dT_max": (_estimate(summaries, level, float(temperature.max() - t_in), "dT_max",
                                                ORDER_DT_MAX), "1"),
            "error_estimate_mu": (_estimate(summaries, level, mu, "mu", ORDER), "1"),
            "thermal_floor": (history.thermal_floor, "K"),
            "thermal_layers": (float(temperature.shape[0]), "1"),
        })
        weights = simpson_weights(temperature.shape[0])
        fields["temperature_mean"] = Field(np.tensordot(weights, temperature, axes=1), "K",
                                           "film-averaged temperature (Simpson across the layers)")
        fields["temperature_mid"] = Field(temperature[temperature.shape[0] // 2], "K", "mid-film temperature")
        fields["temperature_surface_1"] = Field(temperature[0], "K", "surface temperature of body 1")
        fields["temperature_surface_2"] = Field(temperature[-1], "K", "surface temperature of body 2")
        if mode != "off":
            rho_c = (lubricant.density_at(np.broadcast_to(level.pressure * p_h, temperature.shape), temperature)
                     * lubricant.specific_heat)
            budget = energy_budget(state, level.film * film_scale, (level.x[1] - level.x[0]) * scaling.b,
                                   (level.y[1] - level.y[0]) * scaling.a, rho_c, t_in)
            units = {"energy_balance_error": "1"}
            scalars.update({k: (v, units.get(k, "W")) for k, v in budget.items()})
            fields["heat_flux_1"] = Field(state.heat_flux_1, "W/m^2", "heat flux from the film into body 1")
            fields["heat_flux_2"] = Field(state.heat_flux_2, "W/m^2", "heat flux from the film into body 2")
        for body, stress in ((1, state.stress_1), (2, state.stress_2)):
            for axis, component in (("x", 0), ("y", 1)):
                fields[f"shear_stress_{body}_{axis}"] = Field(
                    stress[component], "Pa", f"shear stress eta* du/dz at surface {body}, {axis} component")
    scalars = {k: v for k, v in scalars.items() if math.isfinite(v[0])}
    hist = {
        "pressure_change_history": Field(np.nan_to_num(np.array(history.changes), nan=0.0), "1",
                                         "relative L1 change of pressure per finest-grid cycle (0: FMG start)"),
        "residual_history": Field(np.array(history.residuals), "1",
                                  "mean |Reynolds residual| over pressurised nodes after each cycle"),
        "load_error_history": Field(np.array(history.loads), "1", "relative load-balance error after each cycle"),
        "level_h_c": Field(np.array([s.h_c * film_scale for s in summaries]), "m",
                           "central film on each full-multigrid level as solved there (isothermal start; "
                           "the last two levels with their film state in the reduced model), coarsest first"),
        "level_h_min": Field(np.array([s.h_min * film_scale for s in summaries]), "m",
                             "minimum film on each full-multigrid level as solved there, coarsest first"),
        "level_nodes": Field(np.array([float(s.n) for s in summaries]), "1", "nodes per side of each level"),
    }
    if history.thermal_changes:
        hist["thermal_change_history"] = Field(np.array(history.thermal_changes), "K",
                                               "largest layer-temperature change per outer iteration")
        hist["thermal_h_c_history"] = Field(np.array(history.thermal_h_c), "m", "central film per outer iteration")
    models = {
        "viscosity": f"{lubricant.viscosity_model} (Roelands 1966)" if lubricant.viscosity_model == "roelands"
        else "barus (Barus 1893)",
        "density": "dowson_higginson (Dowson & Higginson 1966)" if lubricant.density_model == "dowson_higginson"
        else "incompressible",
        "rheology": "ree_eyring (Ree & Eyring 1955)" if lubricant.rheology == "ree_eyring" else "newtonian",
        "thermal": mode,
        "thermal_reason": reason,
        "solver": "FAS multigrid, line GS / Jacobi distributive (Venner & Lubrecht 2000), FFT deflection",
    }
    if mode != "off":
        models["thermal_solids"] = "Jaeger (1942) high-Peclet moving heat source per surface"
        a, b = lubricant.conductivity_pressure_coefficient, lubricant.conductivity_pressure_saturation
        models["conductivity"] = (f"larsson (Larsson et al. 2000): k_0 [1 + a p/(1 + b p)], a = {a:g}/GPa, "
                                  f"b = {b:g}/GPa" if a > 0.0 else "constant")
    return PointSolution(name=point.name, converged=converged, message=message, scalars=scalars, fields=fields,
                         axes={"x": Field(level.x * scaling.b, "m", "node coordinates along the minor axis (x = X b)"),
                               "y": Field(level.y * scaling.a, "m", "node coordinates along the major axis (y = Y a)")},
                         history=hist, models=models)
