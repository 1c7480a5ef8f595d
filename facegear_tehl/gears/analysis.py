"""Contact analysis of a face gear pair: everything the EHL solver needs along the path and at each point.

`analyse_gear_pair` samples the whole path s in [s_min, s_max] and evaluates the requested meshing points.
Each sample: contact state (semi-analytic, or general TCA under misalignment), curvatures (face gear by
the fundamental forms, checked against Litvin's direct relation), velocities, load share and exact Hertz.

Contact frame of every sample (as `contact.ContactPoint` expects): x along the minor axis of the Hertz
ellipse (direction of the larger relative curvature), oriented so that the entrainment U_e . x > 0;
y = n x x along the major axis, with n the common normal out of the pinion (body 1) into the face gear
(body 2). The entrainment keeps its true angle psi_e to the minor axis (oblique entrainment).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields
import math
from types import MappingProxyType

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.gears.curvature import (
    face_gear_shape_operator,
    pinion_shape_operator,
    principal_curvatures,
)
from facegear_tehl.gears.geometry import PairGeometry, axial_section, pointing_limit, undercut_limit
from facegear_tehl.gears.kinematics import surface_velocities
from facegear_tehl.gears.loads import contact_ratio, interpolated_share, load_share, normal_load
from facegear_tehl.gears.spec import GearSpec
from facegear_tehl.gears.tca import ContactPath, ContactState, meshing_points, order_warnings
from facegear_tehl.hertz import hertz_contact
from facegear_tehl.materials import Solid, reduced_modulus

PATH_UNITS = MappingProxyType(
    {
        "s": "m",  # path coordinate (pinion roll distance from the pitch position, + toward the pinion tip)
        "contact_point": "m",  # (n, 3) fixed frame
        "face_gear_radius": "m",
        "pinion_profile_radius": "m",  # rho_1
        "Rx": "m",
        "Ry": "m",
        "pinion_curvature": "1/m",  # 1/rho_1 along the profile (convex positive; 0 along the axis)
        "face_gear_curvature_1": "1/m",  # principal curvatures of the face gear, convex positive, 1 >= 2
        "face_gear_curvature_2": "1/m",
        "ellipse_angle": "deg",  # major axis from the pinion axis, positive toward the pinion tip
        "load_share": "1",
        "load": "N",
        "u1": "m/s",  # (n, 2) pinion surface velocity relative to the contact, (x, y) contact frame
        "u2": "m/s",  # (n, 2) face-gear surface velocity
        "entrainment": "m/s",  # (n, 2)
        "sliding": "m/s",  # (n, 2)
        "entrainment_speed": "m/s",
        "sliding_speed": "m/s",
        "srr": "1",  # |V_s|/|U_e|, signed by V_s . U_e
        "entrainment_angle": "deg",  # psi_e, U_e from the minor (x) axis
        "a": "m",  # Hertz major semi-axis
        "b": "m",  # Hertz minor semi-axis
        "ellipticity": "1",  # a/b
        "p_h": "Pa",  # maximum Hertz pressure
        "transmission_error": "rad",
    }
)
PATH_DESCRIPTIONS = MappingProxyType(
    {
        "s": "path coordinate: pinion roll distance from the pitch position, positive toward the pinion tip",
        "contact_point": "contact point (X, Y, Z) in the fixed frame",
        "face_gear_radius": "radius of the contact point on the face gear",
        "pinion_profile_radius": "involute profile radius of curvature of the pinion, rho_1",
        "Rx": "reduced radius of curvature along the minor axis x of the contact ellipse",
        "Ry": "reduced radius of curvature along the major axis y of the contact ellipse",
        "pinion_curvature": "pinion curvature along its profile, 1/rho_1 (convex positive; 0 along the axis)",
        "face_gear_curvature_1": "larger principal curvature of the face gear (convex positive)",
        "face_gear_curvature_2": "smaller principal curvature of the face gear (convex positive)",
        "ellipse_angle": "major axis of the contact ellipse from the pinion axis, positive toward the pinion tip",
        "load_share": "share of the normal load carried by this tooth pair",
        "load": "normal load on this tooth pair",
        "u1": "pinion surface velocity relative to the contact, (x, y) of the contact frame",
        "u2": "face-gear surface velocity relative to the contact, (x, y) of the contact frame",
        "entrainment": "entrainment velocity U_e = (u1 + u2)/2, (x, y) of the contact frame",
        "sliding": "sliding velocity V_s = u1 - u2, (x, y) of the contact frame",
        "entrainment_speed": "entrainment speed |U_e|",
        "sliding_speed": "sliding speed |V_s|",
        "srr": "slide-to-roll ratio |V_s|/|U_e|, signed by V_s . U_e (positive: the pinion surface is faster)",
        "entrainment_angle": "angle psi_e of the entrainment velocity from the minor (x) axis",
        "a": "Hertz semi-axis along the major axis y",
        "b": "Hertz semi-axis along the minor axis x",
        "ellipticity": "Hertz ellipticity a/b",
        "p_h": "maximum Hertz pressure",
        "transmission_error": "transmission error -(phi_2 - phi_1 N1/N2), positive when the face gear leads its ideal "
                              "position",
    }
)
"""A one-line description of each quantity of PATH_UNITS (the result file's /contact datasets)."""


@dataclass(frozen=True)
class GearContactAnalysis:
    """Result of `analyse_gear_pair`: path samples, meshing points and scalar geometry (SI units).

    path[name] and point_values[name] hold the quantities of PATH_UNITS along the path and at the points.
    """

    spec: GearSpec
    path: Mapping[str, np.ndarray]
    point_values: Mapping[str, np.ndarray]
    points: tuple[ContactPoint, ...]
    pinion_base_radius: float = field(metadata={"unit": "m"})
    pitch_point_height: float = field(metadata={"unit": "m"})  # z_P
    face_gear_pitch_radius: float = field(metadata={"unit": "m"})  # L0
    undercut_limit: float = field(metadata={"unit": "m"})  # L1
    pointing_limit: float = field(metadata={"unit": "m"})  # L2
    path_start: float = field(metadata={"unit": "m"})  # s_min
    path_end: float = field(metadata={"unit": "m"})  # s_max
    base_pitch: float = field(metadata={"unit": "m"})
    contact_ratio: float = field(metadata={"unit": "1"})
    normal_load: float = field(metadata={"unit": "N"})  # F_n = T1/r_b1
    pinion_cone_angle: float = field(metadata={"unit": "deg"})  # delta_1
    face_gear_cone_angle: float = field(metadata={"unit": "deg"})  # delta_2
    transmission_error: float = field(metadata={"unit": "rad"})  # mean over the path
    curvature_check: float = field(metadata={"unit": "1"})  # max relative gap between the two curvature routes
    warnings: tuple[str, ...] = ()

    @property
    def units(self) -> Mapping[str, str]:
        return PATH_UNITS

    def scalars(self) -> dict[str, tuple[float, str]]:
        """Scalar geometry as {name: (value, unit)}."""
        return {f.name: (getattr(self, f.name), f.metadata["unit"]) for f in fields(self) if "unit" in f.metadata}


def analyse_gear_pair(spec: GearSpec, body_1: Solid, body_2: Solid, n_path: int = 101) -> GearContactAnalysis:
    """Contact analysis of `spec` with the pinion `body_1` and the face gear `body_2` (see the module docstring)."""
    geo = spec.geometry
    contact_path = ContactPath(geo, spec.misalignment)
    s_min, s_max = contact_path.limits()
    p_b = geo.base_pitch
    names = spec.point_names
    if isinstance(spec.points, int):
        point_s = np.linspace(s_min, s_max, spec.points)
    else:
        s_of = meshing_points(s_min, s_max, p_b)
        point_s = np.array([s_of[name] for name in names])
    path_s = np.linspace(s_min, s_max, n_path)
    if isinstance(spec.load_sharing, str):
        path_share = load_share(spec.load_sharing, path_s, s_min, s_max, p_b, spec.transition_side)
        point_share = load_share(spec.load_sharing, point_s, s_min, s_max, p_b, spec.transition_side)
    else:
        path_share = interpolated_share(path_s, point_s, spec.load_sharing)
        point_share = np.array(spec.load_sharing)
    f_n = normal_load(geo, spec.pinion_torque)
    e_reduced = reduced_modulus(body_1, body_2)
    path, route_gap = _sample(geo, contact_path, spec.pinion_speed, path_s, path_share * f_n, path_share, e_reduced)
    values, _ = _sample(geo, contact_path, spec.pinion_speed, point_s, point_share * f_n, point_share, e_reduced)
    points = tuple(
        ContactPoint(
            name=name,
            radius_x=float(values["Rx"][i]),
            radius_y=float(values["Ry"][i]),
            load=float(values["load"][i]),
            velocity_1=(float(values["u1"][i, 0]), float(values["u1"][i, 1])),
            velocity_2=(float(values["u2"][i, 0]), float(values["u2"][i, 1])),
            body_1=body_1,
            body_2=body_2,
            path_coordinate=float(point_s[i]),
            rotation_radius_1=math.hypot(geo.r_b1, float(values["pinion_profile_radius"][i])),
            rotation_radius_2=float(values["face_gear_radius"][i]),
        )
        for i, name in enumerate(names)
    )
    return GearContactAnalysis(
        spec=spec,
        path=path,
        point_values=values,
        points=points,
        pinion_base_radius=geo.r_b1,
        pitch_point_height=geo.z_P,
        face_gear_pitch_radius=geo.L0,
        undercut_limit=undercut_limit(geo),
        pointing_limit=pointing_limit(geo),
        path_start=s_min,
        path_end=s_max,
        base_pitch=p_b,
        contact_ratio=contact_ratio(s_min, s_max, p_b),
        normal_load=f_n,
        pinion_cone_angle=math.degrees(geo.delta_1),
        face_gear_cone_angle=math.degrees(geo.delta_2),
        transmission_error=float(np.mean(path["transmission_error"])),
        curvature_check=route_gap,
        warnings=_warnings(spec, points, meshing_points(s_min, s_max, p_b)),
    )


def _warnings(spec: GearSpec, points: tuple[ContactPoint, ...], s_points: dict[str, float]) -> tuple[str, ...]:
    """The analysis's warnings: the S-points out of order (where they are solved), ellipses past the face width."""
    return (() if isinstance(spec.points, int) else order_warnings(s_points)) + tuple(edge_warnings(spec, points))


def edge_warnings(spec: GearSpec, points: tuple[ContactPoint, ...]) -> list[str]:
    """A message per point whose Hertzian ellipse, its major axis lengthwise along the face-gear tooth (Litvin & Fuentes
    2004, the contact ellipse of a localized bearing contact), reaches past the face width [inner_radius,
    outer_radius] about its face-gear radius: the ellipse and the film solved over it assume the tooth goes on."""
    messages = []
    for point in points:
        a, radius = point.hertz.a, point.rotation_radius_2
        past = max(spec.inner_radius - (radius - a), (radius + a) - spec.outer_radius)
        if past > 0.0:
            messages.append(f"{point.name}: its contact ellipse (major semi-axis a = {a * 1e3:.3g} mm, lengthwise) "
                            f"about face-gear radius {radius * 1e3:.4g} mm reaches {past * 1e3:.2g} mm past the face "
                            f"width [{spec.inner_radius * 1e3:.4g}, {spec.outer_radius * 1e3:.4g}] mm: the edge "
                            "contact there is not modelled (the ellipse and its film assume the tooth goes on)")
    return messages


def _sample(
    geo: PairGeometry,
    contact_path: ContactPath,
    pinion_speed: float,
    s_values: np.ndarray,
    loads: np.ndarray,
    shares: np.ndarray,
    e_reduced: float,
) -> tuple[Mapping[str, np.ndarray], float]:
    """All PATH_UNITS quantities at the path coordinates s_values; also the largest relative difference
    between the face-gear shape operators of the two curvature routes."""
    rows: dict[str, list] = {name: [] for name in PATH_UNITS}
    route_gap = 0.0
    for s, load, share in zip(s_values, loads, shares):
        state = contact_path.state(float(s))
        face_gear = face_gear_shape_operator(geo, state)
        direct = face_gear_shape_operator(geo, state, direct=True)
        route_gap = max(route_gap, float(np.max(np.abs(face_gear - direct)) / np.max(np.abs(face_gear))))
        values = _point_values(geo, state, face_gear, pinion_speed, float(load), e_reduced)
        values.update({"s": float(s), "load_share": float(share), "load": float(load)})
        for name, value in values.items():
            rows[name].append(value)
    table = {}
    for name, column in rows.items():
        array = np.array(column, dtype=float)
        array.setflags(write=False)
        table[name] = array
    return MappingProxyType(table), route_gap


def _point_values(geo: PairGeometry, state: ContactState, face_gear: np.ndarray, pinion_speed: float, load: float,
                  e_reduced: float) -> dict[str, object]:
    """The PATH_UNITS quantities of one contact state but its s, load share and load: the contact frame (x along
    the relative curvature's largest principal direction, against the entrainment's sign), curvatures, surface
    velocities in that frame and the Hertz contact under `load` (N) for the reduced modulus `e_reduced` (Pa)."""
    n, axis = state.normal, state.pinion_axis
    profile = np.cross(axis, n)
    relative = principal_curvatures(face_gear - pinion_shape_operator(state), profile, axis)
    own = principal_curvatures(face_gear, profile, axis)
    velocities = surface_velocities(geo, state, pinion_speed)
    x = relative.direction_max
    if velocities.entrainment @ x < 0.0:
        x = -x
    y = np.cross(n, x)
    major = y if y @ axis >= 0.0 else -y
    u1 = np.array([velocities.pinion @ x, velocities.pinion @ y])
    u2 = np.array([velocities.face_gear @ x, velocities.face_gear @ y])
    entrainment, sliding = 0.5 * (u1 + u2), u1 - u2
    radius_x, radius_y = 1.0 / relative.kappa_max, 1.0 / relative.kappa_min
    hertz = hertz_contact(radius_x, radius_y, load, e_reduced)
    speed_e, speed_s = float(np.hypot(*entrainment)), float(np.hypot(*sliding))
    return {
        "contact_point": state.point,
        "face_gear_radius": axial_section(geo, state.point - state.face_gear_origin)[1],
        "pinion_profile_radius": state.rho_1,
        "Rx": radius_x,
        "Ry": radius_y,
        "pinion_curvature": 1.0 / state.rho_1,
        "face_gear_curvature_1": own.kappa_max,
        "face_gear_curvature_2": own.kappa_min,
        "ellipse_angle": math.degrees(math.atan2(major @ profile, major @ axis)),
        "u1": u1,
        "u2": u2,
        "entrainment": entrainment,
        "sliding": sliding,
        "entrainment_speed": speed_e,
        "sliding_speed": speed_s,
        "srr": math.copysign(speed_s / speed_e, float(sliding @ entrainment)),
        "entrainment_angle": math.degrees(math.atan2(entrainment[1], entrainment[0])),
        "a": hertz.a,
        "b": hertz.b,
        "ellipticity": hertz.ellipticity,
        "p_h": hertz.p_max,
        "transmission_error": state.transmission_error(geo),
    }
