"""Speed and accuracy of the isothermal solver on the circular benchmark of Venner & Lubrecht
(2000), docs/benchmarks.md.

For M = 20 and 200 at L = 10 (steel, R = 12.7 mm, eta_0 = 0.04 Pa s, alpha = 2.2e-8 1/Pa; domain
X in [-4.5, 1.5], Y in [-3, 3]) and grids 65^2 .. 513^2, prints H_c and H_min in Venner's scaling
(H = h R/a^2), the solver's own error estimate, V-cycles on the finest grid, work units and wall time
(median of --repeat runs, single process). Then the time to reach H_c within 0.5 % of the 513^2 value
with the full-multigrid start only (2 V-cycles per level, as the reference C code's 0.46 s / 2.0 s runs; its first
attempt alone, without the damped retry that a solve ending short of its tolerance gets).

    python scripts/bench_isothermal.py [--repeat 3] [--max-grid 513]
"""

from __future__ import annotations

import argparse
import statistics
import time

from facegear_tehl.case import SolverSettings
from facegear_tehl.ehl.scaling import contact_from_moes
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.ehl.staged import STAGED, solve_point

# Reference C code of Venner & Lubrecht (2000) run on this machine type, 513^2 values (docs/benchmarks.md).
REFERENCE = {
    ("barus", 20.0): (0.4973, 0.3065),
    ("roelands", 20.0): (0.4318, 0.2924),
}
REFERENCE_TIME_257 = {"barus": 0.46, "roelands": 2.0}  # s, 257^2 (Barus: 2 V-cycles per level)


def settings(grid: int, max_cycles: int = 40) -> SolverSettings:
    return SolverSettings(grid=grid, domain_x=(-4.5, 1.5), domain_y=(-3.0, 3.0), thermal="off", coarsest_grid=17,
                          cycles_per_level=2, max_cycles=max_cycles, tolerance=1e-4, load_tolerance=1e-4)


def _first_attempt(point, lub, settings_: SolverSettings):
    """The solve's first attempt alone: a full-multigrid start without cycles (max_cycles 0) ends 'not converged',
    which solve_point would retry damped (StagedSolver.needs_retry), timing two solves."""
    begun = STAGED.begin(point, lub, settings_)
    return begun.finish() if isinstance(begun, PointSolve) else begun


def run(m: float, model: str, grid: int, repeat: int, max_cycles: int = 40):
    density = "dowson_higginson" if model == "roelands" else "incompressible"
    point, lub = contact_from_moes(m, 10.0, viscosity_model=model, density_model=density)
    times, sol = [], None
    solver = solve_point if max_cycles > 0 else _first_attempt
    for _ in range(repeat):
        t = time.perf_counter()
        sol = solver(point, lub, settings(grid, max_cycles))
        times.append(time.perf_counter() - t)
    scale = point.radius_x / sol.scalar("a") ** 2
    return sol, sol.scalar("h_c") * scale, sol.scalar("h_min") * scale, statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--max-grid", type=int, default=513)
    args = parser.parse_args()
    grids = [g for g in (65, 129, 257, 513) if g <= args.max_grid]
    run(20.0, "barus", 65, 1)  # compile the Numba kernels (cached on disk afterwards)

    print("| viscosity | M | grid | H_c | H_min | error est. H_c | cycles | work units | wall time s |")
    print("|---|---|---|---|---|---|---|---|---|")
    finest = {}
    for model in ("roelands", "barus"):
        for m in (20.0, 200.0):
            for grid in grids:
                sol, hc, hmin, wall = run(m, model, grid, args.repeat)
                finest[(model, m)] = hc
                est = sol.scalars.get("error_estimate_h_c", (float("nan"), ""))[0]
                flag = "" if sol.converged else " (not converged)"
                print(f"| {model} | {m:g} | {grid} | {hc:.4f} | {hmin:.4f} | {100 * est:+.2f} % | "
                      f"{sol.scalar('iterations'):.0f} | {sol.scalar('work_units'):.1f} | {wall:.2f}{flag} |")
    print()
    print("Reference (Venner & Lubrecht C code, 513^2):", {f"{k[0]} M={k[1]:g}": v for k, v in REFERENCE.items()})
    print()
    print("| viscosity | grid | FMG only: H_c | vs 513^2 | wall time s | reference C time s |")
    print("|---|---|---|---|---|---|")
    for model in ("roelands", "barus"):
        target = finest.get((model, 20.0), REFERENCE[(model, 20.0)][0])
        sol, hc, _, wall = run(20.0, model, 257, args.repeat, max_cycles=0)
        print(f"| {model} | 257 | {hc:.4f} | {100 * (hc / target - 1):+.2f} % | {wall:.2f} | "
              f"{REFERENCE_TIME_257[model]:.2f} |")


if __name__ == "__main__":
    main()
