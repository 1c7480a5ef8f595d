"""The time a point solve has spent, wall and CPU, carried across the worker processes its stages run in.

The grid refinement's time budget (`solver.time_budget`) reads the CPU time: a solve is single-threaded (one BLAS
thread, Numba kernels without threads), so its CPU time is its wall time on an unloaded core, and a point's grid
does not depend on how loaded the machine was while it was solved."""

from __future__ import annotations

from dataclasses import dataclass
import time

from facegear_tehl.solution import PointSolution


@dataclass(frozen=True)
class Spent:
    """Seconds spent on a point: elapsed real time and CPU time of the processes that solved it."""

    wall: float = 0.0
    cpu: float = 0.0

    def __add__(self, other: Spent) -> Spent:
        return Spent(self.wall + other.wall, self.cpu + other.cpu)

    def scalars(self) -> dict[str, tuple[float, str]]:
        """The solution scalars `wall_time` and `cpu_time` (s)."""
        return {"wall_time": (self.wall, "s"), "cpu_time": (self.cpu, "s")}


NOTHING_SPENT = Spent()  # a point's first attempt


def spent_on(solution: PointSolution) -> Spent:
    """The time a solution reports (`wall_time`, `cpu_time`; a solution without `cpu_time` counts its wall time)."""
    wall = solution.scalars.get("wall_time", (0.0, "s"))[0]
    return Spent(wall, solution.scalars.get("cpu_time", (wall, "s"))[0])


class Stopwatch:
    """Counts on from `spent` in this process (`spent()`); it does not travel between processes."""

    def __init__(self, spent: Spent = NOTHING_SPENT) -> None:
        self._wall = time.perf_counter() - spent.wall
        self._cpu = time.process_time() - spent.cpu

    def spent(self) -> Spent:
        return Spent(time.perf_counter() - self._wall, time.process_time() - self._cpu)
