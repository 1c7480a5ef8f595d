"""Random face gear designs (facegear_tehl/suites/gear_designs.py: their ranges) through the whole chain: what a
designer trying new gears meets (issue 14).

A design the case checks reject (e.g. a contact path reaching into the undercut zone) counts as rejected, with the
check's message: `tehl validate` would say the same. The others are solved with `tehl run`'s runner on the grid
asked (default: the quick 65 x 17 of `tehl run --grid 65`) and their five points tallied by outcome.

    python scripts/gear_designs.py [--designs 40] [--seed 1] [--grid 65] [--grid-y 17] [--jobs 2]

Prints one row per design (its gear, speed, torque, the largest p_h and a/b, each point's outcome as a letter:
c converged, n not converged, d diverged, f film closed, x failed) and a summary. Exit code 1 if a point of an
accepted design did not converge.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from pathlib import Path
import sys
import time

from facegear_tehl.case import parse_case
from facegear_tehl.schema import CaseError, CaseErrors
from facegear_tehl.solution import Outcome
from facegear_tehl.suites.gear_designs import Design, random_designs
from facegear_tehl.tables import format_table

CASE = Path(__file__).resolve().parents[1] / "cases" / "facegear_110.yaml"
LETTERS = {Outcome.CONVERGED: "c", Outcome.NOT_CONVERGED: "n", Outcome.DIVERGED: "d", Outcome.FILM_CLOSED: "f",
           Outcome.FAILED: "x"}



def solve_design(design: Design, grid: int, grid_y: int, jobs: int) -> list[str]:
    """The table row of one design: rejected by the case checks (their message), or its points' outcomes."""
    from facegear_tehl.run import run_case

    head = [str(design.index), f"{design.pinion_teeth}/{design.shaper_teeth}/{design.face_gear_teeth}",
            f"{design.module * 1e3:.2f}", f"{design.shaft_angle:.0f}", f"{design.pressure_angle:.1f}",
            f"{design.pitch_speed:.1f}", f"{design.pinion_torque:.4g}"]
    try:
        case = parse_case(design.case_text(CASE.read_text(), grid, grid_y), name=f"design{design.index}")
    except (CaseError, CaseErrors) as error:
        return head + ["-", "-", "rejected", "-", str(error).splitlines()[0]]
    start = time.perf_counter()
    run = run_case(case, jobs=jobs)
    p_h = max(p.scalar("p_hertz") for p in run.points) / 1e6
    ab = max(p.scalar("a") / p.scalar("b") for p in run.points)
    outcomes = "".join(LETTERS[p.outcome] for p in run.points)
    failed = "; ".join(f"{p.name}: {p.message}" for p in run.points if not p.converged)
    return head + [f"{p_h:.0f}", f"{ab:.0f}", outcomes, f"{time.perf_counter() - start:.1f}", failed[:160]]


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=40, help="number of random designs (default 40)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the draw (default 1)")
    parser.add_argument("--grid", type=int, default=65, help="nodes along x (default 65, the quick grid)")
    parser.add_argument("--grid-y", type=int, default=17, help="nodes along y (default 17)")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes per design (default 1)")
    args = parser.parse_args(argv)
    rows = []
    for design in random_designs(args.designs, args.seed):
        rows.append(solve_design(design, args.grid, args.grid_y, args.jobs))
        print(" ".join(rows[-1][:10]), file=sys.stderr, flush=True)
    headers = ["design", "N1/Ns/N2", "m mm", "shaft deg", "alpha deg", "v m/s", "T N m", "p_h max MPa",
               "a/b max", "points", "wall s", "why not converged"]
    print(format_table(headers, rows))
    accepted = [r for r in rows if r[9] != "rejected"]
    letters = "".join(r[9] for r in accepted)
    print(f"\n{len(rows)} designs: {len(rows) - len(accepted)} rejected by the case checks, {len(accepted)} solved "
          f"({len(letters)} points: " + ", ".join(f"{letters.count(v)} {k.value}" for k, v in LETTERS.items()
                                                  if letters.count(v)) + ")")
    return 0 if all(set(r[9]) <= {"c"} for r in accepted) else 1


if __name__ == "__main__":
    sys.exit(main())
