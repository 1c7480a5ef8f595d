"""The point solve's plan, record and convergence monitor (ehl/plan.py, record.py, ehl/convergence.py,
ehl/snapshot.py): the plan against the hierarchy the multigrid builds, the record through the result file and
`tehl info`, the predicates on hand-made histories, the explicit snapshot against the solve it was taken from."""

from __future__ import annotations

import json

from click.testing import CliRunner
import numpy as np
import pytest

from facegear_tehl.cli import tehl
from facegear_tehl.ehl import grid
from facegear_tehl.ehl.convergence import at_algebraic_floor, at_thermal_floor, h_c_steady, stalled
from facegear_tehl.ehl.plan import plan_for
from facegear_tehl.ehl.scaling import contact_from_moes
from facegear_tehl.ehl.snapshot import restore_snapshot, take_snapshot
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.ehl.start import start
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.record import (
    Action,
    Reason,
    RetryRecord,
    SolveRecord,
    Stage,
    record_from_dict,
    record_lines,
    record_to_dict,
)
from facegear_tehl.results import read_result
from facegear_tehl.settings import SolverSettings, ThermalMode
from facegear_tehl.solution import Outcome


def _plan(nx: int, ny: int, mode: ThermalMode, coupled: bool = True, **settings):
    shapes = grid.hierarchy_shapes(nx, ny, 17)
    return plan_for(shapes, mode, coupled, SolverSettings(grid=nx, grid_y=ny, thermal=mode, **settings), 5.0)


def test_the_plan_follows_the_hierarchy():
    # 513 x 65 from 17: 17^2, 33^2, 65^2, 129 x 65, 257 x 65, 513 x 65 (grid.hierarchy_shapes' semi-coarsening)
    full = _plan(513, 65, ThermalMode.FULL)
    assert [(p.stage, p.nx, p.ny) for p in full.stages] == [
        (Stage.START, 129, 65), (Stage.SEED, 129, 65), (Stage.COARSE, 257, 65), (Stage.FINEST, 513, 65),
        (Stage.OUTLET, 513, 65)]
    # the seed stage needs 129 nodes in x two grids below the finest; the coarse stage 65 one grid below
    assert [p.stage for p in _plan(257, 65, ThermalMode.FULL).stages] == [
        Stage.START, Stage.COARSE, Stage.FINEST, Stage.OUTLET]
    # without a coarse stage no outlet stage: it refines the finish of one (PointSolve.finish)
    assert [p.stage for p in _plan(65, 17, ThermalMode.FULL).stages] == [Stage.START, Stage.FINEST]
    assert not _plan(65, 17, ThermalMode.FULL, outlet_refinement="always").has(Stage.OUTLET)
    assert [p.stage for p in _plan(257, 65, ThermalMode.REDUCED).stages] == [Stage.START, Stage.COARSE, Stage.FINEST]
    assert [p.stage for p in _plan(257, 65, ThermalMode.OFF, coupled=False).stages] == [Stage.START, Stage.FINEST]
    assert not _plan(513, 65, ThermalMode.FULL, outlet_refinement="never").has(Stage.OUTLET)
    assert TUNING.min_seed_stage_grid == 129 and TUNING.min_coarse_thermal_grid == 65


def test_reduced_without_a_coarse_stage_is_solved_and_named_full():
    """`reduced` freezes the state of its coarse stage on the finest grid; on 65 x 17 there is none (the grid below has
    33 nodes along x), so its one coupled loop is `full`'s: the solve says full, and why; `always` there notes that no
    outlet stage can run."""
    point, lubricant = contact_from_moes(20.0, 10.0)
    solve = PointSolve(point, lubricant, SolverSettings(grid=65, grid_y=17, thermal="reduced",
                                                        outlet_refinement="always"))
    assert solve.mode is ThermalMode.FULL and "solved full" in solve.reason
    assert not solve.plan.has(Stage.OUTLET)
    assert any("outlet refinement 'always' not run" in note for note in solve.record(Outcome.CONVERGED).notes)
    staged = PointSolve(point, lubricant, SolverSettings(grid=257, grid_y=65, thermal="reduced"))
    assert staged.mode is ThermalMode.REDUCED and staged.plan.has(Stage.COARSE)


def test_the_record_survives_its_plain_data():
    record = SolveRecord(("a", "b"), (), (RetryRecord(Reason.RAN_AWAY, Action.NEXT_RELAXATION, 2, "why"),), 2,
                         "Venner's switch", Outcome.NOT_CONVERGED, ("note",), check_seed="P11", check_attempt=2)
    assert record_from_dict(json.loads(json.dumps(record_to_dict(record)))) == record
    assert "ran away (why): solved again with the next relaxation" in record.render()
    assert "  check    the error bounds' check seeded from P11's check, begun with attempt 2" in record_lines("P12",
                                                                                                            record)
    older = {k: v for k, v in record_to_dict(record).items() if not k.startswith("check_")}  # a file from before
    assert (record_from_dict(older).check_seed, record_from_dict(older).check_attempt) == ("", 1)


def test_a_run_writes_its_record_and_info_shows_it(facegear_file):
    run = read_result(facegear_file)
    for point in run.points.values():
        record = point.record
        ran = [stage.stage for stage in record.stages]
        assert ran[0] is Stage.START and Stage.FINEST in ran
        assert sum(stage.outer for stage in record.stages) == point.scalars["thermal_iterations"]
        assert record.plan and record.attempt == point.scalars["attempts"]
        _check_stage_starts(point)
    result = CliRunner().invoke(tehl, ["info", str(facegear_file)])
    assert result.exit_code == 0, result.output
    assert "solve of S1:" in result.output and "  planned  " in result.output and "  ran      " in result.output
    as_json = json.loads(CliRunner().invoke(tehl, ["info", str(facegear_file), "--json"]).output)
    assert record_from_dict(as_json["solve"]["S3"]) == run.points["S3"].record


def _check_stage_starts(point) -> None:
    """Each stage's first entries lie in the histories in the order the stages ran, and the last stage with outer
    iterations holds the per-outer-iteration history's tail: its outer-iteration count (the loop's counter) equals
    the entries after its start (the history's list), two counts kept apart."""
    stages = [s for s in point.record.stages if s.first_cycle >= 0]
    cycles = len(point.history["pressure_change_history"].values)
    assert [s.first_cycle for s in stages] == sorted(s.first_cycle for s in stages)
    assert all(s.first_cycle < cycles for s in stages)
    if "thermal_change_history" in point.history:
        last = [s for s in stages if s.outer > 0][-1]
        assert len(point.history["thermal_change_history"].values) - last.first_outer == last.outer


def test_the_monitor_on_hand_made_histories():
    tolerance = SolverSettings().tolerance
    loads = [0.0] * 6
    flicker = [np.nan, 1e-2, 1e-3, 5e-4, 4.9e-4, 4.8e-4]  # stalled below 10x the tolerance: the floor
    assert at_algebraic_floor(flicker, loads, SolverSettings())
    assert not at_algebraic_floor(flicker[:4] + [2e-4, 1e-4], loads, SolverSettings())  # still falling by 2x
    assert not at_algebraic_floor([np.nan, 1e-2, 5e-2, 2e-2, 2e-2, 2e-2], loads, SolverSettings())  # above the band
    assert not at_algebraic_floor(flicker, [0.0] * 4 + [2 * tolerance, 2 * tolerance], SolverSettings())
    window = TUNING.thermal_floor_window
    assert stalled([1.0] * window) and not stalled([2.0 ** -k for k in range(window)])
    assert h_c_steady([1.0, 1.0004]) and not h_c_steady([1.0, 1.001])
    assert h_c_steady([1.0, 1.001], h_c_error=4e-3)  # half of a 4e-3 estimate allows 2e-3
    assert at_thermal_floor([0.5] * window, [1.0] * window, bound=1.0)
    assert not at_thermal_floor([0.5] * window, [1.0] * window, bound=0.4)


def test_a_restored_snapshot_gives_the_same_cycles():
    """Cycled on after restoring a snapshot, the solve repeats bit for bit what it did after taking it."""
    point, lubricant = contact_from_moes(20.0, 10.0)
    solve = PointSolve(point, lubricant, SolverSettings(grid=65, domain_x=(-4.5, 1.5), domain_y=(-3.0, 3.0)))
    index, status = start(solve, below_top=0)
    assert status.converged
    snapshot = take_snapshot(solve)
    solve.cycle(index, 3)
    first = solve.solver.levels[index].pressure.copy(), solve.solver.h0, list(solve.history.changes)
    restore_snapshot(solve, snapshot)
    solve.cycle(index, 3)
    level = solve.solver.levels[index]
    assert np.array_equal(level.pressure, first[0]) and solve.solver.h0 == first[1]
    assert np.array_equal(solve.history.changes, first[2], equal_nan=True)


@pytest.mark.parametrize("word", ["off", "reduced", "full", "auto"])
def test_the_thermal_mode_reads_and_writes_as_its_word(word):
    mode = SolverSettings(thermal=word).thermal
    assert mode is ThermalMode(word) and mode == word and f"{mode}" == word
