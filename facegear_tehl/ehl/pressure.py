"""The pressure iteration on a frozen film state: V-cycles on one level until its tolerances or its algebraic floor.

`PressureIteration.cycle` is the one loop every stage cycles the pressure with (Venner & Lubrecht 2000, ch. 5):
per cycle it records the change, residual and load error into the solve's History and judges them with
convergence.py. Once a call's bare cycles stop contracting (the change fell by less than 1 - floor_stall over two
cycles: a mode with an iteration factor near -1 or slightly above 1) where the phase means below do not reach (above
phase_mean_band times the tolerance, or with the call's phase means used up), each cycle starts from Anderson's
combination of the cycles of the call so far on the map (P, H_0) -> V(P, H_0) (`accelerate`; Walker & Ni 2011;
Brune, Knepley, Smith & Tu 2015), which damps those few modes; a call whose bare cycles contract is not touched. It
deals with the two limit cycles the V-cycle can fall into above its floor:
- a period-2 limit cycle between floor_band and phase_mean_band times the tolerance is replaced by the mean of its
  last two iterates (the fixed point its phases straddle), at most max_phase_means times per call;
- a stall below truncation_band times the tolerance switches the truncated coarse-grid correction on (the nodes next
  to cavitation skip it, multigrid.corrected_nodes) for the rest of the solve; if the change then leaves the band on
  one film state it is switched off for good and, within the call that switched it on, the iterate it began at is
  restored.
The discrete solution is unchanged by all three: convergence is judged on an undamped cycle's change and load error,
and a call that converges ends on that cycle's iterate.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
import itertools
import math

import numpy as np

from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.convergence import (
    History,
    at_algebraic_floor,
    call_drifting,
    finite,
    flicker_stalled,
    running_away,
)
from facegear_tehl.ehl.multigrid import Iterate, MultigridSolver
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import CONVERGED, Outcome, Status


class Truncation(Enum):
    """The truncated coarse-grid correction of a solve: not yet tried, on, or switched off after it failed."""

    OFF = "off"
    ON = "on"
    FAILED = "failed"


@dataclass
class Best:
    """The best iterate of a finest-grid iteration (smallest pressure change + |load error|)."""

    score: float
    iterate: Iterate


def pressure_mixer() -> Anderson | None:
    """The Anderson history of one call of the pressure iteration (None: bare V-cycles)."""
    depth = TUNING.pressure_anderson_depth
    return Anderson(depth, TUNING.pressure_anderson_growth) if depth else None


def accelerate(solver: MultigridSolver, index: int, before: Iterate, mixer: Anderson, apply: bool = True) -> None:
    """Level `index` on Anderson's combination of the V-cycles so far (Walker & Ni 2011, eq. 1.3) on the map
    x = (P, H_0) -> V(x): the last cycle went from `before` to the level's pressure and H_0, its plain step
    f = V(x) - x; the combination is projected on P >= 0 (Brune, Knepley, Smith & Tu 2015, SIAM Rev. 57:535-565, the
    FAS cycle as the nonlinear preconditioner of Anderson's method). Without `apply` the pair (x, f) only enters the
    history (Anderson's columns are differences of pairs, whichever iterate each cycle started from) and the level
    stays on the plain step."""
    level = solver.levels[index]
    x = np.append(before.pressure.ravel(), before.h0)
    f = np.append(level.pressure.ravel(), solver.h0) - x
    mixed = mixer.step(x, f)
    if apply and mixer.columns:  # else the plain step: the level is on it
        solver.restore(index, Iterate(np.maximum(mixed[:-1], 0.0).reshape(level.pressure.shape), float(mixed[-1])))


class PressureIteration:
    """The pressure iteration of one point solve: the current multigrid solver and history (the solve replaces
    them when it begins a new hierarchy or adds an outlet patch), and the state its limit-cycle remedies keep
    across calls."""

    def __init__(self, solver: MultigridSolver, settings: SolverSettings, history: History):
        self.solver, self.settings, self.history = solver, settings, history
        self.before_cycle: tuple[Iterate, np.ndarray] | None = None  # the iterate and film before the last V-cycle
        self.truncation = Truncation.OFF
        self.truncated_since = 0  # cycles in the history when it was switched on
        # the iterate it was switched on at, its change if that was the algebraic floor (else NaN), the call
        self.before_truncation: tuple[Iterate, float, int] | None = None
        self.calls = 0  # calls of `cycle` so far
        self.mixer: Anderson | None = None  # the Anderson history of the call under way (None: bare V-cycles)
        self.mixed_under = self.truncation  # the truncation its history was gathered with
        self.engaged = False  # the call's bare cycles stopped contracting: its cycles start from the combination

    def cycle(self, index: int, max_cycles: int, best: Best | None = None) -> Status:
        """V-cycles on level `index` until the tolerances are met (or the algebraic floor is reached), at most
        `max_cycles`. `best` (if given) keeps the best iterate for reporting a solve that does not converge."""
        solver, settings, history = self.solver, self.settings, self.history
        level = solver.levels[index]
        previous = level.pressure.copy()
        self.calls += 1
        means = 0  # period-2 cycles replaced by the mean of their phases
        self.mixer, self.mixed_under, self.engaged = pressure_mixer(), self.truncation, False
        for extra in itertools.count():
            change, load_error = self._record(index, previous, extra)
            if running_away(load_error):
                return Status(Outcome.DIVERGED,
                              f"diverged at cycle {history.cycles} on the finest grid (load error {load_error:.2e})")
            if best is not None:
                self._keep_best(best, index, change if extra > 0 else 1.0, load_error)
            if extra > 0:
                ended = self._judge(index, change, load_error, extra, extra == max_cycles)
                if ended is not None:
                    return ended
            if extra == max_cycles:
                return Status(Outcome.NOT_CONVERGED, (
                    f"not converged after {history.cycles} cycles on the finest grid: pressure change {change:.2e} "
                    f"(tolerance {settings.tolerance:.0e}), load error {load_error:.2e} "
                    f"(tolerance {settings.load_tolerance:.0e})"))
            if extra >= 3 and means < TUNING.max_phase_means and self._in_phase_band(change):
                self._restore_mean(index)
                means += 1
                if self.mixer is not None:
                    self.mixer.reset()
            elif extra > 0:
                self.engaged = self.engaged or self._stalled_past_means(change, extra, means)
                self._mix(index)
            previous = self._one_cycle(index)
            if not finite(level):
                return Status(Outcome.DIVERGED,
                              f"diverged at cycle {history.cycles} on the finest grid (non-finite pressure or film)")

    def _stalled_past_means(self, change: float, extra: int, means: int) -> bool:
        """The call's bare cycles stopped contracting (`flicker_stalled`) where the phase means do not reach: above
        phase_mean_band times the tolerance, or with the call's max_phase_means used up (a period-2 stall inside the
        band is the phase means', whose mean is the fixed point its phases straddle)."""
        reached = change < TUNING.phase_mean_band * self.settings.tolerance and means < TUNING.max_phase_means
        return not reached and flicker_stalled(self.history.changes[-extra:])

    def _record(self, index: int, previous: np.ndarray, extra: int) -> tuple[float, float]:
        """The change against `previous` and the load error of level `index`, appended to the history (the entry
        iterate of a call only as the first entry of a history, its change NaN)."""
        solver, history = self.solver, self.history
        level = solver.levels[index]
        change = solver.pressure_change(level, previous)
        load_error = solver.force_error(level) / solver.problem.load_integral
        residual = solver.residual(level)
        positive = level.pressure > 0.0
        if extra > 0 or not history.changes:
            history.changes.append(change if extra > 0 else math.nan)
            history.residuals.append(float(np.abs(residual[positive]).mean()) if positive.any() else 0.0)
            history.loads.append(load_error)
            history.films.append((float(level.nx), solver.central_film(level),
                                  float(level.film.min())))
        return change, load_error

    def _keep_best(self, best: Best, index: int, change: float, load_error: float) -> None:
        score = change + abs(load_error)
        if score < best.score:
            best.score, best.iterate = score, self.solver.snapshot(index)

    def _judge(self, index: int, change: float, load_error: float, extra: int, last: bool) -> Status | None:
        """CONVERGED on the tolerances or on the algebraic floor (not while the truncation is on trial), neither
        before the `last` cycle of the call while this call's central film drifts one way (its fixed point lies
        further on); or on a failed truncation taken back to the floor it began at; None to go on."""
        settings, history = self.settings, self.history
        settled = last or not call_drifting(history.films, extra)
        if change < settings.tolerance and abs(load_error) < settings.load_tolerance and settled:
            return CONVERGED
        if self._update_truncation(index, extra):
            return CONVERGED
        if at_algebraic_floor(history.changes, history.loads, settings) and not self._on_trial() and settled:
            history.floor = change
            return CONVERGED
        return None

    def _in_phase_band(self, change: float) -> bool:
        """A flicker stall between floor_band and phase_mean_band times the tolerance, with an iterate to mean."""
        tolerance = self.settings.tolerance
        return (self.before_cycle is not None
                and TUNING.floor_band * tolerance <= change < TUNING.phase_mean_band * tolerance
                and flicker_stalled(self.history.changes))

    def _one_cycle(self, index: int) -> np.ndarray:
        """One V-cycle on level `index` (truncated while the truncation is on); returns the pressure before it."""
        solver, level = self.solver, self.solver.levels[index]
        previous = level.pressure.copy()
        self.before_cycle = (Iterate(previous, solver.h0), level.film.copy())
        solver.truncated = self.truncation is Truncation.ON
        try:
            solver.cycle(index)
        finally:
            solver.truncated = False
        self.history.cycles += 1
        return previous

    def _mix(self, index: int) -> None:
        """The last V-cycle into the Anderson history and, once the call is `engaged`, level `index` on the
        combination (`accelerate`); the history is dropped where the map changed (the truncation switched) or the last
        cycle's start is not known."""
        mixer = self.mixer
        if mixer is None:
            return
        if self.before_cycle is None or self.truncation is not self.mixed_under:
            mixer.reset()
            self.mixed_under = self.truncation
        if self.before_cycle is not None:
            accelerate(self.solver, index, self.before_cycle[0], mixer, self.engaged)

    def _update_truncation(self, index: int, extra: int) -> bool:
        """Switch the truncated correction on at a flicker stall below truncation_band times the tolerance; switch it
        off for good once the change leaves the band on one film state (at a later cycle of a call, `extra` > 1, or
        in the call that switched it on) and, within that call, take level `index` back to the iterate it was
        switched on at. Returns True when that iterate was at the algebraic floor, where the iteration then ends."""
        history = self.history
        changes = history.changes
        band = TUNING.truncation_band * self.settings.tolerance
        same_call = self.before_truncation is not None and self.before_truncation[2] == self.calls
        if self.truncation is Truncation.OFF and flicker_stalled(changes) and changes[-1] < band:
            self.truncation, self.truncated_since = Truncation.ON, len(changes)
            floor = changes[-1] if at_algebraic_floor(changes, history.loads, self.settings) else math.nan
            self.before_truncation = (self.solver.snapshot(index), floor, self.calls)
        elif self.truncation is Truncation.ON and changes[-1] > band and (extra > 1 or same_call):
            self.truncation = Truncation.FAILED
            iterate, floor, _ = self.before_truncation
            self.before_truncation = None
            if same_call:
                self.solver.restore(index, iterate)
                self.before_cycle = None  # its phases are the trial's
                if math.isfinite(floor):
                    history.floor = floor
                    return True
        return False

    def _on_trial(self) -> bool:
        """The truncated correction was switched on less than truncation_trial cycles ago: a stall is no floor yet."""
        return (self.truncation is Truncation.ON
                and len(self.history.changes) - self.truncated_since < TUNING.truncation_trial)

    # ------------------------------------------------------------ the settled iterate of a flicker
    def flickering(self, index: int) -> bool:
        """The pressure of level `index` flickers: a flicker stall below phase_mean_band times the tolerance (up to
        floor_band the algebraic floor; above it a limit cycle that the outer loops' few V-cycles per update never
        leave)."""
        changes, before = self.history.changes, self.before_cycle
        if len(changes) < 3 or before is None or before[1].shape != self.solver.levels[index].film.shape:
            return False
        return flicker_stalled(changes) and changes[-1] < TUNING.phase_mean_band * self.settings.tolerance

    def settled_pressure(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        """The pressure and film of level `index` (dimensionless) a film state is evaluated at: on a flicker the mean
        of its last two iterates, the fixed point the two phases straddle; else the last iterate."""
        level = self.solver.levels[index]
        if not self.flickering(index):
            return level.pressure, level.film
        iterate, film = self.before_cycle
        return 0.5 * (level.pressure + iterate.pressure), 0.5 * (level.film + film)

    def settle(self, index: int) -> None:
        """Leave level `index` on the mean of its last two iterates if its pressure flickers: the result then does
        not depend on the phase the loop stops on."""
        if self.flickering(index):
            self._restore_mean(index)

    def _restore_mean(self, index: int) -> None:
        """Level `index` on the mean of its pressure and H_0 and those before the last V-cycle (`before_cycle`)."""
        iterate = self.before_cycle[0]
        self.solver.restore(index, Iterate(0.5 * (self.solver.levels[index].pressure + iterate.pressure),
                                           0.5 * (self.solver.h0 + iterate.h0)))
