"""The gear: block, its input errors, the case file integration, the ContactPoints and the report table."""

from __future__ import annotations

from dataclasses import replace
import math

import numpy as np
import pytest

from facegear_tehl.case import load_case, parse_case
from facegear_tehl.gears.analysis import PATH_UNITS, analyse_gear_pair
from facegear_tehl.gears.report import contact_table
from facegear_tehl.points import contact_analysis
from facegear_tehl.schema import CaseError

from gear_examples import CASE_FILE, EXAMPLE_A, EXAMPLE_B, MM, STEEL, analysis, assert_reference, case_variant, spec


@pytest.mark.parametrize(
    "overrides,key,fragment",
    [
        ({"shaper_teeth": 25}, "gear.shaper_teeth", "shaper_teeth - pinion_teeth in 1..3"),
        ({"shaper_teeth": 24}, "gear.shaper_teeth", "in 1..3"),
        ({"shaper_teeth": 29}, "gear.shaper_teeth", "in 1..3"),
        ({"inner_radius": 0.462}, "gear.inner_radius", "undercut limit L1"),
        ({"outer_radius": 0.570}, "gear.outer_radius", "pointing limit L2"),
        ({"pinion_torque": 0}, "gear.pinion_torque", "positive"),
        ({"pinion_torque": -5.0}, "gear.pinion_torque", "positive"),
        ({"pinion_speed": 0}, "gear.pinion_speed", "positive"),
        ({"shaft_angle": 180}, "gear.shaft_angle", "< 180"),
        ({"shaft_angle": 0}, "gear.shaft_angle", "> 0"),
        ({"pressure_angle": 10.0}, "gear.pressure_angle", "an undercut and a pointing limit"),  # 25 deg would have
        ({"pinion_addendum": 0.5 * 6.35e-3, "face_gear_addendum": 0.5 * 6.35e-3}, "gear.pinion_addendum",
         "contact ratio in [1, 2)"),
        ({"inner_radius": 0.5075, "outer_radius": 0.548}, "gear.inner_radius", "covering the contact path"),
        ({"outer_radius": 0.509}, "gear.outer_radius", "covering the contact path"),
        ({"outer_radius": 0.46, "inner_radius": 0.47}, "gear.outer_radius", "more than inner_radius"),
        ({"points": [1, 2]}, "gear.points", "names among S1"),
        ({"points": ["S1", "S1"]}, "gear.points", "each point named once"),
        ({"points": 1}, "gear.points", "count of points"),
        ({"load_sharing": "linear"}, "gear.load_sharing", "iso_linear"),
        ({"load_sharing": [0.5, 1.0]}, "gear.load_sharing", "one coefficient per point (5)"),
        ({"load_sharing": [0.3, 1, 1, 1, 1.2]}, "gear.load_sharing", "(0, 1]"),
        ({"transition_side": "both"}, "gear.transition_side", "one of single, double"),
        ({"transition_side": 2}, "gear.transition_side", "one of single, double"),
        ({"load_sharing": [0.5, 1, 1, 1, 0.5], "transition_side": "double"}, "gear.transition_side",
         "no transition_side when load_sharing is a list of coefficients"),
        ({"load_sharing": [0.5, 1, 1, 1, 0.5], "transition_side": "single"}, "gear.transition_side",
         "list of coefficients"),
        ({"shaft_angle_error": -0.05, "outer_radius": 0.520}, "gear.outer_radius", "covering the contact path"),
        ({"shaft_angle_error": 2.0}, "gear.shaft_angle_error", "<= 1"),
        ({"pinion_teth": 25}, "gear.pinion_teth", "did you mean 'pinion_teeth'"),
    ],
)
def test_impossible_gears_are_input_errors(overrides, key, fragment):
    with pytest.raises(CaseError) as error:
        spec(EXAMPLE_A, **overrides)
    assert error.value.key == key
    assert str(error.value).startswith(key + ":")
    assert fragment in str(error.value)


def test_defaults_and_units():
    gear = spec(EXAMPLE_A)
    assert gear.pinion_addendum == gear.face_gear_addendum == gear.module == 6.35e-3
    assert gear.points == ("S1", "S2", "S3", "S4", "S5") and gear.load_sharing == "iso_linear"
    assert gear.transition_side == "single"
    assert (gear.pressure_angle == pytest.approx(math.radians(25.0))
            and gear.shaft_angle == pytest.approx(math.radians(110)))
    assert gear.pinion_speed == pytest.approx(3000 * 2 * math.pi / 60)
    assert gear.misalignment.is_zero


def test_shipped_case_reproduces_example_a():
    case = load_case(CASE_FILE)
    assert case.contact is None and case.gear is not None
    assert (case.solver.grid, case.solver.nodes_y, case.solver.thermal) == (257, 65, "full")
    gear = case.gear
    assert gear.inner_radius > 0.4659 and gear.outer_radius < 0.5664  # inside [L1, L2] of example A at 110 deg
    # the case takes S2 and S4 at the double-tooth side (2/3 of F_n); the reference tables at the single side (1)
    assert gear.transition_side == "double"
    double = analyse_gear_pair(gear, case.materials.body_1, case.materials.body_2)
    assert [p.load / double.points[2].load for p in double.points] == pytest.approx([1 / 3, 2 / 3, 1, 2 / 3, 1 / 3])
    result = analyse_gear_pair(replace(gear, transition_side="single"), case.materials.body_1, case.materials.body_2)
    assert [p.name for p in result.points] == ["S1", "S2", "S3", "S4", "S5"]
    for point, rx, ry, p0, load in zip(result.points, ["18.914", "29.562", "34.751", "37.734", "47.941"],
                                       ["14147", "14255", "14327", "14374", "14574"],
                                       ["556", "647", "598", "575", "355"], ["2317", "6950", "6950", "6950", "2317"]):
        assert_reference(point.radius_x / MM, rx, f"{point.name} R_x")
        assert_reference(point.radius_y / MM, ry, f"{point.name} R_y")
        assert_reference(point.hertz.p_max / 1e6, p0, f"{point.name} p_h")
        assert_reference(point.load, load, f"{point.name} load")


def test_transition_side_double_reaches_the_contact_points(tmp_path):
    """contact_analysis gives `tehl run` its ContactPoints (solved, written to /points) and the path table
    (/contact): with transition_side double, S2 and S4 carry 2/3 F_n at the Hertz pressure of that load,
    and the path, which has no sample at S2 or S4, keeps its zones."""
    single = contact_analysis(load_case(CASE_FILE))
    double = contact_analysis(load_case(case_variant(tmp_path, transition_side="double")))
    f_n = double.scalars["normal_load"][0]
    np.testing.assert_allclose([p.load / f_n for p in double.points], [1 / 3, 2 / 3, 1, 2 / 3, 1 / 3], rtol=1e-12)
    for one, two in zip(single.points, double.points):
        assert two.hertz.p_max == pytest.approx(one.hertz.p_max * (two.load / one.load) ** (1 / 3), rel=1e-9)
    np.testing.assert_array_equal(double.path["load_share"].values, single.path["load_share"].values)


def test_case_needs_exactly_one_of_contact_and_gear():
    text = CASE_FILE.read_text()
    contact = "contact: {radius_x: 0.01, radius_y: 0.02, load: 100, entrainment_speed: 1.0}\n"
    with pytest.raises(CaseError) as both:
        parse_case(text + contact)
    without_gear = text.split("gear:\n")[0] + "materials:" + text.split("\nmaterials:")[1]
    with pytest.raises(CaseError) as neither:
        parse_case(without_gear)
    for error in (both, neither):
        message = str(error.value)
        assert "contact" in message and "gear" in message
    assert parse_case(without_gear + contact).gear is None


def test_contact_points_frame_and_oblique_entrainment():
    result = analysis(EXAMPLE_A)
    for i, point in enumerate(result.points):
        assert point.radius_x <= point.radius_y
        assert point.path_coordinate == pytest.approx(float(result.point_values["s"][i]))
        assert point.entrainment[0] > 0  # x along the minor axis, oriented with the entrainment
        # psi_e is kept: 2 to 12 deg in example A (docs/accuracy.md), not aligned with x
        assert 2.0 < point.entrainment_angle < 12.5
        assert point.entrainment_speed == pytest.approx(float(result.point_values["entrainment_speed"][i]), rel=1e-12)
        assert abs(point.slide_roll_ratio) == pytest.approx(
            float(result.point_values["sliding_speed"][i] / result.point_values["entrainment_speed"][i]), rel=1e-12
        )
        assert point.hertz.a == pytest.approx(float(result.point_values["a"][i]), rel=1e-12)
        assert point.body_1 is STEEL and point.body_2 is STEEL


def test_path_arrays_and_units():
    result = analyse_gear_pair(spec(EXAMPLE_A), STEEL, STEEL, n_path=101)
    assert set(result.path) == set(PATH_UNITS) == set(result.units)
    for name, values in result.path.items():
        assert values.shape[0] == 101 and not values.flags.writeable, name
    assert result.path["u1"].shape == (101, 2)
    assert result.path["s"][0] == result.path_start and result.path["s"][-1] == result.path_end
    assert np.all(np.diff(result.path["s"]) > 0)
    # iso_linear: two pairs share the load in the double-tooth zones, 1/3 .. 2/3 each.
    share = result.path["load_share"]
    assert share[0] == pytest.approx(1 / 3) and share[-1] == pytest.approx(1 / 3) and share.max() == 1.0
    assert result.scalars()["normal_load"] == (pytest.approx(6950.412, rel=1e-6), "N")


def test_evenly_spaced_points():
    result = analysis(EXAMPLE_A, points=7, load_sharing="equal")
    names = [p.name for p in result.points]
    assert names == [f"P{i:02d}" for i in range(1, 8)]
    s = np.array([p.path_coordinate for p in result.points])
    np.testing.assert_allclose(s, np.linspace(result.path_start, result.path_end, 7), rtol=0, atol=1e-15)
    loads = np.array([p.load for p in result.points]) / result.normal_load
    assert loads[0] == 0.5 and loads[-1] == 0.5 and 1.0 in loads


def test_an_evenly_sampled_path_names_no_meshing_point_order():
    # Example B's S4 lies before its pitch point (test_gear_examples); its evenly sampled path solves no S-point.
    assert not any("lies before" in w for w in analysis(EXAMPLE_B, points=9, load_sharing="equal").warnings)


def test_a_contact_ellipse_past_the_face_width_is_named():
    # Example A's S2 at four times the torque: a = 15.19 mm x 4^(1/3) (Hertz, a ~ W^(1/3)) = 24.1 mm about its
    # face-gear radius 507.3 mm reaches the inner edge 482.7 mm if the face starts above 483 mm.
    loaded = analysis(EXAMPLE_A, pinion_torque=4 * EXAMPLE_A["pinion_torque"])
    s2 = loaded.points[1]
    assert s2.hertz.a == pytest.approx(15.191e-3 * 4.0 ** (1.0 / 3.0), rel=2e-3)
    assert not any("past the face" in w for w in loaded.warnings)
    inner = s2.rotation_radius_2 - s2.hertz.a + 1.0e-3
    narrow = analysis(EXAMPLE_A, pinion_torque=4 * EXAMPLE_A["pinion_torque"], inner_radius=inner)
    named = [w for w in narrow.warnings if "past the face width" in w]
    assert any(w.startswith("S2: ") and "reaches 1 mm past" in w for w in named)
    assert all(p.rotation_radius_2 - p.hertz.a < inner for p in narrow.points if any(
        w.startswith(f"{p.name}: ") for w in named))


def test_contact_table():
    table = contact_table(analysis(EXAMPLE_A))
    lines = table.splitlines()
    for header in ("s", "R_x", "R_y", "a/b", "p_h", "|U_e|", "|V_s|", "SRR", "psi_e", "load"):
        assert header in lines[0]
    for unit in ("[mm]", "[MPa]", "[m/s]", "[N]", "[deg]"):
        assert unit in lines[1]
    assert [line.split()[0] for line in lines[2:7]] == ["S1", "S2", "S3", "S4", "S5"]
    s1 = lines[2].split()
    assert s1[1:4] == ["-15.177", "18.914", "14147"] and s1[7] == "556"
    assert "-0.000" not in table


@pytest.mark.parametrize("overrides", [{"inner_radius": 0.30}, {"outer_radius": 0.70}])
def test_a_face_width_outside_the_limits_names_the_usable_width_and_following_it_validates(overrides):
    """A designer of a new gear does not know L1 and L2: either radius outside them names both, and a face width
    inside the range the message gives is accepted (the shipped case's 0.468 .. 0.548 m lies inside it)."""
    with pytest.raises(CaseError) as error:
        spec(EXAMPLE_A, **overrides)
    low, high = (float(v) for v in str(error.value).split("[L1, L2] = [")[1].split("] m")[0].split(", "))
    assert low < 0.468 < 0.548 < high
    gear = spec(EXAMPLE_A, inner_radius=low + 0.1 * (high - low), outer_radius=high - 0.1 * (high - low))
    assert gear.inner_radius > low and gear.outer_radius < high


def test_a_contact_path_reaching_into_the_undercut_zone_is_a_design_error():
    """25/28/40 at 110 deg: few face-gear teeth for the shaper (q = Ns/N2 = 0.7) push the undercut limit L1 above
    the localised contact path, which runs about the pitch radius L0 = m N2/2 (Litvin et al. 2000): no face width
    can hold it, and the message names the path's radii (bracketing L0) and [L1, L2] instead of asking for a
    face width that cannot exist."""
    with pytest.raises(CaseError) as error:
        spec(EXAMPLE_A, face_gear_teeth=40, inner_radius=0.01, outer_radius=10.0)
    message = str(error.value)
    assert error.value.key == "gear.face_gear_teeth" and "no face width fits this path" in message
    lowest, highest = (float(v) for v in message.split("radii ")[1].split(" m,")[0].split(" to "))
    l1 = float(message.split("[L1, L2] = [")[1].split(",")[0])
    assert lowest < 6.35e-3 * 40 / 2 < highest and lowest < l1
