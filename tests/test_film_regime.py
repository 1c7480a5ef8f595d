"""The film regime of each point (film_regime.py, verdict.assess): thresholds and the boundary warning."""

from dataclasses import replace

import pytest

from facegear_tehl.cli import info_json, info_text
from facegear_tehl.cycle import with_film_parameter
from facegear_tehl.film_regime import Regime, regime
from facegear_tehl.points import contact_analysis
from facegear_tehl.results import RunResult, read_result, write_result
from facegear_tehl.scuffing import flash_safety
from facegear_tehl.verdict import assess

import synthetic


@pytest.mark.parametrize("value, expected", [(0.2, Regime.BOUNDARY), (0.999, Regime.BOUNDARY), (1.0, Regime.MIXED),
                                             (2.999, Regime.MIXED), (3.0, Regime.FULL_FILM), (12.0, Regime.FULL_FILM)])
def test_regime_thresholds(value, expected):
    # Hamrock, Schmid & Jacobson (2004): boundary below lambda = 1, full film from lambda = 3, mixed between
    assert regime(value) is expected


def rough_run(roughness: float) -> RunResult:
    """The synthetic ball-on-disc run (h_c = 150 nm, h_min = 90 nm) with both surfaces of RMS roughness R_q."""
    case = synthetic.ball_on_disc()
    body = replace(case.materials.body_1, roughness=roughness)
    case = replace(case, materials=replace(case.materials, body_1=body, body_2=body))
    point = contact_analysis(case).points[0]
    return RunResult(case=case, points=(with_film_parameter(synthetic.solution(point), point),))


def test_a_boundary_point_is_named_in_the_warnings_and_the_file(tmp_path):
    # sigma = sqrt(2) x 100 nm = 141.4 nm: lambda_min = 90/141.4 = 0.636, lambda_c = 150/141.4 = 1.061 (by hand)
    run = assess(rough_run(1.0e-7))
    point = run.points[0]
    assert point.scalar("film_parameter") == pytest.approx(0.6364, rel=1e-3)
    assert point.scalar("film_parameter_central") == pytest.approx(1.0607, rel=1e-3)
    assert len(run.warnings) == 1 and f"below 1 at {point.name} 0.64: boundary lubrication" in run.warnings[0]
    result = read_result(write_result(run, tmp_path / "rough.h5"), fields=False)
    assert result.warnings == run.warnings
    assert "boundary lubrication" in info_text(result)


def test_a_full_film_and_a_smooth_case_warn_nothing():
    # sigma = sqrt(2) x 20 nm = 28.3 nm: lambda_min = 3.18, full film
    assert assess(rough_run(2.0e-8)).warnings == ()
    smooth = assess(rough_run(0.0))
    assert smooth.warnings == () and "lambda_min" not in smooth.verdict
    assert "film_parameter_central" not in smooth.points[0].scalars


def test_the_verdict_names_the_lowest_film_the_hottest_flank_and_one_efficiency(tmp_path):
    run = rough_run(1.0e-7)
    hot = replace(run.points[0], scalars={**run.points[0].scalars, "contact_temperature_1": (400.0, "K"),
                                          "contact_temperature_2": (410.0, "K"),
                                          "contact_temperature_blok_1": (395.0, "K"),
                                          "contact_temperature_blok_2": (395.0, "K")})
    cycle = {"mesh_efficiency": (0.99, "1"), "power_loss": (100.0, "W"), "mesh_efficiency_dissipated": (0.97, "1"),
             "power_loss_dissipated": (300.0, "W"), "mesh_efficiency_xu": (0.995, "1"), "power_loss_xu": (50.0, "W")}
    # theta_S = 300 degC given, theta_oil = the 40 degC inlet: S_B = (573.15 - 313.15)/(410 - 313.15) = 2.6846
    # solved and (573.15 - 313.15)/(395 - 313.15) = 3.1765 by Blok (the form of DIN 3990-4's S_B)
    oil = replace(run.case.lubricant, scuffing_temperature=573.15)
    run = replace(run, case=replace(run.case, lubricant=oil))
    verdict = assess(replace(run, points=(hot,), cycle_scalars=cycle))
    assert verdict.verdict["scuffing_safety"][0] == pytest.approx(2.6846, rel=1e-4)
    assert verdict.verdict["scuffing_safety_blok"][0] == pytest.approx(3.1765, rel=1e-4)
    assert verdict.verdict["lambda_min"][0] == pytest.approx(0.6364, rel=1e-3)
    assert verdict.verdict_labels == {"lambda_min_point": hot.name, "regime": "boundary"}
    assert verdict.verdict["contact_temperature_max"] == (410.0, "K")
    assert verdict.verdict["contact_temperature_blok_max"] == (395.0, "K")
    assert verdict.verdict["mesh_efficiency"] == (0.99, "1") and verdict.verdict["power_loss"] == (100.0, "W")
    result = read_result(write_result(verdict, tmp_path / "verdict.h5"), fields=False)
    assert result.verdict["lambda_min"] == pytest.approx(0.6364, rel=1e-3)
    assert result.verdict_labels["regime"] == "boundary"
    assert info_json(result)["verdict"]["labels"]["regime"] == "boundary"
    text = info_text(result)
    assert f"lambda_min 0.64 at {hot.name}, lambda_c 1.06 there: boundary" in text
    assert "max 136.9 °C solved TEHL" in text and "121.9 °C Blok" in text
    assert "99.000 % recommended: film mu (solved) x sliding speed, power loss 100.0 W, an upper bound" in text
    assert "97.000 % film dissipation" in text and "99.500 % Xu et al." in text
    assert "S_B 2.68 solved, 3.18 Blok formula against theta_S 300 °C given" in text


def test_no_scuffing_safety_without_a_temperature_rise():
    assert flash_safety(573.15, 313.15, 313.15) is None
    assert flash_safety(573.15, 313.15, 443.15) == pytest.approx(2.0)
