"""Invariants of the gear contact analysis (docs/method.md §1), one test (or a few) per item, checked against
closed forms and geometry."""

from __future__ import annotations

import math

from hypothesis import given, settings
from hypothesis import strategies as st
import numpy as np
import pytest

from facegear_tehl.gears.curvature import (
    closed_form_relative_curvature,
    face_gear_shape_operator,
    pinion_shape_operator,
    principal_curvatures,
    shape_operator_direct,
    shape_operator_forms,
)
from facegear_tehl.gears.geometry import (
    K_AXIS,
    face_gear_jet,
    generating_point,
    pointing_limit,
    profile_normal,
    undercut_limit,
)
from facegear_tehl.gears.kinematics import surface_velocities
from facegear_tehl.gears.tca import ContactPath, aligned_state
from facegear_tehl.hertz import hertz_contact
from facegear_tehl.materials import reduced_modulus

from gear_examples import EXAMPLE_A, EXAMPLE_B, MM, STEEL, analysis, assert_reference, pair

W1 = 3000.0 * 2 * math.pi / 60  # rad/s, example A pinion speed
GEARS = {
    "A110": pair(EXAMPLE_A),
    "A90": pair(EXAMPLE_A, shaft_angle=90.0),
    "A70": pair(EXAMPLE_A, shaft_angle=70.0),
    "B": pair(EXAMPLE_B),
}


def _path(geo, count=9):
    s_min, s_max = ContactPath(geo).limits()
    return np.linspace(s_min, s_max, count)


def _tangent_matrix(tensor, state):
    """A 3x3 tangent tensor as a 2x2 matrix in the basis (e_p, k) of the pinion."""
    basis = np.column_stack([np.cross(state.pinion_axis, state.normal), state.pinion_axis])
    return basis.T @ tensor @ basis


# 1. Pure rolling at the pitch point.
def test_pitch_point_pure_rolling():
    geo = GEARS["A110"]
    velocity = surface_velocities(geo, aligned_state(geo, 0.0), W1)
    entrainment = np.linalg.norm(velocity.entrainment)
    assert np.linalg.norm(velocity.sliding) < 1e-9 * entrainment
    expected = W1 * geo.r_p1 * math.sin(geo.pressure_angle)
    assert entrainment == pytest.approx(expected, rel=1e-12)
    assert_reference(entrainment, "10.5386")


# 2. Relative velocities are tangent: n . v_(12) = 0 on the path, n . v_(s2) = 0 on the generated surface.
@pytest.mark.parametrize("name", GEARS)
def test_relative_velocity_tangent_on_path(name):
    geo = GEARS[name]
    for s in _path(geo):
        state = aligned_state(geo, s)
        velocity = surface_velocities(geo, state, W1)
        scale = np.linalg.norm(velocity.entrainment)
        assert abs(state.normal @ velocity.sliding) < 1e-12 * scale
        assert abs(state.normal @ velocity.pinion) < 1e-12 * scale
        assert abs(state.normal @ velocity.face_gear) < 1e-12 * scale


@settings(max_examples=40, deadline=None)
@given(theta=st.floats(0.05, 0.9), a=st.floats(-0.6, 0.9), shaft=st.floats(30.0, 150.0))
def test_equation_of_meshing_holds_on_generated_surface(theta, a, shaft):
    geo = pair(EXAMPLE_A, shaft_angle=shaft)
    point = generating_point(geo, theta, a)
    omega = K_AXIS + geo.q * geo.a2
    relative = np.cross(omega, point)
    assert abs(profile_normal(a) @ relative) <= 1e-12 * np.linalg.norm(omega) * np.linalg.norm(point)


# 3. Aligned general TCA: exact ratio, z = z_P, path line tangent to the base circle (see also test_gear_tca).
def test_aligned_tca_path_line():
    geo = GEARS["A110"]
    path = ContactPath(geo)
    first, last = (path.state(s) for s in path.limits())
    direction = (last.point - first.point) / np.linalg.norm(last.point - first.point)
    offset = geo.pinion_centre - first.point
    distance = abs(offset[0] * direction[1] - offset[1] * direction[0])  # in the transverse plane
    assert distance == pytest.approx(geo.r_b1, rel=1e-12)
    assert first.point[2] == pytest.approx(geo.z_P, rel=1e-14) and last.point[2] == pytest.approx(geo.z_P, rel=1e-14)


# 4. Pitch point and pitch cones.
@pytest.mark.parametrize("shaft_angle", [45.0, 70.0, 90.0, 110.0, 135.0])
def test_pitch_point_and_cones(shaft_angle):
    geo = pair(EXAMPLE_A, shaft_angle=shaft_angle)
    g = math.radians(shaft_angle)
    point = geo.pitch_point
    assert np.linalg.norm(np.cross(point, geo.a2)) == pytest.approx(geo.module * geo.face_gear_teeth / 2, rel=1e-14)
    assert geo.z_P == pytest.approx(
        geo.module / 2 * (geo.face_gear_teeth + geo.shaper_teeth * math.cos(g)) / math.sin(g))
    # Pinion pitch cone: the line from the apex O_1 through P, and the relative rotation axis W1 a_1 + W2 a_2.
    generator = point - geo.pinion_apex
    cone = math.atan2(np.linalg.norm(np.cross(generator, K_AXIS)), generator @ K_AXIS)
    assert math.tan(geo.delta_1) == pytest.approx(math.sin(g) / (geo.face_gear_teeth / geo.pinion_teeth + math.cos(g)))
    assert cone == pytest.approx(geo.delta_1, rel=1e-12)
    axis = K_AXIS + geo.pinion_teeth / geo.face_gear_teeth * geo.a2
    assert math.atan2(np.linalg.norm(np.cross(axis, K_AXIS)), axis @ K_AXIS) == pytest.approx(geo.delta_1, rel=1e-12)
    assert geo.delta_1 + geo.delta_2 == pytest.approx(g, rel=1e-14)


# 5. Line contact when N1 = Ns; rank-one generation (det(S_s - S_2) = 0 along the generation contact line).
def test_line_contact_when_pinion_equals_shaper():
    geo = pair(EXAMPLE_A, pinion_teeth=28)
    for s in np.linspace(-0.012, 0.012, 7):
        _, closed = closed_form_relative_curvature(geo, s)
        state = aligned_state(geo, s)
        relative = _tangent_matrix(face_gear_shape_operator(geo, state) - pinion_shape_operator(state), state)
        for matrix in (closed, relative):
            assert abs(np.linalg.det(matrix)) < 1e-12 * np.trace(matrix) ** 2
        assert np.max(np.abs(relative - closed)) < 1e-8 * np.max(np.abs(closed))
        principal = principal_curvatures(face_gear_shape_operator(geo, state) - pinion_shape_operator(state),
                                         np.cross(state.pinion_axis, state.normal), state.pinion_axis)
        assert 1.0 / abs(principal.kappa_min) > 1e3  # R_y above a kilometre: a line contact


@pytest.mark.parametrize("name", GEARS)
def test_generation_is_a_line_contact(name):
    geo = GEARS[name]
    for s in _path(geo, 5):
        state = aligned_state(geo, s)
        theta_s, phi_s = state.theta_s, state.phi_s
        a = geo.mu + theta_s + phi_s
        profile = np.array([math.cos(a), math.sin(a), 0.0])
        rho_s = geo.r_bs * theta_s
        difference = -np.outer(profile, profile) / rho_s - shape_operator_forms(geo, theta_s, phi_s)
        matrix = _tangent_matrix(difference, state)
        assert abs(np.linalg.det(matrix)) < 1e-9 * np.max(np.abs(matrix)) ** 2
        contact_line = face_gear_jet(geo, theta_s, phi_s).r_t  # the shaper's u_s(theta) line at fixed phi_s
        contact_line = contact_line / np.linalg.norm(contact_line)
        assert np.linalg.norm(difference @ contact_line) < 1e-9 * np.max(np.abs(matrix))
        beta_c = math.atan2(abs(contact_line @ profile), abs(contact_line @ K_AXIS))
        expected = math.atan(rho_s / (geo.z_P * math.tan(geo.pressure_angle)))
        assert beta_c == pytest.approx(expected, rel=1e-12)
    if name == "A110":
        beta_p = math.degrees(
            math.atan(geo.r_ps * math.sin(geo.pressure_angle) / (geo.z_P * math.tan(geo.pressure_angle))))
        assert_reference(beta_p, "9.0")


# 6. Hyperbolic face-gear points; the pinion and shaper profile radii differ by e sin(alpha).
@pytest.mark.parametrize("name", GEARS)
def test_face_gear_points_are_hyperbolic(name):
    result = analysis(EXAMPLE_B if name == "B" else EXAMPLE_A,
                      **({} if name == "B" else {"shaft_angle": float(name[1:])}))
    assert np.all(result.point_values["face_gear_curvature_1"] * result.point_values["face_gear_curvature_2"] < 0)
    assert np.all(result.path["face_gear_curvature_1"] * result.path["face_gear_curvature_2"] < 0)
    geo = GEARS[name]
    for s in _path(geo, 5):
        state = aligned_state(geo, s)
        assert geo.r_bs * state.theta_s - state.rho_1 == pytest.approx(geo.e * math.sin(geo.pressure_angle), rel=1e-12)


# 7. Pitch-point closed forms.
@pytest.mark.parametrize("shaft_angle", [60.0, 90.0, 110.0, 130.0])
def test_pitch_point_curvature_closed_forms(shaft_angle):
    geo = pair(EXAMPLE_A, shaft_angle=shaft_angle)
    g, alpha = geo.shaft_angle, geo.pressure_angle
    state = aligned_state(geo, 0.0)
    for direct in (False, True):
        matrix = _tangent_matrix(face_gear_shape_operator(geo, state, direct=direct), state)
        scale = 1.0 / geo.L0
        assert matrix[0, 0] == pytest.approx(math.cos(g) / (geo.L0 * math.sin(alpha)), abs=1e-12 * scale)
        assert abs(matrix[0, 1]) == pytest.approx(math.sin(g) / (geo.L0 * math.tan(alpha)), rel=1e-10)
        expected_kk = geo.q**2 * math.sin(g) ** 2 * math.cos(alpha) ** 2 / (geo.c * geo.r_ps * math.sin(alpha))
        assert matrix[1, 1] == pytest.approx(expected_kk, rel=1e-10)
    supplementary = pair(EXAMPLE_A, shaft_angle=180.0 - shaft_angle)
    flipped = _tangent_matrix(face_gear_shape_operator(supplementary, aligned_state(supplementary, 0.0)), state)
    assert flipped[0, 0] == pytest.approx(-matrix[0, 0], abs=1e-12 / geo.L0)


def test_pitch_point_curvature_example_a():
    geo = GEARS["A110"]
    state = aligned_state(geo, 0.0)
    matrix = _tangent_matrix(face_gear_shape_operator(geo, state), state) * MM  # 1/mm
    assert_reference(matrix[0, 0] * 1e3, "-1.5931")
    assert_reference(abs(matrix[0, 1]) * 1e3, "3.9669")
    assert_reference(matrix[1, 1] * 1e4, "6.2886")


# 8. Closed form, fundamental forms (a) and direct relation (b) agree.
@pytest.mark.parametrize("name", GEARS)
def test_three_curvature_routes_agree(name):
    geo = GEARS[name]
    for s in _path(geo, 11):
        state = aligned_state(geo, s)
        forms = shape_operator_forms(geo, state.theta_s, state.phi_s)
        direct = shape_operator_direct(geo, state.theta_s, state.phi_s)
        assert np.max(np.abs(forms - direct)) < 1e-8 * np.max(np.abs(forms))
        closed_face_gear, closed_relative = closed_form_relative_curvature(geo, s)
        assert (np.max(np.abs(_tangent_matrix(forms, state) - closed_face_gear))
                < 1e-8 * np.max(np.abs(closed_face_gear)))
        relative = _tangent_matrix(forms - pinion_shape_operator(state), state)
        assert np.max(np.abs(relative - closed_relative)) < 1e-8 * np.max(np.abs(closed_relative))
        # The small principal relative curvature (1/R_y) comes from a near-cancellation: check it too.
        ours = principal_curvatures(forms - pinion_shape_operator(state), np.cross(state.pinion_axis, state.normal),
                                    state.pinion_axis)
        det, trace = np.linalg.det(closed_relative), np.trace(closed_relative)
        kappa_max = 0.5 * (trace + math.sqrt(trace * trace - 4 * det))
        assert ours.kappa_min == pytest.approx(det / kappa_max, rel=1e-8)


@settings(max_examples=25, deadline=None)
@given(shaft=st.floats(40.0, 140.0), fraction=st.floats(0.0, 1.0))
def test_curvature_routes_agree_for_any_shaft_angle(shaft, fraction):
    geo = pair(EXAMPLE_A, shaft_angle=shaft)
    s_min, s_max = ContactPath(geo).limits()
    state = aligned_state(geo, s_min + fraction * (s_max - s_min))
    forms = shape_operator_forms(geo, state.theta_s, state.phi_s)
    direct = shape_operator_direct(geo, state.theta_s, state.phi_s)
    assert np.max(np.abs(forms - direct)) < 1e-8 * np.max(np.abs(forms))


# 9. Constant sliding direction, linear in s.
@pytest.mark.parametrize("name", GEARS)
def test_sliding_direction_is_constant(name):
    geo = GEARS[name]
    g, alpha = geo.shaft_angle, geo.pressure_angle
    expected = math.sin(g) * math.cos(alpha) / (geo.face_gear_teeth / geo.pinion_teeth + math.cos(g))
    s_values = [s for s in _path(geo, 9) if abs(s) > 1e-6]
    slopes = []
    for s in s_values:
        state = aligned_state(geo, s)
        sliding = surface_velocities(geo, state, W1).sliding
        profile = np.cross(state.pinion_axis, state.normal)
        assert abs(sliding @ state.pinion_axis) / abs(sliding @ profile) == pytest.approx(abs(expected), rel=1e-10)
        slopes.append(sliding / s)
    assert np.max(np.abs(np.array(slopes) - slopes[0])) < 1e-9 * np.linalg.norm(slopes[0])
    if name == "A110":
        assert_reference(abs(expected), "0.14058")


# 10. Load, contact ratio and the orthogonal path start.
def test_load_contact_ratio_and_path_start():
    result = analysis(EXAMPLE_A, shaft_angle=90.0)
    geo = result.spec.geometry
    assert result.normal_load == pytest.approx(500.0 / geo.r_b1, rel=1e-15)
    assert result.contact_ratio == pytest.approx((result.path_end - result.path_start) / result.base_pitch, rel=1e-15)
    assert result.path_start == pytest.approx(-geo.face_gear_addendum / math.sin(geo.pressure_angle), rel=1e-12)
    assert result.path_end == pytest.approx(
        math.sqrt(geo.r_a1**2 - geo.r_b1**2) - geo.r_p1 * math.sin(geo.pressure_angle), rel=1e-15
    )


# 11. Hertz routine.
def test_hertz_reference_and_limits():
    """The reference Hertz check was first quoted with R_y = 40 mm, but its a = 2.1040, b = 0.1992 mm,
    p0 = 1139 MPa (a/b = 10.6) belong to R_y = 400 mm (R_y/R_x = 40); with R_y = 40 mm the exact values are
    a = 0.786, b = 0.314 mm."""
    reduced = reduced_modulus(STEEL, STEEL)
    assert_reference(reduced / 1e9, "226.37")
    contact = hertz_contact(10 * MM, 400 * MM, 1000.0, reduced)
    assert_reference(contact.a / MM, "2.1040")
    assert_reference(contact.b / MM, "0.1992")
    assert_reference(contact.p_max / 1e6, "1139")
    radius = 20 * MM
    circle = hertz_contact(radius, radius, 1000.0, reduced)
    e_star = reduced / 2
    assert circle.a == pytest.approx((3 * 1000.0 * radius / (4 * e_star)) ** (1 / 3), rel=1e-10)  # R_x = R_y = R
    assert circle.b == pytest.approx(circle.a, rel=1e-10)
    heavier = hertz_contact(10 * MM, 400 * MM, 8000.0, reduced)
    assert heavier.a == pytest.approx(2 * contact.a, rel=1e-12)
    assert heavier.b == pytest.approx(2 * contact.b, rel=1e-12)
    assert heavier.p_max == pytest.approx(2 * contact.p_max, rel=1e-12)


# 13. (misalignment) in test_gear_tca.py. 14. Undercut and pointing.
@pytest.mark.parametrize("name", GEARS)
def test_undercut_limit_above_base_radius_section(name):
    geo = GEARS[name]
    assert undercut_limit(geo) > geo.L0 * math.cos(geo.pressure_angle)
    assert pointing_limit(geo) > geo.L0 > undercut_limit(geo)


def test_equivalent_rack_pointing_limit_orthogonal():
    """Equivalent rack (docs/method.md §1.2): r_w = L Ns/N2, cos alpha_L = r_bs/r_w,
    e_s = 2 r_w (pi/(2Ns) - inv alpha + inv alpha_L), s_tip = e_s - 2 (r_w - (r_ps - h_a2)) tan alpha_L = 0; within
    0.5 % of the exact L2 for g = 90 deg."""
    from scipy import optimize

    geo = GEARS["A90"]
    inv = lambda x: math.tan(x) - x  # noqa: E731

    def tip_width(radius):
        r_w = radius * geo.shaper_teeth / geo.face_gear_teeth
        alpha_l = math.acos(geo.r_bs / r_w)
        space = 2 * r_w * (math.pi / (2 * geo.shaper_teeth) - inv(geo.pressure_angle) + inv(alpha_l))
        return space - 2 * (r_w - (geo.r_ps - geo.face_gear_addendum)) * math.tan(alpha_l)

    rack = optimize.brentq(tip_width, geo.L0, 1.5 * geo.L0)
    assert_reference(rack / MM, "569.2")
    assert pointing_limit(geo) == pytest.approx(rack, rel=5e-3)
