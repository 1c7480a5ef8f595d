r"""The outlet stage: the thermal film's pressure spike and hot spot solved on a patch twice as fine along x.

On the uniform grid the outlet spike is a few nodes wide, and the hottest film temperature sits on its rising flank:
the oil is compressed adiabatically through it (docs/accuracy.md), so ΔT_max converges only as fast as the spike
is sampled, and the traction ahead of it (μ) at first order. The stage takes the converged coupled solution of the
finest uniform grid and adds a patch (patch.py) over [X_a, outlet] with half its x spacing:
- the composite pressure (the patch inside, the grid below outside) is solved by the patch's FAS cycles;
- the film state on the patch (temperatures and η*/η per layer) is iterated with it, as the outer loop of
  solve.py does on a uniform grid: the energy equation on the patch's columns alone, its inflow at X_a the
  temperatures of the grid below interpolated along x (GHOST columns held, the MUSCL face values need two), its
  surfaces from Jaeger's moving heat source of the composite wall flux (the grid below's flux upstream, the
  patch's on it) along the whole x axis at the patch's spacing;
- the grid below keeps its converged film state (the patch moves its h_c by less than its error estimate).
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
import pickle
from typing import TYPE_CHECKING, Callable

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import grid, jaeger
from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.friction import friction_coefficients
from facegear_tehl.ehl.multigrid import Level, MultigridSolver
from facegear_tehl.ehl.patch import COARSE_CYCLES, PatchedSolver
from facegear_tehl.ehl.report import ORDER_DT_MAX, ORDER_MU, cell_area
from facegear_tehl.ehl.richardson import richardson_error
from facegear_tehl.ehl.thermal import FilmState, FilmThermalModel
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.solution import CONVERGED, Outcome, Status

if TYPE_CHECKING:
    from facegear_tehl.ehl.solve import History, PointSolve
    from facegear_tehl.settings import SolverSettings

STATE_FIELDS = tuple(f.name for f in fields(FilmState) if f.name != "change")  # its arrays over (.., ny, nx)
GHOST = 2  # upstream columns of the patch's energy equation held at the grid below's temperatures (MUSCL: two)
# X_a / b: the patch starts on the outlet side of the centre. From -0.5 b the isothermal composite put the spike on the
# node of the uniform grid of its spacing at S1-S5 of the default face gear case and left h_c at the value of the grid
# below (from -1.5 b, in the inlet side of the Hertzian zone, the patch's upstream end overshot h_c: its coupling to
# the grid below is not conservative there).
PATCH_START = -0.5
# `auto`: the hot node lies this many nodes or fewer upstream of its row's pressure maximum (at S2 and S4 of the
# default face gear case one node: its temperature is the adiabatic compression through the spike, docs/accuracy.md;
# at S1 and S5 the hottest node is the pressure maximum itself, at S3 upstream of the centre)
SPIKE_FLANK_NODES = 2
# ... and only where the grid's own error estimates miss the accuracy asked of these figures (2 % in ΔT_max, 1 % in
# μ: issue 19, docs/accuracy.md). On the 41-point cycle of the default case every flank point misses them (estimates
# 2.3-19 % against the coarse stage, about twice the patch's change): 20 of 41 points are refined, +72 % CPU.
AUTO_DT_MAX_ERROR = 0.02
# The patch refines along x, toward the domain's +x end: the outlet of an entrainment within this angle (deg) of the
# x axis (the case reader allows -90 to 90; the face gear points lie at 2-12 deg). Beyond it the outlet spike lies
# across the patch's rows, not along them, and no stage runs, even with `always`.
MAX_ENTRAINMENT_ANGLE = 45.0
AUTO_MU_ERROR = 0.01
# V-cycles of the uniform hierarchy per coarse-grid correction of the patch, by attempt: the stage starts from the
# converged uniform solution, where one (a plain V-cycle) converged S1-S5 of the default case (`always`; S3's own
# limit cycle aside) with dT_max within 0.15 % and p_max within 0.12 % of three, at half the cost (S2 4.7 against
# 9.2 s, S4 6.2 against 11.6 s CPU); one ran away for a third of the isothermal patch starts from an interpolated
# coarse solution (patch.COARSE_CYCLES), so a stage that runs away or stalls with one is solved again with three.
STAGE_COARSE_CYCLES = (1, COARSE_CYCLES)
# X_a / b of the nested patches, each inside the one before (from its third column on at least: its inflow columns):
# a quarter and an eighth of the uniform grid's x spacing at the spike. ΔT_max converges at order 1.4-1.7 as the spike
# is resolved (docs/accuracy.md): at S4 of the default case the second patch still moves it by 3.8 % (the third by
# 0.9 %), at S2 by 2.1 % (both take the third under `auto`; at 842c29a, whose stages ran to the uniform loop's floor,
# S2's second moved it by 1.7 % and `auto` stopped there).
NESTED_PATCH_STARTS = (-0.4, 0.0)
# A stage's loop also stops once the figure it is run for has settled: over the last FIGURE_WINDOW outer iterations the
# hottest film temperature rise of the patch's updates spans at most FIGURE_SPREAD of its mean (a quarter of the
# accuracy asked of ΔT_max, AUTO_DT_MAX_ERROR), their changes stay below FLICKER_BOUND of the rise (past the
# transient), h_c is steady and the pressure settled. Past its transient (5-8 updates) a stage's temperatures flicker
# by 0.3-0.9 K per update (1-2.5 % of the rise, node to node around the spike) with the pressure at its algebraic
# floor: above the floor bound of the uniform loop (1 % of the rise), so the loop ran a window at full relaxation,
# halved it and ran another, 16-17 outer iterations per stage at S4 of the default case while the hottest rise moved
# by 0.1-0.3 K from the 8th on (docs/benchmarks.md, the nested outlet patches).
FIGURE_WINDOW = 4
FIGURE_SPREAD = 0.25 * AUTO_DT_MAX_ERROR
FLICKER_BOUND = 0.025
# ... and the composite's load balance within STAGE_LOAD_BAND times the load tolerance. A third nested patch (S4 of
# the default case, an eighth of the uniform x spacing) holds a steady load error of -1.4e-4 to -2.9e-4 through 40
# outer iterations and max_cycles V-cycles on a settled film state alike (the FAS correction from three partial levels
# below, cut where the patch's pressure is zero behind the spike): its loop never saw the balance of the uniform loop
# and ran out (or stopped by chance when the flicker dipped below 1e-4). 1e-3 of the load moves h_c by 7e-5
# (h ~ W^-0.067, Hamrock & Dowson 1977) and p_h by 3e-4 (p_h ~ W^(1/3)), far inside the stage's ΔT_max and μ
# estimates (1-2 %); the uniform grid's own load error, which the result reports, is not touched.
STAGE_LOAD_BAND = 10.0
# V-cycles of a stage's composite per update of its film state (the uniform loop: two). A stage starts from a converged
# solution and its updates move the pressure by the spike's flicker: with one, S4 of the default case took its three
# stages in 23 outer iterations and 26 V-cycles instead of 27 and 54 (12.5 against 21.1 s CPU), S2 in 17 and 20
# instead of 18 and 32 (9.9 against 12.0 s), ΔT_max +0.5 and -0.2 %, μ within 3e-4 (docs/benchmarks.md).
STAGE_CYCLES_PER_UPDATE = 1
# A stage with another on top of it ends provisionally once that next stage is certain: `always`, or (`auto`) the
# composite's ΔT_max or μ has moved against the figures before the stage by more than PROVISIONAL_MARGIN times
# AUTO_DT_MAX_ERROR or AUTO_MU_ERROR at each of its last PROVISIONAL_WINDOW outer iterations, from its
# PROVISIONAL_MIN_ITERATIONS-th on. Only its figures had to be converged for that decision: the next patch covers
# all of it but the strip upstream of the next start (its inflow columns, its load and Jaeger's composite flux
# there), which is far from the spike. The hot spot of a nested stage flickered by 0.5-2 K for 12-20 outer
# iterations on the pitch-point side of the default case's 41-point cycle (P21, P24) while its ΔT_max had moved by
# 5-9 %. The first iteration is the interpolated state's transient (changes of 15-30 % of the rise), hence the
# minimum of three.
PROVISIONAL_MARGIN = 1.5
PROVISIONAL_WINDOW = 2
PROVISIONAL_MIN_ITERATIONS = 3


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
        composite = self.below_flux[index].copy()
        composite[:, self.offset + GHOST:self.offset + self.x.size] = flux[:, GHOST:]
        return composite

    def _surface(self, flux: np.ndarray, index: int, speed: float) -> np.ndarray:
        """Jaeger's rise of the composite flux at the patch's columns. By linearity G q = G q_below + G (q - q_below)
        where they differ: the grids' below part along the whole axis once per body, then per call the block of G
        from the patch's own columns to its energy columns (on the eighth-spacing patch of the default case's S4 the
        whole-axis product was 12 of its 37 s), the whole axis's by an FFT convolution (jaeger.convolved_rise) and the
        block alone of its matrix (jaeger.influence_block): 4097 nodes along x there."""
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


@dataclass(frozen=True)
class OutletStage:
    """An outlet stage that ended (converged, or provisional): the patched solver (its last level the stage's patch),
    the film state of each part of the composite (PatchedSolver.parts: the uniform grid's, then each patch's on its
    own columns) and the composite wall heat fluxes of bodies 1 and 2 along the whole x axis at the last patch's
    spacing (W/m^2; None for a candidate whose figures are only looked at)."""

    solver: PatchedSolver
    states: tuple[FilmState, ...]
    flux: tuple[np.ndarray, np.ndarray] | None
    provisional: bool = False  # ended once the stage on top of it was certain (PROVISIONAL_MARGIN), not converged

    @property
    def state(self) -> FilmState:
        """The last patch's film state."""
        return self.states[-1]


def patch_state_columns(state: FilmState, columns: slice) -> FilmState:
    """A film state cut to `columns` along x (every field's last axis; fields that are None stay None)."""
    cut = {name: getattr(state, name)[..., columns] for name in STATE_FIELDS if getattr(state, name) is not None}
    return replace(state, **cut)



def needs_outlet_patch(solve: PointSolve, index: int, state: FilmState) -> bool:
    """Whether the outlet stage runs after the coupled solve of level `index` converged with `state` (never for an
    entrainment more than MAX_ENTRAINMENT_ANGLE from the x axis): `always`,
    `never`, or (`auto`) when the hottest film node lies on the outlet spike's rising flank (within
    SPIKE_FLANK_NODES upstream of its row's largest pressure, downstream of the contact centre; a flank node within
    the thermal loop's tolerance of the hottest counts as the hottest, `_hot_flank`) and the grid's own estimate of
    ΔT_max or μ against the coarse thermal stage exceeds AUTO_DT_MAX_ERROR or AUTO_MU_ERROR."""
    from facegear_tehl.ehl.solve import MIN_RISE

    choice = solve.settings.outlet_refinement
    if abs(solve.point.entrainment_angle) > MAX_ENTRAINMENT_ANGLE:
        return False
    if choice != "auto":
        return choice == "always"
    level = solve.solver.levels[index]
    hottest = float(state.temperature.max())
    tie = solve.settings.thermal_tolerance * max(hottest - solve.lubricant.inlet_temperature, MIN_RISE)
    if not _hot_flank(level, state.temperature, hottest - tie):
        return False
    coarse = solve.summaries[-2] if len(solve.summaries) >= 2 else None
    if coarse is None or not (np.isfinite(coarse.dT_max) and np.isfinite(coarse.mu)):
        return True
    figures = _uniform_figures(solve, level, state)
    dT_max, mu = figures["dT_max"], figures["mu"]
    return ((dT_max != 0.0 and abs(richardson_error(dT_max, coarse.dT_max, ORDER_DT_MAX)) > AUTO_DT_MAX_ERROR)
            or (mu != 0.0 and abs(richardson_error(mu, coarse.mu, ORDER_MU)) > AUTO_MU_ERROR))


def _hot_flank(level: Level, temperature: np.ndarray, threshold: float) -> bool:
    """Whether a film node on an outlet spike's rising flank (1 to SPIKE_FLANK_NODES nodes upstream of its row's
    largest pressure, downstream of the contact centre) is at `threshold` (K) or hotter. The outer loop knows the
    temperatures to its tolerance only: at S2 of the default face gear case the hottest node sat one node upstream of
    the spike at one run and on the spike itself, 0.001 K above the flank's hottest, at a run that differed in
    round-off (its ΔT_max then 56.3 K without the patch, 60.1 K with it)."""
    for j in range(temperature.shape[1]):
        spike = int(np.argmax(level.pressure[j]))
        flank = [i for i in range(max(spike - SPIKE_FLANK_NODES, 0), spike) if level.x[i] > 0.0]
        if flank and float(temperature[:, j, flank].max()) >= threshold:
            return True
    return False


def refine_outlet(solve: PointSolve, index: int, state: FilmState, coarse_cycles: int = COARSE_CYCLES,
                  base: OutletStage | None = None, span_start: float = PATCH_START,
                  next_certain: Callable[[OutletStage], bool] | None = None) -> tuple[OutletStage | None, Status]:
    """An outlet stage: a patch over [`span_start`, outlet] (X) on top of level `index` of `solve.solver`, whose
    coupled loop converged with the film state `state`: the finest uniform grid (`base` None), or the last patch of
    the stage `base`. `coarse_cycles` V-cycles of the grid below per coarse-grid correction of the patch.
    `next_certain` (a stage with another on top of it): whether that next stage is certain, asked of the candidate
    stage of each outer iteration; the stage ends provisionally once it holds (PROVISIONAL_MARGIN). On success
    `solve.solver` is the patched solver; if the stage runs away or does not converge, the solution before it is
    restored and None returned with the status."""
    from facegear_tehl.ehl.solve import (
        ANDERSON_DEPTH,
        MIN_RELAXATION_SCALE,
        MIN_RISE,
        STEADY_UPDATES,
        THERMAL_FLOOR_FRACTION,
        _at_thermal_floor,
        _h_c_steady,
        _next_film_state,
        _pressure_settled,
        _stalled,
        energy_forcing,
    )

    before, settings, scaling = solve.solver, solve.settings, solve.scaling
    below = before.levels[index]
    below_state = state if base is None else base.state
    saved = _save(before, index)
    solver = PatchedSolver.over(before, (span_start, float(below.x[-1])), coarse_cycles)
    top = index + 1
    start = 2 * solver.first - GHOST  # the patch's first energy column on the grid below interpolated
    if start < 0:
        return None, Status(Outcome.NOT_CONVERGED, "outlet patch: no room for its inflow columns")
    columns = slice(start, 2 * solver.last + 1)  # the patch with its inflow columns
    temperature = np.ascontiguousarray(along_x(below_state.temperature)[..., columns])
    factor = np.ascontiguousarray(np.exp(along_x(np.log(below_state.viscosity_factor)))[..., columns])
    inflow = temperature[..., :GHOST].copy()
    x = along_x(below.x)[columns]
    flux = (below_state.heat_flux_1, below_state.heat_flux_2) if base is None else base.flux
    model = PatchFilmModel(x * scaling.b, below.y * scaling.a, temperature.shape[0], solve.lubricant, solve.point,
                           solver.columns.start - GHOST, (along_x(flux[0]), along_x(flux[1])))
    solve.solver = solver
    solver.interpolate_up(top)
    solver.set_patch_state(temperature[..., GHOST:], factor[..., GHOST:])
    status = solve.cycle(top, STAGE_CYCLES_PER_UPDATE)
    accelerator = Anderson(ANDERSON_DEPTH)
    last_change = None
    t_in = solve.lubricant.inlet_temperature
    changes: list[float] = []
    films: list[float] = []
    hottest: list[float] = []  # the largest film temperature rise of each update on the patch (K)
    relaxation, window = 1.0, 0
    certain = 0  # consecutive outer iterations at which the next stage was certain
    below_states = (state,) if base is None else base.states  # the film states of the parts under the patch
    for _ in range(settings.max_thermal_iterations):
        if status.diverged:
            break
        forcing = energy_forcing(changes) * last_change if last_change is not None else np.inf
        pressure, film = _with_inflow(solver, start, *solve.settled_pressure(top))
        temperature[..., :GHOST] = inflow
        update = model.update(pressure * scaling.p_h, film * scaling.film_scale, temperature, forcing,
                              wall_fluxes=False)
        rise = max(float(temperature.max() - t_in), MIN_RISE)
        temperature, factor, last_change, _ = _next_film_state(accelerator, temperature, factor, update, relaxation,
                                                               rise)
        temperature[..., :GHOST] = inflow
        solver.set_patch_state(temperature[..., GHOST:], factor[..., GHOST:])
        status = solve.cycle(top, STAGE_CYCLES_PER_UPDATE)
        solve.history.outer += 1
        solve.history.thermal_changes.append(last_change)
        changes.append(last_change)
        films.append(solver.summary().h_c)
        hottest.append(float(update.temperature[..., GHOST:].max()) - t_in)
        done = (status.converged and last_change < settings.thermal_tolerance * rise
                and len(films) >= STEADY_UPDATES and _h_c_steady(films[-STEADY_UPDATES:]))
        # the thermal floor of solve.py's outer loop: a flicker of the hot spot below 1 % of the rise, h_c steady
        settled = status.converged or _pressure_settled(solve.history, settings)
        floor = settled and _at_thermal_floor(changes, films, THERMAL_FLOOR_FRACTION * rise)
        ended = done or floor or (figures_settled(hottest, films, changes, rise)
                                  and stage_pressure_settled(solve.history, settings))
        judged = len(changes) > PROVISIONAL_MIN_ITERATIONS - PROVISIONAL_WINDOW  # the window can end by the minimum
        if not ended and next_certain is not None and judged:
            candidate = replace(update, temperature=temperature, viscosity_factor=factor)
            candidate_states = below_states + (patch_state_columns(candidate, slice(GHOST, None)),)
            certain = certain + 1 if next_certain(OutletStage(solver, candidate_states, None)) else 0
        provisional = not ended and certain >= PROVISIONAL_WINDOW and len(changes) >= PROVISIONAL_MIN_ITERATIONS
        if ended or provisional:
            if floor:
                solve.history.thermal_floor = last_change
            solve.settle(top)  # on a flicker of the spike the mean of its two phases, as the uniform loop ends
            update = model.completed(update)
            patch_state = replace(update, temperature=temperature, viscosity_factor=factor)
            states = below_states + (patch_state_columns(patch_state, slice(GHOST, None)),)
            return OutletStage(solver, states, (model.composite_flux(update.heat_flux_1, 0),
                                                model.composite_flux(update.heat_flux_2, 1)), provisional), CONVERGED
        # A limit cycle above the floor: relax harder, as the uniform loop does. The patch on the default case's S4
        # at the spacing of uniform 2049 x 65 flickered at 0.5-0.7 K (1.5-2 % of its rise) for 40 outer iterations
        # at full relaxation; halved, it converged in 18.
        if _stalled(changes[window:]):
            relaxation = max(0.5 * relaxation, MIN_RELAXATION_SCALE)
            window = len(changes)
            accelerator.reset()
    solve.solver = before
    before.work_units = solver.work_units
    _restore(before, index, saved)
    if base is None:
        before.set_film_state(index, state.temperature, state.viscosity_factor)
    if not status.diverged:
        status = Status(Outcome.NOT_CONVERGED, f"outlet patch: thermal loop not converged ({last_change:.2e} K)")
    return None, status


def figures_settled(hottest: list[float], films: list[float], changes: list[float], rise: float) -> bool:
    """Over the last FIGURE_WINDOW outer iterations of a stage the hottest rise (K) spans at most FIGURE_SPREAD of its
    mean, the changes of the film temperatures (K) stay below FLICKER_BOUND times the rise (K) and h_c
    (dimensionless) spans at most THERMAL_FLOOR_H_C of its last value."""
    from facegear_tehl.ehl.solve import THERMAL_FLOOR_H_C

    if len(hottest) < FIGURE_WINDOW:
        return False
    rises, h_c = hottest[-FIGURE_WINDOW:], films[-FIGURE_WINDOW:]
    return (max(rises) - min(rises) <= FIGURE_SPREAD * sum(rises) / FIGURE_WINDOW
            and max(changes[-FIGURE_WINDOW:]) < FLICKER_BOUND * rise
            and max(h_c) - min(h_c) <= THERMAL_FLOOR_H_C * abs(h_c[-1]))


def stage_pressure_settled(history: History, settings: SolverSettings) -> bool:
    """An outlet stage's pressure has settled: solve.py's algebraic floor (the last four changes per cycle below
    FLOOR_BAND times the tolerance) with the load error of the last two cycles within STAGE_LOAD_BAND times the load
    tolerance."""
    from facegear_tehl.ehl.solve import _pressure_settled

    return _pressure_settled(history, settings, STAGE_LOAD_BAND)


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


def outlet_stages(solve: PointSolve, index: int, state: FilmState) -> tuple[Composite | None, str]:
    """The outlet stages on top of level `index` (the finest uniform grid, converged with `state`): a patch at half
    its x spacing from PATCH_START, then (`always`, or `auto` while the last patch moved ΔT_max or μ by more than
    AUTO_DT_MAX_ERROR or AUTO_MU_ERROR) patches at half the spacing of the one before from NESTED_PATCH_STARTS, each
    tried with STAGE_COARSE_CYCLES in turn; a stage with another on top of it may end provisionally
    (PROVISIONAL_MARGIN). The composite of the last converged stage (None if the first failed) and why a stage
    failed ("" if none did). A stage that fails on top of a provisional one: the solve goes back to where the
    stages began (a copy of it kept then) and solves the stages below the failed one again, each to convergence, as
    a run whose settings stop there (`solver.outlet_patches`); the work of both counts."""
    starts = ((PATCH_START,) + NESTED_PATCH_STARTS)[:solve.settings.outlet_patches]
    before = pickle.dumps(solve) if len(starts) > 1 else None  # the solve as the stages find it
    result, note, depth, provisional = _in_stages(solve, index, state, starts, early=True)
    if provisional:
        outer, cycles, work = solve.history.outer, solve.history.cycles, solve.solver.work_units
        solve.__dict__.update(pickle.loads(before).__dict__)
        solve.history.outer, solve.history.cycles, solve.solver.work_units = outer, cycles, work
        result, _, _, _ = _in_stages(solve, index, state, starts[:depth], early=False)
    return result, note


def _in_stages(solve: PointSolve, index: int, state: FilmState, starts: tuple[float, ...],
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
        for cycles in STAGE_COARSE_CYCLES:
            refined, status = refine_outlet(solve, top, state, cycles, stage, starts[depth], next_certain)
            if refined is not None:
                break
        if refined is None:
            what = "outlet patch" if stage is None else f"outlet patch {depth + 1}"
            return result, f"{what}: {status.message}", depth, stage is not None and stage.provisional
        stage, previous = refined, figures
        result = composite(solve, stage)
        figures = _figures(result)
        if solve.settings.outlet_refinement == "auto" and not (_moved(figures, previous, 1.0)
                                                               or _estimate_above(figures, uniform, depth + 1)):
            break
    return result, "", len(stage.solver.patches), stage.provisional


def _estimate_above(figures: dict[str, float], uniform: dict[str, float], patches: int) -> bool:
    """The error estimate the result reports after `patches` patches (Richardson over the whole refinement from the
    uniform grid's `uniform` figures, report._outlet_scalars) exceeds AUTO_DT_MAX_ERROR for ΔT_max or AUTO_MU_ERROR
    for μ: a last stage that moved its figures by less than the bounds (`_moved`) may still leave that estimate above
    them when the stages before moved them far (S2 of the default case: its second patch moved ΔT_max by 1.6 %, the
    two by 6.6 %, an estimate of 2.1 %)."""
    ratio = 2 ** patches
    return any(figures[name] != 0.0 and abs(richardson_error(figures[name], uniform[name], order, ratio)) > bound
               for name, order, bound in (("dT_max", ORDER_DT_MAX, AUTO_DT_MAX_ERROR), ("mu", ORDER_MU, AUTO_MU_ERROR)))


def _next_certain(solve: PointSolve, previous: dict[str, float]) -> Callable[[OutletStage], bool]:
    """Whether the stage on top of a candidate stage is certain: always under `always`; under `auto` when the
    candidate's composite moved ΔT_max or μ against `previous` by more than PROVISIONAL_MARGIN times the bounds."""
    if solve.settings.outlet_refinement != "auto":
        return lambda candidate: True
    return lambda candidate: _moved(_stage_figures(solve, candidate), previous, PROVISIONAL_MARGIN)


def _figures(result: Composite) -> dict[str, float]:
    """dT_max (K) and mu of a composite."""
    return {name: result.scalars[name][0] for name in ("dT_max", "mu")}


def _moved(figures: dict[str, float], previous: dict[str, float], margin: float) -> bool:
    """ΔT_max or μ moved from `previous` by more than `margin` times AUTO_DT_MAX_ERROR or AUTO_MU_ERROR (relative;
    a previous value of zero never counts)."""
    moved = {name: abs(figures[name] / previous[name] - 1.0) if previous[name] != 0.0 else 0.0
             for name in ("dT_max", "mu")}
    return moved["dT_max"] > margin * AUTO_DT_MAX_ERROR or moved["mu"] > margin * AUTO_MU_ERROR


def _uniform_figures(solve: PointSolve, level: Level, state: FilmState) -> dict[str, float]:
    """dT_max (K) and mu of the uniform grid's solution."""
    mu = friction_coefficients(state, level.pressure, cell_area(level, solve.scaling), solve.point.load)[0]
    return {"dT_max": float(state.temperature.max()) - solve.lubricant.inlet_temperature, "mu": mu}


def _with_inflow(solver: PatchedSolver, start: int, pressure: np.ndarray,
                 film: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The composite pressure and film on the patch's energy columns: the grid below interpolated (bicubic along x)
    on the GHOST inflow columns, then the patch's `pressure` and `film` (its settled ones, PointSolve.settled_pressure:
    on a flicker of the spike the mean of its two phases, as the uniform loop evaluates its film state)."""
    below = solver.below
    ghost = slice(start, start + GHOST)
    inflow = np.maximum(grid.SEMI_X.prolong_cubic(below.pressure)[:, ghost], 0.0)
    return np.hstack([inflow, pressure]), np.hstack([grid.SEMI_X.prolong_cubic(below.film)[:, ghost], film])


@dataclass(frozen=True)
class Composite:
    """The composite solution on the grid below's nodes (the patches' values injected at the nodes they share) and
    the figures of the composite over all its parts (SI), which replace the uniform grid's in the results."""

    pressure: np.ndarray  # Pa, (ny, nx) of the uniform grid
    film: np.ndarray  # m
    state: FilmState  # the uniform grid's film state with the patches' injected on its columns
    scalars: dict[str, tuple[float, str]]
    note: str  # the patches, for models.solver


def composite(solve: PointSolve, stage: OutletStage) -> Composite:
    """The composite of an outlet stage for the results: fields on the uniform grid's nodes, and p_max, h_min,
    the temperature extremes and the friction coefficients over all parts (each part's traction integrated on its
    spacing, with the weights of the composite trapezoid rule)."""
    solver, scaling = stage.solver, solve.scaling
    parts = [(level, own, state) for (level, own), state in zip(solver.parts(), stage.states, strict=True)]
    # fields: each patch injected into the part below it, from the last one down
    pressure, film = parts[-1][0].pressure.copy(), parts[-1][0].film.copy()
    state_fields = {name: getattr(parts[-1][2], name) for name in STATE_FIELDS}
    for (level, _, state), place in zip(reversed(parts[:-1]), reversed(solver.patches), strict=True):
        inside = slice(place.first, place.last + 1)
        pressure, film = _inject(level.pressure, pressure, inside), _inject(level.film, film, inside)
        state_fields = {name: None if getattr(state, name) is None else
                        _inject(getattr(state, name), state_fields[name], inside) for name in STATE_FIELDS}
    t_in = solve.lubricant.inlet_temperature
    own_parts = [(level.x[own], level.y, level.pressure[:, own], level.film[:, own],
                  patch_state_columns(state, own)) for level, own, state in parts if own.any()]
    scalars: dict[str, tuple[float, str]] = {}
    figures = _stage_figures(solve, stage)
    cold = min(own_parts, key=lambda part: part[4].temperature.min())
    low = min(own_parts, key=lambda part: part[3].min())
    j, i = np.unravel_index(int(np.argmin(low[3])), low[3].shape)
    _, jc, ic = np.unravel_index(int(np.argmin(cold[4].temperature)), cold[4].temperature.shape)
    middle = stage.state.temperature.shape[0] // 2
    scalars.update({
        "h_c": (solver.summary().h_c * scaling.film_scale, "m"),
        "p_max": (max(float(part[2].max()) for part in own_parts) * scaling.p_h, "Pa"),
        "h_min": (float(low[3][j, i]) * scaling.film_scale, "m"),
        "x_h_min": (float(low[0][i]) * scaling.b, "m"),
        "y_h_min": (float(low[1][j]) * scaling.a, "m"),
        "dT_max": (figures["dT_max"], "K"),
        "dT_min": (float(cold[4].temperature.min()) - t_in, "K"),
        "x_dT_min": (float(cold[0][ic]) * scaling.b, "m"),
        "y_dT_min": (float(cold[1][jc]) * scaling.a, "m"),
        "dT_mid_max": (max(float(part[4].temperature[middle].max()) for part in own_parts) - t_in, "K"),
        "dT_surface_1_max": (max(float(part[4].temperature[0].max()) for part in own_parts) - t_in, "K"),
        "dT_surface_2_max": (max(float(part[4].temperature[-1].max()) for part in own_parts) - t_in, "K"),
    })
    scalars.update({"mu": (figures["mu"], "1"), "mu_1": (figures["mu_1"], "1"), "mu_2": (figures["mu_2"], "1"),
                    "outlet_patch_start": (float(solver.levels[solver.uniform_count].x[0]) * scaling.b, "m"),
                    "outlet_patches": (float(len(solver.patches)), "1")})
    note = "; ".join(f"a patch at {'half the x spacing' if k == 0 else 'half that'} over X >= {level.x[0]:.2f} b"
                     for k, (level, _, _) in enumerate(parts[1:]))
    return Composite(pressure * scaling.p_h, film * scaling.film_scale, replace(parts[0][2], **state_fields), scalars,
                     note)


def _friction(solve: PointSolve, stage: OutletStage) -> tuple[float, float]:
    """The friction coefficients of bodies 1 and 2 over the composite: each part's traction on its own spacing, with
    the weights of the composite trapezoid rule, over the load."""
    solver, scaling, mu = stage.solver, solve.scaling, []
    levels = [level for level, _ in solver.parts()]
    for body in (1, 2):
        force = sum(_traction(getattr(state, f"stress_{body}"), level.pressure, weight) * level.hx
                    for level, state, weight in zip(levels, stage.states, _trapezoid_weights(solver), strict=True))
        mu.append(float(np.hypot(*(force * levels[0].hy * scaling.a * scaling.b)) / solve.point.load))
    return mu[0], mu[1]


def _stage_figures(solve: PointSolve, stage: OutletStage) -> dict[str, float]:
    """dT_max (K) and the friction coefficients mu, mu_1, mu_2 of a stage's composite, over all its parts (`composite`
    takes them from here; a candidate stage of refine_outlet needs no more)."""
    hottest = max(float(state.temperature[..., own].max())
                  for (_, own), state in zip(stage.solver.parts(), stage.states, strict=True) if own.any())
    mu_1, mu_2 = _friction(solve, stage)
    return {"dT_max": hottest - solve.lubricant.inlet_temperature, "mu": 0.5 * (mu_1 + mu_2), "mu_1": mu_1,
            "mu_2": mu_2}


def _inject(coarse: np.ndarray, fine: np.ndarray, inside: slice) -> np.ndarray:
    """`coarse` (.., nx) with the nodes it shares with `fine`, a patch over its columns `inside`, taken from it."""
    out = coarse.copy()
    out[..., inside] = fine[..., ::2]
    return out


def _trapezoid_weights(solver: PatchedSolver) -> list[np.ndarray]:
    """The column weights of the composite's trapezoid rule along x on each part (uniform grid first), in cells of
    that part: a patch's end columns a half (the grid below counts the other half), and the columns a finer patch
    covers take its trapezoid weights off."""
    weights = []
    for index in range(solver.uniform_count - 1, len(solver.levels)):
        level = solver.levels[index]
        weight = np.ones(level.nx) if index < solver.uniform_count else _trapezoid(level.nx)
        if index + 1 < len(solver.levels):
            place = solver.patches[index + 1 - solver.uniform_count]
            weight[place.first:place.last + 1] -= _trapezoid(place.last - place.first + 1)
        weights.append(weight)
    return weights


def _trapezoid(n: int) -> np.ndarray:
    weight = np.ones(n)
    weight[0] = weight[-1] = 0.5
    return weight


def _traction(stress: np.ndarray, pressure: np.ndarray, weight: np.ndarray) -> np.ndarray:
    """\\sum of the (x, y) shear stress over the pressurised nodes with column weights `weight` (per unit cell)."""
    wet = (pressure > 0.0) * weight
    return np.array([(stress[0] * wet).sum(), (stress[1] * wet).sum()])
