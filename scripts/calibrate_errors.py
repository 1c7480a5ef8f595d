"""Calibration of the error bounds: every reported bound against the true error of the same point (the points,
grids and references: facegear_tehl/suites/calibration.py). Prints one line per point and figure, then the table
per figure (share bounded, unresolved, understated more than 2x); docs/accuracy.md (error bounds) holds its output.
Exit code 1 if a resolved figure's bound is below its true error by more than 2x.

    python scripts/calibrate_errors.py [--quick] [--only PATTERN] [--jobs N] [--designs 10]
                                       [--case cases/facegear_110.yaml]

--quick: the isothermal envelope core at 2 m/s on 129 x 33 and the shipped case's S3 at 65 x 17 and 129 x 33
(a few minutes on one core); without it 222 points, hours. --only: the points whose name matches the shell pattern
(e.g. '*129x33'); --jobs: points solved side by side in worker processes.
"""

from __future__ import annotations

import argparse
from concurrent.futures import ProcessPoolExecutor
import fnmatch
from functools import partial
from pathlib import Path
import sys
import time

from facegear_tehl.ehl.staged import StagedSolver
from facegear_tehl.suites.calibration import calibration_points, compare, point_lines, summary

ROOT = Path(__file__).resolve().parent.parent


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="the subset that runs in a few minutes")
    parser.add_argument("--designs", type=int, default=10, help="random face gear designs (S3 of each)")
    parser.add_argument("--case", type=Path, default=ROOT / "cases" / "facegear_110.yaml", help="the gear case")
    parser.add_argument("--only", default="*", help="shell pattern of the point names to run")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes")
    args = parser.parse_args(argv)
    compared = partial(compare, bounded=StagedSolver(), reference=StagedSolver(bounded=False))
    comparisons, start, unsolved = [], time.perf_counter(), 0
    points = [p for p in calibration_points(args.quick, args.case, args.designs) if fnmatch.fnmatch(p.name, args.only)]
    with ProcessPoolExecutor(args.jobs) as pool:
        for index, (point, found) in enumerate(zip(points, pool.map(compared, points)), 1):
            print(f"[{index}/{len(points)}] {point.name}: {len(found)} figures", file=sys.stderr, flush=True)
            print("\n".join(point_lines(found)), flush=True)
            comparisons += found
            unsolved += not found
    print()
    print(summary(comparisons))
    print(f"\n{len(points)} points ({unsolved} without a comparison: the point or its reference did not converge), "
          f"{time.perf_counter() - start:.0f} s")
    return 1 if any(c.understated for c in comparisons) else 0


if __name__ == "__main__":
    sys.exit(main())
