"""Mesh independence (`tehl sweep`): one contact point solved on a sequence of grids, the change from grid
to grid, the observed order of convergence and a Richardson-extrapolated value with its uncertainty.

The grids refine by 2 (n = 33, 65, 129, ...: node spacing 4h, 2h, h). From the values f_4h, f_2h, f_h of a
quantity on three consecutive grids:

    relative change      c   = (f_h - f_2h) / |f_h|
    observed order       p   = log2(|f_2h - f_4h| / |f_h - f_2h|)
    extrapolated value   f*  = f_h + (f_h - f_2h) / (2^q - 1)                      (Richardson)
    uncertainty          U   = F_s |f_h - f_2h| / (2^q - 1)

U is Roache's (1994) grid convergence index of the fine grid, in the units of f. Up to MAX_ORDER
(2.05, just above the scheme's formal order 2) q = p and F_s = 1.25, the safety factor of a three-grid
study. An observed order above that is not a faster convergence the scheme can have but a sign that the
triplet is not yet asymptotic, or that the finest change sits at the solver's iteration floor (a change of
h_c near 5e-4 of it); p taken as it is would shrink U (by 7x at p = 3 against p = 2). There q is the
formal order 2 and F_s = 3, so U = |f_h - f_2h|: Roache's reversion to the theoretical order with
F_s = 3 when the observed one is not credible (Roache 2011, J. Fluids Eng. 133:115501), and the
theoretical order Eça & Hoekstra (2014, J. Comput. Phys. 262:104-130) take for p >= 2.05. The table keeps
the observed p. p is not defined when a difference is zero (f* = f_h, U = 0 when the last one is); f* and
U are not given when p < 0.5: the grids are then not in the asymptotic range (Eça & Hoekstra 2014 use the
same bound), and the correction, more than 2.4 times the last change, would amplify noise (p <= 0: the
values do not converge). The error of each grid is taken against
f* of the three finest grids: e = (f - f*)/|f*|. A grid whose solve did not converge gives no value: it
enters no change, order or extrapolation (the errors are then against the three finest grids that
converged). A quantity is converged to a tolerance from the first grid whose change to the next grid, and
every later change, is below it.

Grids are independent solves (each with its own full-multigrid start); they run on worker processes.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from itertools import pairwise
import math
import os
from pathlib import Path

import numpy as np

from facegear_tehl.atomic_files import remove_stale, temporary_beside
from facegear_tehl.case import THERMAL_MODELS, Case, check_thermal_inputs
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.domain import solution_domain
from facegear_tehl.ehl.richardson import ORDER
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.ehl.tuning import convergence_bands
from facegear_tehl.parallel import Progress, Solver, SolveTask, StagedSolver, solve_all
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.results import RunResult
from facegear_tehl.run import ehl_solver, solved_to_accuracy
from facegear_tehl.schema import CaseError, check
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import Field, PointSolution
from facegear_tehl.tables import COST, UNRESOLVED_WORD, cell, format_table, yes_no
from facegear_tehl.units import PERCENT, display

SAFETY_FACTOR = 1.25  # Roache (1994), grid convergence index of a three-grid study
MIN_ORDER = 0.5  # below this observed order no extrapolation is given (Eça & Hoekstra 2014)
# Above this observed order f* and U take the formal order ORDER and HIGH_ORDER_SAFETY_FACTOR (module docstring):
# Eça & Hoekstra's (2014) bound for a nominally second-order scheme, and Roache's (2011) factor of safety 3
MAX_ORDER = 2.05
HIGH_ORDER_SAFETY_FACTOR = 3.0
QUANTITIES = ("p_max", "h_c", "h_min", "dT_max", "mu")
"""Point scalars the sweep tabulates, when the solver gives them (dT_max and mu: thermal solver)."""
# dT_max's change between the two finest grids must exceed this multiple of the thermal loop's tolerance (K: the
# case's thermal_tolerance times the rise) for its order and extrapolation to measure the grid, else the sweep warns:
# the loop stops once an update moves the temperatures by less than that, and at its contraction of ~0.6 per update
# each grid keeps up to 1.5 times as much iteration error, two grids up to 3 times apart (measured: docs/accuracy.md).
ITERATION_MARGIN = 5.0


@dataclass(frozen=True)
class Convergence:
    """One quantity over the grids of a sweep (SI; NaN where a value is not defined, see the module)."""

    name: str
    units: str
    grids: tuple[int, ...]
    values: np.ndarray
    change: np.ndarray  # relative change from the previous grid; NaN on the first
    order: np.ndarray  # observed order from this grid and the two coarser ones; NaN on the first two
    extrapolated: np.ndarray  # Richardson value from the same three grids
    uncertainty: np.ndarray  # its GCI uncertainty, units of the quantity
    error: np.ndarray  # relative error against the extrapolated value of the three finest grids
    converged_grid: int | None  # first grid from which every change to the next grid is below the tolerance


@dataclass(frozen=True)
class Sweep:
    """A finished sweep: `run` holds the point solved on every grid (named <point>@<grid>) and the /sweep
    table, ready for `results.write_result`."""

    point: str
    grids: tuple[int, ...]
    tolerance: float
    quantities: tuple[Convergence, ...]
    run: RunResult


def convergence(name: str, units: str, grids: Sequence[int], values: Sequence[float], tolerance: float) -> Convergence:
    """The convergence table of one quantity over grids that refine by 2 (see the module for the formulas)."""
    f = np.asarray(values, dtype=float)
    n = len(f)
    change, order, extrapolated, uncertainty = (np.full(n, math.nan) for _ in range(4))
    change[1:] = np.diff(f) / np.abs(f[1:])
    for i in range(2, n):
        coarse, fine = f[i - 1] - f[i - 2], f[i] - f[i - 1]
        if fine == 0.0:
            extrapolated[i], uncertainty[i] = f[i], 0.0
            continue
        if coarse == 0.0:
            continue
        order[i] = math.log2(abs(coarse) / abs(fine))
        if order[i] >= MIN_ORDER:
            taken, factor = (order[i], SAFETY_FACTOR) if order[i] <= MAX_ORDER else (ORDER, HIGH_ORDER_SAFETY_FACTOR)
            extrapolated[i] = f[i] + fine / (2.0**taken - 1.0)
            uncertainty[i] = factor * abs(fine) / (2.0**taken - 1.0)
    solved = np.flatnonzero(np.isfinite(f))
    reference = extrapolated[solved[-1]] if solved.size else math.nan  # f* of the three finest solved grids
    error = (f - reference) / abs(reference)
    converged_grid = None
    for i in range(n - 2, -1, -1):
        if not abs(change[i + 1]) < tolerance:
            break
        converged_grid = int(grids[i])
    return Convergence(name, units, tuple(int(g) for g in grids), f, change, order, extrapolated, uncertainty, error,
                       converged_grid)


def time_to_reach(times: Sequence[float], errors: Sequence[float], target: float) -> float:
    """Wall time at which |error| falls to `target` and stays below it on every finer grid, interpolated
    linearly in log(time) against log(|error|) between the two grids around the crossing; the coarsest
    grid's time if it is already below; NaN if never reached (or the errors are not defined)."""
    magnitude = np.abs(np.asarray(errors, dtype=float))
    if not np.isfinite(magnitude).all():
        return math.nan
    below = magnitude <= target
    if not below[-1]:
        return math.nan
    first = len(below) - int(np.argmin(below[::-1])) if not below.all() else 0
    if first == 0:
        return float(times[0])
    e0, e1 = magnitude[first - 1], magnitude[first]
    t0, t1 = times[first - 1], times[first]
    if e1 == 0.0:
        return float(t1)
    weight = math.log(e0 / target) / math.log(e0 / e1)
    return math.exp(math.log(t0) + weight * (math.log(t1) - math.log(t0)))


def parse_grids(text: str, case: Case) -> tuple[int, ...]:
    """'33,65,129' -> (33, 65, 129), checked by `check_grids`; CaseError under the key --grids."""
    try:
        grids = [int(item) for item in text.split(",")]
    except ValueError:
        raise CaseError("--grids", text, "comma-separated nodes per side, e.g. 33,65,129,257") from None
    return check_grids(grids, case)


def check_grids(grids: Sequence[int], case: Case) -> tuple[int, ...]:
    """At least three grids of 2^n + 1 nodes (each validated like solver.grid), ascending, each refining
    the previous by 2; CaseError under the key --grids otherwise."""
    key = "--grids"
    for grid in grids:
        try:
            case.with_grid(grid)
        except CaseError as exc:
            raise CaseError(key, grid, exc.expected) from None
    shown = ",".join(str(grid) for grid in grids)
    check(len(grids) >= 3, key, shown, "at least three grids (the observed order needs three)")
    check(all(b - 1 == 2 * (a - 1) for a, b in pairwise(grids)), key, shown,
          "ascending grids, each refining the previous by 2 (n - 1 doubles), e.g. 33,65,129")
    return tuple(int(grid) for grid in grids)


def check_tolerance(tolerance: float) -> None:
    """CaseError under --tol unless 0 < tolerance < 1."""
    check(0.0 < tolerance < 1.0, "--tol", tolerance, "a relative tolerance in (0, 1), e.g. 0.01")


def with_thermal(case: Case, thermal: str) -> Case:
    """The case with solver.thermal replaced (CaseError under --thermal for an unknown model)."""
    check(thermal in THERMAL_MODELS, "--thermal", thermal, "one of " + ", ".join(THERMAL_MODELS))
    chosen = replace(case, solver=replace(case.solver, thermal=thermal))
    check_thermal_inputs(chosen, "--thermal")
    return chosen


def run_sweep(
    case: Case,
    grids: Sequence[int],
    *,
    point: str | None = None,
    thermal: str | None = None,
    tolerance: float = 0.01,
    jobs: int | None = None,
    progress: Progress | None = None,
    solver: Solver | StagedSolver | None = None,
) -> Sweep:
    """Solve `point` (default: the case's first) of `case` on every grid of `grids` (see `check_grids`),
    on up to `jobs` worker processes (None: all cores), the finest grid first; `thermal` overrides
    solver.thermal; `solver`: the EHL solver unless a stand-in is given. Bad input raises CaseError before any
    solve."""
    grids = check_grids(grids, case)
    check_tolerance(tolerance)
    if thermal is not None:
        case = with_thermal(case, thermal)
    analysis = contact_analysis(case)
    target = analysis.points[0] if point is None else select_points(analysis.points, [point], key="--point")[0]
    # The finest grid, the longest solve, starts first so that the others fill the remaining workers.
    finest_first = sorted(range(len(grids)), key=lambda i: -grids[i])
    settings = _on_one_domain(target, case, [case.with_grid(g).solver for g in grids])
    tasks = [SolveTask(replace(target, name=f"{target.name}@{grids[i]}"), case.lubricant, settings[i])
             for i in finest_first]
    solved, failed_tasks = solve_all(tasks, solver or ehl_solver(), jobs=jobs, progress=progress)
    solutions: list[PointSolution] = [None] * len(grids)
    for task_index, index in enumerate(finest_first):
        solutions[index] = solved[task_index]
    failed = {finest_first[task_index] for task_index in failed_tasks}
    quantities = _quantities(grids, solutions, tolerance)
    overrides: dict[str, object] = {"point": target.name, "grids": list(grids)}
    if thermal is not None:
        overrides["thermal"] = thermal
    targeted: list[PointSolution] = []
    if case.solver.accuracy is not None:  # the point solved to the accuracy target, against the sweep's f*
        targeted = solved_to_accuracy([SolveTask(replace(target, name=f"{target.name}@accuracy"), case.lubricant,
                                                 case.solver)], solver, jobs, progress)
        overrides["accuracy"] = case.solver.accuracy
    run = RunResult(
        case=case,
        points=tuple(solutions + targeted),
        failed=tuple(solutions[i].name for i in sorted(failed)),
        contact=analysis.path,
        contact_scalars=analysis.scalars,
        sweep=sweep_table(grids, solutions, quantities),
        sweep_scalars=_sweep_scalars(tolerance, quantities) | _accuracy_scalars(targeted, quantities),
        warnings=analysis.warnings + _model_warnings(case, solutions)
        + iteration_warnings(quantities, case.solver.thermal_tolerance),
        overrides=overrides,
        convergence_bands=convergence_bands(),
    )
    return Sweep(point=target.name, grids=grids, tolerance=tolerance, quantities=quantities, run=run)


def _on_one_domain(point: ContactPoint, case: Case, settings: list[SolverSettings]) -> list[SolverSettings]:
    """The grids' settings on one domain: without `solver.domain`, the one the finest grid's solve would choose
    (ehl.domain: an inlet lengthened at the spacing of each grid), so that the grids differ in spacing alone."""
    if case.solver.domain_x is not None and case.solver.domain_y is not None:
        return settings
    finest = settings[-1]
    domain = solution_domain(scaling_for(point, case.lubricant), finest)
    fx, fy = (domain.nx - 1) // (finest.grid - 1), (domain.ny - 1) // (finest.nodes_y - 1)
    return [replace(s, grid=(s.grid - 1) * fx + 1, grid_y=(s.nodes_y - 1) * fy + 1, domain_x=domain.x,
                    domain_y=domain.y) for s in settings]


def _quantities(grids: Sequence[int], solutions: Sequence[PointSolution], tolerance: float) -> tuple[Convergence, ...]:
    """Every quantity of QUANTITIES that all grids whose solve converged give, non-zero (a relative change needs it).
    A grid whose solve did not converge counts as NaN, whether or not it reports the quantity (a closed film reports
    none): no change, order or extrapolation is taken from it."""
    table = []
    converged = [s for s in solutions if s.converged]
    for name in QUANTITIES:
        if converged and all(name in s.scalars and s.scalar(name) != 0.0 for s in converged):
            units = converged[0].scalars[name][1]
            values = [s.scalar(name) if s.converged else math.nan for s in solutions]
            table.append(convergence(name, units, grids, values, tolerance))
    return tuple(table)


def iteration_warnings(quantities: Sequence[Convergence], thermal_tolerance: float) -> tuple[str, ...]:
    """A warning when dT_max changes between the two finest grids that converged by less than ITERATION_MARGIN
    times the thermal loop's tolerance, thermal_tolerance (of the rise) times the finest grid's dT_max (K)."""
    dt_max = next((q for q in quantities if q.name == "dT_max"), None)
    solved = [] if dt_max is None else [v for v in dt_max.values if math.isfinite(v)]
    if len(solved) < 2:
        return ()
    rise = abs(solved[-1])
    change, loop = abs(solved[-1] - solved[-2]), thermal_tolerance * rise
    if change >= ITERATION_MARGIN * loop:
        return ()
    return (f"dT_max changes by {change:.3g} K between the two finest grids, less than {ITERATION_MARGIN:g}x the "
            f"thermal loop's tolerance ({thermal_tolerance:.0e} of the {rise:.3g} K rise = {loop:.3g} K): "
            f"its order and extrapolation measure the loop's iteration error as much as the grid; sweep with "
            f"solver.thermal_tolerance below {change / (ITERATION_MARGIN * rise):.1e}",)


def _model_warnings(case: Case, solutions: Sequence[PointSolution]) -> tuple[str, ...]:
    """A remark for each grid whose solver used another thermal model than the case asks for (`auto` picks
    one per solve: a remark when the grids did not all get the same)."""
    wanted = case.solver.thermal
    used = [str(s.models["thermal"]) for s in solutions if "thermal" in s.models]
    if wanted == "auto":
        return () if len(set(used)) <= 1 else (f"thermal model auto chose differently per grid: {', '.join(used)}",)
    return tuple(
        f"{s.name}: thermal model {str(wanted)!r} asked for, the solver used {s.models['thermal']!r}"
        for s in solutions
        if "thermal" in s.models and s.models["thermal"] != wanted
    )


def sweep_table(
    grids: Sequence[int], solutions: Sequence[PointSolution], quantities: Sequence[Convergence]
) -> dict[str, Field]:
    """The /sweep table (SI), one row per grid: the solve's convergence and cost, then for each quantity its
    value, change, order, extrapolated value, uncertainty and error (NaN where not defined)."""

    def scalar(key: str) -> np.ndarray:
        return np.array([s.scalar(key) if key in s.scalars else math.nan for s in solutions])

    table = {
        "grid": Field(np.array(grids, dtype=float), "1",
                      "nodes per side of the grid asked (along x with grid_y): its spacing over the default 6 "
                      "semi-axes; a lengthened inlet adds nodes at that spacing (ehl.domain)"),
        "converged": Field(np.array([float(s.converged) for s in solutions]), "1", "1: the solve met its tolerances"),
        "iterations": Field(scalar("iterations"), "1", "V-cycles on the finest grid"),
        "work_units": Field(scalar("work_units"), "1", "work units of the solve"),
        "wall_time": Field(scalar("wall_time"), "s", "wall time of the solve"),
    }
    for q in quantities:
        table[q.name] = Field(q.values, q.units, f"{q.name} on this grid")
        table[f"{q.name}_change"] = Field(q.change, "1", "relative change from the previous grid, (f_h - f_2h)/|f_h|")
        table[f"{q.name}_order"] = Field(q.order, "1", "observed order, log2(|f_2h - f_4h| / |f_h - f_2h|)")
        table[f"{q.name}_extrapolated"] = Field(q.extrapolated, q.units,
                                                f"Richardson value f_h + (f_h - f_2h)/(2^p - 1); p above {MAX_ORDER}: "
                                                f"the formal order {ORDER}")
        table[f"{q.name}_uncertainty"] = Field(
            q.uncertainty, q.units, f"GCI (Roache 1994), {SAFETY_FACTOR} |f_h - f_2h|/(2^p - 1); p above {MAX_ORDER}: "
                                    f"{HIGH_ORDER_SAFETY_FACTOR:g} |f_h - f_2h|/(2^{ORDER} - 1)")
        table[f"{q.name}_error"] = Field(q.error, "1", "relative error against the extrapolated value of the "
                                                       "three finest grids")
        table[f"{q.name}_bound"] = Field(scalar(f"error_bound_{q.name}"), "1",
                                         "the solve's own error bound on this grid (ehl/error_bounds.py); NaN where "
                                         "unresolved or not given")
        table[f"{q.name}_unresolved"] = Field(scalar(f"unresolved_{q.name}"), "1",
                                              "1: the solve cannot bound the figure on this grid (NaN: not given)")
    return table


def _sweep_scalars(tolerance: float, quantities: Sequence[Convergence]) -> dict[str, tuple[float, str]]:
    scalars = {"tolerance": (tolerance, "1"), "safety_factor": (SAFETY_FACTOR, "1"),
               "high_order_safety_factor": (HIGH_ORDER_SAFETY_FACTOR, "1"), "max_order": (MAX_ORDER, "1")}
    for q in quantities:
        if q.converged_grid is not None:
            scalars[f"{q.name}_converged_grid"] = (float(q.converged_grid), "1")
    return scalars


def _accuracy_scalars(targeted: Sequence[PointSolution], quantities: Sequence[Convergence]
                      ) -> dict[str, tuple[float, str]]:
    """The accuracy target's solution against the sweep: the target, the grid it was solved on and the relative
    difference of each quantity from the extrapolated value f* of the three finest grids (where there is one)."""
    if not targeted or not targeted[0].accuracy or "grid" not in targeted[0].scalars:
        return {}
    solution = targeted[0]
    scalars = {"accuracy": (solution.accuracy.target, "1"), "accuracy_grid": (solution.scalar("grid"), "1"),
               "accuracy_grid_y": (solution.scalar("grid_y"), "1")}
    for q in quantities:
        best = q.extrapolated[-1]
        if q.name in solution.scalars and math.isfinite(best) and best != 0.0:
            scalars[f"{q.name}_accuracy_error"] = ((solution.scalar(q.name) - best) / abs(best), "1")
    return scalars


def _accuracy_lines(table: Mapping[str, Field], scalars: Mapping[str, float]) -> list[str]:
    """The accuracy target's solution against the sweep's extrapolation, one line per quantity."""
    if "accuracy" not in scalars:
        return []
    grid = f"{scalars['accuracy_grid']:.0f} x {scalars['accuracy_grid_y']:.0f}"
    lines = [f"accuracy target {PERCENT(scalars['accuracy']):g} %: solved on {grid} (the point @accuracy; its "
             "figures' bounds: tehl info)"]
    for name in tabulated(table):
        error = scalars.get(f"{name}_accuracy_error")
        against = "no extrapolated value" if error is None else f"{PERCENT(error):+.2f} % from the extrapolated value"
        lines.append(f"  {name}: {against}")
    return lines


def write_csv(table: Mapping[str, Field], path: str | Path) -> Path:
    """The table as CSV (header `name [units]`, SI, an empty cell where a value is not defined), written
    to a temporary file and renamed onto `path`."""
    target = Path(path)
    names = list(table)
    lines = [",".join(f"{name} [{table[name].units}]" for name in names)]
    for row in zip(*(np.asarray(table[name].values, dtype=float) for name in names)):
        lines.append(",".join("" if math.isnan(v) else f"{v:.10g}" for v in row))
    remove_stale(target)  # a killed writer's temporary file
    temporary = temporary_beside(target)
    try:
        temporary.write_text("\n".join(lines) + "\n", encoding="utf-8")
        os.replace(temporary, target)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    return target


def report(table: Mapping[str, Field], scalars: Mapping[str, float]) -> str:
    """The printed report of a /sweep table and its scalars: the cost of each grid, each quantity's
    convergence in display units, then a line per quantity (grid within the tolerance, extrapolated value)."""
    grids = [f"{g:.0f}" for g in table["grid"].values]
    cost_rows = [[grid, yes_no(table["converged"].values[i]), *(c.text(table[c.key].values[i], "") for c in COST)]
                 for i, grid in enumerate(grids)]
    tables = [format_table(["grid", "converged", *(c.header for c in COST)], cost_rows)]
    for name in tabulated(table):
        unit = display(table[name].units)
        value, extra = f".{unit.decimals}f", f".{unit.decimals + 1}f"
        columns = [(name, unit, value), (f"{name}_change", PERCENT, "+.2f"), (f"{name}_order", display("1"), ".2f"),
                   (f"{name}_extrapolated", unit, extra), (f"{name}_uncertainty", unit, extra),
                   (f"{name}_error", PERCENT, "+.2f")]
        rows = [[grid, *(cell(shown(table[key].values[i]), spec) for key, shown, spec in columns),
                 _bound_text(table, name, i)] for i, grid in enumerate(grids)]
        headers = [f"{name} [{unit.label}]", "value", "change %", "order", "extrapolated", "± GCI", "error %",
                   "bound %"]
        tables.append(format_table(headers, rows))
    return "\n\n".join(tables) + "\n\n" + "\n".join(_summary_lines(table, scalars) + _accuracy_lines(table, scalars))


def _bound_text(table: Mapping[str, Field], name: str, row: int) -> str:
    """The solve's own error bound of a quantity on one grid in %, "unresolved" where it cannot bound it, "-" where
    the table has none (a table written before the bounds)."""
    if f"{name}_unresolved" not in table:
        return "-"
    if table[f"{name}_unresolved"].values[row] == 1.0:
        return UNRESOLVED_WORD
    return cell(PERCENT(table[f"{name}_bound"].values[row]), ".2f", "-")


def _summary_lines(table: Mapping[str, Field], scalars: Mapping[str, float]) -> list[str]:
    """Per quantity of a /sweep table: the first grid within the tolerance, and the extrapolated value of
    the three finest grids."""
    tolerance = PERCENT(scalars["tolerance"])
    lines = []
    for name in tabulated(table):
        unit = display(table[name].units)
        grid = scalars.get(f"{name}_converged_grid")
        within = f"within {tolerance:g} % from grid {grid:.0f} on" if grid else f"not within {tolerance:g} %"
        best, spread = table[f"{name}_extrapolated"].values[-1], table[f"{name}_uncertainty"].values[-1]
        order = table[f"{name}_order"].values[-1]
        if math.isnan(best):
            reason = "no change between the two coarser" if math.isnan(order) else f"observed order {order:.2f}"
            extrapolated = f"no extrapolated value from the three finest grids ({reason})"
        else:
            spec = f".{unit.decimals + 1}f"
            bound = scalars.get("max_order", math.inf)  # a file written before the bound: p was taken as observed
            taken = (f"; above {bound:g}: order {ORDER}, safety factor {scalars['high_order_safety_factor']:g}"
                     if order > bound else "")
            extrapolated = (f"extrapolated {unit(best):{spec}} ± {unit(spread):{spec}} {unit.label} "
                            f"(order {cell(order, '.2f') or 'not defined'}{taken})")
        lines.append(f"{name}: {within}; {extrapolated}")
    return lines


def tabulated(table: Mapping[str, Field]) -> list[str]:
    """The quantities a /sweep table holds, in its order."""
    return [name for name in table if f"{name}_order" in table]
