"""The coupled outer loop, written once: the film state (layer temperatures and eta*/eta) and the pressure iterated
together on a frozen-state pressure iteration (thermal.py, pressure.py).

Each outer iteration evaluates the film state at the settled pressure, takes an under-relaxed, Anderson-accelerated
step towards it (anderson.py; Walker & Ni 2011), freezes the new state into the flow coefficients and cycles the
pressure a few times. What the loop runs on is a `CoupledTarget`: the uniform grid's level (solve.py) or an outlet
patch over the grid below (outlet.py). The target says when the loop has ended (`judge`); the loop itself handles
divergence, the energy sweeps' forcing, the relaxation of a loop that stalls above its floor and a film that closes.

A film state is evaluated on an open film only. Where the film of the pressure iterate is closed (h <= 0) the film
has no thickness to shear, conduct across or carry heat in: the layer velocities and temperatures of the energy
equation are undefined there, and its discrete form (energy.py) makes a closed column a sink of the enthalpy its open
neighbours carry into it, handed to the solids' surfaces through their moving heat sources. That loop has no fixed
point: on the thermal Ree-Eyring contacts of the wide envelope whose grid does not resolve the film (w34 on 129 x 65:
169 pressurised nodes with H down to -0.011 against H_c = 0.007) the layer temperatures moved by the 50 K cap at every
update from the second on, first on the closed band and downstream of it, above and below the inlet temperature,
until they were not finite (docs/envelope.md). A closed film is therefore cycled on its frozen film state to the
pressure's tolerance first (an iterate's closure can be transient); a film still closed then is what the grid
solves, and the loop ends with it closed (`Ending.FILM_CLOSED`): the grid does not resolve the film (retry.py
refines it), the thermal physics is not at fault.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from enum import Enum
import math
from typing import Protocol

import numpy as np

from facegear_tehl.ehl import rheology
from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.convergence import History, stalled
from facegear_tehl.ehl.pressure import PressureIteration
from facegear_tehl.ehl.thermal import FilmState, FilmThermalModel, relaxed_steps
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.solution import CONVERGED, Outcome, Status


class Ending(Enum):
    """How an outer loop ended."""

    GOING = "going on"  # not yet (a target's judgement)
    TOLERANCE = "converged to the tolerance"
    FLOOR = "converged to the algebraic floor"
    PROVISIONAL = "ended provisionally"  # an outlet stage whose next stage is certain
    STOPPED = "stopped"  # a seeding stage as good as its grid makes it (not converged, but usable)
    DIVERGED = "diverged"
    FILM_CLOSED = "the film closed"  # the pressure iterate's film closed on its converged frozen state
    EXHAUSTED = "out of outer iterations"


@dataclass
class LoopState:
    """What the loop has done so far, for a target's judgement: this loop's changes of the film state (K, or of
    ln(eta*/eta)) and central films (the target's units), its outer iteration (0-based) and the last
    evaluation of the film state (`update`) and relaxed iterate (`state`)."""

    changes: list[float]
    films: list[float]
    outer: int = 0
    update: FilmState | None = None
    state: FilmState | None = None


@dataclass(frozen=True)
class LoopEnd:
    """The end of an outer loop: how, with which status (the reason of a failure), its last relaxed iterate and
    evaluation of the film state (None if it never updated), and the loop's changes."""

    ending: Ending
    status: Status
    state: FilmState | None
    update: FilmState | None
    changes: tuple[float, ...]


class CoupledTarget(Protocol):
    """What a coupled loop runs on."""

    index: int  # the level of the pressure iteration cycled
    model: FilmThermalModel

    def evaluate(self, temperature: np.ndarray, forcing: float) -> FilmState:
        """The film state at the settled pressure and `temperature` (K), energy sweeps to `forcing` (K)."""

    def constrain(self, temperature: np.ndarray) -> None:
        """Hold what the loop must not move in the next temperatures (K), in place."""

    def freeze(self, state: FilmState) -> None:
        """Freeze the relaxed film state into the flow coefficients."""

    def central_film(self) -> float:
        """h_c after the last cycles, in the target's units."""

    def judge(self, loop: LoopState, status: Status, rise: float) -> tuple[Ending, Status]:
        """Whether the loop has ended after its last cycles (with `status`), the rise (K) its tolerance is relative
        to."""


def film_closed(film: np.ndarray) -> bool:
    """The film closes somewhere (h <= 0): not a film the smooth-film equations have (solve.FILM_CLOSED_MESSAGE)."""
    return bool(film.min() <= 0.0)


def energy_forcing(changes: list[float]) -> float:
    """The share of a loop's last change its next update's energy sweeps stop below: Eisenstat & Walker's (1996,
    SIAM J. Sci. Comput. 17:16-32) choice 2, energy_forcing (c_k/c_k-1)^energy_forcing_exponent over the loop's last
    two changes `changes`, within [min_energy_forcing, energy_forcing]."""
    if len(changes) < 2 or not changes[-2] > 0.0:
        return TUNING.energy_forcing
    ratio = min(changes[-1] / changes[-2], 1.0)
    return max(TUNING.energy_forcing * ratio**TUNING.energy_forcing_exponent, TUNING.min_energy_forcing)


def next_film_state(accelerator: Anderson, temperature: np.ndarray, factor: np.ndarray, update: FilmState,
                    scale: float, rise: float | None,
                    film_step: float = math.inf) -> tuple[np.ndarray, np.ndarray, float, float]:
    """The next layer temperatures (K) and eta*/eta from the current ones and the film state `update` evaluated at
    them, and the largest changes of the plain step at the full relaxation (K; of ln(eta*/eta)). The plain step is
    under-relaxed (thermal_relaxation and viscosity_relaxation times `scale`; eyring_relaxation without the energy
    equation; eta*/eta in log space) and Anderson-accelerated, the temperatures weighted by 1/rise (K) against
    ln(eta*/eta); the accelerated temperatures move by at most max_temperature_step, as a plain update does, and the
    accelerated ln(eta*/eta) by at most `film_step` (the relaxation's Relaxation.film_step: a continuation in eta*). The
    changes returned are those of `scale` 1 (the step over `scale`): a loop whose relaxation a stall halved is judged,
    and its iteration error estimated, by the same measure as before, not by a change the halving alone shrank.
    rise None: no energy equation (the temperatures stay)."""
    if rise is None:  # the change judged stays viscosity_relaxation times the residual: the tolerance keeps its meaning
        log_factor, residual = np.empty(factor.shape), np.empty(factor.shape)
        largest = rheology.log_factor_change(factor, update.viscosity_factor, log_factor, residual)
        step_f = residual * (scale * TUNING.eyring_relaxation)
        stepped = _bounded(accelerator.step(log_factor, step_f), log_factor, film_step)
        return temperature, np.exp(stepped), 0.0, TUNING.viscosity_relaxation * largest
    size = temperature.size
    x, f = np.empty(2 * size), np.empty(2 * size)
    np.log(factor.ravel(), out=x[size:])
    np.log(update.viscosity_factor.ravel(), out=f[size:])
    thermal_change, viscosity_change = relaxed_steps(temperature, update.temperature, scale * TUNING.thermal_relaxation,
                                                     scale * TUNING.viscosity_relaxation, x, f)
    stepped = accelerator.step(x, f, (1.0 / rise, 1.0))
    accelerated = stepped[:size].reshape(temperature.shape)
    step = TUNING.max_temperature_step
    np.clip(accelerated, temperature - step, temperature + step, out=accelerated)
    log_factor = _bounded(stepped[size:], x[size:], film_step)
    return accelerated, np.exp(log_factor).reshape(temperature.shape), thermal_change / scale, viscosity_change / scale


def _bounded(stepped: np.ndarray, before: np.ndarray, film_step: float) -> np.ndarray:
    """ln(eta*/eta) `stepped` within `film_step` of `before` (in place; as it is when unbounded)."""
    if math.isfinite(film_step):
        np.clip(stepped, before - film_step, before + film_step, out=stepped)
    return stepped


class CoupledLoop:
    """The outer loop of one target, from the film state (`temperature` K, `factor` eta*/eta) it starts at."""

    def __init__(self, target: CoupledTarget, pressure: PressureIteration, history: History, max_iterations: int,
                 inlet_temperature: float, floor_ends: bool = True):
        self.target, self.pressure, self.history = target, pressure, history
        self.floor_ends = floor_ends  # a floor ends the loop (else it goes on to max_iterations, for a retry)
        self.max_iterations, self.t_inlet = max_iterations, inlet_temperature
        self.energy = target.model.solve_energy
        depth = TUNING.anderson_depth if self.energy else TUNING.eyring_anderson_depth
        self.accelerator = Anderson(depth)
        self.cycles = TUNING.cycles_per_thermal_update if self.energy else TUNING.cycles_per_eyring_update

    def run(self, temperature: np.ndarray, factor: np.ndarray, cycles: int | None = None) -> LoopEnd:
        """Iterate until the target's judgement ends the loop, it runs away or max_iterations are spent.
        `cycles`: V-cycles per update, if not the model's default."""
        target, loop = self.target, LoopState([], [])
        relaxation, window, last_change = 1.0, 0, None
        cycles = self.cycles if cycles is None else cycles
        for outer in range(self.max_iterations):
            loop.outer = outer
            closed = self._closed_film(outer)
            if closed is not None:
                return self._end(Ending.DIVERGED if closed.diverged else Ending.FILM_CLOSED, closed, loop)
            forcing = energy_forcing(loop.changes) * last_change if last_change is not None else math.inf
            update = target.evaluate(temperature, forcing)
            rise = max(float(temperature.max() - self.t_inlet), TUNING.min_rise)
            temperature, factor, thermal_change, viscosity_change = next_film_state(
                self.accelerator, temperature, factor, update, relaxation, rise if self.energy else None,
                self.pressure.solver.relaxation.film_step)
            target.constrain(temperature)
            last_change = thermal_change if self.energy else viscosity_change
            loop.changes.append(last_change)
            loop.update = update
            if not (np.isfinite(temperature).all() and np.isfinite(factor).all()):
                status = Status(Outcome.DIVERGED, f"diverged in the film temperature at outer iteration {outer + 1}")
                return self._end(Ending.DIVERGED, status, loop)
            loop.state = replace(update, temperature=temperature, viscosity_factor=factor)
            target.freeze(loop.state)
            status = self.pressure.cycle(target.index, cycles)
            self.history.outer += 1
            (self.history.thermal_changes if self.energy else self.history.viscosity_changes).append(last_change)
            if status.diverged:
                return self._end(Ending.DIVERGED, status, loop)
            loop.films.append(target.central_film())
            ending, status = target.judge(loop, status, rise)
            if ending is not Ending.GOING:
                return self._end(ending, status, loop)
            if stalled(loop.changes[window:]):  # a limit cycle above the floor (or h_c unsteady): which one?
                window = len(loop.changes)
                self.accelerator.reset()
                relieved, status = self._relieve_stall(relaxation)
                if status.diverged:
                    return self._end(Ending.DIVERGED, status, loop)
                if relieved is None and self.floor_ends:  # nothing left to relieve: the loop is at its floor
                    self._record_floor(loop.changes)
                    return self._end(Ending.FLOOR, CONVERGED, loop)
                relaxation = relaxation if relieved is None else relieved
        return self._end(Ending.EXHAUSTED, Status(Outcome.NOT_CONVERGED), loop)

    def _relieve_stall(self, relaxation: float) -> tuple[float | None, Status]:
        """The film-state relaxation after the loop's change stopped falling at `relaxation`, and the status of the
        pressure cycled to its tolerance on the frozen film state, which shows the iteration that stalls. Pressure
        V-cycles that do not converge on a frozen film state (their own limit cycle: the film state is then evaluated
        on a different pressure at every update) have their Gauss-Seidel and Jacobi changes damped by
        cycle_damping, down to min_under_gs; a pressure that converges leaves a limit cycle of the film state (the
        hot spot), whose relaxation is halved, down to min_relaxation_scale. None instead of a relaxation where the
        pressure converges and the relaxation is at its limit: the full step stopped contracting at the smallest
        relaxation on a converged pressure, the loop's floor."""
        index, pressure = self.target.index, self.pressure
        status = pressure.cycle(index, pressure.settings.max_cycles)
        solver = pressure.solver
        cycles = solver.relaxation
        if status.converged or status.diverged or cycles.under_gs <= TUNING.min_under_gs:
            halved = max(0.5 * relaxation, TUNING.min_relaxation_scale)
            return (None if halved == relaxation and status.converged else halved), status
        damping = TUNING.cycle_damping
        solver.relaxation = replace(cycles, under_gs=damping * cycles.under_gs, under_jd=damping * cycles.under_jd)
        return relaxation, status

    def _record_floor(self, changes: list[float]) -> None:
        """The loop's floor into the history: the largest full-step change of its last stall window, the amplitude
        its figures' iteration errors carry (error_bounds.iteration_error)."""
        amplitude = max(changes[-TUNING.thermal_floor_window:])
        if self.energy:
            self.history.thermal_floor = amplitude
        else:
            self.history.viscosity_floor = amplitude

    def _closed_film(self, outer: int) -> Status | None:
        """None while the settled film is open (or opens when its pressure is cycled on the frozen film state to its
        tolerance), else the status the loop ends with at outer iteration `outer` (0-based): the film closed, or the
        pressure diverged."""
        index = self.target.index
        if not film_closed(self.pressure.settled_pressure(index)[1]):
            return None
        status = self.pressure.cycle(index, self.pressure.settings.max_cycles)
        if not status.diverged and not film_closed(self.pressure.settled_pressure(index)[1]):
            return None
        if status.diverged:
            return status
        return Status(Outcome.FILM_CLOSED, (
            f"the film closed before outer iteration {outer + 1}, its pressure cycled on the frozen film state "
            f"({status.outcome.value}): no film state is evaluated on a closed film"))

    @staticmethod
    def _end(ending: Ending, status: Status, loop: LoopState) -> LoopEnd:
        return LoopEnd(ending, status, loop.state, loop.update, tuple(loop.changes))
