"""Worker supervision: a process pool that survives the loss of a worker (docs/guarantees.md).

A worker process that dies (SIGKILL from the out-of-memory killer, a crash in native code) breaks a
`ProcessPoolExecutor`: every call still pending on it ends with `BrokenProcessPool`, the one that was running in
the dead worker and all the others, and the pool does not say which one it was. `SupervisedPool` then starts a
fresh pool and submits each of those calls again; a call lost a second time is solved alone, in a pool of its own,
so that only the call that kills its worker is lost a third time (MAX_LOSSES): it ends with `BrokenProcessPool`
like any failed call, and its point is recorded as failed with `LOST_MESSAGE`. One lost worker costs the time of
the calls it interrupted and no point.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
import ctypes
import ctypes.util
from dataclasses import dataclass
import multiprocessing.context
import os
import signal
import sys
import threading
import time

PR_SET_PDEATHSIG = 1  # prctl(2) option: the signal this process gets when its parent dies (Linux)
PARENT_POLL = 1.0  # s, how often a worker without prctl looks whether its parent is still there
MAX_LOSSES = 3  # lost once: solved again in a fresh pool; twice: solved alone; a third time, alone: it is the culprit
LOST_MESSAGE = (f"its worker process was lost {MAX_LOSSES} times, the last time solving this point alone (killed, "
                "e.g. by the out-of-memory killer): run it on a coarser --grid, or on a machine with more memory")


def die_with_parent(parent: int) -> None:
    """End this worker process when its parent `parent` (the pid that started it) ends, whatever ends it: SIGKILL
    of the parent leaves no worker computing for nobody. On Linux the kernel sends SIGKILL (prctl
    PR_SET_PDEATHSIG); elsewhere a daemon thread looks every PARENT_POLL seconds."""
    libc = ctypes.CDLL(ctypes.util.find_library("c"), use_errno=True) if sys.platform.startswith("linux") else None
    if libc is not None and libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) == 0:
        if os.getppid() != parent:  # the parent died before the call: nobody would send the signal
            os._exit(1)
        return

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(PARENT_POLL)
        os._exit(1)

    threading.Thread(target=watch, name="parent-watch", daemon=True).start()


class WorkerLost(RuntimeError):
    """A call whose worker process died MAX_LOSSES times, the last time solving it alone."""


@dataclass(frozen=True)
class _Call:
    key: Hashable
    function: Callable
    args: tuple[object, ...]
    executor: ProcessPoolExecutor


def worker_lost(future: Future) -> bool:
    """The future ended because its pool lost a worker process."""
    return not future.cancelled() and isinstance(future.exception(), BrokenProcessPool)


class SupervisedPool:
    """A ProcessPoolExecutor of `workers` processes (`shared`) replaced by a fresh one when a worker dies; each
    call it lost is submitted again (`resubmitted`): to the fresh pool after its first loss, to a pool of its own
    after its second (a call lost while it waited beside the culprit must not be blamed for it), and not after
    its third (MAX_LOSSES: lost while solved alone, the call itself kills its worker)."""

    def __init__(self, workers: int, context: multiprocessing.context.BaseContext,
                 initializer: Callable[[int], None]) -> None:
        """`initializer` runs first in each worker, given this process's pid (for `die_with_parent`)."""
        self._options = {"mp_context": context, "initializer": initializer, "initargs": (os.getpid(),)}
        self._workers = workers
        self.shared = ProcessPoolExecutor(max_workers=workers, **self._options)
        self.alone: list[ProcessPoolExecutor] = []
        self._calls: dict[Future, _Call] = {}
        self._losses: dict[Hashable, int] = {}

    @property
    def executors(self) -> list[ProcessPoolExecutor]:
        return [self.shared, *self.alone]

    def submit(self, key: Hashable, function: Callable, *args: object,
               executor: ProcessPoolExecutor | None = None) -> Future:
        """`function(*args)` on a worker (of `executor`, default the shared pool), remembered under `key` so that
        it can be submitted again."""
        executor = executor or self.shared
        future = executor.submit(function, *args)
        self._calls[future] = _Call(key, function, args, executor)
        return future

    def wait(self, futures: set[Future] | dict[Future, object], timeout: float) -> set[Future]:
        """The futures among `futures` that finished within `timeout` seconds. After the shared pool lost a
        worker all of its futures have finished (the broken pool ends every pending call at once) and a fresh
        shared pool takes the next calls."""
        finished, _ = wait(futures, timeout=timeout, return_when=FIRST_COMPLETED)
        if any(worker_lost(f) and self._calls[f].executor is self.shared for f in finished if f in self._calls):
            broken = [f for f in futures if f in self._calls and self._calls[f].executor is self.shared]
            wait(broken)
            finished = set(finished) | set(broken)
            self.shared.shutdown(wait=True)  # the broken pool has already ended its processes
            self.shared = ProcessPoolExecutor(max_workers=self._workers, **self._options)
        return set(finished)

    def retry_lost(self, finished: set[Future], pending: dict[Future, object]) -> set[Future]:
        """`finished` less the futures whose calls were submitted again (`resubmitted`), each new future taking
        its old one's entry in `pending`."""
        kept = set()
        for future in finished:
            again = self.resubmitted(future)
            if again is None:
                kept.add(future)
            else:
                pending[again] = pending.pop(future)
        return kept

    def resubmitted(self, future: Future) -> Future | None:
        """The call of `future` submitted again when its worker was lost, as the class says, else None (also for
        every future that did not end by a worker loss). Forgets `future` either way."""
        call = self._calls.pop(future, None)
        if call is None:
            return None
        if call.executor in self.alone:  # a pool of its own: done with it
            call.executor.shutdown(wait=False)
            self.alone.remove(call.executor)
        if not worker_lost(future):
            return None
        losses = self._losses[call.key] = self._losses.get(call.key, 0) + 1
        if losses >= MAX_LOSSES:
            return None
        executor = None
        if losses == MAX_LOSSES - 1:
            executor = ProcessPoolExecutor(max_workers=1, **self._options)
            self.alone.append(executor)
        return self.submit(call.key, call.function, *call.args, executor=executor)
