"""General tooth contact analysis (5 equations) against the semi-analytic path, and misalignment.

The misalignment table of docs/accuracy.md (example A, 110 deg). Its shaft-angle error is a pinion rotation of
+0.05 deg about y through O_1, which is our shaft_angle_error = -0.05 deg (we count the change of the
shaft angle). TE counts rotations in the direction of motion (TE > 0 when the face gear leads); its
signs then agree with the table's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from facegear_tehl.gears.analysis import analyse_gear_pair
from facegear_tehl.gears.geometry import axial_section
from facegear_tehl.gears.kinematics import surface_velocities
from facegear_tehl.gears.tca import ContactPath, Misalignment, aligned_state, solve_contact

from gear_examples import EXAMPLE_A, EXAMPLE_B, MM, STEEL, assert_reference, pair, spec

ARCSEC = math.pi / (180 * 3600)
GEARS = {
    "A110": pair(EXAMPLE_A),
    "A90": pair(EXAMPLE_A, shaft_angle=90.0),
    "A70": pair(EXAMPLE_A, shaft_angle=70.0),
    "A130": pair(EXAMPLE_A, shaft_angle=130.0),
    "B": pair(EXAMPLE_B),
}


@pytest.mark.parametrize("name", GEARS)
def test_general_tca_reproduces_semi_analytic_path(name):
    geo = GEARS[name]
    s_min, s_max = ContactPath(geo).limits()
    guess = None
    worst = 0.0
    for s in np.linspace(s_min, s_max, 101):
        exact = aligned_state(geo, s)
        if guess is None:  # start away from the solution, then continue along the path
            guess = exact.unknowns + np.array([0.01, 1 * MM, 0.01, -0.01, 0.002])
        state = solve_contact(geo, exact.phi_1, guess)
        guess = state.unknowns
        worst = max(worst, float(np.max(np.abs(state.point - exact.point))))
        assert abs(state.transmission_error(geo)) < 1e-10
        assert state.ratio == pytest.approx(geo.pinion_teeth / geo.face_gear_teeth, rel=1e-10)
        assert state.point[2] == pytest.approx(geo.z_P, abs=1e-12)
        assert np.max(np.abs(state.point_rate - exact.point_rate)) < 1e-10 * geo.r_b1
        assert np.max(np.abs(state.normal - exact.normal)) < 1e-12
    assert worst < 1e-9 * MM


def test_pinion_axial_shift_has_no_effect():
    geo = GEARS["A110"]
    aligned = ContactPath(geo)
    shifted = ContactPath(geo, Misalignment(pinion_axial_shift=1 * MM))
    for s in np.linspace(-0.015, 0.013, 9):
        state = shifted.state(s)
        assert np.max(np.abs(state.point - aligned.state(s).point)) < 1e-12
        assert abs(state.transmission_error(geo)) < 1e-12
    assert np.allclose(shifted.limits(), aligned.limits(), rtol=0, atol=1e-12)


@pytest.mark.parametrize(
    "misalignment,te_arcsec,shift_z_mm,radius_mm",
    [
        (Misalignment(shaft_angle_error=math.radians(-0.05)), "98.6", "35.5", "543"),
        (Misalignment(offset=0.1 * MM), "-40.5", "2.56", None),
        (Misalignment(face_gear_axial_shift=0.1 * MM), "-17.4", "-5.05", None),
    ],
)
def test_misalignment_gives_constant_transmission_error(misalignment, te_arcsec, shift_z_mm, radius_mm):
    geo = GEARS["A110"]
    path = ContactPath(geo, misalignment)
    s_min, s_max = path.limits()
    errors = np.array([path.state(s).transmission_error(geo) for s in np.linspace(s_min, s_max, 15)])
    assert np.ptp(errors) < 1e-9 * abs(errors.mean())
    assert_reference(errors.mean() / ARCSEC, te_arcsec, "TE")
    pitch = path.state(0.0)
    assert_reference((pitch.point[2] - geo.z_P) / MM, shift_z_mm, "path shift")
    if radius_mm is not None:
        assert_reference(axial_section(geo, pitch.point)[1] / MM, radius_mm, "R_2 at P")


def test_misaligned_analysis_is_consistent():
    """Under misalignment the whole analysis runs on the general TCA: velocities stay tangent, both
    curvature routes agree, the path moves along the tooth and TE is reported."""
    misaligned = spec(EXAMPLE_A, offset=0.1 * MM, load_sharing="iso_linear")
    result = analyse_gear_pair(misaligned, STEEL, STEEL, n_path=21)
    aligned = analyse_gear_pair(spec(EXAMPLE_A, load_sharing="iso_linear"), STEEL, STEEL, n_path=21)
    assert result.curvature_check < 1e-8
    assert_reference(result.transmission_error / ARCSEC, "-40.5")
    radius_shift = result.point_values["face_gear_radius"][2] - aligned.point_values["face_gear_radius"][2]
    assert radius_shift > 2 * MM
    geo = misaligned.geometry
    path = ContactPath(geo, misaligned.misalignment)
    for s in np.linspace(*path.limits(), 7):
        state = path.state(s)
        velocity = surface_velocities(geo, state, misaligned.pinion_speed)
        scale = np.linalg.norm(velocity.entrainment)
        assert abs(state.normal @ velocity.pinion) < 1e-9 * scale
        assert abs(state.normal @ velocity.face_gear) < 1e-9 * scale
