"""The example tables of an independent implementation (docs/accuracy.md) reproduced by the gear contact analysis.

Convention differences, documented: SRR and psi_e are signed here (by V_s . U_e and by the right-handed
contact frame); the tables print magnitudes, so magnitudes are compared. Velocity components along the
profile and the tooth length are compared as magnitudes for the same reason. L1 is Litvin's shaper-tip
criterion (the tables quote the range "462.5 to 465.8": the top-land crossing and the deepest point).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize

from facegear_tehl.gears.geometry import axial_section, pointing_limit, singular_point, undercut_limit
from facegear_tehl.gears.kinematics import surface_velocities
from facegear_tehl.gears.tca import aligned_state

from gear_examples import EXAMPLE_A, EXAMPLE_B, MM, analysis, assert_reference, pair

# Table A1 of docs/accuracy.md (g = 110 deg), columns in the printed units.
A1_COLUMNS = ("s", "psi1", "rho1", "R2", "fg_neg", "fg_pos", "Rx", "Ry", "major_angle", "Ue", "Ue_prof", "Ue_len",
              "Vs_prof", "Vs_len", "SRR", "psi_e", "F", "a", "b", "p0")
A1_ROWS = {
    "S1": "-15.177 12.088 18.369 505.993 -202.1 290.1 18.914 14147 4.40 8.033 "
          "8.027 0.317 4.513 0.634 0.567 2.14 2317 10.709 0.1857 556",
    "S2": "-5.003 3.984 28.543 507.297 -212.3 279.9 29.562 14255 6.83 9.711 "
          "9.711 0.105 1.488 0.209 0.155 6.22 6950 15.191 0.3376 647",
    "S3": "0 0 33.545 508.000 -217.3 274.9 34.751 14327 8.02 10.539 10.539 0 0 0 0 8.02 6950 15.109 0.3671 598",
    "S4": "2.903 -2.312 36.449 508.426 -220.2 272.0 37.734 14374 8.71 11.019 "
          "11.019 0.061 0.863 0.121 0.079 9.03 6950 15.070 0.3830 575",
    "S5": "13.077 -10.416 46.623 510.028 -230.4 261.8 47.941 14574 11.10 12.705 "
          "12.703 0.273 3.889 0.547 0.309 12.34 2317 10.386 0.3002 355",
}


def _point_columns(result, index: int) -> dict[str, float]:
    """Our values of one meshing point in the units of the reference table."""
    spec = result.spec
    geo = spec.geometry
    values = result.point_values
    s = float(values["s"][index])
    state = aligned_state(geo, s)
    velocity = surface_velocities(geo, state, spec.pinion_speed)
    profile = np.cross(state.pinion_axis, state.normal)
    return {
        "s": s / MM,
        "psi1": math.degrees(state.phi_1),
        "rho1": float(values["pinion_profile_radius"][index]) / MM,
        "R2": float(values["face_gear_radius"][index]) / MM,
        "fg_neg": 1.0 / float(values["face_gear_curvature_2"][index]) / MM,
        "fg_pos": 1.0 / float(values["face_gear_curvature_1"][index]) / MM,
        "Rx": float(values["Rx"][index]) / MM,
        "Ry": float(values["Ry"][index]) / MM,
        "major_angle": float(values["ellipse_angle"][index]),
        "Ue": float(values["entrainment_speed"][index]),
        "Ue_prof": abs(velocity.entrainment @ profile),
        "Ue_len": abs(velocity.entrainment @ state.pinion_axis),
        "Vs_prof": abs(velocity.sliding @ profile),
        "Vs_len": abs(velocity.sliding @ state.pinion_axis),
        "SRR": abs(float(values["srr"][index])),
        "psi_e": abs(float(values["entrainment_angle"][index])),
        "F": float(values["load"][index]),
        "a": float(values["a"][index]) / MM,
        "b": float(values["b"][index]) / MM,
        "p0": float(values["p_h"][index]) / 1e6,
    }


@pytest.fixture(scope="module")
def a1():
    return analysis(EXAMPLE_A)


@pytest.mark.parametrize("index,name", list(enumerate(A1_ROWS)))
def test_table_a1_row(a1, index, name):
    ours = _point_columns(a1, index)
    for column, printed in zip(A1_COLUMNS, A1_ROWS[name].split()):
        assert_reference(ours[column], printed, f"{name} {column}")


def test_example_a1_scalars(a1):
    geo = a1.spec.geometry
    for value, printed in [
        (geo.r_p1, "79.375"), (geo.r_b1, "71.938"), (geo.r_a1, "85.725"), (geo.r_ps, "88.900"), (geo.r_bs, "80.571"),
        (geo.L0, "508.000"), (geo.e, "9.525"), (geo.z_P, "508.245"), (a1.base_pitch, "18.080"),
        (a1.path_start, "-15.177"), (a1.path_end, "13.077"), (a1.pointing_limit, "566.4"),
        (a1.undercut_limit, "465.8"),
    ]:
        assert_reference(value / MM, printed)
    assert_reference(a1.pinion_cone_angle, "8.817")
    assert_reference(a1.face_gear_cone_angle, "101.183")
    assert_reference(a1.contact_ratio, "1.5627")
    assert_reference(a1.normal_load, "6950.4")
    assert a1.warnings == ()


def _top_land_crossing(geo) -> float:
    """Face-gear radius where the singular line crosses the top land (the lower end of the reference L1 range)."""
    theta_tip = math.sqrt(geo.r_as**2 - geo.r_bs**2) / geo.r_bs
    theta = optimize.brentq(lambda t: axial_section(geo, singular_point(geo, t))[0] - geo.tip_depth, 0.05, theta_tip)
    return axial_section(geo, singular_point(geo, theta))[1]


@pytest.mark.parametrize("shaft_angle,crossing,deepest,l2", [(110.0, "462.5", "465.8", "566.4"),
                                                             (90.0, "462.2", "465.2", "569.3"),
                                                             (70.0, None, None, "572.2")])
def test_undercut_and_pointing_limits(shaft_angle, crossing, deepest, l2):
    geo = pair(EXAMPLE_A, shaft_angle=shaft_angle)
    if crossing is not None:
        assert_reference(_top_land_crossing(geo) / MM, crossing, "top-land crossing of the singular line")
        assert_reference(undercut_limit(geo) / MM, deepest, "L1")
    assert_reference(pointing_limit(geo) / MM, l2, "L2")


def test_litvin_elastic_approach_ellipse(a1):
    """Litvin & Fuentes (2004) elastic-approach ellipse: 2a = 2 sqrt(delta/A), 2b = 2 sqrt(delta/B),
    delta = 0.0065 mm; 27.3 / 1.34 mm at P."""
    delta = 0.0065 * MM
    index = 2  # S3
    kappa_min = 1.0 / float(a1.point_values["Ry"][index])
    kappa_max = 1.0 / float(a1.point_values["Rx"][index])
    assert_reference(2 * math.sqrt(delta / (kappa_min / 2)) / MM, "27.3")
    assert_reference(2 * math.sqrt(delta / (kappa_max / 2)) / MM, "1.34")


def test_example_a0_orthogonal():
    result = analysis(EXAMPLE_A, shaft_angle=90.0)
    assert_reference(result.pitch_point_height / MM, "508.000")
    assert_reference(result.path_start / MM, "-15.025")
    assert_reference(result.contact_ratio, "1.5544")
    s1, s3, s5 = (_point_columns(result, i) for i in (0, 2, 4))
    for column, printed in [("fg_neg", "-256.4"), ("fg_pos", "218.8"), ("Rx", "32.884"), ("Ry", "14220"),
                            ("Ue", "10.539"), ("a", "15.104"), ("b", "0.3571"), ("p0", "615")]:
        assert_reference(s3[column], printed, f"S3 {column}")
    for column, printed in [("Rx", "18.499"), ("Ry", "14040"), ("Vs_prof", "4.720"), ("Vs_len", "0.668"),
                            ("SRR", "0.582")]:
        assert_reference(s1[column], printed, f"S1 {column}")
    for column, printed in [("Rx", "44.387"), ("Ry", "14469"), ("Vs_prof", "4.108"), ("Vs_len", "0.582"),
                            ("SRR", "0.329")]:
        assert_reference(s5[column], printed, f"S5 {column}")


def test_example_a2_seventy_degrees():
    result = analysis(EXAMPLE_A, shaft_angle=70.0)
    assert_reference(result.pitch_point_height / MM, "572.959")
    assert_reference(result.contact_ratio, "1.546")
    s3 = _point_columns(result, 2)
    for column, printed in [("fg_neg", "-341.9"), ("fg_pos", "197.0"), ("Rx", "31.343"), ("Ry", "17907")]:
        assert_reference(s3[column], printed, f"S3 {column}")


def test_example_b():
    result = analysis(EXAMPLE_B)
    geo = result.spec.geometry
    assert_reference(result.pitch_point_height / MM, "138.501")
    assert_reference(geo.e / MM, "4.5")
    assert_reference(result.contact_ratio, "1.8197")
    assert_reference(result.normal_load, "5912")
    assert_reference(result.undercut_limit / MM, "138.2")
    assert_reference(result.pointing_limit / MM, "162.4")
    s1, s3, s5 = (_point_columns(result, i) for i in (0, 2, 4))
    for column, printed in [("s", "-9.023"), ("rho1", "3.290"), ("Rx", "3.396"), ("Ry", "1687"), ("SRR", "1.134"),
                            ("psi_e", "3.97"), ("p0", "1789")]:
        assert_reference(s1[column], printed, f"S1 {column}")
    for column, printed in [("Rx", "12.717"), ("Ry", "1769"), ("Ue", "1.934"), ("psi_e", "13.7"), ("a", "6.749"),
                            ("b", "0.3061"), ("p0", "1366")]:
        assert_reference(s3[column], printed, f"S3 {column}")
    for column, printed in [("s", "7.094"), ("Rx", "18.503"), ("Ry", "1909"), ("SRR", "0.412"), ("psi_e", "23.9")]:
        assert_reference(s5[column], printed, f"S5 {column}")
    # Reference example B: S4 = -0.166 mm lies before the pitch point; the analysis says so.
    assert_reference(float(result.point_values["s"][3]) / MM, "-0.166")
    order = [w for w in result.warnings if "lies before" in w]
    assert len(order) == 1 and "S4" in order[0] and "S3" in order[0]
    # Its pitch point's ellipse (a = 6.749 mm, the reference's) about face-gear radius 144.0 mm passes the inner edge
    # at 139 mm by 1.75 mm; S5's (a = 4.72 mm about 145.0 mm) stays on the tooth.
    edge = {w.split(":")[0]: w for w in result.warnings if "past the face width" in w}
    assert sorted(edge) == ["S1", "S2", "S3", "S4"] and "reaches 1.7 mm past" in edge["S3"]
