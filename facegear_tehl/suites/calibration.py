"""Calibration of the error bounds (ehl/error_bounds.py): points solved on a coarse grid, each reported bound set
against the true error, from a reference of the same model on the same domain with twice the nodes along x and y,
Richardson-extrapolated at each figure's order (f* = f_2 + (f_2 - f_1)/(2^p - 1); p = 2 for the film and pressure
figures, 1 for temperatures and mu, the orders report.py assumes). scripts/calibrate_errors.py runs it; its table
is in docs/accuracy.md (error bounds).

The points: the envelope suite (suites/envelope.py) on ENVELOPE_GRIDS, S1-S5 of the shipped face gear case (shaft
angle 110 deg) and of the orthogonal cases/facegear_90.yaml on GEAR_GRIDS, and the S3 of random face gear designs
(suites/gear_designs.py, fixed seed: shaft angles 60-135 deg, unit loads 5-80 N/mm^2) on the coarse gear grid.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
import fnmatch
import math
from pathlib import Path
import statistics

from facegear_tehl.case import Case, load_case, parse_case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.error_bounds import FILM_FIGURES, ORDERS, STATE_FIGURES
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.points import contact_analysis
from facegear_tehl.schema import CaseError
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import Outcome, PointSolution
from facegear_tehl.suites.envelope import envelope_cases
from facegear_tehl.suites.gear_designs import random_designs

ENVELOPE_GRIDS = ((129, 33), (257, 65))  # (nx, ny) asked: coarse, and the shipped case's default
GEAR_GRIDS = ((65, 17), (129, 33))  # the gear cases' --grid 65 and --grid 129 (65 x 17 has no y-check: unresolved)
GEAR_CASES = ("facegear_110.yaml", "facegear_90.yaml")  # in cases/: shaft angles 110 and 90 deg
QUICK_ENVELOPE = "ab*_ph*_u2_iso"  # the quick subset's envelope cases: the isothermal core at 2 m/s (16 contacts)
# and four of its thermal Ree-Eyring core (u_e 10 m/s, SRR 0.5) on the coarse grid alone
QUICK_THERMAL = ("ab5_ph0.8_u10_srr0.5_th", "ab30_ph0.8_u10_srr0.5_th", "ab5_ph1.5_u10_srr0.5_th",
                 "ab30_ph1.5_u10_srr0.5_th")
DESIGN_SEED = 46  # the random designs' seed (fixed: the calibration is repeatable)
UNDERSTATED = 2.0  # a bound below the true error by more than this factor is a failure of the acceptance


@dataclass(frozen=True)
class CalibrationPoint:
    """One point of the calibration on the grid asked (`settings`)."""

    name: str
    group: str
    point: ContactPoint
    lubricant: Lubricant
    settings: SolverSettings


@dataclass(frozen=True)
class Comparison:
    """One reported figure of one point against its true error (relative); bound NaN where unresolved; estimate:
    the x-only Richardson estimate the solve reported before the bounds (NaN where it had none)."""

    name: str
    quantity: str
    true_error: float
    bound: float
    unresolved: bool
    estimate: float = math.nan
    shift: float = math.nan  # h_min: how far its place moved to the reference's, in the point's grid spacings
    check_cost: float = math.nan  # the error check's time over the point's own solve time

    @property
    def bounded(self) -> bool:
        return not self.unresolved and abs(self.true_error) <= self.bound

    @property
    def understated(self) -> bool:
        return not self.unresolved and abs(self.true_error) > UNDERSTATED * self.bound


def calibration_points(quick: bool, cases_folder: Path, designs: int = 10,
                       envelope_grids: int = 1) -> list[CalibrationPoint]:
    """The points (module docstring): the envelope on its first `envelope_grids` grids; `quick`: the isothermal
    envelope core at 2 m/s, four thermal core contacts and the gear cases' S3 alone."""
    points, envelope = [], []  # the gear points first
    for case in envelope_cases():
        if quick and not (fnmatch.fnmatch(case.name, QUICK_ENVELOPE) or case.name in QUICK_THERMAL):
            continue
        for nx, ny in ENVELOPE_GRIDS[:1] if quick and case.thermal else ENVELOPE_GRIDS[:envelope_grids]:
            envelope.append(CalibrationPoint(f"{case.name} {nx}x{ny}", "envelope", case.point(), case.lubricant(),
                                             case.settings(nx, ny)))
    text = (cases_folder / GEAR_CASES[0]).read_text()
    gears = [(Path(name).stem, load_case(cases_folder / name), GEAR_GRIDS) for name in GEAR_CASES]
    if not quick:
        gears += [(f"design{d.index}", case, GEAR_GRIDS[1:]) for d in random_designs(designs, DESIGN_SEED)
                  if (case := _design_case(d.case_text(text, *GEAR_GRIDS[1]), d.index)) is not None]
    for label, case, grids in gears:
        for point in contact_analysis(case).points:
            if (quick or label.startswith("design")) and point.name != "S3":
                continue
            for nx, ny in grids:
                points.append(CalibrationPoint(f"{label} {point.name} {nx}x{ny}", "gear", point, case.lubricant,
                                               replace(case.solver, grid=nx, grid_y=ny)))
    return points + envelope


Solve = Callable[[ContactPoint, Lubricant, SolverSettings], PointSolution]


def _design_case(text: str, index: int) -> Case | None:
    """A random design's case; None for a design the case check rejects (no drive: e.g. a face gear tip that meets
    the pinion below its base circle)."""
    try:
        return parse_case(text, f"design{index}")
    except CaseError:
        return None


def compare(calibration: CalibrationPoint, bounded: Solve, reference: Solve) -> list[Comparison]:
    """The point solved with its bounds (`bounded`), then again (`reference`) on its domain with 2n - 1 nodes along
    x and y; one Comparison per figure both report. None where either solve did not converge."""
    solution = bounded(calibration.point, calibration.lubricant, calibration.settings)
    if solution.outcome is not Outcome.CONVERGED or "h_min" not in solution.scalars:
        return []
    x, y = solution.axes["x"].values, solution.axes["y"].values
    a, b = solution.scalar("a"), solution.scalar("b")
    finer = replace(calibration.settings, grid=2 * x.size - 1, grid_y=2 * y.size - 1,
                    domain_x=(x[0] / b, x[-1] / b), domain_y=(y[0] / a, y[-1] / a))
    fine = reference(calibration.point, calibration.lubricant, finer)
    if fine.outcome is not Outcome.CONVERGED or "h_min" not in fine.scalars:
        return []
    out, cost = [], _check_cost(solution)
    for name in FILM_FIGURES + STATE_FIGURES:
        if name not in solution.scalars or name not in fine.scalars or f"unresolved_{name}" not in solution.scalars:
            continue
        coarse, ref = solution.scalar(name), fine.scalar(name)
        truth = ref + (ref - coarse) / (2.0 ** ORDERS[name] - 1.0)
        if truth == 0.0:
            continue
        unresolved = solution.scalar(f"unresolved_{name}") == 1.0
        bound = math.nan if unresolved else solution.scalar(f"error_bound_{name}")
        estimate = solution.scalars.get(f"error_estimate_{name}", (math.nan, "1"))[0]
        shift = _place_shift(solution, fine) if name == "h_min" else math.nan
        out.append(Comparison(calibration.name, name, coarse / truth - 1.0, bound, unresolved, estimate, shift, cost))
    return out


def _place_shift(solution: PointSolution, fine: PointSolution) -> float:
    """How far the lowest film's place moved from `solution` to `fine`: the larger of |dx| and |dy| in the
    solution's grid spacings along x and y."""
    x, y = solution.axes["x"].values, solution.axes["y"].values
    return max(abs(fine.scalar("x_h_min") - solution.scalar("x_h_min")) / (x[1] - x[0]),
               abs(fine.scalar("y_h_min") - solution.scalar("y_h_min")) / (y[1] - y[0]))


def _check_cost(solution: PointSolution) -> float:
    """The error check's time over the point's own solve time (error_bounds.with_error_bounds)."""
    check = solution.scalars.get("error_check_time", (math.nan, "s"))[0]
    return check / solution.scalar("wall_time")


def point_lines(comparisons: Iterable[Comparison]) -> list[str]:
    """One line per comparison: point, figure, true error and bound in %, and the verdict."""
    lines = []
    for c in comparisons:
        bound = "unresolved" if c.unresolved else f"{100 * c.bound:9.3f}"
        verdict = "unresolved" if c.unresolved else "bounded" if c.bounded else "NOT BOUNDED"
        place = f"  place moved {c.shift:.1f} spacings" if math.isfinite(c.shift) else ""
        lines.append(f"{c.name:40s} {c.quantity:7s} true {100 * c.true_error:+9.3f} %  bound {bound:>10s}  {verdict}"
                     + place)
    return lines


def summary(comparisons: Sequence[Comparison]) -> str:
    """Per figure and in all: figures compared, unresolved, bounded (share of the resolved), understated more than
    UNDERSTATED-fold, the largest |true error|/bound among the resolved, and for comparison the share of all
    figures whose x-only estimate alone was at least the true error (a Markdown table)."""
    lines = ["| figure | compared | unresolved | bounded | share bounded | understated > 2x | largest true/bound | "
             "x-estimate alone bounded |", "|---|---|---|---|---|---|---|---|"]
    for name in (*FILM_FIGURES, *STATE_FIGURES, "all"):
        chosen = [c for c in comparisons if name in ("all", c.quantity)]
        if not chosen:
            continue
        resolved = [c for c in chosen if not c.unresolved]
        bounded = sum(c.bounded for c in resolved)
        share = f"{100 * bounded / len(resolved):.0f} %" if resolved else "-"
        worst = max((abs(c.true_error) / c.bound if c.bound > 0 else math.inf for c in resolved), default=math.nan)
        alone = sum(abs(c.true_error) <= abs(c.estimate) for c in chosen)  # False for a NaN estimate
        lines.append(f"| {name} | {len(chosen)} | {len(chosen) - len(resolved)} | {bounded} | {share} | "
                     f"{sum(c.understated for c in resolved)} | {worst:.2f} | {100 * alone / len(chosen):.0f} % |")
    unresolved = [abs(c.true_error) for c in comparisons if c.unresolved]
    shifts = [c.shift for c in comparisons if c.quantity == "h_min" and not c.unresolved and math.isfinite(c.shift)]
    costs = {c.name: c.check_cost for c in comparisons if math.isfinite(c.check_cost)}
    lines.append("")
    if unresolved:
        lines.append(f"unresolved figures: median |true error| {100 * statistics.median(unresolved):.2f} %, largest "
                     f"{100 * max(unresolved):.1f} %")
    if shifts:
        lines.append(f"place of a resolved h_min: moved {statistics.median(shifts):.1f} grid spacings (median), "
                     f"{max(shifts):.1f} at most")
    if costs:
        lines.append(f"error check time over the point's own solve: median {statistics.median(costs.values()):.2f} "
                     f"({len(costs)} points)")
    return "\n".join(lines)
