"""Worker supervision: a process pool that survives the loss of a worker (docs/guarantees.md).

A worker process that dies (SIGKILL from the out-of-memory killer, a crash in native code) breaks a
`ProcessPoolExecutor`: every call still pending on it ends with `BrokenProcessPool`, the one that was running in
the dead worker and all the others. `SupervisedPool` then starts a fresh pool and submits each of those calls
again, at most RETRIES times per key (a point), so that one lost worker costs the time of the calls it
interrupted and no point; a call lost more often than that ends with `BrokenProcessPool` like any failed call,
and its point is recorded as failed with `LOST_MESSAGE`.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
import multiprocessing.context

RETRIES = 1  # a point whose worker died is solved once more: a second loss points at the point itself (its memory)
LOST_MESSAGE = (f"its worker process was lost {RETRIES + 1} times (killed, e.g. by the out-of-memory killer): run "
                "it alone with --jobs 1, or on a coarser --grid")


class WorkerLost(RuntimeError):
    """A call whose worker process died more often than RETRIES allows."""


@dataclass(frozen=True)
class _Call:
    key: Hashable
    function: Callable
    args: tuple[object, ...]


def worker_lost(future: Future) -> bool:
    """The future ended because its pool lost a worker process."""
    return not future.cancelled() and isinstance(future.exception(), BrokenProcessPool)


class SupervisedPool:
    """A ProcessPoolExecutor of `workers` processes that is replaced by a fresh one when a worker dies; the calls
    the dead pool lost are submitted again (`resubmitted`), at most RETRIES times per key."""

    def __init__(self, workers: int, context: multiprocessing.context.BaseContext,
                 initializer: Callable[[], None]) -> None:
        self._options = {"max_workers": workers, "mp_context": context, "initializer": initializer}
        self.executor = ProcessPoolExecutor(**self._options)
        self._calls: dict[Future, _Call] = {}
        self._retries: dict[Hashable, int] = {}

    def submit(self, key: Hashable, function: Callable, *args: object) -> Future:
        """`function(*args)` on a worker, remembered under `key` so that it can be submitted again."""
        future = self.executor.submit(function, *args)
        self._calls[future] = _Call(key, function, args)
        return future

    def wait(self, futures: set[Future] | dict[Future, object], timeout: float) -> set[Future]:
        """The futures among `futures` that finished within `timeout` seconds. After a worker loss all of them
        have finished (the broken pool ends every pending call at once) and a fresh pool takes the next calls."""
        finished, _ = wait(futures, timeout=timeout, return_when=FIRST_COMPLETED)
        if any(worker_lost(future) for future in finished):
            finished, _ = wait(futures)
            self.executor.shutdown(wait=True)  # the broken pool has already ended its processes
            self.executor = ProcessPoolExecutor(**self._options)
        return set(finished)

    def resubmitted(self, future: Future) -> Future | None:
        """The call of `future` submitted again when its worker was lost and its key has a retry left, else None
        (also for every future that did not end by a worker loss). Forgets `future` either way."""
        call = self._calls.pop(future, None)
        if call is None or not worker_lost(future) or self._retries.get(call.key, 0) >= RETRIES:
            return None
        self._retries[call.key] = self._retries.get(call.key, 0) + 1
        return self.submit(call.key, call.function, *call.args)
