"""Solve one elliptical EHL contact: ContactPoint + Lubricant + SolverSettings -> PointSolution (SI).

A point solve runs the stages its plan lists (plan.py): the full-multigrid start from the Hertz pressure on the
coarsest grid (start.py; Venner & Lubrecht 2000), then on the finest grid the pressure cycles to tolerance
(pressure.py) and, for a thermal or Ree-Eyring film, the coupled outer loop (coupled.py). From 129^2 up a thermal
solve is a thermal full multigrid: the coupled problem one grid coarser (`begin`, which returns the picklable solve
itself; seeded two grids below from 513 nodes in x), then the finest grid from its interpolated state (`finish`);
`retry.StagedSolver` composes them and may run them in different workers. A `full` solve whose hot spot lies on the
outlet spike's flank adds the outlet patches (outlet.py). The discretisation error is estimated from the solution
one grid coarser (report.py), Richardson-scaled for a second-order scheme: e = (H_h - H_2h)/(2^2 - 1).
"""

from __future__ import annotations

from dataclasses import replace
import math
import time
from typing import NamedTuple

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import grid
from facegear_tehl.ehl.convergence import History, at_thermal_floor, h_c_error, h_c_steady, pressure_settled, stalled
from facegear_tehl.ehl.coupled import CoupledLoop, Ending, LoopState, film_closed
from facegear_tehl.ehl.domain import solution_domain, venner_lubrecht_domain
from facegear_tehl.ehl.energy_balance import energy_failure, energy_unbalanced
from facegear_tehl.ehl.grid_mode import grid_mode
from facegear_tehl.ehl.multigrid import Iterate, Level, MultigridSolver, Problem, Relaxation
from facegear_tehl.ehl.outlet import Composite, needs_outlet_patch, outlet_stages
from facegear_tehl.ehl.plan import SolvePlan, has_coarse_stage, plan_for
from facegear_tehl.ehl.pressure import Best, PressureIteration
from facegear_tehl.ehl.report import FILM_SCALARS, LevelSummary, point_solution, summarise, with_film_state
from facegear_tehl.ehl.retry import POLICY
from facegear_tehl.ehl.scaling import Scaling, scaling_for
from facegear_tehl.ehl.start import hierarchy_shapes, start
from facegear_tehl.ehl.stopwatch import NOTHING_SPENT, Spent, Stopwatch
from facegear_tehl.ehl.thermal import FilmState, FilmThermalModel, thermal_choice
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.record import Action, Reason, RetryRecord, SolveRecord, Stage, StageRecord
from facegear_tehl.settings import OutletRefinement, SolverSettings, ThermalMode
from facegear_tehl.solution import CONVERGED, Outcome, PointSolution, Status

# A smooth-surface EHL film is open at any load (H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k)) > 0,
# Hamrock & Dowson 1977, J. Lubr. Technol. 99:264-276): an iterate whose film closes is not a solution of the
# smooth-film equations but of a grid that does not resolve the film, or of an iteration that failed.
FILM_CLOSED_MESSAGE = ("the film closes on the {} x {} grid (h_min <= 0): not a solution of the smooth-film equations, "
                       "whose film is open at any load; the grid does not resolve it or the iteration failed")


def problem_for(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings, scaling: Scaling) -> Problem:
    """The dimensionless problem of a point on the settings' domain (Venner & Lubrecht's when not set; a solve
    lengthens its inlet first, domain.solution_domain)."""
    domain_x, domain_y = settings.domain_x, settings.domain_y
    if domain_x is None or domain_y is None:
        domain_x, domain_y = venner_lubrecht_domain(scaling)
    return Problem(
        lam=scaling.lam, deflection_coefficient=scaling.deflection_coefficient, ellipticity=scaling.ellipticity,
        geometry_y=scaling.geometry_y, wedge_x=scaling.wedge_x, wedge_y=scaling.wedge_y, p_hertz=scaling.p_h,
        law=lubricant.law_parameters(), inlet_temperature=lubricant.inlet_temperature,
        velocity_1=np.asarray(point.velocity_1) / point.entrainment_speed,
        velocity_2=np.asarray(point.velocity_2) / point.entrainment_speed,
        domain_x=domain_x, domain_y=domain_y,
    )


class StageMark(NamedTuple):
    """Where a stage began: V-cycles, outer iterations, clock (s), work units, and its first entries' places in the
    per-cycle and per-outer-iteration histories."""

    cycles: int
    outer: int
    clock: float
    work: float
    first_cycle: int
    first_outer: int


class PointSolve:
    """One contact point's solve: its inputs, its plan, the multigrid solver with its pressure iteration, the thermal
    model chosen and why, and the bookkeeping every stage adds to (level summaries, history, stage and retry
    records). `begin` runs the solve up to the end of its coarse thermal stage and returns itself (picklable) when a
    fine stage follows, else the solution; `finish` runs the fine stage."""

    def __init__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
                 relaxation: Relaxation | None = None, elapsed: Spent = NOTHING_SPENT, escalate_start: bool = False,
                 attempt: int = 1, max_doublings: int = TUNING.max_inlet_doublings, load_continuation: bool = False):
        """`elapsed`: time already spent on this point (earlier attempts), counted in its wall and CPU time;
        `escalate_start`: a start that runs away begins again from a finer coarsest grid (start.py); `attempt`: which
        attempt at the point this is (1: the first); `max_doublings`: of the inlet (domain.py); `load_continuation`:
        above Moes M = continuation_moes_m the start begins at a fraction of the load; `relaxation`: the attempt's
        on this grid (RetryPolicy.attempt) unless given."""
        self.scaling = scaling_for(point, lubricant)
        self.domain = solution_domain(self.scaling, settings, max_doublings)
        self.point, self.lubricant, self.asked = point, lubricant, settings
        self.settings = settings = self.domain.settings(settings)  # the domain and nodes solved on
        mode, self.reason = thermal_choice(settings.thermal, point, lubricant)
        self.mode = ThermalMode(mode)
        self.coarsest = settings.coarsest_grid  # nodes of the coarsest grid's shorter side (start.py)
        fraction = TUNING.continuation_moes_m / self.scaling.moes_m
        self.start_load_fraction = min(1.0, fraction) if load_continuation else 1.0
        problem = problem_for(point, lubricant, settings, self.scaling)
        shapes = hierarchy_shapes(settings, self.coarsest, problem, self.start_load_fraction < 1.0)
        self.spacing = (problem.domain_x[1] - problem.domain_x[0]) / (shapes[-1][0] - 1)  # X = x/b, finest grid
        if relaxation is None:
            relaxation = POLICY.attempt(attempt, self.spacing).relaxation
        self.pressure = PressureIteration(MultigridSolver(problem, shapes, relaxation), settings,
                                          History(cycles=settings.cycles_per_level))
        if self.mode is ThermalMode.REDUCED and not has_coarse_stage(shapes):  # its coupled loop is full's
            self.mode = ThermalMode.FULL
            below = f"{shapes[-2][0]} nodes" if len(shapes) > 1 else "no grid"
            self.reason += (f"; solved full: reduced freezes the coupled state of the grid below the finest, which "
                            f"needs {TUNING.min_coarse_thermal_grid} nodes along x or more ({below} here)")
        self.plan: SolvePlan = plan_for(shapes, self.mode, self.coupled, settings, point.entrainment_angle)
        self.summaries: list[LevelSummary] = []
        self.coarse_state: FilmState | None = None  # the film state of the coarse thermal stage
        self.loop_ending: Ending | None = None  # how the last coupled loop (`couple`) ended
        self.escalate_start, self.attempt = escalate_start, attempt
        self.load_reached = 1.0  # of the load, by the start's last level (start.py: below 1 if its continuation failed)
        self.stages: list[StageRecord] = []
        self.retries: list[RetryRecord] = []
        self.outlet: Composite | None = None  # the outlet stage's composite solution (outlet.py), when it ran
        self.outlet_note = ""  # why the outlet stage was not reported (it ran away or did not converge)
        self.elapsed = elapsed  # spent up to the last pause (a solve paused between stages has no clock)
        self._clock = Stopwatch(elapsed)

    @property
    def solver(self) -> MultigridSolver:
        return self.pressure.solver

    @solver.setter
    def solver(self, solver: MultigridSolver) -> None:
        self.pressure.solver = solver

    @property
    def history(self) -> History:
        return self.pressure.history

    @property
    def coupled(self) -> bool:
        """The film state is iterated with the pressure (thermal, or an isothermal Ree-Eyring film)."""
        return self.mode is not ThermalMode.OFF or self.lubricant.rheology == "ree_eyring"

    def cycle(self, index: int, max_cycles: int, best: Best | None = None) -> Status:
        """The pressure iteration on level `index` (pressure.PressureIteration.cycle)."""
        return self.pressure.cycle(index, max_cycles, best)

    # ------------------------------------------------------------------ stages
    def begin(self) -> PointSolution | PointSolve:
        """The solve up to the end of its coarse thermal stage (self, to be finished), or the whole solve when
        it has no separate fine stage or the coarse stage failed."""
        if self.plan.has(Stage.COARSE):
            return self._coarse_thermal_stage()
        return self._solve_finest()

    def finish(self) -> PointSolution:
        """The fine stage of a thermal full-multigrid solve: the coarse solution and film state interpolated
        and frozen on the finest grid, its pressure converged; `reduced` evaluates the film state once there,
        `full` couples again on the finest grid. A finest grid that runs away reports the converged coarse
        solution."""
        self._clock = Stopwatch(self.elapsed)
        solver, top = self.solver, len(self.solver.levels) - 1
        coarse = solver.levels[top - 1]
        # the coarse level, now with its film state (its dT_max and mu give the fine grid's error estimates)
        self.summaries[-1] = with_film_state(summarise(coarse), coarse, self.coarse_state, self.scaling,
                                             self.point.load, self.lubricant.inlet_temperature)
        mark = self._mark()
        saved = solver.snapshot(top - 1)
        frozen, status = self._start_fine_grid(top)
        if status.diverged:
            self._stage_done(Stage.FINEST, top, status, mark)
            solver.restore(top - 1, saved)
            solver.set_film_state(top - 1, self.coarse_state.temperature, self.coarse_state.viscosity_factor)
            message = f"finest grid: {status.message}; the result is the {coarse.nx}^2 solution"
            return self.report(top - 1, Status(Outcome.DIVERGED, message), self.coarse_state)
        if self.mode is ThermalMode.REDUCED:
            fine = solver.levels[top]
            state = self._film_model(fine).update(fine.pressure * self.scaling.p_h,
                                                  fine.film * self.scaling.film_scale, frozen.temperature)
        else:
            state, status = self.couple(top, frozen, self.summaries[-1].h_c)
        self.summaries.append(summarise(solver.levels[top]))
        self._stage_done(Stage.FINEST, top, status, mark)
        if self.mode is ThermalMode.FULL and status.converged and needs_outlet_patch(self, top, state):
            mark = self._mark()
            self.outlet, self.outlet_note = outlet_stages(self, top, state)
            self._stage_done(Stage.OUTLET, top, CONVERGED if self.outlet else Status(Outcome.NOT_CONVERGED), mark)
        return self.report(top, status, state)

    def _coarse_thermal_stage(self) -> PointSolution | PointSolve:
        """Thermal full multigrid, first stage: the coupled problem one grid coarser than the finest (`reduced`
        stops after the fine stage's single film-state evaluation, `full` couples again there). The isothermal
        pressure is cycled first; its tolerance is not required, the coupled loop goes on from where it got. A plan
        with a seed stage starts from that stage's state instead."""
        seeded = self._seed_stage() if self.plan.has(Stage.SEED) else None
        seed = None if seeded is None else seeded[0]
        if seeded is None:
            index, status = self.start(below_top=1)
            mark = self._mark()
            if status.converged:
                self.cycle(index, self.settings.max_cycles)
        else:
            index, status, mark = len(self.solver.levels) - 2, CONVERGED, seeded[1]
        state = None
        if status.converged:
            state, status = self.couple(index, seed, math.nan if seed is None else self.summaries[-1].h_c)
            if seed is not None:  # this level's summary, after the seed stage's (the full-multigrid start's are below)
                self.summaries.append(summarise(self.solver.levels[index]))
            self._stage_done(Stage.COARSE, index, status, mark)
            closed = status.outcome is Outcome.FILM_CLOSED
            if state is not None and not status.diverged and not closed and not self.coarse_stage_stalled():
                self.coarse_state = state
                self.elapsed = self._clock.spent()
                return self
            if POLICY.couples_on_finest(self.attempt, closed):
                return self._couple_on_finest(status)
        return self.report(index, status, state)

    def coarse_stage_stalled(self) -> bool:
        """The coarse stage's loop spent max_thermal_iterations short of its tolerance on an attempt before the
        damped one: the attempt stalled (retry.RetryPolicy.next_attempt goes on with the damped one) without the finest
        grid from that state, whose loop met the same limit cycle on every such attempt measured (docs/tuning.md)."""
        return self.loop_ending is Ending.EXHAUSTED and not POLICY.couples_on_finest(self.attempt)

    def _seed_stage(self) -> tuple[FilmState, StageMark] | None:
        """The coupled problem two grids below the finest to seed_stage_limit of the rise, its solution and film
        state interpolated to the next grid and cycled there; returns the frozen state there and the coarse stage's
        mark, taken before those cycles, or None (the solver begun again from the coarsest grid) when the stage ran
        away."""
        reached, status = self.start(below_top=2)
        index = len(self.solver.levels) - 3  # (a start that began again from a finer coarsest grid has fewer levels)
        mark = self._mark()
        if status.converged and reached == index:
            self.cycle(index, self.settings.max_cycles)
            state, status = self.couple(index)
            self._stage_done(Stage.SEED, index, status, mark)
            if state is not None and not status.diverged and status.outcome is not Outcome.FILM_CLOSED:
                level = self.solver.levels[index]  # its summary with its film state: the third grid of dT and mu
                self.summaries[-1] = with_film_state(summarise(level), level, state, self.scaling, self.point.load,
                                                     self.lubricant.inlet_temperature)
                coarse_mark = self._mark()
                frozen, status = self._interpolated_state(index + 1, state, TUNING.cycles_per_thermal_update)
                if not status.diverged:
                    return frozen, coarse_mark
        reason = Reason.SEED_FILM_CLOSED if status.outcome is Outcome.FILM_CLOSED else Reason.SEED_RAN_AWAY
        self.retries.append(RetryRecord(reason, Action.COARSEST_GRID_AGAIN, self.attempt, status.message))
        self.new_hierarchy(self.hierarchy(self.coarsest))
        return None

    def _couple_on_finest(self, status: Status) -> PointSolution:
        """After the coarse thermal stage ran away or closed its film with `status`, the coupled problem on the finest
        grid alone, from its converged isothermal solution: the grid below the finest may not hold a film the finest
        resolves."""
        level = self.solver.levels[-2]
        reason = (Reason.COARSE_STAGE_FILM_CLOSED if status.outcome is Outcome.FILM_CLOSED
                  else Reason.COARSE_STAGE_RAN_AWAY)
        self.retries.append(RetryRecord(reason, Action.COUPLED_ON_FINEST, self.attempt,
                                        f"{level.nx} x {level.ny}: {status.message}"))
        self.new_hierarchy(self.hierarchy(self.coarsest))
        return self._solve_finest()

    def _solve_finest(self) -> PointSolution:
        """Full multigrid to the finest grid, cycles to tolerance there, then (thermal or Ree-Eyring films) the
        outer loop there. An isothermal Newtonian solve that does not converge reports its best iterate."""
        index, status = self.start(below_top=0)
        mark = self._mark()
        best = None if self.coupled else Best(math.inf, self.solver.snapshot(index))
        state = None
        if status.converged:
            # an isothermal Ree-Eyring film's loop starts from the full-multigrid start: its own V-cycles converge
            # the pressure while eta*/eta moves it
            if self.mode is not ThermalMode.OFF or not self.coupled:
                status = self.cycle(index, self.settings.max_cycles, best)
            if self.coupled and not status.diverged:
                state, status = self.couple(index)
            self._stage_done(Stage.FINEST, index, status, mark)
        if best is not None and not status.converged:
            self.solver.restore(index, best.iterate)  # the best iterate, not the last (it may be running away)
        return self.report(index, status, state)

    def start(self, below_top: int) -> tuple[int, Status]:
        """The full-multigrid start (start.py) up to `below_top` levels below the finest, recorded as a stage."""
        mark = self._mark()
        index, status = start(self, below_top)
        self._stage_done(Stage.START, index, status, mark)
        return index, status

    def hierarchy(self, coarsest: int) -> list[tuple[int, int]]:
        """The grids of the solve from `coarsest` nodes up, coarsest first (start.hierarchy_shapes: along the strongly
        coupled axes alone for a start at a fraction of the load)."""
        return hierarchy_shapes(self.settings, coarsest, self.solver.problem, self.start_load_fraction < 1.0)

    def new_hierarchy(self, shapes: list[tuple[int, int]]) -> None:
        """A new multigrid solver on `shapes` (coarsest first), summaries and history begun again; the work done so
        far is kept in the count."""
        work = self.solver.work_units
        self.solver = MultigridSolver(self.solver.problem, shapes, self.solver.relaxation)
        self.solver.work_units = work
        self.summaries = []
        self.pressure.history = History(cycles=self.settings.cycles_per_level)
        # the stages so far are not in the history begun again
        self.stages = [replace(s, first_cycle=-1, first_outer=-1) for s in self.stages]

    # ------------------------------------------------------------------ the coupled loop on a uniform grid
    def couple(self, index: int, initial: FilmState | None = None,
               coarse_h_c: float = math.nan) -> tuple[FilmState | None, Status]:
        """Outer loop of the film state and the pressure on level `index`, from `initial` (default: the inlet
        temperature and a Newtonian film). If the iteration runs away, the last finite iterate (at worst the
        entry state) is restored and reported with the reason. coarse_h_c: the dimensionless h_c one grid
        coarser, for the discretisation error the thermal floor is judged against."""
        model = self._film_model(self.solver.levels[index])
        temperature = model.initial_temperature() if initial is None else initial.temperature
        factor = np.ones_like(temperature) if initial is None else initial.viscosity_factor
        target = UniformTarget(self, index, model, initial, coarse_h_c)
        floor_ends = self.attempt >= TUNING.damped_attempt  # before it a floor is a stall the damped attempt may pass
        end = CoupledLoop(target, self.pressure, self.history, self.settings.max_thermal_iterations,
                          self.lubricant.inlet_temperature, floor_ends).run(temperature, factor)
        self.loop_ending = end.ending
        if end.ending in (Ending.TOLERANCE, Ending.FLOOR, Ending.STOPPED):
            if end.ending is not Ending.STOPPED:
                self.pressure.settle(index)
            return model.completed(end.state), end.status
        if end.ending is Ending.FILM_CLOSED:  # no film state on a closed film: the grid does not resolve it
            return model.completed(end.state), end.status
        if end.ending is Ending.DIVERGED:
            iterate, state = target.last_finite
            return model.completed(self._last_finite(index, model, initial, iterate, state)), end.status
        what = ("thermal loop not converged after {} outer iterations: temperature change {:.2e} K (tolerance {:.0e} "
                "of the rise)" if model.solve_energy else
                "Ree-Eyring loop not converged after {} outer iterations: largest change of ln(eta*/eta) {:.2e} "
                "(tolerance {:.0e})")
        return model.completed(end.state), Status(Outcome.NOT_CONVERGED, (
            what.format(self.settings.max_thermal_iterations, end.changes[-1], target.tolerance)
            + f", last pressure change {self.history.changes[-1]:.2e}"))

    def _last_finite(self, index: int, model: FilmThermalModel, initial: FilmState | None, iterate: Iterate,
                     state: FilmState | None) -> FilmState | None:
        """Restore the last finite iterate of the outer loop on level `index` with its film state; returns the
        state to report (an interpolated entry state evaluated on this grid)."""
        solver = self.solver
        solver.restore(index, iterate)
        if state is None:
            solver.set_film_state(index, None, None)
            return None
        solver.set_film_state(index, state.temperature, state.viscosity_factor)
        if state is initial:  # an interpolated state: evaluate it on this grid for the outputs
            level = solver.levels[index]
            return model.update(level.pressure * self.scaling.p_h, level.film * self.scaling.film_scale,
                                initial.temperature)
        return state

    def _start_fine_grid(self, index: int) -> tuple[FilmState, Status]:
        """Interpolate the coarse solution and film state to the finest grid, freeze the state on every grid and
        cycle the pressure against it: `full` cycles_per_thermal_update times (its outer loop goes on from there),
        else to convergence. Returns (frozen state, status)."""
        cycles = TUNING.cycles_per_thermal_update if self.mode is ThermalMode.FULL else self.settings.max_cycles
        return self._interpolated_state(index, self.coarse_state, cycles)

    def _interpolated_state(self, index: int, coarse_state: FilmState, cycles: int) -> tuple[FilmState, Status]:
        """Level `index` from the solution one grid coarser, its film state `coarse_state` interpolated (ln(eta*/eta)
        bilinearly) and frozen on every grid, then `cycles` V-cycles on the pressure; returns (frozen state,
        status)."""
        solver = self.solver
        solver.interpolate_up(index)
        frozen = replace(coarse_state, temperature=solver.prolong_layers(index, coarse_state.temperature),
                         viscosity_factor=np.exp(solver.prolong_layers(index, np.log(coarse_state.viscosity_factor))))
        solver.set_film_state(index, frozen.temperature, frozen.viscosity_factor)
        return frozen, self.cycle(index, cycles)

    def _film_model(self, level: Level) -> FilmThermalModel:
        """The film model of `level`: its columns below the Newtonian bound r_N = sqrt(6 share eyring_tolerance) taken
        as Newtonian (ln(eta*/eta) off by at most r_N^2/6, a share of the change of ln(eta*/eta) an isothermal
        Ree-Eyring loop stops at; a thermal loop stops at about 1e-3 in ln(eta) too: 2e-3 of a rise of 20-50 K at
        beta = 0.02-0.03 1/K)."""
        newtonian_below = math.sqrt(6.0 * TUNING.eyring_newtonian_share * self.settings.eyring_tolerance)
        if self.mode is not ThermalMode.OFF:
            return FilmThermalModel(level.x * self.scaling.b, level.y * self.scaling.a, self.settings.thermal_layers,
                                    self.lubricant, self.point, solve_energy=True, newtonian_below=newtonian_below)
        return FilmThermalModel(level.x * self.scaling.b, level.y * self.scaling.a, TUNING.eyring_layers,
                                self.lubricant, self.point, solve_energy=False, newtonian_below=newtonian_below)

    # ------------------------------------------------------------------ record and report
    def _mark(self) -> StageMark:
        """The counts a stage record is measured from."""
        history = self.history
        return StageMark(history.cycles, history.outer, time.perf_counter(), self.solver.work_units,
                         len(history.changes), len(history.thermal_changes) + len(history.viscosity_changes))

    def _stage_done(self, stage: Stage, index: int, status: Status, mark: StageMark) -> None:
        level, history = self.solver.levels[index], self.history
        self.stages.append(StageRecord(stage, level.nx, level.ny, max(history.cycles - mark.cycles, 0),
                                       max(history.outer - mark.outer, 0), status.outcome,
                                       time.perf_counter() - mark.clock, self.solver.work_units - mark.work,
                                       mark.first_cycle, mark.first_outer))

    def record(self, iteration: Outcome) -> SolveRecord:
        """The solve record so far; `iteration`: how the iteration ended before a closed film was checked."""
        notes = [self.domain.note(self.asked)]
        if (self.mode is ThermalMode.FULL and not self.plan.has(Stage.COARSE)
                and self.settings.outlet_refinement == OutletRefinement.ALWAYS):
            notes.append(f"outlet refinement 'always' not run: it refines the finest grid after a coarse stage, which "
                         f"needs at least {TUNING.min_coarse_thermal_grid} nodes along x one grid below the finest")
        if self.outlet is not None:
            notes.append(f"outlet refined: {self.outlet.note} (FAS composite grid, the film state solved on each)")
        if self.start_load_fraction < 1.0:
            notes.append(f"full-multigrid start at {self.start_load_fraction:.3g} of the load (Moes M "
                         f"{self.scaling.moes_m:.3g}), raised to the full load in steps the iteration holds")
        # named by the attempt, on the switch it runs (staged.finest_again keeps the coarse stage's; a stalled loop's
        # damping of the cycles, coupled.py, leaves the name as it is)
        attempt = POLICY.attempt(self.attempt, self.spacing)
        switch = self.solver.relaxation.scale_switch
        attempt = replace(attempt, relaxation=replace(attempt.relaxation, scale_switch=switch))
        return SolveRecord(self.plan.describe(), tuple(self.stages), tuple(self.retries), self.attempt, attempt.name,
                           iteration, tuple(note for note in notes if note))

    def report(self, index: int, status: Status, state: FilmState | None) -> PointSolution:
        """The PointSolution of level `index`; a film that closes (h_min <= 0) is never reported as converged, nor one
        whose rows or columns alternate node to node (grid_mode.py: reported as an iteration that ran away), nor a
        thermal film state whose energy balance misses (energy_balance.py: reported as a loop that stopped short)."""
        level = self.solver.levels[index]
        iteration = status.outcome
        if film_closed(level.film):
            message = FILM_CLOSED_MESSAGE.format(level.nx, level.ny)
            message += "; " + status.message if status.message else ""
            status = Status(Outcome.DIVERGED if status.diverged else Outcome.FILM_CLOSED, message)
        elif status.converged and (mode := grid_mode(level.film, level.pressure)) is not None:
            status = Status(Outcome.DIVERGED, mode.message(level.nx, level.ny))
        solution = point_solution(self, level, status, state, self._clock.spent(), self.record(iteration))
        if energy_unbalanced(solution):
            solution = replace(solution, outcome=Outcome.NOT_CONVERGED, message=energy_failure(solution))
        if self.load_reached < 1.0:  # its film is that of a lighter contact: not this one's
            return self._lighter_contact(solution)
        return solution

    def _lighter_contact(self, solution: PointSolution) -> PointSolution:
        """A solution whose start did not reach the full load: no film nor fields (they are a lighter contact's),
        only where its lowest film lies (as where a film closed: the way a finer grid must resolve it)."""
        scalars = {k: v for k, v in solution.scalars.items() if k not in FILM_SCALARS}
        for axis in ("x", "y"):
            if f"{axis}_h_min" in solution.scalars:
                scalars[f"{axis}_film_closed"] = solution.scalars[f"{axis}_h_min"]
        return replace(solution, scalars=scalars, fields={}, message=(
            f"{solution.message}; its iterate carries {self.load_reached:.3g} of the load: no film is reported"))

    def __getstate__(self) -> dict:
        """Between stages the solve travels to another process: its clock does not (see `elapsed`)."""
        return {k: v for k, v in self.__dict__.items() if k != "_clock"}


class UniformTarget:
    """The coupled loop on level `index` of a point solve's uniform hierarchy (coupled.CoupledTarget). A loop below
    the finest grid of a `full` solve seeds the next one: the coarse stage stops at coarse_stage_tolerance times the
    tolerance (at most coarse_stage_limit of the rise), the seed stage at seed_stage_limit of the rise, neither
    waiting for a steady h_c."""

    def __init__(self, solve: PointSolve, index: int, model: FilmThermalModel, initial: FilmState | None,
                 coarse_h_c: float):
        self.solve, self.index, self.model = solve, index, model
        top = len(solve.solver.levels) - 1
        self.seeding = solve.mode is ThermalMode.FULL and index < top
        self.coarse_stage = self.seeding and index == top - 1
        self.coarse_h_c = coarse_h_c * solve.scaling.film_scale
        settings = solve.settings
        self.tolerance = settings.thermal_tolerance if model.solve_energy else settings.eyring_tolerance
        self.factors = None  # the temperature factors set_film_state evaluated for the frozen state
        self.cycled_out = False  # the pressure was cycled to its tolerance on a converged film state (judge)
        self.last_finite: tuple[Iterate, FilmState | None] = (solve.solver.snapshot(index), initial)

    def evaluate(self, temperature: np.ndarray, forcing: float) -> FilmState:
        pressure, film = self.solve.pressure.settled_pressure(self.index)
        scaling = self.solve.scaling
        return self.model.update(pressure * scaling.p_h, film * scaling.film_scale, temperature, forcing,
                                 wall_fluxes=False, temperature_factor=self.factors)

    def constrain(self, temperature: np.ndarray) -> None:
        """Nothing is held on a uniform grid."""

    def freeze(self, state: FilmState) -> None:
        solver = self.solve.solver
        solver.set_film_state(self.index, state.temperature, state.viscosity_factor)
        self.factors = solver.levels[self.index].temperature_factor

    def central_film(self) -> float:
        """h_c (m) at the settled pressure, also recorded in the history."""
        level = self.solve.solver.levels[self.index]
        film = self.solve.pressure.settled_pressure(self.index)[1]
        h_c = grid.bilinear_at(film, level.x, level.y, 0.0, 0.0) * self.solve.scaling.film_scale
        self.solve.history.thermal_h_c.append(h_c)
        return h_c

    def judge(self, loop: LoopState, status: Status, rise: float) -> tuple[Ending, Status]:
        """The tolerance stop (the last change below tolerance, the pressure converged, h_c steady over
        steady_updates unless seeding) or the thermal floor (convergence.at_thermal_floor); a converged film state
        whose pressure has not converged cycles the pressure to tolerance once (a seeding stage whose pressure then
        stalls stops there)."""
        solve, changes = self.solve, loop.changes
        self.last_finite = (solve.solver.snapshot(self.index), loop.state)
        tolerance, floor_bound = self._bounds(rise)
        settled = changes[-1:] if self.seeding else changes[-2:]
        if loop.outer > 0 and not status.converged and not self.cycled_out and max(settled) < tolerance:
            self.cycled_out = True
            status = solve.cycle(self.index, solve.settings.max_cycles)
            if status.diverged:
                return Ending.DIVERGED, status
            if self.seeding and not status.converged and stalled(solve.history.changes):
                return Ending.STOPPED, Status(Outcome.NOT_CONVERGED, (
                    f"coarse stage stopped at outer iteration {loop.outer + 1}: film state within {tolerance:.2e} of "
                    f"its last two updates, pressure stalled at {solve.history.changes[-1]:.2e} per cycle"))
        coarse_error = h_c_error(loop.films[-1], self.coarse_h_c)
        steady = self.seeding or (len(loop.films) >= TUNING.steady_updates and h_c_steady(
            loop.films[-TUNING.steady_updates:], coarse_error))
        if loop.outer > 0 and status.converged and changes[-1] < tolerance and steady:
            return Ending.TOLERANCE, CONVERGED
        if ((status.converged or pressure_settled(solve.history, solve.settings))
                and at_thermal_floor(changes, loop.films, floor_bound, coarse_error)):
            if self.model.solve_energy:
                solve.history.thermal_floor = changes[-1]
            else:
                solve.history.viscosity_floor = changes[-1]
            return Ending.FLOOR, CONVERGED
        return Ending.GOING, status

    def _bounds(self, rise: float) -> tuple[float, float]:
        """The loop's tolerance and floor bound (K, or of ln(eta*/eta))."""
        if self.model.solve_energy:
            tolerance, floor_bound = self.tolerance * rise, TUNING.thermal_floor_fraction * rise
        else:
            tolerance, floor_bound = self.tolerance, TUNING.floor_band * self.tolerance
        if self.coarse_stage:
            tolerance = min(TUNING.coarse_stage_tolerance * tolerance, TUNING.coarse_stage_limit * rise)
        elif self.seeding:
            tolerance = max(TUNING.seed_stage_limit * rise, tolerance)
        return tolerance, floor_bound
