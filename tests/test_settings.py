"""Solver settings: the dataclass defaults are the case file's defaults, every solver key is read back as
written, and `facegear_tehl.settings` loads without the gear geometry."""

from __future__ import annotations

from dataclasses import MISSING, fields
from enum import Enum
import subprocess
import sys

import pytest
import yaml

from facegear_tehl.case import PlainContact, parse_case
from facegear_tehl.gears.spec import GearSpec
from facegear_tehl.gears.tca import Misalignment
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.materials import Solid
from facegear_tehl.schema import CaseError
from facegear_tehl.settings import OutputSettings, SolverSettings

CONTACT = "contact: {radius_x: 0.0127, radius_y: 0.0254, load: 6.0, entrainment_speed: 0.6}\n"
GEAR = ("gear: {pinion_teeth: 25, shaper_teeth: 28, face_gear_teeth: 160, module: 0.00635, pressure_angle: 25.0, "
        "shaft_angle: 110.0, inner_radius: 0.468, outer_radius: 0.548, pinion_speed: 3000.0, pinion_torque: 500.0}\n")
MINIMAL = CONTACT + """\
materials:
  body_1: {elastic_modulus: 2.0e11, poisson_ratio: 0.3}
  body_2: {elastic_modulus: 2.1e11, poisson_ratio: 0.28}
lubricant: {viscosity: 0.04, pressure_viscosity: 2.2e-8}
"""


@pytest.mark.parametrize("blocks", ["", "solver: {}\noutput: {}\n", "solver:\noutput:\n"])
def test_absent_keys_take_the_dataclass_defaults(blocks):
    case = parse_case(MINIMAL + blocks)
    assert case.solver == SolverSettings()
    assert case.output == OutputSettings()
    assert case.materials.body_1 == Solid(elastic_modulus=2.0e11, poisson_ratio=0.3)
    assert case.lubricant == Lubricant(viscosity=0.04, pressure_viscosity=2.2e-8)
    assert case.contact == PlainContact(radius_x=0.0127, radius_y=0.0254, load=6.0, entrainment_speed=0.6)


def test_absent_gear_keys_take_the_dataclass_defaults():
    gear = parse_case(MINIMAL.replace(CONTACT, GEAR)).gear
    expected = {f.name: f.default for f in fields(GearSpec) if f.default is not MISSING}
    assert {name: getattr(gear, name) for name in expected} == expected
    assert gear.misalignment == Misalignment()
    assert gear.pinion_addendum == gear.face_gear_addendum == gear.module


def test_every_solver_key_round_trips():
    written = SolverSettings(grid=129, domain_x=(-5.0, 2.0), domain_y=(-2.5, 2.5), thermal="full", coarsest_grid=9,
                             cycles_per_level=3, max_cycles=12, tolerance=2e-5, load_tolerance=3e-4, thermal_layers=7,
                             max_thermal_iterations=25, thermal_tolerance=5e-4, eyring_tolerance=3e-4, grid_y=65,
                             outlet_refinement="never", outlet_patches=1, time_budget=120.0, accuracy=0.02)
    default = SolverSettings()
    assert all(getattr(written, f.name) != getattr(default, f.name) for f in fields(SolverSettings))
    block = {f.name: getattr(written, f.name) for f in fields(SolverSettings)}
    block = {name: value.value if isinstance(value, Enum) else value for name, value in block.items()}  # YAML words
    block["domain"] = {"x": list(block.pop("domain_x")), "y": list(block.pop("domain_y"))}
    thermal_oil = MINIMAL.replace("2.2e-8}", "2.2e-8, temperature_viscosity: 0.04}")  # thermal full needs beta
    text = thermal_oil + yaml.safe_dump({"solver": block, "output": {"file": "out/run.h5"}})
    case = parse_case(text)
    assert case.solver == written
    assert case.output == OutputSettings(file="out/run.h5")


def test_settings_load_without_the_gear_geometry():
    probe = ("import sys, facegear_tehl.settings; "
             "print(sorted(m for m in sys.modules if m.startswith(('facegear_tehl.', 'scipy'))))")
    loaded = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True).stdout
    assert loaded.strip() == "['facegear_tehl.kernel_cache', 'facegear_tehl.settings']"  # kernel_cache: the
    # package's own import, before any kernel (the standard library only)


def test_the_solver_blocks_independent_problems_are_named_together():
    # A grid, a thermal model and an accuracy, each wrong on its own: one line each at once (docs/cli.md), the
    # thermal model's naming YAML's boolean reading of a bare `yes`.
    text = MINIMAL + "solver: {grid: 100, thermal: yes, accuracy: 60%, domain: {x: [-0.5, 1.5], y: [-3, 3]}}\n"
    with pytest.raises(CaseError) as raised:
        parse_case(text)
    lines = str(raised.value).splitlines()
    assert [line.split(":")[0] for line in lines] == ["solver.grid", "solver.domain.x", "solver.thermal",
                                                      "solver.accuracy"]
    assert "a bare yes or on as true" in lines[2]
    assert parse_case(MINIMAL + "solver: {thermal: off}\n").solver.thermal == "off"
