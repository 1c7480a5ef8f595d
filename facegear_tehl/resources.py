"""The resource guard: memory and time a run will take, estimated before it starts (docs/guarantees.md).

Each solve holds a working set proportional to its grid's nodes (the domain it is solved on, its inlet
lengthened: ehl.domain.solution_domain), its worker process a fixed base (interpreter, NumPy, the Numba kernels),
and the run keeps every point's fields until it writes the file. Peak memory of a run of `processes` workers:

    M = (processes [+ 1 for the parent with a pool]) * BASE + sum of the `processes` largest working sets
        + sum over the points of their fields' bytes per node * nodes

with the per-node bytes below, measured as the peak resident set (ru_maxrss) of `tehl run --jobs 1` against its
grid's nodes; the ball-on-disc case on 4097^2 nodes gives 5.5 GB, within the 5-6 GB the issue that asked for this
guard saw it allocate. The time is as rough: nodes times the measured seconds per node of a whole solve, over the
processes. A run whose estimate passes the machine's memory (its physical memory, or the cgroup's limit when
lower) is refused before it starts unless --force; the refinement that run.py may add (a finer grid for a film
the first grid did not resolve) is not in the estimate.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
import os
from pathlib import Path

from facegear_tehl.case import Case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.domain import solution_domain
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.points import contact_analysis
from facegear_tehl.schema import CaseError
from facegear_tehl.settings import SolverSettings

BASE = 210e6  # bytes per process: `tehl run` of the ball-on-disc case on 33^2 nodes peaked at 208 MB
ISOTHERMAL_NODE = 300.0  # bytes per node: the same case on 257^2 and 513^2 nodes, +20 MB and +71 MB over BASE
THERMAL_NODE = 6000.0  # bytes per node: S1 of the face gear case, thermal full, on 257 x 33 and 513 x 65 nodes
# (its inlet lengthened), +48 MB and +196 MB over BASE (the temperature layers across film and solids)
# Bytes per node and point kept until the file is written: the float64 fields of a point (S1 thermal full: 15; the
# isothermal ball-on-disc case: 2)
THERMAL_FIELD_BYTES = 120.0
ISOTHERMAL_FIELD_BYTES = 16.0
ISOTHERMAL_SECONDS = 25e-6  # s per node of a whole solve: 6.5 s on 513^2 nodes (the ball-on-disc case, one core)
THERMAL_SECONDS = 200e-6  # s per node: 5.9 s on 513 x 65 nodes (S1, thermal full, one core)
CGROUP_LIMIT = Path("/sys/fs/cgroup/memory.max")  # cgroup v2: the memory this process's group may use


@dataclass(frozen=True)
class Estimate:
    """Peak memory (bytes) and rough wall time (s) of a run, and the nodes of its largest solve."""

    memory: float
    seconds: float
    largest: int

    def text(self) -> str:
        return (f"estimated peak memory {self.memory / 1e9:.1f} GB, roughly {_duration(self.seconds)} "
                f"(largest solve {self.largest} nodes)")


def estimate(tasks: Sequence[tuple[ContactPoint, Lubricant, SolverSettings]], processes: int) -> Estimate:
    """The Estimate of solving `tasks` (point, lubricant, settings) on `processes` worker processes."""
    nodes = [_nodes(point, lubricant, settings) for point, lubricant, settings in tasks]
    thermal = [settings.thermal != "off" for _, _, settings in tasks]
    working = sorted((n * (THERMAL_NODE if t else ISOTHERMAL_NODE) for n, t in zip(nodes, thermal)), reverse=True)
    kept = sum(n * (THERMAL_FIELD_BYTES if t else ISOTHERMAL_FIELD_BYTES) for n, t in zip(nodes, thermal))
    processes = max(1, min(processes, len(tasks)))
    memory = (processes + (processes > 1)) * BASE + sum(working[:processes]) + kept
    seconds = sum(n * (THERMAL_SECONDS if t else ISOTHERMAL_SECONDS) for n, t in zip(nodes, thermal)) / processes
    return Estimate(memory, seconds, max(nodes, default=0))


def study_estimate(cases: Sequence[Case], workers: int) -> Estimate:
    """The Estimate of a study's variants `cases` on `workers` processes, each solving one variant's points in
    turn: `workers` times the largest variant's. Variants are grouped by grid and thermal model and the first and
    last of each group estimated (the grid sets the nodes; the load and speed only how far the inlet is lengthened)."""
    groups: dict[tuple[object, ...], list[Case]] = {}
    for case in cases:
        groups.setdefault((case.solver.grid, case.solver.nodes_y, case.solver.thermal), []).append(case)
    singles = [estimate([(p, c.lubricant, c.solver) for p in contact_analysis(c).points], 1)
               for group in groups.values() for c in {id(group[0]): group[0], id(group[-1]): group[-1]}.values()]
    largest = max(singles, key=lambda e: e.memory)
    count = max(1, min(workers, len(cases)))
    return Estimate(count * largest.memory, sum(e.seconds for e in singles) / len(singles) * len(cases) / count,
                    largest.largest)


def machine_memory() -> float:
    """Bytes this process may use: the physical memory, or its cgroup's limit when lower."""
    total = float(os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    try:
        limit = CGROUP_LIMIT.read_text().strip()
    except OSError:
        return total
    return min(total, float(limit)) if limit.isdigit() else total


def check_fits(found: Estimate, key: str, value: object, force: bool, memory: float | None = None) -> None:
    """CaseError under `key` (the option or case key that set the grid) when `found` needs more memory than the
    machine has, unless `force`."""
    available = machine_memory() if memory is None else memory
    if found.memory > available and not force:
        raise CaseError(key, value, f"a run that fits this machine's memory ({found.text()}; this machine has "
                                    f"{available / 1e9:.1f} GB): a coarser grid, fewer worker processes, or --force")


def _nodes(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> int:
    domain = solution_domain(scaling_for(point, lubricant), settings)
    return domain.nx * domain.ny


def _duration(seconds: float) -> str:
    if seconds < 60:
        return f"{seconds:.0f} s"
    if seconds < 3600:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"
