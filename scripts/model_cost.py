"""What each cheaper model of the accuracy target saves: the CPU time of a point's solve (without its error check) in
the case's model against thermal `reduced`, 7 layers and Newtonian, interleaved per repeat, medians of the ratios
(TUNING.accuracy_saving_*, docs/tuning.md; the target runs a model check only where the saving can pay for it).

    python scripts/model_cost.py [--case cases/facegear_110.yaml] [--points S1,S3] [--grid 257] [--repeats 3]
"""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path
import statistics
import time

from facegear_tehl.accuracy_target import CHEAPER
from facegear_tehl.case import load_case
from facegear_tehl.ehl.staged import UNBOUNDED
from facegear_tehl.parallel import SolveTask
from facegear_tehl.points import contact_analysis
from facegear_tehl.settings import ThermalMode

ROOT = Path(__file__).resolve().parent.parent


def cpu_seconds(task: SolveTask) -> tuple[float, bool]:
    """CPU time (s, this process) of the task's solve without its error check, and whether it converged."""
    clock = time.process_time()
    solution = UNBOUNDED(task.point, task.lubricant, task.settings)
    return time.process_time() - clock, solution.converged


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", type=Path, default=ROOT / "cases" / "facegear_110.yaml")
    parser.add_argument("--points", default="S1,S3")
    parser.add_argument("--grid", type=int, default=None, help="nodes along x asked (default: the case's)")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    case = load_case(args.case)
    settings = case.solver if args.grid is None else replace(case.solver, grid=args.grid,
                                                             grid_y=(case.solver.nodes_y - 1) * (args.grid - 1)
                                                             // (case.solver.grid - 1) + 1)
    if settings.thermal is ThermalMode.AUTO:
        settings = replace(settings, thermal=ThermalMode.FULL)
    wanted = args.points.split(",")
    print("| point | grid | model | CPU s (median) | over the case's model | converged |")
    print("|---|---|---|---|---|---|")
    for point in (p for p in contact_analysis(case).points if p.name in wanted):
        base = SolveTask(point, case.lubricant, settings)
        models = {"case": base} | {c.what: c.apply(base) for c in CHEAPER if c.applies(base)}
        times: dict[str, list[float]] = {name: [] for name in models}
        ratios: dict[str, list[float]] = {name: [] for name in models}
        converged = dict.fromkeys(models, True)
        cpu_seconds(base)  # kernels loaded before the first timed solve
        for _ in range(args.repeats):  # interleaved: each repeat solves every model once
            for name, task in models.items():
                seconds, ok = cpu_seconds(task)
                times[name].append(seconds)
                converged[name] = converged[name] and ok
            ratios = {name: ratios[name] + [times[name][-1] / times["case"][-1]] for name in models}
        for name in models:
            print(f"| {point.name} | {settings.grid} x {settings.nodes_y} | {name} | "
                  f"{statistics.median(times[name]):.2f} | {statistics.median(ratios[name]):.2f} | "
                  f"{converged[name]} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
