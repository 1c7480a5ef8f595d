"""The `gear:` block of a case: a face gear pair, validated and converted to SI units (`GearSpec`).

Keys (YAML units): pinion_teeth, shaper_teeth, face_gear_teeth, module (m), pressure_angle (deg),
shaft_angle (deg, 0 < g < 180; docs/method.md §1.1: the pitch-cone angles add up, delta_1 + delta_2 = g, so
g = 110 deg gives delta_2 = 101.2 deg for 25/160 teeth, a face gear whose pitch cone opens toward the
pinion; a paper's "110 deg" meaning the supplementary drive is our 70 deg), pinion_addendum and
face_gear_addendum (m, default = module), inner_radius and outer_radius of the face gear (m),
pinion_speed (rpm), pinion_torque (N m), load_sharing (iso_linear | equal | one coefficient per point),
transition_side (single | double: K of a point exactly at S2 or S4 with a sharing model, loads.load_share),
points ([S1, ..., S5] by default, any subset of these names, or a count of evenly spaced points over the
whole path), and the optional misalignment shaft_angle_error (deg), offset (m), pinion_axial_shift (m),
face_gear_axial_shift (m), and the bulk temperatures pinion_bulk_temperature and face_gear_bulk_temperature
(degC, default: the oil inlet temperature) to which the flash temperature of each flank adds (cycle.py).

Impossible gears are input errors (`CaseError` naming the key): Ns - N1 not in 1..3, a face width
outside [L1, L2] or not covering the contact path, a contact ratio outside [1, 2), a face-gear tip that
reaches below the pinion base circle, no contact under the given misalignment.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math

import numpy as np

from facegear_tehl.gears.geometry import PairGeometry, axial_section, pointing_limit, undercut_limit
from facegear_tehl.gears.loads import LOAD_SHARING_MODELS, TRANSITION_SIDES, contact_ratio
from facegear_tehl.gears.tca import ALIGNED, MESHING_POINTS, ContactError, ContactPath, Misalignment
from facegear_tehl.lubricant import KELVIN
from facegear_tehl.schema import Block, CaseError, check, defaults

RPM = 2.0 * math.pi / 60.0  # rad/s per rev/min
MAX_POINT_COUNT = 1000
_PATH_CHECK_SAMPLES = 21  # samples of the path checked against the face width


@dataclass(frozen=True)
class GearSpec:
    """A face gear pair and its operating point, SI units (angles in rad, speed in rad/s)."""

    pinion_teeth: int
    shaper_teeth: int
    face_gear_teeth: int
    module: float  # m
    pressure_angle: float  # rad
    shaft_angle: float  # rad
    pinion_addendum: float  # m
    face_gear_addendum: float  # m
    inner_radius: float  # m, of the face gear
    outer_radius: float  # m
    pinion_speed: float  # rad/s
    pinion_torque: float  # N m
    load_sharing: str | tuple[float, ...] = "iso_linear"  # of loads.LOAD_SHARING_MODELS, or one coefficient per point
    points: tuple[str, ...] | int = MESHING_POINTS  # names among S1..S5, or a count of evenly spaced points
    transition_side: str = "single"  # of loads.TRANSITION_SIDES: K exactly at S2 and S4 under a sharing model
    misalignment: Misalignment = ALIGNED
    pinion_bulk_temperature: float | None = None  # K; None: the oil inlet temperature
    face_gear_bulk_temperature: float | None = None  # K; None: the oil inlet temperature

    @property
    def geometry(self) -> PairGeometry:
        return PairGeometry(
            pinion_teeth=self.pinion_teeth,
            shaper_teeth=self.shaper_teeth,
            face_gear_teeth=self.face_gear_teeth,
            module=self.module,
            pressure_angle=self.pressure_angle,
            shaft_angle=self.shaft_angle,
            pinion_addendum=self.pinion_addendum,
            face_gear_addendum=self.face_gear_addendum,
        )

    @property
    def point_names(self) -> tuple[str, ...]:
        """S1..S5 names, or P01..Pnn for a count of evenly spaced points."""
        if isinstance(self.points, int):
            width = max(2, len(str(self.points)))
            return tuple(f"P{i + 1:0{width}d}" for i in range(self.points))
        return self.points


# Ranges of real face gear drives: a value outside is accepted with a warning (a unit mistaken, most likely).
USUAL_PINION_SPEED = (1.0, 1e5)  # rpm: a slow hand-driven drive up to beyond the 20000-30000 rpm of helicopter inputs
USUAL_PINION_TORQUE = (0.1, 1e5)  # N m: instrument drives up to 10 times helicopter face-gear pinions (a few kN m)
_GEAR = defaults(GearSpec)  # an absent (or null) key takes the default of its field
_MISALIGNMENT = defaults(Misalignment)


def parse_gear_block(block: Block) -> GearSpec:
    """Read and validate the `gear:` block (see the module docstring)."""
    n1 = block.integer("pinion_teeth", low=8, high=1000)
    ns = block.integer("shaper_teeth", low=1)
    check(1 <= ns - n1 <= 3, block.key_path("shaper_teeth"), ns, "shaper_teeth - pinion_teeth in 1..3")
    n2 = block.integer("face_gear_teeth", low=1, high=10000)
    check(n2 > ns, block.key_path("face_gear_teeth"), n2, f"more teeth than the shaper ({ns})")
    module = block.number("module", positive=True, high=0.1, unit="m")
    pressure_angle = block.number("pressure_angle", low=10.0, high=35.0, unit="deg")
    shaft_angle = block.number("shaft_angle", low=0.0, high=180.0, open_low=True, open_high=True, unit="deg")
    addendum_1 = block.number("pinion_addendum", module, positive=True, high=2.0 * module, unit="m")
    addendum_2 = block.number("face_gear_addendum", module, positive=True, high=2.0 * module, unit="m")
    inner = block.number("inner_radius", positive=True, unit="m")
    outer = block.number("outer_radius", positive=True, unit="m")
    check(outer > inner, block.key_path("outer_radius"), outer, f"more than inner_radius = {inner:g} m")
    speed = block.number("pinion_speed", positive=True, low=1e-3, high=1e6, unit="rpm", usual=USUAL_PINION_SPEED,
                         hint="the key is in rpm (a value in rad/s is about 10 times smaller)")
    torque = block.number("pinion_torque", positive=True, low=1e-3, high=1e7, unit="N m", usual=USUAL_PINION_TORQUE,
                          hint="the key is in N m (a value in N mm is 1000 times larger)")
    points = _points(block)
    count = points if isinstance(points, int) else len(points)
    load_sharing = _load_sharing(block, count)
    spec = GearSpec(
        pinion_teeth=n1,
        shaper_teeth=ns,
        face_gear_teeth=n2,
        module=module,
        pressure_angle=math.radians(pressure_angle),
        shaft_angle=math.radians(shaft_angle),
        pinion_addendum=addendum_1,
        face_gear_addendum=addendum_2,
        inner_radius=inner,
        outer_radius=outer,
        pinion_speed=speed * RPM,
        pinion_torque=torque,
        load_sharing=load_sharing,
        points=points,
        transition_side=_transition_side(block, load_sharing),
        misalignment=_misalignment(block, module),
        pinion_bulk_temperature=_bulk_temperature(block, "pinion_bulk_temperature"),
        face_gear_bulk_temperature=_bulk_temperature(block, "face_gear_bulk_temperature"),
    )
    block.finish()
    _check_feasible(spec, block)
    return spec


def _bulk_temperature(block: Block, key: str) -> float | None:
    """A bulk temperature, degC in the file (the range of lubricant.inlet_temperature), K; None if absent."""
    if not block.has(key):
        return _GEAR[key]
    return block.number(key, low=-100.0, high=400.0, unit="degC") + KELVIN


def _misalignment(block: Block, module: float) -> Misalignment:
    d = _MISALIGNMENT
    angle_error = d["shaft_angle_error"]
    if block.has("shaft_angle_error"):  # deg in the file
        angle_error = math.radians(block.number("shaft_angle_error", low=-1.0, high=1.0, unit="deg"))
    return Misalignment(
        shaft_angle_error=angle_error,
        offset=block.number("offset", d["offset"], low=-module, high=module, unit="m"),
        pinion_axial_shift=block.number("pinion_axial_shift", d["pinion_axial_shift"], low=-10 * module,
                                        high=10 * module, unit="m"),
        face_gear_axial_shift=block.number("face_gear_axial_shift", d["face_gear_axial_shift"], low=-module,
                                           high=module, unit="m"),
    )


def _points(block: Block) -> tuple[str, ...] | int:
    value = block.get("points", list(_GEAR["points"]))
    key = block.key_path("points")
    if isinstance(value, int) and not isinstance(value, bool):
        check(2 <= value <= MAX_POINT_COUNT, key, value, f"a count of points in 2..{MAX_POINT_COUNT}")
        return value
    check(
        isinstance(value, list) and len(value) > 0 and all(isinstance(v, str) and v in MESHING_POINTS for v in value),
        key,
        value,
        "a list of names among " + ", ".join(MESHING_POINTS) + " or a count of evenly spaced points",
    )
    check(len(set(value)) == len(value), key, value, "each point named once")
    return tuple(value)


def _load_sharing(block: Block, count: int) -> str | tuple[float, ...]:
    value = block.get("load_sharing", _GEAR["load_sharing"])
    key = block.key_path("load_sharing")
    if isinstance(value, str):
        check(value in LOAD_SHARING_MODELS, key, value, "one of " + ", ".join(LOAD_SHARING_MODELS) + " or a list")
        return value
    check(
        isinstance(value, list)
        and all(isinstance(v, (int, float)) and not isinstance(v, bool) and 0.0 < v <= 1.0 for v in value),
        key,
        value,
        "one of " + ", ".join(LOAD_SHARING_MODELS) + ", or a list of coefficients in (0, 1]",
    )
    check(len(value) == count, key, value, f"one coefficient per point ({count})")
    return tuple(float(v) for v in value)


def _transition_side(block: Block, load_sharing: str | tuple[float, ...]) -> str:
    """single (default) or double; only with a sharing model: a list of coefficients fixes K at every point."""
    if not isinstance(load_sharing, str) and block.has("transition_side"):
        raise CaseError(block.key_path("transition_side"), block.get("transition_side"),
                        "no transition_side when load_sharing is a list of coefficients (the list sets K at "
                        "every point; transition_side applies to " + ", ".join(LOAD_SHARING_MODELS) + ")")
    return block.choice("transition_side", TRANSITION_SIDES, _GEAR["transition_side"])


def _misalignment_key(spec: GearSpec, block: Block) -> str:
    mis = spec.misalignment
    for name in ("shaft_angle_error", "offset", "face_gear_axial_shift", "pinion_axial_shift"):
        if getattr(mis, name):
            return block.key_path(name)
    return block.key_path("shaft_angle")


# deg: the pressure angle tried in its place to tell which key makes a drive without face-width limits (25 deg, the
# Litvin et al. 2000 example set of cases/facegear_110.yaml)
USUAL_PRESSURE_ANGLE = 25.0


def _face_width_limits(geo: PairGeometry) -> tuple[float, float] | None:
    """The undercut and pointing limits L1, L2 (m), or None where the drive has none."""
    try:
        with np.errstate(over="raise", invalid="raise"):  # a shaft angle near 0 overflows or divides by 0
            return undercut_limit(geo), pointing_limit(geo)
    except (ValueError, ArithmeticError):
        return None


def _check_feasible(spec: GearSpec, block: Block) -> None:
    """Cross-key checks that need the geometry: L1, L2, path limits, contact ratio, face width."""
    geo = spec.geometry
    limits = _face_width_limits(geo)
    if limits is None:  # the key to blame: the pressure angle where the usual one gives this drive its limits
        usual = _face_width_limits(replace(geo, pressure_angle=math.radians(USUAL_PRESSURE_ANGLE)))
        key = "pressure_angle" if usual is not None else "shaft_angle"
        raise CaseError(block.key_path(key), block.raw.get(key),
                        f"a {key.replace('_', ' ')} for which the face gear of this drive has an undercut and a "
                        "pointing limit") from None
    l1, l2 = limits
    check(l2 > l1, block.key_path("face_gear_teeth"), spec.face_gear_teeth,
          f"a face gear with pointing limit L2 = {l2:.4g} m above undercut limit L1 = {l1:.4g} m")
    try:
        path = ContactPath(geo, spec.misalignment)
        s_min, s_max = path.limits()
        samples = [path.state(s) for s in np.linspace(s_min, s_max, _PATH_CHECK_SAMPLES)]
    except (ContactError, ValueError, np.linalg.LinAlgError):
        key = _misalignment_key(spec, block)
        raise CaseError(key, block.raw.get(key.rsplit(".", 1)[-1]),
                        "a drive with a continuous pinion / face-gear contact") from None
    check(s_min > -geo.r_p1 * math.sin(geo.pressure_angle), block.key_path("face_gear_addendum"),
          spec.face_gear_addendum, "a face-gear addendum whose tip meets the pinion above its base circle")
    eps = contact_ratio(s_min, s_max, geo.base_pitch)
    check(1.0 <= eps < 2.0, block.key_path("pinion_addendum"), spec.pinion_addendum,
          f"addenda giving a contact ratio in [1, 2); these give {eps:.4f}")
    radii = [axial_section(geo, st.point - st.face_gear_origin)[1] for st in samples]
    lowest, highest = min(radii), max(radii)
    check(l1 <= lowest and highest <= l2, block.key_path("face_gear_teeth"), spec.face_gear_teeth,
          f"a pair whose contact path, at face-gear radii {lowest:.5g} to {highest:.5g} m, lies inside the usable "
          f"face width [L1, L2] = [{l1:.5g}, {l2:.5g}] m (no face width fits this path: change the teeth numbers, "
          "the pressure angle or the shaft angle)")
    usable = f"; the usable face width of this gear is [L1, L2] = [{l1:.5g}, {l2:.5g}] m"
    check(spec.inner_radius >= l1, block.key_path("inner_radius"), spec.inner_radius,
          f"at least the undercut limit L1 = {l1:.5g} m (the face gear is undercut below it){usable}")
    check(spec.outer_radius <= l2, block.key_path("outer_radius"), spec.outer_radius,
          f"at most the pointing limit L2 = {l2:.5g} m (the face-gear teeth are pointed beyond it){usable}")
    if lowest < spec.inner_radius or highest > spec.outer_radius:
        key = block.key_path("inner_radius" if lowest < spec.inner_radius else "outer_radius")
        value = spec.inner_radius if lowest < spec.inner_radius else spec.outer_radius
        raise CaseError(key, value, f"a face width covering the contact path, at face-gear radii "
                        f"{lowest:.5g} to {highest:.5g} m")
