"""Tooth contact analysis of the pinion / face-gear mesh: the contact path and the meshing points S1..S5.

Frames and conventions as in `geometry` (docs/method.md §1.1, §1.3). The pinion drives clockwise (about -k):
its rotation from the pitch position is phi_1 (right hand about its axis), and the path coordinate is
s = -r_b1 phi_1, the pinion roll distance, positive toward the pinion tip (later in the mesh).

Aligned drive (docs/method.md §1.3, exact): the contact point runs along the pinion's transverse line of
action, Q(s) = P + s t_LA, with phi_2 = phi_1 N1/N2 (no transmission error).

General TCA (docs/method.md §1.3): for a pinion angle phi_1 solve five equations in
x = (theta_1, u_1, theta_s, phi_s, phi_2):

    M_1 r_1(theta_1, u_1; phi_1) = Rot(a_2, -phi_2) r_2(theta_s, phi_s) + dq a_2     (3, positions)
    n_2f . a_1 = 0,   n_2f . (a_1 x n_1f) = 0                                          (2, normals)

where M_1 places the pinion: turned about the y axis through its apex O_1 by -d_gamma (so the shaft
angle becomes g + d_gamma), offset by dE along y and shifted by dA along its own axis; the face gear is
shifted by dq along a_2. The face gear enters through its explicit (theta_s, phi_s) form, so the
shaper / face-gear equation of meshing needs no sixth equation. Newton with the analytic Jacobian;
the derivative of the solution along the path follows from the same Jacobian (implicit function theorem).
Transmission error TE = -(phi_2 - phi_1 N1/N2): rotations counted in the direction of motion, positive
when the face gear leads. (The misalignment table of docs/accuracy.md lists TE for a pinion turned by +d
about y, i.e. our shaft_angle_error = -d.)
"""

from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from facegear_tehl.gears.geometry import (
    K_AXIS,
    Y_AXIS,
    PairGeometry,
    axial_section,
    face_gear_jet,
    involute_point,
    profile_normal,
    profile_tangent,
    rotation,
)
from facegear_tehl.roots import brentq

MESHING_POINTS = ("S1", "S2", "S3", "S4", "S5")
_NEWTON_TOLERANCE = 1e-15  # relative step size at which Newton stops (machine precision of positions ~ 0.5 m)
_NEWTON_ITERATIONS = 30
_HOMOTOPY_STEPS = 8  # misalignment is switched on in this many steps from the aligned solution


class ContactError(ValueError):
    """The tooth contact analysis found no contact (misalignment too large, or a degenerate drive)."""


@dataclass(frozen=True)
class Misalignment:
    """Assembly errors: shaft angle error (rad), offset along y, pinion and face-gear axial shifts (m)."""

    shaft_angle_error: float = 0.0  # d_gamma: actual shaft angle g + d_gamma
    offset: float = 0.0  # dE: pinion axis moved along y (the axes no longer intersect)
    pinion_axial_shift: float = 0.0  # dA: pinion moved along its own axis
    face_gear_axial_shift: float = 0.0  # dq: face gear moved along a_2

    @property
    def is_zero(self) -> bool:
        return not any((self.shaft_angle_error, self.offset, self.pinion_axial_shift, self.face_gear_axial_shift))

    def scaled(self, factor: float) -> Misalignment:
        return Misalignment(
            self.shaft_angle_error * factor,
            self.offset * factor,
            self.pinion_axial_shift * factor,
            self.face_gear_axial_shift * factor,
        )


ALIGNED = Misalignment()  # no assembly error


@dataclass(frozen=True)
class ContactState:
    """The pinion / face-gear contact at one pinion angle (fixed frame, SI units, rad).

    point: contact point Q; normal: common unit normal, out of the pinion into the face gear.
    pinion_axis, pinion_centre: a_1 and a point of it; theta_1, u_1: pinion flank parameters.
    theta_s, phi_s: face-gear surface parameters; phi_2: face-gear rotation (mesh); phi_1: pinion rotation.
    face_gear_turn: rotation from the generation frame of (theta_s, phi_s) to the fixed frame,
        Rot(a_2, q phi_s - phi_2) (identity for the aligned drive).
    point_rate: dQ/dphi_1, m/rad; ratio: dphi_2/dphi_1.
    """

    s: float
    phi_1: float
    point: np.ndarray
    normal: np.ndarray
    pinion_axis: np.ndarray
    pinion_centre: np.ndarray
    theta_1: float
    u_1: float
    theta_s: float
    phi_s: float
    phi_2: float
    face_gear_turn: np.ndarray
    point_rate: np.ndarray
    ratio: float
    face_gear_origin: np.ndarray  # a point of the face-gear axis (O + dq a_2)
    rho_1: float  # pinion profile radius of curvature r_b1 theta_1, m

    def transmission_error(self, geo: PairGeometry) -> float:
        """TE = -(phi_2 - phi_1 N1/N2), rad: angles counted in the direction of motion, TE > 0 when the
        face gear leads its ideal position."""
        return -(self.phi_2 - self.phi_1 * geo.pinion_teeth / geo.face_gear_teeth)

    @property
    def unknowns(self) -> np.ndarray:
        return np.array([self.theta_1, self.u_1, self.theta_s, self.phi_s, self.phi_2])


def aligned_state(geo: PairGeometry, s: float) -> ContactState:
    """Semi-analytic contact at path coordinate s (docs/method.md §1.3): Q = P + s t_LA, TE = 0."""
    alpha = geo.pressure_angle
    t_la = geo.line_of_action
    rho_1 = geo.r_p1 * math.sin(alpha) + s
    phi_1 = -s / geo.r_b1
    phi_s = -s / geo.r_bs
    return ContactState(
        s=s,
        phi_1=phi_1,
        point=geo.pitch_point + s * t_la,
        normal=t_la,
        pinion_axis=K_AXIS,
        pinion_centre=geo.pinion_centre,
        theta_1=rho_1 / geo.r_b1,
        u_1=geo.z_P,
        theta_s=math.tan(alpha) + s / geo.r_bs,
        phi_s=phi_s,
        phi_2=geo.q * phi_s,
        face_gear_turn=np.eye(3),
        point_rate=-geo.r_b1 * t_la,
        ratio=geo.pinion_teeth / geo.face_gear_teeth,
        face_gear_origin=np.zeros(3),
        rho_1=rho_1,
    )


@dataclass(frozen=True)
class _Placement:
    """Pinion placement x_f = rot x + shift; face-gear origin shift dq a_2."""

    rot: np.ndarray
    shift: np.ndarray
    axis: np.ndarray
    face_gear_origin: np.ndarray


def _placement(geo: PairGeometry, mis: Misalignment) -> _Placement:
    rot = rotation(Y_AXIS, -mis.shaft_angle_error)
    axis = rot @ K_AXIS
    apex = geo.pinion_apex
    shift = apex - rot @ apex + mis.offset * Y_AXIS + mis.pinion_axial_shift * axis
    return _Placement(rot=rot, shift=shift, axis=axis, face_gear_origin=mis.face_gear_axial_shift * geo.a2)


@dataclass(frozen=True)
class _System:
    """The five TCA equations at one (x, phi_1): residual F, Jacobian dF/dx, dF/dphi_1, and the pinion side."""

    residual: np.ndarray
    jacobian: np.ndarray
    d_phi1: np.ndarray
    pinion_point: np.ndarray
    pinion_normal: np.ndarray
    pinion_centre: np.ndarray
    face_gear_turn: np.ndarray

    def unknowns_rate(self) -> np.ndarray:
        """dx/dphi_1 = -J^-1 dF/dphi_1 (implicit function theorem)."""
        return -np.linalg.solve(self.jacobian, self.d_phi1)


def _equations(geo: PairGeometry, place: _Placement, phi_1: float, x: np.ndarray) -> _System:
    """The TCA system at the unknowns x for the pinion angle phi_1 (module docstring)."""
    theta_1, u_1, theta_s, phi_s, phi_2 = x
    rb1, q, a2, axis = geo.r_b1, geo.q, geo.a2, place.axis
    # Pinion flank (geometry module docstring), placed by M_1.
    a1 = geo.mu + theta_1 + phi_1
    local = geo.pinion_centre + involute_point(rb1, theta_1, a1) + u_1 * K_AXIS
    r1 = place.rot @ local + place.shift
    n1 = place.rot @ profile_normal(a1)
    ep1 = np.cross(axis, n1)
    centre = place.rot @ geo.pinion_centre + place.shift
    # Face gear in the fixed frame: G X(theta_s, a_s) + dq a_2, G = Rot(a_2, q phi_s - phi_2).
    a_s = geo.mu + theta_s + phi_s
    turn = rotation(a2, q * phi_s - phi_2)
    jet = face_gear_jet(geo, theta_s, phi_s)  # generation frame: r_p includes the face-gear turn q a_2 x X
    GX = turn @ jet.point
    r2 = GX + place.face_gear_origin
    n2 = turn @ jet.normal
    Gep = turn @ profile_tangent(a_s)  # d n_s / d a, turned

    residual = np.concatenate([r1 - r2, [n2 @ axis, n2 @ ep1]])
    jac = np.zeros((5, 5))
    jac[:3, 0] = rb1 * theta_1 * ep1
    jac[4, 0] = -(n2 @ n1)  # d ep1/d theta_1 = axis x ep1 = -n1
    jac[:3, 1] = axis
    jac[:3, 2] = -(turn @ jet.r_t)
    jac[3, 2], jac[4, 2] = Gep @ axis, Gep @ ep1
    dn2_dphis = Gep + q * np.cross(a2, n2)
    jac[:3, 3] = -(turn @ jet.r_p)
    jac[3, 3], jac[4, 3] = dn2_dphis @ axis, dn2_dphis @ ep1
    dn2_dphi2 = -np.cross(a2, n2)
    jac[:3, 4] = np.cross(a2, GX)
    jac[3, 4], jac[4, 4] = dn2_dphi2 @ axis, dn2_dphi2 @ ep1
    d_phi1 = np.concatenate([np.cross(axis, r1 - centre), [0.0, -(n2 @ n1)]])
    return _System(residual, jac, d_phi1, r1, n1, centre, turn)


def solve_contact(
    geo: PairGeometry, phi_1: float, guess: np.ndarray, mis: Misalignment = ALIGNED
) -> ContactState:
    """General TCA at pinion angle phi_1 (rad) by Newton from `guess` = (theta_1, u_1, theta_s, phi_s, phi_2)."""
    place = _placement(geo, mis)
    x = np.array(guess, dtype=float)
    scale = np.array([1.0, geo.z_P, 1.0, 1.0, 1.0])
    for _ in range(_NEWTON_ITERATIONS):
        system = _equations(geo, place, phi_1, x)
        step = np.linalg.solve(system.jacobian, -system.residual)
        x = x + step
        if np.max(np.abs(step) / scale) < _NEWTON_TOLERANCE:
            break
    system = _equations(geo, place, phi_1, x)
    residual = system.residual
    if (not np.all(np.isfinite(x)) or np.max(np.abs(residual[:3])) > 1e-9 * geo.z_P
            or np.max(np.abs(residual[3:])) > 1e-9):
        raise ContactError(f"no pinion / face-gear contact found at phi_1 = {phi_1:.6g} rad")
    rate = system.unknowns_rate()
    r1, n1, axis = system.pinion_point, system.pinion_normal, place.axis
    # dQ/dphi_1: rotation of the pinion point plus its motion over the flank (d theta_1, d u_1).
    point_rate = (np.cross(axis, r1 - system.pinion_centre) + geo.r_b1 * x[0] * np.cross(axis, n1) * rate[0]
                  + axis * rate[1])
    return ContactState(
        s=-geo.r_b1 * phi_1,
        phi_1=phi_1,
        point=r1,
        normal=n1,
        pinion_axis=axis,
        pinion_centre=system.pinion_centre,
        theta_1=float(x[0]),
        u_1=float(x[1]),
        theta_s=float(x[2]),
        phi_s=float(x[3]),
        phi_2=float(x[4]),
        face_gear_turn=system.face_gear_turn,
        point_rate=point_rate,
        ratio=float(rate[4]),
        face_gear_origin=place.face_gear_origin,
        rho_1=geo.r_b1 * float(x[0]),
    )


class ContactPath:
    """Contact states along the path for one assembly: semi-analytic when aligned, general TCA otherwise.

    The misaligned pitch-position contact is reached by switching the misalignment on in steps from the
    aligned solution; other states start from it with a first-order predictor.
    """

    def __init__(self, geo: PairGeometry, mis: Misalignment = ALIGNED):
        self.geo = geo
        self.mis = mis
        if mis.is_zero:
            self._reference = aligned_state(geo, 0.0)
        else:
            state = aligned_state(geo, 0.0)
            for step in range(1, _HOMOTOPY_STEPS + 1):
                state = solve_contact(geo, 0.0, state.unknowns, mis.scaled(step / _HOMOTOPY_STEPS))
            self._reference = state
            self._reference_rate = _equations(geo, _placement(geo, mis), 0.0, state.unknowns).unknowns_rate()

    def state(self, s: float) -> ContactState:
        """Contact at path coordinate s (m)."""
        if self.mis.is_zero:
            return aligned_state(self.geo, s)
        phi_1 = -s / self.geo.r_b1
        guess = self._reference.unknowns + self._reference_rate * phi_1
        return solve_contact(self.geo, phi_1, guess, self.mis)

    def limits(self) -> tuple[float, float]:
        """(s_min, s_max): face-gear top land reaches the contact (pinion root side) and pinion tip, m."""
        geo = self.geo
        rho_tip = math.sqrt(geo.r_a1**2 - geo.r_b1**2)
        span = 4.0 * geo.module / math.sin(geo.pressure_angle)

        def tip_excess(s: float) -> float:
            return self.state(s).rho_1 - rho_tip

        def depth_excess(s: float) -> float:
            state = self.state(s)
            return axial_section(geo, state.point - state.face_gear_origin)[0] - geo.tip_depth

        if self.mis.is_zero:
            s_max = rho_tip - geo.r_p1 * math.sin(geo.pressure_angle)
        else:
            s_max = brentq(tip_excess, 0.0, span, xtol=1e-14)
        s_min = brentq(depth_excess, -span, 0.0, xtol=1e-14)
        return s_min, s_max


def meshing_points(s_min: float, s_max: float, base_pitch: float) -> dict[str, float]:
    """S1..S5 by definition (docs/method.md §1.6): s_min, s_max - p_b, 0, s_min + p_b, s_max."""
    return {
        "S1": s_min,
        "S2": s_max - base_pitch,
        "S3": 0.0,
        "S4": s_min + base_pitch,
        "S5": s_max,
    }


def order_warnings(points: dict[str, float]) -> tuple[str, ...]:
    """Messages when S1 < S2 <= S3 <= S4 < S5 fails (e.g. the pitch point in a double-tooth zone)."""
    values = [points[name] for name in MESHING_POINTS]
    messages = []
    for (name_a, a), (name_b, b) in zip(zip(MESHING_POINTS, values), zip(MESHING_POINTS[1:], values[1:])):
        if a > b:
            messages.append(
                f"{name_b} (s = {b * 1e3:.3f} mm) lies before {name_a} (s = {a * 1e3:.3f} mm): "
                "the pitch point is not in the single-tooth zone"
            )
    return tuple(messages)
