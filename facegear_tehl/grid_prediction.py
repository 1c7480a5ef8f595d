"""The grid the accuracy target predicts for a point (accuracy_target.py) from the error estimates of a solve.

A figure's bound on the solved nx x ny grid is B = F_s (|e_x| + |e_y|) + e_it (ehl/error_bounds.py: F_s =
TUNING.bound_safety, e_x and e_y the Richardson estimates along x and y, e_it the iteration error). Under the additive
error model f = f* + C_x h_x^p + C_y h_y^p (Roache 1998, "Verification and Validation in Computational Science and
Engineering", ch. 5) each estimate falls as h^p, so kx doublings along x and ky along y give

    B(kx, ky) = F_s (|e_x| 2^(-p kx) + |e_y| 2^(-p ky)) + e_it + m,

m the cheaper model's measured effect (it does not fall with the grid). p along an axis is the order at which the
figure's estimate along it was measured to fall over the point's last refinement along that axis
(accuracy_target.measured_orders), at most 2, the order of the discretisation (ehl/richardson.ORDER); before any
such refinement it is 2, for every figure, also for dT_max and mu, whose bounds assume the first order (ehl/report.py:
their observed order is 0.7-1.7): an error that falls no faster than h^2 is not within the target before the
predicted grid, so the plan never passes the first grid that can meet it. The predicted grid is the one of fewest
nodes within TUNING.accuracy_max_grid x accuracy_max_grid_y whose B of every figure is within
TUNING.accuracy_jump_margin of the target (else within the target); on a square grid (its e_x covers both axes,
e_y = 0) both axes are refined together.
A figure whose B stays above the target even on the finest grid within the caps is not refined for (`reachable`). A
prediction is never a verdict: a figure is met only by the bound of its own solve on the grid reached.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
import itertools
import math

from facegear_tehl.ehl.tuning import TUNING


@dataclass(frozen=True)
class Estimate:
    """One figure's bound on the solved grid (relative), its estimates along x and y, the orders they are planned to
    fall at along each axis and the cheaper model's measured effect (relative)."""

    bound: float
    e_x: float
    e_y: float
    order_x: float
    order_y: float
    model: float = 0.0

    def predicted(self, kx: int, ky: int) -> float:
        """B(kx, ky) of the module docstring, each estimate falling at its own axis's order; e_it is the part of the
        bound the estimates do not explain."""
        safety, e_x, e_y = TUNING.bound_safety, abs(self.e_x), abs(self.e_y)
        iteration = max(self.bound - safety * (e_x + e_y), 0.0)
        return (safety * (e_x * 2.0 ** (-self.order_x * kx) + e_y * 2.0 ** (-self.order_y * ky)) + iteration
                + self.model)

    @property
    def predictable(self) -> bool:
        return all(math.isfinite(v) for v in (self.bound, self.e_x, self.e_y))


def doubled(nodes: int, times: int) -> int:
    """Nodes of a grid `times` times twice as fine as one of `nodes` nodes."""
    return (nodes - 1) * 2**times + 1


def doublings(nodes: int, cap: int) -> int:
    """How many times a grid of `nodes` can be made twice as fine within `cap` nodes."""
    times = 0
    while doubled(nodes, times + 1) <= cap:
        times += 1
    return times


@dataclass(frozen=True)
class Prediction:
    """A grid (nx, ny) and each figure's predicted bound there."""

    grid: int
    grid_y: int
    bounds: dict[str, float]

    def words(self) -> str:
        figures = ", ".join(f"{name} {100 * b:.2g} %" for name, b in self.bounds.items())
        return f"{self.grid} x {self.grid_y} predicted to bound {figures}"


def candidates(grid: int, grid_y: int) -> list[tuple[int, int]]:
    """(kx, ky) of every finer grid within the caps, fewest nodes first (then fewer doublings along y); both alike
    on a square grid."""
    kx_max, ky_max = doublings(grid, TUNING.accuracy_max_grid), doublings(grid_y, TUNING.accuracy_max_grid_y)
    pairs = itertools.product(range(kx_max + 1), range(ky_max + 1))
    finer = [(kx, ky) for kx, ky in pairs if (kx, ky) != (0, 0) and (grid != grid_y or kx == ky)]
    return sorted(finer, key=lambda k: (doubled(grid, k[0]) * doubled(grid_y, k[1]), k[1]))


def reachable(grid: int, grid_y: int, estimates: Mapping[str, Estimate], target: float) -> dict[str, Estimate]:
    """The figures predicted within `target` on the finest grid within the caps (the others cannot be met by
    refining: refining for them would cost without a verdict)."""
    finest = max(candidates(grid, grid_y), key=lambda k: doubled(grid, k[0]) * doubled(grid_y, k[1]), default=(0, 0))
    return {name: e for name, e in estimates.items() if e.predicted(*finest) <= target}


def predicted_grid(grid: int, grid_y: int, estimates: Mapping[str, Estimate], target: float) -> Prediction | None:
    """The grid of fewest nodes predicted to bring every figure of `estimates` (each predictable) within
    TUNING.accuracy_jump_margin of `target`, else within `target` (module docstring); None where none is."""
    for within in (TUNING.accuracy_jump_margin * target, target):
        for kx, ky in candidates(grid, grid_y):
            bounds = {name: e.predicted(kx, ky) for name, e in estimates.items()}
            if max(bounds.values(), default=0.0) <= within:
                return Prediction(doubled(grid, kx), doubled(grid_y, ky), bounds)
    return None
