"""Solve one elliptical EHL contact: ContactPoint + Lubricant + SolverSettings -> PointSolution (SI).

Full multigrid (Venner & Lubrecht 2000) for the isothermal Newtonian film: the coarsest grid starts from the
Hertz pressure with H_0 set so that the central film equals the Hamrock & Dowson (1977) estimate; each finer
grid starts from the bicubic interpolation of the coarser solution and gets `cycles_per_level` V-cycles;
the finest grid then cycles until the pressure change per cycle is below `tolerance` and the load error
below `load_tolerance` (or `max_cycles` is spent: reported as not converged).

Thermal and/or Ree-Eyring films (thermal.py) then iterate an outer loop: the across-film state (temperature
and eta*/eta per layer) is updated from the current pressure and film, frozen into the flow coefficients of
every grid (flow.py), and the pressure is cycled again; the loop stops when temperature, pressure and load
have all converged. From 129^2 up a thermal solve is a thermal full multigrid in two stages: the coupled
problem one grid coarser (`begin_point`, which returns a picklable `Stage`), then the finest grid from its
interpolated state (`finish_point`); `solve_point` composes them, parallel.solve_each may run them in
different workers. The discretisation error is estimated from the solution one grid coarser (isothermal, or
the coarse thermal stage), Richardson-scaled for a second-order scheme: e = (H_h - H_2h)/(2^2 - 1).
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math
import time

import numpy as np

from facegear_tehl.case import SolverSettings
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import flow, grid
from facegear_tehl.ehl.multigrid import Level, MultigridSolver, Problem, Relaxation
from facegear_tehl.ehl.scaling import Scaling, scaling_for
from facegear_tehl.ehl.report import (ORDER, LevelSummary, point_solution, richardson_error, summarise,
                                      with_film_state)
from facegear_tehl.ehl.thermal import FilmState, FilmThermalModel, thermal_choice
from facegear_tehl.film_formulas import hamrock_dowson_central
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.solution import PointSolution

DIVERGED_LOAD_ERROR = 0.5  # a relative load error above this after a full cycle means the iteration is running away
EYRING_LAYERS = 9  # layers for an isothermal Ree-Eyring film
CYCLES_PER_THERMAL_UPDATE = 2  # V-cycles on the pressure between two updates of the film state
THERMAL_RELAXATION = 0.7  # under-relaxation of the layer temperatures between outer iterations
VISCOSITY_RELAXATION = 0.4  # under-relaxation of ln(eta*/eta) between outer iterations
MIN_COARSE_THERMAL_GRID = 65  # the coupled problem is solved one grid coarser first only from this grid up


@dataclass
class _History:
    """Bookkeeping of the finest-grid iteration (solver state, not passed between stages)."""

    changes: list = field(default_factory=list)
    residuals: list = field(default_factory=list)
    loads: list = field(default_factory=list)
    cycles: int = 0
    floor: float = math.nan
    thermal_floor: float = math.nan
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
    return stalled and small and _balanced(loads, settings)


def _balanced(loads: list[float], settings: SolverSettings) -> bool:
    """The load error averaged over the last two cycles is within tolerance."""
    return len(loads) >= 2 and abs(0.5 * (loads[-1] + loads[-2])) < settings.load_tolerance


THERMAL_FLOOR_WINDOW = 8  # outer iterations over which a stalled thermal change is judged
THERMAL_FLOOR_FRACTION = 0.01  # largest stalled change accepted, as a fraction of the temperature rise
THERMAL_FLOOR_H_C = 5e-4  # largest relative spread of h_c over the window (its grid error: 1e-3 to 6e-3)


def _at_thermal_floor(changes: list[float], h_c: list[float], rise: float, h_c_error: float = 0.0) -> bool:
    """The outer loop has reached its algebraic floor: over the last THERMAL_FLOOR_WINDOW outer iterations
    (of this grid) the largest temperature change stopped falling (the smallest change of the last half is
    above half the smallest of the first half), stays below 1 % of the temperature rise, and h_c is steady
    to 5e-4 or to half its estimated discretisation error `h_c_error` (relative), if larger (the error is
    1e-3 to 6e-3 on 129^2-257^2). What is left is a period-2 flicker of a few nodes where a layer velocity changes sign between
    iterations (the upwind direction of the energy equation switches; under-relaxing the temperature only
    scales it): e.g. the heaviest face gear point of cases/hard, 0.43 K at the inlet edge with a 98 K rise.
    """
    n = THERMAL_FLOOR_WINDOW
    if len(changes) < n:
        return False
    recent, films = changes[-n:], h_c[-n:]
    half = n // 2
    stalled = min(recent[half:]) > 0.5 * min(recent[:half])
    small = max(recent) < THERMAL_FLOOR_FRACTION * max(rise, 1.0)
    steady = (max(films) - min(films)) <= max(THERMAL_FLOOR_H_C, 0.5 * h_c_error) * abs(films[-1])
    return stalled and small and steady


def _h_c_error(h_c: float, coarse_h_c: float) -> float:
    """|Richardson estimate| of the relative error of h_c (m) from h_c one grid coarser (m); 0 without it."""
    return abs(richardson_error(h_c, coarse_h_c, ORDER)) if math.isfinite(coarse_h_c) and h_c != 0.0 else 0.0


def _pressure_settled(history: _History, settings: SolverSettings) -> bool:
    """Between film-state updates the pressure stays within its algebraic floor (_at_algebraic_floor's bound:
    the last four changes per cycle below 10x the tolerance, the load error of the last two cycles within
    tolerance), though two cycles per update are too few to see it stall."""
    changes = history.changes[-4:]
    return len(changes) == 4 and max(changes) < 10.0 * settings.tolerance and _balanced(history.loads, settings)


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
        summaries.append(summarise(solver.levels[0]))
        first = 1
    snapshot = (solver.levels[first - 1].pressure.copy(), solver.h0)
    for index in range(first, last + 1):
        solver.interpolate_up(index)
        for _ in range(settings.cycles_per_level):
            solver.cycle(index)
        level = solver.levels[index]
        diverged = not _finite(level) or abs(solver.force_error(level)) > DIVERGED_LOAD_ERROR * solver.problem.load_integral
        if diverged:
            # the coarser level was overwritten by the FAS cycles of this one: restore its own solution
            coarser = solver.levels[index - 1]
            solver.reset_rhs(coarser)
            coarser.pressure, solver.h0 = snapshot
            solver.update_film(coarser)
            return index - 1, f"diverged during the full-multigrid start on the {level.nx}^2 grid"
        snapshot = (level.pressure.copy(), solver.h0)
        summaries.append(summarise(level))
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
    top = solver.levels[index]
    for level_index in range(index + 1):
        level = solver.levels[level_index]
        sx, sy = (top.nx - 1) // (level.nx - 1), (top.ny - 1) // (level.ny - 1)
        level.temperature = np.ascontiguousarray(state.temperature[:, ::sy, ::sx])
        level.viscosity_factor = np.ascontiguousarray(state.viscosity_factor[:, ::sy, ::sx])
        level.temperature_factor = flow.temperature_factors(level.temperature, solver.problem.law)
        if level_index == index:
            solver.update_film(level)


def solve_point(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
    """Solve the EHL problem of one contact point (thermal model and rheology as the settings say).

    Convergence policy: a solve that runs away is repeated once with the other Gauss-Seidel / Jacobi switch
    (the ellipse-scaled one first, then Venner's circle value; multigrid.Level), and the retry is reported.
    The same steps, split into stages that can run in different processes: `begin_point`, `finish_point`,
    `needs_retry`, `with_retry` (parallel.solve_each).
    """
    first = _through(begin_point(point, lubricant, settings))
    if not needs_retry(first):
        return first
    return with_retry(first, _through(begin_point(point, lubricant, settings, retry_after=first)))


def _through(begun: "PointSolution | Stage") -> PointSolution:
    return finish_point(begun) if isinstance(begun, Stage) else begun


def needs_retry(solution: PointSolution) -> bool:
    """The first attempt ran away: repeat it with Venner's switch."""
    return not solution.converged and "diverged" in solution.message


def with_retry(first: PointSolution, retry: PointSolution) -> PointSolution:
    """The retry's solution, noted, if it did better than running away; else the first attempt's."""
    if retry.converged or "diverged" not in retry.message:
        note = f"converged after a retry with Venner's switch (first attempt: {first.message})"
        return PointSolution(**{**retry.__dict__, "message": retry.message or "", "models": {
            **retry.models, "solver": retry.models["solver"] + "; " + note}})
    return first


@dataclass
class Stage:
    """A thermal full-multigrid solve after its coarse stage (the coupled problem one grid coarser, converged),
    before the fine stage: everything `finish_point` needs, picklable, so that the two stages of a point can
    run in different processes (parallel.solve_each) with the same result as in one."""

    point: ContactPoint
    lubricant: Lubricant
    settings: SolverSettings
    scaling: Scaling
    solver: MultigridSolver
    mode: str
    reason: str
    summaries: list
    history: _History
    coarse_state: FilmState
    elapsed: float  # s spent so far (first attempt included)


def begin_point(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
                retry_after: PointSolution | None = None) -> "PointSolution | Stage":
    """The solve up to the end of its coarse thermal stage (a Stage), or the whole solve when it has no
    separate fine stage or the coarse stage failed. `retry_after`: the first attempt, which ran away: this
    one uses Venner's switch, and its wall time counts the first's."""
    relaxation = Relaxation() if retry_after is None else Relaxation(scale_switch=False)
    start = time.perf_counter() - (0.0 if retry_after is None else retry_after.scalar("wall_time"))
    return _solve(point, lubricant, settings, relaxation, start)


def _solve(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings, relaxation: Relaxation,
           start: float) -> PointSolution:
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
    shapes = grid.hierarchy_shapes(settings.grid, settings.nodes_y, settings.coarsest_grid)
    solver = MultigridSolver(problem, shapes, relaxation)
    mode, reason = thermal_choice(settings.thermal, point, lubricant)
    coupled = mode != "off" or lubricant.rheology == "ree_eyring"
    top = len(solver.levels) - 1
    summaries: list[LevelSummary] = []
    history = _History(cycles=settings.cycles_per_level)
    state = None
    converged = False
    if mode != "off" and top > 0 and solver.levels[top - 1].nx >= MIN_COARSE_THERMAL_GRID:
        # thermal full multigrid: the coupled problem one grid coarser first, its film state interpolated and
        # frozen on the finest grid; `reduced` stops there (one film-state evaluation for the outputs), `full`
        # goes on coupling on the finest grid from that state (below 65^2 both couple on the finest grid)
        finest, message = _full_multigrid(solver, scaling, settings, summaries, 0, top - 1)
        if not message:
            converged, message = _cycle(solver, finest, settings, history, settings.max_cycles, None)
            coarse_state, converged, message = _couple(solver, finest, point, lubricant, scaling, settings, mode,
                                                       history)
            if coarse_state is not None and not message.startswith("diverged"):
                return Stage(point, lubricant, settings, scaling, solver, mode, reason, summaries, history,
                             coarse_state, time.perf_counter() - start)
            state = coarse_state
        level = solver.levels[finest]
    else:
        finest, message = _full_multigrid(solver, scaling, settings, summaries, 0, top)
        level = solver.levels[finest]
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
    return _report(point, lubricant, scaling, solver, level, summaries, converged, message, start, history, state,
                   mode, reason)


def finish_point(stage: Stage) -> PointSolution:
    """The fine stage of a thermal full-multigrid solve: the coarse solution and film state interpolated and
    frozen on the finest grid, its pressure converged; `reduced` evaluates the film state once there, `full`
    couples again on the finest grid. A finest grid that runs away reports the converged coarse solution."""
    start = time.perf_counter() - stage.elapsed
    solver, summaries, history, coarse_state = stage.solver, stage.summaries, stage.history, stage.coarse_state
    point, lubricant, scaling, settings, mode = stage.point, stage.lubricant, stage.scaling, stage.settings, stage.mode
    top = len(solver.levels) - 1
    finest = top - 1
    coarse = solver.levels[finest]
    # the coarse level, now with its film state (its dT_max and mu give the fine grid's error estimates)
    summaries[-1] = with_film_state(summarise(coarse), coarse, coarse_state, scaling, point.load,
                                    lubricant.inlet_temperature)
    snapshot = (coarse.pressure.copy(), solver.h0)
    frozen, converged, message = _start_fine_grid(solver, top, coarse_state, settings, history)
    if message.startswith("diverged"):
        # the finest grid ran away: report the converged coarse-grid solution, flagged
        solver.reset_rhs(coarse)
        coarse.pressure, solver.h0 = snapshot
        _freeze_film_state(solver, finest, coarse_state)
        state = coarse_state
        message = f"finest grid: {message}; the result is the {coarse.nx}^2 solution"
        converged = False
    else:
        finest = top
        if mode == "reduced":
            fine = solver.levels[top]
            model = _film_model(fine, point, lubricant, scaling, settings, mode)
            state = model.update(fine.pressure * scaling.p_h, fine.film * scaling.film_scale, frozen.temperature)
        else:
            state, converged, message = _couple(solver, top, point, lubricant, scaling, settings, mode, history,
                                                frozen, summaries[-1].h_c)
        summaries.append(summarise(solver.levels[top]))
    return _report(point, lubricant, scaling, solver, solver.levels[finest], summaries, converged, message, start,
                   history, state, mode, stage.reason)


def _report(point, lubricant, scaling, solver, level, summaries, converged, message, start, history, state, mode,
            reason) -> PointSolution:
    if level.film.min() <= 0.0:
        converged = False
        message = ("the film closes (h_min <= 0: solid contact, outside the EHL model)" + ("; " + message if message
                                                                                           else ""))
    wall = time.perf_counter() - start
    return point_solution(point, lubricant, scaling, solver, level, summaries, converged, message, wall, history,
                           state, mode, reason)


def _film_model(level: Level, point, lubricant, scaling, settings, mode) -> FilmThermalModel:
    layers = settings.thermal_layers if mode != "off" else EYRING_LAYERS
    return FilmThermalModel(level.x * scaling.b, level.y * scaling.a, layers, lubricant, point.body_1, point.body_2,
                            np.asarray(point.velocity_1), np.asarray(point.velocity_2), scaling.b,
                            solve_energy=mode != "off")


def _start_fine_grid(solver, index, coarse_state, settings, history):
    """Interpolate the coarse solution and film state to the finest grid, freeze the state on every grid and
    converge the pressure against it. Returns (frozen state, converged, message)."""
    solver.interpolate_up(index)
    frozen = FilmState(**{**coarse_state.__dict__,
                          "temperature": _prolong_layers(solver, index, coarse_state.temperature),
                          "viscosity_factor": np.exp(_prolong_layers(solver, index,
                                                                     np.log(coarse_state.viscosity_factor)))})
    _freeze_film_state(solver, index, frozen)
    converged, message = _cycle(solver, index, settings, history, settings.max_cycles, None)
    return frozen, converged, message


def _prolong_layers(solver: MultigridSolver, index: int, field: np.ndarray) -> np.ndarray:
    """Each layer of `field` (nz, ny, nx) of level `index - 1` interpolated to level `index`."""
    return np.stack([solver.transfers[index].prolong(layer) for layer in field])


def _couple(solver, index, point, lubricant, scaling, settings, mode, history, initial: FilmState | None = None,
            coarse_h_c: float = math.nan):
    """Outer loop of the film state and the pressure on level `index`, from `initial` (default: the inlet
    temperature and a Newtonian film); returns (film state, converged, message). If the iteration runs away,
    the last finite iterate (at worst the entry state) is restored and reported with the reason. coarse_h_c:
    the dimensionless h_c one grid coarser, for the discretisation error the thermal floor is judged against."""
    level = solver.levels[index]
    model = _film_model(level, point, lubricant, scaling, settings, mode)
    temperature = model.initial_temperature() if initial is None else initial.temperature
    factor = np.ones_like(temperature) if initial is None else initial.viscosity_factor
    state = initial
    last_finite = (level.pressure.copy(), level.film.copy(), solver.h0, initial)
    first = len(history.thermal_changes)  # this grid's outer iterations start here
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
        if ((met or _pressure_settled(history, settings))
                and _at_thermal_floor(history.thermal_changes[first:], history.thermal_h_c[first:], rise,
                                      _h_c_error(history.thermal_h_c[-1], coarse_h_c * scaling.film_scale))):
            history.thermal_floor = thermal_change
            return state, True, ""
    if message.startswith("diverged"):
        level.pressure, level.film, solver.h0, state = last_finite  # report the last finite iterate
        if state is not None:
            _freeze_film_state(solver, index, state)
            if state is initial:  # an interpolated state: evaluate it on this grid for the outputs
                state = model.update(level.pressure * scaling.p_h, level.film * scaling.film_scale,
                                     initial.temperature)
        else:
            level.temperature = level.viscosity_factor = level.temperature_factor = None
            solver.update_film(level)
        return state, False, message
    return state, False, (
        f"thermal loop not converged after {settings.max_thermal_iterations} outer iterations: temperature change "
        f"{history.thermal_changes[-1]:.2e} K (tolerance {settings.thermal_tolerance:.0e} of the rise), last "
        f"pressure change {history.changes[-1]:.2e}"
    )
