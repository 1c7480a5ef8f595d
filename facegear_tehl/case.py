"""Case file (YAML) -> validated, frozen `Case` in SI units.

Top-level blocks: `name`, `description`, one of `contact` (a plain elliptical contact) or `gear`
(a face gear pair), and `materials`, `lubricant`, `solver`, `output`. The problems of a case raise
`schema.CaseError` (one) or `schema.CaseErrors` (several, all found), each naming the key path, the value and
what was expected. Values that are valid but unusual for a lubricated contact (a unit mistaken, most likely)
are kept, with a warning in `Case.warnings`.
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass, replace
import math
from pathlib import Path
from typing import Any

import yaml

from facegear_tehl.fzg import MICROPITTING_STAGES
from facegear_tehl.gears.spec import GearSpec, parse_gear_block
from facegear_tehl.lubricant import DENSITY_MODELS, KELVIN, OIL_TYPES, RHEOLOGY_MODELS, VISCOSITY_MODELS, Lubricant
from facegear_tehl.materials import Solid
from facegear_tehl.oils import (
    ASSUMED_DENSITY_15,
    ASSUMED_VISCOSITY_INDEX,
    ISO_VG_GRADES,
    WALTHER_LOWEST,
    derive,
    grade_viscosity,
    nu100_for_index,
)
from facegear_tehl.schema import Block, CaseError, attempt, check, collecting, defaults, warn
from facegear_tehl.scuffing import FZG_STAGES, LUBRICATION_METHODS
from facegear_tehl.settings import (  # also imported from here
    MAX_OUTLET_PATCHES,
    OUTLET_REFINEMENTS,
    THERMAL_MODELS,
    OutputSettings,
    SolverSettings,
)
from facegear_tehl.yaml_numbers import Yaml12Loader

MAX_GRID = 4097  # nodes per side: 16.8 million nodes, beyond what one machine solves
# solver.accuracy: below 0.1 % the loops' own floors (h_c steady to 5e-4, TUNING.thermal_floor_h_c) are of the size
# of the target; above 50 % no figure is worth reporting
ACCURACY_RANGE = (0.001, 0.5)
# Ranges of real lubricated contacts: a value outside is accepted with a warning (a unit mistaken, most likely).
OIL_HOTTEST = 200.0  # degC: the flash points of gear and bearing oils start near 200 degC (ISO 6743-6 grades)
USUAL_VISCOSITY = (1e-4, 10.0)  # Pa s: a tenth of water's 1e-3 up to a heavy gear oil near its pour point
USUAL_MODULUS = (1e9, 1.2e12)  # Pa: engineering polymers (about 1 GPa) up to diamond (1.05 to 1.2 TPa)
USUAL_LOAD = (1e-2, 1e6)  # N: micro-tribometer loads up to the heaviest gear-tooth contacts
USUAL_SPEED = (1e-3, 100.0)  # m/s: slow-roll tribometer tests up to the pitch-line speeds of aerospace gears
# Physical numbers are checked against broad ranges (moduli from rubber to beyond diamond, loads 1e-6..1e9 N,
# speeds 1e-6..1e3 m/s, ...): far wider than any lubricated contact, they keep the contact analysis and the
# solver clear of overflow to Inf and underflow to 0.


class _Loader(Yaml12Loader):
    """Safe YAML loader reading numbers as YAML 1.2 does (yaml_numbers.py: `040` is 40, `1e-3` a float, `1:30` a
    string), and refusing a key given twice in one mapping (YAML requires unique keys; PyYAML would keep the last
    one silently)."""

    def construct_mapping(self, node: yaml.MappingNode, deep: bool = False) -> dict:
        first: dict[Any, int] = {}
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=deep)
            if isinstance(key, Hashable) and key in first:
                raise yaml.constructor.ConstructorError(
                    None, None, f"duplicate key {key!r} (first given at line {first[key] + 1})", key_node.start_mark)
            if isinstance(key, Hashable):
                first[key] = key_node.start_mark.line
        return super().construct_mapping(node, deep)


@dataclass(frozen=True)
class PlainContact:
    """One elliptical contact given directly (SI; angle in degrees)."""

    radius_x: float  # m
    radius_y: float  # m
    load: float  # N
    entrainment_speed: float  # m/s, |(u1 + u2)/2|
    slide_roll_ratio: float = 0.0  # (u1 - u2)/u_e along the entrainment direction
    entrainment_angle: float = 0.0  # deg, entrainment velocity to the x (minor) axis


@dataclass(frozen=True)
class Materials:
    body_1: Solid
    body_2: Solid


@dataclass(frozen=True)
class Case:
    name: str
    description: str
    text: str  # the YAML text the case was read from
    contact: PlainContact | None
    materials: Materials
    lubricant: Lubricant
    solver: SolverSettings
    output: OutputSettings
    gear: GearSpec | None = None  # a face gear pair; exactly one of contact and gear is set
    warnings: tuple[str, ...] = ()  # '<key path>: <remark>' for each valid but unusual value
    derived: tuple[str, ...] = ()  # '<key path> = <value>: <source>' for each input derived from others (oils.py)
    missing_thermal: tuple[str, ...] = ()  # lubricant keys a thermal model needs, neither given nor derived

    def with_grid(self, grid: int) -> Case:
        """The same case on another finest grid (validated like the YAML key solver.grid)."""
        _check_grid(grid, "--grid")
        check(grid >= self.solver.coarsest_grid, "--grid", grid,
              f"at least solver.coarsest_grid = {self.solver.coarsest_grid}")
        grid_y = self.solver.grid_y
        if grid_y is not None:  # keep the case's aspect: grid_y refines (or coarsens) with grid, to coarsest_grid
            grid_y = max((grid_y - 1) * (grid - 1) // (self.solver.grid - 1) + 1, self.solver.coarsest_grid)
        return replace(self, solver=replace(self.solver, grid=grid, grid_y=grid_y))

    def with_accuracy(self, accuracy: object) -> Case:
        """The same case with the accuracy target `accuracy` (validated like solver.accuracy, under --accuracy)."""
        return replace(self, solver=replace(self.solver, accuracy=accuracy_fraction(accuracy, "--accuracy")))


def accuracy_fraction(value: object, key: str) -> float:
    """The accuracy asked (`solver.accuracy`, `--accuracy`) as a fraction: a number (0.01) or a percentage ("1%").
    CaseError under `key` unless it lies in ACCURACY_RANGE."""
    fraction: object = value
    if isinstance(value, str):
        text = value.strip()
        number = text[:-1] if text.endswith("%") else text
        try:
            fraction = float(number) / (100.0 if text.endswith("%") else 1.0)
        except ValueError:
            fraction = None
    low, high = ACCURACY_RANGE
    check(isinstance(fraction, (int, float)) and not isinstance(fraction, bool) and low <= fraction <= high, key,
          value, f"a relative accuracy from {low:g} to {high:g} or a percentage from {100 * low:g}% to "
          f"{100 * high:g}% (e.g. 0.01 or 1%)")
    return float(fraction)


def _check_grid(n: int, key: str) -> None:
    m = n - 1
    check(5 <= n <= MAX_GRID and m & (m - 1) == 0, key, n,
          f"2^n + 1 nodes per side, at most {MAX_GRID} (e.g. 65, 129, 257, 513)")


# Field defaults of the dataclasses: an absent (or null) key takes the default of its field.
_SOLID = defaults(Solid)
_LUBRICANT = defaults(Lubricant)
_CONTACT = defaults(PlainContact)
_SOLVER = defaults(SolverSettings)
_OUTPUT = defaults(OutputSettings)


def _solid(block: Block) -> Solid:
    solid = Solid(
        elastic_modulus=block.number("elastic_modulus", positive=True, low=1e5, high=1e13, unit="Pa",
                                     usual=USUAL_MODULUS, hint="the key is in Pa (steel: 2.06e11)"),
        poisson_ratio=block.number("poisson_ratio", low=0.0, high=0.5, open_low=True, open_high=True),
        density=block.number("density", _SOLID["density"], positive=True, low=1.0, high=1e5, unit="kg/m^3"),
        thermal_conductivity=block.number("thermal_conductivity", _SOLID["thermal_conductivity"], positive=True,
                                          low=1e-3, high=1e4, unit="W/(m K)"),
        specific_heat=block.number("specific_heat", _SOLID["specific_heat"], positive=True, low=1.0, high=1e5,
                                   unit="J/(kg K)"),
        roughness=block.number("roughness", _SOLID["roughness"], nonnegative=True, high=1e-4, unit="m (RMS)"),
    )
    block.finish()
    return solid


def _materials(block: Block) -> Materials:
    materials = Materials(body_1=attempt(lambda: _solid(block.block("body_1"))),
                          body_2=attempt(lambda: _solid(block.block("body_2"))))
    block.finish()
    return materials


# the lubricant keys a thermal model (solver.thermal reduced | full | auto) needs, and what each is
THERMAL_NEEDS = {"temperature_viscosity": "beta = -d ln(eta)/dT at the inlet temperature, 1/K (about 0.02-0.06 for "
                                          "gear oils; given by an oil's grade or nu40 and nu100)"}


def _lubricant(block: Block) -> tuple[Lubricant, tuple[str, ...], tuple[str, ...]]:
    """The lubricant, the lines saying which of its values were derived (from an ISO grade or nu_40, nu_100), and
    the keys a thermal model needs that the block neither gives nor derives (THERMAL_NEEDS)."""
    d = _LUBRICANT
    rheology = block.choice("rheology", RHEOLOGY_MODELS, d["rheology"])
    eyring = d["eyring_stress"]
    if rheology == "ree_eyring" or block.has("eyring_stress"):  # required by Ree-Eyring, checked if given
        eyring = block.number("eyring_stress", positive=True, low=1e4, unit="Pa")
    temperature = _inlet_temperature(block)
    oil_type = block.choice("oil_type", OIL_TYPES, d["oil_type"])
    oil, derived = _oil(block, temperature, oil_type)
    d = {**d, **oil}
    lubricant = Lubricant(
        viscosity=oil["viscosity"] if oil else block.number(
            "viscosity", positive=True, low=1e-6, high=1e6, unit="Pa s", usual=USUAL_VISCOSITY,
            hint="the key is in Pa s (a value in mPa s is 1000 times larger)"),
        inlet_temperature=temperature,
        pressure_viscosity=_pressure_viscosity(block, oil, oil_type),
        density=block.number("density", d["density"], positive=True, low=1.0, high=1e5, unit="kg/m^3"),
        viscosity_model=block.choice("viscosity_model", VISCOSITY_MODELS, d["viscosity_model"]),
        density_model=block.choice("density_model", DENSITY_MODELS, d["density_model"]),
        rheology=rheology,
        eyring_stress=eyring,
        roelands_z=block.number("roelands_z", d["roelands_z"], low=0.0, high=2.0, open_low=True),
        temperature_viscosity=block.number("temperature_viscosity", d["temperature_viscosity"], nonnegative=True,
                                           high=1.0, unit="1/K"),
        thermal_expansion=block.number("thermal_expansion", d["thermal_expansion"], nonnegative=True, high=0.01,
                                       unit="1/K"),
        thermal_conductivity=block.number("thermal_conductivity", d["thermal_conductivity"], positive=True,
                                          low=1e-3, high=100.0, unit="W/(m K)"),
        # k(p) = k_0 [1 + a p/(1 + b p)], p in GPa (Larsson et al. 2000; PAOB a = 1.40, b = 0.34); the broad
        # bound 100/GPa (70 times PAOB's a) keeps k/k_0 <= 1 + 100 p/GPa
        conductivity_pressure_coefficient=block.number("conductivity_pressure_coefficient",
                                                       d["conductivity_pressure_coefficient"], nonnegative=True,
                                                       high=100.0, unit="1/GPa"),
        conductivity_pressure_saturation=block.number("conductivity_pressure_saturation",
                                                      d["conductivity_pressure_saturation"], nonnegative=True,
                                                      high=100.0, unit="1/GPa"),
        specific_heat=block.number("specific_heat", d["specific_heat"], positive=True, low=1.0, high=1e5,
                                   unit="J/(kg K)"),
        oil_type=oil_type,
        scuffing_temperature=_scuffing_temperature(block, temperature),
        fzg_scuffing_stage=block.number("fzg_scuffing_stage", None, low=FZG_STAGES[0], high=FZG_STAGES[1],
                                        unit="load stages of the FZG A/8.3/90 scuffing test"),
        micropitting_stage=block.number("micropitting_stage", None, low=MICROPITTING_STAGES[0],
                                        high=MICROPITTING_STAGES[1], unit="load stages of the FZG GF-C/8.3/90 test"),
        micropitting_test_film=block.number("micropitting_test_film", None, positive=True, high=10.0,
                                            hint="lambda_GFT of the oil's FZG GF-C/8.3/90 test"),
        lubrication=block.choice("lubrication", LUBRICATION_METHODS, d["lubrication"]),
    )
    _check_lubricant(block, lubricant)
    block.finish()
    missing = tuple(key for key in THERMAL_NEEDS if not block.has(key) and key not in oil)
    return lubricant, tuple(line for line in derived if not block.has(line.split(" = ")[0].split(".")[-1])), missing


def _check_lubricant(block: Block, lubricant: Lubricant) -> None:
    """The checks across the lubricant's keys."""
    check(lubricant.micropitting_stage is None or lubricant.micropitting_test_film is None,
          block.key_path("micropitting_test_film"), lubricant.micropitting_test_film,
          "either micropitting_stage (its lambda_GFT is computed) or micropitting_test_film, not both")
    check(
        lubricant.roelands_log_term > 0.0 or lubricant.viscosity_model != "roelands",
        block.key_path("viscosity"),
        lubricant.viscosity,
        "a viscosity above the Roelands asymptote 6.3e-5 Pa s (use viscosity_model: barus otherwise)",
    )


def _inlet_temperature(block: Block) -> float:
    """lubricant.inlet_temperature (degC in the file) in K, with a warning when hotter than an oil bath runs."""
    if not block.has("inlet_temperature"):
        return _LUBRICANT["inlet_temperature"]
    celsius = block.number("inlet_temperature", low=-100.0, high=400.0, unit="degC")
    if celsius > OIL_HOTTEST:
        warn(block.key_path("inlet_temperature"), f"{celsius:g} degC is hotter than an oil bath runs (at most "
             f"{OIL_HOTTEST:g} degC); the key is in degC: if {celsius:g} is kelvin, write {celsius - KELVIN:g}")
    return celsius + KELVIN


def _scuffing_temperature(block: Block, inlet: float) -> float | None:
    """lubricant.scuffing_temperature (degC in the file) in K, above the inlet temperature; None if not given."""
    if not block.has("scuffing_temperature"):
        return None
    celsius = block.number("scuffing_temperature", low=0.0, high=2000.0, unit="degC")
    check(celsius + KELVIN > inlet, block.key_path("scuffing_temperature"), celsius,
          f"a temperature above the inlet's {inlet - KELVIN:g} degC (the oil scuffs above its bath temperature)")
    return celsius + KELVIN


# The keys of an oil given in engineering units (oils.py) instead of viscosity in Pa s.
_OIL_KEYS = ("grade", "nu40", "nu100", "viscosity_index", "density_15")


def _oil(block: Block, temperature: float, oil_type: str) -> tuple[dict[str, float], tuple[str, ...]]:
    """The Lubricant values derived from grade or nu40, nu100 and density_15 (oils.derive) with their provenance
    lines ('lubricant.<key> = ...'); ({}, ()) for an oil given by viscosity in Pa s."""
    if not any(block.has(key) for key in _OIL_KEYS):
        return {}, ()
    check(not block.has("viscosity"), block.key_path("viscosity"), block.raw.get("viscosity"),
          "no viscosity with grade/nu40/nu100 (the viscosity at the inlet is derived from them)")
    check(block.has("grade") != block.has("nu40"), block.key_path("nu40"), block.raw.get("nu40"),
          "exactly one of grade (an ISO 3448 grade, e.g. VG100) or nu40 (mm^2/s at 40 degC)")
    source = "mm^2/s given"
    if block.has("grade"):
        grade = _grade(block)
        nu_40, source = grade_viscosity(grade), f"the ISO 3448 VG {grade} midpoint"
    else:
        nu_40 = block.number("nu40", low=WALTHER_LOWEST, high=1e6, unit="mm^2/s")
    nu_100, assumed = _nu100(block, nu_40, oil_type)
    density_15, density_line = _density_15(block, oil_type)
    if not all(math.isfinite(v) for v in (nu_40, nu_100, density_15)):  # recorded by the readers
        return {"viscosity": math.nan}, ()
    check(nu_100 < nu_40, block.key_path("nu100"), nu_100, f"less than nu_40 = {nu_40:g} mm^2/s")
    if nu_100 >= nu_40:
        return {"viscosity": math.nan}, ()
    given = block.raw.get("density")  # checked where it is read; a valid one makes the dynamic viscosity
    valid = isinstance(given, (int, float)) and not isinstance(given, bool) and 0 < given < math.inf
    density = given if valid else None
    oil = derive(nu_40, nu_100, density_15, temperature, oil_type, source, density)
    values = {key: getattr(oil, key) for key in ("viscosity", "density", "temperature_viscosity", "thermal_expansion",
                                                 "pressure_viscosity", "thermal_conductivity", "specific_heat")}
    lines = (*assumed, *density_line, *oil.provenance)
    return ({key: value for key, value in values.items() if value is not None},
            tuple(f"{block.key_path(line)}" for line in lines))


def _nu100(block: Block, nu_40: float, oil_type: str) -> tuple[float, tuple[str, ...]]:
    """lubricant.nu100 in mm^2/s: given, else at lubricant.viscosity_index (given, or the one assumed for the oil
    type, oils.ASSUMED_VISCOSITY_INDEX) by ASTM D2270; with the provenance line of a derived value."""
    if block.has("nu100"):
        check(not block.has("viscosity_index"), block.key_path("viscosity_index"), block.raw.get("viscosity_index"),
              "no viscosity_index with nu100 (nu100 fixes the index)")
        return block.number("nu100", low=WALTHER_LOWEST, high=1e6, unit="mm^2/s (from the oil's datasheet)"), ()
    assumed = ASSUMED_VISCOSITY_INDEX.get(oil_type)
    if assumed is None and not block.has("viscosity_index"):
        check(False, block.key_path("nu100"), None, f"a value in mm^2/s from the datasheet (or viscosity_index): no "
              f"viscosity index is assumed for oil_type {oil_type}")
        return math.nan, ()
    index = block.number("viscosity_index", assumed, low=-100.0, high=400.0, unit="(ASTM D2270)")
    if not math.isfinite(nu_40 + index):
        return math.nan, ()
    source = "given" if block.has("viscosity_index") else f"assumed for {oil_type} gear oils"
    try:
        nu_100 = nu100_for_index(nu_40, index)
    except ValueError as error:
        check(False, block.key_path("viscosity_index"), index, f"an index reached at nu_100 >= 2 mm^2/s ({error})")
        return math.nan, ()
    return nu_100, (f"nu100 = {nu_100:.4g} mm^2/s: ASTM D2270-10 (Appendix X2 reference oils) at nu_40 = "
                    f"{nu_40:g} mm^2/s and viscosity index {index:g} ({source})",)


def _density_15(block: Block, oil_type: str) -> tuple[float, tuple[str, ...]]:
    """lubricant.density_15 in kg/m^3: given, else the one assumed for the oil type (oils.ASSUMED_DENSITY_15)."""
    if block.has("density_15") or oil_type not in ASSUMED_DENSITY_15:
        return block.number("density_15", low=500.0, high=2000.0, unit="kg/m^3 (from the oil's datasheet)"), ()
    density_15 = ASSUMED_DENSITY_15[oil_type]
    return density_15, (f"density_15 = {density_15:g} kg/m^3: assumed for {oil_type} gear oils (datasheets' range, "
                        "docs/verdict.md)",)


def _grade(block: Block) -> int:
    """lubricant.grade: VG100, 'VG 100', 'ISO VG 100' or 100, one of the ISO 3448 grades."""
    raw = block.get("grade")
    text = str(raw).upper().replace("ISO", "").replace("VG", "").strip() if not isinstance(raw, bool) else ""
    grade = int(text) if text.isdigit() else None
    check(grade in ISO_VG_GRADES, block.key_path("grade"), raw,
          "an ISO 3448 grade: " + ", ".join(f"VG{g}" for g in ISO_VG_GRADES))
    return grade if grade in ISO_VG_GRADES else ISO_VG_GRADES[0]


def _pressure_viscosity(block: Block, oil: dict[str, float], oil_type: str) -> float:
    """lubricant.pressure_viscosity, 1/Pa: given, else derived for an oil given in engineering units (oils.py)."""
    if oil and "pressure_viscosity" not in oil and not block.has("pressure_viscosity"):
        check(False, block.key_path("pressure_viscosity"), None,
              f"a value in 1/Pa: none is derived for oil_type {oil_type} (the built-in correlations, ISO/TR 15144-1, "
              "are for mineral, pao and pag oils)")
        return math.nan
    default = [oil["pressure_viscosity"]] if "pressure_viscosity" in oil else []
    return block.number("pressure_viscosity", *default, positive=True, high=1e-6, unit="1/Pa")


def _plain_contact(block: Block) -> PlainContact:
    contact = PlainContact(
        radius_x=block.number("radius_x", positive=True, low=1e-6, high=1e4, unit="m"),
        radius_y=block.number("radius_y", positive=True, low=1e-6, high=1e4, unit="m"),
        load=block.number("load", positive=True, low=1e-6, high=1e9, unit="N", usual=USUAL_LOAD),
        entrainment_speed=block.number("entrainment_speed", positive=True, low=1e-6, high=1e3, unit="m/s",
                                       usual=USUAL_SPEED, hint="the key is in m/s (a value in mm/s is 1000 times "
                                       "larger)"),
        # |SRR| > 2: the surfaces move in opposite directions (u_2 = u_e (1 - SRR/2) < 0); at |SRR| = 4 the
        # slower one moves backward at the entrainment speed.
        slide_roll_ratio=block.number("slide_roll_ratio", _CONTACT["slide_roll_ratio"], low=-4.0, high=4.0),
        entrainment_angle=block.number("entrainment_angle", _CONTACT["entrainment_angle"], low=-90.0, high=90.0,
                                       unit="deg"),
    )
    check(
        contact.radius_y >= contact.radius_x,
        block.key_path("radius_y"),
        contact.radius_y,
        f"radius_y >= radius_x = {contact.radius_x:g} m (x is the minor axis of the contact ellipse)",
    )
    check(
        contact.radius_y / contact.radius_x <= 5000.0,
        block.key_path("radius_y"),
        contact.radius_y,
        "radius_y / radius_x <= 5000",
    )
    block.finish()
    return contact


def _solver(block: Block) -> SolverSettings:
    """The solver: block. Its grids, its domain, its thermal model and its accuracy are checked apart (each an
    `attempt` of its own), so that a problem in one does not hide another's."""
    d = _SOLVER
    grid = block.integer("grid", d["grid"])
    coarsest = block.integer("coarsest_grid", d["coarsest_grid"], low=9)
    grid_y = block.integer("grid_y") if block.has("grid_y") else d["grid_y"]
    attempt(lambda: _check_grids(block, grid, coarsest, grid_y))
    dx, dy = d["domain_x"], d["domain_y"]
    if block.has("domain"):
        dx, dy = attempt(lambda: _domain(block.block("domain"))) or (dx, dy)
    thermal = block.get("thermal", d["thermal"])
    if thermal is False:  # YAML 1.1 reads a bare `off` as false
        thermal = "off"
    attempt(lambda: check(isinstance(thermal, str) and thermal in THERMAL_MODELS, block.key_path("thermal"), thermal,
                          "one of " + ", ".join(THERMAL_MODELS) + (" (YAML reads a bare yes or on as true)"
                                                                    if thermal is True else "")))
    accuracy = d["accuracy"]
    if block.has("accuracy"):
        accuracy = attempt(lambda: accuracy_fraction(block.get("accuracy"), block.key_path("accuracy")))
    settings = SolverSettings(
        grid=grid,
        domain_x=dx,
        domain_y=dy,
        thermal=thermal,
        coarsest_grid=coarsest,
        cycles_per_level=block.integer("cycles_per_level", d["cycles_per_level"], low=1, high=20),
        max_cycles=block.integer("max_cycles", d["max_cycles"], low=1, high=1000),
        tolerance=block.number("tolerance", d["tolerance"], positive=True, high=0.1),
        load_tolerance=block.number("load_tolerance", d["load_tolerance"], positive=True, high=0.1),
        thermal_layers=block.integer("thermal_layers", d["thermal_layers"], low=3, high=41),
        max_thermal_iterations=block.integer("max_thermal_iterations", d["max_thermal_iterations"], low=1, high=500),
        thermal_tolerance=block.number("thermal_tolerance", d["thermal_tolerance"], positive=True, high=0.1),
        eyring_tolerance=block.number("eyring_tolerance", d["eyring_tolerance"], positive=True, high=0.1),
        grid_y=grid_y,
        outlet_refinement=block.choice("outlet_refinement", OUTLET_REFINEMENTS, d["outlet_refinement"]),
        outlet_patches=block.integer("outlet_patches", d["outlet_patches"], low=1, high=MAX_OUTLET_PATCHES),
        time_budget=block.number("time_budget", d["time_budget"], positive=True, high=1e6, unit="s"),
        accuracy=accuracy,
    )
    check(settings.thermal_layers % 2 == 1, block.key_path("thermal_layers"), settings.thermal_layers,
          "an odd number of layer nodes (Simpson's rule across the film), e.g. 7, 9 or 11")
    if block.has("domain"):
        _warn_unresolved_domain(block, settings)
    block.finish()
    return settings


# nodes across the contact's width (two semi-axes) below which a domain given is warned of: the smallest grid, 17
# nodes over the default 6 semi-axes, puts 5.3 there
MIN_NODES_ACROSS = 4.0


def _warn_unresolved_domain(block: Block, settings: SolverSettings) -> None:
    """A warning for each axis of solver.domain that leaves fewer than MIN_NODES_ACROSS nodes of the grid asked across
    the contact (a domain of a million semi-axes passes the checks and runs away on every grid)."""
    for axis, (low, high), nodes in (("x", settings.domain_x, settings.grid), ("y", settings.domain_y,
                                                                                 settings.nodes_y)):
        across = 2.0 * (nodes - 1) / (high - low)
        if across < MIN_NODES_ACROSS:
            warn(f"{block.key_path('domain')}.{axis}", f"{[low, high]} puts {across:.2g} of the {nodes} nodes across "
                 "the contact (two semi-axes): no film is resolved (the default spans 6 semi-axes, and the solver "
                 "lengthens the inlet itself)")


def _check_grids(block: Block, grid: int, coarsest: int, grid_y: int) -> None:
    """solver.grid, coarsest_grid and grid_y: each 2^n + 1, the coarsest the smallest."""
    _check_grid(grid, block.key_path("grid"))
    _check_grid(coarsest, block.key_path("coarsest_grid"))
    if block.has("coarsest_grid"):
        check(coarsest <= grid, block.key_path("coarsest_grid"), coarsest, f"at most solver.grid = {grid}")
    else:  # the default coarsest grid: the grid given is the one too small
        check(coarsest <= grid, block.key_path("grid"), grid,
              f"at least solver.coarsest_grid = {coarsest} (its default)")
    if block.has("grid_y"):
        _check_grid(grid_y, block.key_path("grid_y"))
        check(coarsest <= grid_y, block.key_path("grid_y"), grid_y, f"at least solver.coarsest_grid = {coarsest}")


def _domain(domain: Block) -> tuple[tuple[float, float], tuple[float, float]]:
    """solver.domain: its x and y intervals, each containing the contact."""
    dx = domain.interval("x")
    dy = domain.interval("y")
    domain.finish()
    check(dx[0] < -1.0 and dx[1] > 1.0, domain.key_path("x"), list(dx),
          "an interval containing the contact [-1, 1] (units of the semi-axis b), e.g. [-4.5, 1.5]")
    check(dy[0] < -1.0 and dy[1] > 1.0, domain.key_path("y"), list(dy),
          "an interval containing the contact [-1, 1] (units of the semi-axis a), e.g. [-3, 3]")
    return dx, dy


def _output(block: Block) -> OutputSettings:
    settings = OutputSettings(file=block.string("file") if block.has("file") else _OUTPUT["file"])
    check(settings.file is None or (settings.file.strip() != "" and "\0" not in settings.file),
          block.key_path("file"), settings.file, "a file path (not empty, no NUL character)")
    block.finish()
    return settings


def parse_case(text: str, name: str = "case") -> Case:
    """Parse and validate the YAML text of a case: CaseError, or CaseErrors naming every problem found."""
    try:
        raw: Any = yaml.load(text, Loader=_Loader)
    except yaml.YAMLError as exc:
        raise _yaml_error(exc, text) from None
    except (ValueError, RecursionError) as exc:  # an impossible date, an int of > 4300 digits; deep nesting
        reason = "nesting too deep" if isinstance(exc, RecursionError) else str(exc)
        raise CaseError("(file)", "a value YAML cannot read", f"valid YAML ({reason})") from None
    if raw is None:
        raise CaseError("(file)", "an empty document", "a case: contact: or gear:, materials:, lubricant:, ...")
    case, warnings = collecting(lambda: _case(raw, text, name))
    return replace(case, warnings=warnings)


def _yaml_error(exc: yaml.YAMLError, text: str) -> CaseError:
    """(file): got the offending line; expected valid YAML (line, column: the parser's message)."""
    mark = getattr(exc, "problem_mark", None)
    position = getattr(exc, "position", None)  # a character YAML does not accept (yaml.reader.ReaderError)
    if mark is None:
        where = f"character {position + 1}" if position is not None else "unknown position"
        return CaseError("(file)", f"YAML syntax error at {where}", "valid YAML")
    lines = text.splitlines()
    line = " ".join(lines[mark.line].split(" #")[0].split()) if mark.line < len(lines) else ""  # without comment
    context, started = getattr(exc, "context", None), getattr(exc, "context_mark", None)
    if context and started is not None and started.line != mark.line:  # where the construct that broke began
        context = f"{context} started at line {started.line + 1},"
    problem = " ".join(f"{context or ''} {getattr(exc, 'problem', None) or ''}".split())
    return CaseError("(file)", line, f"valid YAML (syntax error at line {mark.line + 1}, column {mark.column + 1}"
                     + (f": {problem})" if problem else ")"))


def _case(raw: Any, text: str, name: str) -> Case:
    top = Block(raw, "")
    case_name = top.string("name", name)
    check(case_name.strip() != "" and case_name.isprintable() and not {"/", "\\"} & set(case_name), "name",
          case_name, "a non-empty name on one line without '/' or '\\' (it names the default result file)")
    description = top.string("description", "")
    has_contact, has_gear = top.has("contact"), top.has("gear")
    check(has_contact != has_gear, "contact/gear", "both blocks" if has_contact else None,
          "exactly one of a contact: block (one plain elliptical contact) or a gear: block (a face gear pair)")
    contact = attempt(lambda: _plain_contact(top.block("contact"))) if has_contact else None
    gear = attempt(lambda: parse_gear_block(top.block("gear"))) if has_gear else None
    materials = attempt(lambda: _materials(top.block("materials")))
    lubricant = attempt(lambda: _lubricant(top.block("lubricant")))
    case = Case(
        name=case_name,
        description=description,
        text=text,
        contact=contact,
        materials=materials,
        lubricant=lubricant[0] if lubricant else None,
        solver=attempt(lambda: _solver(top.block("solver", {}))),
        output=attempt(lambda: _output(top.block("output", {}))),
        gear=gear,
        derived=lubricant[1] if lubricant else (),
        missing_thermal=lubricant[2] if lubricant else (),
    )
    if case.solver is not None:
        check_thermal_inputs(case, "solver.thermal")
    top.finish()
    return case


def check_thermal_inputs(case: Case, key: str) -> None:
    """CaseError where the case's thermal model (`key`: the YAML key or the option that set it) is not off and the
    lubricant leaves out a key that model needs: with no temperature-viscosity coefficient its oil would be heated
    without thinning, a film state no thermal EHL analysis means (an explicit 0 is taken as given)."""
    for missing in case.missing_thermal:
        check(case.solver.thermal == "off", f"lubricant.{missing}", None,
              f"this key to be present with {key} {case.solver.thermal} (or thermal off): {THERMAL_NEEDS[missing]}")


def load_case(path: str | Path) -> Case:
    """Read and validate a case file."""
    path = Path(path)
    return parse_case(read_input(path, "case file"), name=path.stem)


def read_input(path: Path, what: str) -> str:
    """The text of an input file (`what`: "case file", "study file"); CaseError naming the file if it cannot be read
    or is not UTF-8 text, or is not a regular file (a FIFO would block the read until someone writes to it)."""
    if path.exists() and not path.is_file():
        raise CaseError("(file)", str(path), f"a {what} (a regular file, not a directory, device or FIFO)")
    try:
        return path.read_text(encoding="utf-8")
    except OSError as exc:
        raise CaseError("(file)", str(path), f"a readable {what} ({exc.strerror})") from None
    except UnicodeDecodeError:
        raise CaseError("(file)", str(path), "a UTF-8 text file") from None
