"""Hard-case suite: solve every case of cases/hard/, record whether and how each point converged, write each
result file and check that it holds no NaN or Inf; print a markdown table (docs/benchmarks.md "Hard cases").

Per point: converged, cycles (V-cycles on the finest grid), thermal outer iterations, solve wall time, h_min,
p_max (and p_h), the file check, and below the table the solver's message for every point that did not
converge. Exit code 1 if a point failed with an error or ended without a message, or if a file holds NaN/Inf
or the writer refused to write one.

    python scripts/hard_cases.py [--cases heavy_m1000_l10,skew_60] [--grid N] [--jobs N] [-o DIR]
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from pathlib import Path
import sys
import tempfile
import time

from facegear_tehl.case import load_case
from facegear_tehl.results import NonFiniteError, non_finite_entries, write_result
from facegear_tehl.run import run_case
from facegear_tehl.solution import PointSolution

HARD_CASES = Path(__file__).resolve().parents[1] / "cases" / "hard"


@dataclass(frozen=True)
class Row:
    """One solved point of the suite."""

    case: str
    solution: PointSolution
    failed: bool  # the solve raised an error
    file_check: str  # 'clean', or what the file check found


def run_suite(paths: list[Path], folder: Path, grid: int | None, jobs: int) -> tuple[list[Row], float]:
    """Solve and write every case; returns the rows and the total wall time, s."""
    rows: list[Row] = []
    start = time.perf_counter()
    for path in paths:
        case = load_case(path)
        print(f"{case.name} ...", file=sys.stderr, flush=True)
        run = run_case(case, grid=grid, jobs=jobs)
        try:
            target = write_result(run, folder / f"{case.name}.h5")
            bad = non_finite_entries(target)
            file_check = "clean" if not bad else "NaN/Inf in the file: " + "; ".join(bad)
        except NonFiniteError as exc:  # the writer refuses the run: no file (tehl run exits 1)
            file_check = f"not written: {exc}"
        rows += [Row(case.name, p, p.name in run.failed, file_check) for p in run.points]
    return rows, time.perf_counter() - start


def _value(solution: PointSolution, key: str, factor: float, fmt: str) -> str:
    return fmt.format(solution.scalar(key) * factor) if key in solution.scalars else "–"


def markdown_table(rows: list[Row]) -> str:
    """The suite table: one row per solved point."""
    lines = [
        "| case | point | converged | cycles | thermal iterations | wall time s | h_min nm | p_max GPa | p_h GPa"
        " | file |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for row in rows:
        s = row.solution
        converged = "yes" if s.converged else ("failed" if row.failed else "no")
        cells = [
            row.case,
            s.name,
            converged,
            _value(s, "iterations", 1.0, "{:.0f}"),
            _value(s, "thermal_iterations", 1.0, "{:.0f}"),
            _value(s, "wall_time", 1.0, "{:.1f}"),
            _value(s, "h_min", 1e9, "{:.4g}"),
            _value(s, "p_max", 1e-9, "{:.3f}"),
            _value(s, "p_hertz", 1e-9, "{:.3f}"),
            "**" + row.file_check.split(":")[0] + "**" if row.file_check != "clean" else "clean",
        ]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def problems(rows: list[Row]) -> list[str]:
    """What the suite must never see: an error during a solve, a point ending without a message, NaN/Inf."""
    found = []
    for row in rows:
        where = f"{row.case}/{row.solution.name}"
        if row.failed:
            found.append(f"{where}: the solve raised an error: {row.solution.message}")
        elif not row.solution.converged and not row.solution.message:
            found.append(f"{where}: not converged, without a message")
        if row.file_check != "clean":
            found.append(f"{where}: {row.file_check}")
    return found


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", help="comma-separated case names (file stems in cases/hard/); default all")
    parser.add_argument("--grid", type=int, help="finest grid for every case (default: each case's own)")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes per case (default 1: wall times "
                        "of one point at a time)")
    parser.add_argument("-o", "--output", type=Path, help="keep the result files in this folder")
    args = parser.parse_args()
    paths = sorted(HARD_CASES.glob("*.yaml"))
    if args.cases:
        names = args.cases.split(",")
        paths = [HARD_CASES / f"{name}.yaml" for name in names]
    with tempfile.TemporaryDirectory(prefix="tehl_hard_") as scratch:
        folder = args.output or Path(scratch)
        folder.mkdir(parents=True, exist_ok=True)
        rows, total = run_suite(paths, folder, args.grid, args.jobs)
    print(markdown_table(rows))
    print(f"\n{len(paths)} cases, {len(rows)} points, {sum(r.solution.converged for r in rows)} converged, "
          f"{total:.0f} s in all")
    for row in rows:
        if not row.solution.converged:
            print(f"- {row.case}/{row.solution.name}: {row.solution.message}")
    found = problems(rows)
    for line in found:
        print(f"PROBLEM {line}", file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
