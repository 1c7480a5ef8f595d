"""The plan of a point solve: its stages as data, decided from the grid hierarchy, the thermal model and the
settings before anything runs. The solve follows it (solve.PointSolve), the record shows it beside what ran
(record.py), and `tehl info` prints both.
"""

from __future__ import annotations

from dataclasses import dataclass

from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.record import Stage
from facegear_tehl.settings import OutletRefinement, SolverSettings, ThermalMode


@dataclass(frozen=True)
class PlannedStage:
    """A stage to run on a grid of nx x ny nodes, and what it does there."""

    stage: Stage
    nx: int
    ny: int
    what: str

    def describe(self) -> str:
        return f"{self.stage.value} on {self.nx} x {self.ny}: {self.what}"


@dataclass(frozen=True)
class SolvePlan:
    """The stages of a point solve in order."""

    stages: tuple[PlannedStage, ...]

    def has(self, stage: Stage) -> bool:
        return any(planned.stage is stage for planned in self.stages)

    def describe(self) -> tuple[str, ...]:
        return tuple(planned.describe() for planned in self.stages)


def has_coarse_stage(shapes: list[tuple[int, int]]) -> bool:
    """Whether a thermal solve on the hierarchy `shapes` ((nx, ny), coarsest first) solves the coupled problem one
    grid coarser first: that grid has min_coarse_thermal_grid nodes in x or more. Without it `reduced` (whose result
    is that stage's state) is solved `full`, and no outlet stage follows (it refines the finish of a coarse stage)."""
    return len(shapes) > 1 and shapes[-2][0] >= TUNING.min_coarse_thermal_grid


def plan_for(shapes: list[tuple[int, int]], mode: ThermalMode, coupled: bool, settings: SolverSettings,
             entrainment_angle: float) -> SolvePlan:
    """The plan on the hierarchy `shapes` ((nx, ny), coarsest first) for the thermal model `mode` (not AUTO) of a
    film whose state is iterated with the pressure (`coupled`). A thermal solve whose grid below the finest has
    min_coarse_thermal_grid nodes in x or more solves the coupled problem there first (the coarse stage); `full`
    seeds that stage two grids below the finest from min_seed_stage_grid nodes in x. `full` then may refine the
    outlet (outlet.py) where the entrainment is within max_entrainment_angle of x."""
    top = len(shapes) - 1
    coarse = mode is not ThermalMode.OFF and has_coarse_stage(shapes)
    seed = coarse and mode is ThermalMode.FULL and len(shapes) >= 3 and shapes[-3][0] >= TUNING.min_seed_stage_grid
    below = 2 if seed else 1 if coarse else 0
    stages = [PlannedStage(Stage.START, *shapes[top - below], f"from the Hertz pressure on {shapes[0][0]} x "
                                                              f"{shapes[0][1]}, {settings.cycles_per_level} V-cycles "
                                                              f"per level")]
    if seed:
        stages.append(PlannedStage(Stage.SEED, *shapes[-3], f"coupled loop to {TUNING.seed_stage_limit:g} of the rise"))
    if coarse:
        loop = ("coupled loop seeding the finest grid" if mode is ThermalMode.FULL
                else "coupled loop; its temperatures are the result")
        stages.append(PlannedStage(Stage.COARSE, *shapes[-2], loop))
    fine = {ThermalMode.REDUCED: "pressure cycles on the interpolated state, one film-state evaluation",
            ThermalMode.FULL: "coupled loop to the thermal tolerance"}.get(mode, "pressure cycles to tolerance")
    if mode is ThermalMode.OFF and coupled:
        fine = "Ree-Eyring coupled loop to the eyring tolerance"
    stages.append(PlannedStage(Stage.FINEST, *shapes[-1], fine))
    if (mode is ThermalMode.FULL and coarse and settings.outlet_refinement != OutletRefinement.NEVER
            and abs(entrainment_angle) <= TUNING.max_entrainment_angle):
        always = settings.outlet_refinement == OutletRefinement.ALWAYS
        when = "always" if always else "where the hot spot lies on the spike's flank"
        stages.append(PlannedStage(Stage.OUTLET, *shapes[-1], f"up to {settings.outlet_patches} nested patches over "
                                                             f"its outlet at 1/2, 1/4, 1/8 of its x spacing, {when}"))
    return SolvePlan(tuple(stages))
