"""The thermal film against a published one (facegear_tehl/suites/thermal_validation.py): the central film lost to
inlet shear heating in pure rolling, h_c(thermal)/h_c(isothermal), of the line solver and of a long ellipse solved as
a `contact:` case (run_case, the path of `tehl run`), against a thermal inlet-zone analysis solved from scratch under
the published analyses' assumptions (facegear_tehl/suites/thermal_inlet.py) and the thermal correction factor of
Wilson & Sheu (1983, J. Lubr. Technol. 105:187, eq. 8), C = 1/(1 + 0.241 L^0.64), L = eta_0 beta u_e^2/k_f; and the
inlet analysis itself against Ertel & Grubin's film, the Hertz gap and, at the large L where they were fitted, the
published fits. Tolerances and their reasons: those modules' docstrings and docs/accuracy.md (Published thermal
validation)."""

from __future__ import annotations

import math

import pytest
from scipy import integrate

from facegear_tehl.suites import thermal_inlet as ti
from facegear_tehl.suites import thermal_validation as tv

WORKING_GRID = (401, 12)  # nodes x layers: C within 0.7 % of the 801 x 24 grid's (the script's table)
ELLIPSE_GRID = (65, 17)  # grid x grid_y: C within 0.2 % of the 129 x 33 grid's (the script's table)
ASSERTED_SPEEDS = tuple(u for u in tv.ROLLING_SPEEDS if tv.thermal_loading(tv.OIL, u) <= tv.LARGEST_ASSERTED_LOADING)


def _rows(nodes: int, layers: int, solver: str = "line") -> list[tv.Row]:
    rows = [tv.compare(u, nodes, layers, (nodes, layers), solver) for u in ASSERTED_SPEEDS]
    assert all(r.converged for r in rows)
    return rows


def test_loadings_span_the_face_gear_points():
    """The asserted rows reach L = 0.86, inside the face gear points' 0.57-1.42, from the near-isothermal
    L = 0.03."""
    loadings = [tv.thermal_loading(tv.OIL, u) for u in ASSERTED_SPEEDS]
    assert loadings[0] < tv.SMALL_LOADING and 0.57 < loadings[-1] <= tv.LARGEST_ASSERTED_LOADING


@pytest.fixture(scope="module")
def line_rows() -> list[tv.Row]:
    return _rows(*WORKING_GRID)


def test_rolling_film_reduction_against_the_inlet_analysis_and_wilson_sheu(line_rows):
    """401 x 12: C within 3 % of the inlet analysis's (measured -0.7, -1.2, -0.4 % at L = 0.034, 0.21, 0.86),
    within 2 % of Wilson & Sheu's at L = 0.034 (measured +1.5 %) and within 10 % at L = 0.21 and 0.86 (+3.7 %,
    +6.4 %: their fit's own departure from the analysis, test_published_fits_overstate_the_loss_below_their_range);
    all fall with L."""
    rows = line_rows
    for r in rows:
        assert r.ratio == pytest.approx(r.inlet, rel=tv.INLET_TOLERANCE), (r.loading, r.ratio, r.inlet)
        assert r.ratio == pytest.approx(r.wilson_sheu, rel=r.tolerance), (r.loading, r.ratio, r.wilson_sheu)
    ours = [r.ratio for r in rows]
    published = [r.wilson_sheu for r in rows]
    assert ours == sorted(ours, reverse=True) and published == sorted(published, reverse=True)
    assert all(c < 1.0 for c in ours)


def test_case_path_film_reduction_against_wilson_sheu(line_rows):
    """The long ellipse (a/b = 99.9) as a `contact:` case, 65 x 17, thermal full against off: the same tolerances
    (measured +1.4, +3.6, +6.4 %; against the inlet analysis -0.8, -1.3, -0.4 %), and its C is the line solver's
    within 0.5 % (measured 0.1 %)."""
    ellipse = _rows(*ELLIPSE_GRID, solver="ellipse")
    for e, r in zip(ellipse, line_rows, strict=True):
        assert e.ratio == pytest.approx(e.inlet, rel=tv.INLET_TOLERANCE), (e.loading, e.ratio, e.inlet)
        assert e.ratio == pytest.approx(e.wilson_sheu, rel=e.tolerance), (e.loading, e.ratio, e.wilson_sheu)
        assert e.ratio == pytest.approx(r.ratio, rel=0.005)


@pytest.mark.slow
def test_rolling_film_reduction_on_the_check_grid(line_rows):
    """801 x 24 (the script's check grid): the same tolerances hold (measured against the inlet analysis -0.6, -1.0,
    +0.1 %, against Wilson & Sheu +1.5, +3.9, +7.0 %) and C moves by less than 1 % from the working grid."""
    fine = _rows(801, 24)
    for r, c in zip(fine, line_rows, strict=True):
        assert r.ratio == pytest.approx(r.inlet, rel=tv.INLET_TOLERANCE)
        assert r.ratio == pytest.approx(r.wilson_sheu, rel=r.tolerance)
        assert r.ratio == pytest.approx(c.ratio, rel=0.01)


def test_inlet_gap_is_the_hertz_deflection():
    """The inlet analysis's gap outside the contact, (b^2/2R) G(X), against a quadrature of the Hertz deflection:
    H(X) - H(1) = X^2/2 - (1/pi) int sqrt(1 - S^2) ln|X - S| dS - (1 + 2 ln 2)/4 (H = h R/b^2; the last term is
    the flat gap of the contact, facegear_tehl.line.elastic), to 1e-8."""
    for x in (-1.01, -1.3, -2.0, -4.0):
        integral, _ = integrate.quad(lambda s, x=x: math.sqrt(1.0 - s * s) * math.log(abs(x - s)), -1.0, 1.0,
                                     limit=200)
        gap = 0.5 * x * x - integral / math.pi - 0.25 * (1.0 + 2.0 * math.log(2.0))
        assert 0.5 * float(ti.hertz_gap(x)) == pytest.approx(gap, rel=1e-8, abs=1e-12)


def test_inlet_isothermal_film_is_ertel_grubin():
    """At L = 0 the inlet analysis is Grubin's (1949): its film is Ertel & Grubin's h_0 = 1.95 R (U G)^(8/11)
    W^(-1/11) within 2 % (that formula is a power-law fit of Grubin's integral; measured +1.1, +0.7, -0.01, -0.6 %
    at 2, 5, 10, 15 m/s)."""
    for speed in tv.ROLLING_SPEEDS:
        inlet = tv.rolling_inlet(speed)
        reference = ti.ertel_grubin(inlet.radius, inlet.half_width, speed, inlet.viscosity, inlet.pressure_viscosity)
        assert inlet.film(0.0) == pytest.approx(reference, rel=0.02)


def test_inlet_analysis_reproduces_the_published_fits_at_large_loading():
    """At L = 10 and 20 the inlet analysis's C is Wilson & Sheu's eq. 8 and Murch & Wilson's within 3 % (measured
    +0.3 / +0.6 % and -1.9 / -2.3 %): the same analysis and the same L = eta_0 beta u_e^2/k_f as theirs (a factor
    2 in L moves C by 24-26 %). 3 %: a two-constant power law reproduces its data to a few per cent."""
    inlet = tv.rolling_inlet(tv.SENSITIVITY_SPEED)
    for loading in (10.0, 20.0):
        c = inlet.correction(loading)
        assert c == pytest.approx(tv.wilson_sheu(loading, 0.0), rel=0.03)
        assert c == pytest.approx(tv.murch_wilson(loading), rel=0.03)
        assert abs(inlet.correction(2.0 * loading) / c - 1.0) > 0.15


def test_published_fits_overstate_the_loss_below_their_range():
    """Below L ~ 3 the analysis's loss 1 - C is linear in L (the first-order cross-film solution, phi = 1 +
    lambda_0/336: (1 - C)/L = 0.180 at L = 0.001, 0.002 and 0.004, constant to 0.1 %), while the fits' form gives
    1 - C ~ L^0.64, which cannot follow it: their C is below the analysis's by more than 2 % at L = 0.034, 0.21,
    0.86 and 1.93 (measured 2.1, 4.8, 6.4, 5.8 %), the one-signed difference the line solver shows too."""
    inlet = tv.rolling_inlet(tv.SENSITIVITY_SPEED)
    slopes = [(1.0 - inlet.correction(loading)) / loading for loading in (0.001, 0.002, 0.004)]
    assert max(slopes) / min(slopes) < 1.01
    for loading in (0.034, 0.21, 0.86, 1.93):
        assert tv.wilson_sheu(loading, 0.0) < 0.98 * inlet.correction(loading)


def test_an_attempt_that_runs_away_warns_no_one(monkeypatch):
    """The long ellipse at 15 m/s on 129 x 33, isothermal, with the ellipse-scaled switch first (129 x 33 tries
    Venner's first, which converges at once): its first start overflows (inf - inf in a coarse right-hand side)
    before the finiteness checks stop the attempt and the solver retries it to convergence. The outcome says what
    happened; numpy's RuntimeWarning would only have printed noise on the user's terminal."""
    import dataclasses
    import warnings

    from facegear_tehl.case import parse_case
    from facegear_tehl.ehl import retry
    from facegear_tehl.ehl.staged import solve_point
    from facegear_tehl.points import contact_analysis

    monkeypatch.setattr(retry, "TUNING", dataclasses.replace(retry.TUNING, venner_first_nodes=1))

    case = parse_case(tv.ellipse_case_text(15.0, 129, 33, "off"), "long_ellipse_rolling")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        solution = solve_point(contact_analysis(case).points[0], case.lubricant, case.solver)
    assert solution.converged and solution.scalar("attempts") > 1
