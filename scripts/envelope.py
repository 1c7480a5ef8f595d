"""Envelope suite (the contacts and their check: facegear_tehl/suites/envelope.py), solved and mapped (issue 14).

Solves them all with the project's parallel runner and prints a markdown table (outcome, grid, cycles, thermal
outer iterations, wall time, h_c, h_min, p_max, error estimates or why a figure is unresolved, the energy balance of
thermal cases, the sides' pressure ratio (ehl.domain.side_pressure_ratio), a check of the fields and of that balance,
the message of a case that did not converge or kept a coarser grid), a summary per model, p_h and a/b, the failures
grouped by outcome and message, and the median and worst wall time. Exit code 1 if
any case did not converge or a solution fails its check.

    python scripts/envelope.py [--grid 257] [--grid-y 65] [--jobs N] [--only PATTERN[,PATTERN]]
                               [--thermal-only | --iso-only] [--map FILE.png] [--save DIR] [--list]
"""

from __future__ import annotations

import argparse
from collections import defaultdict
from collections.abc import Sequence
import csv
from dataclasses import dataclass
import math
from pathlib import Path
import re
import statistics
import sys
import time

from facegear_tehl.ehl.unresolved import Why
from facegear_tehl.solution import Outcome, PointSolution
from facegear_tehl.suites.envelope import (
    CHECK_PASSED,
    CORE_PRESSURES,
    CORE_SPEEDS,
    GRID,
    GRID_Y,
    PRESSURE_VISCOSITY,
    THERMAL_SRR,
    VISCOSITY,
    EnvelopeCase,
    check_solution,
    envelope_cases,
    scalar_or_nan,
    select,
)
from facegear_tehl.tables import UNRESOLVED_REASON, format_table

OUTCOME_COLOURS = {
    Outcome.CONVERGED: "tab:green",
    Outcome.NOT_CONVERGED: "tab:orange",
    Outcome.DIVERGED: "tab:red",
    Outcome.FILM_CLOSED: "tab:purple",
    Outcome.FAILED: "black",
}


def _cell(solution: PointSolution, key: str, factor: float, spec: str) -> str:
    value = scalar_or_nan(solution, key)
    return "–" if math.isnan(value) else format(value * factor, spec)


def _estimate(solution: PointSolution, figure: str) -> str:
    """The error estimate of `figure` in per cent, or why it is unresolved (the solve bounds no error there: a starved
    domain, a feature the grid does not resolve, ...; ehl.unresolved.Why)."""
    if scalar_or_nan(solution, f"unresolved_{figure}") == 1.0:
        reason = scalar_or_nan(solution, f"{UNRESOLVED_REASON}{figure}")
        return "unresolved" if math.isnan(reason) else f"unresolved: {Why(int(reason)).name.lower().replace('_', ' ')}"
    return _cell(solution, f"error_estimate_{figure}", 100.0, ".2g")


@dataclass(frozen=True)
class Row:
    case: EnvelopeCase
    solution: PointSolution
    check: str

    @property
    def wall_time(self) -> float:
        return scalar_or_nan(self.solution, "wall_time")


COLUMNS = ("case", "a/b", "p_h GPa", "u_e m/s", "SRR", "skew deg", "eta_0 Pa s", "model", "outcome", "grid",
           "cycles", "outer it.", "wall s", "h_c µm", "h_min µm", "p_max GPa", "err h_c %", "err h_min %", "energy %",
           "side p %", "check", "message")


def row_cells(row: Row) -> list[str]:
    c, s = row.case, row.solution
    return [
        c.name, f"{c.ellipticity:g}", f"{c.hertz_pressure * 1e-9:g}", f"{c.entrainment_speed:g}",
        f"{c.slide_roll_ratio:g}", f"{c.skew:g}", f"{c.viscosity:g}", c.model, s.outcome.value,
        _grid(s), _cell(s, "iterations", 1.0, ".0f"), _cell(s, "thermal_iterations", 1.0, ".0f"),
        _cell(s, "wall_time", 1.0, ".1f"), _cell(s, "h_c", 1e6, ".4g"), _cell(s, "h_min", 1e6, ".4g"),
        _cell(s, "p_max", 1e-9, ".3f"), _estimate(s, "h_c"), _estimate(s, "h_min"),
        _cell(s, "energy_balance_error", 100.0, ".2g"), _cell(s, "side_pressure_ratio", 100.0, ".2g"),
        row.check, s.message,
    ]


def _grid(solution: PointSolution) -> str:
    """The nodes of the grid the solution is on ("nx x ny"; its inlet may have been lengthened: ehl.domain)."""
    if "grid" not in solution.scalars:
        return "–"
    return f"{scalar_or_nan(solution, 'grid'):.0f} x {scalar_or_nan(solution, 'grid_y'):.0f}"


def markdown_table(rows: Sequence[Row]) -> str:
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    lines += ["| " + " | ".join(cell.replace("|", "/") for cell in row_cells(r)) + " |" for r in rows]
    return "\n".join(lines)


def _tally(rows: Sequence[Row], key) -> str:
    """'label: converged/total' for each value of key(row), in sorted order."""
    groups: dict[object, list[Row]] = defaultdict(list)
    for r in rows:
        groups[key(r)].append(r)
    return ", ".join(f"{k:g}: {sum(r.solution.converged for r in g)}/{len(g)}" if isinstance(k, float)
                     else f"{k}: {sum(r.solution.converged for r in g)}/{len(g)}" for k, g in sorted(groups.items()))


def _matrix(rows: Sequence[Row]) -> str:
    """Converged/total over p_h (rows) x a/b (columns), all speeds together."""
    pressures = sorted({r.case.hertz_pressure for r in rows})
    ks = sorted({r.case.ellipticity for r in rows})
    cells = []
    for p in pressures:
        line = [f"{p * 1e-9:g}"]
        for k in ks:
            here = [r for r in rows if r.case.hertz_pressure == p and r.case.ellipticity == k]
            line.append(f"{sum(r.solution.converged for r in here)}/{len(here)}" if here else "")
        cells.append(line)
    return format_table(["p_h GPa \\ a/b", *(f"{k:g}" for k in ks)], cells)


def summary(rows: Sequence[Row], total_time: float, grid: int, grid_y: int | None) -> str:
    """Converged counts overall, per model, per p_h, per a/b (core cases) and per group; failures grouped by
    outcome and message (numbers masked); median and worst wall time."""
    converged = sum(r.solution.converged for r in rows)
    lines = [f"{converged} converged of {len(rows)} on {grid} x {grid_y or grid} "
             f"({total_time:.0f} s in all)"]
    lines.append("per model: " + _tally(rows, lambda r: r.case.model))
    lines.append("per group: " + _tally(rows, lambda r: r.case.group))
    for model in (False, True):
        core = [r for r in rows if r.case.group.startswith("core") and r.case.thermal is model]
        if core:
            name = core[0].case.model
            lines.append(f"core {name} per p_h GPa: " + _tally(core, lambda r: r.case.hertz_pressure * 1e-9))
            lines.append(f"core {name} per a/b: " + _tally(core, lambda r: r.case.ellipticity))
            lines.append(f"core {name} per u_e m/s: " + _tally(core, lambda r: r.case.entrainment_speed))
            lines.append(_matrix(core))
    times = [(r.wall_time, r.case.name) for r in rows if math.isfinite(r.wall_time)]
    if times:
        worst = max(times)
        lines.append(f"wall time per case: median {statistics.median(t for t, _ in times):.1f} s, "
                     f"worst {worst[0]:.1f} s ({worst[1]})")
    bad_checks = [r for r in rows if r.check not in CHECK_PASSED and r.solution.outcome is not Outcome.FAILED]
    if bad_checks:
        lines.append("check: " + "; ".join(f"{r.case.name}: {r.check}" for r in bad_checks))
    groups: dict[tuple[str, str], list[str]] = defaultdict(list)
    for r in rows:
        if not r.solution.converged:
            pattern = re.sub(r"[-+]?\d+(\.\d+)?(e[-+]?\d+)?", "#", r.solution.message)
            groups[(r.solution.outcome.value, pattern)].append(r.case.name)
    if groups:
        lines.append("\nnot converged, by outcome and message (# stands for numbers):")
        for (outcome, pattern), names in sorted(groups.items(), key=lambda item: -len(item[1])):
            lines.append(f"- {outcome} ({len(names)}): {pattern}\n    {', '.join(names)}")
    return "\n".join(lines)


def write_csv(rows: Sequence[Row], path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(COLUMNS)
        writer.writerows(row_cells(r) for r in rows)


# ------------------------------------------------------------------------------------------------------ map
SPEED_BANDS = ((0.0, 1.0), (1.0, 5.0), (5.0, 15.0), (15.0, math.inf))  # m/s, (low, high]


def _band_label(low: float, high: float) -> str:
    if math.isinf(high):
        return f"u_e > {low:g} m/s"
    return f"u_e ≤ {high:g} m/s" if low == 0.0 else f"{low:g} < u_e ≤ {high:g} m/s"


def _variant(case: EnvelopeCase) -> str:
    """The short tag of what differs from its core point ('' for a core case)."""
    tags = []
    if case.thermal and case.slide_roll_ratio != THERMAL_SRR or not case.thermal and case.slide_roll_ratio:
        tags.append(f"SRR{case.slide_roll_ratio:g}")
    if case.skew:
        tags.append(f"{case.skew:g}°")
    if case.viscosity != VISCOSITY:
        tags.append(f"η{case.viscosity:g}")
    if case.pressure_viscosity != PRESSURE_VISCOSITY:
        tags.append(f"α{case.pressure_viscosity * 1e8:g}")
    if case.entrainment_speed not in CORE_SPEEDS + (30.0,):
        tags.append(f"{case.entrainment_speed:g}m/s")
    return " ".join(tags)


def _seconds(t: float) -> str:
    if not math.isfinite(t):
        return ""
    return f"{t:.1f}s" if t < 10.0 else f"{t:.0f}s"


def _clusters(rows: Sequence[Row]) -> dict[tuple[float, float], list[Row]]:
    """Rows by (p_h, a/b), the one without a variant tag (the core case) first in each."""
    clusters: dict[tuple[float, float], list[Row]] = defaultdict(list)
    for r in rows:
        clusters[(r.case.hertz_pressure, r.case.ellipticity)].append(r)
    return {key: sorted(group, key=lambda r: _variant(r.case) != "") for key, group in clusters.items()}


def _ring(group: Sequence[Row]) -> list[tuple[float, float]]:
    """(p_h offset GPa, a/b factor) of each marker of a cluster: a lone or core case at the centre, the others
    evenly on a ring around it."""
    centred = len(group) == 1 or _variant(group[0].case) == ""
    around = len(group) - (1 if centred else 0)
    spots = [(0.0, 1.0)] if centred else []
    for n in range(around):
        angle = math.pi / 2.0 + 2.0 * math.pi * n / around
        spots.append((0.3 * math.cos(angle), math.exp(0.5 * math.sin(angle))))
    return spots


def draw_map(rows: Sequence[Row], path: Path, grid: int, grid_y: int | None) -> None:
    """One panel per model and speed band: p_h against a/b (log), markers coloured by outcome, area by wall time,
    each labelled with its wall time (and what varies, for the one-factor cases)."""
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    models = [m for m in (False, True) if any(r.case.thermal is m for r in rows)]
    bands = [b for b in SPEED_BANDS if any(b[0] < r.case.entrainment_speed <= b[1] for r in rows)]
    fig = Figure(figsize=(4.2 * len(bands), 3.9 * len(models) + 0.8), layout="constrained")
    axes = fig.subplots(len(models), len(bands), squeeze=False, sharex=True, sharey=True)
    finite = [r.wall_time for r in rows if math.isfinite(r.wall_time)]
    scale = max(finite) if finite else 1.0
    for i, model in enumerate(models):
        for j, (low, high) in enumerate(bands):
            ax = axes[i][j]
            members = [r for r in rows if r.case.thermal is model and low < r.case.entrainment_speed <= high]
            for (ph, k), group in _clusters(members).items():
                for (dx, factor), r in zip(_ring(group), group, strict=True):
                    x, y = ph * 1e-9 + dx, k * factor
                    t = r.wall_time
                    size = 25.0 + 400.0 * math.sqrt(t / scale) if math.isfinite(t) else 25.0
                    ax.scatter([x], [y], s=size, c=OUTCOME_COLOURS[r.solution.outcome], alpha=0.75,
                               edgecolors="k", linewidths=0.5, zorder=3)
                    label = " ".join(p for p in (_variant(r.case), _seconds(t)) if p)
                    left = dx < -1e-9
                    ax.annotate(label, (x, y), xytext=(-4 if left else 4, 3), textcoords="offset points",
                                ha="right" if left else "left", fontsize=5.5, zorder=4)
            ax.set_xscale("linear")
            ax.set_yscale("log")
            ax.set_xlim(0.0, 2.9)
            ax.set_ylim(0.6, 200.0)
            ax.grid(True, which="major", alpha=0.3)
            speeds = sorted({r.case.entrainment_speed for r in members})
            if not members:
                ax.text(0.5, 0.5, "no case", transform=ax.transAxes, ha="center", va="center", color="0.5")
            listed = f"\n(u_e = {', '.join(f'{u:g}' for u in speeds)} m/s)" if speeds else "\n"
            ax.set_title(f"{'thermal Ree-Eyring' if model else 'isothermal Newtonian'}, {_band_label(low, high)}"
                         + listed, fontsize=8)
            ax.set_xticks([p * 1e-9 for p in CORE_PRESSURES] + [1.2])
            if i == len(models) - 1:
                ax.set_xlabel("p_h, GPa")
            if j == 0:
                ax.set_ylabel("a/b")
    handles = [Line2D([], [], marker="o", ls="", color=colour, markeredgecolor="k", label=outcome.value)
               for outcome, colour in OUTCOME_COLOURS.items()]
    converged = sum(r.solution.converged for r in rows)
    fig.suptitle(f"Envelope suite on {grid} x {grid_y or grid}: {converged} of {len(rows)} converged "
                 f"(marker area ~ sqrt(wall time); label: variant and wall time)", fontsize=9)
    fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), fontsize=8)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=150)


# ----------------------------------------------------------------------------------------------------- main
def solve_cases(cases: Sequence[EnvelopeCase], grid: int, grid_y: int | None,
                jobs: int) -> tuple[list[Row], float, dict[str, tuple[str, str]]]:
    """Every case solved as `tehl run` solves its points (the parallel runner; a film that closes is solved
    again on a finer grid the solver chooses; progress on stderr); the rows, the total wall time (s) and the
    cases solved on a finer grid (grid asked, grid solved on)."""
    from facegear_tehl.parallel import SolveTask
    from facegear_tehl.run import ehl_solver, solve_refining

    tasks = [SolveTask(c.point(), c.lubricant(), c.settings(grid, grid_y)) for c in cases]

    def progress(solution: PointSolution, done: int, total: int) -> None:
        print(f"[{done}/{total}] {solution.name}: {solution.outcome.value}, "
              f"{_cell(solution, 'wall_time', 1.0, '.1f')} s", file=sys.stderr, flush=True)

    start = time.perf_counter()
    solutions, _, refined = solve_refining(tasks, ehl_solver(), jobs=jobs, progress=progress)
    elapsed = time.perf_counter() - start
    return [Row(c, s, check_solution(s)) for c, s in zip(cases, solutions, strict=True)], elapsed, refined


def selection_arguments(parser: argparse.ArgumentParser) -> None:
    """The grid, jobs and case-selection options of an envelope script."""
    parser.add_argument("--grid", type=int, default=GRID, help=f"nodes along x, the minor axis (default {GRID})")
    parser.add_argument("--grid-y", type=int, default=GRID_Y, help=f"nodes along y, the major axis (default {GRID_Y})")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    parser.add_argument("--only", help="comma-separated name patterns (globs, or substrings without a wildcard)")
    model = parser.add_mutually_exclusive_group()
    model.add_argument("--thermal-only", action="store_true", help="only the thermal Ree-Eyring cases")
    model.add_argument("--iso-only", action="store_true", help="only the isothermal Newtonian cases")


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    selection_arguments(parser)
    parser.add_argument("--map", type=Path, help="draw the envelope map into this PNG")
    parser.add_argument("--save", type=Path, help="write the table as envelope.csv into this folder")
    parser.add_argument("--list", action="store_true", help="list the selected cases and their contacts, no solve")
    args = parser.parse_args(argv)
    thermal = True if args.thermal_only else (False if args.iso_only else None)
    cases = select(envelope_cases(), args.only, thermal)
    if not cases:
        print("no case matches", file=sys.stderr)
        return 2
    if args.list:
        for c in cases:
            point = c.point()
            print(f"{c.name:<34} {c.group:<13} R_y/R_x = {point.radius_y / point.radius_x:9.2f}  "
                  f"W = {point.load:10.4g} N  {c.model}")
        print(f"{len(cases)} cases")
        return 0
    from facegear_tehl.run import refinement_note

    rows, total, refined = solve_cases(cases, args.grid, args.grid_y, args.jobs)
    print(markdown_table(rows))
    print()
    print(summary(rows, total, args.grid, args.grid_y))
    by_name = {row.solution.name: row.solution for row in rows}
    for name, refinement in refined.items():
        print(f"- {refinement_note(name, refinement, by_name[name])}")
    if args.save:
        write_csv(rows, args.save / "envelope.csv")
    if args.map:
        draw_map(rows, args.map, args.grid, args.grid_y)
    ok = all(r.solution.converged and r.check == "ok" for r in rows)  # a converged case must pass its check
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
