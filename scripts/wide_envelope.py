"""Wide envelope suite (issue 47): the contacts drawn at random in facegear_tehl/suites/wide_envelope.py, solved as
`tehl run` solves a point (run.solve_refining, grid 257 x 65 as the public envelope) and checked.

Prints one line per contact (outcome, the reason of a failure or the retries the solve took, Moes M, the grid
solved on, h_min, the load error, the energy balance error of a thermal contact, thermal outer iterations,
V-cycles, wall time, the check) as a markdown table, then the counts and the median and worst wall time.
A contact passes when it converged with h_min > 0, its load balanced to LOAD_LIMIT and, thermal, its energy
balance within ENERGY_BALANCE_LIMIT. Exit code 1 if any does not.

    python scripts/wide_envelope.py [--grid 257] [--grid-y 65] [--jobs N] [--only PATTERN[,PATTERN]]
                                    [--thermal-only | --iso-only] [--save DIR] [--list]
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
import csv
import math
from pathlib import Path
import statistics
import sys

from envelope import Row, _cell, _grid, selection_arguments, solve_cases

from facegear_tehl.solution import PointSolution
from facegear_tehl.suites.envelope import ENERGY_BALANCE_LIMIT, check_solution, scalar_or_nan, select
from facegear_tehl.suites.wide_envelope import moes_m, wide_cases

LOAD_LIMIT = 1e-3  # relative load-balance error a converged contact must reach (issue 47's acceptance)

COLUMNS = ("case", "M", "model", "outcome", "grid", "h_min µm", "load err", "energy %", "outer it.", "cycles",
           "wall s", "check", "reason")


def check(solution: PointSolution) -> str:
    """'ok', or what keeps the contact from passing: not converged, the file check (envelope.check_solution:
    finite fields, h_min > 0, the energy balance within 1 %), the load error above LOAD_LIMIT."""
    if not solution.converged:
        return f"not converged ({solution.outcome.value})"
    problems = [] if (found := check_solution(solution)) == "ok" else [found]
    load = scalar_or_nan(solution, "load_error")
    if not abs(load) <= LOAD_LIMIT:
        problems.append(f"load error {load:.2g}")
    return "; ".join(problems) or "ok"


def reason(solution: PointSolution) -> str:
    """The solver's message, and the retries it took (their reasons and actions, from the solve record)."""
    retries = () if solution.record is None else solution.record.retries
    taken = "; ".join(f"{r.reason.value} -> {r.action.value}" for r in retries)
    return " | ".join(part for part in (solution.message, f"retries: {taken}" if taken else "") if part)


def cells(row: Row) -> list[str]:
    s = row.solution
    return [row.case.name, f"{moes_m(row.case):.3g}", row.case.model, s.outcome.value, _grid(s),
            _cell(s, "h_min", 1e6, ".4g"), _cell(s, "load_error", 1.0, ".1e"),
            _cell(s, "energy_balance_error", 100.0, ".2g"), _cell(s, "thermal_iterations", 1.0, ".0f"),
            _cell(s, "iterations", 1.0, ".0f"), _cell(s, "wall_time", 1.0, ".1f"), row.check, reason(s)]


def table(rows: Sequence[Row]) -> str:
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    lines += ["| " + " | ".join(c.replace("|", "/") for c in cells(r)) + " |" for r in rows]
    return "\n".join(lines)


def summary(rows: Sequence[Row], total: float) -> str:
    """Passed counts overall and per model, wall time median and worst."""
    lines = [f"{sum(r.check == 'ok' for r in rows)} of {len(rows)} pass (converged, h_min > 0, load error <= "
             f"{LOAD_LIMIT:g}, thermal energy balance <= {100 * ENERGY_BALANCE_LIMIT:g} %); {total:.0f} s in all"]
    for model in sorted({r.case.model for r in rows}):
        members = [r for r in rows if r.case.model == model]
        lines.append(f"{model}: {sum(r.check == 'ok' for r in members)} of {len(members)}")
    times = sorted((r.wall_time, r.case.name) for r in rows if math.isfinite(r.wall_time))
    if times:
        lines.append(f"wall time per contact: median {statistics.median(t for t, _ in times):.1f} s, "
                     f"worst {times[-1][0]:.1f} s ({times[-1][1]})")
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    selection_arguments(parser)
    parser.add_argument("--save", type=Path, help="write the table as wide_envelope.csv into this folder")
    parser.add_argument("--list", action="store_true", help="list the selected contacts, no solve")
    args = parser.parse_args(argv)
    cases = select(wide_cases(), args.only, True if args.thermal_only else (False if args.iso_only else None))
    if not cases:
        print("no case matches", file=sys.stderr)
        return 2
    if args.list:
        for c in cases:
            print(f"{c.name:<62} M = {moes_m(c):9.3g}  W = {c.point().load:10.4g} N  {c.model}")
        print(f"{len(cases)} contacts")
        return 0
    solved, total, _ = solve_cases(cases, args.grid, args.grid_y, args.jobs)
    rows = [Row(r.case, r.solution, check(r.solution)) for r in solved]
    print(table(rows))
    print()
    print(summary(rows, total))
    if args.save:
        args.save.mkdir(parents=True, exist_ok=True)
        with (args.save / "wide_envelope.csv").open("w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(COLUMNS)
            writer.writerows(cells(r) for r in rows)
    return 0 if all(r.check == "ok" for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
