"""Thermal models on the face gear points: accuracy against `full` and cost, and the whole S1-S5 run.

For each meshing point of a gear case (default cases/facegear_110.yaml, its own grid) and each thermal model
(off, reduced, full) prints h_c, h_min, p_max, dT_max, the friction coefficient and the wall time, with the
error of `off` and `reduced` against `full`; the film reduction by heating, h_c(full)/h_c(off), next to Gupta
et al.'s (1992) thermal reduction factor; which model `auto` picks; and the wall time of the whole S1-S5
`full` run with --jobs 1 and --jobs 2 (median of --repeat runs).

    python scripts/bench_thermal.py [CASE] [--grid N] [--repeat 1]
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import time

from facegear_tehl.case import load_case
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.ehl.thermal import gupta_reduction, thermal_choice
from facegear_tehl.points import contact_analysis
from facegear_tehl.run import run_case

MODELS = ("off", "reduced", "full")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", nargs="?", default="cases/facegear_110.yaml")
    parser.add_argument("--grid", type=int, default=None)
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    case = load_case(args.case)
    if args.grid:
        case = case.with_grid(args.grid)
    points = contact_analysis(case).points
    lub = case.lubricant

    results = {}
    for point in points:
        for model in MODELS:
            settings = dataclasses.replace(case.solver, thermal=model)
            t = time.perf_counter()
            sol = solve_point(point, lub, settings)
            results[point.name, model] = (sol, time.perf_counter() - t)

    print(f"{case.name}, grid {case.solver.grid}^2, rheology {lub.rheology}\n")
    print("| point | SRR | model | h_c µm | h_min µm | p_max MPa | dT_max K | mu | wall s | h_c err | h_min err "
          "| mu err | converged |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for point in points:
        ref = results[point.name, "full"][0]
        for model in MODELS:
            sol, wall = results[point.name, model]

            def err(key, sol=sol, ref=ref, model=model):
                if key not in sol.scalars or key not in ref.scalars or model == "full":
                    return "–"
                return f"{100 * (sol.scalar(key) / ref.scalar(key) - 1):+.1f} %"

            dt = sol.scalars.get("dT_max", (0.0, ""))[0]
            mu = sol.scalars.get("mu", (float("nan"), ""))[0]
            print(f"| {point.name} | {point.slide_roll_ratio:+.3f} | {model} | {1e6 * sol.scalar('h_c'):.3f} | "
                  f"{1e6 * sol.scalar('h_min'):.3f} | {1e-6 * sol.scalar('p_max'):.0f} | {dt:.1f} | {mu:.4f} | "
                  f"{wall:.1f} | {err('h_c')} | {err('h_min')} | {err('mu')} | {'yes' if sol.converged else 'no'} |")

    print("\nFilm reduction by heating, h_c(full)/h_c(off), against Gupta et al. (1992) phi_T; auto's choice:\n")
    print("| point | SRR | L_th | h_c full/off | Gupta phi_T | difference | auto picks |")
    print("|---|---|---|---|---|---|---|")
    for point in points:
        full, off = results[point.name, "full"][0], results[point.name, "off"][0]
        ratio = full.scalar("h_c") / off.scalar("h_c")
        phi = gupta_reduction(point, lub)
        choice = thermal_choice("auto", point, lub)[0]
        print(f"| {point.name} | {point.slide_roll_ratio:+.3f} | {full.scalar('thermal_loading'):.3f} | {ratio:.3f} | "
              f"{phi:.3f} | {100 * (ratio - phi):+.1f} points | {choice} |")

    full_case = dataclasses.replace(case, solver=dataclasses.replace(case.solver, thermal="full"))
    print("\nWhole S1-S5 `full` run (run_case), median of", args.repeat, "run(s):\n")
    print("| jobs | wall time s |")
    print("|---|---|")
    for jobs in (1, 2):
        times = []
        for _ in range(args.repeat):
            t = time.perf_counter()
            run_case(full_case, jobs=jobs)
            times.append(time.perf_counter() - t)
        print(f"| {jobs} | {statistics.median(times):.1f} |")


if __name__ == "__main__":
    main()
