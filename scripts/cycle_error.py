"""The iteration error of the pressure cycles (ehl/error_bounds.cycle_error) against the true one.

Tolerance study (default): circular Roelands/Dowson-Higginson contacts at L = 10 (M = 200 and 1000) on 129^2 stopped at
pressure tolerances 3e-3 .. 3e-5, against the same grid cycled to a change of ~1e-9 per cycle (the same discrete
problem: the difference is the iteration error alone). Prints per stop the true error of h_c and h_min, the bound's
iteration part (the film's own tail and with the pressure's tail scaled) and whether it holds.

--contact NAME: an envelope contact solved as the envelope suite solves it (scripts/envelope.py: 257 x 65 asked, the
solver refining), its finest grid's per-cycle history (pressure change, residual, load error, h_c, h_min) and the
bounds it reports.

    python scripts/cycle_error.py [--contact NAME]
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import math
import sys

import numpy as np

from facegear_tehl.ehl.error_bounds import cycle_changes, cycle_error, drifting, remaining_error
from facegear_tehl.ehl.scaling import contact_from_moes
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import PointSolution

TOLERANCES = (3e-3, 1e-3, 3e-4, 1e-4, 3e-5)


def own_tail(solution: PointSolution, name: str) -> float:
    """The film's own tail alone (remaining_error of its changes per cycle), without the pressure's."""
    changes, _ = cycle_changes(solution, name)
    floored = math.isfinite(solution.scalars.get("algebraic_floor", (math.nan, "1"))[0])
    return remaining_error(np.abs(changes), floored) if changes.size else 0.0


def tolerance_study() -> int:
    """The table of the module docstring; exit 1 if a bound fell below its true error."""
    print("| M | tolerance | cycles | figure | true error | film's own tail | bound's iteration part | holds |")
    print("|---|---|---|---|---|---|---|---|")
    missed = 0
    for moes_m in (200.0, 1000.0):
        point, lubricant = contact_from_moes(moes_m, 10.0, viscosity_model="roelands", density_model="dowson_higginson")
        settings = SolverSettings(grid=129, domain_x=(-4.5, 1.5), domain_y=(-3.0, 3.0), thermal="off")
        tight = replace(settings, tolerance=1e-8, load_tolerance=1e-8, max_cycles=200)
        converged = solve_point(point, lubricant, tight)
        for tolerance in TOLERANCES:
            stopped = solve_point(point, lubricant, replace(settings, tolerance=tolerance, load_tolerance=tolerance))
            for name in ("h_c", "h_min"):
                true = abs(stopped.scalar(name) / converged.scalar(name) - 1.0)
                bound = cycle_error(stopped, name)
                missed += bound < true
                print(f"| {moes_m:g} | {tolerance:g} | {stopped.scalar('iterations'):.0f} | {name} | {true:.1e} | "
                      f"{own_tail(stopped, name):.1e} | {bound:.1e} | {'yes' if bound >= true else 'NO'} |")
    print(f"\n{missed} of {2 * 2 * len(TOLERANCES)} below their true error")
    return 1 if missed else 0


def contact_history(name: str) -> int:
    """The per-cycle history and bounds of an envelope contact solved as the envelope suite solves it."""
    from facegear_tehl.parallel import SolveTask
    from facegear_tehl.run import ehl_solver, solve_refining
    from facegear_tehl.suites.envelope import GRID, GRID_Y, envelope_cases

    cases = [c for c in envelope_cases() if c.name == name]
    if not cases:
        print(f"no envelope contact {name!r}", file=sys.stderr)
        return 2
    case = cases[0]
    solution = solve_refining([SolveTask(case.point(), case.lubricant(), case.settings(GRID, GRID_Y))], ehl_solver(),
                              jobs=1)[0][0]
    print(f"{name}: {solution.outcome.value} on {solution.scalar('grid'):.0f} x {solution.scalar('grid_y'):.0f}, "
          f"algebraic floor {solution.scalars.get('algebraic_floor', (math.nan, '1'))[0]:.3g}")
    keys = ("pressure_change_history", "residual_history", "load_error_history", "cycle_h_c_history",
            "cycle_h_min_history")
    print("| cycle | pressure change | residual | load error | h_c nm | h_min nm |")
    print("|---|---|---|---|---|---|")
    rows = zip(*(np.asarray(solution.history[k].values) for k in keys))
    for i, (dp, r, w, h_c, h_min) in enumerate(rows):
        print(f"| {i} | {dp:.2e} | {r:.3g} | {w:.2e} | {h_c * 1e9:.3f} | {h_min * 1e9:.3f} |")
    for figure in ("h_c", "h_min"):
        changes, _ = cycle_changes(solution, figure)
        flag = solution.scalars.get(f"unresolved_{figure}", (math.nan, "1"))[0]
        bound = solution.scalars.get(f"error_bound_{figure}", (math.nan, "1"))[0]
        print(f"{figure}: last changes {np.array2string(changes[-5:], precision=4)}, drifting {drifting(changes)}, "
              f"iteration part {cycle_error(solution, figure):.3g}, "
              + ("unresolved" if flag == 1.0 else f"bound {100 * bound:.2f} %"))
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contact", help="an envelope contact's per-cycle history (scripts/envelope.py --list)")
    args = parser.parse_args(argv)
    return contact_history(args.contact) if args.contact else tolerance_study()


if __name__ == "__main__":
    sys.exit(main())
