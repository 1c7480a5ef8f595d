"""FAS multigrid for the EHL point contact: V-cycles, full-multigrid start, load balance, work units.

Algorithm of Venner & Lubrecht (2000, ch. 8), written for any ellipticity and entrainment direction:
- Unknowns per level: pressure P; film H = H_0 + C_d K*P + F_h, where F_h is the film right-hand side
  (the gap geometry on the finest grid; on coarse grids the FAS term that makes H(I P) = I H).
- Coarse-grid correction (FAS): P_c = I P, f_c = I (f - L P) + L_c P_c, F_c = I H - H_0 - C_d K_c*P_c,
  force balance g_c = g_h + \\iint P_h - \\iint P_c; then P += I(P_c - I P) where P > 0 (near the solution, where
  no neighbour is cavitated: `corrected_nodes`).
- The force balance \\iint P dX dY = 2 pi/3 fixes H_0; it is relaxed on the coarsest grid
  (H_0 += c_h g), where its FAS right-hand side carries the fine-grid information.
- Work unit: one relaxation sweep on the finest grid; a sweep on a grid with n nodes costs n/n_finest.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
import math

import numpy as np

from facegear_tehl.ehl import flow, grid, reynolds
from facegear_tehl.ehl.elastic import DeflectionOperator
from facegear_tehl.ehl.relaxation import Relaxation

CIRCLE_SELF_COEFFICIENT = 8.0 * math.asinh(1.0) / math.pi**2  # C_d K_00/h for a circle on square cells


@dataclass(frozen=True)
class Problem:
    """The dimensionless problem on a rectangular domain (see scaling.py)."""

    lam: float  # lambda
    deflection_coefficient: float  # C_d
    ellipticity: float  # k = a/b
    geometry_y: float  # k^2 R_x/R_y
    wedge_x: float  # cos psi
    wedge_y: float  # kappa sin psi
    p_hertz: float  # Pa, to evaluate the lubricant laws
    law: np.ndarray  # lubricant law parameters (lubricant.Lubricant.law_parameters)
    inlet_temperature: float  # K
    velocity_1: np.ndarray  # surface velocity of body 1 / |u_e|, (x, y)
    velocity_2: np.ndarray  # surface velocity of body 2 / |u_e|, (x, y)
    domain_x: tuple[float, float]
    domain_y: tuple[float, float]
    load_integral: float = 2.0 * math.pi / 3.0


def corrected_nodes(pressure: np.ndarray) -> np.ndarray:
    """The nodes that take the coarse-grid correction near the solution: pressurised (P > 0) and none of their four
    neighbours cavitated (an interior node at P = 0; the domain's boundary nodes, zero by the boundary condition, do
    not count). The coarse grid sees the cavitation boundary smeared over its own cells: added at the last pressurised
    nodes, its correction flipped the boundary by one node every V-cycle, a period-2 limit cycle that held the
    pressure change at its "algebraic floor" (measured in docs/tuning.md, "Pressure cycles and algebraic floors").
    This follows the truncated coarse-grid corrections of multigrid for obstacle problems (Kornhuber 1994, Numer. Math.
    69:167-184): a node next to the contact set is left to the relaxation. The discrete solution is unchanged (the
    correction vanishes at convergence). Far from the solution the truncated correction can run away where the
    pressurised zone is a few nodes wide (the circle at M = 20, L = 10 on 513 x 33 from its full-multigrid start):
    PressureIteration.cycle truncates from a stall below TUNING.truncation_band on (pressure.py)."""
    wet = pressure > 0.0
    dry = ~wet
    dry[0, :] = dry[-1, :] = False
    dry[:, 0] = dry[:, -1] = False
    near = dry.copy()
    near[:, 1:] |= dry[:, :-1]
    near[:, :-1] |= dry[:, 1:]
    near[1:, :] |= dry[:-1, :]
    near[:-1, :] |= dry[1:, :]
    return wet & ~near


def at_load_fraction(problem: Problem, fraction: float) -> Problem:
    """The same contact carrying `fraction` of its load, in the Hertzian units of the full load's grid.

    With W -> f W at fixed radii p_h and b scale as f^(1/3) (Hertz; Johnson 1985, §4.2), so lambda =
    12 eta_0 u_e R_x^2/(p_h b^3) scales as f^(-4/3) and the lubricant laws see p_h f^(1/3); C_d = 2 p_h a R_x/(pi E'
    b^2), the ellipticity and the gap geometry do not change. The domain keeps its extent in semi-axes."""
    if fraction == 1.0:
        return problem
    return replace(problem, lam=problem.lam * fraction ** (-4.0 / 3.0),
                   p_hertz=problem.p_hertz * fraction ** (1.0 / 3.0))


@dataclass(frozen=True)
class Iterate:
    """A saved pressure iterate of one grid and the film constant H_0 that goes with it."""

    pressure: np.ndarray
    h0: float


@dataclass
class Level:
    """One grid of the hierarchy with its state (mutable solver state, not passed between stages)."""

    x: np.ndarray
    y: np.ndarray
    deflection: DeflectionOperator
    pattern_gs: np.ndarray
    pattern_jd: np.ndarray
    pattern_gs_t: np.ndarray  # the same for Y-line relaxation (transposed problem)
    pattern_jd_t: np.ndarray
    weight_x: float
    weight_y: float
    switch_scale: float  # the factor of the ellipse-scaled Gauss-Seidel / Jacobi-distributive switch on this grid
    pressure: np.ndarray
    film_rhs: np.ndarray
    reynolds_rhs: np.ndarray
    force_rhs: float = 0.0
    film: np.ndarray = field(default=None)
    eps: np.ndarray = field(default=None)
    flux_x: np.ndarray = field(default=None)  # Couette factors f_x, f_y (flow.py)
    flux_y: np.ndarray = field(default=None)
    pressure_restricted: np.ndarray = field(default=None)
    # Frozen across-film state of the thermal / non-Newtonian model, shape (nz, ny, nx) (temperature and its factor
    # (1, ny, nx) for a state of one temperature per column: set_film_state); None: isothermal Newtonian film at the
    # inlet temperature.
    temperature: np.ndarray | None = None
    viscosity_factor: np.ndarray | None = None
    temperature_factor: np.ndarray | None = None  # flow.temperature_factors of `temperature`, set with it
    frozen: np.ndarray | None = None  # flow.frozen_shapes of a layered state, set with it (None: isothermal)
    # A state whose layers share one temperature per column (an isothermal Ree-Eyring film): flow.column_integrals of
    # its viscosity_factor, (2, ny, nx); None: the layered coefficients
    column_shapes: np.ndarray | None = None
    deflected: tuple[np.ndarray, np.ndarray] | None = None  # (P, K*P) of its last deflection (MultigridSolver)

    @property
    def nx(self) -> int:
        return self.x.size

    @property
    def ny(self) -> int:
        return self.y.size

    @property
    def hx(self) -> float:
        return float(self.x[1] - self.x[0])

    @property
    def hy(self) -> float:
        return float(self.y[1] - self.y[0])

    @property
    def nodes(self) -> int:
        return self.x.size * self.y.size

    def load_integral(self) -> float:
        return float(self.pressure.sum()) * self.hx * self.hy


class MultigridSolver:
    """FAS multigrid solver of one dimensionless EHL problem on a hierarchy of nested grids."""

    def __init__(self, problem: Problem, shapes: list[tuple[int, int]], relaxation: Relaxation = Relaxation()):
        """`shapes`: (nx, ny) of each grid, coarsest first (grid.hierarchy_shapes)."""
        self.problem = problem
        self.relaxation = relaxation
        self.levels: list[Level] = [self._make_level(nx, ny) for nx, ny in shapes]
        # transfers[i]: between levels i - 1 and i (transfers[0] unused)
        self.transfers = [grid.STANDARD] + [grid.transfer(fine, coarse) for coarse, fine in zip(shapes, shapes[1:])]
        self.h0 = 0.0
        self.last_h0_step = 0.0  # H_0 change of the last coarsest-grid solve
        self.work_units = 0.0
        self.truncated = False  # the coarse-grid corrections skip the nodes next to cavitation (corrected_nodes)
        self.finest_nodes = self.levels[-1].nodes

    # ----------------------------------------------------------------- set-up
    def _make_level(self, nx: int, ny: int) -> Level:
        pb = self.problem
        x = np.linspace(pb.domain_x[0], pb.domain_x[1], nx)
        y = np.linspace(pb.domain_y[0], pb.domain_y[1], ny)
        hx, hy = x[1] - x[0], y[1] - y[0]
        deflection = DeflectionOperator(nx, ny, hx, hy, pb.ellipticity)
        # Jacobi-distributive weights of a physical Laplacian (reynolds.py).
        cx, cy = 1.0 / hx**2, 1.0 / (pb.ellipticity * hy) ** 2
        wx, wy = 0.5 * cx / (cx + cy), 0.5 * cy / (cx + cy)
        e_gs, e_jd = reynolds.pattern_kernels(deflection.coefficients, pb.deflection_coefficient, wx, wy)
        e_gs_t, e_jd_t = reynolds.pattern_kernels(deflection.coefficients.T, pb.deflection_coefficient, wy, wx)
        # Venner's switch eps/h^2 > 0.3 is set for a circle, where the elastic self-coefficient C_d K_00/h_x is
        # (2/pi^2) 4 asinh(1); a long ellipse has a larger one (2.3-2.6x for the face gear contacts) and its line
        # Gauss-Seidel goes unstable where the circle's would not (seen at 513^2): the switch is scaled by the
        # fourth power of that ratio (1 for a circle; 30-45 for the face gear points, where 3 still diverged at
        # 513^2 and 10 converged: an empirical calibration). Cells longer along Y than along X (h_y > h_x, a grid
        # refined along X) scale it again by (h_y/h_x)^2: their line Gauss-Seidel, which leaves the elastic
        # coupling to the other lines and beyond the band to the next sweep, diverged on the 513 x 129 face gear
        # grid (h_y = 4 h_x) with switches up to 30 and converged from 100 to 3000 (here 490).
        elastic_ratio = pb.deflection_coefficient * deflection.coefficients[0, 0] / hx / CIRCLE_SELF_COEFFICIENT
        scale = elastic_ratio**4 * max(hy / hx, 1.0) ** 2
        xx, yy = np.meshgrid(x, y)
        return Level(
            x=x,
            y=y,
            deflection=deflection,
            pattern_gs=e_gs,
            pattern_jd=e_jd,
            pattern_gs_t=e_gs_t,
            pattern_jd_t=e_jd_t,
            weight_x=wx,
            weight_y=wy,
            switch_scale=scale,
            pressure=np.zeros((ny, nx)),
            film_rhs=0.5 * xx**2 + 0.5 * pb.geometry_y * yy**2,
            reynolds_rhs=np.zeros((ny, nx)),
        )

    def start_from_hertz(self, central_film: float) -> None:
        """Coarsest grid: the Hertz pressure P = sqrt(1 - X^2 - Y^2) (zero on the boundary), with H_0 such that
        the film at the centre is `central_film` (dimensionless)."""
        level = self.levels[0]
        self.reset_rhs(level)
        xx, yy = np.meshgrid(level.x, level.y)
        level.pressure = np.sqrt(np.maximum(1.0 - xx**2 - yy**2, 0.0))
        level.pressure[0, :] = level.pressure[-1, :] = 0.0
        level.pressure[:, 0] = level.pressure[:, -1] = 0.0
        self.h0 = 0.0
        self.update_film(level)
        self.h0 = central_film - self.central_film(level)
        self.update_film(level)

    def snapshot(self, index: int) -> Iterate:
        """A copy of the pressure of level `index` and H_0."""
        return Iterate(self.levels[index].pressure.copy(), self.h0)

    def restore(self, index: int, iterate: Iterate) -> None:
        """Make level `index` the finest grid again with a saved iterate: its original right-hand sides
        (a coarser level's were overwritten by the FAS cycles of the finer ones), the pressure and H_0."""
        level = self.levels[index]
        self.reset_rhs(level)
        level.pressure = iterate.pressure.copy()
        self.h0 = iterate.h0
        self.update_film(level)

    def set_film_state(self, index: int, temperature: np.ndarray | None,
                       viscosity_factor: np.ndarray | None) -> None:
        """Freeze the across-film state (nz, ny, nx) of level `index` on it and, injected, on every coarser
        grid, and recompute the film and flow coefficients of level `index`; None: the isothermal Newtonian
        film at the inlet temperature. The temperature factor is evaluated node by node on level `index` once and
        injected like the state (the same numbers as evaluating it on each grid). A state with one temperature per
        column (every layer at the first layer's: an isothermal Ree-Eyring film) carries its columns' Eyring shapes
        (flow.column_integrals) on each grid instead, for flow.isothermal_layered_coefficients; any other state its
        columns' integrals at the pressure of level `index` (flow.frozen_shapes), injected (the same numbers as
        freezing each grid at its injected pressure: on S1's thermal loop 11 -> 5.4 ms per update), for
        flow.frozen_layered_coefficients. An isothermal state keeps its first layer of temperature and temperature
        factor alone (the other eight of 513 x 65 x 9 cost 0.8 of the 3.8 ms a call took)."""
        top = self.levels[index]
        isothermal = temperature is not None and bool((temperature == temperature[0]).all())
        if isothermal:  # its first layer stands for all (flow.isothermal_layered_coefficients reads no other)
            temperature = temperature[:1]
        factor = None if temperature is None else flow.temperature_factors(temperature, self.problem.law)
        # the frozen shapes are column by column: a coarser grid's are the finest's at its nodes, injected
        frozen = None if temperature is None or isothermal else flow.frozen_shapes(
            np.ascontiguousarray(top.pressure) * self.problem.p_hertz, np.ascontiguousarray(temperature), factor,
            np.ascontiguousarray(viscosity_factor), self.problem.law)
        for level in self.levels[:index + 1]:
            level.column_shapes = level.frozen = None
            if temperature is None:
                level.temperature = level.viscosity_factor = level.temperature_factor = None
                continue
            sx, sy = (top.nx - 1) // (level.nx - 1), (top.ny - 1) // (level.ny - 1)
            level.temperature = np.ascontiguousarray(temperature[:, ::sy, ::sx])
            level.viscosity_factor = np.ascontiguousarray(viscosity_factor[:, ::sy, ::sx])
            level.temperature_factor = np.ascontiguousarray(factor[:, ::sy, ::sx])
            if isothermal:
                level.column_shapes = flow.column_integrals(level.viscosity_factor)
            else:
                level.frozen = np.ascontiguousarray(frozen[:, ::sy, ::sx])
        self.update_film(top)

    def freeze(self, level: Level, pressure: np.ndarray) -> None:
        """The flow shapes of the layered film state of `level` frozen at `pressure` (dimensionless, on its nodes)."""
        level.frozen = flow.frozen_shapes(np.ascontiguousarray(pressure) * self.problem.p_hertz, level.temperature,
                                          level.temperature_factor, level.viscosity_factor, self.problem.law)

    def prolong_layers(self, index: int, layers: np.ndarray) -> np.ndarray:
        """Each layer of `layers` (nz, ny, nx) on level `index - 1` interpolated to level `index`."""
        return np.stack([self.transfers[index].prolong(layer) for layer in layers])

    def central_film(self, level: Level) -> float:
        """The film H at the contact centre X = Y = 0 (bilinear between the nodes)."""
        return grid.bilinear_at(level.film, level.x, level.y, 0.0, 0.0)

    def reset_rhs(self, level: Level) -> None:
        """The original (finest-grid) right-hand sides: gap geometry, f = 0, target load."""
        xx, yy = np.meshgrid(level.x, level.y)
        level.film_rhs = 0.5 * xx**2 + 0.5 * self.problem.geometry_y * yy**2
        level.reynolds_rhs = np.zeros_like(level.pressure)
        level.force_rhs = -self.problem.load_integral

    # ---------------------------------------------------------- single grid
    def update_film(self, level: Level) -> None:
        """H = H_0 + C_d K*P + F; then the flow coefficients eps, f_x, f_y (flow.py)."""
        pb = self.problem
        w = self.deflection(level)
        level.film = self.h0 + pb.deflection_coefficient * w + level.film_rhs
        if level.eps is None:
            level.eps = np.empty_like(level.film)
            level.flux_x = np.empty_like(level.film)
            level.flux_y = np.empty_like(level.film)
        p_pa = level.pressure * pb.p_hertz
        if level.temperature is None:
            flow.isothermal_coefficients(p_pa, level.film, pb.law, pb.inlet_temperature, pb.lam, pb.wedge_x,
                                         pb.wedge_y, level.eps, level.flux_x, level.flux_y)
        elif level.column_shapes is not None:
            flow.isothermal_layered_coefficients(p_pa, level.film, level.temperature[0], level.temperature_factor[0],
                                                 level.column_shapes, pb.law, pb.lam, 1.0 / pb.ellipticity,
                                                 float(np.sign(pb.wedge_x)), float(np.sign(pb.wedge_y)),
                                                 pb.velocity_1, pb.velocity_2, level.eps, level.flux_x, level.flux_y)
        else:
            flow.frozen_layered_coefficients(p_pa, level.film, level.frozen, level.temperature,
                                             level.temperature_factor, level.viscosity_factor, pb.law, pb.lam,
                                             1.0 / pb.ellipticity, float(np.sign(pb.wedge_x)),
                                             float(np.sign(pb.wedge_y)), pb.velocity_1, pb.velocity_2, level.eps,
                                             level.flux_x, level.flux_y)

    def deflection(self, level: Level) -> np.ndarray:
        """W = K*P at the nodes of `level` (without C_d): its own pressure on its own grid, kept with the pressure it
        is of (`Level.deflected`): the film is formed again on an unchanged pressure when H_0 or the right-hand side
        moved (the coarsest grid's force balance, a FAS restriction); comparing the pressures costs 1-2 % of a
        transform's convolution (about 1 of the 8 us of the coarsest grid's dense one). (Read-only: the same array is
        returned until the pressure changes.)"""
        if level.deflected is not None and np.array_equal(level.deflected[0], level.pressure):
            return level.deflected[1]
        w = level.deflection.apply(level.pressure)
        level.deflected = (level.pressure.copy(), w)
        return w

    def _args(self, level: Level):
        pb = self.problem
        return level.hx, level.hy, 1.0, 1.0 / pb.ellipticity**2, int(np.sign(pb.wedge_x)), int(np.sign(pb.wedge_y))

    def _fluxes(self, level: Level):
        return level.flux_x * level.film, level.flux_y * level.film

    def switch(self, level: Level) -> float:
        """The Gauss-Seidel / Jacobi-distributive switch on `level` under the current relaxation: Venner's eps/h^2,
        times the level's ellipse and cell-aspect factor (`switch_scale`) where the relaxation scales it."""
        rx = self.relaxation
        return rx.xi_switch * level.switch_scale if rx.scale_switch else rx.xi_switch

    def relax(self, level: Level) -> float:
        """One sweep of X-line relaxation (plus one of Y-line relaxation when the entrainment is skewed),
        then the film; returns the mean absolute pressure change."""
        rx = self.relaxation
        hx, hy, px, py, sx, sy = self._args(level)
        qx, qy = self._fluxes(level)
        change = reynolds.relax_lines(
            level.pressure, qx, qy, level.flux_x, level.flux_y, level.eps, level.reynolds_rhs,
            hx, hy, px, py, sx, sy,
            level.pattern_gs, level.pattern_jd, level.weight_x, level.weight_y,
            self.switch(level), rx.under_gs, rx.under_jd,
        )
        self.work_units += level.nodes / self.finest_nodes
        self.update_film(level)
        if abs(self.problem.wedge_y) > rx.alternate_above * abs(self.problem.wedge_x):
            # Y-lines: the same kernel on the transposed problem (axes, factors and patterns swapped).
            qx, qy = self._fluxes(level)
            t = np.ascontiguousarray
            pressure_t = t(level.pressure.T)
            change += reynolds.relax_lines(
                pressure_t, t(qy.T), t(qx.T), t(level.flux_y.T), t(level.flux_x.T), t(level.eps.T),
                t(level.reynolds_rhs.T), hy, hx, py, px, sy, sx,
                level.pattern_gs_t, level.pattern_jd_t, level.weight_y, level.weight_x,
                self.switch(level), rx.under_gs, rx.under_jd,
            )
            level.pressure = t(pressure_t.T)
            self.work_units += level.nodes / self.finest_nodes
            self.update_film(level)
        return change / level.nodes

    def residual(self, level: Level) -> np.ndarray:
        out = np.empty_like(level.pressure)
        reynolds.residual(level.pressure, *self._fluxes(level), level.eps, level.reynolds_rhs, *self._args(level), out)
        return out

    def operator(self, level: Level) -> np.ndarray:
        out = np.empty_like(level.pressure)
        reynolds.apply_operator(level.pressure, *self._fluxes(level), level.eps, *self._args(level), out)
        return out

    def pressure_change(self, level: Level, previous: np.ndarray) -> float:
        """The relative L1 change \\sum |P - P_previous| / \\sum |P| of level `level` from `previous`."""
        return float(np.abs(level.pressure - previous).sum() / max(np.abs(level.pressure).sum(), 1e-300))

    def force_error(self, level: Level) -> float:
        """g = \\iint P dX dY + force_rhs (zero when the load balance holds)."""
        return level.load_integral() + level.force_rhs

    def solve_coarsest(self, level: Level) -> None:
        """Relax the coarsest grid and its force balance together.

        The sweeps come in `force_updates` groups; after each group H_0 moves to the root of the load error
        g(H_0), by the secant through the last two (H_0, g) pairs once the slope has the physical sign
        (dg/dH_0 < 0), else by H_0 += c_h g.
        """
        rx = self.relaxation
        sweeps = max(rx.coarsest_sweeps // rx.force_updates, 1)
        h0_start = self.h0
        previous = None
        for _ in range(rx.force_updates):
            for _ in range(sweeps):
                self.relax(level)
            g = self.force_error(level)
            step = rx.force_factor * g
            if previous is not None:
                h_prev, g_prev = previous
                if self.h0 != h_prev:
                    slope = (g - g_prev) / (self.h0 - h_prev)
                    if slope < 0.0:
                        limit = 4.0 * abs(rx.force_factor * g)
                        step = min(max(-rx.force_damping * g / slope, -limit), limit)
            previous = (self.h0, g)
            self.h0 += step
            self.update_film(level)
        total = self.h0 - h0_start
        if total * self.last_h0_step < 0.0:
            # The step reverses the previous cycle's: damp the period-2 mode that noise on the free boundary
            # excites through the FAS right-hand side of the force balance.
            self.h0 = h0_start + 0.5 * total
            self.update_film(level)
        self.last_h0_step = self.h0 - h0_start

    # ------------------------------------------------------------ multigrid
    def coarsen(self, index: int) -> None:
        """FAS restriction from level `index` to `index - 1`."""
        fine, coarse, transfer = self.levels[index], self.levels[index - 1], self.transfers[index]
        coarse.pressure = transfer.restrict_pressure(fine.pressure)
        coarse.pressure_restricted = coarse.pressure.copy()
        w = self.deflection(coarse)
        coarse.film_rhs = transfer.inject(fine.film) - self.h0 - self.problem.deflection_coefficient * w
        self.update_film(coarse)
        coarse.reynolds_rhs = transfer.restrict(self.residual(fine)) + self.operator(coarse)
        coarse.force_rhs = fine.force_rhs + fine.load_integral() - coarse.load_integral()

    def refine(self, index: int) -> None:
        """Add the interpolated coarse-grid correction where the fine pressure is positive (`truncated`: at the
        nodes `corrected_nodes` picks)."""
        fine, coarse = self.levels[index], self.levels[index - 1]
        correction = self.transfers[index].prolong(coarse.pressure - coarse.pressure_restricted)
        active = corrected_nodes(fine.pressure) if self.truncated else fine.pressure > 0.0
        fine.pressure[active] += correction[active]
        np.maximum(fine.pressure, 0.0, out=fine.pressure)
        self.update_film(fine)

    def cycle(self, index: int) -> None:
        """One V-cycle starting on level `index` (index 0: the coarsest grid, relaxed to convergence)."""
        rx = self.relaxation
        level = self.levels[index]
        if index == 0:
            self.solve_coarsest(level)
            return
        for _ in range(rx.pre_sweeps):
            self.relax(level)
        self.coarsen(index)
        for _ in range(self.coarse_cycles(index)):
            self.cycle(index - 1)
        self.refine(index)
        for _ in range(rx.post_sweeps):
            self.relax(level)

    def coarse_cycles(self, index: int) -> int:
        """V-cycles on level `index - 1` per coarse-grid correction of level `index` (a V-cycle: one)."""
        return 1

    def interpolate_up(self, index: int) -> None:
        """Full-multigrid step: start level `index` from the bicubic interpolation of level `index - 1`."""
        fine, coarse = self.levels[index], self.levels[index - 1]
        self.reset_rhs(fine)
        fine.pressure = np.maximum(self.transfers[index].prolong_cubic(coarse.pressure), 0.0)
        fine.pressure[0, :] = fine.pressure[-1, :] = 0.0
        fine.pressure[:, 0] = fine.pressure[:, -1] = 0.0
        self.update_film(fine)
