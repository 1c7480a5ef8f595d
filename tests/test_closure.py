"""A closed film that no grid within the caps resolves (ehl/closure.py, run.solve_refining): the Hertzian edge's gap law
against its closed form, the refinement's decision against Hamrock & Dowson's (1977) film and the grid's spacing
worked out here, and the slow face gear's real closed film reported at once with why."""

from __future__ import annotations

from dataclasses import replace
import math
from pathlib import Path

import pytest

from facegear_tehl.case import load_case
from facegear_tehl.ehl import closure
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.film_formulas import hamrock_dowson_minimum
from facegear_tehl.parallel import SolveTask
from facegear_tehl.points import contact_analysis
from facegear_tehl.record import Action, Reason, RetryRecord
from facegear_tehl.run import refinement_note, solve_refining
from facegear_tehl.solution import Outcome, PointSolution

import synthetic

FACEGEAR_90 = Path(__file__).resolve().parents[1] / "cases" / "facegear_90.yaml"


def _slow_case(tmp_path: Path, rpm: float) -> Path:
    """The shipped 90 deg face gear at `rpm` (its 3000 rpm replaced; the film thins as the speed^0.68)."""
    text = FACEGEAR_90.read_text(encoding="utf-8")
    assert "pinion_speed: 3000.0" in text
    target = tmp_path / f"slow_{rpm:g}.yaml"
    target.write_text(text.replace("pinion_speed: 3000.0", f"pinion_speed: {rpm:g}").replace(
        "file: facegear_90.h5", f"file: slow_{rpm:g}.h5"), encoding="utf-8")
    return target


def _hertz_edge_gap(xi: float) -> float:
    """The exact gap past the edge of a Hertzian line contact in H = h R/b^2: the integral of sqrt(T^2 - 1) from 1 to
    X = 1 + xi, (X sqrt(X^2 - 1) - arccosh X)/2."""
    x = 1.0 + xi
    return 0.5 * (x * math.sqrt(x * x - 1.0) - math.acosh(x))


@pytest.mark.parametrize("xi", [1e-4, 1e-3, 1e-2])
def test_the_constriction_of_a_film_is_where_the_hertzian_gap_has_risen_by_it(xi):
    """The width closure takes for a film is the distance past the edge at which the exact gap rises by that film,
    within the O(xi) of the 3/2 law."""
    width = closure.constriction_width(_hertz_edge_gap(xi))
    assert width == pytest.approx(xi, rel=xi)
    assert closure.constriction_width(-1.0) == 0.0  # a closed film has no constriction


def _point_and_task(case_file: Path, grid: int = 257, grid_y: int = 65) -> SolveTask:
    case = load_case(case_file)
    point = next(p for p in contact_analysis(case).points if p.name == "S3")
    return SolveTask(point, case.lubricant, replace(case.solver, grid=grid, grid_y=grid_y))


def _formula_nodes(task: SolveTask) -> float:
    """Nodes across the constriction of Hamrock & Dowson's h_min on the thermal cap's grid along x, worked out from
    the formula and Venner & Lubrecht's 6 b long domain (the slow gear's inlet is long enough unlengthened: its gap
    ratio passes the target at once)."""
    from facegear_tehl.ehl.scaling import scaling_for

    s = scaling_for(task.point, task.lubricant)
    film = hamrock_dowson_minimum(s.hamrock_u, s.hamrock_g, s.hamrock_w, s.ellipticity) * task.point.radius_x
    big_h = film * task.point.radius_x / s.b**2
    spacing = 6.0 / (TUNING.max_refined_thermal_grid - 1)
    return (3.0 * big_h / (2.0 * math.sqrt(2.0))) ** (2.0 / 3.0) / spacing + 1.0


class _AlwaysClosed:
    """A stand-in solver whose film closes on every grid (no film reported, as the EHL solver reports one)."""

    def __init__(self):
        self.grids: list[tuple[int, int]] = []

    def __call__(self, point, lubricant, settings) -> PointSolution:
        self.grids.append((settings.grid, settings.nodes_y))
        solution = synthetic.solution(point, nx=settings.grid, ny=settings.nodes_y)
        scalars = {k: v for k, v in solution.scalars.items() if k not in ("h_min", "h_c")}
        return replace(solution, outcome=Outcome.FILM_CLOSED, fields={}, message="the film closes on the grid",
                       scalars={**scalars, "wall_time": (1.0, "s"), "cpu_time": (1.0, "s"),
                                "x_film_closed": (0.0, "m"), "y_film_closed": (0.0, "m")},
                       models={**solution.models, "thermal": "full"})


def test_a_closed_film_below_what_the_finest_grid_resolves_is_not_refined(tmp_path):
    """At 20 rpm Hamrock & Dowson's film spans fewer than closure_nodes nodes on 513 along x (worked out here): the
    closed film of the grid asked is reported at once, with the formula's film and the rule in its message, record
    and the run's note."""
    task = _point_and_task(_slow_case(tmp_path, 20.0))
    assert _formula_nodes(task) < TUNING.closure_nodes
    solver = _AlwaysClosed()
    (solution,), failed, refined = solve_refining([task], solver, jobs=1)
    assert solver.grids == [(257, 65)] and failed == ()
    assert solution.outcome is Outcome.FILM_CLOSED and "h_min" not in solution.scalars
    last = solution.record.retries[-1]
    assert (last.reason, last.action) == (Reason.FILM_CLOSED, Action.NOT_RESOLVABLE)
    nodes = f"would span {_formula_nodes(task):.1f} nodes across its outlet constriction"
    assert nodes in solution.message and "Hamrock & Dowson's (1977) minimum film" in solution.message
    note = refinement_note("S3", refined["S3"], solution)
    assert note.startswith("S3: the 257 x 65 grid did not resolve the film; not refined: ") and nodes in note


def test_a_closed_film_the_finest_grid_resolves_is_refined_to_the_cap(tmp_path):
    """At 150 rpm the formula's film spans more than closure_nodes nodes on 513: a closed film goes on to finer grids
    as before, up to the thermal cap."""
    task = _point_and_task(_slow_case(tmp_path, 150.0))
    assert _formula_nodes(task) > TUNING.closure_nodes
    solver = _AlwaysClosed()
    (solution,), _, refined = solve_refining([task], solver, jobs=1)
    assert len(solver.grids) > 1 and max(max(g) for g in solver.grids) == TUNING.max_refined_thermal_grid
    assert Action.NOT_RESOLVABLE not in {r.action for r in solution.record.retries}
    assert refined["S3"].unresolvable == ""


@pytest.mark.slow
def test_the_slow_face_gear_reports_its_closed_film_at_once(tmp_path):
    """The real solver on the 20 rpm gear's S3: the film closes on 257 x 65 and the run ends there, exit 3 with why;
    the file holds no film for it and the typed record of the decision."""
    from click.testing import CliRunner

    from facegear_tehl.cli import tehl
    from facegear_tehl.results import read_result

    case_file, target = _slow_case(tmp_path, 20.0), tmp_path / "slow.h5"
    result = CliRunner().invoke(tehl, ["run", str(case_file), "--points", "S3", "--jobs", "1", "-o", str(target)])
    assert result.exit_code == 3, result.output
    assert "S3: the 257 x 65 grid did not resolve the film; not refined: Hamrock & Dowson's" in result.stderr
    point = read_result(target, fields=False).points["S3"]
    assert point.outcome == Outcome.FILM_CLOSED.value and "h_min" not in point.scalars and "h_c" not in point.scalars
    assert [r.action for r in point.record.retries][-1] is Action.NOT_RESOLVABLE
    assert "no grid within the caps opens it" in point.message
    assert "film closed          S3: the film closes on the grids solved, no film solved; Hamrock & Dowson (1977) " \
           "formula, not solved" in result.stdout


# ------------------------------------------------------------------------------- the verdict of a closed film

def _formula_film(task: SolveTask) -> float:
    from facegear_tehl.ehl.scaling import scaling_for

    s = scaling_for(task.point, task.lubricant)
    return hamrock_dowson_minimum(s.hamrock_u, s.hamrock_g, s.hamrock_w, s.ellipticity) * task.point.radius_x


def _closed_run(case_file: Path, outcome: Outcome = Outcome.FILM_CLOSED, unresolvable: bool = True):
    """A run of the case's S3 alone whose film closed (as the EHL solver reports one: no film scalars, no fields),
    recorded as no grid within the caps resolving it (`unresolvable`) or as closed in a failed iteration."""
    from facegear_tehl.record import SolveRecord
    from facegear_tehl.results import RunResult

    case = load_case(case_file)
    point = next(p for p in contact_analysis(case).points if p.name == "S3")
    solution = synthetic.solution(point)
    scalars = {k: v for k, v in solution.scalars.items() if k not in ("h_min", "h_c")}
    record = SolveRecord()
    if unresolvable:
        record = record.with_retry(RetryRecord(Reason.FILM_CLOSED, Action.NOT_RESOLVABLE, 0, "the formula's film"))
    return RunResult(case=case, points=(replace(solution, outcome=outcome, scalars=scalars, fields={}, record=record,
                                                message="the film closes on the grid"),))


def test_the_verdict_gives_the_formula_film_of_a_closed_point_labelled_as_such(tmp_path):
    """The verdict of a point whose film closed: Hamrock & Dowson's h_min and its lambda over the composite roughness
    (both worked out here from the formula and the case's R_q), the regime by lambda < 1, and a line that says it is
    the formula's and not solved; the point itself gets no film."""
    from facegear_tehl.results import read_result, write_result
    from facegear_tehl.verdict import assess, verdict_text

    case_file = _slow_case(tmp_path, 20.0)
    run = assess(_closed_run(case_file))
    film = _formula_film(_point_and_task(case_file))
    sigma = math.hypot(3.0e-7, 3.0e-7)  # the case's R_q of both flanks
    assert run.verdict["h_min_formula_closed"][0] == pytest.approx(film, rel=1e-12)
    assert run.verdict["lambda_formula_closed"][0] == pytest.approx(film / sigma, rel=1e-12) and film / sigma < 1.0
    assert run.verdict_labels["film_closed_formula_regime"] == "boundary"
    assert "lambda_min" not in run.verdict and "h_min" not in run.points[0].scalars
    text = verdict_text(read_result(write_result(run, tmp_path / "closed.h5"), fields=False))
    line = next(line for line in text.splitlines() if line.startswith("  film closed"))
    assert f"Hamrock & Dowson (1977) formula, not solved: h_min {1e9 * film:.3g} nm at S3" in line
    assert f"lambda {film / sigma:.2g}: boundary" in line and "the smooth-film model does not apply" in line


def test_a_point_that_did_not_converge_otherwise_gets_no_formula_film(tmp_path):
    """Only a closed film is estimated by the formula: a stalled point is left out as before."""
    from facegear_tehl.verdict import assess

    run = assess(_closed_run(_slow_case(tmp_path, 20.0), Outcome.NOT_CONVERGED))
    assert "h_min_formula_closed" not in run.verdict and "film_closed_points" not in run.verdict_labels
    assert run.verdict_labels["left_out"] == "S3"


def test_a_film_closed_in_a_failed_iteration_is_named_without_the_formulas_film(tmp_path):
    """A closed film without the evidence that no grid resolves it (an iteration that failed) gets no formula film:
    the formula's lambda would contradict the closure it stands beside; the point is named once, not also left out."""
    from facegear_tehl.verdict import assess, verdict_text

    run = assess(_closed_run(_slow_case(tmp_path, 20.0), unresolvable=False))
    assert "h_min_formula_closed" not in run.verdict and run.verdict_labels["film_closed_points"] == "S3"
    assert "left_out" not in run.verdict_labels
    assert verdict_text(run).count("S3") == 1
