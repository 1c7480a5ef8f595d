"""What a solve reports: the `PointSolution` of a finished point solve (SI units), assembled from the solver's
finest level, its film state, its history and its level summaries; and the level summaries themselves."""

from __future__ import annotations

from dataclasses import dataclass, replace
import math
from typing import Protocol

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import grid
from facegear_tehl.ehl.composite import Composite
from facegear_tehl.ehl.convergence import History
from facegear_tehl.ehl.domain import rigid_gap_ratio, side_pressure_ratio
from facegear_tehl.ehl.energy import dissipated_power, energy_budget
from facegear_tehl.ehl.friction import friction_coefficients
from facegear_tehl.ehl.layers import simpson_weights
from facegear_tehl.ehl.multigrid import Level, MultigridSolver
from facegear_tehl.ehl.richardson import ORDER, richardson_error
from facegear_tehl.ehl.scaling import Scaling
from facegear_tehl.ehl.stopwatch import Spent
from facegear_tehl.ehl.thermal import FilmState, thermal_loading
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.record import Action, Reason, RetryRecord, SolveRecord
from facegear_tehl.settings import ThermalMode
from facegear_tehl.solution import Field, PointSolution, Status

ORDER_DT_MAX = 1  # observed order of the largest temperature rise (at the outlet pressure spike; docs/accuracy.md)
# Observed order of mu along x (its y-dependence is below 0.01 %): on the default face gear case, from the coarse
# stage (257 x 65), the default grid (513 x 65) and 1025 x 513, 1.7 at S1, 1.0 at S2 and 0.7 at S4; the second-order
# estimate gave S4 -0.56 % against a change of -1.04 % to the next grid.
ORDER_MU = 1


@dataclass(frozen=True)
class LevelSummary:
    """Film and pressure figures of one converged full-multigrid level (dimensionless)."""

    n: int
    h_c: float
    h_min: float
    p_max: float
    dT_max: float = math.nan  # K, with a film state (thermal full multigrid: the coarse stage)
    mu: float = math.nan
    dT_min: float = math.nan  # K, with a film state


def summarise(level: Level) -> LevelSummary:
    return LevelSummary(
        n=level.nx,
        h_c=grid.bilinear_at(level.film, level.x, level.y, 0.0, 0.0),
        h_min=float(level.film.min()),
        p_max=float(level.pressure.max()),
    )


def with_film_state(summary: LevelSummary, level: Level, state: FilmState, scaling: Scaling, load: float,
                    t_inlet: float) -> LevelSummary:
    """The summary of a level with its converged film state: largest temperature rise and friction coefficient."""
    mu = friction_coefficients(state, level.pressure, cell_area(level, scaling), load)[0]
    return replace(summary, dT_max=float(state.temperature.max() - t_inlet), mu=mu,
                   dT_min=float(state.temperature.min() - t_inlet))


def cell_area(level: Level, scaling: Scaling) -> float:
    """Area of one grid cell, m^2."""
    return level.hx * scaling.b * level.hy * scaling.a


def estimate(summaries: list[LevelSummary], level: Level, fine: float, name: str, order: int) -> float:
    """`richardson_error` of `fine` against the summary one grid coarser; NaN without one."""
    if len(summaries) < 2 or summaries[-1].n != level.nx or fine == 0.0:
        return math.nan
    return richardson_error(fine, getattr(summaries[-2], name), order)


def inlet_gap_ratio(level: Level, scaling: Scaling, radius_x: float, radius_y: float, h_c: float) -> float:
    """domain.rigid_gap_ratio of the level's domain (radii and h_c in m). Measured on the face gear points
    (docs/accuracy.md, domain size): the h_c error of the truncated inlet is 140-200 G^(-3/2) percent."""
    return rigid_gap_ratio((level.x[0], level.x[-1]), (level.y[0], level.y[-1]), scaling, radius_x, radius_y, h_c)


# Scalars that describe the film: not reported when the film closes (a negative film is never a result).
# Largest load-balance error of an unconverged solve whose film is still reported: its film then carries the load to
# within this share, which moves h_c by less than 0.4 % (h_c ~ W^-0.067, Hamrock & Dowson 1977). A solve that ran
# away in its full-multigrid start reports a start level whose pressure carried 3.8x the load (an a/b = 100 film
# at 124 m/s, Moes M = 3.7), or a film of 1e14 um: no film of the contact.
UNBALANCED_LOAD = 0.05
FILM_SCALARS = ("h_c", "h_min", "x_h_min", "y_h_min", "p_max", "error_estimate_h_c", "error_estimate_h_min",
                "error_estimate_p_max", "algebraic_floor", "inlet_gap_ratio", "side_pressure_ratio")


class Reported(Protocol):
    """What the report reads of a finished point solve (solve.PointSolve)."""

    point: ContactPoint
    lubricant: Lubricant
    scaling: Scaling
    solver: MultigridSolver
    summaries: list[LevelSummary]
    mode: ThermalMode
    reason: str
    attempt: int
    coarsest: int
    outlet: Composite | None
    outlet_note: str

    @property
    def history(self) -> History: ...


def point_solution(solve: Reported, level: Level, status: Status, state: FilmState | None,
                   spent: Spent, record: SolveRecord) -> PointSolution:
    """The PointSolution of a finished solve reported on `level`: scalars with units, fields, histories, models and
    the solve record. A film that closed (h_min <= 0) gives no fields and no film scalars: only the point, its cost,
    histories and the reason."""
    record = _with_outlet_note(solve, record)
    scaling = solve.scaling
    scalars = _film_scalars(solve, level, spent)
    fields = {
        "pressure": Field(level.pressure * scaling.p_h, "Pa", "film pressure"),
        "film_thickness": Field(level.film * scaling.film_scale, "m", "film thickness"),
    }
    message = status.message
    if level.film.min() <= 0.0:
        # where the film closed (the lowest node) stays: it tells which way a finer grid must resolve it
        scalars = {k: v for k, v in scalars.items() if k not in FILM_SCALARS}
        scalars["x_film_closed"], scalars["y_film_closed"] = _lowest_film_place(solve, level)
        fields, state = {}, None
    elif not status.converged and not abs(scalars["load_error"][0]) <= UNBALANCED_LOAD:
        scalars = {k: v for k, v in scalars.items() if k not in FILM_SCALARS}
        fields, state = {}, None
        message += (f"; its last iterate does not carry the load (load error {scalars['load_error'][0]:.2g}): "
                    "no film is reported")
    if state is not None:
        state_scalars, state_fields = _film_state_outputs(solve, level, state)
        if solve.outlet is not None and fields:
            state_scalars.update(_outlet_scalars(solve, state_scalars))
            scalars.update({k: v for k, v in solve.outlet.scalars.items() if k in scalars})
            state_fields = _film_state_outputs(solve, level, solve.outlet.state)[1]
            fields["pressure"] = Field(solve.outlet.pressure, "Pa", "film pressure")
            fields["film_thickness"] = Field(solve.outlet.film, "m", "film thickness")
        scalars.update(state_scalars)
        fields.update(state_fields)
    return PointSolution(
        name=solve.point.name, outcome=status.outcome, message=message,
        scalars={k: v for k, v in scalars.items() if math.isfinite(v[0])}, fields=fields,
        axes={"x": Field(level.x * scaling.b, "m", "node coordinates along the minor axis (x = X b)"),
              "y": Field(level.y * scaling.a, "m", "node coordinates along the major axis (y = Y a)")},
        history=_histories(solve), models=_models(solve, record), record=record)


def _with_outlet_note(solve: Reported, record: SolveRecord) -> SolveRecord:
    """The record with the outlet stage's failure, if one failed: its composite of the patches before it is
    reported, or the uniform grid's solution."""
    if not solve.outlet_note:
        return record
    action = Action.KEPT_COARSER if solve.outlet is not None else Action.DROPPED
    return record.with_retry(RetryRecord(Reason.STAGE_FAILED, action, solve.attempt, solve.outlet_note))


def _film_scalars(solve: Reported, level: Level, spent: Spent) -> dict[str, tuple[float, str]]:
    """Film, pressure, contact and cost figures of any solve."""
    point, scaling, summaries, history = solve.point, solve.scaling, solve.summaries, solve.history
    film_scale = scaling.film_scale
    fine = summarise(level)
    x_min, y_min = _lowest_film_place(solve, level)
    # the error estimates compare the levels as the full-multigrid start left them (none where a start that stopped
    # short of the load dropped its levels: estimate gives NaN without two)
    last = summaries[-1] if summaries else fine
    h_c_start, h_min_start, p_max_start = last.h_c, last.h_min, last.p_max
    return {
        "h_c": (fine.h_c * film_scale, "m"),
        "h_min": (fine.h_min * film_scale, "m"),
        "x_h_min": x_min,
        "y_h_min": y_min,
        "p_max": (fine.p_max * scaling.p_h, "Pa"),
        "p_hertz": (scaling.p_h, "Pa"),
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
        "thermal_loading": (thermal_loading(point, solve.lubricant), "1"),
        "load_error": (solve.solver.force_error(level) / solve.solver.problem.load_integral, "1"),
        "iterations": (float(history.cycles), "1"),
        "work_units": (solve.solver.work_units, "1"),
        **spent.scalars(),
        "attempts": (float(solve.attempt), "1"),
        "error_estimate_h_c": (estimate(summaries, level, h_c_start, "h_c", ORDER), "1"),
        "error_estimate_h_min": (estimate(summaries, level, h_min_start, "h_min", ORDER), "1"),
        "error_estimate_p_max": (estimate(summaries, level, p_max_start, "p_max", ORDER), "1"),
        "grid": (float(level.nx), "1"),
        "grid_y": (float(level.ny), "1"),
        "coarsest_grid": (float(solve.coarsest), "1"),
        "algebraic_floor": (history.floor, "1"),
        "inlet_gap_ratio": (inlet_gap_ratio(level, scaling, point.radius_x, point.radius_y,
                                            fine.h_c * film_scale), "1"),
        "side_pressure_ratio": (side_pressure_ratio(level.pressure, level.x, level.y, scaling), "1"),
    }


def _lowest_film_place(solve: Reported, level: Level) -> tuple[tuple[float, str], tuple[float, str]]:
    """x and y (m) of the node of the lowest film on `level`."""
    j_min, i_min = np.unravel_index(np.argmin(level.film), level.film.shape)
    return (float(level.x[i_min]) * solve.scaling.b, "m"), (float(level.y[j_min]) * solve.scaling.a, "m")


def _film_state_outputs(solve: Reported, level: Level, state: FilmState
                        ) -> tuple[dict[str, tuple[float, str]], dict[str, Field]]:
    """Friction, temperatures (their rises: thermal models), energy budget (thermal models) and surface stresses of a
    film state."""
    scaling, lubricant, summaries = solve.scaling, solve.lubricant, solve.summaries
    t_in = lubricant.inlet_temperature
    mu, mu_1, mu_2 = friction_coefficients(state, level.pressure, cell_area(level, scaling), solve.point.load)
    temperature = state.temperature
    middle = temperature.shape[0] // 2
    dT_max = float(temperature.max() - t_in)
    # the coldest film temperature relative to the inlet (negative where the oil cools by expansion in the
    # outlet) and where it lies
    _, j_min, i_min = np.unravel_index(np.argmin(temperature), temperature.shape)
    scalars = {
        "mu": (mu, "1"),
        "mu_1": (mu_1, "1"),
        "mu_2": (mu_2, "1"),
        "thermal_iterations": (float(solve.history.outer), "1"),
        "error_estimate_mu": (estimate(summaries, level, mu, "mu", ORDER_MU), "1"),
        "thermal_floor": (solve.history.thermal_floor, "K"),
        "viscosity_floor": (solve.history.viscosity_floor, "1"),
        "thermal_layers": (float(temperature.shape[0]), "1"),
    }
    if solve.mode is not ThermalMode.OFF:  # an isothermal Ree-Eyring film's layers all hold the inlet temperature
        scalars.update({
            "dT_max": (dT_max, "K"),
            "dT_min": (float(temperature.min() - t_in), "K"),
            "x_dT_min": (float(level.x[i_min]) * scaling.b, "m"),
            "y_dT_min": (float(level.y[j_min]) * scaling.a, "m"),
            "dT_mid_max": (float(temperature[middle].max() - t_in), "K"),
            "dT_surface_1_max": (float(temperature[0].max() - t_in), "K"),
            "dT_surface_2_max": (float(temperature[-1].max() - t_in), "K"),
            "error_estimate_dT_max": (estimate(summaries, level, dT_max, "dT_max", ORDER_DT_MAX), "1"),
            "error_estimate_dT_min": (estimate(summaries, level, float(temperature.min() - t_in), "dT_min",
                                               ORDER_DT_MAX), "1"),
        })
    fields = {
        "temperature_mean": Field(np.tensordot(simpson_weights(temperature.shape[0]), temperature, axes=1), "K",
                                  "film-averaged temperature (Simpson across the layers)"),
        "temperature_mid": Field(temperature[middle], "K", "mid-film temperature"),
        "temperature_surface_1": Field(temperature[0], "K", "surface temperature of body 1"),
        "temperature_surface_2": Field(temperature[-1], "K", "surface temperature of body 2"),
    }
    film, dx, dy = level.film * scaling.film_scale, level.hx * scaling.b, level.hy * scaling.a
    scalars["dissipated_power"] = (dissipated_power(state, film, dx, dy), "W")
    fields["dissipation_column"] = Field(
        np.tensordot(simpson_weights(temperature.shape[0]), state.dissipation, axes=1) * film, "W/m^2",
        "power dissipated by shear per unit area, the integral of tau . gamma_dot across the film (Simpson; its sum "
        "times dx dy is dissipated_power)")
    if solve.mode is not ThermalMode.OFF:
        budget = energy_budget(state, film, dx, dy, t_in)
        scalars.update({k: (v, "1" if k == "energy_balance_error" else "W") for k, v in budget.items()})
        fields["heat_flux_1"] = Field(state.heat_flux_1, "W/m^2", "heat flux from the film into body 1")
        fields["heat_flux_2"] = Field(state.heat_flux_2, "W/m^2", "heat flux from the film into body 2")
    for body, stress in ((1, state.stress_1), (2, state.stress_2)):
        for axis, component in (("x", 0), ("y", 1)):
            fields[f"shear_stress_{body}_{axis}"] = Field(
                stress[component], "Pa", f"shear stress eta* du/dz at surface {body}, {axis} component")
    return scalars, fields


def _outlet_scalars(solve: Reported, uniform: dict[str, tuple[float, str]]) -> dict[str, tuple[float, str]]:
    """The outlet stage's figures of the film state (outlet.composite), with the error estimates of dT_max and mu
    from the uniform grid's values, Richardson over the whole refinement (n patches divide the x spacing where they are
    set by 2^n; first order, the order ΔT_max shows from the uniform grid to the first patch). At S2 and S4 of the
    default case that brackets the error against the extrapolations of docs/accuracy.md (2.0 and 1.6 % against 1.0-1.9
    and 1.2-1.6 %); the last patch's change alone (1.8 and 0.8 %) does not see the share of the inlet, which the
    patches leave at the uniform grid's spacing. The energy budget stays the uniform grid's (its discrete balance is
    exact there; the composite's is not conservative across the patch's ends)."""
    figures = {k: v for k, v in solve.outlet.scalars.items()
               if k in uniform or k in ("outlet_patch_start", "outlet_patches")}
    ratio = 2 ** int(figures["outlet_patches"][0])  # the spike's spacing on the uniform grid over the last patch's
    for name, order in (("dT_max", ORDER_DT_MAX), ("mu", ORDER_MU)):
        if figures[name][0] != 0.0:
            figures[f"error_estimate_{name}"] = (richardson_error(figures[name][0], uniform[name][0], order, ratio),
                                                 "1")
    return figures


def _histories(solve: Reported) -> dict[str, Field]:
    """Per-cycle, per-level and per-outer-iteration records of the solve."""
    history, summaries, film_scale = solve.history, solve.summaries, solve.scaling.film_scale
    records = {
        "pressure_change_history": Field(np.nan_to_num(np.array(history.changes), nan=0.0), "1",
                                         "relative L1 change of pressure per finest-grid cycle (0: FMG start)"),
        "residual_history": Field(np.array(history.residuals), "1",
                                  "mean |Reynolds residual| over pressurised nodes after each cycle"),
        "load_error_history": Field(np.array(history.loads), "1", "relative load-balance error after each cycle"),
        **_film_histories(history, film_scale),
        "level_h_c": Field(np.array([s.h_c * film_scale for s in summaries]), "m",
                           "central film on each level as solved there, coarsest first (the full-multigrid "
                           "start's levels Newtonian and isothermal, a coupled stage's with its film state)"),
        "level_h_min": Field(np.array([s.h_min * film_scale for s in summaries]), "m",
                             "minimum film on each full-multigrid level as solved there, coarsest first"),
        "level_nodes": Field(np.array([float(s.n) for s in summaries]), "1", "nodes per side of each level"),
        **_film_state_levels(summaries),
    }
    if history.thermal_changes:
        records["thermal_change_history"] = Field(np.array(history.thermal_changes), "K",
                                                  "largest layer-temperature change per outer iteration")
    if history.viscosity_changes:
        records["viscosity_change_history"] = Field(np.array(history.viscosity_changes), "1",
                                                    "largest change of ln(eta*/eta) per outer iteration")
    if history.thermal_h_c:
        records["thermal_h_c_history"] = Field(np.array(history.thermal_h_c), "m", "central film per outer iteration")
    return records


def _film_state_levels(summaries: list[LevelSummary]) -> dict[str, Field]:
    """The film-state figures of the levels summarised with their converged film state (with_film_state: a thermal
    solve's seed and coarse stages), coarsest first, and their nodes along x; none without such a level."""
    stated = [s for s in summaries if math.isfinite(s.dT_max)]
    if not stated:
        return {}
    return {"level_state_nodes": Field(np.array([float(s.n) for s in stated]), "1",
                                       "nodes along x of each level solved with its film state (seed and coarse "
                                       "stages), coarsest first"),
            "level_dT_max": Field(np.array([s.dT_max for s in stated]), "K",
                                  "largest temperature rise on each level of level_state_nodes"),
            "level_dT_min": Field(np.array([s.dT_min for s in stated]), "K",
                                  "coldest temperature relative to the inlet on each level of level_state_nodes"),
            "level_mu": Field(np.array([s.mu for s in stated]), "1",
                              "friction coefficient on each level of level_state_nodes")}


def _film_histories(history: History, film_scale: float) -> dict[str, Field]:
    """The film after each cycle (the pressure iteration's own change history of the figures) and the level's nodes
    along x it was on."""
    films = np.array(history.films, dtype=float).reshape(-1, 3)
    return {"cycle_nodes_history": Field(films[:, 0], "1", "nodes along x of the level each cycle ran on"),
            "cycle_h_c_history": Field(films[:, 1] * film_scale, "m", "central film after each cycle"),
            "cycle_h_min_history": Field(films[:, 2] * film_scale, "m", "minimum film after each cycle")}


def _models(solve: Reported, record: SolveRecord) -> dict[str, str]:
    """Which models produced the solution, with their sources; the solver's words rendered from its record."""
    lubricant, mode = solve.lubricant, solve.mode
    models = {
        "viscosity": f"{lubricant.viscosity_model} (Roelands 1966)" if lubricant.viscosity_model == "roelands"
        else "barus (Barus 1893)",
        "density": "dowson_higginson (Dowson & Higginson 1966)" if lubricant.density_model == "dowson_higginson"
        else "incompressible",
        "rheology": "ree_eyring (Ree & Eyring 1955)" if lubricant.rheology == "ree_eyring" else "newtonian",
        "thermal": mode.value,
        "thermal_reason": solve.reason,
        "solver": record.render(),
    }
    if mode is not ThermalMode.OFF:
        models["thermal_solids"] = "Jaeger (1942) high-Peclet moving heat source per surface"
        a, b = lubricant.conductivity_pressure_coefficient, lubricant.conductivity_pressure_saturation
        models["conductivity"] = (f"larsson (Larsson et al. 2000): k_0 [1 + a p/(1 + b p)], a = {a:g}/GPa, "
                                  f"b = {b:g}/GPa" if a > 0.0 else "constant")
    return models
