"""The film regime of each point (film_regime.py, verdict.assess): thresholds and the boundary warning."""

from dataclasses import replace

import pytest

from facegear_tehl.cli import info_text
from facegear_tehl.cycle import with_film_parameter
from facegear_tehl.film_regime import Regime, regime
from facegear_tehl.points import contact_analysis
from facegear_tehl.results import RunResult, read_result, write_result
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
    smooth = rough_run(0.0)
    assert assess(smooth) is smooth
