"""The accuracy target (`solver.accuracy`, `--accuracy 1%`): each point's grid along x and y and its cheaper models
chosen by the solver until the error bound of every asked figure (h_c, h_min, p_max, dT_max, mu) is within the target.

Per point, on a start grid of TUNING.accuracy_start_grid nodes along x (the case's aspect along y):
1. The case's model (thermal `auto`: `full`) is solved with its error bounds, and the grid the point is expected to
   end on predicted from them (`planned`).
2. Each cheaper model (thermal `reduced`, TUNING.accuracy_fewer_layers layers, Newtonian instead of Ree-Eyring) whose
   check can pay for itself on that grid (Cheaper.pays, its measured saving TUNING.accuracy_saving_*) is solved on
   the start grid without error bounds; a cheaper model is taken where its measured change of every asked figure,
   summed over the cheaper models taken, stays within TUNING.accuracy_model_share of the target (the solve's own
   measured effect, not a correlation: Gupta et al.'s 1992 thermal factor is pessimistic on the project's own
   solutions, docs/accuracy.md).
3. The chosen model is solved on the grid predicted from the last solve's estimates (grid_prediction.py: e ~ h^2 of
   each axis, the grid of fewest nodes predicted to bring every figure above the target within
   TUNING.accuracy_jump_margin of it), and again from that solve's estimates, until each figure's bound plus its
   model effect is within the target, or no grid within TUNING.accuracy_max_grid x accuracy_max_grid_y is predicted
   to bring the rest within it, or the next grid passes the point's time budget (`solver.time_budget`). A figure
   without a bound to predict from is refined for twice as fine along the axis whose estimate dominates (at its cap:
   the other), or along the axes on which its feature spans fewer than TUNING.feature_nodes nodes (the error bounds'
   feature rule), along both where a figure's estimate along the other axis alone keeps its bound above the target;
   such a figure is set aside, unresolved with why, where no grid within reach can bound it (`out_of_reach`: its
   feature narrows with the grid, or the first grid that could resolve it passes the caps or the time budget). A finer
   grid along one axis that does not converge is followed by one along both; where that fails too the converged
   coarser solution is kept.

A figure's bound (`figure_bound`) is the solve's own `error_bound_<name>` (ehl/error_bounds.py: every converged solve
with a film reports it, with its y-check, or `unresolved_<name>`); after one doubling along x it is checked
against the last grid's x-estimates, the next coarser pair along x (`three_grid_checked`: Roache's asymptotic-range
check, asymptotic_range.three_grid_estimate); a figure the solve reports unresolved, or without a bound, has none and is
refined for while the grid and the time allow. The axis to refine is read from the solve's
estimates along x (`error_estimate_<name>`) and y (`error_estimate_y_<name>`). p_max is never bounded: the pressure
maximum is the outlet spike, which grows with every refinement on practical grids (Venner & Lubrecht 2000, ch. 8): it
is reported as achieved, "unresolved", and never refined for; so is a dT_max the solve reports unresolved because the
film's compression sets its temperatures through the outlet spike (`never_refined`). A solve's cost is its wall and
CPU time and its error check's (`error_check_time`, `error_check_cpu_time`); the time budget reads the CPU time.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
import math

from facegear_tehl.accuracy_record import AccuracyRecord, Choice, FigureBound, SolveStep, Verdict
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.domain import solution_domain
from facegear_tehl.ehl.richardson import ORDER
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.ehl.stopwatch import Spent, spent_on
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.grid_prediction import Estimate, predicted_grid, reachable
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.parallel import Progress, Solver, SolveTask, StagedSolver, solve_all, worker_count
from facegear_tehl.settings import SolverSettings, ThermalMode
from facegear_tehl.solution import PointSolution

FIGURES = ("h_c", "h_min", "p_max", "dT_max", "mu")  # the figures the target asks for, where the model reports them
NEVER_BOUNDED = ("p_max",)  # module docstring


Effects = Mapping[str, float]  # relative change of each figure


@dataclass(frozen=True)
class Bound:
    """One figure's relative bound (inf where none can be given), its estimates along x and y (NaN: none)."""

    bound: float
    e_x: float
    e_y: float


def figure_bound(solution: PointSolution, name: str) -> Bound:
    """The bound of figure `name` of `solution`: the solve's own error_bound_<name>, inf where it reports the figure
    unresolved or no bound (module docstring); its estimates along x and y as the solve reports them."""
    scalars = solution.scalars
    e_x = scalars.get(f"error_estimate_{name}", (math.nan, "1"))[0]
    e_y = scalars.get(f"error_estimate_y_{name}", (math.nan, "1"))[0]
    unresolved = scalars.get(f"unresolved_{name}", (1.0, "1"))[0] != 0.0
    if name in NEVER_BOUNDED or not solution.converged or unresolved:
        return Bound(math.inf, e_x, e_y)
    return Bound(scalars.get(f"error_bound_{name}", (math.inf, "1"))[0], e_x, e_y)


def never_refined(solution: PointSolution, name: str) -> bool:
    """A figure no finer grid bounds: p_max (NEVER_BOUNDED), any figure unresolved because the domain starves the film
    (its inlet or its sides: a finer grid keeps the domain), and dT_max where the solve reports it unresolved because
    the film's compression sets its temperatures through an outlet spike it does not resolve (error_bounds.
    compression_held: the hot spot grows with the spike under refinement, as p_max does)."""
    if name in NEVER_BOUNDED:
        return True
    from facegear_tehl.ehl.error_bounds import compression_held  # here: the command line loads no solver kernels
    from facegear_tehl.ehl.unresolved import Why

    reason = solution.scalars.get(f"unresolved_reason_{name}", (0.0, "1"))[0]
    if reason in (Why.STARVED_INLET, Why.STARVED_SIDES):  # the domain starves the film: no grid moves its edges
        return True

    flagged = solution.scalars.get("unresolved_dT_max", (0.0, "1"))[0] != 0.0
    return name == "dT_max" and flagged and compression_held(solution)


def model_words(task: SolveTask) -> str:
    """The model of a task in words: thermal model (with its layers when full) and rheology."""
    settings = task.settings
    layers = f" {settings.thermal_layers} layers" if settings.thermal is ThermalMode.FULL else ""
    return f"thermal {settings.thermal}{layers}, {task.lubricant.rheology}"


def grid_words(settings: SolverSettings) -> str:
    return f"{settings.grid} x {settings.nodes_y}"


def start_task(task: SolveTask) -> SolveTask:
    """The task on the start grid: TUNING.accuracy_start_grid along x, y at the case's aspect (not below the
    coarsest grid), thermal `auto` solved `full` (the cheaper models are the target's to choose)."""
    settings = task.settings
    grid = TUNING.accuracy_start_grid
    grid_y = None if settings.grid_y is None else max((settings.grid_y - 1) * (grid - 1) // (settings.grid - 1) + 1,
                                                      settings.coarsest_grid)
    thermal = ThermalMode.FULL if settings.thermal is ThermalMode.AUTO else settings.thermal
    return replace(task, settings=replace(settings, grid=grid, grid_y=grid_y, thermal=thermal))


@dataclass(frozen=True)
class Cheaper:
    """A cheaper model: what it changes, to what, the change made to a task, where it applies, and the share of a
    solve's CPU time it saves (TUNING.accuracy_saving_*, scripts/model_cost.py)."""

    what: str
    chosen: str
    apply: Callable[[SolveTask], SolveTask]
    applies: Callable[[SolveTask], bool]
    saving: float

    def pays(self, expected_nodes: int, start_nodes: int) -> bool:
        """Its check, one solve on the start grid in this model, can pay for itself: the point is expected to go on
        past the start grid, and the saving on the grid it is expected to end on is at least the check's cost (both
        scaled by the nodes: multigrid work grows with them)."""
        return expected_nodes > start_nodes and self.saving * expected_nodes >= (1.0 - self.saving) * start_nodes


def _reduced(task: SolveTask) -> SolveTask:
    return replace(task, settings=replace(task.settings, thermal=ThermalMode.REDUCED))


def _fewer_layers(task: SolveTask) -> SolveTask:
    return replace(task, settings=replace(task.settings, thermal_layers=TUNING.accuracy_fewer_layers))


def _newtonian(task: SolveTask) -> SolveTask:
    return replace(task, lubricant=replace(task.lubricant, rheology="newtonian"))


def _full(task: SolveTask) -> bool:
    return task.settings.thermal is ThermalMode.FULL


CHEAPER = (  # in the order they are tried: the largest saving first
    Cheaper("thermal", "reduced", _reduced, _full, TUNING.accuracy_saving_reduced),
    Cheaper("thermal_layers", str(TUNING.accuracy_fewer_layers), _fewer_layers,
            lambda task: _full(task) and task.settings.thermal_layers > TUNING.accuracy_fewer_layers,
            TUNING.accuracy_saving_layers),
    Cheaper("rheology", "newtonian", _newtonian, lambda task: task.lubricant.rheology == "ree_eyring",
            TUNING.accuracy_saving_newtonian),
)


def model_effect(reference: PointSolution, cheaper: PointSolution) -> dict[str, float]:
    """Relative change of each asked figure the reference reports from the reference to the cheaper model's solve
    of the same grid (inf where the cheaper one did not converge or does not report it)."""
    names = [name for name in FIGURES if name in reference.scalars]
    if not (reference.converged and cheaper.converged):
        return dict.fromkeys(names, math.inf)
    return {name: abs(cheaper.scalar(name) - reference.scalar(name)) / abs(reference.scalar(name))
            if name in cheaper.scalars and reference.scalar(name) != 0.0 else math.inf for name in names}


def _summed(first: Effects, second: Effects) -> dict[str, float]:
    return {name: first.get(name, 0.0) + second.get(name, math.inf) for name in second}


def _percent(effects: Effects) -> str:
    return ", ".join(f"{name} {100 * value:.2g} %" for name, value in effects.items())


def choose_models(reference: SolveTask, solved: Mapping[str, PointSolution], base: PointSolution, target: float
                  ) -> tuple[tuple[Cheaper, ...], dict[str, float], tuple[Choice, ...]]:
    """The cheaper models taken, in CHEAPER's order, while the sum of their measured effects on every figure stays
    within TUNING.accuracy_model_share of `target`; `solved` the cheaper models' solves by `what`, `base` the
    reference's. Returns the models taken, their summed effects and a choice per model considered."""
    share = TUNING.accuracy_model_share * target
    task, total, taken, choices = reference, {name: 0.0 for name in FIGURES if name in base.scalars}, [], []
    for cheaper in CHEAPER:
        if cheaper.what not in solved or not cheaper.applies(task):
            continue
        effect = model_effect(base, solved[cheaper.what])
        summed = _summed(total, effect)
        against = f"changes {_percent(effect)} against {model_words(reference)} on {grid_words(reference.settings)}"
        if max(summed.values(), default=math.inf) <= share:
            task, total = cheaper.apply(task), summed
            taken.append(cheaper)
            choices.append(Choice(cheaper.what, cheaper.chosen, f"{against}: within {100 * share:.2g} %, "
                                  f"{TUNING.accuracy_model_share:g} of the target"))
        else:
            choices.append(Choice(cheaper.what, "as the case", f"{cheaper.chosen} {against}: beyond "
                                  f"{100 * share:.2g} %, {TUNING.accuracy_model_share:g} of the target"))
    return tuple(taken), total, tuple(choices)


def _applied(task: SolveTask, taken: Sequence[Cheaper]) -> SolveTask:
    for cheaper in taken:
        task = cheaper.apply(task)
    return task


@dataclass(frozen=True)
class Spans:
    """The grid a solution was solved on (as asked: nx x ny) and the nodes across each local figure's feature along x
    and y (error_bounds.feature_runs)."""

    grid: int
    grid_y: int
    runs: Mapping[str, tuple[int, int]]

    def short(self, name: str) -> str:
        """The axes along which figure `name`'s feature spans fewer than TUNING.feature_nodes nodes ("": none)."""
        runs = self.runs.get(name, (TUNING.feature_nodes, TUNING.feature_nodes))
        return "x" * (runs[0] < TUNING.feature_nodes) + "y" * (runs[1] < TUNING.feature_nodes)


FEATURES = {"h_min": "the lowest film's basin", "dT_max": "the hot spot"}  # the local figures' features


@dataclass(frozen=True)
class Progressing:
    """One point under the target: its task and latest solution, the model's effects, the choices and solves so far,
    and why it stopped ("" while refining)."""

    task: SolveTask
    solution: PointSolution
    effects: Mapping[str, float]
    choices: tuple[Choice, ...]
    steps: tuple[SolveStep, ...]
    stop: str = ""
    failed: str = ""  # the finer grid, refined along one axis, that did not converge: the next refines both
    after_jump: str = ""  # the predicted grid, past one doubling, that did not converge: one doubling at a time on
    failed_grids: tuple[tuple[int, int], ...] = ()  # the grids (nx, ny) that did not converge: not solved again
    model_solved: bool = True  # the solution is in the task's model (False: the start's, before a cheaper one)
    coarser: Spans | None = None  # the features' spans on the converged grid before this one (None: none)
    beyond_reach: Mapping[str, str] = field(default_factory=dict)  # the figures left unresolved, each with why
    orders: Mapping[str, tuple[float, float]] = field(default_factory=dict)  # measured along x, y (`measured_orders`)
    last_orders: Mapping[str, tuple[float, float]] = field(default_factory=dict)  # ... by the last refinement alone
    not_following: Mapping[str, str] = field(default_factory=dict)  # the figures set aside "not met", each with why

    def bounds(self) -> dict[str, Bound]:
        return {name: figure_bound(self.solution, name) for name in FIGURES if name in self.solution.scalars}

    def missing(self, target: float) -> dict[str, Bound]:
        """The figures (those never refined for, or beyond reach, aside) whose bound plus model effect exceeds
        `target`."""
        return {name: bound for name, bound in self.bounds().items()
                if not never_refined(self.solution, name) and name not in self.beyond_reach
                and name not in self.not_following and bound.bound + self.effects.get(name, 0.0) > target}

    def spans(self) -> Spans:
        """The nodes across each local figure's feature on the solution's grid (none without its fields)."""
        settings, solution = self.task.settings, self.solution
        if not solution.converged or "film_thickness" not in solution.fields:
            return Spans(settings.grid, settings.nodes_y, {})
        from facegear_tehl.ehl.error_bounds import feature_runs  # here: the command line loads no solver kernels

        return Spans(settings.grid, settings.nodes_y, feature_runs(solution, self.task.lubricant.inlet_temperature))


def solve_seconds(solution: PointSolution) -> Spent:
    """Wall and CPU time of a solve with its error check's (s; ehl/error_bounds.py keeps that apart from the solve's
    own; a solution without CPU times counts its wall times)."""
    check = solution.scalars.get("error_check_time", (0.0, "s"))[0]
    return spent_on(solution) + Spent(check, solution.scalars.get("error_check_cpu_time", (check, "s"))[0])


def step(task: SolveTask, solution: PointSolution, purpose: str) -> SolveStep:
    spent = solve_seconds(solution)
    return SolveStep(grid_words(task.settings), model_words(task), purpose, solution.outcome.value, spent.wall,
                     spent.cpu)


def refined_axis(missing: Mapping[str, Bound]) -> str:
    """The axis to refine for the figures above the target: the one whose largest estimate among them is larger
    (an unknown estimate counts as infinite); both where neither is known."""
    along_x = max((abs(b.e_x) if math.isfinite(b.e_x) else math.inf for b in missing.values()), default=0.0)
    along_y = max((abs(b.e_y) if math.isfinite(b.e_y) else math.inf for b in missing.values()), default=0.0)
    if math.isinf(along_x) and math.isinf(along_y):
        return "xy"
    return "x" if along_x >= along_y else "y"


def with_other_axis(axis: str, missing: Mapping[str, Bound], target: float) -> str:
    """`axis`, or both where a figure's estimate along the other axis alone keeps its bound above `target` (F_s |e| >
    target): under the additive error model f = f* + C_x h_x^p + C_y h_y^p (Roache 1998, ch. 5) refining one axis
    leaves the other's error as it is, so that figure needs both, and doubling both at once saves the solve between."""
    if axis == "xy":
        return axis
    other = "y" if axis == "x" else "x"
    along = [abs(b.e_y if other == "y" else b.e_x) for b in missing.values()]
    return "xy" if any(math.isfinite(e) and TUNING.bound_safety * e > target for e in along) else axis


def out_of_reach(point: Progressing, name: str, bound: Bound, spans: Spans) -> str:
    """Why no grid within the caps and the time budget can bound figure `name` ("" where one may): it has no bound
    because its feature spans fewer than TUNING.feature_nodes nodes along an axis (error_bounds.py), and either it
    narrows with the grid, or the fewest doublings that could bring it onto TUNING.feature_nodes nodes pass the largest
    grid or the time budget. A feature of fixed width across n nodes is at least n - 1 spacings wide and narrower than
    n + 1: one doubling puts it on at least 2n - 1 nodes, and k doublings on fewer than (n + 1) 2^k, so it needs k >=
    log2((feature_nodes + 1)/(n + 1)) doublings; one that spanned n >= 2 nodes on the last converged grid coarser along
    that axis and no more now narrows with the grid (a feature below the spacing, as the outlet spike: refining does
    not resolve it). A feature on one node gives no such evidence (any width below two spacings)."""
    short = spans.short(name)
    if not math.isinf(bound.bound) or not short or name not in FEATURES:
        return ""
    feature, here, coarser, finer = FEATURES[name], grid_words(point.task.settings), point.coarser, point.task.settings
    for k, axis in ((0, "x"), (1, "y")):
        if axis not in short:
            continue
        nodes_along = spans.runs[name][k]
        before = coarser.runs.get(name, (0, 0))[k] if coarser is not None and _finer_along(coarser, spans, k) else 0
        if before >= max(nodes_along, 2):
            return (f"{feature} spans {nodes_along} nodes along {axis} on {here}, {before} on the "
                    f"coarser {coarser.grid} x {coarser.grid_y}: it narrows with the grid, refining does not "
                    "resolve it")
        for _ in range(math.ceil(math.log2((TUNING.feature_nodes + 1) / (nodes_along + 1)))):
            finer = None if finer is None else refined_settings(finer, axis)
    needs = ", ".join(f"{spans.runs[name][k]} nodes along {axis}" for k, axis in ((0, "x"), (1, "y")) if axis in short)
    if finer is None:
        return f"{feature} spans {needs} on {here}: the grid that could resolve it passes the largest grid"
    if over_budget(point, finer):
        return f"{feature} spans {needs} on {here}: {grid_words(finer)}, the first grid that could resolve it, " \
               f"would pass the time budget {point.task.settings.time_budget:g} s"
    return ""


def _finer_along(coarser: Spans, spans: Spans, k: int) -> bool:
    return (spans.grid, spans.grid_y)[k] > (coarser.grid, coarser.grid_y)[k]


def feature_axes(missing: Mapping[str, Bound], spans: Spans) -> str:
    """The axes along which the features of the figures without a bound among `missing` span too few nodes."""
    short = "".join(spans.short(name) for name, bound in missing.items() if math.isinf(bound.bound))
    return "".join(axis for axis in "xy" if axis in short)


def refined_settings(settings: SolverSettings, axis: str) -> SolverSettings | None:
    """`settings` twice as fine along `axis` (x, y or xy); None past TUNING.accuracy_max_grid / accuracy_max_grid_y."""
    grid = 2 * settings.grid - 1 if "x" in axis else settings.grid
    grid_y = 2 * settings.nodes_y - 1 if "y" in axis else settings.nodes_y
    if grid > TUNING.accuracy_max_grid or grid_y > TUNING.accuracy_max_grid_y:
        return None
    return replace(settings, grid=grid, grid_y=grid_y)


def over_budget(point: Progressing, finer: SolverSettings) -> bool:
    """The finer solve would pass the point's time budget: the CPU time spent plus the last solve's with its error
    check (`solve_seconds`) scaled by the finer grid's nodes (multigrid work grows with the nodes). CPU time, as the
    refinement of run.py reads it (ehl/stopwatch.py): a loaded machine does not change the grid a point ends on."""
    settings = point.task.settings
    spent = sum(s.cpu_seconds for s in point.steps)
    ratio = (finer.grid * finer.nodes_y) / (settings.grid * settings.nodes_y)
    return spent + ratio * solve_seconds(point.solution).cpu > settings.time_budget


# solves tasks side by side, each with its purpose (for the progress lines), in task order
Batch = Callable[[Sequence[tuple[SolveTask, str]]], list[PointSolution]]


def screened(tasks: Sequence[SolveTask], solve: Batch, check: Batch, target: float) -> list[Progressing]:
    """Steps 1 and 2 (module docstring): each point on the start grid in its case's model; the cheaper models whose
    check can pay for itself on the grid the point is expected to end on (`expected_nodes`, Cheaper.pays) solved
    there by `check` (figures alone, no error bounds: only their change is read), and chosen (`choose_models`); where
    two or more are taken, `combined`. The point goes on from its start solve in the case's model."""
    starts = [start_task(task) for task in tasks]
    bases = solve([(start, "start") for start in starts])
    trials, skipped = [], []
    for start, base in zip(starts, bases):
        expected, applying = expected_nodes(start, base, target), [c for c in CHEAPER if c.applies(start)]
        trials.append([c for c in applying if c.pays(expected, nodes(start.settings))])
        skipped.append(tuple(_not_checked(c, expected, nodes(start.settings)) for c in applying
                             if c not in trials[-1]))
    checks = [(c.apply(start), f"model check: {c.what}") for start, each in zip(starts, trials) for c in each]
    rest = iter(check(checks))
    points = []
    for start, base, each, unchecked in zip(starts, bases, trials, skipped):
        by_what = {c.what: next(rest) for c in each}
        steps = (step(start, base, "start"),) + tuple(step(c.apply(start), by_what[c.what], f"model check: {c.what}")
                                                      for c in each)
        taken, effects, choices = choose_models(start, by_what, base, target)
        progressing = Progressing(_applied(start, taken), base, effects, unchecked + choices, steps,
                                  model_solved=not taken)
        points.append(Screened(progressing, start, base, taken, by_what))
    return combined(points, check, target)


def nodes(settings: SolverSettings) -> int:
    return settings.grid * settings.nodes_y


def expected_nodes(start: SolveTask, base: PointSolution, target: float) -> int:
    """Nodes of the grid a point is expected to end on from its start solve: the start grid where it meets the
    target, the predicted grid (`planned`) where there is one, else at least one doubling."""
    point = Progressing(start, base, {}, (), ())
    missing = point.missing(target)
    if not missing:
        return nodes(start.settings)
    finer, _ = planned(point, missing, target)
    return 2 * nodes(start.settings) if finer is None else nodes(finer)


def _not_checked(cheaper: Cheaper, expected: int, start: int) -> Choice:
    if expected <= start:
        return Choice(cheaper.what, "as the case", f"{cheaper.chosen} not checked: the start grid meets the target")
    if cheaper.saving <= 0.0:
        return Choice(cheaper.what, "as the case", f"{cheaper.chosen} not checked: it costs "
                      f"{-100 * cheaper.saving:.0f} % more than the case's model (no saving to check for)")
    return Choice(cheaper.what, "as the case", f"{cheaper.chosen} not checked: it saves {100 * cheaper.saving:.0f} % "
                  f"of a solve, and the point is expected to end on {expected / start:.2g}x the start grid's nodes: "
                  "its check would cost more than it can save")


@dataclass(frozen=True)
class Screened:
    """A point after the model checks: its progress, the start task and solve in the case's model, the cheaper
    models taken and each cheaper model's solve by `what`."""

    point: Progressing
    start: SolveTask
    base: PointSolution
    taken: tuple[Cheaper, ...]
    solved: Mapping[str, PointSolution]


def combined(screens: Sequence[Screened], check: Batch, target: float) -> list[Progressing]:
    """The points that took two or more cheaper models solved in their combination (by `check`): its measured effect
    against the case's model replaces the sum, and beyond TUNING.accuracy_model_share of the target the first model
    alone is kept, with its effect measured alone."""
    points = [screen.point for screen in screens]
    together = [i for i, screen in enumerate(screens) if len(screen.taken) > 1]
    share = TUNING.accuracy_model_share * target
    for i, solution in zip(together, check([(points[i].task, "model check: combined") for i in together])):
        screen, effects = screens[i], model_effect(screens[i].base, solution)
        point = replace(points[i], steps=points[i].steps + (step(points[i].task, solution, "model check: combined"),))
        if max(effects.values(), default=math.inf) <= share:
            note = Choice("model", model_words(point.task), f"the combination changes {_percent(effects)}")
            points[i] = replace(point, effects=effects, choices=point.choices + (note,))
            continue
        first = screen.taken[0]
        note = Choice("model", model_words(first.apply(screen.start)), f"the combination changes {_percent(effects)}:"
                      f" beyond {100 * share:.2g} %; {first.what} {first.chosen} alone kept")
        points[i] = replace(point, task=first.apply(screen.start), effects=model_effect(screen.base,
                                                                                         screen.solved[first.what]),
                            choices=point.choices + (note,))
    return points


def estimates(point: Progressing, missing: Mapping[str, Bound]) -> dict[str, Estimate]:
    """The figures above the target as the grid prediction reads them: bound, estimates, the order each estimate was
    measured to fall at along each axis (`measured_orders`), at most the discretisation's, which it is where not
    measured (grid_prediction.py: the plan never passes the first grid that can meet the target), model effect."""
    def planned_order(name: str, k: int) -> float:
        measured = point.orders.get(name, (math.nan, math.nan))[k]
        return ORDER if math.isnan(measured) else min(measured, ORDER)

    return {name: Estimate(b.bound, b.e_x, b.e_y, planned_order(name, 0), planned_order(name, 1),
                           point.effects.get(name, 0.0)) for name, b in missing.items()}


def measured_orders(coarse: Mapping[str, Bound], fine: Mapping[str, Bound], kx: int, ky: int
                    ) -> dict[str, tuple[float, float]]:
    """The order at which each figure's estimates fell along x and y from the `coarse` solve to the `fine` one, kx and
    ky doublings finer: p = log2(|e coarse| / |e fine|) / k (an estimate C h^p falls 2^p per doubling), NaN along an
    axis not refined or where either estimate is not a finite non-zero number."""
    def order(before: float, after: float, k: int) -> float:
        if k == 0 or not (math.isfinite(before) and math.isfinite(after)) or before == 0.0 or after == 0.0:
            return math.nan
        return math.log2(abs(before) / abs(after)) / k

    return {name: (order(coarse[name].e_x, bound.e_x, kx), order(coarse[name].e_y, bound.e_y, ky))
            for name, bound in fine.items() if name in coarse}


def not_following(point: Progressing, target: float) -> Progressing:
    """The point with the figures above the target whose estimates fell, over the last refinement, at an order below
    TUNING.accuracy_min_order along every axis it refined set aside, with their measured order: not refined for again
    (their verdict is their bound's on the grid the point ends on: "not met" unless a refinement for the others brings
    it within the target) (another doubling would not bring them within the target: at that order each halves their
    error at most once in 2^(1/p) doublings)."""
    floor, here = TUNING.accuracy_min_order, grid_words(point.task.settings)
    set_aside = {}
    for name, bound in point.missing(target).items():
        orders = [(axis, p) for axis, p in zip("xy", point.last_orders.get(name, ())) if not math.isnan(p)]
        if orders and max(p for _, p in orders) < floor:
            words = ", ".join(f"{p:.2g} along {axis}" for axis, p in orders)
            set_aside[name] = (f"its estimates fell at order {words} over the last refinement, to {here} (bound "
                               f"{100 * bound.bound:.2g} %): below {floor:g}, it does not converge as planned")
    if not set_aside:
        return point
    notes = tuple(Choice(name, "not refined for", why) for name, why in set_aside.items())
    return replace(point, not_following={**point.not_following, **set_aside}, choices=point.choices + notes)


def planned(point: Progressing, missing: Mapping[str, Bound], target: float) -> tuple[SolverSettings | None, str]:
    """The point's next grid and why (None: none, with the reason). After a finer grid along one axis that did not
    converge: both axes twice as fine. Where every figure above the target has a bound: the predicted grid
    (grid_prediction.py) for those predicted to come within the target at all within the caps (none: it stops).
    Else, and once a predicted grid past one doubling did not converge, twice as fine along the axes on which a
    feature is too narrow, else along the axis whose estimate dominates (`refined_axis`), with the other where its
    estimate alone keeps a figure above the target (`with_other_axis`); at an axis's cap along the other."""
    settings = point.task.settings
    largest = f"the largest grid {TUNING.accuracy_max_grid} x {TUNING.accuracy_max_grid_y}"
    if point.failed:
        finer = refined_settings(settings, "xy")
        if finer is not None and (finer.grid, finer.nodes_y) in point.failed_grids:
            return None, f"{grid_words(finer)} did not converge before"
        return finer, (f"refining xy would pass {largest}" if finer is None else f"both axes after {point.failed}")
    figures = estimates(point, missing)
    if not point.after_jump and all(e.predictable for e in figures.values()):
        pursued = reachable(settings.grid, settings.nodes_y, figures, target)
        beyond = ", ".join(name for name in figures if name not in pursued)
        beyond = f"; {beyond} predicted above the target even on {largest}" if beyond else ""
        prediction = predicted_grid(settings.grid, settings.nodes_y, pursued, target) if pursued else None
        if prediction is None:
            return None, f"none predicted within the target even on {largest}"
        margin = f"{100 * TUNING.accuracy_jump_margin * target:.2g} %"
        return (replace(settings, grid=prediction.grid, grid_y=prediction.grid_y),
                f"{prediction.words()} (margin {margin}){beyond}")
    axis = with_other_axis(feature_axes(missing, point.spans()) or refined_axis(missing), missing, target)
    finer = next((s for a in (axis, *axis, *"xy") if (s := refined_settings(settings, a)) is not None), None)
    if finer is not None and (finer.grid, finer.nodes_y) in point.failed_grids:  # as if it had failed again
        return planned(replace(point, failed=f"{grid_words(finer)} ended as before"), missing, target)
    reason = f"after {point.after_jump}" if point.after_jump else "a figure above the target without a bound"
    why = f"refining {axis} would pass {largest}" if finer is None else f"twice as fine along {axis} or, at its " \
          f"cap, the other axis: {reason}"
    return finer, why


def next_step(point: Progressing, target: float) -> tuple[Progressing, SolveTask | None]:
    """The point's next solve (None: it stops, with the reason): the grid `planned` for the figures above the target,
    its reason recorded, unless the grid cap or the time budget comes first; a predicted grid past one doubling that
    would pass the time budget turns the point to one doubling at a time."""
    point = not_following(reached(point, target), target)
    missing = point.missing(target)
    if not missing:
        beyond = f"; {', '.join(point.beyond_reach)} unresolved, beyond reach" if point.beyond_reach else ""
        bounds = point.bounds()
        still = [name for name in point.not_following if bounds[name].bound + point.effects.get(name, 0.0) > target]
        beyond += f"; {', '.join(still)} not met, not converging as planned" if still else ""
        if not any(math.isfinite(bound.bound) for bound in bounds.values()):  # nothing to hold the target against
            return replace(point, stop=f"no figure bounded: the target is not checked{beyond}"), None
        return replace(point, stop=f"every bounded figure within the target{beyond}"), None
    finer, why = planned(point, missing, target)
    above = ", ".join(missing)
    if finer is not None and over_budget(point, finer) and max(doublings_to(point.task.settings, finer)) > 1:
        point = replace(point, after_jump=f"{grid_words(finer)} would pass the time budget")  # one doubling on
        finer, why = planned(point, missing, target)
    if finer is None:
        return replace(point, stop=f"{above} above the target; {why}"), None
    if over_budget(point, finer):
        return replace(point, stop=f"{above} above the target; {grid_words(finer)} not started: it would pass the "
                                   f"time budget {point.task.settings.time_budget:g} s (solver.time_budget)"), None
    choice = Choice("refine", grid_words(finer), f"{above} above the target on {grid_words(point.task.settings)}: "
                                                 f"{why}")
    return replace(point, choices=point.choices + (choice,)), replace(point.task, settings=finer)


def reached(point: Progressing, target: float) -> Progressing:
    """The point with the figures above the target that no grid within reach can bound (`out_of_reach`) set aside:
    they are reported unresolved, each with why, and not refined for."""
    spans = point.spans()
    beyond = {name: why for name, bound in point.missing(target).items() if (why := out_of_reach(point, name, bound,
                                                                                                   spans))}
    if not beyond:
        return point
    notes = tuple(Choice(name, "unresolved", why) for name, why in beyond.items())
    return replace(point, beyond_reach={**point.beyond_reach, **beyond}, choices=point.choices + notes)


def doublings_to(coarse: SolverSettings, fine: SolverSettings) -> tuple[int, int]:
    """How many times `fine` is twice as fine as `coarse` along x and along y."""
    return (round(math.log2((fine.grid - 1) / (coarse.grid - 1))),
            round(math.log2((fine.nodes_y - 1) / (coarse.nodes_y - 1))))


def three_grid_checked(coarser: PointSolution, solution: PointSolution, t_inlet: float) -> PointSolution:
    """`solution` with its bounds checked against `coarser`, the same point's converged solve in the same model one
    doubling coarser along x on the same domain, both grids square or both not (error_bounds.one_doubling_coarser):
    its x-estimates are the next coarser pair's, the third grid of Roache's asymptotic-range check
    (error_bounds.with_coarser_pair); as it is elsewhere. t_inlet in K. The accuracy target's and run.py's refinement
    both check their finer solve so."""
    from facegear_tehl.ehl.error_bounds import with_coarser_pair  # here: the command line loads no solver kernels

    return with_coarser_pair(solution, coarser, t_inlet)


def refined(point: Progressing, task: SolveTask, solution: PointSolution) -> Progressing:
    """The point after its finer solve: the finer solution; where it did not converge after a converged one, the
    coarser one kept: after a jump past one doubling, one doubling at a time from then on; after one doubling along
    one axis, both axes next (the cells' aspect kept: the default case's S2 and S4 diverge on 513 x 65 and converge
    on 1025 x 129, docs/accuracy.md); after both, stopped."""
    kx, ky = doublings_to(point.task.settings, task.settings)
    axis = "x" * (kx > 0) + "y" * (ky > 0)
    steps = point.steps + (step(task, solution, f"refine {axis}"),)
    if point.solution.converged and not solution.converged:
        ended = f"{grid_words(task.settings)} ended {solution.outcome.value}"
        point = replace(point, failed_grids=point.failed_grids + ((task.settings.grid, task.settings.nodes_y),))
        if max(kx, ky) > 1:
            return replace(point, steps=steps, after_jump=ended)
        if axis != "xy":
            return replace(point, steps=steps, failed=ended)
        before = f" (after {point.failed or point.after_jump})" if point.failed or point.after_jump else ""
        return replace(point, steps=steps, stop=f"{ended}{before}; the converged {grid_words(point.task.settings)} "
                                                "solution kept")
    if point.solution.converged and point.model_solved:
        solution = three_grid_checked(point.solution, solution, task.lubricant.inlet_temperature)
    after = replace(point, task=task, solution=solution, steps=steps, failed="", model_solved=True,
                    coarser=point.spans() if point.solution.converged else point.coarser)
    if not (point.solution.converged and point.model_solved):  # no converged solve in this model to measure from
        return replace(after, last_orders={})
    last = measured_orders(point.bounds(), after.bounds(), kx, ky)
    orders = {name: tuple(p if not math.isnan(p) else before for p, before in
                          zip(pair, point.orders.get(name, (math.nan, math.nan)))) for name, pair in last.items()}
    return replace(after, orders=orders, last_orders=last)


def solve_to_accuracy(tasks: Sequence[SolveTask], solver: Solver | StagedSolver, *,
                      checks: Solver | StagedSolver | None = None, jobs: int | None = None,
                      progress: Progress | None = None) -> list[PointSolution]:
    """Every task solved to its settings' accuracy target (module docstring); `checks` solves the model checks (None:
    `solver`; the EHL solver's without error bounds: only their figures are read). Each point is refined within one
    process, so that a `solver` that keeps a point's converged state seeds its finer grid from it
    (ehl/seeded.SeededRefinement); the points side by side on `jobs` worker processes (`PointTarget`), else in this
    one. Each solution carries its AccuracyRecord and the wall time of all its solves."""
    if len(tasks) > 1 and worker_count(jobs) > 1:
        return solve_all(tasks, PointTarget(solver, checks), jobs=jobs, progress=progress)[0]
    return targeted(tasks, solver, checks, progress)


@dataclass(frozen=True)
class PointTarget:
    """One point solved to its accuracy target in the process that calls it (`targeted`): a worker's unit of
    `solve_to_accuracy`. The pool warms up (parallel.py) with `warm_up_solver`, the model checks' solver (it keeps no
    state), not with `solver`, whose kept seeds go to the workers."""

    solver: Solver | StagedSolver
    checks: Solver | StagedSolver | None

    @property
    def warm_up_solver(self) -> Solver | StagedSolver:
        return self.checks or self.solver

    def __call__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
        return targeted([SolveTask(point, lubricant, settings)], self.solver, self.checks, None)[0]


def targeted(tasks: Sequence[SolveTask], solver: Solver | StagedSolver, checks: Solver | StagedSolver | None,
             progress: Progress | None) -> list[PointSolution]:
    """Every task solved to its accuracy target in this process, the points' solves round by round."""
    target = float(tasks[0].settings.accuracy)

    def solve(batch: Sequence[tuple[SolveTask, str]]) -> list[PointSolution]:
        return _solved_batch(batch, solver, progress)

    def check(batch: Sequence[tuple[SolveTask, str]]) -> list[PointSolution]:
        return _solved_batch(batch, checks or solver, progress)

    points = screened(tasks, solve, check, target)
    while True:
        finer_tasks = {}
        for i, point in enumerate(points):
            if not point.stop:
                points[i], finer = next_step(point, target)
                finer_tasks.update({} if finer is None else {i: finer})
        if not finer_tasks:
            break
        for i, solution in zip(finer_tasks, solve([(task, "refine") for task in finer_tasks.values()])):
            points[i] = refined(points[i], finer_tasks[i], solution)
    return [finished(point, task, target) for point, task in zip(points, tasks)]


def _solved_batch(batch: Sequence[tuple[SolveTask, str]], solver: Solver | StagedSolver,
                  progress: Progress | None) -> list[PointSolution]:
    """The tasks solved in this process in order (`solve_all`, one job), each progress line naming the point with the
    solve's purpose ("S1 (refine)"); the solutions keep the point's name."""
    if not batch:
        return []
    named = [replace(task, point=replace(task.point, name=f"{task.point.name} ({purpose})")) for task, purpose in batch]
    solved = solve_all(named, solver, jobs=1, progress=progress)[0]
    return [replace(solution, name=task.point.name) for (task, _), solution in zip(batch, solved)]


def finished(point: Progressing, case_task: SolveTask, target: float) -> PointSolution:
    """The point's reported solution with its AccuracyRecord: each figure's bound and verdict, the choices (the
    grid's with the reason the refinement stopped), the solves and their cost."""
    if not point.model_solved:  # stopped before a solve in the cheaper model chosen: the start's model reported
        note = Choice("model", "as the case", f"{model_words(point.task)} chosen, but no grid was solved in it "
                      "before the refinement stopped: the start solve's model is reported")
        point = replace(point, effects={}, choices=point.choices + (note,))
    figures = []
    for name, bound in point.bounds().items():
        effect = point.effects.get(name, 0.0)
        if name in NEVER_BOUNDED or math.isinf(bound.bound):
            figures.append(FigureBound(name, math.nan, effect, Verdict.UNRESOLVED))
        else:
            verdict = Verdict.MET if bound.bound + effect <= target else Verdict.NOT_MET
            figures.append(FigureBound(name, bound.bound + effect, effect, verdict))
    solution = point.solution
    solved = f"{int(solution.scalars.get('grid', (0, ''))[0])} x {int(solution.scalars.get('grid_y', (0, ''))[0])}"
    grid = Choice("grid", f"{grid_words(point.task.settings)} ({solved} solved)", point.stop)
    record = AccuracyRecord(target, tuple(figures), point.choices + (grid,), point.steps, point.stop,
                            _nodes(solution), case_nodes(case_task))
    scalars = {**solution.scalars, **Spent(record.wall_time, record.cpu_time).scalars()}
    return replace(solution, scalars=scalars, accuracy=record)


def _nodes(solution: PointSolution) -> int:
    return int(solution.scalars.get("grid", (0, ""))[0] * solution.scalars.get("grid_y", (0, ""))[0])


def case_nodes(task: SolveTask) -> int:
    """Nodes the case's own settings solve the point on (the lengthened inlet's, ehl.domain)."""
    domain = solution_domain(scaling_for(task.point, task.lubricant), task.settings)
    return domain.nx * domain.ny
