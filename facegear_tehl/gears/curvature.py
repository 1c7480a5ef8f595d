"""Curvatures of the pinion and face-gear tooth surfaces and their relative curvature (SI units, 1/m).

Sign convention (docs/method.md §1.5): one unit normal n for all surfaces, out of the pinion / shaper and into
the face gear; shape operator S from dn = -S dr, so the normal curvature along a unit tangent t is
t.S t = II/I with II_ij = r_ij . n. Then -S_1 and S_2 are the curvatures of pinion and face gear taken
positive where the body is convex, and the relative curvature is K_rel = S_2 - S_1.

Two independent routes give the face-gear shape operator, both with analytic derivatives (no finite
differences: the lengthwise relative curvature comes from a near-cancellation):
(a) `shape_operator_forms`: fundamental forms of the explicit surface r_2(theta_s, phi_s);
(b) `shape_operator_direct`: Litvin's direct relation S_2 = S_s - w w^T / D (geometry.GenerationContact).
`closed_form_relative_curvature` is the closed form along the aligned path (docs/method.md §1.5), a check.
"""

from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from facegear_tehl.gears.geometry import PairGeometry, face_gear_jet, generation_contact
from facegear_tehl.gears.tca import ContactState


def shape_operator_forms(geo: PairGeometry, theta_s: float, phi_s: float) -> np.ndarray:
    """Face-gear shape operator (3x3 tangent tensor, generation frame) from the fundamental forms, 1/m.

    I = [[r_t.r_t, r_t.r_p], [., r_p.r_p]],  II = [[r_tt.n, r_tp.n], [., r_pp.n]],
    S = T I^-1 II I^-1 T^T with T = [r_t r_p] (the Weingarten map I^-1 II pushed to 3-D).
    """
    jet = face_gear_jet(geo, theta_s, phi_s)
    tangents = np.column_stack([jet.r_t, jet.r_p])
    first = tangents.T @ tangents
    n = jet.normal
    second = np.array([[jet.r_tt @ n, jet.r_tp @ n], [jet.r_tp @ n, jet.r_pp @ n]])
    inverse = np.linalg.inv(first)
    return tangents @ inverse @ second @ inverse @ tangents.T


def shape_operator_direct(geo: PairGeometry, theta_s: float, phi_s: float) -> np.ndarray:
    """Face-gear shape operator (3x3, generation frame) by Litvin's direct relation, 1/m:
    S_2 = S_s - w w^T / D, with the shaper's S_s = -(1/rho_s) e_p e_p^T (docs/method.md §1.5)."""
    gen = generation_contact(geo, theta_s, geo.mu + theta_s + phi_s)
    return -np.outer(gen.profile, gen.profile) / gen.rho - np.outer(gen.w, gen.w) / gen.D


def closed_form_relative_curvature(geo: PairGeometry, s: float) -> tuple[np.ndarray, np.ndarray]:
    """(S_2, K_rel) as 2x2 matrices in the basis (e_p, k) at path coordinate s of the aligned drive, 1/m.

    Closed form (docs/method.md §1.5): w_p = c r_ps sin(alpha)/rho_s, w_k = -q sin g cos(alpha),
    D = -c r_ps sin(alpha) + s [c^2 r_ps sin(alpha)/rho_s + q^2 sin^2 g cos^2 alpha],
    S_2 = [[-1/rho_s - w_p^2/D, -w_p w_k/D], [., -w_k^2/D]],  K_rel = S_2 + diag(1/rho_1, 0).
    """
    alpha, g, q, c = geo.pressure_angle, geo.shaft_angle, geo.q, geo.c
    rho_1 = geo.r_p1 * math.sin(alpha) + s
    rho_s = geo.r_ps * math.sin(alpha) + s
    w_p = c * geo.r_ps * math.sin(alpha) / rho_s
    w_k = -q * math.sin(g) * math.cos(alpha)
    D = -c * geo.r_ps * math.sin(alpha) + s * (
        c * c * geo.r_ps * math.sin(alpha) / rho_s + (q * math.sin(g) * math.cos(alpha)) ** 2
    )
    face_gear = np.array([[-1.0 / rho_s - w_p * w_p / D, -w_p * w_k / D], [-w_p * w_k / D, -w_k * w_k / D]])
    return face_gear, face_gear + np.diag([1.0 / rho_1, 0.0])


def pinion_shape_operator(state: ContactState) -> np.ndarray:
    """Pinion (involute cylinder) shape operator S_1 = -(1/rho_1) e_p e_p^T, fixed frame, 1/m."""
    ep = np.cross(state.pinion_axis, state.normal)
    return -np.outer(ep, ep) / state.rho_1


def face_gear_shape_operator(geo: PairGeometry, state: ContactState, direct: bool = False) -> np.ndarray:
    """Face-gear shape operator at the contact, turned into the fixed frame (route (a), or (b) if direct)."""
    route = shape_operator_direct if direct else shape_operator_forms
    turn = state.face_gear_turn
    return turn @ route(geo, state.theta_s, state.phi_s) @ turn.T


@dataclass(frozen=True)
class PrincipalCurvature:
    """Principal values (kappa_max >= kappa_min) and the unit direction of kappa_max of a 2x2 tangent tensor,
    given in the orthonormal tangent basis (e_1, e_2); the kappa_min direction is n x (kappa_max direction)."""

    kappa_max: float  # 1/m
    kappa_min: float  # 1/m
    direction_max: np.ndarray  # 3-D unit vector
    angle: float  # angle of direction_max from e_1 toward e_2, rad, in (-pi/2, pi/2]


def principal_curvatures(tensor: np.ndarray, e_1: np.ndarray, e_2: np.ndarray) -> PrincipalCurvature:
    """Eigen-decomposition of the symmetric tangent tensor projected on (e_1, e_2).

    kappa_max = tr/2 + sqrt(((k11 - k22)/2)^2 + k12^2), kappa_min = det/kappa_max (no cancellation when
    kappa_min << kappa_max), angle = atan2(2 k12, k11 - k22)/2.
    """
    k11, k12, k22 = e_1 @ tensor @ e_1, e_1 @ tensor @ e_2, e_2 @ tensor @ e_2
    half_diff = 0.5 * (k11 - k22)
    radius = math.hypot(half_diff, k12)
    mean = 0.5 * (k11 + k22)
    det = k11 * k22 - k12 * k12
    if mean >= 0.0:
        kappa_max = mean + radius
        kappa_min = det / kappa_max if kappa_max != 0.0 else mean - radius
    else:
        kappa_min = mean - radius
        kappa_max = det / kappa_min
    angle = 0.5 * math.atan2(2.0 * k12, k11 - k22)
    return PrincipalCurvature(
        kappa_max=float(kappa_max),
        kappa_min=float(kappa_min),
        direction_max=math.cos(angle) * e_1 + math.sin(angle) * e_2,
        angle=angle,
    )
