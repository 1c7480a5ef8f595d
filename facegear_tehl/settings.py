"""Numerical settings of the EHL solver and output settings of a case: plain data with their defaults.

The defaults here are the only ones: the case parser (`case.py`) reads an absent key as the field's default.
This module imports nothing of the package, so the solver loads it without the gear geometry.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum


class ThermalMode(str, Enum):
    """The thermal model of a solve (`solver.thermal`): isothermal, reduced (one temperature per column from the
    isothermal film), full (layered energy equation coupled with the pressure), or chosen per point (auto). A str
    enum: it reads and writes as its word."""

    OFF = "off"
    REDUCED = "reduced"
    FULL = "full"
    AUTO = "auto"

    def __str__(self) -> str:
        return self.value


class OutletRefinement(str, Enum):
    """When a `full` thermal solve refines its outlet on patches (ehl/outlet.py): where its hot spot lies on the
    outlet spike's flank and the grid's estimates miss their bounds (auto), always, or never. A str enum."""

    AUTO = "auto"
    ALWAYS = "always"
    NEVER = "never"

    def __str__(self) -> str:
        return self.value


THERMAL_MODELS = tuple(mode.value for mode in ThermalMode)
OUTLET_REFINEMENTS = tuple(choice.value for choice in OutletRefinement)
MAX_OUTLET_PATCHES = 3  # the outlet stage's nested patches (TUNING.patch_start, nested_patch_starts)


@dataclass(frozen=True)
class SolverSettings:
    """Numerical settings of the EHL solver."""

    grid: int = 257  # nodes per side on the finest grid, 2^n + 1 (along x, the minor axis, when grid_y is set)
    # in units of the minor semi-axis b; None: automatic, 4.5 semi-axes upstream and 1.5 downstream of the
    # entrainment (Venner & Lubrecht 2000; ehl.solve)
    domain_x: tuple[float, float] | None = None
    domain_y: tuple[float, float] | None = None  # in units of the major semi-axis a; None: automatic
    thermal: ThermalMode = ThermalMode.OFF  # a ThermalMode or its word
    coarsest_grid: int = 17  # nodes per side on the coarsest grid of the hierarchy
    cycles_per_level: int = 2  # V-cycles per level in the full-multigrid start
    max_cycles: int = 40  # extra V-cycles allowed on the finest grid to meet the tolerances
    tolerance: float = 1e-4  # relative change of pressure between cycles (L1 norm) to stop
    load_tolerance: float = 1e-4  # relative load-balance error to accept
    thermal_layers: int = 9  # layer nodes across the film of the `full` thermal model (odd)
    max_thermal_iterations: int = 40  # outer iterations of film state and pressure
    # largest temperature change per outer iteration of the thermal loop, relative to the rise: its iteration error
    # then stays within a quarter of the grid error (the measurements: docs/tuning.md)
    thermal_tolerance: float = 2e-3
    # largest change of ln(eta*/eta) per outer iteration of an isothermal Ree-Eyring film's loop (docs/tuning.md)
    eyring_tolerance: float = 1e-3
    grid_y: int | None = None  # nodes along y (the major axis) on the finest grid, 2^n + 1; None: as `grid`
    # thermal full: the outlet solved again on a patch twice as fine along x (ehl/outlet.py), one of
    # OUTLET_REFINEMENTS; auto: where the hottest film node lies on the outlet spike's rising flank and the grid's
    # estimate of dT_max or mu misses 2 % or 1 %
    outlet_refinement: OutletRefinement = OutletRefinement.AUTO
    # the most nested outlet patches (1-3: half, a quarter, an eighth of the x spacing at the spike); each after the
    # first only where the one before moved dT_max or mu by more than 2 % or 1 %, or left the estimate reported
    # after it above them (`auto`)
    outlet_patches: int = MAX_OUTLET_PATCHES
    # s: CPU time a point may take with the finer grids the solver chooses for a film its grid does not resolve; the
    # next grid is not started when the time spent times the next grid's node ratio would pass it (the point then
    # reports its best solution so far, with its estimate and why); several times the envelope's slowest point
    time_budget: float = 600.0
    # the accuracy asked of h_c, h_min, p_max, dT_max and mu, relative (0.01: 1 %); None: the grid and models as given.
    # Set, the solver chooses the grid in x and y and the cheaper models itself (accuracy_target.py)
    accuracy: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "thermal", ThermalMode(self.thermal))
        object.__setattr__(self, "outlet_refinement", OutletRefinement(self.outlet_refinement))

    @property
    def nodes_y(self) -> int:
        return self.grid if self.grid_y is None else self.grid_y


@dataclass(frozen=True)
class OutputSettings:
    file: str | None = None  # default result path (relative to the case file); None: <case name>.h5
