"""Load continuation of the full-multigrid start (ehl/solve.py: a heavily loaded point's last retry starts at a fraction
of its load) and the retry policy that leads to it (issue 14)."""

from __future__ import annotations

from dataclasses import replace
import math
from types import SimpleNamespace

import numpy as np
import pytest

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.multigrid import at_load_fraction
from facegear_tehl.ehl.retry import ATTEMPTS, DAMPED, POLICY
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.ehl.solve import PointSolve, problem_for
from facegear_tehl.ehl.staged import noted_retry
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.film_formulas import nijenbanning_central
from facegear_tehl.lubricant import KELVIN, Lubricant
from facegear_tehl.materials import Solid
from facegear_tehl.record import SolveRecord
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import CONVERGED, Outcome, PointSolution

STEEL = Solid(elastic_modulus=210e9, poisson_ratio=0.3, density=7850.0, thermal_conductivity=46.0, specific_heat=470.0)
# the envelope suite's gear oil (scripts/envelope.py: ISO VG 320 at 80 degC, Roelands + Dowson-Higginson)
OIL = Lubricant(viscosity=0.04, pressure_viscosity=2.0e-8, inlet_temperature=80.0 + KELVIN, density=835.0,
                viscosity_model="roelands", density_model="dowson_higginson")
RADIUS_Y = 0.020 * 11.8266  # R_y/R_x of an a/b = 5 ellipse (exact Hertz ellipticity; suites/envelope.py)


def _point(load: float, speed: float = 0.5) -> ContactPoint:
    return ContactPoint.from_rolling_sliding("P", 0.020, RADIUS_Y, load, speed, 0.0, 0.0, STEEL, STEEL)


def test_a_load_fraction_is_the_hertzian_problem_of_the_lighter_contact():
    # the same radii at a tenth of the load, solved by Hertz anew: lambda and p_h of its own scaling
    settings = SolverSettings(grid=65, thermal="off")
    full, light = _point(40e3), _point(4e3)
    expected = problem_for(light, OIL, settings, scaling_for(light, OIL))
    got = at_load_fraction(problem_for(full, OIL, settings, scaling_for(full, OIL)), 0.1)
    assert got.lam == pytest.approx(expected.lam, rel=1e-9)
    assert got.p_hertz == pytest.approx(expected.p_hertz, rel=1e-9)
    for name in ("deflection_coefficient", "ellipticity", "geometry_y"):
        assert getattr(got, name) == pytest.approx(getattr(expected, name), rel=1e-9)


def _solution(outcome: Outcome, attempt: int, moes_m: float, iteration: Outcome = Outcome.CONVERGED) -> PointSolution:
    """A solution of `outcome` whose iteration ended `iteration` (before its closed film was checked)."""
    return PointSolution("P", outcome, "", {"attempts": (float(attempt), "1"), "moes_m": (moes_m, "1")}, {}, {},
                         {}, {}, record=SolveRecord(attempt=attempt, iteration=iteration))


STALL, CLOSED = Outcome.NOT_CONVERGED, Outcome.CONVERGED  # the film closed in a stall, in a converged iteration


@pytest.mark.parametrize(("outcome", "attempt", "moes_m", "iteration", "expected"), [
    (Outcome.DIVERGED, 1, 10.0, Outcome.DIVERGED, 2),
    (Outcome.NOT_CONVERGED, 1, 10.0, STALL, 3),  # a stall: the damped relaxation at once
    (Outcome.NOT_CONVERGED, 3, 1e5, STALL, None),  # a damped stall is reported as it is
    (Outcome.DIVERGED, 3, 10.0, Outcome.DIVERGED, None),  # a light load has no continued start
    (Outcome.DIVERGED, 3, 1e5, Outcome.DIVERGED, 4),
    (Outcome.FILM_CLOSED, 1, 1e5, STALL, None),  # the first attempt's closed film goes to a finer grid (run.py)
    (Outcome.FILM_CLOSED, 2, 10.0, STALL, 3),  # a retry's stall that closed the film: as a stall
    (Outcome.FILM_CLOSED, 2, 1e5, CLOSED, 4),
    (Outcome.FILM_CLOSED, 2, 10.0, CLOSED, None),
    (Outcome.FILM_CLOSED, 3, 1e5, STALL, 4),
    (Outcome.FILM_CLOSED, 4, 1e5, STALL, None),
    (Outcome.CONVERGED, 1, 1e5, CLOSED, None),
])
def test_next_attempt(outcome, attempt, moes_m, iteration, expected):
    assert POLICY.next_attempt(_solution(outcome, attempt, moes_m, iteration)) == expected
    if expected is not None:
        assert ATTEMPTS[expected - 1].load_continuation == (expected == len(ATTEMPTS))


def test_a_heavy_ellipse_converges_only_from_a_start_at_a_fraction_of_its_load():
    # a/b = 5, p_h = 2.5 GPa, 0.5 m/s: Moes M = 4.0e4, L = 7.9 (scripts/envelope.py ab5_ph2.5_u0.5_iso) on 513^2
    point = _point((2.5e9 / scaling_for(_point(1.0), OIL).p_h) ** 3)  # p_h ~ W^(1/3) (Hertz)
    scaling = scaling_for(point, OIL)
    assert scaling.ellipticity == pytest.approx(5.0, rel=1e-3) and scaling.moes_m > 30 * TUNING.continuation_moes_m
    settings = SolverSettings(grid=513, thermal="off")
    plain = PointSolve(point, OIL, settings, DAMPED, attempt=3).begin()
    assert plain.outcome is not Outcome.CONVERGED
    solution = PointSolve(point, OIL, settings, DAMPED, attempt=4, load_continuation=True).begin()
    assert solution.outcome is Outcome.CONVERGED, solution.message
    assert solution.record.attempt == 4 and any("of the load" in note for note in solution.record.notes)
    # an open film, and the pressure field carries the applied load (force balance)
    assert solution.scalar("h_min") > 0.0
    dx = np.diff(solution.axes["x"].values)[0]
    dy = np.diff(solution.axes["y"].values)[0]
    carried = solution.fields["pressure"].values.sum() * dx * dy
    assert carried == pytest.approx(point.load, rel=1e-3)
    # the pressure is Hertzian at this low L (no pronounced spike), and the central film is that of the
    # Nijenbanning, Venner & Moes (1994) fit within its scatter at this load (their fit uses Barus' law; the
    # Roelands + Dowson-Higginson films of the envelope's converged M > 1e4 points are 25-35 % below it)
    assert solution.scalar("p_max") == pytest.approx(scaling.p_h, rel=0.05)
    h_nij = (nijenbanning_central(scaling.moes_m, scaling.moes_l, point.radius_x / point.radius_y)
             * math.sqrt(2.0 * scaling.hamrock_u) * point.radius_x)
    assert 0.55 < solution.scalar("h_c") / h_nij < 1.0


def test_an_unconverged_iterate_that_does_not_carry_the_load_reports_no_film():
    """A solve that ends unconverged with its pressure carrying twice the load (the force balance, a conservation
    law, off by 100 %) reports neither a film nor fields, and says why; within UNBALANCED_LOAD it still reports its
    film, flagged by its outcome."""
    from facegear_tehl.ehl.report import UNBALANCED_LOAD
    from facegear_tehl.solution import Status

    solve = PointSolve(_point(1e3, speed=2.0), OIL, SolverSettings(grid=65, thermal="off"))
    index, _ = solve.start(below_top=0)
    assert solve.cycle(index, 30).converged
    level = solve.solver.levels[index]
    balanced = solve.report(index, Status(Outcome.NOT_CONVERGED, "budget spent"), None)
    assert abs(balanced.scalar("load_error")) <= UNBALANCED_LOAD and "h_c" in balanced.scalars
    level.pressure *= 2.0
    solve.solver.update_film(level)
    unbalanced = solve.report(index, Status(Outcome.NOT_CONVERGED, "budget spent"), None)
    load = level.load_integral() / solve.solver.problem.load_integral
    assert unbalanced.scalar("load_error") == pytest.approx(load - 1.0) and load == pytest.approx(2.0, rel=0.05)
    assert "h_c" not in unbalanced.scalars and "h_min" not in unbalanced.scalars and not unbalanced.fields
    assert unbalanced.message.startswith("budget spent; ") and "does not carry the load" in unbalanced.message


def _at_hertz_pressure(p_h: float, speed: float) -> ContactPoint:
    """The a/b = 5 contact at maximum Hertz pressure `p_h` (Pa): p_h ~ W^(1/3) at fixed radii (Hertz)."""
    return _point((p_h / scaling_for(_point(1.0), OIL).p_h) ** 3, speed=speed)


def test_the_continued_start_reaches_the_discrete_solution_of_the_plain_one():
    """a/b = 5, 1.5 GPa, 2 m/s (M = 3.0e3) on 129^2: the plain damped start and the start at 1000/M of the load
    raised under step control (on the continued attempt's own hierarchy, its rows not coarsened) are two paths to
    one discrete solution, both cycled to 1e-6 (at the default 1e-4 the plain solve's h_min is 2.7e-3 short of it)."""
    point = _at_hertz_pressure(1.5e9, 2.0)
    settings = SolverSettings(grid=129, thermal="off", tolerance=1e-6, load_tolerance=1e-6, max_cycles=200)
    plain = PointSolve(point, OIL, settings, DAMPED, attempt=3).begin()
    continued = PointSolve(point, OIL, settings, DAMPED, attempt=4, load_continuation=True).begin()
    assert plain.converged and continued.converged, (plain.message, continued.message)
    assert any("of the load" in note for note in continued.record.notes)
    for key in ("h_c", "h_min", "p_max"):
        assert continued.scalar(key) == pytest.approx(plain.scalar(key), rel=1e-4)
    assert abs(continued.scalar("load_error")) < settings.load_tolerance


class _CarriesUpTo:
    """A stand-in for the multigrid solver whose iteration runs away (non-finite pressure) once the load exceeds
    `limit` of the full load: what a grid that cannot carry a heavier film does."""

    def __init__(self, problem, fraction: float, limit: float):
        from facegear_tehl.ehl.multigrid import Iterate

        self.full, self.limit, self.Iterate = problem, limit, Iterate
        self.problem = at_load_fraction(problem, fraction)
        shape = (5, 5)
        self.level = type("L", (), {"pressure": np.ones(shape), "film": np.ones(shape), "eps": np.ones(shape),
                                    "nx": 5, "ny": 5})()
        self.levels, self.h0 = [self.level], 0.0

    def fraction(self) -> float:  # p_h ~ f^(1/3) (multigrid.at_load_fraction)
        return (self.problem.p_hertz / self.full.p_hertz) ** 3

    def snapshot(self, index):
        return self.Iterate(self.level.pressure.copy(), self.h0)

    def restore(self, index, iterate):
        self.level.pressure, self.h0 = iterate.pressure.copy(), iterate.h0

    def central_film(self, level):
        return 0.1

    def update_film(self, level):
        pass

    def cycle(self, index):
        self.level.pressure = np.full((5, 5), math.nan if self.fraction() > self.limit * (1 + 1e-12) else 1.0)

    def force_error(self, level):
        return 0.0


class _Steps:
    """A stand-in for the pressure iteration of a load step (pressure.PressureIteration.cycle) on `solver`: diverged
    where the cycles leave the pressure non-finite, not converged where `converges` says so, else converged."""

    def __init__(self, solver, converges=lambda fraction: True):
        self.solver, self.converges = solver, converges

    def cycle(self, index, max_cycles):
        from facegear_tehl.solution import Status

        self.solver.cycle(index)
        if not np.isfinite(self.solver.level.pressure).all():
            return Status(Outcome.DIVERGED, "ran away")
        return CONVERGED if self.converges(self.solver.fraction()) else Status(Outcome.NOT_CONVERGED, "stalled")


@pytest.mark.parametrize("limit", [0.3, 0.77, 1.0])
def test_the_step_control_raises_the_load_as_far_as_the_grid_carries_it(limit):
    """start._raise_load from 1 % of the load: where the iteration runs away above `limit` of the load, the steps
    shrink until they fall below min_load_step and stop within such a step of it, the last sound iterate restored
    and the problem at the load reached; where it carries the full load, it gets there."""
    from facegear_tehl.ehl.start import _raise_load

    problem = problem_for(_point(4e4), OIL, SolverSettings(grid=65, thermal="off"), scaling_for(_point(4e4), OIL))
    solver = _CarriesUpTo(problem, 0.01, limit)
    reached, status = _raise_load(_Steps(solver), 0, problem, 0.01)
    if limit == 1.0:
        assert status.converged and reached == 1.0
        return
    assert status.diverged and f"past {reached:.3g}" in status.message
    # the last step that ran away had a factor below min_load_step^2 (its square root fell below min_load_step)
    assert limit / TUNING.min_load_step**2 < reached <= limit
    assert solver.fraction() == pytest.approx(reached, rel=1e-9) and np.isfinite(solver.level.pressure).all()


def test_a_load_step_whose_cycles_do_not_converge_is_taken_back():
    """A step whose V-cycles stay finite but do not reach the step's tolerances (a limit cycle) is taken back as one
    that runs away: the continuation holds a load only where its iteration converges, and stops within a step of
    min_load_step of the load where the cycles stop converging, typed as not converged."""
    from facegear_tehl.ehl.start import _raise_load

    problem = problem_for(_point(4e4), OIL, SolverSettings(grid=65, thermal="off"), scaling_for(_point(4e4), OIL))
    solver = _CarriesUpTo(problem, 0.01, 1.0)
    reached, status = _raise_load(_Steps(solver, lambda fraction: fraction <= 0.5 * (1 + 1e-12)), 0, problem, 0.01)
    assert status.outcome is Outcome.NOT_CONVERGED and "the V-cycles do not converge" in status.message
    assert 0.5 / TUNING.min_load_step**2 < reached <= 0.5
    assert solver.fraction() == pytest.approx(reached, rel=1e-9)


@pytest.mark.parametrize("outcome", [Outcome.DIVERGED, Outcome.NOT_CONVERGED, Outcome.FILM_CLOSED])
def test_a_start_short_of_the_load_reports_no_film(outcome):
    """A solve whose start ended at a fraction of the load (start.py: its continuation could not go on, whichever way
    its last step failed) reports no film: the film of its iterate is a lighter contact's. Only the share of the load
    and where its lowest film lies (the way a finer grid must resolve it) are reported, and the refinement takes it as
    unresolved."""
    from facegear_tehl.solution import Status

    solve = PointSolve(_point(1e3, speed=2.0), OIL, SolverSettings(grid=65, thermal="off"))
    index, _ = solve.start(below_top=0)
    solve.load_reached = 0.4
    solution = solve.report(index, Status(outcome, "raising the load failed"), None)
    assert "carries 0.4 of the load: no film is reported" in solution.message
    assert not solution.fields and "h_min" not in solution.scalars and "h_c" not in solution.scalars
    assert "y_film_closed" in solution.scalars and POLICY.unresolved(solution)


class _ClosesAbove(_CarriesUpTo):
    """A stand-in whose iteration stays finite and balanced but whose film closes (h_min <= 0) once the load exceeds
    `limit` of the full load: what a grid that does not resolve a heavier contact's thinner film does."""

    def update_film(self, level):
        level.film = np.full((5, 5), -1e-3 if self.fraction() > self.limit * (1 + 1e-12) else 1e-3)

    def cycle(self, index):
        self.update_film(self.level)

    def restore(self, index, iterate):
        super().restore(index, iterate)
        self.update_film(self.level)


@pytest.mark.parametrize("limit", [0.3, 0.77])
def test_a_load_step_whose_film_closes_is_taken_back_and_the_step_shortened(limit):
    """start._raise_load does not carry a closed film forward (issue 47): the smooth-film equations have an open film
    at any load (Hamrock & Dowson 1977, H_min > 0), so a step whose film closes is what the grid does not resolve; it
    is taken back like one that runs away, and the continuation stops within a step of min_load_step of the load
    where the film closes, the last open iterate restored and the outcome the closed film's."""
    from facegear_tehl.ehl.start import _raise_load

    problem = problem_for(_point(4e4), OIL, SolverSettings(grid=65, thermal="off"), scaling_for(_point(4e4), OIL))
    solver = _ClosesAbove(problem, 0.01, limit)
    reached, status = _raise_load(_Steps(solver), 0, problem, 0.01)
    assert status.outcome is Outcome.FILM_CLOSED
    assert f"the film closes raising the load of the full-multigrid start past {reached:.3g}" in status.message
    assert limit / TUNING.min_load_step**2 < reached <= limit
    assert solver.fraction() == pytest.approx(reached, rel=1e-9) and solver.level.film.min() > 0.0


def test_the_continued_hierarchy_coarsens_an_axis_only_where_its_nodes_are_coupled():
    """start.continued_shapes: the Reynolds operator couples rows by eps/(k h_y)^2 against eps/h_x^2 along a row. A
    circle's rows are coupled like its columns once the cells are square: its hierarchy is the one coarsened along
    both axes (grid.hierarchy_shapes, built independently), from the continued attempt's coarsest columns; an a/b = 74.5
    ellipse's rows are 10^-5 as coupled on (257, 65): every coarse grid keeps them."""
    from facegear_tehl.ehl import grid
    from facegear_tehl.ehl.start import continued_shapes

    columns = TUNING.semi_coarsest_columns
    for nodes in ((257, 65), (129, 129), (513, 513)):
        circle = problem_for(_point(4e4), OIL, SolverSettings(grid=nodes[0], grid_y=nodes[1], thermal="off"),
                             scaling_for(_point(4e4), OIL))
        circle = replace(circle, ellipticity=1.0, domain_x=(-4.5, 1.5), domain_y=(-3.0, 3.0))
        assert continued_shapes(*nodes, circle, columns) == grid.hierarchy_shapes(*nodes, columns)
    ellipse = replace(circle, ellipticity=74.5)
    assert continued_shapes(257, 65, ellipse, columns) == [(33, 65), (65, 65), (129, 65), (257, 65)]


@pytest.mark.slow
def test_a_heavy_thermal_long_ellipse_converges_from_the_continued_start():
    """The wide envelope's w24 (a/b 74.5, 2.3 GPa, 34.6 m/s, Ree-Eyring, thermal full, M = 7.7e4), whose starts on
    the hierarchy coarsened along both axes run away on every attempt: its load-continued attempt on 257 x 65
    converges with an open film, its load balanced (the integral of the pressure against the load) and its energy
    balanced (heat conducted into the solids and convected out against the heat generated, energy.py) within 1 %."""
    from facegear_tehl.ehl.staged import StagedSolver
    from facegear_tehl.suites.wide_envelope import wide_envelope_contact

    case = wide_envelope_contact("w24")
    solve = PointSolve(case.point(), case.lubricant(), case.settings(257, 65), ATTEMPTS[3].relaxation, attempt=4,
                       escalate_start=True, load_continuation=True)
    solution = StagedSolver(bounded=False).finish(solve.begin())
    assert solution.converged, solution.message
    assert solution.scalar("h_min") > 0.0 and abs(solution.scalar("load_error")) < 1e-3
    assert abs(solution.scalar("energy_balance_error")) < 1e-2


def test_a_continued_solve_without_an_estimate_is_refined_like_a_coarse_one():
    """retry.RetryPolicy.unestimated: a converged solve of the load-continued attempt whose load was raised on its
    finest grid has no level one grid coarser at the full load and so no error estimate of h_min; nothing bounds its
    film, and the refinement takes it as one whose estimate exceeds its bound. Another attempt's solve without an
    estimate (a trial grid's) is left as it is."""
    from dataclasses import replace as replaced

    from facegear_tehl.solution import CONVERGED as DONE

    solve = PointSolve(_point(1e3, speed=2.0), OIL, SolverSettings(grid=65, thermal="off"), attempt=4)
    index, _ = solve.start(below_top=0)
    solution = solve.report(index, DONE, None)
    bare = replaced(solution, scalars={k: v for k, v in solution.scalars.items() if not k.startswith("error_")})
    assert solution.converged and "error_estimate_h_min" in solution.scalars and not POLICY.unestimated(solution)
    assert POLICY.unestimated(bare) and POLICY.coarse(bare)
    first = replaced(bare, scalars={**bare.scalars, "attempts": (1.0, "1")})
    assert not POLICY.unestimated(first) and not POLICY.coarse(first)


@pytest.mark.parametrize(("outcome", "attempt", "moes_m", "iteration"), [
    (Outcome.NOT_CONVERGED, 1, 10.0, STALL),  # attempt 1's stall is retried by attempt 3
    (Outcome.DIVERGED, 3, 1e5, Outcome.DIVERGED),
    (Outcome.FILM_CLOSED, 2, 1e5, CLOSED),  # attempt 2's closed film is retried by attempt 4
])
def test_the_retry_record_names_the_attempt_that_failed(outcome, attempt, moes_m, iteration):
    failed = replace(_solution(outcome, attempt, moes_m, iteration), message="the failure")
    following = POLICY.next_attempt(failed)
    retried = noted_retry(SimpleNamespace(retries=[]), failed, following)
    (record,) = retried.retries
    assert (record.attempt, record.detail) == (following, f"attempt {attempt}: the failure")
