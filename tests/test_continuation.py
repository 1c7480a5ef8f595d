"""The meshing cycle by continuation (ehl/seeded.py, parallel.PathSolver): each point of a path seeded from its
solved neighbour lands within its own error estimate of the cold start's result, says so in its solve record, and a
seeded solve that fails is solved again from the cold start; the chunks of a path give the same outcomes on one
worker or two."""

from __future__ import annotations

from dataclasses import replace
import time

import numpy as np
import pytest
import yaml

from facegear_tehl.case import parse_case
from facegear_tehl.ehl import flow
from facegear_tehl.ehl.seeded import CheckPath, SeededSolve, resample, solve_path, solve_seeded
from facegear_tehl.ehl.staged import UNBOUNDED, solve_point
from facegear_tehl.parallel import PathSolver, SolveTask, solve_all
from facegear_tehl.points import contact_analysis
from facegear_tehl.record import Action, Reason, Stage
from facegear_tehl.run import path_solver
from facegear_tehl.solution import Outcome

import synthetic

FACE_GEAR = synthetic.CASES / "facegear_110.yaml"
FIGURES = ("h_c", "h_min", "dT_max", "mu")


def _path_case(points: int = 41, grid: int | None = None, thermal: str | None = None):
    """The shipped face gear case with `points` evenly spaced points (and another grid or thermal model)."""
    raw = yaml.safe_load(FACE_GEAR.read_text())
    raw["gear"]["points"] = points
    raw["solver"].update({k: v for k, v in (("grid", grid), ("thermal", thermal)) if v is not None})
    return parse_case(yaml.safe_dump(raw), name="facegear_110")


def test_resample_is_exact_for_a_bilinear_field_and_holds_the_edge_values():
    # a + b X + c Y + d X Y is bilinear in every cell: interpolation between nodes reproduces it exactly
    def field(x, y):
        return 2.0 + 3.0 * x[None, :] - y[:, None] + 0.5 * x[None, :] * y[:, None]

    x, y = np.linspace(-2.0, 1.0, 13), np.linspace(-1.0, 1.0, 9)
    to_x, to_y = np.linspace(-2.5, 1.3, 20), np.linspace(-0.9, 1.2, 7)
    layers = np.stack([field(x, y), 2.0 * field(x, y)])[:, :, ::-1][:, :, ::-1]  # not C-contiguous
    out = resample(layers, x, y, to_x, to_y)
    assert out.shape == (2, 7, 20) and out.flags["C_CONTIGUOUS"]
    held_x, held_y = np.clip(to_x, x[0], x[-1]), np.clip(to_y, y[0], y[-1])  # beyond the axes: the edge values
    np.testing.assert_allclose(out[0], field(held_x, held_y), rtol=0, atol=1e-12)
    np.testing.assert_allclose(out[1], 2.0 * field(held_x, held_y), rtol=0, atol=1e-12)


def test_temperature_factors_do_not_depend_on_the_layout_of_the_temperatures():
    law = _path_case().lubricant.law_parameters()
    temperature = np.linspace(300.0, 400.0, 3 * 5 * 8).reshape(3, 5, 8)
    strided = np.asfortranarray(temperature)
    assert not strided.flags["C_CONTIGUOUS"]
    np.testing.assert_array_equal(flow.temperature_factors(strided, law), flow.temperature_factors(temperature, law))


def _chunk_stand_in(tasks):
    """A stand-in of ehl.seeded.solve_path: synthetic solutions, each message naming its chunk's first point; a
    chunk holding P10 raises."""
    names = [point.name for point, _, _ in tasks]
    if "P10" in names:
        raise FloatingPointError("overflow in the elastic deflection")
    return [replace(synthetic.solution(point), message=f"chunk from {names[0]}") for point, _, _ in tasks]


def test_a_path_goes_to_the_workers_in_chunks_of_neighbours_the_same_with_one_or_two():
    case = _path_case(points=17)
    tasks = [SolveTask(p, case.lubricant, case.solver) for p in contact_analysis(case).points]
    runs = [solve_all(tasks, PathSolver(_chunk_stand_in, 7), jobs=jobs) for jobs in (1, 2)]
    for solutions, failed in runs:
        assert [s.name for s in solutions] == [t.point.name for t in tasks]
        assert failed == tuple(range(7, 14))  # P08..P14, the chunk holding P10: each failed with the error
        assert all(solutions[i].outcome is Outcome.FAILED and "overflow" in solutions[i].message for i in failed)
        assert [s.message for s in solutions[:7]] == ["chunk from P01"] * 7
        assert [s.message for s in solutions[14:]] == ["chunk from P15"] * 3
    assert [s.message for s in runs[0][0]] == [s.message for s in runs[1][0]]


def test_only_a_thermal_path_of_evenly_spaced_points_is_solved_by_continuation():
    assert isinstance(path_solver(_path_case()), PathSolver)
    assert not isinstance(path_solver(_path_case(thermal="off")), PathSolver)
    raw = yaml.safe_load(FACE_GEAR.read_text())
    assert not isinstance(path_solver(parse_case(yaml.safe_dump(raw), name="facegear_110")), PathSolver)  # S1..S5


def _within_estimates(seeded, cold) -> dict[str, float]:
    """|seeded - cold| of each figure over the cold start's own error estimate of it (relative estimates)."""
    return {k: abs(seeded.scalar(k) - cold.scalar(k)) / abs(cold.scalar(f"error_estimate_{k}") * cold.scalar(k))
            for k in FIGURES}


def _check_neighbours(first: int, count: int, grid: int | None) -> None:
    case = _path_case(grid=grid)
    points = contact_analysis(case).points[first:first + count]
    seeded = solve_path([(p, case.lubricant, case.solver) for p in points])
    assert [r.stage for r in seeded[0].record.stages][0] is Stage.START  # the first of a path: the cold start
    for before, point, solution in zip(points, points[1:], seeded[1:]):
        cold = solve_point(point, case.lubricant, case.solver)
        assert cold.converged and solution.converged
        stages = [r.stage for r in solution.record.stages]
        assert stages[0] is Stage.SEEDED and Stage.START not in stages and Stage.SEED not in stages
        assert solution.record.plan[0].startswith("seeded start") and f"from {before.name}" in solution.record.plan[0]
        shares = _within_estimates(solution, cold)
        assert max(shares.values()) < 1.0, (point.name, shares)


def test_seeded_points_lie_within_their_error_estimates_of_the_cold_start():
    _check_neighbours(10, 3, grid=129)  # P11 cold, P12 and P13 seeded (each solved on 257 x 33)


@pytest.mark.slow
def test_seeded_points_on_the_default_grid_lie_within_their_error_estimates_of_the_cold_start():
    _check_neighbours(9, 4, grid=None)  # P10 cold, P11-P13 seeded on 513 x 65 (outlet stages at P10 and P12)


@pytest.mark.slow
def test_the_error_bounds_checks_of_a_path_are_seeded_and_land_within_their_estimates_of_cold_checks():
    # the checks of P17-P19 as y_estimates solves them for the default 513 x 65 solves: 257 x 33 over the lengthened
    # domain, no outlet patches. Their first attempt runs away from the cold start (the ellipse-scaled switch): P17's
    # check is retried, P18's begins cold with the attempt that converged P17's, P19's seeded from P18's with it
    case = _path_case()
    points = contact_analysis(case).points[16:19]
    check = replace(case.solver, grid=257, grid_y=33, domain_x=(-10.5, 1.5), domain_y=(-3.0, 3.0),
                    outlet_refinement="never")
    path, seconds, before = CheckPath(), {"path": 0.0, "cold": 0.0}, None
    for i, point in enumerate(points):
        clock = time.process_time()
        led = path(point, case.lubricant, check)
        seconds["path"] += time.process_time() - clock
        clock = time.process_time()
        cold = UNBOUNDED(point, case.lubricant, check)
        seconds["cold"] += time.process_time() - clock
        assert led.converged and cold.converged and cold.record.attempt > 1  # the cold start's first ran away
        source = points[1].name if i == 2 else ""
        assert (path.source, path.attempt) == (source, 1 if i == 0 else before.record.attempt)
        assert led.record.stages[0].stage is (Stage.SEEDED if i == 2 else Stage.START)
        assert (led.record.retries == ()) == (i > 0)
        shares = _within_estimates(led, cold)
        assert max(shares.values()) < 1.0, (point.name, shares)
        before = led
    print(seconds)  # CPU of the three checks on the path and from the cold start


def test_a_seeded_solve_that_fails_is_solved_again_from_the_cold_start():
    case = _path_case(grid=129)
    before, point = contact_analysis(case).points[10:12]
    solve = SeededSolve(before, case.lubricant, case.solver, None)
    solve.begin().finish()
    seed = solve.seed_for_next()
    broken = replace(seed, pressure=np.full_like(seed.pressure, np.nan))  # a seed that is not finite
    solution, next_seed = solve_seeded(point, case.lubricant, case.solver, broken)
    cold = solve_point(point, case.lubricant, case.solver)
    assert next_seed is None  # the point after it starts cold again
    retry = solution.record.retries[-1]
    assert (retry.reason, retry.action) == (Reason.SEEDED_START_FAILED, Action.COLD_START)
    assert f"seeded from {before.name}" in retry.detail and "cold start" in solution.models["solver"]
    assert [r.stage for r in solution.record.stages][0] is Stage.START
    assert all(solution.scalar(k) == cold.scalar(k) for k in FIGURES)  # the cold start's own solve
