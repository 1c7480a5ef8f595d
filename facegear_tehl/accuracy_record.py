"""What the accuracy target did for one point (`solver.accuracy`, accuracy_target.py): the bound each asked figure
reached, each choice of grid and model with its reason, every solve it ran and what they cost. Plain data, written
to the result file as /points/<name>/accuracy (results.py) and printed by `tehl info`."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
import math


class Verdict(str, Enum):
    """How a figure ended against the target: its bound within it (met), above it (not met: a grid or time cap came
    first), or no bound the solver can give (unresolved: p_max, or a figure without an estimate)."""

    MET = "met"
    NOT_MET = "not met"
    UNRESOLVED = "unresolved"

    def __str__(self) -> str:
        return self.value


@dataclass(frozen=True)
class FigureBound:
    """One asked figure at the end: its relative bound (grid and the cheaper model's measured effect; NaN where
    unresolved), the model's share of it, and the verdict."""

    name: str
    bound: float
    model_effect: float
    verdict: Verdict


@dataclass(frozen=True)
class Choice:
    """One decision: what was chosen (`what`: grid, thermal, thermal_layers, rheology), the value and why."""

    what: str
    chosen: str
    reason: str


@dataclass(frozen=True)
class SolveStep:
    """One solve the target ran for the point: grid asked, model, why (start, model check, refine x|y|xy), its
    outcome, and its wall and CPU time with its error check's (s; the time budget reads the CPU time)."""

    grid: str
    model: str
    purpose: str
    outcome: str
    seconds: float
    cpu_seconds: float


@dataclass(frozen=True)
class AccuracyRecord:
    """The accuracy target of one point: the target (relative), the figures' bounds, the choices, the solves, why the
    refinement stopped, and the cost: wall and CPU time of all solves (s) and the reported grid's nodes against the
    case's."""

    target: float
    figures: tuple[FigureBound, ...]
    choices: tuple[Choice, ...]
    steps: tuple[SolveStep, ...]
    stop: str
    nodes: int  # nodes of the reported solution (as solved)
    case_nodes: int  # nodes the case's own grid is solved on (the lengthened inlet's), for the cost comparison

    @property
    def wall_time(self) -> float:
        return sum(step.seconds for step in self.steps)

    @property
    def cpu_time(self) -> float:
        return sum(step.cpu_seconds for step in self.steps)


def accuracy_to_dict(record: AccuracyRecord) -> dict[str, object]:
    """The record as plain data (enums by their words; an unresolved bound as None), for the file and JSON."""
    return {
        "target": record.target,
        "figures": [{"name": f.name, "bound": None if math.isnan(f.bound) else f.bound,
                     "model_effect": f.model_effect, "verdict": f.verdict.value} for f in record.figures],
        "choices": [{"what": c.what, "chosen": c.chosen, "reason": c.reason} for c in record.choices],
        "steps": [{"grid": s.grid, "model": s.model, "purpose": s.purpose, "outcome": s.outcome,
                   "seconds": s.seconds, "cpu_seconds": s.cpu_seconds} for s in record.steps],
        "stop": record.stop,
        "nodes": record.nodes,
        "case_nodes": record.case_nodes,
    }


def accuracy_from_dict(data: dict[str, object]) -> AccuracyRecord:
    """The record from `accuracy_to_dict`'s plain data (a step without `cpu_seconds`, written before it was kept:
    its wall time)."""
    figures = tuple(FigureBound(str(f["name"]), math.nan if f["bound"] is None else float(f["bound"]),
                                float(f["model_effect"]), Verdict(f["verdict"])) for f in data["figures"])
    choices = tuple(Choice(str(c["what"]), str(c["chosen"]), str(c["reason"])) for c in data["choices"])
    steps = tuple(SolveStep(str(s["grid"]), str(s["model"]), str(s["purpose"]), str(s["outcome"]),
                            float(s["seconds"]), float(s.get("cpu_seconds", s["seconds"]))) for s in data["steps"])
    return AccuracyRecord(float(data["target"]), figures, choices, steps, str(data["stop"]), int(data["nodes"]),
                          int(data["case_nodes"]))


def accuracy_lines(name: str, record: AccuracyRecord) -> list[str]:
    """The record of point `name` for `tehl info`: target and stop, each figure's bound, the choices, the solves and
    the cost against the case's grid."""
    lines = [f"accuracy of {name}: target {100 * record.target:g} %, {record.stop}"]
    for figure in record.figures:
        bound = "no bound" if math.isnan(figure.bound) else f"bound {100 * figure.bound:.2g} %"
        model = f" (model {100 * figure.model_effect:.2g} %)" if figure.model_effect > 0.0 else ""
        lines.append(f"  figure   {figure.name}: {bound}{model}, {figure.verdict.value}")
    lines += [f"  chose    {c.what} {c.chosen}: {c.reason}" for c in record.choices]
    lines += [f"  solved   {s.grid}, {s.model}, {s.purpose}: {s.outcome}, {s.seconds:.2f} s ({s.cpu_seconds:.2f} s "
              "CPU)" for s in record.steps]
    lines.append(f"  cost     {len(record.steps)} solves, {record.wall_time:.1f} s ({record.cpu_time:.1f} s CPU); "
                 f"reported grid {record.nodes} "
                 f"nodes, the case's grid {record.case_nodes} ({record.nodes / record.case_nodes:.2g}x)")
    return lines


def accuracy_summary(name: str, record: AccuracyRecord) -> str:
    """One line for point `name`: its grid, each figure's bound and verdict, and the cost."""
    grid = next((c.chosen for c in record.choices if c.what == "grid"), "")
    figures = ", ".join(f"{f.name} " + ("unresolved" if math.isnan(f.bound) else
                                        f"{100 * f.bound:.2g} % {f.verdict.value}") for f in record.figures)
    cost = f"{record.wall_time:.1f} s ({record.cpu_time:.1f} s CPU)"
    return f"{name}: {grid}; {figures}; {len(record.steps)} solves, {cost}"
