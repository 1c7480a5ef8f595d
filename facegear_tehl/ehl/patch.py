r"""Locally X-refined patches of the finest uniform grid (the outlet and its pressure spike): a composite grid
solved by FAS (Brandt 1977, "Multi-level adaptive solutions to boundary-value problems", Math. Comp. 31;
McCormick 1989, the fast adaptive composite grid method).

A patch spans the columns [first, last] of the grid below it (all its rows) at half its X spacing; its end columns
coincide with nodes of that grid. The grid below is the finest uniform grid or another patch (a stack, each patch
inside the one below it). The composite problem:
- at a patch's interior nodes outside the patch above it the Reynolds equation on its spacing (reynolds.py); its
  end columns are held at the values of the grid below (Dirichlet), P = 0 on the Y boundaries as everywhere;
- the film on a patch H = H_0 + C_d W + F_h, W the deflection of the composite pressure up to that patch (the patch
  inside, the fourth-order interpolation along X of the composite below it outside) convolved on the uniform grid of
  the patch's spacing over the whole domain (elastic.py);
- at the nodes of the uniform grid outside the first patch its own equations;
- the load \iint P dX dY of the composite pressure (trapezoid rule along X on each part) = 2 pi/3.

Each patch is one more level above the uniform hierarchy, and multigrid.MultigridSolver.cycle runs over them
unchanged; only their transfers differ (FAS, as between the uniform levels): P_c = I P_f at the patch's interior
coarse columns, f_c = I (f_f - L_f P_f) + L_c P_c and F_c = I H_f - H_0 - C_d W_c there (W_c the deflection of the
composite at the coarse spacing), the force balance's right-hand side g_c = g_f + \iint_f P - \iint_c P (each the
composite up to that level); back, P_f += I (P_c - I P_f) where P_f > 0 and the end columns take P_c.
Work units count sweeps of the uniform grid of the first patch's spacing.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from facegear_tehl.ehl import flow, grid
from facegear_tehl.ehl.elastic import DeflectionOperator
from facegear_tehl.ehl.multigrid import Level, MultigridSolver, Problem, Relaxation, corrected_nodes
from facegear_tehl.ehl.tuning import TUNING


@dataclass(frozen=True)
class CompositeSummary:
    """The figures of a composite solution (dimensionless): the film at the centre, the smallest film, the largest
    pressure and its X."""

    h_c: float
    h_min: float
    p_max: float
    x_p_max: float


def patch_columns(x: np.ndarray, span: tuple[float, float]) -> tuple[int, int]:
    """The columns (first, last) of the uniform axis `x` that enclose `span` = (X_a, X_b): the nodes at or
    outside its ends (the domain's end nodes at most)."""
    first = int(np.searchsorted(x, span[0], side="right")) - 1
    last = int(np.searchsorted(x, span[1], side="left"))
    first, last = max(first, 0), min(last, x.size - 1)
    if last - first < 2:
        raise ValueError(f"patch span {span} covers fewer than two cells of the grid below (spacing {x[1] - x[0]:g})")
    return first, last


def trapezoid(pressure: np.ndarray, hx: float, hy: float) -> float:
    """\\iint P dX dY over an array's extent, trapezoid rule (P = 0 on the Y boundaries, so only X's end columns
    weigh half)."""
    return (float(pressure.sum()) - 0.5 * float(pressure[:, 0].sum() + pressure[:, -1].sum())) * hx * hy


@dataclass
class _Patch:
    """One patch level's place: its columns [first, last] on the grid below (that grid's own indexing), its columns
    on the whole X axis of its spacing, the deflection operator over its own extent and the cache of
    PatchedSolver._interpolated_below."""

    first: int
    last: int
    columns: slice
    local: DeflectionOperator
    cache: tuple[list[np.ndarray], np.ndarray, np.ndarray] | None = field(default=None)


class PatchedSolver(MultigridSolver):
    """FAS multigrid on a uniform hierarchy plus a stack of patches, each twice as fine along X as the grid below it
    over a span of it; the patches are the last levels (the last one `levels[-1]`, the finest)."""

    def __init__(self, problem: Problem, shapes: list[tuple[int, int]], span: tuple[float, float],
                 relaxation: Relaxation = Relaxation(), coarse_cycles: int = TUNING.patch_coarse_cycles):
        """`shapes`: (nx, ny) of the uniform levels, coarsest first (grid.hierarchy_shapes); `coarse_cycles`: V-cycles
        of the grid below per coarse-grid correction of a patch."""
        super().__init__(problem, shapes, relaxation)
        self.patch_coarse_cycles = coarse_cycles
        self.uniform_count = len(self.levels)
        self.patches: list[_Patch] = []
        self._add_patch(span)

    @classmethod
    def over(cls, solver: MultigridSolver, span: tuple[float, float],
             coarse_cycles: int = TUNING.patch_coarse_cycles) -> PatchedSolver:
        """A patch over `span` (X) on top of a solved hierarchy (uniform, or patched already: then the new patch lies
        over the last one): its levels (the same objects, which the composite cycles go on changing), H_0 and work
        count are taken over."""
        patched = cls.__new__(cls)
        patched.__dict__.update(solver.__dict__)
        patched.patch_coarse_cycles = coarse_cycles
        patched.levels, patched.transfers = list(solver.levels), list(solver.transfers)
        if not isinstance(solver, PatchedSolver):
            patched.uniform_count, patched.patches = len(solver.levels), []
        else:
            patched.patches = list(solver.patches)
        patched._add_patch(span)
        patched.finest_nodes = solver.finest_nodes  # work units stay in sweeps of the grid solved before
        return patched

    def _add_patch(self, span: tuple[float, float]) -> None:
        below, problem = self.levels[-1], self.problem
        first, last = patch_columns(below.x, span)
        below_start = self.patches[-1].columns.start if self.patches else 0
        whole = 2 * (self._whole_nx(len(self.levels) - 1)) - 1
        columns = slice(2 * (below_start + first), 2 * (below_start + last) + 1)
        # The level of the patch spacing over the whole domain: its deflection operator (the composite W), relaxation
        # patterns and switch are the patch's; its arrays are cut to the patch.
        patch = self._make_level(whole, below.ny)
        patch.x = patch.x[columns].copy()
        patch.pressure = patch.pressure[:, columns].copy()
        patch.film_rhs = patch.film_rhs[:, columns].copy()
        patch.reynolds_rhs = patch.reynolds_rhs[:, columns].copy()
        # Its Gauss-Seidel / Jacobi-distributive switch is not raised above the grid below's: _make_level scales it by
        # (h_y/h_x)^2, calibrated on cells up to 8 times longer along Y than along X; a patch at a quarter or an
        # eighth of the 513 x 65 face gear grid's X spacing (h_y/h_x 32-64) then relaxed its pressure to zero
        # inside the Hertzian zone and ran away in its first sweep (default case S4, switch 7.4e4), while the switch
        # of the grid below (1.3e4, down to 100) relaxed it steadily.
        patch.switch_scale = min(patch.switch_scale, below.switch_scale)
        self.levels.append(patch)
        self.transfers.append(grid.SEMI_X)
        self.patches.append(_Patch(first, last, columns, DeflectionOperator(patch.nx, patch.ny, patch.hx, patch.hy,
                                                                           problem.ellipticity)))
        if len(self.patches) == 1:
            self.finest_nodes = whole * below.ny

    def _whole_nx(self, index: int) -> int:
        """Nodes along X of the whole axis at the spacing of level `index`."""
        nx = self.levels[min(index, self.uniform_count - 1)].nx
        for _ in range(index - self.uniform_count + 1):
            nx = 2 * nx - 1
        return nx

    def _place(self, index: int) -> _Patch | None:
        """The patch at level `index`, None for a uniform level or beyond the last patch."""
        patch = index - self.uniform_count
        return self.patches[patch] if 0 <= patch < len(self.patches) else None

    @property
    def patch(self) -> Level:
        """The last (finest) patch."""
        return self.levels[-1]

    @property
    def below(self) -> Level:
        """The grid under the last patch (the finest uniform grid, or the patch before)."""
        return self.levels[-2]

    @property
    def first(self) -> int:
        """The last patch's first column on the grid below."""
        return self.patches[-1].first

    @property
    def last(self) -> int:
        """The last patch's last column on the grid below."""
        return self.patches[-1].last

    @property
    def columns(self) -> slice:
        """The last patch's columns on the whole X axis of its spacing."""
        return self.patches[-1].columns

    def set_patch_state(self, temperature: np.ndarray, viscosity_factor: np.ndarray) -> None:
        """Freeze an across-film state (nz, ny, patch columns) on the last patch alone (the grids below keep theirs)
        and recompute its film and flow coefficients."""
        patch = self.patch
        patch.temperature = np.ascontiguousarray(temperature)
        patch.viscosity_factor = np.ascontiguousarray(viscosity_factor)
        patch.temperature_factor = flow.temperature_factors(patch.temperature, self.problem.law)
        self.freeze(patch, patch.pressure)
        self.update_film(patch)

    # ------------------------------------------------------------ composite
    def composite_integral(self, index: int | None = None) -> float:
        """\\iint P dX dY of the composite pressure up to level `index` (default: the last patch): the uniform grid
        outside the first patch, each patch outside the next."""
        index = len(self.levels) - 1 if index is None else index
        level, place = self.levels[index], self._place(index)
        if place is None:
            return level.load_integral()
        below = self.levels[index - 1]
        inside = below.pressure[:, place.first:place.last + 1]
        return (self.composite_integral(index - 1) - trapezoid(inside, below.hx, below.hy)
                + trapezoid(level.pressure, level.hx, level.hy))

    def parts(self) -> list[tuple[Level, np.ndarray]]:
        """The composite's parts, finest uniform grid first: each level with the mask of its columns that no finer
        patch covers (a patch's end columns belong to the patch)."""
        parts = []
        for index in range(self.uniform_count - 1, len(self.levels)):
            level, above = self.levels[index], self._place(index + 1)
            own = np.ones(level.nx, dtype=bool)
            if above is not None:
                own[above.first:above.last + 1] = False
            parts.append((level, own))
        return parts

    def summary(self) -> CompositeSummary:
        """h_c (bilinear at X = Y = 0 on the finest part that holds it), h_min and p_max over all parts."""
        parts = self.parts()
        holder = next(level for level, _ in reversed(parts) if level.x[0] <= 0.0 <= level.x[-1])
        x, pressure = max(((level.x[own], level.pressure[:, own]) for level, own in parts if own.any()),
                          key=lambda part: part[1].max())
        j, i = np.unravel_index(int(np.argmax(pressure)), pressure.shape)
        return CompositeSummary(
            h_c=grid.bilinear_at(holder.film, holder.x, holder.y, 0.0, 0.0),
            h_min=min(float(level.film[:, own].min()) for level, own in parts if own.any()),
            p_max=float(pressure[j, i]),
            x_p_max=float(x[i]),
        )

    def whole_pressure(self, index: int) -> np.ndarray:
        """The composite pressure up to level `index` on the whole X axis at its spacing: the levels below
        interpolated (fourth order along X, clipped at 0), the patch's own values over its columns."""
        place = self._place(index)
        if place is None:
            return self.levels[index].pressure
        whole = np.maximum(grid.SEMI_X.prolong_cubic(self.whole_pressure(index - 1)), 0.0)
        whole[:, place.columns] = self.levels[index].pressure
        return whole

    # ---------------------------------------------------- the patch's level
    def _interpolated_below(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        """The composite below patch `index` interpolated to its spacing over the patch (P_I) and its deflection at
        the patch's nodes (K*P_I over the whole domain, without C_d), kept while the pressures of the parts below (the
        finest uniform grid and the patches under this one) do not change: a sweep of the patch compares them, and
        builds the composite only when one did."""
        place, level = self._place(index), self.levels[index]
        parts = [self.levels[i].pressure for i in range(self.uniform_count - 1, index)]
        if place.cache is None or not all(np.array_equal(a, b) for a, b in zip(place.cache[0], parts, strict=True)):
            interpolated = np.maximum(grid.SEMI_X.prolong_cubic(self.whole_pressure(index - 1)), 0.0)
            w = level.deflection.apply(interpolated)[:, place.columns]
            place.cache = ([part.copy() for part in parts], interpolated[:, place.columns].copy(), w)
        return place.cache[1], place.cache[2]

    def _index(self, level: Level) -> int:
        return next(i for i in range(len(self.levels) - 1, -1, -1) if self.levels[i] is level)

    def deflection(self, level: Level) -> np.ndarray:
        """A patch: the deflection of the composite pressure up to it at its nodes; other levels: their own.

        By linearity K*P = K*P_I + K*(P_f - P_I) over the patch, P_I the composite below interpolated
        (_interpolated_below): the domain-sized convolution changes only with the grids below, a patch sweep pays a
        patch-sized one."""
        index = self._index(level)
        place = self._place(index)
        if place is None:
            return super().deflection(level)
        interpolated, w = self._interpolated_below(index)
        return w + place.local.apply(level.pressure - interpolated)

    def pressure_change(self, level: Level, previous: np.ndarray) -> float:
        """A patch: \\iint |P - P_previous| over the patch relative to the composite's load \\iint P (over the patch
        alone the same change of the spike would count more, the smaller the patch); other levels: their own."""
        index = self._index(level)
        if self._place(index) is None:
            return super().pressure_change(level, previous)
        return trapezoid(np.abs(level.pressure - previous), level.hx, level.hy) / max(self.composite_integral(index),
                                                                                       1e-300)

    def force_error(self, level: Level) -> float:
        """A patch: the load error of the composite pressure up to it."""
        index = self._index(level)
        if self._place(index) is None:
            return super().force_error(level)
        return self.composite_integral(index) + level.force_rhs

    def coarse_cycles(self, index: int) -> int:
        """`patch_coarse_cycles` (default TUNING.patch_coarse_cycles) under a patch, one elsewhere."""
        return self.patch_coarse_cycles if self._place(index) is not None else 1

    def coarsen(self, index: int) -> None:
        """From a patch to the grid below: FAS right-hand sides at the patch's interior coarse columns, the grid's
        own ones elsewhere, the composite load in its force balance."""
        place = self._place(index)
        if place is None:
            return super().coarsen(index)
        patch, below = self.levels[index], self.levels[index - 1]
        inner = slice(place.first + 1, place.last)
        below.pressure[:, inner] = grid.restrict_pressure_x(patch.pressure)[:, 1:-1]
        below.pressure_restricted = below.pressure.copy()
        force_rhs = patch.force_rhs + self.composite_integral(index)
        self.reset_rhs(below)
        w = self.deflection(below)
        film = grid.inject_x(patch.film)[:, 1:-1]
        below.film_rhs[:, inner] = film - self.h0 - self.problem.deflection_coefficient * w[:, inner]
        self.update_film(below)
        tau = (grid.restrict_full_weighting_x(self.residual(patch))
               + self.operator(below)[:, place.first:place.last + 1])
        below.reynolds_rhs[:, inner] = tau[:, 1:-1]
        below.force_rhs = force_rhs - self.composite_integral(index - 1)
        return None

    def refine(self, index: int) -> None:
        """The grid below's correction, interpolated linearly, at the patch's `corrected_nodes` (always truncated: a
        patch starts from a converged solution, the closeness the uniform grids wait for, TUNING.truncation_band; with
        the full correction the two-patch composite of tests/test_patch.py stalls at 1.1e-4 per cycle); its end
        columns take the grid below's values."""
        place = self._place(index)
        if place is None:
            return super().refine(index)
        patch, below = self.levels[index], self.levels[index - 1]
        columns = slice(place.first, place.last + 1)
        correction = grid.prolong_linear_x((below.pressure - below.pressure_restricted)[:, columns])
        active = corrected_nodes(patch.pressure)
        patch.pressure[active] += correction[active]
        np.maximum(patch.pressure, 0.0, out=patch.pressure)
        patch.pressure[:, 0] = below.pressure[:, place.first]
        patch.pressure[:, -1] = below.pressure[:, place.last]
        self.update_film(patch)
        return None

    def interpolate_up(self, index: int) -> None:
        """Start a patch from the fourth-order interpolation along X of the grid below."""
        place = self._place(index)
        if place is None:
            return super().interpolate_up(index)
        patch = self.levels[index]
        self.reset_rhs(patch)
        columns = slice(2 * place.first, 2 * place.last + 1)
        patch.pressure = np.maximum(grid.SEMI_X.prolong_cubic(self.levels[index - 1].pressure)[:, columns], 0.0)
        self.update_film(patch)
        return None
