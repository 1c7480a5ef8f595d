"""Accuracy and cost of the X-refined outlet patch (ehl/patch.py) on the default face gear case, isothermal Newtonian.

Per point, on the case's lengthened domain (ehl/domain.py): the uniform grid the case solves on (N x 65; --grid 257
gives 513 x 65 over X in [-10.5, 1.5] b), the uniform grid of half its X spacing ((2N - 1) x 65) and N x 65 with a
patch of that spacing from each X_a of --starts to the outlet. Printed: h_c, h_min, p_max (dimensionless, the
composite's over both parts), X of p_max, the largest |P - P_fine| over the patch's nodes (for N x 65 its
fourth-order interpolation along X), V-cycles of the finest level (after the full-multigrid start), work units
(sweeps of the (2N - 1) x 65 grid) and CPU seconds (median of --repeat runs, one process).

    python scripts/bench_patch.py [--points S2,S4] [--grid 257] [--starts -0.5,-1.25] [--repeat 3]
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path
import statistics
import time

import numpy as np

from facegear_tehl.case import load_case
from facegear_tehl.ehl import grid
from facegear_tehl.ehl.patch import PatchedSolver
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.points import contact_analysis

CASE = Path(__file__).resolve().parents[1] / "cases" / "facegear_110.yaml"


def solve(point, lubricant, settings, start: float | None):
    """(solver, level, cycles, work units, CPU s) of a uniform solve (start None) or one with a patch from `start`."""
    clock = time.process_time()
    run = PointSolve(point, lubricant, settings)
    below_top = 0
    if start is not None:
        run.solver = PatchedSolver(run.solver.problem, grid.hierarchy_shapes(settings.grid, settings.nodes_y,
                                                                              settings.coarsest_grid),
                                   (start, settings.domain_x[1]), run.solver.relaxation)
        below_top = 1
    index, status = run.start(below_top)
    cycles = run.history.cycles
    if start is not None:
        run.solver.interpolate_up(index + 1)
        index += 1
    status = run.cycle(index, settings.max_cycles)
    if not status.converged:
        raise SystemExit(f"{point.name}: {status.message}")
    return run.solver, run.solver.levels[index], run.history.cycles - cycles, run.solver.work_units, \
        time.process_time() - clock


def figures(solver, level) -> tuple[float, float, float, float]:
    """h_c, h_min, p_max, X of p_max."""
    if isinstance(solver, PatchedSolver):
        s = solver.summary()
        return s.h_c, s.h_min, s.p_max, s.x_p_max
    j, i = np.unravel_index(int(np.argmax(level.pressure)), level.pressure.shape)
    return solver.central_film(level), float(level.film.min()), float(level.pressure[j, i]), float(level.x[i])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", default="S2,S4")
    parser.add_argument("--grid", type=int, default=257, help="the case's solver.grid (lengthened as a run does)")
    parser.add_argument("--starts", default="-0.5,-1.25", help="X_a of the patches, in b")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    case = load_case(CASE).with_grid(args.grid)
    lubricant = dataclasses.replace(case.lubricant, rheology="newtonian")
    asked = dataclasses.replace(case.solver, thermal="off")
    points = {p.name: p for p in contact_analysis(case).points}
    print("| point | grid | h_c | h_min | p_max | X(p_max) | max abs(P - P_fine) | cycles | work units | CPU s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name in args.points.split(","):
        point = points[name]
        domain = PointSolve(point, lubricant, asked).settings  # the lengthened domain and its nodes
        coarse = dataclasses.replace(domain, max_cycles=60)
        fine = dataclasses.replace(coarse, grid=2 * coarse.grid - 1)
        starts = [float(s) for s in args.starts.split(",")]
        runs = [(f"{fine.grid} x {fine.nodes_y}", fine, None), (f"{coarse.grid} x {coarse.nodes_y}", coarse, None)]
        runs += [(f"{coarse.grid} x {coarse.nodes_y} + patch [{s:g}, {coarse.domain_x[1]:.3g}]", coarse, s)
                 for s in starts]
        reference = None
        for label, settings, start in runs:
            timed = [solve(point, lubricant, settings, start) for _ in range(args.repeat)]
            solver, level, cycles, work, _ = timed[-1]
            cpu = statistics.median(t[-1] for t in timed)
            if reference is None:
                reference = level
            if isinstance(solver, PatchedSolver):
                error = np.abs(level.pressure - reference.pressure[:, solver.columns]).max()
            else:  # over the smallest patch's extent
                pressure = level.pressure if level is reference else grid.SEMI_X.prolong_cubic(level.pressure)
                span = reference.x >= max(starts)
                error = np.abs(pressure - reference.pressure)[:, span].max()
            h_c, h_min, p_max, x_max = figures(solver, level)
            print(f"| {name} | {label} | {h_c:.5f} | {h_min:.5f} | {p_max:.4f} | {x_max:.4f} | {error:.4f} | "
                  f"{cycles} | {work:.1f} | {cpu:.2f} |", flush=True)


if __name__ == "__main__":
    main()
