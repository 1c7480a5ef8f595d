"""Calibration of the error bounds: every reported bound against the true error of the same point (the points,
grids and references: facegear_tehl/suites/calibration.py). Prints one line per point and figure, then the table
per figure (share bounded, unresolved, understated more than 2x); docs/accuracy.md (error bounds) holds its output.
Exit code 1 if a resolved figure's bound is below its true error by more than 2x.

    python scripts/calibrate_errors.py [--quick] [--only PATTERN] [--jobs N] [--designs 10] [--envelope-grids 1]
                                       [--record FILE.jsonl] [--summary-of FILE.jsonl ...]

--quick: the isothermal envelope core at 2 m/s and four thermal core contacts on 129 x 33 and the gear cases' S3 on
65 x 17 and 129 x 33; without it 126 points (the gear cases' S1-S5 on 65 x 17 and 129 x 33, nine random designs'
S3 on 129 x 33, the envelope's 97 contacts on 129 x 33), hours on a loaded machine. --only: the points whose name
matches any of the comma-separated shell patterns (e.g. 'facegear*,design*'); --jobs: points solved side by side in
worker processes; --record: each point's comparisons appended to a JSON-lines file as they finish (a run stopped
early keeps them); --summary-of: the table of recorded files, solving nothing.
"""

from __future__ import annotations

import argparse
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict
import fnmatch
from functools import partial
import json
from pathlib import Path
import sys
import time

from facegear_tehl.ehl.staged import STAGED, UNBOUNDED
from facegear_tehl.suites.calibration import Comparison, calibration_points, compare, point_lines, summary

ROOT = Path(__file__).resolve().parent.parent


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="the subset that runs in a few minutes")
    parser.add_argument("--designs", type=int, default=10, help="random face gear designs (S3 of each)")
    parser.add_argument("--envelope-grids", type=int, default=1, help="1: the envelope on 129 x 33; 2: also 257 x 65")
    parser.add_argument("--only", default="*", help="comma-separated shell patterns of the point names to run")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes")
    parser.add_argument("--record", type=Path, help="JSON-lines file the comparisons are appended to")
    parser.add_argument("--summary-of", type=Path, nargs="+", help="recorded files to summarise (nothing solved)")
    args = parser.parse_args(argv)
    if args.summary_of:
        comparisons = [Comparison(**json.loads(line)) for path in args.summary_of
                       for line in path.read_text().splitlines() if line.strip()]
        print(summary(comparisons))
        print(f"\n{len({c.name for c in comparisons})} points compared")
        return 1 if any(c.understated for c in comparisons) else 0
    compared = partial(compare, bounded=STAGED, reference=UNBOUNDED)
    comparisons, start, unsolved = [], time.perf_counter(), 0
    patterns = args.only.split(",")
    points = [p for p in calibration_points(args.quick, ROOT / "cases", args.designs, args.envelope_grids)
              if any(fnmatch.fnmatch(p.name, pattern) for pattern in patterns)]
    with ProcessPoolExecutor(args.jobs) as pool:
        for index, (point, found) in enumerate(zip(points, pool.map(compared, points)), 1):
            print(f"[{index}/{len(points)}] {point.name}: {len(found)} figures", file=sys.stderr, flush=True)
            print("\n".join(point_lines(found)), flush=True)
            if args.record is not None:
                with args.record.open("a") as record:
                    record.writelines(json.dumps(asdict(c)) + "\n" for c in found)
            comparisons += found
            unsolved += not found
    print()
    print(summary(comparisons))
    print(f"\n{len(points)} points ({unsolved} without a comparison: the point or its reference did not converge), "
          f"{time.perf_counter() - start:.0f} s")
    return 1 if any(c.understated for c in comparisons) else 0


if __name__ == "__main__":
    sys.exit(main())
