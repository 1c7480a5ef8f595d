"""`solver.thermal: auto` (ehl/thermal.py thermal_choice): its heating number against Blok's published flash
temperature, the envelope fit against an analytic power law, the decision on the shipped cases, and (slow) the
model it picks against `full` on contacts the fit did not see."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.thermal import (
    AUTO_FIGURES,
    heating_number,
    predicted_error,
    sliding_heating,
    thermal_choice,
    thermal_loading,
)
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.points import contact_analysis
from facegear_tehl.suites import thermal_auto as ta

CASES = Path(__file__).resolve().parent.parent / "cases"
BLOK_SAME_MATERIAL = 1.11  # Blok (1937): dT_f = 1.11 mu w' |sqrt(u1) - sqrt(u2)|/(sqrt(k rho c) sqrt(2b))


def _contact(speed: float, srr: float, pressure: float = 1.0e9, ratio: float = 5.0) -> tuple[ContactPoint, object]:
    lubricant = ta.shipped_oils(CASES)["facegear_110"]
    radius_y, load = ta.contact_geometry(ratio, pressure)
    return ContactPoint.from_rolling_sliding("c", ta.RADIUS_X, radius_y, load, speed, srr, 0.0, ta.STEEL,
                                             ta.STEEL), lubricant


def test_sliding_heating_is_beta_times_blok_flash_temperature_per_unit_friction():
    """Theta_s = beta dT_f/mu with Blok's (1937) same-material form on the centre line's load w' = 3W/(4a)."""
    point, lubricant = _contact(5.0, 0.8)
    u1, u2 = point.velocity_1[0], point.velocity_2[0]
    steel = ta.STEEL
    effusivity = math.sqrt(steel.thermal_conductivity * steel.density * steel.specific_heat)
    flash = (BLOK_SAME_MATERIAL * 3.0 * point.load / (4.0 * point.hertz.a) * abs(math.sqrt(u1) - math.sqrt(u2))
             / (effusivity * math.sqrt(2.0 * point.hertz.b)))
    assert sliding_heating(point, lubricant) == pytest.approx(lubricant.temperature_viscosity * flash, rel=2e-3)
    assert sliding_heating(_contact(5.0, 0.0)[0], lubricant) == 0.0


def test_envelope_fit_recovers_a_power_law_and_lies_on_its_highest_point():
    """Errors 0.2 G^0.8 times factors 0.5-1.5: the fit's exponent is the law's (the factors are symmetric in log
    about a line of that slope), the envelope passes through the highest point and overstates the lowest by 3x."""
    groups = np.array([0.01, 0.03, 0.1, 0.3, 1.0, 3.0])
    factors = np.array([1.5, 0.5, 1.0, 1.0, 0.5, 1.5])
    fit = ta.envelope_fit(groups, 0.2 * groups**0.8 * factors)
    assert fit.exponent == pytest.approx(0.8, abs=1e-9)
    assert fit.coefficient == pytest.approx(0.3, rel=1e-9)
    assert fit.spread == pytest.approx(3.0, rel=1e-9)
    assert all(fit(g) >= e * (1 - 1e-12) for g, e in zip(groups, 0.2 * groups**0.8 * factors))


def test_auto_picks_the_cheapest_model_the_envelope_puts_within_tolerance_and_says_why():
    """Slow pure rolling: off; the shipped face gear points (measured: off 12-22 % thin in h_c, docs/accuracy.md)
    never off; a hot sliding contact: full. The reason names the heating number and both predicted errors."""
    cold, lubricant = _contact(0.05, 0.0)
    hot, _ = _contact(15.0, 1.0)
    assert thermal_choice("auto", cold, lubricant)[0] == "off"
    assert thermal_choice("auto", hot, lubricant)[0] == "full"
    case = load_case(CASES / "facegear_110.yaml")
    for point in contact_analysis(case).points:
        model, reason = thermal_choice("auto", point, case.lubricant)
        assert model != "off", reason
        number = heating_number(point, case.lubricant)
        assert f"G = {number:.3g}" in reason and f"{100 * predicted_error('off', number):.3g} %" in reason
        assert (model == "reduced") == (predicted_error("reduced", number) < TUNING.auto_tolerance)
    assert heating_number(cold, lubricant) == pytest.approx(thermal_loading(cold, lubricant))
    assert thermal_choice("full", cold, lubricant) == ("full", "solver.thermal: full")


@pytest.mark.slow
def test_auto_is_within_its_tolerance_of_full_on_contacts_the_fit_did_not_see():
    """The contacts CHECKED of suites/thermal_auto.py (not in the fit) and S3 of the shipped face gear case at
    CHECKED_GEAR_SPEED, solved with `auto` and with `full` on the fit's grid: where auto picks a cheaper model, h_c,
    h_min and mu are within TUNING.auto_tolerance of full."""
    picked = []
    for checked in ta.check_contacts(CASES):
        model, results = ta.auto_against_full(checked)
        picked.append(model)
        if results:
            assert all(r.converged for r in results.values()), checked.name
            errors = {f: ta.relative_error(results, "auto", f) for f in AUTO_FIGURES}
            assert all(e <= TUNING.auto_tolerance for e in errors.values() if math.isfinite(e)), (checked.name, errors)
            assert math.isfinite(errors["h_c"]) and math.isfinite(errors["h_min"])
    assert {"off", "reduced"} <= set(picked), picked


def test_the_design_spans_the_ranges_the_brief_names():
    """The fit's contacts: L_th 2e-3 to 2, SRR 0-2, p_h 0.4-2 GPa, a/b 1-100, both rheologies, the three
    shipped oils."""
    contacts = ta.fit_contacts(CASES)
    loadings = [c.loading for c in contacts]
    assert min(loadings) < 3e-3 and max(loadings) > 1.5
    assert {c.lubricant.rheology for c in contacts} == {"ree_eyring", "newtonian"}
    assert {c.oil for c in contacts} == {Path(n).stem for n in ta.OIL_CASES}
    srr = [c.point.slide_roll_ratio for c in contacts]
    assert min(srr) == 0.0 and 1.5 < max(srr) <= 2.0
    pressures = [c.point.hertz.p_max for c in contacts]
    assert 0.4e9 <= min(pressures) < 0.6e9 and 1.8e9 < max(pressures) <= 2.0e9
