"""Independent EHL solves (the points of a case, the grids of a sweep) over worker processes.

`solve_each` yields the solves in completion order, each with its index in the task list, so callers can
show progress as solves finish; `solve_all` (used by run.py and sweep.py) collects them in task order. The
solver is passed in: a `StagedSolver` (the EHL solver) is run in stages (a thermal full-multigrid point's
coarse and fine stage are separate tasks), so that five points on two workers do not leave one worker idle
while the other solves the fifth point whole: S1-S5 of the face gear case, thermal full 129^2, 1.73x faster
on two workers than on one (1.68x with whole points). A `PathSolver` (the points of a path solved by
continuation, each from the one before it: ehl/seeded.py) goes in chunks of consecutive points instead, each chunk
whole on one worker. A solve that raises is returned as a failed
`PointSolution` (outcome FAILED, the error as its message, no data); the other tasks still run. With one
job, or one task, everything runs in this process (no pool).

Workers are forked on Linux: they inherit the imported modules and the Numba kernels, which this process
compiles (or loads from Numba's on-disk cache) first by solving the first task on its coarsest grid, so
that no worker compiles and each solve's wall time is the solve alone. The solver starts no threads of
its own (no Numba `parallel`, single-threaded `scipy.fft`; OpenBLAS stops its threads around a fork) and
the workers open no HDF5 file, so forking is safe. Elsewhere workers are spawned and load the kernels
from the on-disk cache (`cache=True`; its files are written by rename, so workers compiling at the same
time do not corrupt it).

A worker that dies (SIGKILL, the out-of-memory killer) breaks the pool: its solves and those of the other workers
are submitted again to a fresh pool, and a solve lost twice is run alone (supervision.py), so that a lost worker
costs no point.

Every solve, in this process or a worker, runs with one BLAS thread: OpenBLAS adds in another order with
more threads, so this keeps the results bit-identical whatever `jobs` (and whatever the machine's core
count), and workers that already fill the cores do not also spin BLAS threads against each other.
Each solve is then the same deterministic computation wherever it runs.
"""

from __future__ import annotations

from concurrent.futures import Future, ProcessPoolExecutor
import concurrent.futures.process
from contextlib import closing
from dataclasses import dataclass, replace
import multiprocessing
import os
import signal
import sys
import threading
from typing import Callable, Iterator, Protocol, Sequence, runtime_checkable

from threadpoolctl import threadpool_limits

from facegear_tehl.contact import ContactPoint
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.schema import check
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import Outcome, PointSolution
from facegear_tehl.supervision import LOST_MESSAGE, SupervisedPool, WorkerLost, die_with_parent, worker_lost

Solver = Callable[[ContactPoint, Lubricant, SolverSettings], PointSolution]
"""A whole solve: `ehl.solve.solve_point` or a stand-in with its signature (module-level, so that it can be
pickled)."""


@runtime_checkable
class StagedSolver(Protocol):
    """A solver that can also run in stages that may go to different processes, with the same result as a
    whole solve (ehl.solve.StagedSolver): `begin(point, lubricant, settings, retry_after)` returns the solution
    or a picklable intermediate that `finish` completes; a solution for which `needs_retry` holds is begun
    again with `retry_after` set to it, until `needs_retry` no longer holds, and `with_retry(first, last)` is
    kept."""

    def __call__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution: ...

    def begin(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
              retry_after: PointSolution | None = None) -> object: ...

    def finish(self, stage: object) -> PointSolution: ...

    def needs_retry(self, solution: PointSolution) -> bool: ...

    def with_retry(self, first: PointSolution, retry: PointSolution) -> PointSolution: ...


@dataclass(frozen=True)
class PathSolver:
    """Neighbouring points of a path solved by continuation: `solve_path` solves consecutive tasks in order, each
    from the one before it (ehl.seeded.solve_path); the tasks go to the workers in chunks of `chunk`, each chunk in
    one process, its first point solved cold. The chunks do not depend on the worker count: `--jobs 2` writes the
    same file as `--jobs 1`."""

    solve_path: Callable[[Sequence[tuple[ContactPoint, Lubricant, SolverSettings]]], list[PointSolution]]
    chunk: int

    def __call__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
        return self.solve_path([(point, lubricant, settings)])[0]


@dataclass(frozen=True)
class SolveTask:
    """One independent solve."""

    point: ContactPoint
    lubricant: Lubricant
    settings: SolverSettings


@dataclass(frozen=True)
class Solved:
    """The outcome of one task: `failed` when the solve raised (the solution then holds only the error)."""

    solution: PointSolution
    failed: bool


Progress = Callable[[PointSolution, int, int], None]
"""Called as each solve finishes with (solution, solves done, solves in all)."""


def available_cores() -> int:
    """Cores this process may run on (its CPU affinity where the OS tells, else os.cpu_count())."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def worker_count(jobs: int | None, key: str = "--jobs") -> int:
    """`jobs` checked (CaseError under `key` unless >= 1); None means all available cores."""
    if jobs is None:
        return available_cores()
    check(isinstance(jobs, int) and jobs >= 1, key, jobs, "a number of worker processes >= 1")
    return jobs


def failed_solution(name: str, error: BaseException) -> PointSolution:
    """The record of a solve that raised `error`: failed, no data, the error as the message."""
    return PointSolution(
        name=name,
        outcome=Outcome.FAILED,
        message=f"failed: {type(error).__name__}: {error}",
        scalars={},
        fields={},
        axes={},
    )


def solve_all(tasks: Sequence[SolveTask], solver: Solver | StagedSolver | PathSolver, *, jobs: int | None = None,
              progress: Progress | None = None) -> tuple[list[PointSolution], tuple[int, ...]]:
    """Every task solved (`solve_each`), in task order, and the indices of those whose solve raised.
    `progress` sees the solutions in the order they finish. An exception in `progress` (Ctrl-C while it
    reports) stops the workers at once, not when the generator is collected."""
    solutions: list[PointSolution | None] = [None] * len(tasks)
    failed: list[int] = []
    with closing(solve_each(tasks, solver, jobs=jobs)) as outcomes:
        for done, (index, outcome) in enumerate(outcomes, start=1):
            solutions[index] = outcome.solution
            if outcome.failed:
                failed.append(index)
            if progress is not None:
                progress(outcome.solution, done, len(tasks))
    return solutions, tuple(sorted(failed))


def solve_each(tasks: Sequence[SolveTask], solver: Solver | StagedSolver | PathSolver, *,
               jobs: int | None = None) -> Iterator[tuple[int, Solved]]:
    """Run every task with `solver` on up to `jobs` worker processes (None: all cores); yield (task index,
    outcome) as each solve finishes. A StagedSolver runs in stages on the workers, so that a worker that would
    wait for the last point takes the next stage of another (five thermal points on two workers); a PathSolver
    runs its chunks whole, each task's outcome yielded when its chunk finishes.
    Interrupting the caller (Ctrl-C, SIGTERM, an error in the loop body) stops the workers at once."""
    units = _units(tasks, solver)  # (first task, end) of each submitted unit: one task, or a path's chunk
    workers = min(worker_count(jobs), len(units))
    if workers <= 1:
        with threadpool_limits(limits=1):
            for first, end in units:
                yield from enumerate(_solve_unit(solver, tasks[first:end]), start=first)
        return
    staged = isinstance(solver, StagedSolver)
    context = _context()
    if context.get_start_method() == "fork":
        _warm_up(getattr(solver, "warm_up_solver", solver), tasks[0])  # a unit that runs another solver: with it
    pool = SupervisedPool(workers, context, _init_worker)  # a lost worker's solves are retried once
    try:
        # per future: (task index, first attempt when this is a retry)
        pending: dict[Future, tuple[int, PointSolution | None]] = {}

        def submit(index: int, first: PointSolution | None, function: Callable, *args: object) -> None:
            with _DeferredSignals():
                pending[pool.submit(index, _stage_task, function, tasks[index].point.name, *args)] = (index, first)

        for i, end in units:
            task = tasks[i]
            submit(i, None, *((solver.begin, task.point, task.lubricant, task.settings, None) if staged
                              else (_solve_unit, solver, tasks[i:end])))
        while pending:
            with _DeferredSignals() as signals:
                finished: set[Future] = set()
                while not finished and not signals.received:
                    finished = pool.wait(pending, timeout=0.2)
            for future in sorted(pool.retry_lost(finished, pending), key=lambda f: pending[f][0]):
                index, first = pending.pop(future)
                outcome = _outcome(future, tasks[index])
                if not staged:
                    yield from _unit_outcomes(outcome, index, dict(units)[index], tasks)
                elif isinstance(outcome, Solved):
                    yield index, outcome
                elif not isinstance(outcome, PointSolution):  # an intermediate: its next stage
                    submit(index, first, solver.finish, outcome)
                elif solver.needs_retry(outcome):
                    task = tasks[index]
                    submit(index, first or outcome, solver.begin, task.point, task.lubricant, task.settings, outcome)
                else:
                    yield index, Solved(outcome if first is None else solver.with_retry(first, outcome), failed=False)
    except BaseException:
        for executor in pool.executors:
            _stop_workers(executor)
        raise
    pool.shared.shutdown()


class _DeferredSignals:
    """Within the block, SIGINT and SIGTERM are only recorded; at its end a recorded signal is raised again
    with the handlers restored (Ctrl-C becomes KeyboardInterrupt there). This keeps the exception out of
    `concurrent.futures`' internals: raised inside `wait`, it can leave the futures' locks held, which the
    pool's manager thread then waits on at the interpreter's exit (an interrupted two-worker run once hung
    there, in the test suite on a loaded machine). Only in the main thread (the only one that receives
    signals); elsewhere it does nothing."""

    SIGNALS = (signal.SIGINT, signal.SIGTERM)

    def __init__(self) -> None:
        self.received: list[int] = []
        self._previous: dict[int, object] = {}

    def __enter__(self) -> "_DeferredSignals":
        if threading.current_thread() is threading.main_thread():
            for signum in self.SIGNALS:
                self._previous[signum] = signal.signal(signum, self._record)
        return self

    def _record(self, signum: int, frame: object) -> None:
        self.received.append(signum)

    def __exit__(self, *exc: object) -> None:
        for signum, handler in self._previous.items():
            signal.signal(signum, handler)
        if self.received:
            signal.raise_signal(self.received[0])


def _units(tasks: Sequence[SolveTask], solver: Solver | StagedSolver | PathSolver) -> list[tuple[int, int]]:
    """(first task, end) of each unit of work: a path's chunks (PathSolver), else one task each."""
    size = solver.chunk if isinstance(solver, PathSolver) else 1
    return [(first, min(first + size, len(tasks))) for first in range(0, len(tasks), size)]


def _solve_unit(solver: Solver | PathSolver, tasks: Sequence[SolveTask]) -> list[Solved]:
    """A unit of work in this process or a worker: a path's chunk in order (a chunk that raises: each of its tasks
    failed with the error; the other chunks still run), or one task."""
    if not isinstance(solver, PathSolver):
        return [_solve_task(solver, task) for task in tasks]
    try:
        return [Solved(s, failed=False) for s in solver.solve_path([(t.point, t.lubricant, t.settings)
                                                                     for t in tasks])]
    except Exception as exc:  # one failing chunk must not lose the others; the error is recorded
        return [Solved(failed_solution(task.point.name, exc), failed=True) for task in tasks]


def _unit_outcomes(outcome: object, first: int, end: int, tasks: Sequence[SolveTask]) -> Iterator[tuple[int, Solved]]:
    """Each task's outcome of a finished unit: its solves, or (a unit whose worker was lost) its failure for each."""
    if isinstance(outcome, Solved):  # the worker could not deliver the unit (_outcome)
        yield from ((index, Solved(replace(outcome.solution, name=tasks[index].point.name), failed=True))
                    for index in range(first, end))
        return
    yield from enumerate(outcome, start=first)


def _solve_task(solve: Solver, task: SolveTask) -> Solved:
    """One whole solve: its solution, or a failed record if it raised (the other tasks still run)."""
    try:
        return Solved(solve(task.point, task.lubricant, task.settings), failed=False)
    except Exception as exc:  # one failing solve must not lose the others; the error is recorded
        return Solved(failed_solution(task.point.name, exc), failed=True)


def _stage_task(function: Callable, name: str, *args: object) -> object:
    """One stage in a worker: its result, or a failed record if it raised (the other tasks still run)."""
    try:
        return function(*args)
    except Exception as exc:
        return Solved(failed_solution(name, exc), failed=True)


def _warm_up(solve: Solver, task: SolveTask) -> None:
    """Compile or load the solver's Numba kernels here, before forking: solve `task` on its coarsest grid, square (the
    same kernels as on the coarsest grid's x nodes with the case's rows, for a sixth of the time: 0.07 against 0.41 s
    CPU at S1 of the face gear case, whose 17 x 65 also solved its error bound's check)."""
    settings = replace(task.settings, grid=task.settings.coarsest_grid, grid_y=task.settings.coarsest_grid)
    try:
        solve(task.point, task.lubricant, settings)
    except Exception:  # the task itself will meet and record the same error
        pass


def _outcome(future: Future, task: SolveTask) -> object:
    """The worker's result (a Solved, or with stages a solution or an intermediate), or a failed record if the
    worker could not deliver one (e.g. it was killed)."""
    error = future.exception()
    if worker_lost(future):
        return Solved(failed_solution(task.point.name, WorkerLost(LOST_MESSAGE)), failed=True)
    return future.result() if error is None else Solved(failed_solution(task.point.name, error), failed=True)


def _context() -> multiprocessing.context.BaseContext:
    return multiprocessing.get_context("fork" if sys.platform.startswith("linux") else "spawn")


def _init_worker(parent: int) -> None:
    """Workers end with their parent `parent` (supervision.die_with_parent: a killed `tehl run` leaves no worker),
    leave Ctrl-C to the parent (which stops them), end on SIGTERM without cleanup handlers
    inherited from the CLI, and use one BLAS thread (see the module: same results as in this process; and
    S1-S5 of the face gear case, thermal full, on 2 cores: 15.3 s with OpenBLAS's default threads in both
    workers, 13.1 s with one)."""
    die_with_parent(parent)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    threadpool_limits(limits=1)


def _stop_workers(executor: ProcessPoolExecutor) -> None:
    """Cancel the queued solves and end the running ones now, not when they finish."""
    terminate = getattr(executor, "terminate_workers", None)  # Python >= 3.14
    if terminate is not None:
        terminate()
        return
    # Before 3.14 there is no public call for this: end the processes of the executor's table.
    processes = list((getattr(executor, "_processes", None) or {}).values())
    manager = getattr(executor, "_executor_manager_thread", None)  # shutdown() drops the executor's reference
    executor.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        process.terminate()
    for process in processes:
        process.join()
    # Let the executor's manager thread see the broken pool and close its wake-up pipe now: left running, it
    # can close the pipe while the interpreter's exit hook writes to it ("Bad file descriptor" at exit).
    if manager is not None:
        manager.join(timeout=5.0)
        if manager.is_alive():  # a loaded machine: take its pipe off the exit hook's list (it ends on its own)
            wakeups = getattr(concurrent.futures.process, "_threads_wakeups", None)
            if wakeups is not None:
                wakeups.pop(manager, None)
