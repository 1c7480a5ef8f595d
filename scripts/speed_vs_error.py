"""Work-precision report: the error of each grid against the Richardson-extrapolated value, vs wall time.

Models:
  circle       the isothermal circular case of Venner & Lubrecht (2000) (Moes M = 20, L = 10, Roelands viscosity,
               Dowson-Higginson density, domain X in [-4.5, 1.5], Y in [-3, 3]);
  S1 newtonian point S1 of cases/facegear_110.yaml, isothermal, with a Newtonian lubricant;
  S1 <mode>    the same point with the case's lubricant (rheology) and each thermal model of --thermal (off,
               reduced, full); a model the solver does not offer is skipped with a message.

For every model and grid: the median wall time of --repeat solves in this process (after a warm-up solve
that loads the Numba kernels; the machine is shared, medians damp its noise), work units, h_c and h_min
(and dT_max and mu where the solver gives them), and each one's relative error against the value
extrapolated from the three finest grids (facegear_tehl.sweep.convergence: observed order, Richardson);
a grid that does not converge ends a model's sequence there (it and the finer grids get no error).
Writes the table as CSV and prints, per model and quantity, the wall time to reach 1 % and 0.1 % error
(interpolated on the log-log curve of error against time; 'not reached' if the finest grid is not there).

    python scripts/speed_vs_error.py [--repeat 3] [--grids 33,65,129,257,513] [--thermal off,reduced,full]
                                     [--thermal-grids 33,65,129,257] [-o speed_vs_error.csv]
"""

from __future__ import annotations

import argparse
import csv
from dataclasses import dataclass, replace
import math
from pathlib import Path
import statistics
import time
from typing import Sequence

from facegear_tehl.case import THERMAL_MODELS, Case, load_case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.scaling import contact_from_moes
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.points import contact_analysis
from facegear_tehl.solution import PointSolution
from facegear_tehl.sweep import QUANTITIES, check_grids, convergence, time_to_reach, with_thermal

CASES = Path(__file__).resolve().parents[1] / "cases"
TARGETS = (0.01, 0.001)
FILM = ("h_c", "h_min")  # plus dT_max and mu when given (p_max, the pressure spike, keeps growing: not a target)


@dataclass(frozen=True)
class Model:
    """A contact to solve on each grid: `case` supplies the solver settings (grid, domain, thermal)."""

    name: str
    point: ContactPoint
    lubricant: Lubricant
    case: Case


def models(thermal_modes: Sequence[str]) -> list[Model]:
    """The circular benchmark, S1 of the face gear case isothermal and Newtonian, then S1 with each thermal
    mode the solver offers."""
    ball = load_case(CASES / "ball_on_disc.yaml")  # the domain and settings of docs/benchmarks.md
    point, lubricant = contact_from_moes(20.0, 10.0, viscosity_model="roelands", density_model="dowson_higginson")
    found = [Model("circle M=20 L=10", point, lubricant, with_thermal(ball, "off"))]
    gear = load_case(CASES / "facegear_110.yaml")
    s1 = contact_analysis(gear).points[0]
    gear = replace(gear, solver=replace(gear.solver, grid_y=None))  # square grids, like the circle
    newtonian = replace(gear.lubricant, rheology="newtonian", eyring_stress=math.inf)
    found.append(Model("S1 newtonian off", s1, newtonian, with_thermal(gear, "off")))
    for mode in thermal_modes:
        if mode not in THERMAL_MODELS:
            print(f"skipped thermal model {mode!r}: not one of {', '.join(THERMAL_MODELS)}")
            continue
        case = with_thermal(gear, mode)
        try:  # the warm-up solve on the coarsest grid: does the solver run this model?
            used = solve(Model("", s1, gear.lubricant, case), case.solver.coarsest_grid).models.get("thermal")
        except Exception as exc:  # a model the solver rejects is reported and skipped, not fatal
            print(f"skipped thermal model {mode!r}: the solver raised {type(exc).__name__}: {exc}")
            continue
        if used != mode:
            print(f"skipped thermal model {mode!r}: the solver ran {used!r} instead")
            continue
        found.append(Model(f"S1 {gear.lubricant.rheology} {mode}", s1, gear.lubricant, case))
    return found


def solve(model: Model, grid: int) -> PointSolution:
    return solve_point(model.point, model.lubricant, model.case.with_grid(grid).solver)


def measure(model: Model, grids: Sequence[int], repeat: int) -> list[dict[str, object]]:
    """One row per grid: median wall time, cost, values and errors against the extrapolated values."""
    solve(model, grids[0])  # warm-up: Numba kernels of this model loaded or compiled
    solutions, times = [], []
    for grid in grids:
        runs = []
        for _ in range(repeat):
            start = time.perf_counter()
            solution = solve(model, grid)
            runs.append(time.perf_counter() - start)
        solutions.append(solution)
        times.append(statistics.median(runs))
        print(f"  {model.name}: {grid}^2 {times[-1]:.2f} s{'' if solution.converged else ' (not converged)'}",
              flush=True)
    rows = [{"model": model.name, "grid": grid, "wall_time_s": wall, "work_units": s.scalar("work_units"),
             "iterations": s.scalar("iterations"), "converged": int(s.converged)}
            for grid, wall, s in zip(grids, times, solutions)]
    converged = next((i for i, s in enumerate(solutions) if not s.converged), len(solutions))
    if converged < 3:
        print(f"  {model.name}: {converged} converged grid(s) before the first that is not: no extrapolation")
        return rows
    grids, solutions = grids[:converged], solutions[:converged]
    for name in QUANTITIES:
        if name == "p_max" or not all(name in s.scalars and s.scalar(name) != 0.0 for s in solutions):
            continue
        q = convergence(name, solutions[0].scalars[name][1], grids, [s.scalar(name) for s in solutions], 0.01)
        for i, row in enumerate(rows[:converged]):
            row[name] = q.values[i]
            row[f"{name}_error"] = q.error[i]
            row[f"{name}_order"] = q.order[i]
    return rows


def write_csv(rows: list[dict[str, object]], path: Path) -> None:
    columns = list(dict.fromkeys(key for row in rows for key in row))
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, columns, restval="")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: ("" if isinstance(v, float) and math.isnan(v) else v) for k, v in row.items()})


def report(rows: list[dict[str, object]]) -> None:
    """Markdown tables: error per grid, then the time to reach each target error."""
    print("\n| model | grid | wall time s | work units | error h_c | error h_min | error dT_max | error mu |")
    print("|---|---|---|---|---|---|---|---|")
    for row in rows:
        errors = [f"{100 * row[f'{q}_error']:+.3f} %" if f"{q}_error" in row and not math.isnan(row[f"{q}_error"])
                  else "-" for q in ("h_c", "h_min", "dT_max", "mu")]
        print(f"| {row['model']} | {row['grid']} | {row['wall_time_s']:.3f} | {row['work_units']:.1f} | "
              f"{' | '.join(errors)} |")
    print("\n| model | quantity | time to 1 % s | time to 0.1 % s |")
    print("|---|---|---|---|")
    for name in dict.fromkeys(row["model"] for row in rows):
        mine = [row for row in rows if row["model"] == name]
        quantities = [q for q in (*FILM, "dT_max", "mu") if f"{q}_error" in mine[0]]
        if not quantities:
            print(f"| {name} | - | {' | '.join(['fewer than three converged grids'] * len(TARGETS))} |")
        for q in quantities:
            measured = [r for r in mine if f"{q}_error" in r]
            errors = [r[f"{q}_error"] for r in measured]
            if any(math.isnan(e) for e in errors):
                cells = ["no extrapolated value"] * len(TARGETS)
            else:
                reach = [time_to_reach([r["wall_time_s"] for r in measured], errors, target) for target in TARGETS]
                cells = ["not reached" if math.isnan(t) else f"{t:.3f}" for t in reach]
            print(f"| {name} | {q} | {' | '.join(cells)} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="solves per grid; the median time is kept")
    parser.add_argument("--grids", default="33,65,129,257,513", help="grids of the isothermal models")
    parser.add_argument("--thermal", default="off,reduced,full", help="thermal models of the face gear point")
    parser.add_argument("--thermal-grids", default="33,65,129,257", help="grids of the thermal models")
    parser.add_argument("-o", "--output", default="speed_vs_error.csv", type=Path)
    args = parser.parse_args()
    ball = load_case(CASES / "ball_on_disc.yaml")
    grids = check_grids([int(g) for g in args.grids.split(",")], ball)
    thermal_grids = check_grids([int(g) for g in args.thermal_grids.split(",")], ball)
    rows: list[dict[str, object]] = []
    for model in models(args.thermal.split(",")):
        isothermal = model.case.solver.thermal == "off"
        rows += measure(model, grids if isothermal else thermal_grids, args.repeat)
    write_csv(rows, args.output)
    report(rows)
    print(f"\nwritten: {args.output}")


if __name__ == "__main__":
    main()
