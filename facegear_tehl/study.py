"""Running a study (`tehl study`): every variant of a study file as one Dask task, one result file per variant, an
index of the results, resumable.

Each variant is one task on a Dask cluster (a local one of N worker processes, one thread each, or an existing
cluster by its scheduler's address). The task runs the code path of `tehl run` on the variant's resolved case
text (`run.run_case`, its points solved one after the other in the task) and returns the `RunResult`; this
process writes it with `results.write_result` (atomically) as `<values>.h5` in the study folder
(`pinion_torque=250_pinion_speed=1500.h5`, `study_file.Variant.file_name`), so the workers
need no file system shared with it. Dask reschedules the task of a worker that dies (up to its
`distributed.scheduler.allowed-failures`, 3 by default); a task that still fails, or raises, is recorded as a
failed variant with its message and the other variants go on.

Resuming: a variant whose file exists, reads back as a complete result and holds the variant's resolved case (its
SHA-256 equal) is skipped, so an interrupted study (Ctrl-C, a killed worker, a lost node) completes on the next run
and recomputes nothing that was finished. `index.csv` (one row per variant and point) is rewritten at the end of
every run, interrupted or not, from the files themselves; `failures.txt` lists the variants that failed.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import ExitStack, contextmanager, nullcontext
import csv
from dataclasses import dataclass
import io
import logging
import os
from pathlib import Path
import secrets
import time

import h5py

from facegear_tehl.atomic_files import remove_stale, temporary_beside
from facegear_tehl.folder_lock import exclusive
from facegear_tehl.output_path import starts_with
from facegear_tehl.record import Action
from facegear_tehl.results import ResultFileError, RunResult, read_result, write_result
from facegear_tehl.scheduler_probe import probe
from facegear_tehl.schema import CaseError
from facegear_tehl.study_file import Study, Variant, digest, value_text
from facegear_tehl.study_index import (
    COLUMNS,
    CYCLE_COLUMNS,
    ESTIMATE_COLUMNS,
    GRID,
    INDEX,
    INDEX_HEADER,
    POINT_COLUMNS,
    REFINEMENTS,
)
from facegear_tehl.tables import error_bound

FAILURES = "failures.txt"
# Dask starts worker processes with MALLOC_TRIM_THRESHOLD_=65536 (its distributed.nanny.pre-spawn-environ), which
# fixes glibc's mmap threshold: every array above 128 KiB is then mapped and unmapped anew, and a 257^2 solve of
# the ball-on-disc case takes 2.4 s instead of 1.7 s (scripts/bench_study.py). The local cluster leaves it unset
# (docs/study.md shows the same for `dask worker`).
WORKER_ENVIRON = {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}
CONNECT_TIMEOUT = "10s"  # a scheduler that does not answer within this is taken as absent (Dask's default: 30 s)


@dataclass(frozen=True)
class VariantRun:
    """What a task returns: the variant's run and the seconds it took in the task."""

    run: RunResult
    seconds: float


@dataclass(frozen=True)
class VariantOutcome:
    """One variant after this run: status ok | not_converged | failed (a result file's status, or failed with no
    file when the task raised or its file could not be written) | pending (interrupted before it finished);
    computed here or skipped; whether its result file is in the study folder."""

    variant: Variant
    status: str
    message: str
    computed: bool
    has_file: bool
    seconds: float = 0.0  # the task's own time (computed variants)


@dataclass(frozen=True)
class StudyReport:
    """A finished (or interrupted) study run: every variant's outcome in study order, the wall time from the
    first task submitted to the last result written, and the index written."""

    outcomes: tuple[VariantOutcome, ...]
    seconds: float
    index: Path

    @property
    def failed(self) -> tuple[VariantOutcome, ...]:
        return tuple(o for o in self.outcomes if o.status == "failed")

    @property
    def computed(self) -> int:
        return sum(o.computed for o in self.outcomes)


StudyProgress = Callable[[VariantOutcome, int, int, float], None]
"""Called as each computed variant is written, with (outcome, variants done, variants to compute, the estimated
seconds left)."""


def solve_variant(text: str) -> VariantRun:
    """The task: the variant's resolved case text run as `tehl run` runs it, its points in this process."""
    # imported here, not at the top, for start-up: a study whose variants are all finished loads no solver (Numba)
    from facegear_tehl.case import parse_case
    from facegear_tehl.run import run_case

    start = time.perf_counter()
    case = parse_case(text)
    return VariantRun(run_case(case, jobs=1), time.perf_counter() - start)


def finished(path: Path, variant: Variant) -> bool:
    """The variant's file exists, reads back as a complete result and holds the resolved case that names it."""
    return unfinished_reason(path, variant) is None


def unfinished_reason(path: Path, variant: Variant) -> str | None:
    """None when `finished`; else why not: the reader's sentence (missing, damaged, not a result) or another case."""
    try:
        held = digest(read_result(path).case_yaml)
    except ResultFileError as exc:
        return str(exc)
    return None if held == variant.digest else f"{path}: holds another case than the variant's"


def _resumed(study: Study, folder: Path, notice: Callable[[str], None] | None) -> dict[int, VariantOutcome]:
    """The outcomes of the variants whose files are finished; each file that exists but is not finished (damaged,
    another case) is named to `notice`: the study runs its variant again."""
    outcomes = {}
    for variant in study.variants:
        path = folder / variant.file_name
        reason = unfinished_reason(path, variant) if path.exists() or path.is_symlink() else "missing"
        if reason is None:
            outcomes[variant.index] = _read_outcome(folder, variant)
        elif reason != "missing" and notice is not None:
            notice(f"variant {variant.index + 1} ({variant.label}): {reason}; running it again")
    return outcomes


def check_folder(folder: Path) -> None:
    """CaseError under -o unless `folder` is a directory or can be made one under a writable directory, and any
    index.csv in it is one tehl study wrote (a file, its header starting with INDEX_HEADER)."""
    if folder.exists() and not folder.is_dir():
        raise CaseError("-o", str(folder), "a directory for the study's files, not a file")
    index = folder / INDEX
    if index.exists() and not starts_with(INDEX_HEADER)(index):
        raise CaseError("-o", str(folder), f"a study folder whose {INDEX} tehl study wrote, or a new one ({index} "
                                           "is not one: its index would be overwritten)")
    existing = folder.absolute()
    while not existing.exists():
        existing = existing.parent
    if not os.access(existing, os.W_OK):
        raise CaseError("-o", str(folder), f"a directory under a writable one ({existing} is not writable)")


def run_study(study: Study, folder: Path, *, workers: int = 1, scheduler: str | None = None,
              progress: StudyProgress | None = None, notice: Callable[[str], None] | None = None) -> StudyReport:
    """Run every variant of `study` whose file in `folder` is not already finished, on a local Dask cluster of
    `workers` processes (at most one per variant to run) or on the cluster whose scheduler is at `scheduler`; write
    index.csv (and failures.txt when a variant failed). Bad `folder` or an unreachable scheduler raise CaseError
    before anything is written. `notice` is told of each existing file that is run again (damaged, or another
    case)."""
    check_folder(folder)
    outcomes = _resumed(study, folder, notice)
    todo = [v for v in study.variants if v.index not in outcomes]
    start, started = time.perf_counter(), False
    lock = ExitStack()
    try:
        with _client(min(workers, len(todo)), scheduler) if todo else nullcontext() as client:  # as --jobs
            folder.mkdir(parents=True, exist_ok=True)  # the cluster is there: from here on the index is written
            lock.enter_context(exclusive(folder, "-o"))  # by this study alone
            outcomes.update({v.index: _read_outcome(folder, v) for v in todo if finished(folder / v.file_name, v)})
            todo = [v for v in todo if v.index not in outcomes]  # less what a study before this one finished
            start, started = time.perf_counter(), True
            if todo:
                for outcome in _compute(client, todo, folder, progress, start):
                    outcomes[outcome.variant.index] = outcome
    finally:
        with lock:  # released once the index is written
            if started:
                final = tuple(outcomes.get(v.index) or _unrecorded(folder, v) for v in study.variants)
                index = write_index(study, folder, final)
    return StudyReport(final, time.perf_counter() - start, index)


@contextmanager
def _client(workers: int, scheduler: str | None) -> Iterator[object]:
    """A Dask client: of the cluster at `scheduler`, else of a local cluster of `workers` processes."""
    # imported here, not at the top, for start-up: a study whose variants are all finished does not load Dask
    import dask
    from distributed import Client, LocalCluster

    if scheduler is not None:
        probe(scheduler)  # a server that never answers, or is not Dask's: CaseError, not a hang
        try:
            client = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except (OSError, ValueError, TypeError) as exc:
            raise CaseError("--scheduler", scheduler, f"the address of a running Dask scheduler, e.g. "
                                                      f"tcp://host:8786 ({type(exc).__name__}: {exc})") from None
        with client:
            yield client
        return
    with dask.config.set(WORKER_ENVIRON), LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                                       dashboard_address=None, silence_logs=logging.ERROR) as cluster, \
            Client(cluster) as client:
        yield client


def _compute(client: object, todo: Sequence[Variant], folder: Path, progress: StudyProgress | None,
             start: float) -> Iterator[VariantOutcome]:
    """Submit one task per variant; write each result as it arrives; yield the outcomes in completion order."""
    from distributed import as_completed

    run = secrets.token_hex(4)  # task keys unique to this run: another study on the same cluster has its own
    futures = {client.submit(solve_variant, v.text, key=f"tehl-variant-{v.digest[:16]}-{run}", pure=False): v
               for v in todo}
    for done, future in enumerate(as_completed(futures), start=1):
        variant = futures.pop(future)
        try:
            solved = future.result()
            write_result(solved.run, folder / variant.file_name)
            outcome = VariantOutcome(variant, solved.run.status, solved.run.message, True, True, solved.seconds)
        except Exception as exc:  # noqa: BLE001 - one failing variant is recorded; the others go on
            outcome = VariantOutcome(variant, "failed", f"{type(exc).__name__}: {exc}".replace("\n", " "), True, False)
        future.release()
        if progress is not None:
            elapsed = time.perf_counter() - start
            progress(outcome, done, len(todo), elapsed / done * (len(todo) - done))
        yield outcome


def _read_outcome(folder: Path, variant: Variant) -> VariantOutcome:
    """The outcome of a variant skipped because its file is finished: the file's status and message."""
    result = read_result(folder / variant.file_name, fields=False)
    return VariantOutcome(variant, result.status, result.message, False, True)


def _unrecorded(folder: Path, variant: Variant) -> VariantOutcome:
    """A variant with no outcome when the run stopped: finished if its file was written just before (an
    interruption between the write and its record), else pending."""
    if finished(folder / variant.file_name, variant):
        return _read_outcome(folder, variant)
    return VariantOutcome(variant, "pending", "not run yet", False, False)


def write_index(study: Study, folder: Path, outcomes: Sequence[VariantOutcome]) -> Path:
    """DIR/index.csv, one row per variant and point (a failed or pending variant: one row without a point):
    variant number, the varied values, point, status, converged, the scalars of COLUMNS and their error estimates
    (SI, units in the header; empty where the file has none), the grid solved on (nx x ny), the refinements (solved
    again on a finer grid), the file, the message.
    Then failures.txt (or its removal)."""
    header = ["variant", *study.keys, "point", "status", "converged",
              *(f"{name} [{units}]" for name, units in POINT_COLUMNS + CYCLE_COLUMNS + ESTIMATE_COLUMNS), GRID,
              REFINEMENTS, "file", "message"]
    rows = []
    for outcome in outcomes:
        variant = outcome.variant
        lead = [str(variant.index + 1), *(value_text(value) for _, value in variant.values)]
        path = folder / variant.file_name
        if not outcome.has_file:
            rows.append([*lead, "", outcome.status, "", *([""] * (len(COLUMNS) + len(ESTIMATE_COLUMNS))), "", "", "",
                         outcome.message])
            continue
        result = read_result(path, fields=False)
        cycle = _cycle_attrs(path)
        for point in result.points.values():
            scalars = [_number(point.scalars.get(name)) for name, _ in POINT_COLUMNS]
            rows.append([*lead, point.name, result.status, "yes" if point.converged else "no", *scalars,
                         *(_number(cycle.get(name)) for name, _ in CYCLE_COLUMNS),
                         *(_bound_cell(point.scalars, name) for name, _ in ESTIMATE_COLUMNS),
                         "x".join(str(len(point.axes[k].values)) for k in ("x", "y") if k in point.axes),
                         "" if point.record is None else
                         str(sum(r.action is Action.FINER_GRID for r in point.record.retries)),
                         variant.file_name,
                         point.message.replace("\n", " ")])
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(rows)
    index = _write_text(folder / INDEX, text.getvalue())
    failed = [o for o in outcomes if o.status == "failed"]
    if failed:
        _write_text(folder / FAILURES, "".join(f"variant {o.variant.index + 1} ({o.variant.label}): "
                                               f"{o.message or 'failed'}\n" for o in failed))
    else:
        (folder / FAILURES).unlink(missing_ok=True)
    return index


def _bound_cell(scalars: Mapping[str, float], column: str) -> str:
    """An error-bound cell of the index: the bound, "unresolved", or empty (tables.error_bound)."""
    bound = error_bound(scalars, column.removeprefix("error_bound_"))
    return bound if isinstance(bound, str) else _number(bound)


def _cycle_attrs(path: Path) -> dict[str, float]:
    """The numeric attributes of the file's /cycle group (power loss, mesh efficiency), if it has one."""
    with h5py.File(path, "r") as h5:
        group = h5.get("cycle")
        if group is None:
            return {}
        return {key: float(value) for key, value in group.attrs.items() if key in dict(CYCLE_COLUMNS)}


def _number(value: float | None) -> str:
    return "" if value is None else f"{float(value):.10g}"


def _write_text(path: Path, text: str) -> Path:
    """`text` written to a temporary file and renamed onto `path` (no partial file ever)."""
    remove_stale(path)  # a killed writer's temporary file
    temporary = temporary_beside(path)
    try:
        temporary.write_text(text, encoding="utf-8")
        os.replace(temporary, path)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    return path
