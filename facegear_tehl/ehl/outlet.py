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
from typing import TYPE_CHECKING

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import grid, jaeger
from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.friction import friction_coefficients
from facegear_tehl.ehl.patch import COARSE_CYCLES, PatchedSolver
from facegear_tehl.ehl.report import ORDER_DT_MAX, ORDER_MU, cell_area, richardson_error
from facegear_tehl.ehl.thermal import FilmState, FilmThermalModel
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.solution import CONVERGED, Outcome, Status

if TYPE_CHECKING:
    from facegear_tehl.ehl.solve import PointSolve

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


def along_x(values: np.ndarray) -> np.ndarray:
    """Linear interpolation along x (the last axis) to twice the resolution, for (..., ny, nx) arrays."""
    flat = values.reshape((-1, values.shape[-1]))
    return grid.prolong_linear_x(flat).reshape(values.shape[:-1] + (2 * values.shape[-1] - 1,))


class PatchFilmModel(FilmThermalModel):
    """The film state on the patch's columns with GHOST inflow columns before them (x on the patch's spacing, m).
    The surfaces take Jaeger's rise of the composite flux: `below_flux` (the grid below's wall fluxes on the whole
    x axis at the patch's spacing) with the patch's own flux from column `offset + GHOST` on."""

    first_column = GHOST

    def __init__(self, x: np.ndarray, y: np.ndarray, layers: int, lubricant: Lubricant, point: ContactPoint,
                 offset: int, below_flux: tuple[np.ndarray, np.ndarray]):
        super().__init__(x, y, layers, lubricant, point, solve_energy=True)
        self.offset = offset
        self.below_flux = below_flux
        self.whole_matrix = jaeger.influence_matrix(below_flux[0].shape[1], self.dx)

    def _surface(self, flux: np.ndarray, index: int, speed: float) -> np.ndarray:
        own = slice(self.offset + GHOST, self.offset + self.x.size)
        composite = self.below_flux[index].copy()
        composite[:, own] = flux[:, GHOST:]
        rise = jaeger.surface_temperature_rise(composite, self.dx, self.effusivity[index], matrix=self.whole_matrix,
                                               reverse=speed < 0.0)
        return self.t_inlet + rise[:, self.offset:self.offset + self.x.size]


@dataclass(frozen=True)
class OutletStage:
    """The converged outlet stage: the patched solver (its last level the patch) and the patch's film state on its
    own columns (GHOST columns dropped)."""

    solver: PatchedSolver
    state: FilmState


def patch_state_columns(state: FilmState, columns: slice) -> FilmState:
    """A film state cut to `columns` along x (every field's last axis; fields that are None stay None)."""
    cut = {name: getattr(state, name)[..., columns] for name in STATE_FIELDS if getattr(state, name) is not None}
    return replace(state, **cut)



def needs_outlet_patch(solve: PointSolve, index: int, state: FilmState) -> bool:
    """Whether the outlet stage runs after the coupled solve of level `index` converged with `state` (never for an
    entrainment more than MAX_ENTRAINMENT_ANGLE from the x axis): `always`,
    `never`, or (`auto`) when the hottest film node lies on the outlet spike's rising flank (within
    SPIKE_FLANK_NODES upstream of its row's largest pressure, downstream of the contact centre) and the grid's own
    estimate of ΔT_max or μ against the coarse thermal stage exceeds AUTO_DT_MAX_ERROR or AUTO_MU_ERROR."""
    choice = solve.settings.outlet_refinement
    if abs(solve.point.entrainment_angle) > MAX_ENTRAINMENT_ANGLE:
        return False
    if choice != "auto":
        return choice == "always"
    level = solve.solver.levels[index]
    _, j, i = np.unravel_index(int(np.argmax(state.temperature)), state.temperature.shape)
    spike = int(np.argmax(level.pressure[j]))
    if not (level.x[i] > 0.0 and 0 < spike - i <= SPIKE_FLANK_NODES):
        return False
    coarse = solve.summaries[-2] if len(solve.summaries) >= 2 else None
    if coarse is None or not (np.isfinite(coarse.dT_max) and np.isfinite(coarse.mu)):
        return True
    dT_max = float(state.temperature.max()) - solve.lubricant.inlet_temperature
    mu = friction_coefficients(state, level.pressure, cell_area(level, solve.scaling), solve.point.load)[0]
    return ((dT_max != 0.0 and abs(richardson_error(dT_max, coarse.dT_max, ORDER_DT_MAX)) > AUTO_DT_MAX_ERROR)
            or (mu != 0.0 and abs(richardson_error(mu, coarse.mu, ORDER_MU)) > AUTO_MU_ERROR))


def refine_outlet(solve: PointSolve, index: int, state: FilmState,
                  coarse_cycles: int = COARSE_CYCLES) -> tuple[OutletStage | None, Status]:
    """The outlet stage on top of level `index` (the finest uniform grid, its coupled loop converged with `state`),
    `coarse_cycles` V-cycles of the uniform hierarchy per coarse-grid correction of the patch.
    On success `solve.solver` is the patched solver; if the stage runs away or does not converge, the uniform
    solution is restored and None returned with the status."""
    from facegear_tehl.ehl.solve import (
        ANDERSON_DEPTH,
        CYCLES_PER_THERMAL_UPDATE,
        ENERGY_FORCING,
        MIN_RISE,
        THERMAL_FLOOR_FRACTION,
        _at_thermal_floor,
        _next_film_state,
        _pressure_settled,
    )

    uniform, settings, scaling = solve.solver, solve.settings, solve.scaling
    below = uniform.levels[index]
    saved = uniform.snapshot(index)
    solver = PatchedSolver.over(uniform, (PATCH_START, float(below.x[-1])), coarse_cycles)
    top = index + 1
    start = 2 * solver.first - GHOST
    if start < 0:
        return None, Status(Outcome.NOT_CONVERGED, "outlet patch: no room for its inflow columns")
    columns = slice(start, 2 * solver.last + 1)  # the patch with its inflow columns, on the whole fine x axis
    temperature = np.ascontiguousarray(along_x(state.temperature)[..., columns])
    factor = np.ascontiguousarray(np.exp(along_x(np.log(state.viscosity_factor)))[..., columns])
    inflow = temperature[..., :GHOST].copy()
    x = along_x(below.x)[columns]
    model = PatchFilmModel(x * scaling.b, below.y * scaling.a, temperature.shape[0], solve.lubricant, solve.point,
                           start, (along_x(state.heat_flux_1), along_x(state.heat_flux_2)))
    solve.solver = solver
    solver.interpolate_up(top)
    solver.set_patch_state(temperature[..., GHOST:], factor[..., GHOST:])
    status = solve.cycle(top, CYCLES_PER_THERMAL_UPDATE)
    accelerator = Anderson(ANDERSON_DEPTH)
    last_change = None
    patch_state = None
    t_in = solve.lubricant.inlet_temperature
    changes: list[float] = []
    films: list[float] = []
    for _ in range(settings.max_thermal_iterations):
        if status.diverged:
            break
        forcing = ENERGY_FORCING * last_change if last_change is not None else np.inf
        pressure, film = _with_inflow(solver, start)
        temperature[..., :GHOST] = inflow
        update = model.update(pressure * scaling.p_h, film * scaling.film_scale, temperature, forcing)
        rise = max(float(temperature.max() - t_in), MIN_RISE)
        temperature, factor, last_change, _ = _next_film_state(accelerator, temperature, factor, update, 1.0, rise)
        temperature[..., :GHOST] = inflow
        patch_state = replace(update, temperature=temperature, viscosity_factor=factor)
        solver.set_patch_state(temperature[..., GHOST:], factor[..., GHOST:])
        status = solve.cycle(top, CYCLES_PER_THERMAL_UPDATE)
        solve.history.outer += 1
        solve.history.thermal_changes.append(last_change)
        changes.append(last_change)
        films.append(solver.summary().h_c)
        done = status.converged and last_change < settings.thermal_tolerance * rise
        # the thermal floor of solve.py's outer loop: a flicker of the hot spot below 1 % of the rise, h_c steady
        floor = ((status.converged or _pressure_settled(solve.history, settings))
                 and _at_thermal_floor(changes, films, THERMAL_FLOOR_FRACTION * rise))
        if done or floor:
            if floor:
                solve.history.thermal_floor = last_change
            solve._settle(top)  # on a flicker of the spike the mean of its two phases, as the uniform loop ends
            return OutletStage(solver, patch_state_columns(patch_state, slice(GHOST, None))), CONVERGED
    solve.solver = uniform
    uniform.work_units = solver.work_units
    uniform.restore(index, saved)
    uniform.set_film_state(index, state.temperature, state.viscosity_factor)
    if not status.diverged:
        status = Status(Outcome.NOT_CONVERGED, f"outlet patch: thermal loop not converged ({last_change:.2e} K)")
    return None, status


def _with_inflow(solver: PatchedSolver, start: int) -> tuple[np.ndarray, np.ndarray]:
    """The composite pressure and film on the patch's energy columns: the grid below interpolated (bicubic along x)
    on the GHOST inflow columns, the patch's own after them."""
    below, patch = solver.below, solver.patch
    ghost = slice(start, start + GHOST)
    pressure = np.maximum(grid.SEMI_X.prolong_cubic(below.pressure)[:, ghost], 0.0)
    film = grid.SEMI_X.prolong_cubic(below.film)[:, ghost]
    return np.hstack([pressure, patch.pressure]), np.hstack([film, patch.film])


@dataclass(frozen=True)
class Composite:
    """The composite solution on the grid below's nodes (the patch's values injected at the nodes they share) and
    the figures of the composite over both parts (SI), which replace the grid below's in the results."""

    pressure: np.ndarray  # Pa, (ny, nx) of the grid below
    film: np.ndarray  # m
    state: FilmState  # the grid below's film state with the patch's injected on its columns
    scalars: dict[str, tuple[float, str]]


def composite(solve: PointSolve, stage: OutletStage, below_state: FilmState) -> Composite:
    """The composite of the outlet stage for the results: fields on the grid below's nodes, and p_max, h_min,
    the temperature extremes and the friction coefficients over both parts (the patch's traction integrated on its
    spacing, the trapezoid rule across its end columns)."""
    solver, scaling, state = stage.solver, solve.scaling, stage.state
    below, patch = solver.below, solver.patch
    inside = slice(solver.first, solver.last + 1)
    outside = np.ones(below.nx, dtype=bool)
    outside[inside] = False
    pressure, film = below.pressure.copy(), below.film.copy()
    pressure[:, inside], film[:, inside] = patch.pressure[:, ::2], patch.film[:, ::2]
    injected = {}
    for name in STATE_FIELDS:
        value = getattr(below_state, name)
        if value is not None:
            value = value.copy()
            value[..., inside] = getattr(state, name)[..., ::2]
        injected[name] = value
    t_in = solve.lubricant.inlet_temperature
    parts = ((patch.x, patch.y, patch.pressure, patch.film, state),
             (below.x[outside], below.y, below.pressure[:, outside], below.film[:, outside],
              patch_state_columns(below_state, outside)))
    scalars: dict[str, tuple[float, str]] = {}
    hot = max(parts, key=lambda part: part[4].temperature.max())
    cold = min(parts, key=lambda part: part[4].temperature.min())
    low = min(parts, key=lambda part: part[3].min())
    j, i = np.unravel_index(int(np.argmin(low[3])), low[3].shape)
    _, jc, ic = np.unravel_index(int(np.argmin(cold[4].temperature)), cold[4].temperature.shape)
    middle = state.temperature.shape[0] // 2
    scalars.update({
        "h_c": (solver.summary().h_c * scaling.film_scale, "m"),
        "p_max": (max(float(part[2].max()) for part in parts) * scaling.p_h, "Pa"),
        "h_min": (float(low[3][j, i]) * scaling.film_scale, "m"),
        "x_h_min": (float(low[0][i]) * scaling.b, "m"),
        "y_h_min": (float(low[1][j]) * scaling.a, "m"),
        "dT_max": (float(hot[4].temperature.max()) - t_in, "K"),
        "dT_min": (float(cold[4].temperature.min()) - t_in, "K"),
        "x_dT_min": (float(cold[0][ic]) * scaling.b, "m"),
        "y_dT_min": (float(cold[1][jc]) * scaling.a, "m"),
        "dT_mid_max": (max(float(part[4].temperature[middle].max()) for part in parts) - t_in, "K"),
        "dT_surface_1_max": (max(float(part[4].temperature[0].max()) for part in parts) - t_in, "K"),
        "dT_surface_2_max": (max(float(part[4].temperature[-1].max()) for part in parts) - t_in, "K"),
    })
    # traction: the grid below's cells outside the patch, the patch's inside (its end columns shared half and half)
    weight_below = outside.astype(float)
    weight_below[solver.first] = weight_below[solver.last] = 0.5
    weight_patch = np.ones(patch.nx)
    weight_patch[0] = weight_patch[-1] = 0.5
    mu = []
    for stress_below, stress_patch in ((below_state.stress_1, state.stress_1), (below_state.stress_2,
                                                                                 state.stress_2)):
        force = (_traction(stress_below, below.pressure, weight_below) * below.hx
                 + _traction(stress_patch, patch.pressure, weight_patch) * patch.hx) * below.hy * scaling.a * scaling.b
        mu.append(float(np.hypot(*force) / solve.point.load))
    scalars.update({"mu": (0.5 * (mu[0] + mu[1]), "1"), "mu_1": (mu[0], "1"), "mu_2": (mu[1], "1"),
                    "outlet_patch_start": (float(patch.x[0]) * scaling.b, "m")})
    return Composite(pressure * scaling.p_h, film * scaling.film_scale, replace(below_state, **injected), scalars)


def _traction(stress: np.ndarray, pressure: np.ndarray, weight: np.ndarray) -> np.ndarray:
    """\\sum of the (x, y) shear stress over the pressurised nodes with column weights `weight` (per unit cell)."""
    wet = (pressure > 0.0) * weight
    return np.array([(stress[0] * wet).sum(), (stress[1] * wet).sum()])
