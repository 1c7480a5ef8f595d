"""The composite solution of the outlet stages (outlet.py): the uniform grid with its nested patches, each twice as
fine along x as the part below, as one solution for the results. Fields on the uniform grid's nodes (each patch
injected at the nodes it shares with the part below); p_max, h_min, the temperature extremes and the friction
coefficients over all parts, each part's traction integrated on its own spacing with the weights of the composite
trapezoid rule.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Protocol

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.patch import PatchedSolver
from facegear_tehl.ehl.scaling import Scaling
from facegear_tehl.ehl.thermal import FilmState
from facegear_tehl.lubricant import Lubricant

STATE_FIELDS = tuple(f.name for f in fields(FilmState) if f.name != "change")  # its arrays over (.., ny, nx)


class Composed(Protocol):
    """What the composite needs of a point solve."""

    scaling: Scaling
    lubricant: Lubricant
    point: ContactPoint


@dataclass(frozen=True)
class OutletStage:
    """An outlet stage that ended (converged, or provisional): the patched solver (its last level the stage's patch),
    the film state of each part of the composite (PatchedSolver.parts: the uniform grid's, then each patch's on its
    own columns) and the composite wall heat fluxes of bodies 1 and 2 along the whole x axis at the last patch's
    spacing (W/m^2; None for a candidate whose figures are only looked at)."""

    solver: PatchedSolver
    states: tuple[FilmState, ...]
    flux: tuple[np.ndarray, np.ndarray] | None
    provisional: bool = False  # ended once the stage on top of it was certain (outlet.py), not converged

    @property
    def state(self) -> FilmState:
        """The last patch's film state."""
        return self.states[-1]


def patch_state_columns(state: FilmState, columns: slice) -> FilmState:
    """A film state cut to `columns` along x (every field's last axis; fields that are None stay None)."""
    cut = {name: getattr(state, name)[..., columns] for name in STATE_FIELDS if getattr(state, name) is not None}
    return replace(state, **cut)



@dataclass(frozen=True)
class Composite:
    """The composite solution on the grid below's nodes (the patches' values injected at the nodes they share) and
    the figures of the composite over all its parts (SI), which replace the uniform grid's in the results."""

    pressure: np.ndarray  # Pa, (ny, nx) of the uniform grid
    film: np.ndarray  # m
    state: FilmState  # the uniform grid's film state with the patches' injected on its columns
    scalars: dict[str, tuple[float, str]]
    note: str  # the patches, for models.solver


def composite(solve: Composed, stage: OutletStage) -> Composite:
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
    figures = stage_figures(solve, stage)
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


def _friction(solve: Composed, stage: OutletStage) -> tuple[float, float]:
    """The friction coefficients of bodies 1 and 2 over the composite: each part's traction on its own spacing, with
    the weights of the composite trapezoid rule, over the load."""
    solver, scaling, mu = stage.solver, solve.scaling, []
    levels = [level for level, _ in solver.parts()]
    for body in (1, 2):
        force = sum(_traction(getattr(state, f"stress_{body}"), level.pressure, weight) * level.hx
                    for level, state, weight in zip(levels, stage.states, _trapezoid_weights(solver), strict=True))
        mu.append(float(np.hypot(*(force * levels[0].hy * scaling.a * scaling.b)) / solve.point.load))
    return mu[0], mu[1]


def stage_figures(solve: Composed, stage: OutletStage) -> dict[str, float]:
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
