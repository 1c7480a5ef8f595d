"""Shared data for the gear tests: the example gear sets of docs/accuracy.md and the comparison rule.

Reference values are the printed numbers of an independent implementation of Litvin's method (not this
code; tables in docs/accuracy.md), given here as the printed text. `assert_reference` accepts a relative
error of 1e-3, or half a unit of the last printed digit when the printing is coarser than that (e.g.
p0 = 355 MPa, psi_e = 2.14 deg).
"""

from __future__ import annotations

import math
from pathlib import Path
import re
from typing import Any

from facegear_tehl.gears.analysis import GearContactAnalysis, analyse_gear_pair
from facegear_tehl.gears.geometry import PairGeometry
from facegear_tehl.gears.spec import GearSpec, parse_gear_block
from facegear_tehl.materials import Solid
from facegear_tehl.schema import Block

CASE_FILE = Path(__file__).resolve().parents[2] / "cases" / "facegear_110.yaml"
STEEL = Solid(elastic_modulus=206e9, poisson_ratio=0.3)  # the reference tables' steel: E = 206 GPa, nu = 0.3
MM = 1e-3

# Example A (Litvin et al. 2000 gear set 25/28/160, m = 6.35 mm, 25 deg, 3000 rpm, 500 N m) and example B.
EXAMPLE_A = dict(pinion_teeth=25, shaper_teeth=28, face_gear_teeth=160, module=6.35e-3, pressure_angle=25.0,
                 shaft_angle=110.0, inner_radius=0.468, outer_radius=0.548, pinion_speed=3000.0, pinion_torque=500.0)
EXAMPLE_B = dict(pinion_teeth=24, shaper_teeth=27, face_gear_teeth=96, module=3e-3, pressure_angle=20.0,
                 shaft_angle=110.0, inner_radius=0.139, outer_radius=0.160, pinion_speed=1500.0, pinion_torque=200.0)
TABLE_LOADS = [1 / 3, 1.0, 1.0, 1.0, 1 / 3]  # K at S1..S5 used by the reference tables


def gear_block(base: dict[str, Any] = EXAMPLE_A, **overrides: Any) -> dict[str, Any]:
    """A `gear:` block as read from YAML."""
    return {**base, **overrides}


def spec(base: dict[str, Any] = EXAMPLE_A, **overrides: Any) -> GearSpec:
    return parse_gear_block(Block(gear_block(base, **overrides), "gear"))


def analysis(base: dict[str, Any] = EXAMPLE_A, n_path: int = 41, **overrides: Any) -> GearContactAnalysis:
    overrides.setdefault("load_sharing", TABLE_LOADS)
    return analyse_gear_pair(spec(base, **overrides), STEEL, STEEL, n_path=n_path)


def case_variant(folder: Path, **gear_keys: Any) -> Path:
    """cases/facegear_110.yaml with `gear_keys` set in its gear: block (YAML flow text of each value),
    written to folder/variant.yaml."""
    text = CASE_FILE.read_text()
    for key, value in gear_keys.items():
        line = f"  {key}: {value}\n"
        text, found = re.subn(rf"^  {key}:.*\n", lambda _, line=line: line, text, count=1, flags=re.MULTILINE)
        if not found:
            text = text.replace("\ngear:\n", "\ngear:\n" + line, 1)
    path = folder / "variant.yaml"
    path.write_text(text)
    return path


def pair(base: dict[str, Any] = EXAMPLE_A, **overrides: Any) -> PairGeometry:
    """Geometry only (no validation: also for N1 = Ns)."""
    data = {**base, **overrides}
    return PairGeometry(
        pinion_teeth=data["pinion_teeth"],
        shaper_teeth=data["shaper_teeth"],
        face_gear_teeth=data["face_gear_teeth"],
        module=data["module"],
        pressure_angle=math.radians(data["pressure_angle"]),
        shaft_angle=math.radians(data["shaft_angle"]),
        pinion_addendum=data["module"],
        face_gear_addendum=data["module"],
    )


def assert_reference(value: float, printed: str, label: str = "") -> None:
    """|value - ref| <= max(1e-3 |ref|, half a unit of the last printed digit)."""
    reference = float(printed)
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    tolerance = max(1e-3 * abs(reference), 0.5 * 10.0**-decimals * (1 + 1e-9))
    assert abs(value - reference) <= tolerance, f"{label}: {value!r} vs reference {printed} (tol {tolerance:g})"
