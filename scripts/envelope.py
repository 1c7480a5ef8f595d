"""Envelope suite: elliptical EHL contacts across the gear operating envelope, solved and mapped (issue 14).

A deliberate design, not a full factorial (`envelope_cases`):
  core        p_h {0.3, 0.8, 1.5, 2.5} GPa x a/b {1, 5, 30, 100} at u_e {0.5, 2, 10} m/s, isothermal Newtonian;
  core thermal the same 4 x 4 at u_e 10 m/s, SRR 0.5, thermal ("full") Ree-Eyring;
  then one factor at a time about the gear-like point a/b = 30, p_h = 1.5 GPa (and a few far corners):
  speed (0.5, 2, 30 m/s), SRR (0-2), entrainment skew (10-30 deg), eta_0 (0.01, 0.1 Pa s), alpha
  (1.5, 2.2e-8 1/Pa), and the three failing contacts reported in issue 14.
Each contact: steel on steel, R_x = 20 mm, R_y/R_x from the exact Hertz ellipticity relation for the wanted
a/b (brentq), the load for the wanted p_h; Roelands viscosity, Dowson-Higginson density.

Solves them all with the project's parallel runner and prints a markdown table (outcome, grid, cycles, thermal
outer iterations, wall time, h_c, h_min, p_max, error estimates, the energy balance of thermal cases, a check of
the fields and of that balance, the message of a case that did not converge or kept a coarser grid), a summary per
model, p_h and a/b, the failures grouped by outcome and message, and the median and worst wall time. Exit code 1 if
any case did not converge or a solution fails its check.

    python scripts/envelope.py [--grid 257] [--grid-y 65] [--jobs N] [--only PATTERN[,PATTERN]]
                               [--thermal-only | --iso-only] [--map FILE.png] [--save DIR] [--list]
"""

from __future__ import annotations

import argparse
from collections import defaultdict
import csv
from dataclasses import dataclass
import fnmatch
import math
from pathlib import Path
import re
import statistics
import sys
import time
from typing import Sequence

import numpy as np
from scipy import optimize

from facegear_tehl.contact import ContactPoint
from facegear_tehl.hertz import ellipticity, hertz_contact
from facegear_tehl.lubricant import KELVIN, Lubricant
from facegear_tehl.materials import Solid, reduced_modulus
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import Outcome, PointSolution
from facegear_tehl.tables import format_table

# --- Solids: through-hardened / case-carburised gear steel, nominal handbook values for low-alloy steel
# (E, nu, rho, k, c as in the repository's cases/*.yaml; e.g. ASM Handbook vol. 1, AISI 4340 / 52100 class).
STEEL = Solid(
    elastic_modulus=210e9,  # Pa
    poisson_ratio=0.3,  # -
    density=7850.0,  # kg/m^3
    thermal_conductivity=46.0,  # W/(m K)
    specific_heat=470.0,  # J/(kg K)
)

# --- Lubricant: a mineral gear oil at the bulk temperature of a loaded gearbox.
INLET_TEMPERATURE = 80.0 + KELVIN  # K: a usual sump / bulk oil temperature of loaded industrial gear drives
#   (60-90 degC); a choice of this suite, not a measured value.
VISCOSITY = 0.04  # Pa s, eta_0 of the core cases: ISO VG 320 mineral oil at 80 degC by ASTM D341 (Walther)
#   through nu_40 = 320 and nu_100 = 24 mm^2/s: nu_80 = 46.6 mm^2/s x rho_80 = 835 kg/m^3 = 0.039 Pa s.
#   The eta_0 variations 0.01 and 0.1 Pa s are about ISO VG 68 at 80 degC (0.012) and VG 320 at 55 degC.
PRESSURE_VISCOSITY = 2.0e-8  # 1/Pa, alpha of the core cases; mineral gear oils: about 1.5-2.5e-8 1/Pa at
#   40-100 degC (Gold, Schmidt, Dicke, Loos & Assmann 2001, J. Synthetic Lubrication 18: 51-79); the Roelands
#   index z follows from alpha (Lubricant.z). Variations: 1.5e-8 and 2.2e-8 (Venner & Lubrecht 2000 reference oil).
DENSITY = 835.0  # kg/m^3 at 80 degC: 870 at 15 degC x (1 - 6.5e-4 x 65) (mineral oil, thermal expansion below)
THERMAL_EXPANSION = 6.5e-4  # 1/K, eps_T of the density's temperature term (Yang & Wen 1990, thermal EHL)
TEMPERATURE_VISCOSITY = 0.03  # 1/K, beta = -d ln(eta)/dT at the inlet: ASTM D341 (Walther) gives 0.030-0.032 for
#   ISO VG 68-100 mineral oils at 80 degC (0.038 for VG 320); one value for every case of the suite.
THERMAL_CONDUCTIVITY = 0.13  # W/(m K): Cragoe (1929, NBS Misc. Publ. 97) for petroleum oils,
#   k = 0.117/SG_15 (1 - 5.4e-4 t/degC) = 0.129 at SG_15 = 0.87, t = 80 degC.
SPECIFIC_HEAT = 2000.0  # J/(kg K): Cragoe (1929) gives (1.684 + 0.00339 t/degC)/sqrt(SG_15) kJ/(kg K) = 2.1 at
#   80 degC, 1.9 at 40 degC; 2000 is the common round value of thermal EHL studies.
EYRING_STRESS = 5e6  # Pa, tau_0 of the Ree-Eyring model: Johnson & Tevaarwerk (1977, Proc. R. Soc. A 356: 215-236)
#   and Evans & Johnson (1986, Proc. IMechE C 200: 303-312) fit about 2-10 MPa for mineral oils.

RADIUS_X = 0.020  # m, R_x of every contact: the low end of the shipped face gear case (R_x = 18.9-47.9 mm)
GRID, GRID_Y = 257, 65  # the shipped face gear case's grid (x along the minor axis, y along the major axis)
THERMAL_MODE = "full"  # energy equation across the film with Jaeger solids (SolverSettings.thermal)

# --- The design.
CORE_PRESSURES = (0.3e9, 0.8e9, 1.5e9, 2.5e9)  # Pa
CORE_ELLIPTICITIES = (1.0, 5.0, 30.0, 100.0)  # a/b
CORE_SPEEDS = (0.5, 2.0, 10.0)  # m/s, isothermal core
THERMAL_SPEED = 10.0  # m/s, thermal core
THERMAL_SRR = 0.5  # slide-to-roll ratio of the thermal cases unless varied
BASE_K, BASE_PH, BASE_U = 30.0, 1.5e9, 10.0  # the gear-like point the one-factor variations start from

OUTCOME_COLOURS = {
    Outcome.CONVERGED: "tab:green",
    Outcome.NOT_CONVERGED: "tab:orange",
    Outcome.DIVERGED: "tab:red",
    Outcome.FILM_CLOSED: "tab:purple",
    Outcome.FAILED: "black",
}


@dataclass(frozen=True)
class EnvelopeCase:
    """One contact of the suite (SI units; angles in degrees)."""

    name: str
    group: str  # which part of the design it belongs to
    ellipticity: float  # k = a/b
    hertz_pressure: float  # p_h, Pa
    entrainment_speed: float  # u_e, m/s
    slide_roll_ratio: float  # SRR = (u_1 - u_2)/u_e
    skew: float  # angle of the entrainment to the minor axis x, deg
    viscosity: float  # eta_0, Pa s
    pressure_viscosity: float  # alpha, 1/Pa
    thermal: bool  # thermal Ree-Eyring (True) or isothermal Newtonian (False)

    @property
    def model(self) -> str:
        return "thermal Ree-Eyring" if self.thermal else "iso Newtonian"

    def point(self) -> ContactPoint:
        """The contact: R_x = RADIUS_X, R_y and the load for the asked a/b and p_h (`contact_geometry`)."""
        radius_y, load = contact_geometry(self.ellipticity, self.hertz_pressure)
        return ContactPoint.from_rolling_sliding(
            self.name, RADIUS_X, radius_y, load, self.entrainment_speed, self.slide_roll_ratio, self.skew,
            STEEL, STEEL,
        )

    def lubricant(self) -> Lubricant:
        """The gear oil above; Newtonian for the isothermal cases, Ree-Eyring for the thermal ones."""
        return Lubricant(
            viscosity=self.viscosity,
            pressure_viscosity=self.pressure_viscosity,
            inlet_temperature=INLET_TEMPERATURE,
            density=DENSITY,
            viscosity_model="roelands",
            density_model="dowson_higginson",
            rheology="ree_eyring" if self.thermal else "newtonian",
            eyring_stress=EYRING_STRESS if self.thermal else math.inf,
            temperature_viscosity=TEMPERATURE_VISCOSITY,
            thermal_expansion=THERMAL_EXPANSION,
            thermal_conductivity=THERMAL_CONDUCTIVITY,
            specific_heat=SPECIFIC_HEAT,
        )

    def settings(self, grid: int = GRID, grid_y: int | None = GRID_Y) -> SolverSettings:
        return SolverSettings(grid=grid, grid_y=grid_y, thermal=THERMAL_MODE if self.thermal else "off")


def radius_ratio_for(k: float) -> float:
    """R_y/R_x whose exact Hertz ellipticity (hertz.ellipticity) is k = a/b >= 1 (brentq in log R_y/R_x)."""
    if k < 1.0:
        raise ValueError(f"a/b must be >= 1, got {k}")
    if k == 1.0:
        return 1.0

    def residual(log_ratio: float) -> float:
        return math.log(ellipticity(math.exp(log_ratio))[0] / k)

    # R_y/R_x ~ k^(pi/2) near k = 1 (Hamrock & Brewe 1983: k ~ (R_y/R_x)^(2/pi)) and ~ k^(3/2) (times a log)
    # for long ellipses: k <= R_y/R_x < 3 (k^2 + 1) brackets the root.
    low, high = math.log(k), math.log(3.0 * (k * k + 1.0))
    return math.exp(optimize.brentq(residual, low, high, xtol=1e-14, rtol=1e-14, maxiter=200))


def contact_geometry(k: float, hertz_pressure: float) -> tuple[float, float]:
    """(R_y, load) of the contact with R_x = RADIUS_X, a/b = k and maximum Hertz pressure p_h (Pa).
    p_h is proportional to W^(1/3) at fixed radii (hertz.py), so one Hertz solution at 1 N gives the load."""
    radius_y = RADIUS_X * radius_ratio_for(k)
    unit = hertz_contact(RADIUS_X, radius_y, 1.0, reduced_modulus(STEEL, STEEL))
    return radius_y, (hertz_pressure / unit.p_max) ** 3


def _name(k: float, ph: float, u: float, thermal: bool, srr: float = 0.0, skew: float = 0.0,
          eta: float = VISCOSITY, alpha: float = PRESSURE_VISCOSITY) -> str:
    """'ab30_ph1.5_u2_iso', 'ab30_ph1.5_u10_srr0.5_th', with _skew.., _eta.., _alpha.. when not the default."""
    parts = [f"ab{k:g}", f"ph{ph * 1e-9:g}", f"u{u:g}"]
    if thermal or srr != 0.0:
        parts.append(f"srr{srr:g}")
    if skew != 0.0:
        parts.append(f"skew{skew:g}")
    if eta != VISCOSITY:
        parts.append(f"eta{eta:g}")
    if alpha != PRESSURE_VISCOSITY:
        parts.append(f"alpha{alpha * 1e8:g}")
    parts.append("th" if thermal else "iso")
    return "_".join(parts)


def _case(group: str, k: float, ph: float, u: float, thermal: bool, srr: float | None = None, skew: float = 0.0,
          eta: float = VISCOSITY, alpha: float = PRESSURE_VISCOSITY) -> EnvelopeCase:
    if srr is None:
        srr = THERMAL_SRR if thermal else 0.0
    return EnvelopeCase(_name(k, ph, u, thermal, srr, skew, eta, alpha), group, k, ph, u, srr, skew, eta, alpha,
                        thermal)


def envelope_cases() -> list[EnvelopeCase]:
    """The suite's contacts, in a fixed order (see the module docstring for the design)."""
    cases = [_case("core", k, ph, u, False)
             for u in CORE_SPEEDS for ph in CORE_PRESSURES for k in CORE_ELLIPTICITIES]
    cases += [_case("core thermal", k, ph, THERMAL_SPEED, True) for ph in CORE_PRESSURES for k in CORE_ELLIPTICITIES]
    base_iso = dict(k=BASE_K, ph=BASE_PH, u=BASE_U, thermal=False)
    base_th = dict(k=BASE_K, ph=BASE_PH, u=BASE_U, thermal=True)
    # speed: the top of the range isothermal at three ellipticities, and the thermal model at low/high speed
    cases += [_case("speed", k, ph, 30.0, False) for k, ph in ((1.0, 1.5e9), (30.0, 1.5e9), (100.0, 1.5e9),
                                                              (100.0, 0.8e9))]
    cases += [_case("speed", k, BASE_PH, u, True) for k, u in ((1.0, 2.0), (30.0, 0.5), (30.0, 2.0),
                                                             (100.0, 2.0), (30.0, 30.0))]
    # SRR (the isothermal Newtonian film does not depend on sliding: thermal only)
    cases += [_case("SRR", srr=srr, **base_th) for srr in (0.0, 0.2, 1.0, 2.0)]
    cases += [_case("SRR", 100.0, 0.8e9, BASE_U, True, srr=srr) for srr in (1.0, 2.0)]
    cases += [_case("SRR", 1.0, BASE_PH, BASE_U, True, srr=2.0)]
    # entrainment skew
    cases += [_case("skew", skew=skew, **base_iso) for skew in (10.0, 20.0, 30.0)]
    cases += [_case("skew", k, BASE_PH, BASE_U, False, skew=30.0) for k in (5.0, 100.0)]
    cases += [_case("skew", skew=30.0, **base_th)]
    # inlet viscosity, with the thinnest (heavy, slow, thin oil) and thickest (light, fast, thick oil) films
    cases += [_case("eta_0", eta=eta, **base_iso) for eta in (0.01, 0.1)]
    cases += [_case("eta_0", 1.0, 2.5e9, 0.5, False, eta=0.01), _case("eta_0", 100.0, 0.3e9, 30.0, False, eta=0.1)]
    cases += [_case("eta_0", eta=eta, **base_th) for eta in (0.01, 0.1)]
    # pressure-viscosity coefficient
    cases += [_case("alpha", alpha=alpha, **base_iso) for alpha in (1.5e-8, 2.2e-8)]
    # the contacts that fail in issue 14 (its a/b, p_h, u_e, SRR; this suite's oil)
    cases += [_case("issue 14", 34.0, 1.5e9, 2.0, False), _case("issue 14", 40.0, 1.2e9, 8.0, True, srr=0.4),
              _case("issue 14", 40.0, 1.5e9, 3.0, True, srr=1.0)]
    names = [c.name for c in cases]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise AssertionError(f"duplicate case names: {duplicates}")
    return cases


def select(cases: Sequence[EnvelopeCase], only: str | None, thermal: bool | None) -> list[EnvelopeCase]:
    """The cases whose name matches one of the comma-separated patterns of `only` (a glob, or a substring when
    it has no wildcard) and, unless `thermal` is None, of that model."""
    chosen = list(cases)
    if only:
        patterns = [p.strip() for p in only.split(",") if p.strip()]
        chosen = [c for c in chosen if any(
            fnmatch.fnmatchcase(c.name, p) if any(ch in p for ch in "*?[") else p in c.name for p in patterns)]
    if thermal is not None:
        chosen = [c for c in chosen if c.thermal is thermal]
    return chosen


# --------------------------------------------------------------------------------------------- checks and table
def check_solution(solution: PointSolution) -> str:
    """'ok'; 'no fields' for a solve that did not converge and reports no film (the solver gives no fields when the
    film closes); else what is wrong: no data (the solve raised), non-finite fields or film scalars, a converged
    solution without fields or with h_min <= 0."""
    if solution.outcome is Outcome.FAILED:
        return "no data"
    if not solution.fields:
        return "converged without fields" if solution.converged else "no fields"
    found = [name for name, f in solution.fields.items() if not np.all(np.isfinite(f.values))]
    found += [key for key in ("h_c", "h_min", "p_max") if not math.isfinite(_scalar(solution, key))]
    problems = [f"non-finite {', '.join(found)}"] if found else []
    if solution.converged and not _scalar(solution, "h_min") > 0.0:
        problems.append("converged with h_min <= 0")
    imbalance = _scalar(solution, "energy_balance_error")
    if solution.converged and abs(imbalance) > ENERGY_BALANCE_LIMIT:
        problems.append(f"energy balance {100 * imbalance:.2g} % (limit {100 * ENERGY_BALANCE_LIMIT:g} %)")
    return "; ".join(problems) or "ok"


CHECK_PASSED = ("ok", "no fields")
# The film's energy balance of a converged thermal solution (heat generated + mass defect against heat conducted
# and convected, energy.energy_budget) must close to 1 % (issue 19's acceptance; the discrete budget is exact at
# convergence, so a larger imbalance means the outer loop stopped short).
ENERGY_BALANCE_LIMIT = 0.01


def _scalar(solution: PointSolution, key: str) -> float:
    return solution.scalar(key) if key in solution.scalars else math.nan


def _cell(solution: PointSolution, key: str, factor: float, spec: str) -> str:
    value = _scalar(solution, key)
    return "–" if math.isnan(value) else format(value * factor, spec)


@dataclass(frozen=True)
class Row:
    case: EnvelopeCase
    solution: PointSolution
    check: str

    @property
    def wall_time(self) -> float:
        return _scalar(self.solution, "wall_time")


COLUMNS = ("case", "a/b", "p_h GPa", "u_e m/s", "SRR", "skew deg", "eta_0 Pa s", "model", "outcome", "grid",
           "cycles", "outer it.", "wall s", "h_c µm", "h_min µm", "p_max GPa", "err h_c %", "err h_min %", "energy %",
           "check", "message")


def row_cells(row: Row) -> list[str]:
    c, s = row.case, row.solution
    return [
        c.name, f"{c.ellipticity:g}", f"{c.hertz_pressure * 1e-9:g}", f"{c.entrainment_speed:g}",
        f"{c.slide_roll_ratio:g}", f"{c.skew:g}", f"{c.viscosity:g}", c.model, s.outcome.value,
        _grid(s), _cell(s, "iterations", 1.0, ".0f"), _cell(s, "thermal_iterations", 1.0, ".0f"),
        _cell(s, "wall_time", 1.0, ".1f"), _cell(s, "h_c", 1e6, ".4g"), _cell(s, "h_min", 1e6, ".4g"),
        _cell(s, "p_max", 1e-9, ".3f"), _cell(s, "error_estimate_h_c", 100.0, ".2g"),
        _cell(s, "error_estimate_h_min", 100.0, ".2g"), _cell(s, "energy_balance_error", 100.0, ".2g"),
        row.check, s.message,
    ]


def _grid(solution: PointSolution) -> str:
    """The nodes of the grid the solution is on ("nx x ny"; its inlet may have been lengthened: ehl.domain)."""
    if "grid" not in solution.scalars:
        return "–"
    return f"{_scalar(solution, 'grid'):.0f} x {_scalar(solution, 'grid_y'):.0f}"


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


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=GRID, help=f"nodes along x, the minor axis (default {GRID})")
    parser.add_argument("--grid-y", type=int, default=GRID_Y, help=f"nodes along y, the major axis (default {GRID_Y})")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    parser.add_argument("--only", help="comma-separated name patterns (globs, or substrings without a wildcard)")
    model = parser.add_mutually_exclusive_group()
    model.add_argument("--thermal-only", action="store_true", help="only the thermal Ree-Eyring cases")
    model.add_argument("--iso-only", action="store_true", help="only the isothermal Newtonian cases")
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
