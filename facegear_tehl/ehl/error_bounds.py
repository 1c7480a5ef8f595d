"""Error bounds of a solve's reported figures, and the figures a solve cannot bound ("unresolved").

A reported error estimate is a promise: the bound of a figure f solved on nx x ny nodes is

    B = F_s (|e_x| + e_ref + |e_y|) + e_it,

e_x the Richardson estimate of the solve from the grid one coarser along x alone (report.estimate), checked against the
next coarser pair along x where a third grid is at hand (`three_grid_estimate`: Roache's asymptotic-range check; the
solve's own levels, `coarser_estimates`, the seed stage's film state among them, or the grid the solve was refined from,
`with_coarser_pair`: the accuracy target's last grid, run.py's refinement's), e_ref the iteration
error of the grid e_x compares with (`reference_error`: the coarse stage's loop stops at its own tolerance), e_y the
Richardson
estimate along y (`y_estimates`), e_it the error the iteration left, from its last changes and contraction rate
(`iteration_error`: the outer loop's where the solve has one, else the finest grid's pressure cycles') and F_s =
TUNING.bound_safety, the factor of Roache's grid convergence index (Roache 1994, J. Fluids Eng. 116: 405-413; Roache
1998, "Verification and Validation in Computational Science and Engineering", ch. 5: F_s = 3 for an estimate from two
grids at an assumed order). The x-only hierarchy never refines y, so e_y comes from one more solve of the same point and
model on the solved domain with (ny + 1)/2 nodes along y. Under the additive error model f = f* + C_x h_x^p + C_y h_y^p
(Roache 1998, ch. 5) the y-error does not depend on h_x, so where the solve has a converged coarse stage at (nx + 1)/2 x
ny (a thermal full multigrid), the check solves (nx + 1)/2 x (ny + 1)/2 and e_y = (f_stage - f_check)/((2^p - 1) f): a
quarter of the finest grid's nodes instead of half. Without a coarse stage the check solves nx x (ny + 1)/2 against the
solution itself. On a square finest grid e_x covers both axes (e_y = 0).

A figure is "unresolved" (`unresolved_<name>` = 1 in the file, the word in the tables) where no bound can be given: a
solve that did not converge; no e_x or no e_y (ny is the coarsest grid, or the check did not converge); an e_x or e_y
above TUNING.asymptotic_estimate, or three grids along x whose differences change sign or fall slower than the lowest
order F_s covers (outside the asymptotic range); an x-estimate of another model (a thermal solve without its coarse
stage compares its isothermal start's levels: `estimated_in_model`); its feature (the lowest film's basin, the hot or
the cold spot) spanning fewer than TUNING.feature_nodes nodes along x or y (`feature_nodes`); p_max always (UNBOUNDED);
h_c and h_min of a solve without an outer loop whose pressure cycles left the film `drifting` one way without
contracting (its iteration error has no bound); any figure whose iteration error e_it (`iteration_error_<name>` in the
file, the reason) exceeds TUNING.max_iteration_error, as a loop ended at its floor can leave it (the full step no longer
contracting at the smallest relaxation: e_it is the amplitude of its last window, `floor_error`); and dT_max where the
film's compression, not its shear, sets its temperatures through the outlet spike (`compression_held`); and every
figure of a thermal solve whose energy balance misses TUNING.max_energy_imbalance (`energy_unbalanced`: its film state
is not a solution of the discrete energy equation, so neither its temperatures nor the viscosities they set are known
to the loop's tolerance); and every figure of a film whose inlet reaches fewer than TUNING.min_inlet_gap_ratio central
films (`domain.starved_inlet`: the truncated inlet starves h_c by more than asymptotic_estimate), or whose domain's
sides hold more than TUNING.max_side_pressure of its peak pressure (`domain.starved_sides`).
docs/accuracy.md (error bounds) holds the calibration that chose these rules.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
import math
import time

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.asymptotic_range import CoarserPair, observed_order, three_grid_estimate
from facegear_tehl.ehl.convergence import drifting
from facegear_tehl.ehl.domain import starved_inlet, starved_sides
from facegear_tehl.ehl.energy_balance import energy_unbalanced
from facegear_tehl.ehl.grid import hierarchy_shapes
from facegear_tehl.ehl.report import ORDER_DT_MAX, ORDER_MU, LevelSummary
from facegear_tehl.ehl.richardson import ORDER
from facegear_tehl.ehl.scaling import Scaling
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.ehl.unresolved import Why
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.record import Stage
from facegear_tehl.settings import OutletRefinement, SolverSettings
from facegear_tehl.solution import Outcome, PointSolution

# p_max is never bounded: the pressure maximum is the outlet spike, or a dome that grows into one under refinement,
# whose height grows with every refinement on practical grids (Venner & Lubrecht 2000, ch. 8; the calibration in
# docs/accuracy.md: a bound F_s (|e_x| + |e_y|) held for 87 % of the p_max and understated four more than twofold).
UNBOUNDED = ("p_max",)
FILM_FIGURES = ("h_c", "h_min", "p_max")  # figures of every film
STATE_FIGURES = ("dT_max", "dT_min", "mu")  # figures of the film state (thermal or Ree-Eyring solves)
FIGURES = FILM_FIGURES + STATE_FIGURES
# the order each figure's estimates assume (report.py): second for the film and p_max, first for the film state's
ORDERS = {"h_c": ORDER, "h_min": ORDER, "p_max": ORDER, "dT_max": ORDER_DT_MAX, "dT_min": ORDER_DT_MAX, "mu": ORDER_MU}
Solve = Callable[[ContactPoint, Lubricant, SolverSettings], PointSolution]  # a point solve (staged.StagedSolver)


@dataclass(frozen=True)
class CoarseStage:
    """The figures (SI: m, Pa, K, 1) of a solve's converged coarse stage on nx x ny nodes, the finest grid's ny."""

    nx: int
    ny: int
    figures: dict[str, float]


def coarse_stage(summary: LevelSummary, ny: int, scaling: Scaling) -> CoarseStage | None:
    """The coarse stage of a level summary with its film state (report.with_film_state); None without one."""
    if not math.isfinite(summary.dT_max):
        return None
    figures = {"h_c": summary.h_c * scaling.film_scale, "h_min": summary.h_min * scaling.film_scale,
               "p_max": summary.p_max * scaling.p_h, "dT_max": summary.dT_max, "dT_min": summary.dT_min,
               "mu": summary.mu}
    return CoarseStage(summary.n, ny, figures)


def y_estimates(solution: PointSolution, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
                solve: Solve, coarse: CoarseStage | None = None) -> dict[str, float]:
    """e_y of each reported figure (module docstring; p: ORDERS): from the coarse stage and a check on its x nodes
    with (ny + 1)/2 rows where `coarse` is given, else from the solution and a check on its x nodes with (ny + 1)/2
    rows; the check is `solve` (with its retries) of the same point and model on the solution's domain, without
    outlet patches. 0 on a square grid, NaN where (ny + 1)/2 is below the coarsest grid or the check failed."""
    x, y = solution.axes["x"].values, solution.axes["y"].values
    nx, ny = x.size, y.size
    names = [name for name in FIGURES if name in solution.scalars]
    if nx == ny:
        return dict.fromkeys(names, 0.0)
    if (ny + 1) // 2 < settings.coarsest_grid:
        return dict.fromkeys(names, math.nan)
    usable = coarse is not None and coarse.ny == ny and coarse.nx < nx
    reference = coarse.figures if usable else {name: solution.scalar(name) for name in names}
    a, b = solution.scalar("a"), solution.scalar("b")
    check = replace(settings, grid=coarse.nx if usable else nx, grid_y=(ny + 1) // 2,
                    domain_x=(x[0] / b, x[-1] / b), domain_y=(y[0] / a, y[-1] / a),
                    outlet_refinement=OutletRefinement.NEVER)
    checked = solve(point, lubricant, check)
    if checked.outcome is not Outcome.CONVERGED or "h_min" not in checked.scalars:
        return dict.fromkeys(names, math.nan)
    return {name: (reference[name] - checked.scalar(name)) / (2.0 ** ORDERS[name] - 1.0) / solution.scalar(name)
            if name in checked.scalars and math.isfinite(reference.get(name, math.nan))
            and solution.scalar(name) != 0.0 else math.nan for name in names}


def remaining_error(changes: np.ndarray, floored: bool) -> float:
    """The error a contracting iteration leaves after its last change c_k, c_k rho/(1 - rho) (the a-posteriori
    bound of a contraction with factor rho: Ortega & Rheinboldt 1970, "Iterative Solution of Nonlinear Equations in
    Several Variables", 12.1.2), rho = (c_k/c_k-n)^(1/n) over the last n <= contraction_window changes. Changes that
    no longer contract (rho above max_contraction, or the loop ended on its algebraic floor `floored`) are a flicker
    straddling the fixed point: the largest of those n + 1 changes. No change: 0; one: itself."""
    if changes.size < 2:
        return float(changes[-1]) if changes.size else 0.0
    n = min(TUNING.contraction_window, changes.size - 1)
    first, last = float(changes[-1 - n]), float(changes[-1])
    rho = (last / first) ** (1.0 / n) if first > 0.0 else 0.0
    if floored or rho > TUNING.max_contraction:
        return float(changes[-1 - n:].max())
    return last * rho / (1.0 - rho)


def cycle_changes(solution: PointSolution, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Change of a film figure (h_c, h_min) per pressure cycle relative to its last value, signed, and the pressure's
    relative change in the same cycles, over the cycles on the level the pressure iteration ended on (after the first of
    them, its entry iterate); empty without the per-cycle record of the figure."""
    history, key = solution.history, f"cycle_{name}_history"
    if key not in history or "cycle_nodes_history" not in history or "pressure_change_history" not in history:
        return np.empty(0), np.empty(0)
    values = np.asarray(history[key].values, dtype=float)
    nodes = np.asarray(history["cycle_nodes_history"].values, dtype=float)
    pressure = np.asarray(history["pressure_change_history"].values, dtype=float)
    first = int(np.flatnonzero(nodes != nodes[-1])[-1]) + 1 if np.any(nodes != nodes[-1]) else 0
    if values.size - first < 2 or values[-1] == 0.0:
        return np.empty(0), np.empty(0)
    return np.diff(values[first:]) / abs(values[-1]), pressure[first + 1:]


def cycle_error(solution: PointSolution, name: str) -> float:
    """Relative error the finest grid's pressure cycles left in a film figure, the larger of two readings of the
    contraction (Ortega & Rheinboldt 1970, 12.1.2): remaining_error of the figure's own change per cycle, and that of
    the pressure's change per cycle scaled to the figure by the largest ratio of their changes over the window (the
    figure's sensitivity to the iterate; a figure's change can pass through zero while the iterate still moves).
    Changes that stopped contracting at the algebraic floor are a flicker (the largest of the window); inf where the
    figure is `drifting` (no bound: unresolved); 0 without a per-cycle record."""
    changes, pressure = cycle_changes(solution, name)
    if changes.size == 0:
        return 0.0
    if drifting(changes):
        return math.inf
    floored = math.isfinite(solution.scalars.get("algebraic_floor", (math.nan, "1"))[0])
    own = remaining_error(np.abs(changes), floored)
    n = min(TUNING.contraction_window + 1, changes.size)
    if not np.all(pressure[-n:] > 0.0):
        return own
    sensitivity = float(np.max(np.abs(changes[-n:]) / pressure[-n:]))
    return max(own, sensitivity * remaining_error(pressure, floored))


def floor_error(changes: np.ndarray, films: np.ndarray) -> tuple[float, float]:
    """The error a loop ended at its floor (its full step no longer contracting at the smallest relaxation) leaves:
    the amplitude of its last thermal_floor_window changes (their largest; the floor's iterates straddle the fixed
    point, no rate bounds their distance from it), and that amplitude carried into the central film `films` (one per
    change, m), the larger of h_c's spread over the window and the amplitude times h_c's largest change per unit
    change there (relative). No change: 0."""
    window = changes[-TUNING.thermal_floor_window:]
    if window.size == 0:
        return 0.0, 0.0
    amplitude = float(window.max())
    films = films[-(window.size + 1):]
    if films.size < 2 or films[-1] == 0.0:
        return amplitude, 0.0
    relative = films / abs(films[-1])
    steps = np.abs(np.diff(relative))
    paired = window[-steps.size:]
    sensitivity = float(np.max(np.where(paired > 0.0, steps / np.where(paired > 0.0, paired, 1.0), 0.0)))
    return amplitude, max(float(relative.max() - relative.min()), sensitivity * amplitude)


def loop_error(changes: np.ndarray, films: np.ndarray, floored: bool, name: str, value: float,
               thermal: bool) -> float:
    """Relative error an outer loop with these `changes` (of the largest layer temperature, K, where `thermal`, else of
    ln(eta*/eta)) and central films `films` (m, one per change) left in figure `name` of value `value`
    (`iteration_error`); `floored`: the loop ended at its floor (`floor_error`)."""
    state, film = floor_error(changes, films) if floored else (remaining_error(changes, False), math.nan)
    if name in ("dT_max", "dT_min") and thermal:
        return state / abs(value) if value != 0.0 else 0.0
    if name == "mu" and not thermal:
        return state
    if floored:
        return film
    if films.size < 2 or films[-1] == 0.0:
        return 0.0
    last = abs(films[-1] - films[-2]) / abs(films[-1])
    return last if state == 0.0 or changes[-1] == 0.0 else last * state / float(changes[-1])


def outer_loop(solution: PointSolution) -> tuple[np.ndarray, np.ndarray, bool, bool]:
    """The outer loops' changes and central films over the whole solve (every stage's, in order), whether it is
    thermal, and whether its last loop ended at its floor; empty without an outer loop."""
    history = solution.history
    thermal = "thermal_change_history" in history
    key, floor = ("thermal_change_history", "thermal_floor") if thermal else ("viscosity_change_history",
                                                                                "viscosity_floor")
    if key not in history:
        return np.empty(0), np.empty(0), thermal, False
    changes = np.asarray(history[key].values, dtype=float)
    floored = math.isfinite(solution.scalars.get(floor, (math.nan, "1"))[0])
    h_c = np.asarray(history["thermal_h_c_history"].values if "thermal_h_c_history" in history else (), dtype=float)
    return changes, h_c, thermal, floored


def iteration_error(solution: PointSolution, name: str) -> float:
    """Relative error the iteration left in a figure (remaining_error of its changes): of the outer loop where the
    solve has one, of the largest layer temperature for the temperatures (K over |value|), of ln(eta*/eta) for mu of
    an isothermal Ree-Eyring film, else of the central film, whose last change contracts as the loop's film state does;
    at the loop's floor the amplitude of its last window instead (`floor_error`); without an outer loop, of the
    pressure cycles for the film figures (`cycle_error`, inf where it cannot bound), else 0."""
    changes, h_c, thermal, floored = outer_loop(solution)
    if changes.size == 0:
        return cycle_error(solution, name) if name in ("h_c", "h_min") else 0.0
    return loop_error(changes, h_c, floored, name, solution.scalar(name), thermal)


def over_patches(solution: PointSolution, name: str) -> bool:
    """Whether the x-estimate of `name` compares the outlet patches with the uniform grid under them (dT_max and mu of
    an outlet-refined solve, report._outlet_scalars), not two grids at the ratio 2."""
    return name in ("dT_max", "mu") and solution.scalars.get("outlet_patches", (0.0, "1"))[0] > 0.0


def reference_stage(solution: PointSolution, name: str) -> tuple[Stage, int]:
    """The stage whose figure the x-estimate of `name` compares the reported one with, and the ratio of the x
    spacings: the outlet patches' uniform grid where the estimate is over the patches (`over_patches`: 2^patches),
    else the coarse stage (2)."""
    if over_patches(solution, name):
        return Stage.FINEST, 2 ** int(solution.scalar("outlet_patches"))
    return Stage.COARSE, 2


def reference_error(solution: PointSolution, name: str) -> float:
    """The share of the x-estimate of `name` the reference grid's own iteration error can take (`reference_stage`):
    the loop error that grid's last outer loop left (`stage_error`: its remaining change, or a flicker's largest
    change), over r^p - 1 as the estimate divides its difference (report.estimate, richardson.richardson_error).
    A seeded coarse stage stops at its own tolerance from a state other than the cold start's, so that its figures,
    and the x-estimate with them, carry its iteration error (docs/accuracy.md, error bounds). 0 without a coupled
    reference stage (an isothermal solve's levels are the full-multigrid start's, on both grids of the estimate)."""
    stage, ratio = reference_stage(solution, name)
    return stage_error(solution, stage, name) / (ratio ** ORDERS[name] - 1.0)


def runs(field: np.ndarray, inside: np.ndarray) -> tuple[int, int]:
    """Nodes of the runs through the extreme of `field` (its first arg-extreme, `inside` there) along x (axis 1) and
    along y (axis 0) where `inside` holds without a gap."""
    j, i = np.unravel_index(np.argmax(np.where(inside, field, -np.inf)), field.shape)
    out = []
    for line, at in ((inside[j, :], i), (inside[:, i], j)):
        low, high = at, at
        while low > 0 and line[low - 1]:
            low -= 1
        while high < line.size - 1 and line[high + 1]:
            high += 1
        out.append(high - low + 1)
    return int(out[0]), int(out[1])


def feature_runs(solution: PointSolution, t_inlet: float) -> dict[str, tuple[int, int]]:
    """Nodes across the feature of each local figure along x and along y (`runs`): the lowest film's basin (film
    within feature_depth of h_min above it), the hot spot (rise within feature_depth of dT_max) and the cold spot
    (within feature_depth of dT_min) in the layer field holding the extreme (surface 1, mid-film, surface 2); t_inlet
    in K."""
    depth, out = TUNING.feature_depth, {}
    if "film_thickness" in solution.fields:
        film = solution.fields["film_thickness"].values
        out["h_min"] = runs(-film, film <= film.min() + depth * abs(film.min()))
    layers = [solution.fields[k].values for k in ("temperature_surface_1", "temperature_mid", "temperature_surface_2")
              if k in solution.fields]
    if layers:
        hot = max(layers, key=np.max) - t_inlet
        out["dT_max"] = runs(hot, hot >= hot.max() - depth * abs(hot.max()))
        cold = min(layers, key=np.min) - t_inlet
        out["dT_min"] = runs(-cold, cold <= cold.min() + depth * abs(cold.min()))
    return out


def feature_nodes(solution: PointSolution, t_inlet: float) -> dict[str, int]:
    """Nodes across the feature of each local figure (`feature_runs`), the shorter of its runs along x and y."""
    return {name: min(both) for name, both in feature_runs(solution, t_inlet).items()}


def compression_held(solution: PointSolution) -> bool:
    """Whether the film's temperatures are its compression's, through the outlet spike, which no grid resolves (p_max
    is never bounded): it cools through the outlet at least as much as it heats (-dT_min >= dT_max > 0: the
    compression work beta_T T u.grad p, heating where the pressure rises along the flow and cooling where it falls,
    outweighs the shear heating, as in pure rolling). The spike's rising flank then heats the oil as its fall cools it,
    and grows with every refinement as p_max does: the hot spot can move there on a finer grid whether or not the cold
    spot's own estimate looks resolved (docs/accuracy.md, calibration: design 6's S3 and the shipped case's S3)."""
    rise, cold = solution.scalars.get("dT_max", (0.0, "K"))[0], solution.scalars.get("dT_min", (0.0, "K"))[0]
    return rise > 0.0 and -cold >= rise


def stage_error(solution: PointSolution, stage: Stage, name: str) -> float:
    """Relative error the last outer loop of `stage` left in figure `name` (`loop_error` over that stage's changes in
    the solve's history, read at its place in the record); 0 where the stage has no loop on record."""
    record = solution.record
    ran = [s for s in (record.stages if record is not None else ()) if s.stage is stage and s.outer > 0]
    changes, h_c, thermal, _ = outer_loop(solution)
    if not ran or ran[-1].first_outer < 0 or changes.size == 0 or name not in solution.scalars:
        return 0.0
    window = slice(ran[-1].first_outer, ran[-1].first_outer + ran[-1].outer)
    if changes[window].size < ran[-1].outer:
        return 0.0
    films = h_c[window] if h_c.size >= window.stop else np.empty(0)
    return loop_error(changes[window], films, False, name, solution.scalar(name), thermal)


def level_triple(solution: PointSolution) -> list[int]:
    """Nodes along x of the solve's last three levels (`level_nodes`) where they are one model on one refinement (the
    same rows, or all square): an isothermal Newtonian solve's full-multigrid levels, or a coupled solve's seed stage,
    coarse stage and finest grid; [] elsewhere (a coupled solve without a seed stage: its levels below the coarse stage
    are the isothermal start's)."""
    history, record = solution.history, solution.record
    if "level_nodes" not in history or "grid" not in solution.scalars or "grid_y" not in solution.scalars:
        return []
    coupled = "thermal_change_history" in history or "viscosity_change_history" in history
    # a seed stage's level is in the summaries unless a later failure began the hierarchy again (its place -1)
    if coupled and (record is None or not any(s.stage is Stage.SEED and s.first_outer >= 0 for s in record.stages)):
        return []
    nodes = [int(n) for n in history["level_nodes"].values[-3:]]
    coarsest = int(solution.scalars.get("coarsest_grid", (17.0, "1"))[0])
    shapes = hierarchy_shapes(int(solution.scalar("grid")), int(solution.scalar("grid_y")), coarsest)[-3:]
    same_rows = len({ny for _, ny in shapes}) == 1 or all(nx == ny for nx, ny in shapes)
    return nodes if len(nodes) == 3 and nodes == [nx for nx, _ in shapes] and same_rows else []


def level_values(solution: PointSolution, name: str, nodes: list[int]) -> tuple[float, float, float] | None:
    """A figure on the last three levels `nodes` (`level_triple`), coarsest first: h_c and h_min from their level
    summaries (`level_h_c`, `level_h_min`); the film state's from the seed and coarse stages' (`level_<name>` over
    `level_state_nodes`) and the reported figure, except dT_max and mu of an outlet-refined solve (its estimate
    compares the patches with the uniform grid: report._outlet_scalars). None where they are not on record."""
    history, key = solution.history, f"level_{name}"
    if key not in history or name not in solution.scalars:
        return None
    values = [float(v) for v in history[key].values]
    if name in ("h_c", "h_min"):
        return tuple(values[-3:]) if len(values) >= 3 else None
    stated = [int(n) for n in history["level_state_nodes"].values[-2:]] if "level_state_nodes" in history else []
    if stated != nodes[:2] or over_patches(solution, name):
        return None
    return values[-2], values[-1], solution.scalar(name)


def coarser_estimates(solution: PointSolution) -> dict[str, CoarserPair]:
    """The next coarser pair's x-estimate of h_c, h_min, dT_max, dT_min and mu from the solve's last three levels
    (`level_triple`, `level_values`), with the seed and coarse stages' loop errors as its noise (the seed stage stops
    at seed_stage_limit of the rise); empty without three levels of one model on one refinement."""
    nodes = level_triple(solution)
    out = {}
    for name in (FIGURES if nodes else ()):
        values = level_values(solution, name, nodes)
        if values is None or values[2] == 0.0:
            continue
        third, second, first = values
        scale = 2.0 ** ORDERS[name] - 1.0
        noise = (stage_error(solution, Stage.SEED, name) + stage_error(solution, Stage.COARSE, name)) / scale
        out[name] = CoarserPair((second - third) / scale / first, noise)
    return out


def estimated_in_model(solution: PointSolution) -> bool:
    """Whether the solve's x-estimates compare two grids of its own model: not a thermal solve without its coarse stage
    in the record (below 129 nodes along x, or coupled on its finest grid alone after the coarse stage ran away or
    closed its film), whose level summaries are the isothermal start's: an isothermal film's grid convergence says
    nothing of the thermal one's (the envelope's ab30_ph1.5_u0.5_srr0.5_th coupled on 513 x 513 alone: its isothermal
    start's h_min on 257 and 513 gives e_x 15 %, its thermal h_min grows from 0.111 to 0.123 and 0.139 um on 129, 257
    and 513)."""
    record = solution.record
    if "thermal_change_history" not in solution.history or record is None:
        return True
    return any(s.stage is Stage.COARSE and s.first_outer >= 0 for s in record.stages)


def unresolved_figure(solution: PointSolution, name: str, e_x: float, along_y: float, nodes: int) -> Why | None:
    """Why no bound can be given to a figure from the solve, its estimates along x and y and the nodes across its
    feature (module docstring); None where one may be."""
    if solution.outcome is not Outcome.CONVERGED:
        return Why.NOT_CONVERGED
    if name in UNBOUNDED:
        return Why.NEVER
    if starved_inlet(solution.scalars.get("inlet_gap_ratio", (math.inf, "1"))[0]):
        return Why.STARVED_INLET
    if starved_sides(solution.scalars.get("side_pressure_ratio", (0.0, "1"))[0]):
        return Why.STARVED_SIDES
    if energy_unbalanced(solution):
        return Why.ENERGY_BALANCE
    if not (math.isfinite(e_x) and math.isfinite(along_y)):
        return Why.NO_ESTIMATE
    if max(abs(e_x), abs(along_y)) > TUNING.asymptotic_estimate:
        return Why.OUTSIDE_ASYMPTOTIC_RANGE
    if nodes < TUNING.feature_nodes:
        return Why.NARROW_FEATURE
    if name == "dT_max" and compression_held(solution):
        return Why.COMPRESSION_HELD
    return None


def bounds(solution: PointSolution, e_y: dict[str, float], nodes: dict[str, int] | None = None,
           coarser: dict[str, CoarserPair] | None = None) -> dict[str, tuple[float, str]]:
    """`error_bound_<name>` (relative, >= 0) of every reported figure it can bound, `unresolved_<name>` (1 or 0)
    of every reported figure and `unresolved_reason_<name>` (unresolved.Why) of those it cannot (module docstring);
    `nodes`: feature_nodes of the solution; `coarser`: the next coarser pair along x of a figure
    (`three_grid_estimate`, whose noise adds this solve's e_ref and e_it/(2^p - 1) to the pair's;
    `observed_order_<name>` in the file)."""
    nodes, coarser = nodes or {}, coarser or {}
    in_model = estimated_in_model(solution)
    estimates = {name: (solution.scalars.get(f"error_estimate_{name}", (math.nan, "1"))[0] if in_model else math.nan,
                        e_y.get(name, math.nan)) for name in FIGURES if name in solution.scalars}
    why = {name: unresolved_figure(solution, name, *estimates[name], nodes.get(name, TUNING.feature_nodes))
           for name in estimates}
    out: dict[str, tuple[float, str]] = {}
    for name, (e_x, along_y) in estimates.items():
        converged = solution.outcome is Outcome.CONVERGED
        left = iteration_error(solution, name) if converged else math.inf
        reference = reference_error(solution, name) if converged else 0.0
        pair = coarser.get(name, CoarserPair(math.nan))
        noise = pair.noise + reference + (left / (2.0 ** ORDERS[name] - 1.0) if math.isfinite(left) else 0.0)
        along_x = three_grid_estimate(e_x, pair.estimate, ORDERS[name], noise) + reference
        if why[name] is None and not left <= TUNING.max_iteration_error:
            why[name] = Why.ITERATION_ERROR
        if why[name] is None and not math.isfinite(along_x):
            why[name] = Why.THREE_GRIDS
        bound = math.inf if why[name] is not None else TUNING.bound_safety * (along_x + abs(along_y)) + left
        if why[name] is not None:
            out[f"unresolved_reason_{name}"] = (float(why[name]), "1")
        if math.isfinite(bound):
            out[f"error_bound_{name}"] = (bound, "1")
        if math.isfinite(left):
            out[f"iteration_error_{name}"] = (left, "1")
        order = observed_order(e_x, pair.estimate)
        if math.isfinite(order):  # (none where the differences change sign or one vanishes: no order to read)
            out[f"observed_order_{name}"] = (order, "1")
        out[f"unresolved_{name}"] = (float(not math.isfinite(bound)), "1")
    return out


def one_doubling_coarser(coarser: PointSolution, solution: PointSolution) -> bool:
    """Whether `coarser` lies on the grid `solution`'s coarse stage lies on, as the third grid of the three-grid check
    asks: the same model (thermal, rheology) on the same domain, one doubling coarser along x ((nx - 1) = 2 (nx_c - 1)),
    and both grids square or both not (the x-estimate along x alone, or along both axes at once, in both: the
    hierarchy coarsens x alone while nx > ny, grid.hierarchy_shapes)."""
    if any(axis not in s.axes for s in (coarser, solution) for axis in ("x", "y")):
        return False
    (x_c, y_c), (x, y) = ((s.axes["x"].values, s.axes["y"].values) for s in (coarser, solution))
    same_domain = all(math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9 * float(ends[-1] - ends[0]))
                      for ends, other in ((x, x_c), (y, y_c)) for a, b in ((ends[0], other[0]), (ends[-1], other[-1])))
    same_model = all(coarser.models.get(k) == solution.models.get(k) for k in ("thermal", "rheology"))
    return (same_domain and same_model and x.size - 1 == 2 * (x_c.size - 1)
            and (x_c.size == y_c.size) == (x.size == y.size))


def with_coarser_pair(solution: PointSolution, coarser: PointSolution, t_inlet: float) -> PointSolution:
    """`solution`'s bounds again with the x-estimates of `coarser`, the same point and model solved converged on the
    grid its coarse stage lies on (`one_doubling_coarser`: the accuracy target's last grid, or the grid run.py refined
    from), as the next coarser pair along x (`three_grid_estimate`; in units of `solution`'s figures, its noise the
    coarser solve's e_ref and e_it/(2^p - 1)), for the figures whose estimates both solves take at the ratio 2 (not
    dT_max and mu of an outlet-refined solve, report._outlet_scalars), beside the third grid of its own levels
    (`coarser_estimates`): the stricter of the two (`stricter`); t_inlet in K. As it is where `coarser` is not that
    grid, either did not converge, or `solution` carries no film or no bounds."""
    if (not (solution.converged and coarser.converged) or "film_thickness" not in solution.fields
            or "unresolved_h_min" not in solution.scalars or not one_doubling_coarser(coarser, solution)):
        return solution
    pairs = {}
    for name in FIGURES:
        value, before = solution.scalars.get(name, (0.0, "1"))[0], coarser.scalars.get(name, (0.0, "1"))[0]
        estimate = coarser.scalars.get(f"error_estimate_{name}", (math.nan, "1"))[0]
        if value != 0.0 and math.isfinite(estimate) and not any(over_patches(s, name) for s in (solution, coarser)):
            left = coarser.scalars.get(f"iteration_error_{name}", (0.0, "1"))[0] / (2.0 ** ORDERS[name] - 1.0)
            noise = (reference_error(coarser, name) + left) * before / value
            pairs[name] = CoarserPair(estimate * before / value, noise)
    e_y = {name: solution.scalars.get(f"error_estimate_y_{name}", (math.nan, "1"))[0] for name in FIGURES}
    kept = {k: v for k, v in solution.scalars.items()
            if not k.startswith(("error_bound_", "observed_order_", "unresolved_reason_"))}
    nodes = feature_nodes(solution, t_inlet)
    extra = stricter(bounds(solution, e_y, nodes, coarser_estimates(solution)), bounds(solution, e_y, nodes, pairs))
    return replace(solution, scalars={**kept, **extra})


def stricter(first: dict[str, tuple[float, str]], second: dict[str, tuple[float, str]]) -> dict[str, tuple[float, str]]:
    """Two `bounds` of one solve from two third grids (its own levels, `first`; another solve, `second`) as one: a
    figure unresolved by either is unresolved, else its bound is the larger; the observed order is the second's where
    it has one."""
    out = {**first, **second}
    for name in (k.removeprefix("unresolved_") for k in first
                 if k.startswith("unresolved_") and not k.startswith("unresolved_reason_")):
        key, bound, reason = f"unresolved_{name}", f"error_bound_{name}", f"unresolved_reason_{name}"
        if first[key][0] == 1.0 or second.get(key, (0.0, "1"))[0] == 1.0:
            out[key] = (1.0, "1")
            out[reason] = first[reason] if reason in first else second[reason]
            out.pop(bound, None)
        elif bound in first and bound in second:
            out[bound] = (max(first[bound][0], second[bound][0]), "1")
    return out


def with_error_bounds(solution: PointSolution, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
                      solve: Solve, coarse: CoarseStage | None = None) -> PointSolution:
    """The solution with its error bounds, unresolved flags, y-estimates and the check's wall and CPU time
    (`error_check_time`, `error_check_cpu_time`, s; apart from the solve's own `wall_time` and `cpu_time`); a solution
    without a film is returned as it is, one that did not converge with every figure unresolved and no check."""
    if "h_min" not in solution.scalars or "film_thickness" not in solution.fields:
        return solution
    clock, cpu = time.perf_counter(), time.process_time()
    e_y = {}
    if solution.outcome is Outcome.CONVERGED:
        e_y = y_estimates(solution, point, lubricant, settings, solve, coarse)
    nodes = feature_nodes(solution, lubricant.inlet_temperature)
    extra = bounds(solution, e_y, nodes, coarser_estimates(solution))
    extra |= {f"error_estimate_y_{k}": (v, "1") for k, v in e_y.items() if math.isfinite(v)}
    extra["error_check_time"] = (time.perf_counter() - clock, "s")
    extra["error_check_cpu_time"] = (time.process_time() - cpu, "s")
    return replace(solution, scalars={**solution.scalars, **extra})
