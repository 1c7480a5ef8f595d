"""Random face gear designs (issue 14): what a designer trying new gears meets (scripts/gear_designs.py solves
them through the whole chain and tallies the outcomes).

The envelope suite (envelope.py) spans the contacts; this spans the gear designs that make them. Each
design is the shipped case (cases/facegear_110.yaml: its materials, its VG 32 ester, its solver settings) with
the gear drawn at random, uniformly from:
  shaft angle 60-135 deg, pinion teeth 13-40, shaper teeth pinion + 1..3 (localised contact, Litvin et al. 2000),
  face-gear teeth 40-220, module 2-10 mm (addenda = module), pressure angle 20-28 deg;
  pitch-line speed of the pinion 1-60 m/s (log-uniform; the pinion speed follows from its pitch radius);
  unit load F_t/(b m) 5-80 N/mm^2 (log-uniform; the tangential force over face width times module, with the face
  width taken as 10 modules: industrial spur and bevel gears carry ~10-100 N/mm^2), so that the pinion torque is
  T = U (10 m) m (m N1/2);
  face width: the whole usable width [L1, L2] of the design (undercut and pointing limits).
"""

from __future__ import annotations

from dataclasses import dataclass
import math
import random

import yaml

from facegear_tehl.gears.geometry import PairGeometry, pointing_limit, undercut_limit

SHAFT_ANGLES = (60.0, 135.0)  # deg: the supplementary (acute) drives to strongly obtuse ones
PINION_TEETH = (13, 40)
SHAPER_EXTRA = (1, 3)  # Ns - N1 for localised contact (the case check allows 1..3)
FACE_GEAR_TEETH = (40, 220)
MODULES = (0.002, 0.010)  # m
PRESSURE_ANGLES = (20.0, 28.0)  # deg
PITCH_SPEEDS = (1.0, 60.0)  # m/s, log-uniform
UNIT_LOADS = (5e6, 80e6)  # Pa = N/m^2 (5-80 N/mm^2), log-uniform
FACE_WIDTH_MODULES = 10.0  # face width / module for the unit load (a usual proportion of gear design)


@dataclass(frozen=True)
class Design:
    """One random face gear drive (SI, angles in deg as the case file writes them)."""

    index: int
    shaft_angle: float
    pinion_teeth: int
    shaper_teeth: int
    face_gear_teeth: int
    module: float
    pressure_angle: float
    pitch_speed: float  # m/s
    unit_load: float  # Pa

    @property
    def pinion_speed(self) -> float:
        """rpm from the pitch-line speed: n = v / r_p1 x 60/(2 pi)."""
        return self.pitch_speed / (self.module * self.pinion_teeth / 2.0) * 60.0 / (2.0 * math.pi)

    @property
    def pinion_torque(self) -> float:
        """N m: T = U (FACE_WIDTH_MODULES m) m r_p1."""
        return self.unit_load * FACE_WIDTH_MODULES * self.module**2 * self.module * self.pinion_teeth / 2.0

    def limits(self) -> tuple[float, float]:
        """The undercut and pointing limits L1, L2 (m) of the face gear."""
        geometry = PairGeometry(self.pinion_teeth, self.shaper_teeth, self.face_gear_teeth, self.module,
                                math.radians(self.pressure_angle), math.radians(self.shaft_angle), self.module,
                                self.module)
        return undercut_limit(geometry), pointing_limit(geometry)

    def case_text(self, base: str, grid: int, grid_y: int) -> str:
        """The case `base` (YAML text: the shipped cases/facegear_110.yaml) with this gear on the whole usable face
        width and the grid asked, as YAML."""
        raw = yaml.safe_load(base)
        raw["name"] = f"design{self.index}"
        gear = raw["gear"]
        gear.update(shaft_angle=self.shaft_angle, pinion_teeth=self.pinion_teeth, shaper_teeth=self.shaper_teeth,
                    face_gear_teeth=self.face_gear_teeth, module=self.module, pinion_addendum=self.module,
                    face_gear_addendum=self.module, pressure_angle=self.pressure_angle,
                    pinion_speed=round(self.pinion_speed, 3), pinion_torque=round(self.pinion_torque, 4))
        try:
            l1, l2 = self.limits()
        except (ValueError, ArithmeticError):  # no limits: the case check names the shaft angle
            l1, l2 = gear["inner_radius"], gear["outer_radius"]
        # 1e-9 inside the limits so that rounding keeps the face width valid
        gear["inner_radius"], gear["outer_radius"] = l1 * (1.0 + 1e-9), l2 * (1.0 - 1e-9)
        raw["solver"].update(grid=grid, grid_y=grid_y)
        return yaml.safe_dump(raw, sort_keys=False)


def random_designs(count: int, seed: int) -> list[Design]:
    """`count` designs drawn from the ranges of the module docstring; the face gear has more teeth than the shaper."""
    rng = random.Random(seed)
    designs = []
    for index in range(count):
        pinion = rng.randint(*PINION_TEETH)
        shaper = pinion + rng.randint(*SHAPER_EXTRA)
        designs.append(Design(
            index=index,
            shaft_angle=round(rng.uniform(*SHAFT_ANGLES), 1),
            pinion_teeth=pinion,
            shaper_teeth=shaper,
            face_gear_teeth=rng.randint(max(FACE_GEAR_TEETH[0], shaper + 1), FACE_GEAR_TEETH[1]),
            module=round(rng.uniform(*MODULES), 5),
            pressure_angle=round(rng.uniform(*PRESSURE_ANGLES), 1),
            pitch_speed=math.exp(rng.uniform(*map(math.log, PITCH_SPEEDS))),
            unit_load=math.exp(rng.uniform(*map(math.log, UNIT_LOADS))),
        ))
    return designs
