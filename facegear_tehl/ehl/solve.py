"""Solve one elliptical EHL contact: ContactPoint + Lubricant + SolverSettings -> PointSolution (SI).

Full multigrid (Venner & Lubrecht 2000): the coarsest grid starts from the Hertz pressure with H_0 set so
that the central film equals the Hamrock & Dowson (1977) estimate; each finer grid starts from the bicubic
interpolation of the coarser solution and gets `cycles_per_level` V-cycles; the finest grid then cycles
until the pressure change per cycle is below `tolerance` and the load error below `load_tolerance`
(or `max_cycles` is spent: reported as not converged). The discretisation error is estimated from the
solution one grid coarser, Richardson-scaled for a second-order scheme: e = (H_h - H_2h)/(2^2 - 1).
"""

from __future__ import annotations

from dataclasses import dataclass
import math
import time

import numpy as np

from facegear_tehl.case import SolverSettings
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import grid
from facegear_tehl.ehl.multigrid import Level, MultigridSolver, Problem, Relaxation
from facegear_tehl.ehl.scaling import Scaling, scaling_for
from facegear_tehl.film_formulas import hamrock_dowson_central
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.solution import Field, PointSolution

ORDER = 2  # formal order of the discretisation, for the Richardson-scaled error estimate
DIVERGED_LOAD_ERROR = 0.5  # a relative load error above this after a full cycle means the iteration is running away


@dataclass(frozen=True)
class LevelSummary:
    """Film and pressure figures of one converged full-multigrid level (dimensionless)."""

    n: int
    h_c: float
    h_min: float
    p_max: float


def default_domain(scaling: Scaling) -> tuple[tuple[float, float], tuple[float, float]]:
    """[-3, 3]^2 shifted 1.5 against the entrainment direction (in Hertzian units): 4.5 upstream, 1.5 downstream.

    For entrainment along x this is Venner & Lubrecht's X in [-4.5, 1.5], Y in [-3, 3].
    """
    dx, dy = scaling.wedge_x, scaling.wedge_y
    norm = math.hypot(dx, dy)
    cx, cy = -1.5 * dx / norm, -1.5 * dy / norm
    return (cx - 3.0, cx + 3.0), (cy - 3.0, cy + 3.0)


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


def solve_point(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
    """Solve the isothermal Newtonian EHL problem of one contact point."""
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
    sizes = grid.hierarchy_sizes(settings.grid, settings.coarsest_grid)
    solver = MultigridSolver(problem, sizes, Relaxation())

    summaries: list[LevelSummary] = []
    message = ""
    _start_coarsest(solver, scaling)
    for _ in range(settings.cycles_per_level):
        solver.cycle(0)
    summaries.append(_summary(solver.levels[0]))
    finest = len(solver.levels) - 1
    for index in range(1, finest + 1):
        solver.interpolate_up(index)
        for _ in range(settings.cycles_per_level):
            solver.cycle(index)
        if not _finite(solver.levels[index]):
            finest = index - 1  # report the last level that stayed finite
            message = f"diverged during the full-multigrid start on the {solver.levels[index].nx}^2 grid"
            break
        summaries.append(_summary(solver.levels[index]))

    level = solver.levels[finest]
    change_history, residual_history, load_history = [], [], []
    converged = False
    floor = math.nan
    cycles = settings.cycles_per_level
    best = (math.inf, level.pressure.copy(), level.film.copy(), solver.h0)  # (score, state): the best iterate
    if not message:
        previous = level.pressure.copy()
        for extra in range(settings.max_cycles + 1):
            change = float(np.abs(level.pressure - previous).sum() / max(np.abs(level.pressure).sum(), 1e-300))
            load_error = solver.force_error(level) / problem.load_integral
            residual = solver.residual(level)
            positive = level.pressure > 0.0
            change_history.append(change if extra > 0 else math.nan)
            residual_history.append(float(np.abs(residual[positive]).mean()) if positive.any() else 0.0)
            load_history.append(load_error)
            if abs(load_error) > DIVERGED_LOAD_ERROR:
                message = f"diverged at cycle {cycles} on the finest grid (load error {load_error:.2e})"
                break
            score = (change if extra > 0 else 1.0) + abs(load_error)
            if score < best[0]:
                best = (score, level.pressure.copy(), level.film.copy(), solver.h0)
            if extra > 0 and change < settings.tolerance and abs(load_error) < settings.load_tolerance:
                converged = True
                break
            if _at_algebraic_floor(change_history, load_history, settings):
                converged = True
                floor = change
                break
            if extra == settings.max_cycles:
                message = (
                    f"not converged after {cycles} cycles on the finest grid: pressure change {change:.2e} "
                    f"(tolerance {settings.tolerance:.0e}), load error {load_error:.2e} "
                    f"(tolerance {settings.load_tolerance:.0e})"
                )
                break
            previous = level.pressure.copy()
            solver.cycle(finest)
            cycles += 1
            if not _finite(level):
                message = f"diverged at cycle {cycles} on the finest grid (non-finite pressure or film)"
                break
        if not converged:
            # report the best iterate, not the last (it may be running away)
            _, level.pressure, level.film, solver.h0 = best
            solver.update_film(level)
    wall = time.perf_counter() - start
    return _point_solution(point, lubricant, scaling, solver, level, summaries, converged, message, cycles, wall,
                           change_history, residual_history, load_history, floor)


def _point_solution(point, lubricant, scaling, solver, level, summaries, converged, message, cycles, wall,
                    change_history, residual_history, load_history, floor) -> PointSolution:
    film_scale = scaling.film_scale
    p_h = scaling.p_h
    fine = _summary(level)
    if len(summaries) >= 2 and summaries[-1].n == level.nx:
        coarse = summaries[-2]
        est_hc = (fine.h_c - coarse.h_c) / (2**ORDER - 1) / fine.h_c
        est_hmin = (fine.h_min - coarse.h_min) / (2**ORDER - 1) / fine.h_min
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
        "load_error": (load_error, "1"),
        "iterations": (float(cycles), "1"),
        "work_units": (solver.work_units, "1"),
        "wall_time": (wall, "s"),
        "error_estimate_h_c": (est_hc, "1"),
        "error_estimate_h_min": (est_hmin, "1"),
        "grid": (float(level.nx), "1"),
        "algebraic_floor": (floor, "1"),
    }
    scalars = {k: v for k, v in scalars.items() if math.isfinite(v[0])}
    history = {
        "pressure_change_history": Field(np.nan_to_num(np.array(change_history), nan=0.0), "1",
                                         "relative L1 change of pressure per finest-grid cycle (0: FMG start)"),
        "residual_history": Field(np.array(residual_history), "1",
                                  "mean |Reynolds residual| over pressurised nodes after each cycle"),
        "load_error_history": Field(np.array(load_history), "1", "relative load-balance error after each cycle"),
        "level_h_c": Field(np.array([s.h_c * film_scale for s in summaries]), "m",
                           "central film on each full-multigrid level, coarsest first"),
        "level_h_min": Field(np.array([s.h_min * film_scale for s in summaries]), "m",
                             "minimum film on each full-multigrid level, coarsest first"),
        "level_nodes": Field(np.array([float(s.n) for s in summaries]), "1", "nodes per side of each level"),
    }
    fields = {
        "pressure": Field(level.pressure * p_h, "Pa", "film pressure"),
        "film_thickness": Field(level.film * film_scale, "m", "film thickness"),
    }
    axes = {
        "x": Field(level.x * scaling.b, "m", "node coordinates along the minor axis (x = X b)"),
        "y": Field(level.y * scaling.a, "m", "node coordinates along the major axis (y = Y a)"),
    }
    models = {
        "viscosity": f"{lubricant.viscosity_model} (Roelands 1966)" if lubricant.viscosity_model == "roelands"
        else "barus (Barus 1893)",
        "density": "dowson_higginson (Dowson & Higginson 1966)" if lubricant.density_model == "dowson_higginson"
        else "incompressible",
        "rheology": "newtonian",
        "thermal": "off",
        "solver": "FAS multigrid, line GS / Jacobi distributive (Venner & Lubrecht 2000), FFT deflection",
    }
    return PointSolution(
        name=point.name,
        converged=converged,
        message=message,
        scalars=scalars,
        fields=fields,
        axes=axes,
        history=history,
        models=models,
    )
