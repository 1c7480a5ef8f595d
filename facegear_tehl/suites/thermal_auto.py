"""The contacts `solver.thermal: auto` is fitted to and checked on (ehl/thermal.py `thermal_choice`), their solutions
in the three thermal models, and the upper-envelope fit of the cheaper models' errors against `full`.

The design (`fit_contacts`, `check_contacts`): a Latin hypercube of fixed seed over the entrainment speed u_e (log,
0.5-20 m/s), the slide-to-roll ratio (a fifth of the contacts in pure rolling, the rest uniform on 0-2), the Hertz
pressure p_h (0.4-2 GPa) and the ellipticity a/b (log, 1-100), each contact with one of the oils the project ships
(cases/facegear_110.yaml, cases/facegear_90.yaml, cases/ball_on_disc_sliding.yaml) as Ree-Eyring or Newtonian
fluid, in turn; and four ANCHORS at low heating. Steel on steel, R_x = 20 mm (suites/envelope.py
`contact_geometry`). The thermal loading L_th = beta eta_0 u_e^2/k_f then spans 2.3e-3 to 2.0, the face gear points'
0.08-1.42 inside. Where the hypercube's contacts do not converge on GRID in all three models they are solved on
COARSE_GRID (scripts/thermal_auto_fit.py); the Ree-Eyring ones above 1.3 GPa below 3 m/s and the Newtonian ones at
SRR above 1 converge on neither.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
import math
from pathlib import Path
import time

import numpy as np

from facegear_tehl.case import load_case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.ehl.thermal import AUTO_FIGURES, sliding_heating, thermal_choice, thermal_loading
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.points import contact_analysis
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import PointSolution
from facegear_tehl.suites.envelope import RADIUS_X, STEEL, contact_geometry

FIT_SEED = 46  # the hypercube's seed (fixed: the fit is repeatable)
FIT_COUNT = 20
SPEEDS = (0.5, 20.0)  # m/s, u_e (log-uniform)
PRESSURES = (0.4e9, 2.0e9)  # Pa, p_h
ELLIPTICITIES = (1.0, 100.0)  # a/b (log-uniform)
LARGEST_SRR = 2.0
ROLLING_SHARE = 0.2  # the share of the hypercube's SRR axis mapped to pure rolling
OIL_CASES = ("facegear_110.yaml", "facegear_90.yaml", "ball_on_disc_sliding.yaml")  # in cases/
RHEOLOGIES = ("ree_eyring", "newtonian")
GRID = (257, 65)  # (nx, ny) asked: the shipped case's grid
COARSE_GRID = (129, 33)  # every contact again: the grid check, and the contacts GRID does not converge in all models
MODELS = ("off", "reduced", "full")
FIGURES = ("h_c", "h_min", "mu", "p_max", "dT_max")


@dataclass(frozen=True)
class AutoContact:
    """One contact of the design."""

    name: str
    point: ContactPoint
    lubricant: Lubricant
    oil: str  # the case file whose oil it is

    @property
    def loading(self) -> float:
        """L_th = beta eta_0 u_e^2/k_f (ehl/thermal.py)."""
        return thermal_loading(self.point, self.lubricant)

    @property
    def sliding(self) -> float:
        """Theta_s = beta dT_f/mu (ehl/thermal.py)."""
        return sliding_heating(self.point, self.lubricant)


def shipped_oils(cases_folder: Path) -> dict[str, Lubricant]:
    """The oils of OIL_CASES, by case name."""
    return {Path(name).stem: load_case(cases_folder / name).lubricant for name in OIL_CASES}


def with_rheology(lubricant: Lubricant, rheology: str) -> Lubricant:
    """The oil as a Ree-Eyring fluid (its own tau_0) or as a Newtonian one."""
    if rheology == "newtonian":
        return replace(lubricant, rheology="newtonian", eyring_stress=math.inf)
    return replace(lubricant, rheology="ree_eyring")


def _hypercube(count: int, seed: int) -> np.ndarray:
    """(count, 4) Latin hypercube on [0, 1): one sample in each of `count` strata per axis, strata shuffled."""
    rng = np.random.default_rng(seed)
    strata = np.stack([rng.permutation(count) for _ in range(4)], axis=1)
    return (strata + rng.random((count, 4))) / count


def _log_between(bounds: tuple[float, float], share: float) -> float:
    return bounds[0] * (bounds[1] / bounds[0]) ** share


def contact(name: str, speed: float, srr: float, pressure: float, ratio: float, oil: str, rheology: str,
            oils: dict[str, Lubricant]) -> AutoContact:
    """The contact of u_e (m/s), SRR, p_h (Pa) and a/b with the oil of case `oil` as `rheology`."""
    radius_y, load = contact_geometry(ratio, pressure)
    name = (f"{name}_u{speed:.3g}_srr{srr:.2f}_ph{pressure * 1e-9:.2f}_ab{ratio:.3g}_"
            f"{'RE' if rheology == 'ree_eyring' else 'N'}_{oil}")
    point = ContactPoint.from_rolling_sliding(name, RADIUS_X, radius_y, load, speed, srr, 0.0, STEEL, STEEL)
    return AutoContact(name, point, with_rheology(oils[oil], rheology), oil)


def fit_contacts(cases_folder: Path) -> list[AutoContact]:
    """The FIT_COUNT contacts of the hypercube (module docstring); contact i takes rheology i mod 2 and oil
    (i // 2) mod 3."""
    oils = shipped_oils(cases_folder)
    names = list(oils)
    contacts = []
    for i, (s_speed, s_srr, s_pressure, s_ratio) in enumerate(_hypercube(FIT_COUNT, FIT_SEED)):
        srr = LARGEST_SRR * max(0.0, (s_srr - ROLLING_SHARE) / (1.0 - ROLLING_SHARE))
        pressure = PRESSURES[0] + (PRESSURES[1] - PRESSURES[0]) * s_pressure
        contacts.append(contact(f"F{i:02d}", _log_between(SPEEDS, s_speed), srr, pressure,
                                _log_between(ELLIPTICITIES, s_ratio), names[(i // 2) % len(names)],
                                RHEOLOGIES[i % 2], oils))
    return contacts + [contact(f"A{i:02d}", *row, oils) for i, row in enumerate(ANCHORS)]


# Low heating, where `auto` chooses between off and reduced: the hypercube's contacts there (p_h above 1.3 GPa
# below 3 m/s) mostly do not converge on these grids. (u_e m/s, SRR, p_h Pa, a/b, oil, rheology)
ANCHORS = ((0.5, 0.0, 0.6e9, 5.0, "facegear_110", "ree_eyring"),
           (1.0, 0.1, 0.8e9, 20.0, "facegear_90", "newtonian"),
           (2.0, 0.0, 0.5e9, 2.0, "ball_on_disc_sliding", "newtonian"),
           (1.5, 0.1, 0.7e9, 50.0, "ball_on_disc_sliding", "ree_eyring"))


# Contacts the fit did not see, placed where `auto` picks a cheaper model: (u_e m/s, SRR, p_h Pa, a/b, oil, rheology)
CHECKED = ((0.3, 0.0, 0.8e9, 10.0, "facegear_110", "ree_eyring"),
           (1.0, 0.0, 0.6e9, 3.0, "facegear_90", "newtonian"),
           (0.3, 0.01, 0.5e9, 30.0, "ball_on_disc_sliding", "ree_eyring"))
CHECKED_GEAR_SPEED = 120.0 * math.pi / 30.0  # rad/s (120 rpm): S3 of cases/facegear_110.yaml this slowly (L_th
# 1.6e-3) is where auto picks off


def check_contacts(cases_folder: Path) -> list[AutoContact]:
    """The CHECKED contacts and S3 of cases/facegear_110.yaml at CHECKED_GEAR_SPEED."""
    oils = shipped_oils(cases_folder)
    case = load_case(cases_folder / OIL_CASES[0])
    case = replace(case, gear=replace(case.gear, pinion_speed=CHECKED_GEAR_SPEED))
    gear = next(p for p in contact_analysis(case).points if p.name == "S3")
    return ([contact(f"C{i:02d}", *row, oils) for i, row in enumerate(CHECKED)]
            + [AutoContact("facegear_110 S3 at 120 rpm", gear, case.lubricant, Path(OIL_CASES[0]).stem)])


def auto_against_full(checked: AutoContact, grid: tuple[int, int] = GRID) -> tuple[str, dict[str, ModelFigures]]:
    """`auto`'s choice for the contact and, where it is not `full`, the contact solved with `auto` and with `full`."""
    model = thermal_choice("auto", checked.point, checked.lubricant)[0]
    return model, ({} if model == "full" else solve_models(checked, grid, ("auto", "full")))


@dataclass(frozen=True)
class ModelFigures:
    """One model's figures of one contact (SI; NaN where the solve has none) and its CPU time (s)."""

    converged: bool
    figures: dict[str, float]
    cpu: float


def figures_of(solution: PointSolution) -> dict[str, float]:
    """The FIGURES of a solution, NaN where it has none (dT_max of an isothermal solve is 0)."""
    return {key: solution.scalar(key) if key in solution.scalars else math.nan for key in FIGURES}


def solve_models(contact: AutoContact, grid: tuple[int, int] = GRID,
                 models: Sequence[str] = MODELS) -> dict[str, ModelFigures]:
    """Each model's figures of the contact on `grid`, one solve at a time."""
    results = {}
    for model in models:
        start = time.process_time()
        solution = solve_point(contact.point, contact.lubricant,
                               SolverSettings(grid=grid[0], grid_y=grid[1], thermal=model))
        results[model] = ModelFigures(solution.converged, figures_of(solution), time.process_time() - start)
    return results


def relative_error(results: dict[str, ModelFigures], model: str, figure: str) -> float:
    """|model/full - 1| in `figure`; NaN where either did not converge."""
    cheap, full = results[model], results["full"]
    if not (cheap.converged and full.converged):
        return math.nan
    return abs(cheap.figures[figure] / full.figures[figure] - 1.0)


@dataclass(frozen=True)
class Envelope:
    """error <= coefficient * G^exponent over the measured points: the least-squares line in log-log lifted onto
    the highest point. `spread`: the largest factor by which the envelope overstates a measured error (at the
    point furthest below it); `scatter`: the least-squares line's largest residual, as a factor."""

    coefficient: float
    exponent: float
    spread: float
    scatter: float
    points: int

    def __call__(self, group: float) -> float:
        return self.coefficient * group**self.exponent


def envelope_fit(groups: Sequence[float], errors: Sequence[float]) -> Envelope:
    """The upper envelope (Envelope) of the errors (relative, > 0) over the groups (> 0)."""
    x, y = np.log(np.asarray(groups, dtype=float)), np.log(np.asarray(errors, dtype=float))
    exponent, intercept = np.polyfit(x, y, 1)
    residual = y - (intercept + exponent * x)
    lift = float(residual.max())
    return Envelope(coefficient=math.exp(intercept + lift), exponent=float(exponent),
                    spread=math.exp(lift - float(residual.min())), scatter=math.exp(float(np.abs(residual).max())),
                    points=int(x.size))


def largest_error(results: dict[str, ModelFigures], model: str) -> float:
    """The largest relative error of `model` against `full` over the figures `auto` protects (thermal.AUTO_FIGURES)
    that both report (an isothermal Newtonian film reports no mu); NaN where either did not converge."""
    errors = [relative_error(results, model, figure) for figure in AUTO_FIGURES]
    finite = [e for e in errors if math.isfinite(e)]
    return max(finite) if finite else math.nan
