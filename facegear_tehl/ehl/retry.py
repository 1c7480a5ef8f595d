"""The retry policy of a point solve: which typed failure leads to which next attempt, in which order, with what
budget. Every remedy the solve has is decided here; the stages only ask.

In the order a failing solve meets them:
1. the start runs away (a heavy load's film and spike are not resolved by coarse grids): on a retry, the start is
   begun again from a coarsest grid twice as fine, as long as the hierarchy keeps the levels asked for (start.py);
2. the seed stage runs away or its film closes: the coarse stage begins again from the coarsest grid (solve.py);
3. the coarse thermal stage runs away on a damped attempt, or its film closes on any attempt: the coupled problem is
   solved on the finest grid alone, from its converged isothermal solution (the grid below the finest may not hold a
   film the finest resolves);
4. an outlet stage fails: solved again with more V-cycles of the grid below per correction
   (`stage_coarse_cycles`); a stage that fails on top of a provisional one has the stages below it solved again to
   convergence; a stage that fails for good is dropped and the solution below it reported (outlet.py);
5. the whole attempt runs away, stalls short of its tolerances or closes its film: the next of ATTEMPTS
   (`next_attempt`): the ellipse-scaled Gauss-Seidel / Jacobi switch, Venner's switch (the two swapped on a grid
   with fewer than venner_first_nodes across the contact: `attempt`), that damped, and for a
   heavily loaded point that damped from a start at a fraction of its load, raised in steps the pressure iteration
   converges, on a hierarchy that coarsens only the strongly coupled axes (load continuation, start.py); an attempt
   whose coarse stage converged and whose finest grid failed has that grid solved again from its coarse stage first,
   with the next attempt's under-relaxation that differs from the failed one, on the coarse stage's switch
   (`finest_again`); a point without the continued start whose damped attempt ran away at the first film-state
   updates of its isothermal Ree-Eyring loop, the first made at the Newtonian pressure of the start, has one more:
   that damped attempt with ln(eta*/eta) moved by at most rescue_film_step per update (`RESCUE`, `rescues`), a path
   only a solve that fails otherwise takes;
6. the grid does not resolve the film (it closes, a start's load continuation stops short of the load, or an
   estimate exceeds its bound): the point is solved again on a finer grid, up to a cap (`finer_settings`, run.py),
   twice the rows alone where the film closes in a side lobe;
   of a point whose attempts all failed, where it closes is read on the finest grid an attempt was reported on
   (`closure_place`), not on a runaway start's coarse level.
The measurements behind each choice are in docs/tuning.md.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math

from facegear_tehl.ehl.relaxation import Relaxation
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.record import Reason, Stage
from facegear_tehl.settings import SolverSettings, ThermalMode
from facegear_tehl.solution import Outcome, PointSolution

CLOSURE_PLACE = ("x_film_closed", "y_film_closed")  # where a reported iterate's film is lowest (report.py)


@dataclass(frozen=True)
class Attempt:
    """One attempt at a point: the relaxation of its multigrid cycles and whether its start begins at a fraction of
    the load (above Moes M = continuation_moes_m)."""

    relaxation: Relaxation
    load_continuation: bool = False

    @property
    def name(self) -> str:
        """The words its solve record names it by."""
        return self.relaxation.describe() + (", from a fraction of the load" if self.load_continuation else "")


DAMPED = Relaxation(scale_switch=False, under_gs=0.15, under_jd=0.1)  # Gauss-Seidel halved, Jacobi 0.15 -> 0.1
ATTEMPTS = (
    Attempt(Relaxation()),  # the ellipse-scaled switch
    Attempt(Relaxation(scale_switch=False)),  # Venner's switch
    Attempt(DAMPED),
    Attempt(DAMPED, load_continuation=True),
)
# after all of ATTEMPTS a point takes, where its damped attempt ran away at its first film-state update (`rescues`)
RESCUE = Attempt(replace(DAMPED, film_step=TUNING.rescue_film_step))


@dataclass(frozen=True)
class RetryPolicy:
    """The one retry policy (see the module's list)."""

    attempts: tuple[Attempt, ...] = ATTEMPTS
    rescue: Attempt = RESCUE  # numbered after `attempts`

    @property
    def rescue_attempt(self) -> int:
        """The number (1-based) of the rescue attempt: the one after `attempts`."""
        return len(self.attempts) + 1

    def numbered(self, attempt: int) -> Attempt:
        """Attempt `attempt` (1-based) as listed: one of `attempts`, or the rescue after them."""
        return self.rescue if attempt == self.rescue_attempt else self.attempts[attempt - 1]

    def carries(self, attempt: int) -> bool:
        """Attempt `attempt`, converged, is where a path's next check begins (seeded.CheckPath): one of `attempts`
        without the continued start; not the rescue, which no attempt that converges otherwise reaches."""
        return attempt < self.rescue_attempt and not self.attempts[attempt - 1].load_continuation

    def attempt(self, attempt: int, spacing: float) -> Attempt:
        """Attempt `attempt` (1-based) on a finest grid of X spacing `spacing` (X = x/b): as listed, but on a grid
        with fewer than venner_first_nodes across the Hertzian width 2b the first two swap, Venner's switch first.
        There the ellipse-scaled switch leaves the inlet's nodes up to eps ~ 1 to Jacobi-distributive relaxation and
        stalls where Venner's converges; on finer grids Venner's runs away where the scaled one converges."""
        if attempt <= 2 and spacing > 2.0 / TUNING.venner_first_nodes:
            return self.attempts[2 - attempt]
        return self.numbered(attempt)

    # --- within an attempt
    def escalates_start(self, attempt: int) -> bool:
        """A start that runs away begins again from a finer coarsest grid: on every retry."""
        return attempt > 1

    def couples_on_finest(self, attempt: int, film_closed: bool = False) -> bool:
        """A coarse thermal stage that runs away is followed by the coupled problem on the finest grid alone: from
        the damped attempt on (the attempts before it are where the points that converge do so); one whose film
        closed (coupled.CoupledLoop) on every attempt: the grid below the finest did not resolve the film, the finest
        may."""
        return film_closed or attempt >= TUNING.damped_attempt

    # --- between attempts
    def next_attempt(self, solution: PointSolution) -> int | None:
        """The attempt (1-based) after `solution`'s, or None: the next relaxation after one that ran away; the damped
        one after an undamped attempt's stall (a limit cycle), and after a retry's film that closed in a stall; for a
        point above Moes M = continuation_moes_m the start at a fraction of the load after a damped attempt that ran
        away or closed the film, or a retry whose film closed in a converged iteration. The first attempt's closed
        film is left to a finer grid (`finer_settings`). After the attempts, the rescue where `rescues` says so."""
        following = self._listed_next(solution)
        return self.rescue_attempt if following is None and self.rescues(solution) else following

    def _listed_next(self, solution: PointSolution) -> int | None:
        """The attempt of `attempts` after `solution`'s, or None (`next_attempt`)."""
        attempt = int(solution.scalar("attempts"))
        if solution.outcome is Outcome.DIVERGED:
            following = attempt + 1
        elif solution.outcome is Outcome.NOT_CONVERGED:  # a damped attempt's stall is reported as it is
            following = TUNING.damped_attempt
        elif solution.outcome is Outcome.FILM_CLOSED and attempt > 1:  # a retry's film closed: in a stall, as a stall
            in_stall = solution.record is not None and solution.record.iteration is not Outcome.CONVERGED
            following = max(attempt + 1, TUNING.damped_attempt) if in_stall else len(self.attempts)
        else:
            return None
        if following <= attempt or following > len(self.attempts):
            return None
        heavy = solution.scalar("moes_m") > TUNING.continuation_moes_m
        return following if heavy or not self.attempts[following - 1].load_continuation else None

    @staticmethod
    def rescues(solution: PointSolution) -> bool:
        """`solution`, with no listed attempt after it, is the damped attempt of an isothermal Ree-Eyring film that ran
        away in the V-cycles after one of its loop's first rescue_updates film-state updates. The first update is made
        at the Newtonian pressure of the full-multigrid start, whose spike under an exponential viscosity asks for an
        eta*/eta many e-folds below the film's fixed point: the rescue moves ln(eta*/eta) there by a bounded step per
        update (RESCUE). Every attempt before it is as it was."""
        record = solution.record
        if (solution.outcome is not Outcome.DIVERGED or record is None or not record.stages
                or int(solution.scalar("attempts")) != TUNING.damped_attempt
                or solution.models.get("thermal", "off") != ThermalMode.OFF.value):
            return False
        last = record.stages[-1]
        return (last.stage is Stage.FINEST and last.outcome is Outcome.DIVERGED
                and 1 <= last.outer <= TUNING.rescue_updates)

    def finest_again(self, solution: PointSolution, relaxation: Relaxation,
                     spacing: float) -> tuple[int, Relaxation] | None:
        """The attempt (1-based) and relaxation that solve the finest grid again from the converged coarse stage of
        `solution`, whose finest grid failed (ran away, stalled or closed its film) with `relaxation` at X spacing
        `spacing`: the first attempt from the policy's next one (`next_attempt`) whose under-relaxation, on the switch
        the coarse stage converged with, differs from `relaxation`; else None (the same relaxation from the same
        state is the same iteration). The coarse stage's solution and film state are sound, the failure is the
        finest grid's iteration: a whole new attempt would begin again from the coarsest grid, whose start and seed
        stage the point already got through once."""
        following = self.next_attempt(solution)
        if following is None or solution.record is None:
            return None
        stages = {s.stage: s.outcome for s in solution.record.stages}
        if stages.get(Stage.COARSE) is not Outcome.CONVERGED or stages.get(Stage.FINEST) is Outcome.CONVERGED:
            return None
        for attempt in range(following, len(self.attempts) + 1):
            again = replace(self.attempt(attempt, spacing).relaxation, scale_switch=relaxation.scale_switch)
            if again != relaxation:
                return attempt, again
        return None

    @staticmethod
    def reason(solution: PointSolution) -> Reason:
        """The typed failure of an attempt that is retried."""
        return {Outcome.DIVERGED: Reason.RAN_AWAY, Outcome.NOT_CONVERGED: Reason.STALLED}.get(
            solution.outcome, Reason.FILM_CLOSED)

    @staticmethod
    def closure_place(first: PointSolution, retry: PointSolution) -> dict[str, tuple[float, str]]:
        """Where the film of a point whose attempts failed closed, for the way a finer grid must resolve it
        (`finer_settings`): the place on the finer of the grids the first attempt and the last retry are reported on.
        A first attempt whose start ran away is reported on the start's coarse level, where the film closes wherever
        that grid fails to carry the load; an attempt that reached the finest grid shows where the film of the grid
        asked for closes. Empty when the retry's grid is not finer or it did not close its film, or the first attempt
        has a film (kept as it is)."""
        if "h_min" in first.scalars or reported_nodes(retry) <= reported_nodes(first):
            return {}
        return {key: retry.scalars[key] for key in CLOSURE_PLACE if key in retry.scalars}

    @staticmethod
    def better(first: PointSolution, retry: PointSolution) -> bool:
        """The retry did better than the first attempt: converged after a stall, or anything but running away."""
        if first.outcome is Outcome.NOT_CONVERGED:
            return retry.outcome is Outcome.CONVERGED
        return retry.outcome is not Outcome.DIVERGED

    # --- between grids
    def unresolved(self, solution: PointSolution) -> bool:
        """The grid could not resolve the film: none was reported (it closed, the solve ran away with it closed, or
        the start's load continuation did not carry the full load: the V-cycles of its steps stopped converging),
        or the solve did not converge and estimates its own h_min error above unresolved_h_min."""
        no_film = (Outcome.FILM_CLOSED, Outcome.DIVERGED, Outcome.NOT_CONVERGED)
        if solution.outcome in no_film and "h_min" not in solution.scalars:  # (a failed solve has no data at all)
            return True
        estimate = solution.scalars.get("error_estimate_h_min", (0.0, "1"))[0]
        return solution.outcome is Outcome.NOT_CONVERGED and abs(estimate) > TUNING.unresolved_h_min

    def coarse(self, solution: PointSolution) -> bool:
        """The solve converged but estimates its own h_min or h_c error above coarse_estimate (the two grids then
        differ by more than the asymptotic range the estimate assumes), or has no estimate of h_min after a load
        continuation (`unestimated`)."""
        return solution.converged and (any(abs(e) > TUNING.coarse_estimate for e in estimates(solution))
                                       or self.unestimated(solution))

    def unestimated(self, solution: PointSolution) -> bool:
        """A solve of the load-continued attempt without an error estimate of h_min: its start's grid one coarser
        did not carry the full load and the load was raised on its finest grid (start.py); nothing bounds its film
        (docs/envelope.md, the heavy ellipses of the wide envelope)."""
        attempt = int(solution.scalars.get("attempts", (1.0, "1"))[0])
        return self.numbered(attempt).load_continuation and "error_estimate_h_min" not in solution.scalars

    def finer_settings(self, settings: SolverSettings, solution: PointSolution) -> SolverSettings | None:
        """The settings on the next finer grid for a film that `solution` did not resolve: twice the rows alone when
        its lowest film lies in a side lobe (|y| > side_lobe a) and the grid has fewer rows than columns, else
        twice as fine along each axis; None beyond the largest refined grid."""
        largest = self.largest_grid(solution)
        if in_side_lobe(solution) and settings.nodes_y < settings.grid and 2 * settings.nodes_y - 1 <= largest:
            return replace(settings, grid_y=2 * settings.nodes_y - 1)
        if 2 * max(settings.grid, settings.nodes_y) - 1 > largest:
            return None
        grid_y = None if settings.grid_y is None else 2 * settings.grid_y - 1
        return replace(settings, grid=2 * settings.grid - 1, grid_y=grid_y)

    @staticmethod
    def largest_grid(solution: PointSolution) -> int:
        """max_refined_grid, or max_refined_thermal_grid for a thermal solve."""
        thermal = solution.models.get("thermal", "off") != ThermalMode.OFF.value
        return TUNING.max_refined_thermal_grid if thermal else TUNING.max_refined_grid


def estimates(solution: PointSolution) -> tuple[float, float]:
    """The solve's own relative error estimates of h_c and h_min (0 where it has none)."""
    return tuple(solution.scalars.get(f"error_estimate_{key}", (0.0, "1"))[0] for key in ("h_c", "h_min"))


def reported_nodes(solution: PointSolution) -> int:
    """Nodes of the grid `solution` is reported on (0 without its axes)."""
    axes = solution.axes
    return len(axes["x"].values) * len(axes["y"].values) if "x" in axes and "y" in axes else 0


def in_side_lobe(solution: PointSolution) -> bool:
    """The lowest film of the solve (or where it closed) lies beyond side_lobe semi-axes a from the centre line."""
    scalars = solution.scalars
    y = scalars.get("y_h_min", scalars.get("y_film_closed", (math.nan, "m")))[0]
    a = scalars.get("a", (math.nan, "m"))[0]
    return abs(y) > TUNING.side_lobe * a


POLICY = RetryPolicy()
