"""Heat budget of the face gear points (issue 5): conservation, closed forms, trends."""

import math

import numpy as np
import pytest


@pytest.fixture
def run(facegear_run):
    """The default face gear case on --grid 65, solved once per session (conftest.py)."""
    return facegear_run


def test_heat_table_has_one_row_per_point(run):
    assert list(run.heat["point"].values) == ["S1", "S2", "S3", "S4", "S5"]
    for name, column in run.heat.items():
        if name != "point":
            assert np.isfinite(column.values).all(), name


def test_partition_sums_to_one_and_power_splits(run):
    h = run.heat
    assert np.allclose(h["partition_1"].values + h["partition_2"].values, 1.0, atol=1e-12)
    assert np.allclose(h["friction_power_1"].values + h["friction_power_2"].values, h["friction_power"].values,
                       rtol=1e-12)


def test_duty_ratio_at_the_pitch_point_is_b_over_pi_r_pitch(run):
    # At S3 the contact is on the pinion pitch circle, r = m N1/2 = 6.35 mm * 25/2 (FACEGEAR.md §1), and on the
    # face gear at L0 = m N2/2 = 508 mm: t_c/T = b/(pi r) (PHYSICS.md §5.6).
    s3 = next(p for p in run.points if p.name == "S3")
    b = s3.scalar("b")
    assert s3.scalar("duty_ratio_1") == pytest.approx(b / (math.pi * 0.00635 * 25 / 2), rel=1e-9)
    assert s3.scalar("duty_ratio_2") == pytest.approx(b / (math.pi * 0.00635 * 160 / 2), rel=1e-9)


def test_distributed_heat_sums_to_the_friction_power(run):
    for p in run.points:
        x, y = p.axes["x"].values, p.axes["y"].values
        cell = (x[1] - x[0]) * (y[1] - y[0])
        power = p.scalar("friction_power")
        for field in ("heat_flux_by_pressure", "heat_flux_by_shear"):
            total = p.fields[field].values.sum() * cell
            assert total == pytest.approx(power, rel=1e-9, abs=1e-9), (p.name, field)


def test_friction_heat_and_flash_temperature_are_smallest_at_the_pitch_point(run):
    h = run.heat
    names = list(h["point"].values)
    for column in ("mu", "friction_power", "flash_temperature"):
        values = list(h[column].values)
        assert names[int(np.argmin(values))] == "S3", column
    # the solved surface rise and the Blok flash temperature are both largest at the most sliding point, S1
    assert names[int(np.argmax(h["flash_temperature"].values))] == "S1"
    assert names[int(np.argmax(h["surface_rise_max"].values))] == "S1"


def test_oil_film_holds_a_few_percent_of_the_frictional_heat(run):
    # seed paper §3.5: about 1 %; here 2-6 % (the README discusses the difference)
    ratio = run.heat["oil_to_friction_ratio"].values
    assert ((ratio > 0.001) & (ratio < 0.1)).all()
