"""Mesh-independence sweeps: the convergence table against analytic sequences, time to reach an error,
grid and option checking, `tehl sweep` writing HDF5 + CSV, parallel = serial, and the CI convergence check
of a face gear point (the full 33-513 sweep is `slow`)."""

from __future__ import annotations

import csv
from dataclasses import replace
import math

from click.testing import CliRunner
from hypothesis import given
from hypothesis import strategies as st
import numpy as np
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.cli import tehl
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.results import NonFiniteError, RunResult, read_result, write_result
from facegear_tehl.schema import CaseError
from facegear_tehl.solution import Field
from facegear_tehl.sweep import (
    MAX_ORDER,
    SAFETY_FACTOR,
    check_grids,
    convergence,
    iteration_warnings,
    parse_grids,
    run_sweep,
    tabulated,
    time_to_reach,
)
from facegear_tehl.sweep import _summary_lines as report_lines

import synthetic
from test_parallel import assert_same_file

FACE_GEAR = synthetic.CASES / "facegear_110.yaml"
GRIDS = (33, 65, 129, 257, 513)
SWEEP_THERMAL_TOLERANCE = 3e-4  # of the rise: the loop's iteration error well below the grid changes of dT_max


def _sequence(limit: float, coefficient: float, order: float, grids=GRIDS) -> list[float]:
    """f_h = f* + C h^p with h = 1/(n - 1)."""
    return [limit + coefficient * (1.0 / (n - 1)) ** order for n in grids]


# ---------------------------------------------------------------------------------------- table logic

def test_second_order_sequence_gives_order_2_and_the_exact_limit():
    values = _sequence(2.0, 50.0, 2.0)
    q = convergence("h_c", "m", GRIDS, values, tolerance=0.01)
    assert np.isnan(q.change[0]) and np.isnan(q.order[:2]).all() and np.isnan(q.extrapolated[:2]).all()
    np.testing.assert_allclose(q.order[2:], 2.0, rtol=1e-9)
    np.testing.assert_allclose(q.extrapolated[2:], 2.0, rtol=1e-12)
    np.testing.assert_allclose(q.change[1:], np.diff(values) / np.abs(values[1:]), rtol=1e-15)
    fine = np.diff(values)[1:]
    np.testing.assert_allclose(q.uncertainty[2:], SAFETY_FACTOR * np.abs(fine) / 3.0, rtol=1e-9)
    np.testing.assert_allclose(q.error, (np.array(values) - 2.0) / 2.0, atol=1e-12)


@given(limit=st.floats(0.1, 10.0), coefficient=st.floats(1.0, 100.0), sign=st.sampled_from([-1.0, 1.0]),
       order=st.floats(0.6, MAX_ORDER - 0.01))  # at the bound itself round-off decides the side
def test_any_power_law_gives_its_order_and_limit(limit, coefficient, sign, order):
    grids = GRIDS[:4]  # differences well above round-off
    q = convergence("f", "1", grids, _sequence(limit, sign * coefficient, order, grids), tolerance=0.01)
    np.testing.assert_allclose(q.order[2:], order, rtol=1e-6)
    np.testing.assert_allclose(q.extrapolated[2:], limit, rtol=1e-8)


@given(limit=st.floats(0.1, 10.0), coefficient=st.floats(1.0, 100.0), sign=st.sampled_from([-1.0, 1.0]),
       order=st.floats(2.1, 3.5))
def test_an_order_above_the_formal_one_is_not_trusted_but_its_band_holds_the_limit(limit, coefficient, sign, order):
    """Observed p above 2.05: f* and U with the formal order 2 and F_s = 3 (Roache 2011; Eça & Hoekstra 2014), so
    U = |f_h - f_2h| by hand. For a true power law of that order the limit lies inside f* +- U: f* - limit =
    d (1/3 - 1/(2^p - 1)), below |d| = U for every p > 2. The observed order is still reported."""
    grids = GRIDS[:4]
    values = _sequence(limit, sign * coefficient, order, grids)
    q = convergence("f", "1", grids, values, tolerance=0.01)
    fine = np.diff(values)[1:]
    np.testing.assert_allclose(q.order[2:], order, rtol=1e-6)
    np.testing.assert_allclose(q.uncertainty[2:], np.abs(fine), rtol=1e-9)
    np.testing.assert_allclose(q.extrapolated[2:], np.array(values[2:]) + fine / 3.0, rtol=1e-12)
    assert (np.abs(q.extrapolated[2:] - limit) < q.uncertainty[2:]).all()


def test_the_order_bound_is_just_above_the_formal_order():
    """Just below p = 2.05 the triplet keeps its own order and F_s = 1.25; just above it the formal order with F_s = 3:
    U jumps from 1.25 |d|/(2^2.04 - 1) = 0.405 |d| to |d|, the price of not trusting an order the scheme cannot have."""
    below = convergence("f", "1", (33, 65, 129), [1.0, 1.0 + 2.0**2.04, 1.0 + 2.0**2.04 + 1.0], tolerance=0.01)
    assert below.order[2] == pytest.approx(2.04) and below.uncertainty[2] == pytest.approx(1.25 / (2.0**2.04 - 1.0))
    above = convergence("f", "1", (33, 65, 129), [1.0, 1.0 + 2.0**2.1, 1.0 + 2.0**2.1 + 1.0], tolerance=0.01)
    assert above.uncertainty[2] == pytest.approx(1.0) and above.extrapolated[2] == pytest.approx(2.0 + 2.0**2.1 + 1 / 3)


def test_first_order_sequence_and_the_grid_within_tolerance():
    # f = 1 + 1.28 h: changes 1.96 %, 0.99 %, 0.50 %, 0.25 % (relative to the finer value)
    q = convergence("h_min", "m", GRIDS, _sequence(1.0, 1.28, 1.0), tolerance=0.01)
    np.testing.assert_allclose(q.order[2:], 1.0, rtol=1e-9)
    assert q.converged_grid == 65  # its change to 129 and every later one is below 1 %
    assert convergence("h_min", "m", GRIDS, _sequence(1.0, 1.28, 1.0), tolerance=0.001).converged_grid is None


def test_a_late_jump_resets_the_grid_within_tolerance():
    q = convergence("p_max", "Pa", GRIDS, [100.0, 100.5, 100.6, 103.0, 103.1], tolerance=0.01)
    assert q.converged_grid == 257


def test_undefined_entries():
    exact = convergence("f", "1", (33, 65, 129), [1.0, 1.1, 1.1], tolerance=0.01)
    assert np.isnan(exact.order[2]) and exact.extrapolated[2] == 1.1 and exact.uncertainty[2] == 0.0
    diverging = convergence("f", "1", (33, 65, 129), [1.0, 1.1, 1.3], tolerance=0.01)
    assert diverging.order[2] == pytest.approx(-1.0)
    assert np.isnan(diverging.extrapolated[2]) and np.isnan(diverging.error).all()
    slow = convergence("f", "1", (33, 65, 129), [1.0, 1.1, 1.19], tolerance=0.01)  # p = 0.15: no extrapolation
    assert slow.order[2] == pytest.approx(math.log2(0.1 / 0.09)) and np.isnan(slow.extrapolated[2])
    restarting = convergence("f", "1", (33, 65, 129), [1.0, 1.0, 1.3], tolerance=0.01)
    assert np.isnan(restarting.order[2]) and np.isnan(restarting.extrapolated[2])


def test_the_summary_line_says_when_the_observed_order_was_not_taken():
    """The summary of h_c from the 513 x 129 S1 triplet (docs/accuracy.md: 1.19985, 1.20459, 1.20552 um, observed
    order 2.35) names the formal order it took; a /sweep table written before the bound (no max_order) does not."""
    values = [1.19985e-6, 1.20459e-6, 1.20552e-6]
    q = convergence("h_c", "m", (129, 257, 513), values, tolerance=0.01)
    table = {"h_c": Field(q.values, "m", ""), "h_c_order": Field(q.order, "1", ""),
             "h_c_extrapolated": Field(q.extrapolated, "m", ""), "h_c_uncertainty": Field(q.uncertainty, "m", "")}
    line = report_lines(table, {"tolerance": 0.01, "max_order": MAX_ORDER, "high_order_safety_factor": 3.0})[0]
    assert q.order[2] == pytest.approx(math.log2(474 / 93)) and q.uncertainty[2] == pytest.approx(0.00093e-6)
    assert "(order 2.35; above 2.05: order 2, safety factor 3)" in line and "± 0.00093 µm" in line, line
    assert "above" not in report_lines(table, {"tolerance": 0.01})[0]


def test_time_to_reach_interpolates_on_the_log_log_curve():
    times = [0.1, 0.4, 1.6, 6.4]
    errors = [0.08, -0.02, 0.005, 0.00125]  # |e| = 0.008 t^-1
    assert time_to_reach(times, errors, 0.01) == pytest.approx(0.8)
    assert time_to_reach(times, errors, 0.2) == 0.1  # the coarsest grid is already there
    assert math.isnan(time_to_reach(times, errors, 0.001))  # not reached
    crossing = 0.4 * 4 ** (math.log(2) / math.log(5))  # between 0.02 at 0.4 s and 0.004 at 1.6 s
    assert time_to_reach([0.1, 0.4, 1.6], [0.005, 0.02, 0.004], 0.01) == pytest.approx(crossing)
    assert math.isnan(time_to_reach([0.1, 0.4, 1.6], [math.nan] * 3, 0.01))


# -------------------------------------------------------------------------------------- grid checking

@pytest.mark.parametrize(
    "text, expected",
    [
        ("33,64,129", "2^n + 1"),
        ("9,17,33", "at least solver.coarsest_grid"),
        ("65,33,129", "each refining the previous by 2"),
        ("33,129,513", "each refining the previous by 2"),
        ("33,33,65", "each refining the previous by 2"),
        ("33,65", "at least three grids"),
        ("33,sixty-five,129", "comma-separated"),
        ("", "comma-separated"),
    ],
)
def test_bad_grids(text, expected):
    with pytest.raises(CaseError, match="--grids") as error:
        parse_grids(text, synthetic.ball_on_disc())
    assert expected in str(error.value)


def test_good_grids():
    assert parse_grids("17, 33,65", synthetic.ball_on_disc()) == (17, 33, 65)
    assert check_grids([33, 65, 129, 257, 513], synthetic.ball_on_disc()) == GRIDS


def test_the_sweep_table_keeps_nan_for_undefined_entries_but_refuses_inf(tmp_path):
    case = synthetic.ball_on_disc()
    q = convergence("h_c", "m", (33, 65, 129), [1.0e-7, 1.2e-7, 1.25e-7], tolerance=0.01)
    table = {"grid": Field(np.array([33.0, 65.0, 129.0]), "1"), "h_c_order": Field(q.order, "1", "order")}
    write_result(RunResult(case=case, points=(), sweep=table, sweep_scalars={"tolerance": (0.01, "1")}),
                 tmp_path / "s.h5")
    back = read_result(tmp_path / "s.h5")
    np.testing.assert_array_equal(back.sweep["h_c_order"].values, q.order)
    assert back.sweep_scalars == {"tolerance": 0.01} and back.sweep_units == {"tolerance": "1"}
    table["h_c_order"] = Field(np.array([np.inf, 1.0, 2.0]), "1")
    with pytest.raises(NonFiniteError):
        write_result(RunResult(case=case, points=(), sweep=table), tmp_path / "t.h5")


# ---------------------------------------------------------------------------------------------- CLI

def _invoke(*args) -> object:
    return CliRunner().invoke(tehl, ["sweep", *(str(a) for a in args)])


def _square(case):
    """The face gear case on square grids (its 257 x 65 has too few y nodes below 65 along x for the quick
    sweeps here: 33 x 17 does not converge)."""
    return replace(case, solver=replace(case.solver, grid=129, grid_y=None))


def _square_file(tmp_path):
    path = tmp_path / "facegear_square.yaml"
    text = FACE_GEAR.read_text()
    assert "  grid: 257\n  grid_y: 65\n" in text
    path.write_text(text.replace("  grid: 257\n  grid_y: 65\n", "  grid: 129\n"))
    return path


@pytest.mark.parametrize(
    "options, key, expected",
    [
        (["--grids", "33,64,129"], "--grids", "2^n + 1"),
        (["--grids", "65,33,129"], "--grids", "refining the previous by 2"),
        (["--grids", "33,65"], "--grids", "at least three grids"),
        (["--point", "S9"], "--point", "among: S1, S2, S3, S4, S5"),
        (["--thermal", "warm"], "--thermal", "one of off, reduced, full, auto"),
        (["--tol", "0"], "--tol", "(0, 1)"),
        (["--jobs", "0"], "--jobs", ">= 1"),
        (["-o", "s.csv"], "--output", "HDF5"),
    ],
)
def test_bad_sweep_options_exit_2(tmp_path, monkeypatch, options, key, expected):
    monkeypatch.chdir(tmp_path)
    result = _invoke(FACE_GEAR, *options)
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {key}: ") and expected in lines[0], result.stderr
    assert list(tmp_path.iterdir()) == []


def _read_csv(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def test_sweep_ball_on_disc_writes_hdf5_and_csv(tmp_path):
    target = tmp_path / "out" / "bod.h5"
    result = _invoke(synthetic.BALL_ON_DISC, "--grids", "17,33,65", "-o", target)
    assert result.exit_code in (0, 3), result.output
    assert "tehl sweep: ball_on_disc: contact on grids 17,33,65, thermal off" in result.stderr
    written = read_result(target)
    assert list(written.points) == ["contact@17", "contact@33", "contact@65"]
    assert written.overrides == {"point": "contact", "grids": [17, 33, 65]}
    table = written.sweep
    assert tabulated(table) == ["p_max", "h_c", "h_min"]  # no dT_max or mu from the isothermal solver
    np.testing.assert_array_equal(table["grid"].values, [17, 33, 65])
    assert table["h_c"].units == "m" and table["h_c_uncertainty"].units == "m" and table["wall_time"].units == "s"
    for i, name in enumerate(written.points):
        assert table["h_c"].values[i] == written.points[name].scalars["h_c"]
        assert table["work_units"].values[i] == written.points[name].scalars["work_units"]
    assert written.points["contact@65"].fields["pressure"].values.shape == (65, 65)
    assert written.sweep_scalars["tolerance"] == 0.01 and written.sweep_scalars["safety_factor"] == 1.25
    rows = _read_csv(target.with_suffix(".csv"))
    assert [row["grid [1]"] for row in rows] == ["17", "33", "65"]
    assert rows[0]["h_c_order [1]"] == "" and float(rows[2]["h_c [m]"]) == pytest.approx(table["h_c"].values[2])
    assert "h_c [µm]" in result.stdout and "extrapolated" in result.stdout and "h_c: " in result.stdout
    info = CliRunner().invoke(tehl, ["info", str(target)])
    assert info.exit_code == 0 and "sweep table" in info.stdout and "contact@65" in info.stdout


def test_sweep_a_face_gear_point(tmp_path):
    target = tmp_path / "fg.h5"
    result = _invoke(_square_file(tmp_path), "--grids", "17,33,65", "--point", "S3", "--thermal", "off", "-o", target)
    assert result.exit_code in (0, 3), result.output
    written = read_result(target)
    assert list(written.points) == ["S3@17", "S3@33", "S3@65"] and written.overrides["thermal"] == "off"
    assert written.contact["s"].units == "m"  # the contact path of the gear pair, as in a run
    h_c = written.sweep["h_c"].values
    assert 0.0 < h_c[0] < h_c[1] < h_c[2] < 1e-5  # the film grows with refinement (see the CI test)
    assert len(_read_csv(target.with_suffix(".csv"))) == 3


def test_sweep_jobs_2_gives_the_same_file_as_jobs_1(tmp_path):
    for jobs in ("1", "2"):
        result = _invoke(_square_file(tmp_path), "--grids", "17,33,65", "--jobs", jobs, "-o",
                         tmp_path / f"jobs{jobs}.h5")
        assert result.exit_code in (0, 3), result.output
    assert_same_file(tmp_path / "jobs1.h5", tmp_path / "jobs2.h5")


def test_a_thermal_model_the_solver_did_not_run_is_reported():
    def solve(point, lub, settings):
        return synthetic.solution(point)

    case = synthetic.ball_on_disc()
    case = replace(case, lubricant=replace(case.lubricant, temperature_viscosity=0.042), missing_thermal=())
    sweep = run_sweep(case, (17, 33, 65), thermal="full", jobs=1, solver=solve)
    assert sweep.run.warnings == tuple(f"contact@{n}: thermal model 'full' asked for, the solver used 'off'"
                                       for n in (17, 33, 65))
    assert sweep.run.case.solver.thermal == "full" and sweep.run.overrides["thermal"] == "full"
    assert run_sweep(case, (17, 33, 65), thermal="off", jobs=1, solver=solve).run.warnings == ()


def test_a_dt_max_change_within_the_thermal_loops_iteration_error_is_warned_of():
    """S1 of the default case at its default thermal tolerance (2e-3 of the rise): dT_max 96.94, 97.53, 97.92 K on
    the 129, 257 and 513 grids, a last change of 0.39 K against the loop's 0.20 K per update, whose iteration error
    made the default grid's extrapolated error -1.1 % instead of the converged loop's -0.43 % (96.86, 97.58, 97.84 K
    at 3e-4 of the rise: 0.27 K against 0.03 K, no warning). The warning names the tolerance that would do; a grid
    that did not converge is skipped, a sweep without dT_max (isothermal) has none; through run_sweep it reaches
    the run's warnings."""
    def rises(values, tolerance):
        return iteration_warnings([convergence("dT_max", "K", (129, 257, 513), values, 0.01)], tolerance)

    (warning,) = rises([96.94, 97.53, 97.92], 2e-3)
    assert "0.39 K" in warning and "2e-03 of the 97.9 K rise = 0.196 K" in warning and "below 8.0e-04" in warning
    assert rises([96.86, 97.58, 97.84], 3e-4) == ()
    assert len(rises([96.94, 97.53, math.nan], 2e-3)) == 1  # 96.94 -> 97.53: 0.59 K against 0.98 K
    assert rises([96.94, 97.53, math.nan], 1e-3) == ()
    assert rises([97.53, math.nan, math.nan], 2e-3) == ()
    assert iteration_warnings([convergence("h_c", "m", (129, 257, 513), [1.0, 1.1, 1.11], 0.01)], 2e-3) == ()

    def solve(point, lub, settings):
        solved = synthetic.solution(point)
        rise = 97.0 - 5.0 / (settings.grid - 1)  # 0.10 K between the finest two of 17, 33, 65
        return replace(solved, scalars={**solved.scalars, "dT_max": (rise, "K")})

    case = synthetic.ball_on_disc()
    warnings = run_sweep(case, (17, 33, 65), jobs=1, solver=solve).run.warnings
    assert [w for w in warnings if w.startswith("dT_max changes by 0.0781 K")], warnings
    tight = replace(case, solver=replace(case.solver, thermal_tolerance=1e-4))
    assert not [w for w in run_sweep(tight, (17, 33, 65), jobs=1, solver=solve).run.warnings if "dT_max" in w]


def test_a_grid_that_did_not_converge_enters_no_order_or_extrapolation():
    """The finest grid's solve fails (as the thermal 513^2 face gear does: the 257^2 solution is returned):
    its value must not be read as a converged one (it would fake an order of 8 from a zero change)."""
    def solve(point, lub, settings):
        value = 1.0 + 0.3 / (settings.grid - 1) ** 2
        solved = synthetic.solution(point, converged=settings.grid < 129)
        return replace(solved, scalars={**solved.scalars, "h_c": (value, "m")})

    sweep = run_sweep(synthetic.ball_on_disc(), (17, 33, 65, 129), jobs=1, solver=solve)
    h_c = next(q for q in sweep.quantities if q.name == "h_c")
    assert math.isnan(h_c.values[-1]) and math.isnan(h_c.change[-1]) and math.isnan(h_c.order[-1])
    assert h_c.order[2] == pytest.approx(2.0, rel=1e-9) and h_c.extrapolated[2] == pytest.approx(1.0, rel=1e-12)
    assert h_c.error[0] == pytest.approx(0.3 / 16**2, rel=1e-9)  # against the f* of 17, 33, 65
    assert h_c.converged_grid is None


def test_a_grid_whose_film_closed_leaves_the_others_tables_whole():
    """The coarsest grid's film closes (no h_c reported, as a Barus contact at M = 478 on 65^2): the converged grids'
    tables are still printed and written, the closed grid's entries NaN."""
    def solve(point, lub, settings):
        solved = synthetic.solution(point, converged=settings.grid > 17)
        value = 1.0 + 0.3 / (settings.grid - 1) ** 2
        scalars = {k: v for k, v in solved.scalars.items() if solved.converged or k not in ("h_c", "h_min", "p_max")}
        return replace(solved, scalars={**scalars, **({"h_c": (value, "m")} if solved.converged else {})})

    sweep = run_sweep(synthetic.ball_on_disc(), (17, 33, 65, 129), jobs=1, solver=solve)
    h_c = next(q for q in sweep.quantities if q.name == "h_c")
    assert math.isnan(h_c.values[0]) and h_c.values[1:] == pytest.approx([1.0 + 0.3 / n**2 for n in (32, 64, 128)])
    assert h_c.order[3] == pytest.approx(2.0, rel=1e-9)
    assert {"h_min", "p_max"} <= {q.name for q in sweep.quantities}


# ------------------------------------------------------------------------------- grid convergence (CI)

def _assert_converges(table, names, first, last, iteration_error=0.0):
    """Monotone over the grids first..last, observed order in [1, 2.5] on every triplet ending there, to within the
    order's own uncertainty when each value carries a relative iteration error up to `iteration_error` (a thermal
    loop that ends at its floor: TUNING.thermal_floor_h_c): p = log2(D_1/D_2) of the changes D_1, D_2 between the
    grids, each off by up to 2 e |f|, is uncertain by (2 e |f|/D_1 + 2 e |f|/D_2)/ln 2. A triplet whose uncertainty
    reaches 1 does not measure an order (its finest change is within the iteration error); at least one must."""
    grids = list(table["grid"].values)
    rows = slice(grids.index(first), grids.index(last) + 1)
    for name in names:
        values = table[name].values[rows]
        steps = np.diff(values)
        assert (steps > 0).all() or (steps < 0).all(), (name, table[name].values)
        orders = table[f"{name}_order"].values[rows][2:]
        noise = 2.0 * iteration_error * np.abs(values[2:])
        spread = (noise / np.abs(steps[:-1]) + noise / np.abs(steps[1:])) / math.log(2.0)
        measured = spread < 1.0
        assert measured.any(), (name, orders, spread)
        assert ((orders + spread >= 1.0) & (orders - spread <= 2.5))[measured].all(), (name, orders, spread)


def test_face_gear_point_converges_monotonically_at_second_order():
    """Issue 7, item 3: grids 33-129, isothermal, the pitch point S3 (h_c and h_min; p_max, the spike,
    is not monotone)."""
    sweep = run_sweep(_square(load_case(FACE_GEAR)), (33, 65, 129), point="S3", thermal="off")
    assert sweep.run.status == "ok"
    _assert_converges(sweep.run.sweep, ["h_c", "h_min"], 33, 129)


@pytest.mark.slow
def test_s1_of_the_face_gear_case_converges_and_the_default_grid_is_within_1_percent():
    """Grids 65 x 17 to 513 x 129 at S1 with the case's model (thermal full, Ree-Eyring; the docs/accuracy.md table):
    h_c and h_min converge monotonically, h_c at order 1-2.5 within the order's uncertainty from the thermal loop's
    floor (h_min's order on 65 x 17 - 257 x 65 is 0.36 +- 0.3: 17 rows do not resolve the side lobes where it lies;
    on the finer triplet its change is within the floor), and the default grid (257 x 65) is within 1 % of the
    extrapolated value in h_c, h_min and dT_max (issue 7). The thermal loop is converged to SWEEP_THERMAL_TOLERANCE:
    dT_max changes by 0.3-0.7 K between the finer grids, and the default tolerance's iteration error (up to 2e-3 of
    the 97 K rise per update) moved its extrapolation from -0.43 % (converged) to -1.1 % or -0.40 % depending on
    where each grid's loop stopped (docs/accuracy.md)."""
    case = load_case(FACE_GEAR)
    case = replace(case, solver=replace(case.solver, thermal_tolerance=SWEEP_THERMAL_TOLERANCE))
    sweep = run_sweep(case, GRIDS[1:], point="S1")
    table = sweep.run.sweep
    assert sweep.run.status == "ok"
    _assert_converges(table, ["h_c"], 65, 513, iteration_error=TUNING.thermal_floor_h_c)
    h_min = table["h_min"].values
    assert (np.diff(h_min) > 0).all() or (np.diff(h_min) < 0).all(), h_min
    default = list(table["grid"].values).index(case.solver.grid)
    for name in ("h_c", "h_min", "dT_max"):
        assert abs(table[f"{name}_error"].values[default]) < 0.01, name
    for name in ("h_c", "h_min"):
        assert table[f"{name}_uncertainty"].values[-1] < 0.005 * table[name].values[-1]


@pytest.mark.slow
def test_full_sweep_of_the_circular_benchmark():
    """Grids 33-513 on the isothermal circle of Venner & Lubrecht (2000): monotone, h_c at order 1-2.5 (h_min, a
    minimum over the nodes, reaches 2.8 on the finest triplet), the 513^2 values within 0.1 % of the
    extrapolated ones."""
    sweep = run_sweep(synthetic.ball_on_disc(), GRIDS)
    table = sweep.run.sweep
    assert sweep.run.status == "ok"
    _assert_converges(table, ["h_c"], 33, 513)
    assert (np.diff(table["h_min"].values) > 0).all() and (table["h_min_order"].values[2:] > 1.0).all()
    assert abs(table["h_c_error"].values[-1]) < 1e-3 and abs(table["h_min_error"].values[-1]) < 1e-3


@pytest.mark.slow
def test_full_sweep_of_s1():
    """Issue 19: the thermal face gear converges on 513^2 (S1, thermal full, Ree-Eyring; square grids 33-513, each
    solved to its tolerances), h_c and h_min monotone at observed order 1-2.5 from 65^2 up."""
    case = _square(load_case(FACE_GEAR))
    sweep = run_sweep(case, GRIDS, point="S1")
    assert sweep.run.status == "ok"
    _assert_converges(sweep.run.sweep, ["h_c", "h_min"], 65, 513)
