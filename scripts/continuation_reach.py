"""How far a heavy contact's start holds its load (issue 47): the load continuation of a wide-envelope contact on
its finest grid, each step accepted only when its V-cycles converge.

The contact (facegear_tehl/suites/wide_envelope.py) is started by full multigrid at the load of Moes M =
TUNING.continuation_moes_m (start.py), then its load is raised on the finest grid: a step multiplies it by the
current factor (at most TUNING.load_step), moves H_0 by the predicted change of the central film
(start.FILM_LOAD_EXPONENT) and takes V-cycles until the relative pressure change and the load error are both below
--tolerance (at most --cycles). A step is accepted when they are and the film is open (h_min > 0); otherwise it is
taken back and the logarithm of its factor halved, down to TUNING.min_load_step. With --phase-means a V-cycle
whose pressure change runs against the previous one (correlation below -0.8: a period-2 limit cycle) is replaced by
the mean of its two phases; with --anderson M each step's V-cycles are accelerated by Anderson's method with M
columns (pressure.accelerate, as the pressure iteration does); with --semi the coarse grids are the load-continued
attempt's (start.hierarchy_shapes: coarsened along the strongly coupled axes alone, a long ellipse's keep every row).
Prints per step the load fraction, the cycles, the change, the load error, h_min and where it lies; at the end the
fraction reached, Moes M there, and where the pressure change of the next V-cycles concentrates with the correlation
of successive changes (-1: a period-2 limit cycle).

    python scripts/continuation_reach.py w01 [--grid 257] [--grid-y 65] [--attempt 3] [--phase-means]
                                             [--anderson M] [--semi] [--tolerance 1e-3] [--cycles 12]
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
import math
import sys

import numpy as np

from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.convergence import finite
from facegear_tehl.ehl.domain import predicted_central_film
from facegear_tehl.ehl.multigrid import Iterate, Level, MultigridSolver, Problem, at_load_fraction
from facegear_tehl.ehl.pressure import accelerate
from facegear_tehl.ehl.retry import ATTEMPTS
from facegear_tehl.ehl.solve import PointSolve
from facegear_tehl.ehl.start import FILM_LOAD_EXPONENT, hierarchy_shapes
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.suites.wide_envelope import wide_envelope_contact

LIMIT_CYCLE_CORRELATION = -0.8  # successive pressure changes this anti-correlated: a period-2 limit cycle


def correlation(first: np.ndarray, second: np.ndarray) -> float:
    """The correlation of two pressure changes (-1: opposite, the two phases of a period-2 cycle)."""
    norm = math.sqrt(float((first * first).sum() * (second * second).sum()))
    return float((first * second).sum()) / norm if norm > 0.0 else 0.0


class Continuation:
    """The finest level of one contact's solver, its load raised step by step."""

    def __init__(self, solve: PointSolve, tolerance: float, cycles: int, phase_means: bool, anderson: int = 0):
        self.solver: MultigridSolver = solve.solver
        self.full: Problem = solve.solver.problem
        self.top = len(self.solver.levels) - 1
        self.tolerance, self.cycles, self.phase_means = tolerance, cycles, phase_means
        self.mixer = Anderson(anderson, TUNING.pressure_anderson_growth) if anderson else None
        self.fraction = min(1.0, TUNING.continuation_moes_m / solve.scaling.moes_m)
        self.solver.problem = at_load_fraction(self.full, self.fraction)
        central = predicted_central_film(solve.scaling) / solve.scaling.film_scale
        self.solver.start_from_hertz(central * self.fraction ** FILM_LOAD_EXPONENT)
        for index in range(self.top + 1):
            if index:
                self.solver.interpolate_up(index)
            for _ in range(solve.settings.cycles_per_level):
                self.solver.cycle(index)

    @property
    def level(self) -> Level:
        return self.solver.levels[self.top]

    def load_error(self) -> float:
        return self.solver.force_error(self.level) / self.solver.problem.load_integral

    def one_cycle(self, last: np.ndarray | None) -> np.ndarray:
        """One V-cycle on the finest grid; its pressure change (replaced by the mean of the phases, --phase-means)."""
        before, h0 = self.level.pressure.copy(), self.solver.h0
        self.solver.cycle(self.top)
        change = self.level.pressure - before
        if self.phase_means and last is not None and correlation(change, last) < LIMIT_CYCLE_CORRELATION:
            self.solver.restore(self.top, Iterate(0.5 * (self.level.pressure + before), 0.5 * (self.solver.h0 + h0)))
        return change

    def converge(self) -> tuple[bool, int, float]:
        """V-cycles until the pressure change and the load error are below the tolerance: (met, cycles, change)."""
        last, change = None, math.inf
        if self.mixer is not None:
            self.mixer.reset()
        for cycle in range(1, self.cycles + 1):
            before = self.solver.snapshot(self.top)
            last = self.one_cycle(last)
            if not finite(self.level) or abs(self.load_error()) > TUNING.diverged_load_error:
                return False, cycle, math.inf
            change = float(np.abs(last).sum() / max(np.abs(self.level.pressure).sum(), 1e-300))
            if change < self.tolerance and abs(self.load_error()) < self.tolerance:
                return True, cycle, change
            if self.mixer is not None:
                accelerate(self.solver, self.top, before, self.mixer)
        return False, self.cycles, change

    def step(self, factor: float) -> bool:
        """Raise the load by `factor`; True if the step holds (kept), else taken back."""
        saved, previous = self.solver.snapshot(self.top), self.fraction
        self.fraction = min(factor * previous, 1.0)
        h_c = self.solver.central_film(self.level)
        self.solver.problem = at_load_fraction(self.full, self.fraction)
        self.solver.h0 += h_c * ((self.fraction / previous) ** FILM_LOAD_EXPONENT - 1.0)
        self.solver.update_film(self.level)
        met, cycles, change = self.converge()
        film = self.level.film
        j, i = np.unravel_index(np.argmin(film), film.shape) if finite(self.level) else (0, 0)
        held = met and float(film.min()) > 0.0
        print(f"load {self.fraction:.4f}: {'held' if held else 'taken back'}, {cycles} cycles, change {change:.1e}, "
              f"load error {self.load_error():.1e}, h_min {film.min():.4g} at X {self.level.x[i]:.3f} "
              f"Y {self.level.y[j]:.3f}, h_c {self.solver.central_film(self.level):.4g}", flush=True)
        if not held:
            self.solver.problem = at_load_fraction(self.full, previous)
            self.solver.restore(self.top, saved)
            self.fraction = previous
        return held

    def raise_load(self) -> None:
        """Steps under control of the convergence test (the factor squared after a step that holds, its square
        root after one that does not) up to the full load or the smallest factor."""
        factor = TUNING.load_step
        while self.fraction < 1.0 and factor >= TUNING.min_load_step:
            factor = min(factor * factor, TUNING.load_step) if self.step(factor) else math.sqrt(factor)

    def limit_cycle(self, cycles: int = 8) -> str:
        """Where the pressure change of `cycles` V-cycles past the load reached concentrates, and how successive
        changes correlate (mean over the last four)."""
        last, correlations, changes = None, [], []
        for _ in range(cycles):
            change = self.one_cycle(None)
            if last is not None:
                correlations.append(correlation(change, last))
            last = change
            changes.append(float(np.abs(change).sum() / max(np.abs(self.level.pressure).sum(), 1e-300)))
        j, i = np.unravel_index(np.argmax(np.abs(last)), last.shape)
        return (f"next {cycles} V-cycles: change {changes[-1]:.1e}, largest at X {self.level.x[i]:.3f} "
                f"Y {self.level.y[j]:.3f} (P {self.level.pressure[j, i]:.3f}), correlation of successive changes "
                f"{np.mean(correlations[-4:]):.2f}")


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", type=wide_envelope_contact, help="a wide-envelope contact's name or its prefix (w01)")
    parser.add_argument("--grid", type=int, default=257)
    parser.add_argument("--grid-y", type=int, default=65)
    parser.add_argument("--attempt", type=int, default=3, help="the relaxation of this attempt (retry.ATTEMPTS)")
    parser.add_argument("--phase-means", action="store_true", help="replace period-2 cycles by their mean")
    parser.add_argument("--tolerance", type=float, default=1e-3)
    parser.add_argument("--cycles", type=int, default=12, help="V-cycles per step at most")
    parser.add_argument("--anderson", type=int, default=0, help="Anderson columns on the V-cycle map (0: bare)")
    parser.add_argument("--semi", action="store_true",
                        help="the load-continued attempt's hierarchy: coarse grids with every row (along x alone)")
    args = parser.parse_args(argv)
    case = args.case
    solve = PointSolve(case.point(), case.lubricant(), case.settings(args.grid, args.grid_y),
                       ATTEMPTS[args.attempt - 1].relaxation, attempt=args.attempt)
    if args.semi:
        solve.new_hierarchy(hierarchy_shapes(solve.settings, solve.coarsest, solve.solver.problem, continued=True))
    run = Continuation(solve, args.tolerance, args.cycles, args.phase_means, args.anderson)
    run.raise_load()
    level = run.level
    print(f"{case.name} on {level.nx} x {level.ny}: load reached {run.fraction:.3f} (Moes M "
          f"{run.fraction * solve.scaling.moes_m:.3g} of {solve.scaling.moes_m:.3g}); {run.limit_cycle()}")
    return 0 if run.fraction == 1.0 else 1


if __name__ == "__main__":
    sys.exit(main())
