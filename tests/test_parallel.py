"""Points solved on worker processes: identical to a serial run, failures recorded per point, progress in
completion order with results in the case's order, bad --jobs, and an interrupted parallel run stops its
workers at once."""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
import concurrent.futures.process
from dataclasses import replace
import os
from pathlib import Path
import signal
import subprocess
import sys
import textwrap
import time

from click.testing import CliRunner
import h5py
import numpy as np
import pytest

from facegear_tehl import parallel
from facegear_tehl.case import load_case
from facegear_tehl.cli import tehl
from facegear_tehl.parallel import SolveTask, StagedSolver, available_cores, solve_each, worker_count
from facegear_tehl.points import contact_analysis
from facegear_tehl.run import run_case
from facegear_tehl.schema import CaseError
from facegear_tehl.solution import Outcome

import synthetic

FACE_GEAR = synthetic.CASES / "facegear_110.yaml"
# Attributes and datasets that measure time, not the solution: the only ones allowed to differ.
TIMING = {"wall_time", "cpu_time", "error_check_time", "error_check_cpu_time", "created", "stage_seconds"}


def assert_same_file(first: Path, second: Path) -> None:
    """Every dataset of two result files equal (np.array_equal), and every attribute but the timings."""
    with h5py.File(first, "r") as a, h5py.File(second, "r") as b:
        names_a, names_b = [], []
        a.visit(names_a.append)
        b.visit(names_b.append)
        assert names_a == names_b
        for name in ["/", *names_a]:
            attrs_a, attrs_b = dict(a[name].attrs), dict(b[name].attrs)
            assert sorted(attrs_a) == sorted(attrs_b), name
            for key in attrs_a:
                if key in _DIMENSION_LINKS:  # HDF5 object references: equal when they name the same datasets
                    assert _linked(a, key, attrs_a[key]) == _linked(b, key, attrs_b[key]), f"{name}.{key}"
                elif key not in TIMING:
                    assert np.array_equal(attrs_a[key], attrs_b[key]), f"{name}.{key}"
            if isinstance(a[name], h5py.Dataset) and name.rsplit("/", 1)[-1] not in TIMING:
                assert np.array_equal(a[name][()], b[name][()], equal_nan=a[name].dtype.kind == "f"), name


# Attributes by which HDF5 dimension scales link datasets (object references, different in every file).
_DIMENSION_LINKS = ("DIMENSION_LIST", "REFERENCE_LIST")


def _linked(h5: h5py.File, key: str, value: np.ndarray) -> list:
    """The names of the datasets a DIMENSION_LIST (per dimension) or REFERENCE_LIST (with the dimension) names."""
    if key == "DIMENSION_LIST":
        return [[h5[reference].name for reference in references] for references in value]
    return sorted((h5[reference].name, int(dimension)) for reference, dimension in value)


def test_jobs_2_gives_the_same_file_as_jobs_1(tmp_path):
    files = []
    for jobs in ("1", "2"):
        target = tmp_path / f"jobs{jobs}.h5"
        result = CliRunner().invoke(tehl, ["run", str(FACE_GEAR), "--grid", "33", "--points", "S1,S3,S5",
                                           "--jobs", jobs, "-o", str(target)])
        assert result.exit_code in (0, 3), result.output
        files.append(target)
    assert "2 worker processes" in result.stderr
    assert_same_file(*files)


def _slow_first(point, lubricant, settings):
    """S1 takes longest (on its full grid; the coarsest-grid warm-up is quick)."""
    if point.name == "S1" and settings.grid > settings.coarsest_grid:
        time.sleep(0.5)
    return synthetic.solution(point)


def _fail_at_s2(point, lubricant, settings):
    if point.name == "S2":
        raise FloatingPointError("overflow in the elastic deflection")
    return synthetic.solution(point)


def test_progress_in_completion_order_results_in_case_order(monkeypatch):
    seen = []
    run = run_case(load_case(FACE_GEAR), jobs=2, progress=lambda s, done, total: seen.append((s.name, done, total)),
                   solver=_slow_first)
    assert [p.name for p in run.points] == ["S1", "S2", "S3", "S4", "S5"]
    assert seen[-1] == ("S1", 5, 5)  # finished last, on its own worker
    assert [done for _, done, _ in seen] == [1, 2, 3, 4, 5]
    assert run.status == "ok"


def test_a_failing_point_is_recorded_and_the_others_still_run():
    run = run_case(load_case(FACE_GEAR), jobs=2, solver=_fail_at_s2)
    assert run.failed == ("S2",) and run.status == "failed"
    by_name = {p.name: p for p in run.points}
    assert by_name["S2"].message == "failed: FloatingPointError: overflow in the elastic deflection"
    assert by_name["S2"].outcome is Outcome.FAILED and not by_name["S2"].fields
    assert all(by_name[name].converged and by_name[name].fields for name in ("S1", "S3", "S4", "S5"))
    assert "path_coordinate" in by_name["S2"].scalars  # like every point of a gear case


def test_one_job_runs_in_this_process():
    calls = []

    def recording(point, lubricant, settings):
        calls.append(os.getpid())
        return synthetic.solution(point)

    run = run_case(load_case(FACE_GEAR), jobs=1, points=["S1", "S2"], solver=recording)  # a closure: a pool could
    # not pickle it
    assert calls == [os.getpid()] * 2 and run.status == "ok"


def _blas_threads(point, lubricant, settings):
    """A synthetic solution that records how many BLAS threads the solve could use."""
    from threadpoolctl import threadpool_info

    solution = synthetic.solution(point)
    threads = max(pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas")
    return replace(solution, scalars={**solution.scalars, "blas_threads": (float(threads), "1")})


@pytest.mark.parametrize("jobs", [1, 2])
def test_every_solve_has_one_blas_thread(jobs):
    """OpenBLAS sums in another order with more threads: one everywhere keeps --jobs N bit-identical."""
    case = load_case(FACE_GEAR)
    tasks = [SolveTask(p, case.lubricant, case.solver) for p in contact_analysis(case).points[:3]]
    outcomes = [solved for _, solved in solve_each(tasks, _blas_threads, jobs=jobs)]
    assert [s.solution.scalar("blas_threads") for s in outcomes] == [1.0] * 3


def _begin(point, lubricant, settings, retry_after):
    """A stand-in first stage: S2 fails, S3 runs away on its first attempt, S4 is whole after one stage, the
    others hand an intermediate (with the worker's pid) to the second stage."""
    if point.name == "S2":
        raise FloatingPointError("overflow in the first stage")
    if point.name == "S3" and retry_after is None:
        return replace(synthetic.solution(point, converged=False), outcome=Outcome.DIVERGED,
                       message="diverged at cycle 3")
    if point.name == "S4":
        return synthetic.solution(point)
    return {"point": point, "begun_in": os.getpid(), "retry": retry_after is not None}


def _finish(stage):
    solution = synthetic.solution(stage["point"])
    extra = {"begun_in": (float(stage["begun_in"]), "1"), "finished_in": (float(os.getpid()), "1"),
             "retried": (float(stage["retry"]), "1")}
    return replace(solution, scalars={**solution.scalars, **extra})


class StandIn:
    """A stand-in staged solver (module-level: the pool pickles it): whole solves as _blas_threads, stages as
    _begin and _finish."""

    def __call__(self, point, lubricant, settings):
        return _blas_threads(point, lubricant, settings)

    def begin(self, point, lubricant, settings, retry_after=None):
        return _begin(point, lubricant, settings, retry_after)

    def finish(self, stage):
        return _finish(stage)

    def needs_retry(self, solution):
        return solution.outcome is Outcome.DIVERGED

    def with_retry(self, first, retry):
        return replace(retry, message=f"retried after: {first.message}")


def test_stages_run_on_the_workers_and_give_the_serial_outcomes():
    """Each point's stages go through the pool (a failing stage is recorded, a run-away first attempt is begun
    again and merged by with_retry), with the outcomes the stages give when composed in one process."""
    case = load_case(FACE_GEAR)
    tasks = [SolveTask(p, case.lubricant, case.solver) for p in contact_analysis(case).points]
    outcomes = dict(solve_each(tasks, StandIn(), jobs=2))
    assert sorted(outcomes) == [0, 1, 2, 3, 4]
    by_name = {tasks[i].point.name: solved for i, solved in outcomes.items()}
    assert (by_name["S2"].failed
            and by_name["S2"].solution.message == "failed: FloatingPointError: overflow in the first stage")
    s3 = by_name["S3"].solution
    assert s3.converged and s3.message == "retried after: diverged at cycle 3" and s3.scalar("retried") == 1.0
    assert "begun_in" not in by_name["S4"].solution.scalars  # whole after its first stage
    for name in ("S1", "S5"):
        scalars = by_name[name].solution.scalars
        assert scalars["begun_in"][0] != os.getpid() and scalars["finished_in"][0] != os.getpid()
        assert not by_name[name].failed and scalars["retried"][0] == 0.0


def test_a_solver_is_staged_by_what_it_can_do():
    """The runner stages a solver that has the stages (the EHL solver, a stand-in), not a plain function."""
    from facegear_tehl.ehl.staged import STAGED

    assert isinstance(STAGED, StagedSolver) and isinstance(StandIn(), StagedSolver)
    assert not isinstance(_slow_first, StagedSolver)


def test_thermal_points_split_into_stages_give_the_serial_file(tmp_path):
    """On 129^2 the thermal full points run as a coarse and a fine stage, in different workers when --jobs 2
    (the default case's S1, S5): the file is bit-identical to --jobs 1, where each point runs in one go."""
    files = []
    for jobs in ("1", "2"):
        target = tmp_path / f"jobs{jobs}.h5"
        result = CliRunner().invoke(tehl, ["run", str(FACE_GEAR), "--points", "S1,S5", "--jobs", jobs,
                                           "-o", str(target)])
        assert result.exit_code == 0, result.output
        files.append(target)
    assert_same_file(*files)


def test_worker_count():
    assert worker_count(None) == available_cores() >= 1
    assert worker_count(3) == 3
    for bad in (0, -2):
        with pytest.raises(CaseError, match="--jobs"):
            worker_count(bad)


_STALLING_RUN = textwrap.dedent(
    """
    import os, sys, time
    sys.path.insert(0, {tests!r})
    import synthetic
    from facegear_tehl import cli, run
    def stall(point, lubricant, settings):
        if settings.grid > settings.coarsest_grid:
            with open(os.path.join({folder!r}, f"worker-{{os.getpid()}}"), "w"):
                pass
            time.sleep(60)
        return synthetic.solution(point)
    run.ehl_solver = lambda: stall
    cli.main(sys.argv[1:])
    """
)


def test_stopped_workers_leave_no_open_wakeup_pipe_to_the_exit_hook():
    """The exit hook of `concurrent.futures` writes to the wake-up pipe of every manager thread it lists; one
    still closing its pipe then fails with "Bad file descriptor" (a traceback after an interrupted run)."""
    executor = ProcessPoolExecutor(max_workers=2, mp_context=parallel._context())
    running = [executor.submit(time.sleep, 60) for _ in range(2)]
    deadline = time.monotonic() + 30
    while not all(future.running() for future in running):
        assert time.monotonic() < deadline
        time.sleep(0.01)
    started = time.monotonic()
    parallel._stop_workers(executor)
    assert time.monotonic() - started < 10
    for thread, wakeup in list(concurrent.futures.process._threads_wakeups.items()):
        assert not thread.is_alive() or wakeup._closed


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_interrupted_parallel_run_stops_its_workers(tmp_path, signum):
    script = _STALLING_RUN.format(tests=str(Path(__file__).parent), folder=str(tmp_path))
    command = [sys.executable, "-c", script, "run", str(FACE_GEAR), "--jobs", "2", "-o", str(tmp_path / "r.h5")]
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          preexec_fn=synthetic.sigint_as_in_a_terminal) as process:
        deadline = time.monotonic() + 60
        while len(list(tmp_path.glob("worker-*"))) < 2:
            assert time.monotonic() < deadline and process.poll() is None, process.stderr.read()
            time.sleep(0.05)
        started = time.monotonic()
        process.send_signal(signum)
        code = process.wait(timeout=30)
        assert time.monotonic() - started < 10  # not after the 60 s solves
        stderr = process.stderr.read()
    assert code == 128 + signum, stderr  # 143 for SIGTERM, 130 for Ctrl-C
    assert "Traceback" not in stderr
    assert not (tmp_path / "r.h5").exists()
    for marker in tmp_path.glob("worker-*"):
        pid = int(marker.name.split("-")[1])
        with pytest.raises(ProcessLookupError):
            os.kill(pid, 0)
