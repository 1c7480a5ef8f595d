r"""A locally X-refined patch of the finest uniform grid (the outlet and its pressure spike): a composite grid
solved by FAS (Brandt 1977, "Multi-level adaptive solutions to boundary-value problems", Math. Comp. 31;
McCormick 1989, the fast adaptive composite grid method).

The patch spans the columns [first, last] of the finest uniform grid (all its rows) at half its X spacing; its end
columns coincide with nodes of that grid. The composite problem:
- at the patch's interior nodes the Reynolds equation on the patch spacing (reynolds.py); the end columns are held
  at the values of the grid below (Dirichlet), P = 0 on the Y boundaries as everywhere;
- the film on the patch H = H_0 + C_d W + F_h, W the deflection of the composite pressure (the patch inside, the
  fourth-order interpolation along X of the grid below outside) convolved on the uniform grid of the patch spacing
  over the whole domain (elastic.py);
- at the nodes of the grid below outside the patch its own equations;
- the load \iint P dX dY of the composite pressure (trapezoid rule along X on each part) = 2 pi/3.

The patch is one more level above the uniform hierarchy, and multigrid.MultigridSolver.cycle runs over it unchanged;
only its transfers differ (FAS, as between the uniform levels): P_c = I P_f at the patch's interior coarse columns,
f_c = I (f_f - L_f P_f) + L_c P_c and F_c = I H_f - H_0 - C_d K_c*P_c there, the force balance's right-hand side
g_c = g_f + \iint_composite P - \iint P_c; back, P_f += I (P_c - I P_f) where P_f > 0 and the end columns take P_c.
Work units count sweeps of the uniform grid of the patch spacing, the grid the composite one stands for.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from facegear_tehl.ehl import flow, grid
from facegear_tehl.ehl.elastic import DeflectionOperator
from facegear_tehl.ehl.multigrid import Level, MultigridSolver, Problem, Relaxation

# V-cycles of the uniform hierarchy per coarse-grid correction of the patch. One (a plain V-cycle) leaves the grid
# below's composite problem (its own equations outside the patch, the FAS ones inside) too far from solved near the
# patch's upstream end: the correction alternates in sign there and the iteration ran away for 18 of 55 starts X_a in
# [-1.5, 0] b at S1-S5 of the default face gear case (513 x 65 + patch, isothermal Newtonian; an end in [-1.1, -0.6]
# b, where it crosses the inlet side of the Hertzian zone); two left 4 runaways, three none (the one start not
# converged, S5 at X_a = 0, lies 0.12 b upstream of its spike: a limit cycle). More patch sweeps instead (4 + 3) did
# not help; damping every level's relaxation (0.15/0.1) kept it bounded but flickering at 5e-4 per cycle.
COARSE_CYCLES = 3


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


class PatchedSolver(MultigridSolver):
    """FAS multigrid on a uniform hierarchy plus a patch twice as fine along X over `span` (X_a, X_b) of its finest
    grid: the patch is the last level (`levels[-1]`)."""

    def __init__(self, problem: Problem, shapes: list[tuple[int, int]], span: tuple[float, float],
                 relaxation: Relaxation = Relaxation(), coarse_cycles: int = COARSE_CYCLES):
        """`shapes`: (nx, ny) of the uniform levels, coarsest first (grid.hierarchy_shapes); `coarse_cycles`: V-cycles
        of the uniform hierarchy per coarse-grid correction of the patch."""
        super().__init__(problem, shapes, relaxation)
        self.patch_coarse_cycles = coarse_cycles
        self._add_patch(span)

    @classmethod
    def over(cls, solver: MultigridSolver, span: tuple[float, float],
             coarse_cycles: int = COARSE_CYCLES) -> PatchedSolver:
        """A patch over `span` on top of a solved uniform hierarchy: its levels (the same objects, which the
        composite cycles go on changing), H_0 and work count are taken over."""
        patched = cls.__new__(cls)
        patched.__dict__.update(solver.__dict__)
        patched.patch_coarse_cycles = coarse_cycles
        patched.levels, patched.transfers = list(solver.levels), list(solver.transfers)
        patched._add_patch(span)
        patched.finest_nodes = solver.finest_nodes  # work units stay in sweeps of the uniform grid solved before
        return patched

    def _add_patch(self, span: tuple[float, float]) -> None:
        below, problem = self.levels[-1], self.problem
        self.first, self.last = patch_columns(below.x, span)
        self.columns = slice(2 * self.first, 2 * self.last + 1)  # the patch's columns on the grid of its spacing
        nx = 2 * below.nx - 1
        # The level of the patch spacing over the whole domain: its deflection operator (the composite W), relaxation
        # patterns and switch are the patch's; its arrays are cut to the patch.
        patch = self._make_level(nx, below.ny)
        patch.x = patch.x[self.columns].copy()
        patch.pressure = patch.pressure[:, self.columns].copy()
        patch.film_rhs = patch.film_rhs[:, self.columns].copy()
        patch.reynolds_rhs = patch.reynolds_rhs[:, self.columns].copy()
        self.levels.append(patch)
        self.transfers.append(grid.SEMI_X)
        self.finest_nodes = nx * below.ny
        self.local = DeflectionOperator(patch.nx, patch.ny, patch.hx, patch.hy, problem.ellipticity)
        self._outside: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None  # see _interpolated_below

    @property
    def patch(self) -> Level:
        return self.levels[-1]

    @property
    def below(self) -> Level:
        """The finest uniform grid, under the patch."""
        return self.levels[-2]

    def set_patch_state(self, temperature: np.ndarray, viscosity_factor: np.ndarray) -> None:
        """Freeze an across-film state (nz, ny, patch columns) on the patch alone (the grids below keep theirs) and
        recompute its film and flow coefficients."""
        patch = self.patch
        patch.temperature = np.ascontiguousarray(temperature)
        patch.viscosity_factor = np.ascontiguousarray(viscosity_factor)
        patch.temperature_factor = flow.temperature_factors(patch.temperature, self.problem.law)
        self.update_film(patch)

    def _is_patch(self, index: int) -> bool:
        return index == len(self.levels) - 1

    # ------------------------------------------------------------ composite
    def composite_integral(self) -> float:
        """\\iint P dX dY of the composite pressure: the grid below outside the patch, the patch inside."""
        below, patch = self.below, self.patch
        inside = below.pressure[:, self.first:self.last + 1]
        return below.load_integral() - trapezoid(inside, below.hx, below.hy) + trapezoid(patch.pressure, patch.hx,
                                                                                           patch.hy)

    def summary(self) -> CompositeSummary:
        """h_c (bilinear at X = Y = 0 on the part that holds it), h_min and p_max over both parts."""
        below, patch = self.below, self.patch
        holder = patch if patch.x[0] <= 0.0 <= patch.x[-1] else below
        outside = np.ones(below.nx, dtype=bool)
        outside[self.first:self.last + 1] = False
        parts = [(patch.x, patch.pressure, patch.film), (below.x[outside], below.pressure[:, outside],
                                                         below.film[:, outside])]
        x, pressure, film = max(parts, key=lambda part: part[1].max() if part[1].size else -np.inf)
        j, i = np.unravel_index(int(np.argmax(pressure)), pressure.shape)
        return CompositeSummary(
            h_c=grid.bilinear_at(holder.film, holder.x, holder.y, 0.0, 0.0),
            h_min=min(float(film.min()) for _, _, film in parts if film.size),
            p_max=float(pressure[j, i]),
            x_p_max=float(x[i]),
        )

    # ---------------------------------------------------- the patch's level
    def _interpolated_below(self) -> tuple[np.ndarray, np.ndarray]:
        """The grid below's pressure interpolated to the patch spacing over the patch (P_I) and its deflection at the
        patch's nodes (K*P_I over the whole domain, without C_d), kept while that pressure does not change."""
        below = self.below.pressure
        if self._outside is None or not np.array_equal(self._outside[0], below):
            interpolated = np.maximum(grid.SEMI_X.prolong_cubic(below), 0.0)
            w = self.patch.deflection.apply(interpolated)[:, self.columns]
            self._outside = (below.copy(), interpolated[:, self.columns].copy(), w)
        return self._outside[1], self._outside[2]

    def deflection(self, level: Level) -> np.ndarray:
        """The patch: the deflection of the composite pressure at its nodes; other levels: their own.

        By linearity K*P = K*P_I + K*(P_f - P_I) over the patch, P_I the grid below interpolated (_interpolated_below):
        the domain-sized convolution changes only with the grid below, a patch sweep pays a patch-sized one."""
        if level is not self.patch:
            return super().deflection(level)
        interpolated, w = self._interpolated_below()
        return w + self.local.apply(level.pressure - interpolated)

    def force_error(self, level: Level) -> float:
        """The patch: the load error of the composite pressure."""
        if level is not self.patch:
            return super().force_error(level)
        return self.composite_integral() + level.force_rhs

    def coarse_cycles(self, index: int) -> int:
        """`patch_coarse_cycles` (default COARSE_CYCLES) under the patch, one elsewhere."""
        return self.patch_coarse_cycles if self._is_patch(index) else 1

    def coarsen(self, index: int) -> None:
        """From the patch to the grid below: FAS right-hand sides at the patch's interior coarse columns, the
        grid's own ones outside, the composite load in its force balance."""
        if not self._is_patch(index):
            return super().coarsen(index)
        patch, below = self.patch, self.below
        inner = slice(self.first + 1, self.last)
        below.pressure[:, inner] = grid.restrict_pressure_x(patch.pressure)[:, 1:-1]
        below.pressure_restricted = below.pressure.copy()
        self.reset_rhs(below)
        w = below.deflection.apply(below.pressure)
        film = grid.inject_x(patch.film)[:, 1:-1]
        below.film_rhs[:, inner] = film - self.h0 - self.problem.deflection_coefficient * w[:, inner]
        self.update_film(below)
        tau = grid.restrict_full_weighting_x(self.residual(patch)) + self.operator(below)[:, self.first:self.last + 1]
        below.reynolds_rhs[:, inner] = tau[:, 1:-1]
        below.force_rhs = patch.force_rhs + self.composite_integral() - below.load_integral()
        return None

    def refine(self, index: int) -> None:
        """The grid below's correction, interpolated linearly, where the patch's pressure is positive; its end
        columns take the grid below's values."""
        if not self._is_patch(index):
            return super().refine(index)
        patch, below = self.patch, self.below
        columns = slice(self.first, self.last + 1)
        correction = grid.prolong_linear_x((below.pressure - below.pressure_restricted)[:, columns])
        active = patch.pressure > 0.0
        patch.pressure[active] += correction[active]
        np.maximum(patch.pressure, 0.0, out=patch.pressure)
        patch.pressure[:, 0] = below.pressure[:, self.first]
        patch.pressure[:, -1] = below.pressure[:, self.last]
        self.update_film(patch)
        return None

    def interpolate_up(self, index: int) -> None:
        """Start the patch from the fourth-order interpolation along X of the grid below."""
        if not self._is_patch(index):
            return super().interpolate_up(index)
        patch = self.patch
        self.reset_rhs(patch)
        patch.pressure = np.maximum(grid.SEMI_X.prolong_cubic(self.below.pressure)[:, self.columns], 0.0)
        self.update_film(patch)
        return None
