"""What seeding a finer grid from the same point's coarser converged solve (ehl/seeded.SeededRefinement, the accuracy
target's refinement) costs and changes: per point, the coarser grid solved once, then the finer grid seeded from it
and from the cold start (ehl/staged.solve_point), interleaved per repeat; CPU time of each solve with its error check
(this process), the ratio seeded / cold per point and its median, and each figure's difference seeded - cold against
the cold solve's own error bound, and each solve's x-estimate, reference grid's iteration error, own iteration error
and bound (docs/accuracy.md, the accuracy target).

    python scripts/seeded_refinement.py [--case cases/facegear_110.yaml] [--points S1,S2,S3,S4,S5]
        [--coarse 129x33] [--fine 257x65] [--repeats 1]
"""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path
import statistics
import time

from facegear_tehl.case import load_case
from facegear_tehl.ehl.seeded import SeededRefinement
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.record import Reason, Stage
from facegear_tehl.solution import PointSolution

ROOT = Path(__file__).resolve().parent.parent
FIGURES = ("h_c", "h_min", "dT_max", "mu")


def grid(text: str) -> tuple[int, int]:
    nx, ny = text.lower().split("x")
    return int(nx), int(ny)


def timed(solve, *args) -> tuple[PointSolution, float]:
    clock = time.process_time()
    solution = solve(*args)
    return solution, time.process_time() - clock


def how_started(solution: PointSolution) -> str:
    """seeded, or cold after a failed seeded start, or cold."""
    record = solution.record
    if record is None or not record.stages:
        return "?"
    if any(r.reason is Reason.SEEDED_START_FAILED for r in record.retries):
        return "cold after the seed failed"
    return "seeded" if record.stages[0].stage is Stage.SEEDED else "cold"


def shares(seeded: PointSolution, cold: PointSolution) -> str:
    """|seeded - cold| / cold of each figure over the cold solve's bound of it ("-" where it has none)."""
    words = []
    for name in FIGURES:
        bound = cold.scalars.get(f"error_bound_{name}", (float("nan"), ""))[0]
        difference = abs(seeded.scalar(name) / cold.scalar(name) - 1.0)
        words.append(f"{name} {difference:.1e}/{bound:.1e}")
    return ", ".join(words)


def bound_words(solution: PointSolution) -> str:
    """Each figure's x-estimate, the iteration error of the grid it compares with (error_bounds.reference_error), the
    solve's own iteration error and its bound, in %: where the seeded solve's bound differs from the cold one's."""
    from facegear_tehl.ehl.error_bounds import reference_error

    def percent(key: str) -> str:
        value = solution.scalars.get(key, (float("nan"), ""))[0]
        return f"{100 * value:.2f}"

    return ", ".join(f"{name} e_x {percent(f'error_estimate_{name}')} "
                     f"e_ref {100 * reference_error(solution, name):.2f} e_it {percent(f'iteration_error_{name}')} "
                     f"bound {percent(f'error_bound_{name}')}" for name in FIGURES if name in solution.scalars)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", type=Path, default=ROOT / "cases" / "facegear_110.yaml")
    parser.add_argument("--points", default="S1,S2,S3,S4,S5")
    parser.add_argument("--coarse", type=grid, default=(129, 33))
    parser.add_argument("--fine", type=grid, default=(257, 65))
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args(argv)
    case = load_case(args.case)
    coarse = replace(case.solver, grid=args.coarse[0], grid_y=args.coarse[1])
    fine = replace(case.solver, grid=args.fine[0], grid_y=args.fine[1])
    ratios = []
    for point in select_points(contact_analysis(case).points, args.points.split(",")):
        for _ in range(args.repeats):
            refining = SeededRefinement()
            first, _ = timed(refining, point, case.lubricant, coarse)
            seeded, seeded_cpu = timed(refining, point, case.lubricant, fine)
            cold, cold_cpu = timed(solve_point, point, case.lubricant, fine)
            ratios.append(seeded_cpu / cold_cpu)
            print(f"{point.name}: {args.fine[0]} x {args.fine[1]} seeded ({how_started(seeded)}, "
                  f"{seeded.outcome.value}) {seeded_cpu:.1f} s, cold ({cold.outcome.value}) {cold_cpu:.1f} s CPU, "
                  f"ratio {ratios[-1]:.2f}; coarser {first.outcome.value}", flush=True)
            if seeded.converged and cold.converged:
                print(f"  |seeded - cold| / cold against the cold bound: {shares(seeded, cold)}", flush=True)
                print(f"  seeded (%): {bound_words(seeded)}\n  cold (%): {bound_words(cold)}", flush=True)
    print(f"median ratio seeded / cold CPU: {statistics.median(ratios):.2f} over {len(ratios)} solves")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
