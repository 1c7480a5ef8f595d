r"""The outlet stage: the thermal film's pressure spike and hot spot solved on a patch twice as fine along x.

On the uniform grid the outlet spike is a few nodes wide, and the hottest film temperature sits on its rising flank:
the oil is compressed adiabatically through it (docs/accuracy.md), so ΔT_max converges only as fast as the spike
is sampled, and the traction ahead of it (μ) at first order. The stage takes the converged coupled solution of the
finest uniform grid and adds a patch (patch.py) over [X_a, outlet] with half its x spacing, and runs the coupled
loop (coupled.py) on it:
- the composite pressure (the patch inside, the grid below outside) is solved by the patch's FAS cycles;
- the film state on the patch (temperatures and η*/η per layer) is iterated with it: the energy equation on the
  patch's columns alone, its inflow at X_a the temperatures of the grid below interpolated along x (GHOST columns
  held, the MUSCL face values need two), its surfaces from Jaeger's moving heat source of the composite wall flux
  (the grid below's flux upstream, the patch's on it) along the whole x axis at the patch's spacing;
- the grid below keeps its converged film state (the patch moves its h_c by less than its error estimate).
Nested patches follow, each at half the spacing of the one before, while the figures still move (`auto`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable, Protocol

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import grid, jaeger
from facegear_tehl.ehl.composite import Composite, OutletStage, composite, patch_state_columns, stage_figures
from facegear_tehl.ehl.convergence import History, at_thermal_floor, h_c_steady, pressure_settled
from facegear_tehl.ehl.coupled import CoupledLoop, Ending, LoopState
from facegear_tehl.ehl.friction import friction_coefficients
from facegear_tehl.ehl.multigrid import Level, MultigridSolver
from facegear_tehl.ehl.patch import PatchedSolver
from facegear_tehl.ehl.pressure import PressureIteration
from facegear_tehl.ehl.report import ORDER_DT_MAX, ORDER_MU, LevelSummary, cell_area
from facegear_tehl.ehl.richardson import richardson_error
from facegear_tehl.ehl.scaling import Scaling
from facegear_tehl.ehl.snapshot import SolveSnapshot, restore_snapshot, take_snapshot
from facegear_tehl.ehl.thermal import FilmState, FilmThermalModel
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.record import Action, Reason, RetryRecord
from facegear_tehl.settings import OutletRefinement, SolverSettings
from facegear_tehl.solution import CONVERGED, Outcome, Status

GHOST = 2  # upstream columns of the patch's energy equation held at the grid below's temperatures (MUSCL: two)


class Staging(Protocol):
    """What the outlet stages need of a point solve (solve.PointSolve)."""

    settings: SolverSettings
    scaling: Scaling
    point: ContactPoint
    lubricant: Lubricant
    solver: MultigridSolver
    pressure: PressureIteration
    summaries: list[LevelSummary]
    retries: list[RetryRecord]
    attempt: int

    @property
    def history(self) -> History: ...


def along_x(values: np.ndarray) -> np.ndarray:
    """Linear interpolation along x (the last axis) to twice the resolution, for (..., ny, nx) arrays."""
    flat = values.reshape((-1, values.shape[-1]))
    return grid.prolong_linear_x(flat).reshape(values.shape[:-1] + (2 * values.shape[-1] - 1,))


class PatchFilmModel(FilmThermalModel):
    """The film state on the patch's columns with GHOST inflow columns before them (x on the patch's spacing, m).
    The surfaces take Jaeger's rise of the composite flux: `below_flux` (the grids' below wall fluxes on the whole
    x axis at the patch's spacing) with the patch's own flux from column `offset + GHOST` on."""

    first_column = GHOST

    def __init__(self, x: np.ndarray, y: np.ndarray, layers: int, lubricant: Lubricant, point: ContactPoint,
                 offset: int, below_flux: tuple[np.ndarray, np.ndarray]):
        super().__init__(x, y, layers, lubricant, point, solve_energy=True)
        self.offset = offset
        self.below_flux = below_flux
        self._split: dict[tuple[int, bool], tuple[np.ndarray, np.ndarray]] = {}

    def composite_flux(self, flux: np.ndarray, index: int) -> np.ndarray:
        """The wall heat flux of body `index` (0, 1) along the whole x axis at the patch's spacing: the grids'
        below, the patch's own `flux` (over its columns with the inflow ones) from its first column on."""
        composite_flux = self.below_flux[index].copy()
        composite_flux[:, self.offset + GHOST:self.offset + self.x.size] = flux[:, GHOST:]
        return composite_flux

    def _surface(self, flux: np.ndarray, index: int, speed: float) -> np.ndarray:
        """Jaeger's rise of the composite flux at the patch's columns. By linearity G q = G q_below + G (q - q_below)
        where they differ: the grids' below part along the whole axis once per body (an FFT convolution,
        jaeger.convolved_rise), then per call the block of G from the patch's own columns to its energy columns
        (jaeger.influence_block)."""
        own = slice(self.offset + GHOST, self.offset + self.x.size)
        key = (index, speed < 0.0)
        if key not in self._split:
            nodes = self.below_flux[index].shape[1]
            columns = np.arange(self.offset, self.offset + self.x.size)
            if speed < 0.0:  # the surface moves toward -x: the kernel along the reversed axis
                whole = jaeger.convolved_rise(self.below_flux[index][:, ::-1], self.dx)[:, ::-1]
                block = jaeger.influence_block(nodes, self.dx, nodes - 1 - columns, nodes - 1 - np.arange(nodes)[own])
            else:
                whole = jaeger.convolved_rise(self.below_flux[index], self.dx)
                block = jaeger.influence_block(nodes, self.dx, columns, own)
            self._split[key] = (whole[:, columns], block)
        below, block = self._split[key]
        rise = below + (flux[:, GHOST:] - self.below_flux[index][:, own]) @ block.T
        return self.t_inlet + rise / self.effusivity[index]


def needs_outlet_patch(solve: Staging, index: int, state: FilmState) -> bool:
    """Whether the outlet stage runs after the coupled solve of level `index` converged with `state` (never for an
    entrainment more than max_entrainment_angle from the x axis): `always`, `never`, or (`auto`) when the hottest
    film node lies on the outlet spike's rising flank (`_hot_flank`; a flank node within the thermal loop's
    tolerance of the hottest counts as the hottest: the loop knows the temperatures to its tolerance only) and the
    grid's own estimate of ΔT_max or μ against the coarse thermal stage exceeds auto_dt_max_error or auto_mu_error."""
    choice = solve.settings.outlet_refinement
    if abs(solve.point.entrainment_angle) > TUNING.max_entrainment_angle:
        return False
    if choice != OutletRefinement.AUTO:
        return choice == OutletRefinement.ALWAYS
    level = solve.solver.levels[index]
    hottest = float(state.temperature.max())
    tie = solve.settings.thermal_tolerance * max(hottest - solve.lubricant.inlet_temperature, TUNING.min_rise)
    if not _hot_flank(level, state.temperature, hottest - tie):
        return False
    coarse = solve.summaries[-2] if len(solve.summaries) >= 2 else None
    if coarse is None or not (np.isfinite(coarse.dT_max) and np.isfinite(coarse.mu)):
        return True
    figures = _uniform_figures(solve, level, state)
    dT_max, mu = figures["dT_max"], figures["mu"]
    return ((dT_max != 0.0 and abs(richardson_error(dT_max, coarse.dT_max, ORDER_DT_MAX)) > TUNING.auto_dt_max_error)
            or (mu != 0.0 and abs(richardson_error(mu, coarse.mu, ORDER_MU)) > TUNING.auto_mu_error))


def _hot_flank(level: Level, temperature: np.ndarray, threshold: float) -> bool:
    """Whether a film node on an outlet spike's rising flank (1 to spike_flank_nodes nodes upstream of its row's
    largest pressure, downstream of the contact centre) is at `threshold` (K) or hotter."""
    for j in range(temperature.shape[1]):
        spike = int(np.argmax(level.pressure[j]))
        flank = [i for i in range(max(spike - TUNING.spike_flank_nodes, 0), spike) if level.x[i] > 0.0]
        if flank and float(temperature[:, j, flank].max()) >= threshold:
            return True
    return False


@dataclass
class PatchTarget:
    """The coupled loop on an outlet patch (coupled.CoupledTarget): level `index` of the patched solver, its energy
    columns from `start` on the grid below interpolated, its GHOST inflow columns held at `inflow` (K). It ends on
    the thermal tolerance with h_c steady, on the thermal floor, or once the figure it is run for has settled
    (figures_settled) with the composite's load balanced to stage_load_band times its tolerance; or provisionally,
    once the stage on top of it is certain (`next_certain`, asked of each candidate)."""

    solve: Staging
    solver: PatchedSolver
    index: int
    model: PatchFilmModel
    start: int
    inflow: np.ndarray
    below_states: tuple[FilmState, ...]
    next_certain: Callable[[OutletStage], bool] | None
    hottest: list[float]  # the largest film temperature rise of each update on the patch (K)
    certain: int = 0  # consecutive outer iterations at which the next stage was certain

    def evaluate(self, temperature: np.ndarray, forcing: float) -> FilmState:
        pressure, film = _with_inflow(self.solver, self.start, *self.solve.pressure.settled_pressure(self.index))
        scaling = self.solve.scaling
        return self.model.update(pressure * scaling.p_h, film * scaling.film_scale, temperature, forcing,
                                 wall_fluxes=False)

    def constrain(self, temperature: np.ndarray) -> None:
        temperature[..., :GHOST] = self.inflow

    def freeze(self, state: FilmState) -> None:
        self.solver.set_patch_state(state.temperature[..., GHOST:], state.viscosity_factor[..., GHOST:])

    def central_film(self) -> float:
        return self.solver.summary().h_c

    def judge(self, loop: LoopState, status: Status, rise: float) -> tuple[Ending, Status]:
        solve, changes, films = self.solve, loop.changes, loop.films
        settings, history = solve.settings, solve.history
        self.hottest.append(float(loop.update.temperature[..., GHOST:].max()) - solve.lubricant.inlet_temperature)
        steady = TUNING.steady_updates
        done = (status.converged and changes[-1] < settings.thermal_tolerance * rise
                and len(films) >= steady and h_c_steady(films[-steady:]))
        settled = status.converged or pressure_settled(history, settings)
        floor = settled and at_thermal_floor(changes, films, TUNING.thermal_floor_fraction * rise)
        ended = done or floor or (figures_settled(self.hottest, films, changes, rise)
                                  and stage_pressure_settled(history, settings))
        judged = len(changes) > TUNING.provisional_min_iterations - TUNING.provisional_window
        if not ended and self.next_certain is not None and judged:
            candidate = self.below_states + (patch_state_columns(loop.state, slice(GHOST, None)),)
            self.certain = self.certain + 1 if self.next_certain(OutletStage(self.solver, candidate, None)) else 0
        if floor:
            history.thermal_floor = changes[-1]
            return Ending.FLOOR, CONVERGED
        if ended:
            return Ending.TOLERANCE, CONVERGED
        if self.certain >= TUNING.provisional_window and len(changes) >= TUNING.provisional_min_iterations:
            return Ending.PROVISIONAL, CONVERGED
        return Ending.GOING, status


def refine_outlet(solve: Staging, index: int, state: FilmState, coarse_cycles: int, base: OutletStage | None = None,
                  span_start: float = TUNING.patch_start,
                  next_certain: Callable[[OutletStage], bool] | None = None) -> tuple[OutletStage | None, Status]:
    """An outlet stage: a patch over [`span_start`, outlet] (X) on top of level `index` of `solve.solver`, whose
    coupled loop converged with the film state `state`: the finest uniform grid (`base` None), or the last patch of
    the stage `base`. `coarse_cycles` V-cycles of the grid below per coarse-grid correction of the patch. On success
    `solve.solver` is the patched solver; if the stage runs away or does not converge, the solution before it is
    restored and None returned with the status."""
    before, scaling = solve.solver, solve.scaling
    below = before.levels[index]
    below_state = state if base is None else base.state
    saved = _save(before, index)
    solver = PatchedSolver.over(before, (span_start, float(below.x[-1])), coarse_cycles)
    start = 2 * solver.first - GHOST  # the patch's first energy column on the grid below interpolated
    if start < 0:
        return None, Status(Outcome.NOT_CONVERGED, "outlet patch: no room for its inflow columns")
    columns = slice(start, 2 * solver.last + 1)  # the patch with its inflow columns
    temperature = np.ascontiguousarray(along_x(below_state.temperature)[..., columns])
    factor = np.ascontiguousarray(np.exp(along_x(np.log(below_state.viscosity_factor)))[..., columns])
    flux = (below_state.heat_flux_1, below_state.heat_flux_2) if base is None else base.flux
    model = PatchFilmModel(along_x(below.x)[columns] * scaling.b, below.y * scaling.a, temperature.shape[0],
                           solve.lubricant, solve.point, solver.columns.start - GHOST,
                           (along_x(flux[0]), along_x(flux[1])))
    target = PatchTarget(solve, solver, index + 1, model, start, temperature[..., :GHOST].copy(),
                         (state,) if base is None else base.states, next_certain, [])
    solve.solver = solver
    solver.interpolate_up(index + 1)
    solver.set_patch_state(temperature[..., GHOST:], factor[..., GHOST:])
    status = solve.pressure.cycle(index + 1, TUNING.stage_cycles_per_update)
    if not status.diverged:
        end = CoupledLoop(target, solve.pressure, solve.history, solve.settings.max_thermal_iterations,
                          solve.lubricant.inlet_temperature).run(temperature, factor, TUNING.stage_cycles_per_update)
        if end.ending in (Ending.TOLERANCE, Ending.FLOOR, Ending.PROVISIONAL):
            solve.pressure.settle(index + 1)  # on a flicker of the spike the mean of its two phases
            update = model.completed(end.update)
            relaxed = end.state
            patch_state = replace(update, temperature=relaxed.temperature, viscosity_factor=relaxed.viscosity_factor)
            states = target.below_states + (patch_state_columns(patch_state, slice(GHOST, None)),)
            fluxes = (model.composite_flux(update.heat_flux_1, 0), model.composite_flux(update.heat_flux_2, 1))
            return OutletStage(solver, states, fluxes, end.ending is Ending.PROVISIONAL), CONVERGED
        status = end.status if end.status.diverged else Status(
            Outcome.NOT_CONVERGED, f"outlet patch: thermal loop not converged ({end.changes[-1]:.2e} K)")
    solve.solver = before
    before.work_units = solver.work_units
    _restore(before, index, saved)
    if base is None:
        before.set_film_state(index, state.temperature, state.viscosity_factor)
    return None, status


def figures_settled(hottest: list[float], films: list[float], changes: list[float], rise: float) -> bool:
    """Over the last figure_window outer iterations of a stage the hottest rise (K) spans at most figure_spread of
    its mean, the changes of the film temperatures (K) stay below flicker_bound times the rise (K) and h_c
    (dimensionless) spans at most thermal_floor_h_c of its last value."""
    window = TUNING.figure_window
    if len(hottest) < window:
        return False
    rises, h_c = hottest[-window:], films[-window:]
    return (max(rises) - min(rises) <= TUNING.figure_spread * sum(rises) / window
            and max(changes[-window:]) < TUNING.flicker_bound * rise
            and max(h_c) - min(h_c) <= TUNING.thermal_floor_h_c * abs(h_c[-1]))


def stage_pressure_settled(history: History, settings: SolverSettings) -> bool:
    """An outlet stage's pressure has settled: convergence.pressure_settled with the load error of the last two
    cycles within stage_load_band times the load tolerance (a nested patch's FAS correction from partial levels
    below holds a small steady load bias)."""
    return pressure_settled(history, settings, TUNING.stage_load_band)


def _save(solver: MultigridSolver, index: int) -> tuple[float, list[tuple[np.ndarray, ...]]]:
    """H_0 and, for the composite's parts up to level `index` (that level alone on a uniform hierarchy), copies of
    the pressure and right-hand sides: what a stage on top of them overwrites."""
    first = solver.uniform_count - 1 if isinstance(solver, PatchedSolver) else index
    return solver.h0, [(level.pressure.copy(), level.film_rhs.copy(), level.reynolds_rhs.copy(),
                        np.array(level.force_rhs)) for level in solver.levels[first:index + 1]]


def _restore(solver: MultigridSolver, index: int, saved: tuple[float, list[tuple[np.ndarray, ...]]]) -> None:
    """The parts saved by _save back, their films recomputed from the lowest up (a patch's deflection takes the
    grids' below it)."""
    solver.h0, parts = saved
    for level, (pressure, film_rhs, reynolds_rhs, force_rhs) in zip(solver.levels[index + 1 - len(parts):index + 1],
                                                                     parts, strict=True):
        level.pressure, level.film_rhs, level.reynolds_rhs = pressure, film_rhs, reynolds_rhs
        level.force_rhs = float(force_rhs)
        solver.update_film(level)


def outlet_stages(solve: Staging, index: int, state: FilmState) -> tuple[Composite | None, str]:
    """The outlet stages on top of level `index` (the finest uniform grid, converged with `state`): a patch at half
    its x spacing from patch_start, then (`always`, or `auto` while the last patch moved ΔT_max or μ by more than
    auto_dt_max_error or auto_mu_error) patches at half the spacing of the one before from nested_patch_starts, each
    tried with stage_coarse_cycles in turn; a stage with another on top of it may end provisionally. The composite
    of the last converged stage (None if the first failed) and why a stage failed ("" if none did). A stage that
    fails on top of a provisional one: the solve goes back to where the stages began (an explicit snapshot) and
    solves the stages below the failed one again, each to convergence; the work of both counts."""
    starts = ((TUNING.patch_start,) + TUNING.nested_patch_starts)[:solve.settings.outlet_patches]
    before: SolveSnapshot | None = take_snapshot(solve) if len(starts) > 1 else None
    result, note, depth, provisional = _in_stages(solve, index, state, starts, early=True)
    if provisional:
        solve.retries.append(RetryRecord(Reason.STAGE_FAILED, Action.STAGES_AGAIN, solve.attempt,
                                         f"{note}, on top of a provisional stage"))
        restore_snapshot(solve, before)
        result, _, _, _ = _in_stages(solve, index, state, starts[:depth], early=False)
    return result, note


def _in_stages(solve: Staging, index: int, state: FilmState, starts: tuple[float, ...],
               early: bool) -> tuple[Composite | None, str, int, bool]:
    """outlet_stages' stages from `starts` (`early`: a stage with another on top of it may end provisionally): the
    composite of the last stage that ended, why a stage failed ("" if none did), how many stages ended, and whether
    the last of them is provisional (then its composite is not a result)."""
    figures = uniform = _uniform_figures(solve, solve.solver.levels[index], state)
    stage, result = None, None
    while stage is None or len(stage.solver.patches) < len(starts):
        depth = 0 if stage is None else len(stage.solver.patches)
        top = len(solve.solver.levels) - 1
        next_certain = _next_certain(solve, figures) if early and depth + 1 < len(starts) else None
        for cycles in TUNING.stage_coarse_cycles:
            refined, status = refine_outlet(solve, top, state, cycles, stage, starts[depth], next_certain)
            if refined is not None:
                break
            if cycles != TUNING.stage_coarse_cycles[-1]:
                detail = f"outlet patch {depth + 1}, {cycles} per correction: {status.message}"
                solve.retries.append(RetryRecord(Reason.STAGE_FAILED, Action.MORE_COARSE_CYCLES, solve.attempt, detail))
        if refined is None:
            what = "outlet patch" if stage is None else f"outlet patch {depth + 1}"
            return result, f"{what}: {status.message}", depth, stage is not None and stage.provisional
        stage, previous = refined, figures
        result = composite(solve, stage)
        figures = _figures(result)
        if solve.settings.outlet_refinement == OutletRefinement.AUTO and not (_moved(figures, previous, 1.0)
                                                               or _estimate_above(figures, uniform, depth + 1)):
            break
    return result, "", len(stage.solver.patches), stage.provisional


def _estimate_above(figures: dict[str, float], uniform: dict[str, float], patches: int) -> bool:
    """The error estimate the result reports after `patches` patches (Richardson over the whole refinement from the
    uniform grid's `uniform` figures, report._outlet_scalars) exceeds auto_dt_max_error for ΔT_max or auto_mu_error
    for μ: a last stage that moved its figures by less than the bounds may leave that estimate above them when the
    stages before moved them far."""
    ratio = 2 ** patches
    bounds = (("dT_max", ORDER_DT_MAX, TUNING.auto_dt_max_error), ("mu", ORDER_MU, TUNING.auto_mu_error))
    return any(figures[name] != 0.0 and abs(richardson_error(figures[name], uniform[name], order, ratio)) > bound
               for name, order, bound in bounds)


def _next_certain(solve: Staging, previous: dict[str, float]) -> Callable[[OutletStage], bool]:
    """Whether the stage on top of a candidate stage is certain: always under `always`; under `auto` when the
    candidate's composite moved ΔT_max or μ against `previous` by more than provisional_margin times the bounds."""
    if solve.settings.outlet_refinement != OutletRefinement.AUTO:
        return lambda candidate: True
    return lambda candidate: _moved(stage_figures(solve, candidate), previous, TUNING.provisional_margin)


def _figures(result: Composite) -> dict[str, float]:
    """dT_max (K) and mu of a composite."""
    return {name: result.scalars[name][0] for name in ("dT_max", "mu")}


def _moved(figures: dict[str, float], previous: dict[str, float], margin: float) -> bool:
    """ΔT_max or μ moved from `previous` by more than `margin` times auto_dt_max_error or auto_mu_error (relative;
    a previous value of zero never counts)."""
    moved = {name: abs(figures[name] / previous[name] - 1.0) if previous[name] != 0.0 else 0.0
             for name in ("dT_max", "mu")}
    return moved["dT_max"] > margin * TUNING.auto_dt_max_error or moved["mu"] > margin * TUNING.auto_mu_error


def _uniform_figures(solve: Staging, level: Level, state: FilmState) -> dict[str, float]:
    """dT_max (K) and mu of the uniform grid's solution."""
    mu = friction_coefficients(state, level.pressure, cell_area(level, solve.scaling), solve.point.load)[0]
    return {"dT_max": float(state.temperature.max()) - solve.lubricant.inlet_temperature, "mu": mu}


def _with_inflow(solver: PatchedSolver, start: int, pressure: np.ndarray,
                 film: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The composite pressure and film on the patch's energy columns: the grid below interpolated (bicubic along x)
    on the GHOST inflow columns, then the patch's `pressure` and `film` (its settled ones: on a flicker of the spike
    the mean of its two phases, as the uniform loop evaluates its film state)."""
    below = solver.below
    ghost = slice(start, start + GHOST)
    inflow = np.maximum(grid.SEMI_X.prolong_cubic(below.pressure)[:, ghost], 0.0)
    return np.hstack([inflow, pressure]), np.hstack([grid.SEMI_X.prolong_cubic(below.film)[:, ghost], film])
