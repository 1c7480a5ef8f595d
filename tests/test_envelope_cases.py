"""The envelope suite's case generator (facegear_tehl/suites/envelope.py, run by scripts/envelope.py): its size,
its spans, both models, and contacts that really have the asked ellipticity and Hertz pressure. Nothing is solved."""

from __future__ import annotations

import numpy as np
import pytest

from facegear_tehl.suites import envelope


@pytest.fixture(scope="module")
def cases():
    return envelope.envelope_cases()


def test_at_least_sixty_uniquely_named_cases(cases):
    assert len(cases) >= 60
    assert len({c.name for c in cases}) == len(cases)


@pytest.mark.parametrize(("attribute", "low", "high"), [
    ("ellipticity", 1.0, 100.0),
    ("hertz_pressure", 0.3e9, 2.5e9),
    ("entrainment_speed", 0.5, 30.0),
    ("slide_roll_ratio", 0.0, 2.0),
    ("skew", 0.0, 30.0),
    ("viscosity", 0.01, 0.1),
])
def test_spans_the_envelope(cases, attribute, low, high):
    values = [getattr(c, attribute) for c in cases]
    assert min(values) == pytest.approx(low)
    assert max(values) == pytest.approx(high)


def test_both_models_and_their_settings(cases):
    iso = [c for c in cases if not c.thermal]
    thermal = [c for c in cases if c.thermal]
    assert iso and thermal
    for case, rheology, mode in ((iso[0], "newtonian", "off"), (thermal[0], "ree_eyring", "full")):
        lubricant = case.lubricant()
        assert lubricant.rheology == rheology
        assert (lubricant.viscosity_model, lubricant.density_model) == ("roelands", "dowson_higginson")
        assert case.settings().thermal == mode
    assert 1.5e-8 <= min(c.pressure_viscosity for c in cases) <= max(c.pressure_viscosity for c in cases) <= 2.2e-8


def test_core_grid_is_complete(cases):
    """Every p_h x a/b of the core at every core speed (isothermal) and at the thermal speed."""
    iso = {(c.hertz_pressure, c.ellipticity, c.entrainment_speed) for c in cases if c.group == "core"}
    thermal = {(c.hertz_pressure, c.ellipticity) for c in cases if c.group == "core thermal"}
    grid = {(p, k) for p in envelope.CORE_PRESSURES for k in envelope.CORE_ELLIPTICITIES}
    assert iso == {(p, k, u) for p, k in grid for u in envelope.CORE_SPEEDS}
    assert thermal == grid


def test_contacts_have_the_asked_ellipticity_and_pressure(cases):
    """point.hertz (the project's exact Hertz solution) gives back a/b and p_h to 1e-6 relative."""
    for case in cases:
        point = case.point()
        hertz = point.hertz
        assert hertz.ellipticity == pytest.approx(case.ellipticity, rel=1e-6), case.name
        assert hertz.p_max == pytest.approx(case.hertz_pressure, rel=1e-6), case.name
        assert point.radius_x == envelope.RADIUS_X
        assert point.entrainment_speed == pytest.approx(case.entrainment_speed, rel=1e-12)
        assert point.slide_roll_ratio == pytest.approx(case.slide_roll_ratio, abs=1e-12)
        assert point.entrainment_angle == pytest.approx(case.skew, abs=1e-9)


def test_long_ellipse_radius_ratio():
    """a/b = 100 needs R_y/R_x of about 2000 (issue 14: 'a/b = 100 (R_y/R_x = 2000)')."""
    assert envelope.radius_ratio_for(100.0) == pytest.approx(2000.0, rel=0.01)
    assert envelope.radius_ratio_for(1.0) == 1.0


def test_select_by_pattern_and_model(cases):
    assert [c.name for c in envelope.select(cases, "ab30_ph1.5_u2_iso", None)] == ["ab30_ph1.5_u2_iso"]
    assert all(c.thermal for c in envelope.select(cases, "ab100_*", True))
    assert not any(c.thermal for c in envelope.select(cases, "skew", False))


def _solution(energy_balance_error: float, outcome=None):
    from facegear_tehl.solution import Field, Outcome, PointSolution

    scalars = {"h_c": (1e-7, "m"), "h_min": (5e-8, "m"), "p_max": (1e9, "Pa"),
               "energy_balance_error": (energy_balance_error, "1")}
    return PointSolution(name="c", outcome=outcome or Outcome.CONVERGED, message="", scalars=scalars,
                         fields={"pressure": Field(np.ones((3, 3)), "Pa")}, axes={})


@pytest.mark.parametrize(("imbalance", "passes"), [(0.004, True), (-0.009, True), (0.012, False), (-0.03, False)])
def test_check_holds_converged_thermal_cases_to_a_closed_energy_balance(imbalance, passes):
    """Issue 19: the energy balance closes to 1 % on every converged thermal envelope case; a larger imbalance (of
    either sign) fails the case's check, so the suite exits 1."""
    check = envelope.check_solution(_solution(imbalance))
    assert (check == "ok") is passes
    if not passes:
        assert "energy balance" in check
