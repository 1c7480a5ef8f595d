"""Solve one elliptical EHL contact: ContactPoint + Lubricant + SolverSettings -> PointSolution (SI).

Full multigrid (Venner & Lubrecht 2000) for the isothermal Newtonian film: the coarsest grid starts from the
Hertz pressure with H_0 set so that the central film equals the Hamrock & Dowson (1977) estimate; each finer
grid starts from the bicubic interpolation of the coarser solution and gets `cycles_per_level` V-cycles;
the finest grid then cycles until the pressure change per cycle is below `tolerance` and the load error
below `load_tolerance` (or `max_cycles` is spent: reported as not converged).

Thermal and/or Ree-Eyring films (thermal.py) then iterate an outer loop: the across-film state (temperature
and eta*/eta per layer) is updated from the current pressure and film, frozen into the flow coefficients of
every grid (flow.py), and the pressure is cycled again; the loop stops when temperature, pressure and load
have all converged. The discretisation error is estimated from the isothermal solution one grid coarser,
Richardson-scaled for a second-order scheme: e = (H_h - H_2h)/(2^2 - 1).
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math
import time

import numpy as np

from facegear_tehl.case import SolverSettings
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import grid
from facegear_tehl.ehl.multigrid import Level, MultigridSolver, Problem, Relaxation
from facegear_tehl.ehl.scaling import Scaling, scaling_for
from facegear_tehl.ehl.thermal import FilmState, FilmThermalModel
from facegear_tehl.film_formulas import hamrock_dowson_central
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.solution import Field, PointSolution

ORDER = 2  # formal order of the discretisation, for the Richardson-scaled error estimate
DIVERGED_LOAD_ERROR = 0.5  # a relative load error above this after a full cycle means the iteration is running away
EYRING_LAYERS = 9  # layers for an isothermal Ree-Eyring film
CYCLES_PER_THERMAL_UPDATE = 2  # V-cycles on the pressure between two updates of the film state
THERMAL_RELAXATION = 0.7  # under-relaxation of the layer temperatures between outer iterations
VISCOSITY_RELAXATION = 0.4  # under-relaxation of ln(eta*/eta) between outer iterations


@dataclass(frozen=True)
class LevelSummary:
    """Film and pressure figures of one converged full-multigrid level (dimensionless)."""

    n: int
    h_c: float
    h_min: float
    p_max: float


@dataclass
class _History:
    """Bookkeeping of the finest-grid iteration (solver state, not passed between stages)."""

    changes: list = field(default_factory=list)
    residuals: list = field(default_factory=list)
    loads: list = field(default_factory=list)
    cycles: int = 0
    floor: float = math.nan
    thermal_changes: list = field(default_factory=list)
    thermal_h_c: list = field(default_factory=list)


def default_domain(scaling: Scaling) -> tuple[tuple[float, float], tuple[float, float]]:
    """[-3, 3]^2 shifted 1.5 against the entrainment direction (in Hertzian units): 4.5 upstream, 1.5 downstream.

    For entrainment along x this is Venner & Lubrecht's X in [-4.5, 1.5], Y in [-3, 3].
    """
    dx, dy = scaling.wedge_x, scaling.wedge_y
    norm = math.hypot(dx, dy)
    cx, cy = -1.5 * dx / norm, -1.5 * dy / norm
    return (cx - 3.0, cx + 3.0), (cy - 3.0, cy + 3.0)


def thermal_loading(point: ContactPoint, lubricant: Lubricant) -> float:
    """Thermal loading number L_th = beta eta_0 u_e^2/k_f (Gupta et al. 1992)."""
    return lubricant.temperature_viscosity * lubricant.viscosity * point.entrainment_speed**2 / lubricant.thermal_conductivity


def gupta_reduction(point: ContactPoint, lubricant: Lubricant) -> float:
    """Thermal reduction factor of the central film, phi_T = [1 + 0.1 (1 + 14.8 SRR^0.83) L_th^0.64]^-1
    (Gupta, Cheng, Zhu & Wang 1992, with SRR the slide-to-roll ratio)."""
    srr = abs(point.slide_roll_ratio)
    return 1.0 / (1.0 + 0.1 * (1.0 + 14.8 * srr**0.83) * thermal_loading(point, lubricant) ** 0.64)


# `auto`: predicted error of each model relative to `full`, as a share of the Gupta film reduction 1 - phi_T
# (`off` neglects all of it; `reduced` came within 0.1-0.4 % of `full` in h_c and h_min on the face gear
# points where the thermal reduction is 11-18 %, i.e. ~2 % of it: 5 % is taken, scripts/bench_thermal.py).
AUTO_ERROR_SHARE = {"off": 1.0, "reduced": 0.05}
AUTO_TOLERANCE = 0.01  # accept a model whose predicted h_c error is below 1 %


def thermal_choice(mode: str, point: ContactPoint, lubricant: Lubricant) -> tuple[str, str]:
    """The thermal model to run and why (for `auto`: the cheapest one predicted within 1 % of `full`)."""
    if mode != "auto":
        return mode, f"solver.thermal: {mode}"
    reduction = 1.0 - gupta_reduction(point, lubricant)
    for candidate in ("off", "reduced"):
        predicted = AUTO_ERROR_SHARE[candidate] * reduction
        if predicted < AUTO_TOLERANCE:
            return candidate, (f"auto: Gupta thermal reduction {100 * reduction:.2f} % (L_th = "
                               f"{thermal_loading(point, lubricant):.3g}, SRR = {point.slide_roll_ratio:.3f}); "
                               f"predicted error of {candidate} {100 * predicted:.2f} % < {100 * AUTO_TOLERANCE:g} %")
    return "full", (f"auto: Gupta thermal reduction {100 * reduction:.2f} % (L_th = "
                    f"{thermal_loading(point, lubricant):.3g}, SRR = {point.slide_roll_ratio:.3f}); "
                    f"reduced predicted {100 * AUTO_ERROR_SHARE['reduced'] * reduction:.2f} % >= "
                    f"{100 * AUTO_TOLERANCE:g} %")


def _summary(level: Level) -> LevelSummary:
    return LevelSummary(
        n=level.nx,
        h_c=grid.bilinear_at(level.film, level.x, level.y, 0.0, 0.0),
        h_min=float(level.film.min()),
        p_max=float(level.pressure.max()),
    )


def _finite(level: Level) -> bool:
    return bool(np.isfinite(level.pressure).all() and np.isfinite(level.film).all() and np.isfinite(level.eps).all())


def _at_algebraic_floor(changes: list[float], loads: list[float], settings: SolverSettings) -> bool:
    """The iteration has reached its algebraic floor: the pressure change per cycle stopped falling
    (by less than 20 % over two cycles) below 10x the tolerance, and the load error averaged over the last
    two cycles is within tolerance. The floor is a period-2 flicker of the nodes at the pressure spike and on
    the cavitation boundary (a few 1e-4 of the pressure); h_c and h_min are then steady to about 1e-5.
    """
    if len(changes) < 5:
        return False
    stalled = changes[-1] > 0.8 * changes[-3]
    small = changes[-1] < 10.0 * settings.tolerance
    balanced = abs(0.5 * (loads[-1] + loads[-2])) < settings.load_tolerance
    return stalled and small and balanced


def _start_coarsest(solver: MultigridSolver, scaling: Scaling) -> None:
    level = solver.levels[0]
    solver.reset_rhs(level)
    xx, yy = np.meshgrid(level.x, level.y)
    level.pressure = np.sqrt(np.maximum(1.0 - xx**2 - yy**2, 0.0))
    level.pressure[0, :] = level.pressure[-1, :] = 0.0
    level.pressure[:, 0] = level.pressure[:, -1] = 0.0
    solver.h0 = 0.0
    solver.update_film(level)
    # H_0 such that the Hertzian film at the centre equals the Hamrock-Dowson central film.
    h_c_guess = (
        hamrock_dowson_central(scaling.hamrock_u, scaling.hamrock_g, scaling.hamrock_w, scaling.ellipticity)
        * scaling.hertz.radius_x
        / scaling.film_scale
    )
    solver.h0 = h_c_guess - grid.bilinear_at(level.film, level.x, level.y, 0.0, 0.0)
    solver.update_film(level)


def _full_multigrid(solver: MultigridSolver, scaling: Scaling, settings: SolverSettings, summaries: list,
                    first: int, last: int):
    """Full-multigrid steps from level `first` (0: start from Hertz) up to `last`; appends level summaries.

    Returns (index of the finest finite level, message)."""
    if first == 0:
        _start_coarsest(solver, scaling)
        for _ in range(settings.cycles_per_level):
            solver.cycle(0)
        summaries.append(_summary(solver.levels[0]))
        first = 1
    for index in range(first, last + 1):
        solver.interpolate_up(index)
        for _ in range(settings.cycles_per_level):
            solver.cycle(index)
        if not _finite(solver.levels[index]):
            return index - 1, f"diverged during the full-multigrid start on the {solver.levels[index].nx}^2 grid"
        summaries.append(_summary(solver.levels[index]))
    return last, ""


def _cycle(solver: MultigridSolver, index: int, settings: SolverSettings, history: _History, max_cycles: int,
           best: list | None) -> tuple[bool, str]:
    """V-cycles on level `index` until the tolerances are met, at most `max_cycles`; returns (met, message).

    `best` (if given) keeps the best iterate [score, pressure, film, h0] for reporting a non-converged solve.
    """
    level = solver.levels[index]
    load_integral = solver.problem.load_integral
    previous = level.pressure.copy()
    for extra in range(max_cycles + 1):
        change = float(np.abs(level.pressure - previous).sum() / max(np.abs(level.pressure).sum(), 1e-300))
        load_error = solver.force_error(level) / load_integral
        residual = solver.residual(level)
        positive = level.pressure > 0.0
        if extra > 0 or not history.changes:
            history.changes.append(change if extra > 0 else math.nan)
            history.residuals.append(float(np.abs(residual[positive]).mean()) if positive.any() else 0.0)
            history.loads.append(load_error)
        if abs(load_error) > DIVERGED_LOAD_ERROR:
            return False, f"diverged at cycle {history.cycles} on the finest grid (load error {load_error:.2e})"
        if best is not None:
            score = (change if extra > 0 else 1.0) + abs(load_error)
            if score < best[0]:
                best[:] = [score, level.pressure.copy(), level.film.copy(), solver.h0]
        if extra > 0 and change < settings.tolerance and abs(load_error) < settings.load_tolerance:
            return True, ""
        if extra > 0 and _at_algebraic_floor(history.changes, history.loads, settings):
            history.floor = change
            return True, ""
        if extra == max_cycles:
            return False, (
                f"not converged after {history.cycles} cycles on the finest grid: pressure change {change:.2e} "
                f"(tolerance {settings.tolerance:.0e}), load error {load_error:.2e} "
                f"(tolerance {settings.load_tolerance:.0e})"
            )
        previous = level.pressure.copy()
        solver.cycle(index)
        history.cycles += 1
        if not _finite(level):
            return False, f"diverged at cycle {history.cycles} on the finest grid (non-finite pressure or film)"
    return False, ""


def _freeze_film_state(solver: MultigridSolver, index: int, state: FilmState) -> None:
    """Give every grid the film state (injected to coarse grids) and recompute its flow coefficients."""
    for level_index in range(index + 1):
        stride = 2 ** (index - level_index)
        level = solver.levels[level_index]
        level.temperature = np.ascontiguousarray(state.temperature[:, ::stride, ::stride])
        level.viscosity_factor = np.ascontiguousarray(state.viscosity_factor[:, ::stride, ::stride])
        if level_index == index:
            solver.update_film(level)


def solve_point(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
    """Solve the EHL problem of one contact point (thermal model and rheology as the settings say)."""
    start = time.perf_counter()
    scaling = scaling_for(point, lubricant)
    if settings.domain_x is None or settings.domain_y is None:
        domain_x, domain_y = default_domain(scaling)
    else:
        domain_x, domain_y = settings.domain_x, settings.domain_y
    problem = Problem(
        lam=scaling.lam,
        deflection_coefficient=scaling.deflection_coefficient,
        ellipticity=scaling.ellipticity,
        geometry_y=scaling.geometry_y,
        wedge_x=scaling.wedge_x,
        wedge_y=scaling.wedge_y,
        p_hertz=scaling.p_h,
        law=lubricant.law_parameters(),
        inlet_temperature=lubricant.inlet_temperature,
        velocity_1=np.asarray(point.velocity_1) / point.entrainment_speed,
        velocity_2=np.asarray(point.velocity_2) / point.entrainment_speed,
        domain_x=domain_x,
        domain_y=domain_y,
    )
    solver = MultigridSolver(problem, grid.hierarchy_sizes(settings.grid, settings.coarsest_grid), Relaxation())
    mode, reason = thermal_choice(settings.thermal, point, lubricant)
    coupled = mode != "off" or lubricant.rheology == "ree_eyring"
    top = len(solver.levels) - 1
    summaries: list[LevelSummary] = []
    history = _History(cycles=settings.cycles_per_level)
    state = None
    converged = False
    if mode == "reduced" and top > 0:
        # the coupled problem one grid coarser, its film state interpolated and frozen on the finest grid
        finest, message = _full_multigrid(solver, scaling, settings, summaries, 0, top - 1)
        if not message:
            converged, message = _cycle(solver, finest, settings, history, settings.max_cycles, None)
            coarse_state, converged, message = _couple(solver, finest, point, lubricant, scaling, settings, mode,
                                                       history)
            if coarse_state is not None and not message.startswith("diverged"):
                summaries[-1] = _summary(solver.levels[finest])  # the coarse level, now with its film state
                state, converged, message = _finish_on_fine_grid(solver, top, coarse_state, point, lubricant,
                                                                 scaling, settings, history)
                finest = top
                summaries.append(_summary(solver.levels[top]))
        level = solver.levels[finest]
    else:
        finest, message = _full_multigrid(solver, scaling, settings, summaries, 0, top)
        level = solver.levels[finest]
        converged = False
        best: list = [math.inf, level.pressure.copy(), level.film.copy(), solver.h0]
        if not message:
            converged, message = _cycle(solver, finest, settings, history, settings.max_cycles,
                                        None if coupled else best)
            if coupled and not message.startswith("diverged"):
                state, converged, message = _couple(solver, finest, point, lubricant, scaling, settings, mode, history)
        if not coupled and not converged:
            # report the best iterate, not the last (it may be running away)
            _, level.pressure, level.film, solver.h0 = best
            solver.update_film(level)
    if level.film.min() <= 0.0:
        converged = False
        message = ("the film closes (h_min <= 0: solid contact, outside the EHL model)" + ("; " + message if message
                                                                                           else ""))
    wall = time.perf_counter() - start
    return _point_solution(point, lubricant, scaling, solver, level, summaries, converged, message, wall, history,
                           state, mode, reason)


def _film_model(level: Level, point, lubricant, scaling, settings, mode) -> FilmThermalModel:
    layers = settings.thermal_layers if mode != "off" else EYRING_LAYERS
    return FilmThermalModel(level.x * scaling.b, level.y * scaling.a, layers, lubricant, point.body_1, point.body_2,
                            np.asarray(point.velocity_1), np.asarray(point.velocity_2), scaling.b,
                            solve_energy=mode != "off")


def _finish_on_fine_grid(solver, index, coarse_state, point, lubricant, scaling, settings, history):
    """`reduced`: freeze the interpolated coarse film state on every grid, converge the finest pressure, then
    evaluate the film state once on the finest grid for the outputs. Returns (state, converged, message)."""
    solver.interpolate_up(index)
    frozen = FilmState(**{**coarse_state.__dict__,
                          "temperature": _prolong_layers(coarse_state.temperature),
                          "viscosity_factor": np.exp(_prolong_layers(np.log(coarse_state.viscosity_factor)))})
    _freeze_film_state(solver, index, frozen)
    converged, message = _cycle(solver, index, settings, history, settings.max_cycles, None)
    level = solver.levels[index]
    model = _film_model(level, point, lubricant, scaling, settings, "reduced")
    state = model.update(level.pressure * scaling.p_h, level.film * scaling.film_scale, frozen.temperature)
    return state, converged, message


def _prolong_layers(field: np.ndarray) -> np.ndarray:
    return np.stack([grid.prolong_bilinear(layer) for layer in field])


def _couple(solver, index, point, lubricant, scaling, settings, mode, history):
    """Outer loop of the film state and the pressure; returns (film state, converged, message)."""
    level = solver.levels[index]
    model = _film_model(level, point, lubricant, scaling, settings, mode)
    temperature = model.initial_temperature()
    factor = np.ones_like(temperature)
    state = None
    last_finite = None
    for outer in range(settings.max_thermal_iterations):
        update = model.update(level.pressure * scaling.p_h, level.film * scaling.film_scale, temperature)
        w = THERMAL_RELAXATION
        new = temperature + w * (update.temperature - temperature)
        thermal_change = float(np.abs(new - temperature).max())
        temperature = new
        v = VISCOSITY_RELAXATION
        factor = factor ** (1.0 - v) * update.viscosity_factor**v  # eta*/eta relaxed in log space
        candidate = FilmState(**{**update.__dict__, "temperature": temperature, "viscosity_factor": factor})
        if not (np.isfinite(temperature).all() and np.isfinite(factor).all()):
            message = f"diverged in the film temperature at outer iteration {outer + 1}"
            break
        state = candidate
        _freeze_film_state(solver, index, state)
        met, message = _cycle(solver, index, settings, history, CYCLES_PER_THERMAL_UPDATE, None)
        history.thermal_changes.append(thermal_change)
        history.thermal_h_c.append(grid.bilinear_at(level.film, level.x, level.y, 0.0, 0.0) * scaling.film_scale)
        if message.startswith("diverged"):
            break
        last_finite = (level.pressure.copy(), level.film.copy(), solver.h0, state)
        rise = float(temperature.max() - lubricant.inlet_temperature)
        if outer > 0 and met and thermal_change < settings.thermal_tolerance * max(rise, 1.0):
            return state, True, ""
    if message.startswith("diverged"):
        if last_finite is None:
            return None, False, message
        level.pressure, level.film, solver.h0, state = last_finite  # report the last finite iterate
        return state, False, message
    return state, False, (
        f"thermal loop not converged after {settings.max_thermal_iterations} outer iterations: temperature change "
        f"{history.thermal_changes[-1]:.2e} K (tolerance {settings.thermal_tolerance:.0e} of the rise), last "
        f"pressure change {history.changes[-1]:.2e}"
    )


def _friction(state: FilmState, pressure: np.ndarray, cell: float, load: float) -> tuple[float, float, float]:
    """Friction coefficients from the shear stresses over the pressurised film: mu_i = |F_i|/W with the traction
    on body 1, F_1 = \\iint tau(z = 0) dA, and on body 2, F_2 = -\\iint tau(z = h) dA (Couette and Poiseuille
    parts); returns (mean of mu_1 and mu_2, mu_1, mu_2)."""
    wet = pressure > 0.0
    f1 = np.array([state.stress_1[0][wet].sum(), state.stress_1[1][wet].sum()]) * cell
    f2 = np.array([state.stress_2[0][wet].sum(), state.stress_2[1][wet].sum()]) * cell
    mu_1, mu_2 = float(np.hypot(*f1) / load), float(np.hypot(*f2) / load)
    return 0.5 * (mu_1 + mu_2), mu_1, mu_2


def _simpson(nz: int) -> np.ndarray:
    """Simpson weights of nz (odd) equally spaced nodes on [0, 1]."""
    w = np.full(nz, 2.0)
    w[1::2] = 4.0
    w[0] = w[-1] = 1.0
    return w / (3.0 * (nz - 1))


def energy_budget(state: FilmState, film: np.ndarray, dx: float, dy: float, rho_c: np.ndarray,
                  t_inlet: float) -> dict[str, float]:
    """Power dissipated by shear in the film, heat generated in it (dissipation + compression), conducted into
    the solids and convected out of the domain by the oil (enthalpy flux through its boundary), W; and the
    relative imbalance."""
    depth = _simpson(state.temperature.shape[0])[:, None, None] * film[None, :, :]
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


def _point_solution(point, lubricant, scaling, solver, level, summaries, converged, message, wall, history,
                    state, mode, reason) -> PointSolution:
    film_scale = scaling.film_scale
    p_h = scaling.p_h
    fine = _summary(level)
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
        "algebraic_floor": (history.floor, "1"),
    }
    fields = {
        "pressure": Field(level.pressure * p_h, "Pa", "film pressure"),
        "film_thickness": Field(level.film * film_scale, "m", "film thickness"),
    }
    if state is not None:
        t_in = lubricant.inlet_temperature
        cell = (level.x[1] - level.x[0]) * scaling.b * (level.y[1] - level.y[0]) * scaling.a
        mu, mu_1, mu_2 = _friction(state, level.pressure, cell, point.load)
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
            "thermal_layers": (float(temperature.shape[0]), "1"),
        })
        weights = _simpson(temperature.shape[0])
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
    return PointSolution(name=point.name, converged=converged, message=message, scalars=scalars, fields=fields,
                         axes={"x": Field(level.x * scaling.b, "m", "node coordinates along the minor axis (x = X b)"),
                               "y": Field(level.y * scaling.a, "m", "node coordinates along the major axis (y = Y a)")},
                         history=hist, models=models)
