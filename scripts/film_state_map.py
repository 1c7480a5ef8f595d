"""The thermal outer loop's film-state map with the pressure frozen, and the energy sweeps' forcing.

1. Solves one point of a gear case (default S1 of cases/facegear_110.yaml, thermal full, outlet stage off), keeps its
   pressure and film, iterates the film-state map alone (`FilmThermalModel.update`, no V-cycles) to a reference fixed
   point, raises the interior layers by --perturbation K and iterates again with full steps (no relaxation, no
   Anderson), each update's sweeps run to their cap (--sweeps, default TUNING.energy_sweeps); prints the largest error
   after each update and its ratio to the one before, for the map as solved, with parts of the film state held at the
   reference (the surfaces' Jaeger temperatures, the velocities across the film, the dissipation), and with two and
   four times the sweeps per update.
2. With --forcing F [F ...]: the case's points solved in turn in one process (one BLAS thread) with
   `TUNING.energy_forcing` (the largest share of `coupled.energy_forcing`, the energy sweeps' adaptive tolerance)
   set to each F: outer iterations and CPU time of the solves.

    python scripts/film_state_map.py [CASE] [--point S1] [--perturbation 2] [--sweeps 32] [--forcing 0.3 0.15]

docs/benchmarks.md ("Where S1's thermal time goes") and docs/tuning.md (`energy_forcing`) quote both.
"""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path
import time

import numpy as np
from threadpoolctl import threadpool_limits

from facegear_tehl.case import load_case
from facegear_tehl.ehl import coupled, thermal
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.points import contact_analysis

HERE = Path(__file__).resolve().parents[1]
UPDATES = 10  # updates per variant
REFERENCE_UPDATES = 200  # half steps to the reference fixed point
REFERENCE_TOLERANCE = 1e-6  # K, the sweeps' tolerance: they run to their cap


def frozen_map(case, point_name: str, perturbation: float, sweeps: int) -> None:
    point = next(p for p in contact_analysis(case).points if p.name == point_name)
    settings = replace(case.solver, thermal="full", outlet_refinement="never")
    point_solve = PointSolve(point, case.lubricant, settings)
    begun = point_solve.begin()
    if begun is point_solve:
        point_solve.finish()
    level = point_solve.solver.levels[-1]
    model = point_solve._film_model(level)
    pressure, film = level.pressure * point_solve.scaling.p_h, level.film * point_solve.scaling.film_scale
    temperature = model.update(pressure, film, model.initial_temperature()).temperature
    for _ in range(REFERENCE_UPDATES):
        temperature += 0.5 * (model.update(pressure, film, temperature, REFERENCE_TOLERANCE).temperature - temperature)
    reference = temperature
    at_reference = model.update(pressure, film, reference, REFERENCE_TOLERANCE)
    residual = float(np.abs(at_reference.temperature - reference).max())
    print(f"{case.name} {point_name}, {level.nx} x {level.ny} x {reference.shape[0]}: reference residual "
          f"{residual:.1e} K, rise {reference.max() - case.lubricant.inlet_temperature:.1f} K, interior layers "
          f"+{perturbation} K\n")
    print("| variant | largest error after each update, K | ratio to the one before |")
    print("|---|---|---|")
    shear_state, surface = thermal.rheology.shear_state, model._surface
    held: dict[str, np.ndarray] = {}

    def holding(*args):
        shear_state(*args)
        outputs = {"dissipation": args[10], "velocity_x": args[11], "velocity_y": args[12]}
        for name, value in held.items():
            if name in outputs and outputs[name].size:
                outputs[name][...] = value

    def run(label: str) -> None:
        temperature = reference.copy()
        temperature[1:-1] += perturbation
        errors = []
        for _ in range(UPDATES):
            temperature = model.update(pressure, film, temperature, REFERENCE_TOLERANCE).temperature
            errors.append(float(np.abs(temperature - reference).max()))
        ratios = [b / a for a, b in zip(errors, errors[1:])]
        print(f"| {label} | {', '.join(f'{e:.3f}' for e in errors)} | {', '.join(f'{r:.2f}' for r in ratios)} |")

    thermal.rheology.shear_state = holding
    tuning = thermal.TUNING
    thermal.TUNING = replace(tuning, energy_sweeps=sweeps)
    try:
        run(f"as solved ({sweeps} sweeps per update)")
        model._surface = lambda flux, index, speed: reference[0 if index == 0 else -1]
        run("surfaces held")
        model._surface = surface
        held.update(velocity_x=at_reference.velocity_x, velocity_y=at_reference.velocity_y)
        run("velocities held")
        held.clear()
        held.update(dissipation=at_reference.dissipation)
        run("dissipation held")
        held.update(velocity_x=at_reference.velocity_x, velocity_y=at_reference.velocity_y)
        run("velocities and dissipation held")
        held.clear()
        for more in (2 * sweeps, 4 * sweeps):
            thermal.TUNING = replace(tuning, energy_sweeps=more)
            run(f"{more} sweeps per update")
    finally:
        thermal.rheology.shear_state, model._surface, thermal.TUNING = shear_state, surface, tuning


def forcing_table(case, values: list[float]) -> None:
    points = contact_analysis(case).points
    solve_point(points[0], case.lubricant, case.solver)  # kernels loaded
    default = coupled.TUNING
    print("\n| energy_forcing | outer iterations | CPU s | per point (outer iterations) |")
    print("|---|---|---|---|")
    try:
        for value in values:
            coupled.TUNING = replace(default, energy_forcing=value)
            counts, cpu = [], 0.0
            for point in points:
                start = time.process_time()
                solution = solve_point(point, case.lubricant, case.solver)
                cpu += time.process_time() - start
                counts.append(int(solution.scalar("thermal_iterations")))
            per_point = ", ".join(f"{p.name} {n}" for p, n in zip(points, counts))
            print(f"| {value:g} | {sum(counts)} | {cpu:.1f} | {per_point} |", flush=True)
    finally:
        coupled.TUNING = default


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", nargs="?", default=str(HERE / "cases" / "facegear_110.yaml"))
    parser.add_argument("--point", default="S1")
    parser.add_argument("--perturbation", type=float, default=2.0, help="K added to the interior layers")
    parser.add_argument("--sweeps", type=int, default=None, help="energy sweeps per update (the variants' cap)")
    parser.add_argument("--forcing", type=float, nargs="*", default=[])
    args = parser.parse_args()
    case = load_case(args.case)
    with threadpool_limits(limits=1):
        frozen_map(case, args.point, args.perturbation, args.sweeps or thermal.TUNING.energy_sweeps)
        if args.forcing:
            forcing_table(case, args.forcing)


if __name__ == "__main__":
    main()
