"""The accuracy target against fine-grid references of the same case and model (docs/accuracy.md, the accuracy target).

    python scripts/accuracy_check.py TARGET.h5 --fine FINE.h5... [--finer FINER.h5...] [--default DEFAULT.h5]

TARGET.h5 from `tehl run CASE --accuracy 1%`; FINE.h5 and FINER.h5 from `tehl run CASE --grid N` on two grids, the
second twice as fine (both axes), each of them one file or several (points solved apart with `--points`: each point
from the first file that holds it); DEFAULT.h5 from `tehl run CASE` on the case's own grid, for the cost. The
reference is the Richardson value of FINE and FINER at each figure's order (second for the film and p_max, first for
dT_max and mu: ehl/error_bounds.py); FINER alone where FINE's own solve flags the figure unresolved (a value outside
the asymptotic range extrapolates nowhere); FINE alone where FINER is not given, lacks the point or did not
converge; a reference whose own solve flags the figure unresolved is marked so (it is no reference). Per point and
figure it prints the target's value, its bound and verdict, the reference, which one it is, and the target's error
against it; per point the grid chosen, the cheaper models taken, the grids solved, the solves
and their wall and CPU time, and the reported grid's nodes over the default run's with its wall and CPU time (each
with its error check's time).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from types import SimpleNamespace

from facegear_tehl.accuracy_target import FIGURES
from facegear_tehl.ehl.error_bounds import ORDERS, compression_held
from facegear_tehl.ehl.richardson import richardson_error
from facegear_tehl.results import read_result
from facegear_tehl.tables import format_table


def flagged(solved, name: str) -> bool:
    """The solve flags the figure unresolved (no bound: error_bounds.py), or it is a dT_max the film's compression
    holds (error_bounds.compression_held, applied here too to files written before that rule took its present form)."""
    if solved.scalars.get(f"unresolved_{name}", 0.0) == 1.0:
        return True
    as_solved = SimpleNamespace(scalars={key: (value, "") for key, value in solved.scalars.items()})
    return name == "dT_max" and compression_held(as_solved)


def reference(name: str, point: str, fine: dict, finer: dict) -> tuple[float, str]:
    """The reference value of the figure and where it comes from: the Richardson value of the two reference grids,
    FINER alone where FINE flags the figure unresolved, FINE alone where FINER lacks the point or did not converge;
    "(unresolved)" added where the reference taken flags the figure unresolved itself."""
    coarse = fine[point]
    if point not in finer or not finer[point].converged:
        return coarse.scalars[name], "fine (unresolved)" if flagged(coarse, name) else "fine"
    f_h = finer[point].scalars[name]
    if flagged(coarse, name):
        return f_h, "finer (unresolved)" if flagged(finer[point], name) else "finer"
    f_2h = coarse.scalars[name]
    return f_h * (1.0 + richardson_error(f_h, f_2h, ORDERS[name])), "Richardson"  # f* = f_h + (f_h - f_2h)/(2^p - 1)


def figure_rows(target, fine, finer) -> list[list[str]]:
    """One row per point and figure: value, bound, verdict, reference, error against it; a run without an accuracy
    target (the default grid) has the bound of its file (`error_bound_<name>`, or unresolved) and no verdict."""
    rows = []
    for point, solved in target.points.items():
        if solved.accuracy is not None:
            figures = {f.name: (f.bound, f.verdict.value) for f in solved.accuracy.figures}
        else:
            figures = {name: (solved.scalars.get(f"error_bound_{name}", math.nan),
                              "unresolved" if flagged(solved, name) else "-") for name in FIGURES}
        for name in FIGURES:
            if name not in solved.scalars or name not in figures:
                continue
            best, source = reference(name, point, fine, finer)
            error = (solved.scalars[name] - best) / abs(best)
            bound, verdict = figures[name]
            rows.append([point, name, f"{solved.scalars[name]:.5g}", "-" if math.isnan(bound) else f"{100 * bound:.2f}",
                         verdict, f"{best:.5g}", source, f"{100 * error:+.2f}"])
    return rows


def _seconds(scalars) -> tuple[float, float]:
    """A solve's wall and CPU time with its error check's (s; ehl/error_bounds.py keeps those apart from the solve's;
    a file without CPU times: the wall times)."""
    check = scalars.get("error_check_time", 0.0)
    return (scalars["wall_time"] + check,
            scalars.get("cpu_time", scalars["wall_time"]) + scalars.get("error_check_cpu_time", check))


MODEL_CHOICES = ("thermal", "thermal_layers", "rheology", "model")  # the choices of a cheaper model (the rest: grids)


def cost_rows(target, default) -> list[list[str]]:
    """One row per point: the grid chosen, the cheaper models taken, the grids solved, their wall and CPU time, and
    the reported grid's nodes over the default run's (as solved) with its wall and CPU time."""
    rows = []
    for point, solved in target.points.items():
        record = solved.accuracy
        if record is None:  # a run without an accuracy target: no choices to show
            continue
        grid = next(c.chosen for c in record.choices if c.what == "grid")
        taken = [c for c in record.choices if c.what in MODEL_CHOICES and c.chosen != "as the case"]
        models = "; ".join(f"{c.what} {c.chosen}" for c in taken) or "the case's"
        grids = ", ".join(s.grid + ("" if s.outcome == "converged" else f" ({s.outcome})") for s in record.steps
                          if not s.purpose.startswith("model check"))
        default_time, default_grid, nodes = "-", "-", "-"
        if default is not None:
            scalars = default.points[point].scalars
            default_time = "{:.1f} ({:.1f})".format(*_seconds(scalars))
            default_grid = f"{scalars['grid']:.0f} x {scalars['grid_y']:.0f}"
            nodes = f"{record.nodes / (scalars['grid'] * scalars['grid_y']):.2g}"
        rows.append([point, grid, models, grids, str(len(record.steps)),
                     f"{record.wall_time:.1f} ({record.cpu_time:.1f})", default_grid, nodes, default_time, record.stop])
    return rows


def points_of(paths: list[Path]) -> dict:
    """Point name -> its result, each from the first of `paths` that holds it."""
    points: dict = {}
    for path in paths:
        for name, solved in read_result(path, fields=False).points.items():
            points.setdefault(name, solved)
    return points


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("target", type=Path)
    parser.add_argument("--fine", type=Path, nargs="+", required=True)
    parser.add_argument("--finer", type=Path, nargs="+", default=[])
    parser.add_argument("--default", type=Path)
    args = parser.parse_args()
    target = read_result(args.target, fields=False)
    fine, finer = points_of(args.fine), points_of(args.finer)
    default = read_result(args.default, fields=False) if args.default else None
    print(format_table(["point", "figure", "value (SI)", "bound %", "verdict", "reference", "from", "error %"],
                       figure_rows(target, fine, finer)))
    print()
    print(format_table(["point", "grid chosen", "models", "grids solved", "solves", "wall (CPU) s", "default grid",
                        "nodes / default", "default wall (CPU) s", "stop"], cost_rows(target, default)))


if __name__ == "__main__":
    main()
