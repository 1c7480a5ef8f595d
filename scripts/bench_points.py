"""Per-point cost and results of a gear case, for before/after comparisons of the solver: each point solved in
turn in one process (one BLAS thread, kernels loaded first, as `tehl run --jobs 1` solves it), with its outer
iterations, V-cycles, work units, energy-equation column sweeps (the finest grid's sweeps count 1, a coarser grid's
its share of the nodes), CPU time (time.process_time), of which the error bound's check solve
(error_bounds.y_estimates), and h_c, h_min, dT_max, mu, energy balance and their error estimates.

    python scripts/bench_points.py [CASE] [--points S1 S3 | --count 41] [--thermal full] [--rheology ree_eyring]
                                   [--save now.json] [--compare before.json]

--save writes the rows as JSON; --compare prints each quantity as `before -> now` from a saved file and, for
h_c, h_min, dT_max and mu, the change against the point's own error estimate.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
from pathlib import Path
import time

from threadpoolctl import threadpool_limits

from facegear_tehl.case import load_case
from facegear_tehl.ehl import energy, error_bounds
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.points import contact_analysis

HERE = Path(__file__).resolve().parents[1]
RESULTS = ("h_c", "h_min", "dT_max", "mu")  # compared against their own error estimates (error_estimate_<name>)
COUNTS = ("thermal_iterations", "iterations", "work_units", "energy_sweeps")
SWEEPS = [0.0]  # column nodes swept by the energy equation in the solve under way


def _counted(sweep_columns):
    """energy.sweep_columns, adding the columns it solves to SWEEPS."""
    def counted(temperature, *args):
        done, change, solved = sweep_columns(temperature, *args)
        SWEEPS[0] += solved
        return done, change, solved
    return counted


energy.sweep_columns = _counted(energy.sweep_columns)  # thermal.py calls it through the module
CHECK_CPU = [0.0]  # CPU s of the error bound's check solves in the solve under way


def _timed(y_estimates):
    """error_bounds.y_estimates, adding its CPU time to CHECK_CPU."""
    def timed(*args, **kwargs):
        start = time.process_time()
        try:
            return y_estimates(*args, **kwargs)
        finally:
            CHECK_CPU[0] += time.process_time() - start
    return timed


error_bounds.y_estimates = _timed(error_bounds.y_estimates)  # with_error_bounds calls it through the module


def solve_points(case_path: Path, names: list[str] | None, count: int | None, thermal: str | None,
                 rheology: str | None) -> list[dict]:
    """One row per point: outcome, counts, CPU s and results."""
    case = load_case(case_path)
    if count is not None:
        case = dataclasses.replace(case, gear=dataclasses.replace(case.gear, points=count))
    settings = case.solver if thermal is None else dataclasses.replace(case.solver, thermal=thermal)
    lubricant = case.lubricant if rheology is None else dataclasses.replace(case.lubricant, rheology=rheology)
    points = [p for p in contact_analysis(case).points if names is None or p.name in names]
    rows = []
    with threadpool_limits(limits=1):
        solve_point(points[0], lubricant, dataclasses.replace(settings, grid=33, grid_y=None))  # load the kernels
        for point in points:
            SWEEPS[0] = CHECK_CPU[0] = 0.0
            start = time.process_time()
            solution = solve_point(point, lubricant, settings)
            cpu = time.process_time() - start
            row = {"point": point.name, "outcome": solution.outcome.value, "cpu": cpu, "check_cpu": CHECK_CPU[0],
                   "energy_sweeps": SWEEPS[0] / (solution.scalar("grid") * solution.scalar("grid_y"))}
            for key in (*COUNTS[:-1], *RESULTS, "energy_balance_error", *(f"error_estimate_{k}" for k in RESULTS)):
                row[key] = solution.scalars[key][0] if key in solution.scalars else math.nan
            rows.append(row)
            print(json.dumps(row), flush=True)
    return rows


def _cell(key: str, value: float) -> str:
    if key in COUNTS:
        return f"{value:.0f}" if math.isfinite(value) else "–"
    if key in ("h_c", "h_min"):
        return f"{value * 1e6:.5f}"
    if key == "dT_max":
        return f"{value:.2f}"
    if key in ("cpu", "check_cpu"):
        return f"{value:.2f}"
    return f"{value:.3g}" if key == "energy_balance_error" else f"{value:.5f}"


COLUMNS = (("outcome", "outcome"), ("thermal_iterations", "outer iterations"), ("iterations", "V-cycles"),
           ("work_units", "work units"), ("energy_sweeps", "energy sweeps"), ("cpu", "CPU s"),
           ("check_cpu", "of which check"), ("h_c", "h_c µm"), ("h_min", "h_min µm"),
           ("dT_max", "ΔT_max K"), ("mu", "μ"), ("energy_balance_error", "energy balance error"))


def print_table(rows: list[dict], before: list[dict] | None) -> None:
    """Markdown table; with `before`, `before -> now` per cell and the largest change of each result against
    its error estimate."""
    old = {r["point"]: r for r in before or []}
    print("\n| point | " + " | ".join(title for _, title in COLUMNS) + " |")
    print("|---|" + "---|" * len(COLUMNS))
    for row in rows:
        cells = []
        for key, _ in COLUMNS:
            now = row[key] if key == "outcome" else _cell(key, row[key])
            if row["point"] in old:
                then = old[row["point"]].get(key, math.nan)
                now = f"{then if key == 'outcome' else _cell(key, then)} → {now}"
            cells.append(now)
        print(f"| {row['point']} | " + " | ".join(cells) + " |")
    for key in ("cpu", "check_cpu", "thermal_iterations", "iterations", "work_units", "energy_sweeps"):
        total = sum(r[key] for r in rows if math.isfinite(r[key]))
        then = sum(old[r["point"]].get(key, math.nan) for r in rows if r["point"] in old
                   and math.isfinite(old[r["point"]].get(key, math.nan)))
        print(f"\nsum of {key}: {f'{then:.1f} -> ' if old else ''}{total:.1f}", end="")
    print()
    if not old:
        return
    for key in RESULTS:
        ratios = []
        for row in rows:
            if row["point"] not in old:
                continue
            then, estimate = old[row["point"]][key], abs(old[row["point"]][f"error_estimate_{key}"])
            change = abs(row[key] - then) / abs(then) if then else math.nan
            ratios.append((change / estimate if estimate else math.inf, change, row["point"]))
        worst = max((r for r in ratios if math.isfinite(r[1])), default=None)
        if worst:
            print(f"{key}: largest relative change {worst[1]:.2e} at {worst[2]} ({worst[0]:.2f} of its error estimate)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", nargs="?", default=str(HERE / "cases" / "facegear_110.yaml"))
    parser.add_argument("--points", nargs="*", help="point names (default: all of the case)")
    parser.add_argument("--count", type=int, help="gear.points: N points along the path instead of the case's")
    parser.add_argument("--thermal", help="solver.thermal instead of the case's")
    parser.add_argument("--rheology", help="lubricant.rheology instead of the case's")
    parser.add_argument("--save", type=Path, help="write the rows as JSON")
    parser.add_argument("--compare", type=Path, help="rows saved by --save to print against")
    args = parser.parse_args()
    rows = solve_points(Path(args.case), args.points, args.count, args.thermal, args.rheology)
    if args.save:
        args.save.write_text(json.dumps(rows, indent=1))
    print_table(rows, json.loads(args.compare.read_text()) if args.compare else None)


if __name__ == "__main__":
    main()
