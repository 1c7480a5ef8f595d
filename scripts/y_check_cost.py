"""The y-estimate of the error bounds two ways, and their cost: from the coarse stage and a check with half its rows
(error_bounds.y_estimates, what every solve does) against the check with half the finest grid's rows (the full
y-check). Under the additive error model f = f* + C_x h_x^p + C_y h_y^p both give the same e_y; the table shows how
far they differ and the time of each check over the point's own solve (docs/accuracy.md, error bounds).

    python scripts/y_check_cost.py [--case cases/facegear_110.yaml] [--points S1,S3] [--grid 257] [--no-outlet]

The full check solves without outlet patches; where the point's own solve adds them (S2 and S4 of the default
case), --no-outlet makes both routes compare uniform grids.
"""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path
import statistics
import sys
import time

from facegear_tehl.case import load_case
from facegear_tehl.ehl.error_bounds import y_estimates
from facegear_tehl.ehl.staged import STAGED, UNBOUNDED
from facegear_tehl.points import contact_analysis
from facegear_tehl.settings import OutletRefinement

ROOT = Path(__file__).resolve().parent.parent


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", type=Path, default=ROOT / "cases" / "facegear_110.yaml")
    parser.add_argument("--points", default="S1,S2,S3,S4,S5")
    parser.add_argument("--grid", type=int, default=None, help="nodes along x asked (default: the case's)")
    parser.add_argument("--no-outlet", action="store_true",
                        help="solve without outlet patches: the full check then compares uniform grids alike")
    args = parser.parse_args(argv)
    case = load_case(args.case)
    settings = case.solver if args.grid is None else replace(case.solver, grid=args.grid,
                                                             grid_y=(case.solver.nodes_y - 1) * args.grid
                                                             // case.solver.grid + 1)
    if args.no_outlet:
        settings = replace(settings, outlet_refinement=OutletRefinement.NEVER)
    wanted = args.points.split(",")
    print("| point | grid | figure | e_y coarse-stage route % | e_y full check % | solve s | check s (route) | "
          "check s (full) |")
    print("|---|---|---|---|---|---|---|---|")
    ratios, full_ratios = [], []
    for point in (p for p in contact_analysis(case).points if p.name in wanted):
        solution = STAGED(point, case.lubricant, settings)
        if not solution.converged:
            print(f"| {point.name} | - | {solution.outcome.value} | | | | | |")
            continue
        check = solution.scalar("error_check_time")
        own = solution.scalar("wall_time")
        clock = time.perf_counter()
        full = y_estimates(solution, point, case.lubricant, settings, UNBOUNDED)
        full_time = time.perf_counter() - clock
        ratios.append(check / own)
        full_ratios.append(full_time / own)
        shape = f"{int(solution.scalar('grid'))}x{int(solution.scalar('grid_y'))}"
        for name, value in full.items():
            route = solution.scalars.get(f"error_estimate_y_{name}", (float("nan"), "1"))[0]
            print(f"| {point.name} | {shape} | {name} | {100 * route:.3f} | {100 * value:.3f} | {own:.1f} | "
                  f"{check:.1f} | {full_time:.1f} |", flush=True)
    if ratios:
        print(f"\nmedian check time over the solve's own: {statistics.median(ratios):.2f} (coarse-stage route), "
              f"{statistics.median(full_ratios):.2f} (full y-check), {len(ratios)} points")
    return 0


if __name__ == "__main__":
    sys.exit(main())
