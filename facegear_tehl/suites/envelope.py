"""Envelope suite: elliptical EHL contacts across the gear operating envelope (issue 14), and the check of a
solution (scripts/envelope.py solves, tabulates and maps them).

A deliberate design, not a full factorial (`envelope_cases`):
  core        p_h {0.3, 0.8, 1.5, 2.5} GPa x a/b {1, 5, 30, 100} at u_e {0.5, 2, 10} m/s, isothermal Newtonian;
  core thermal the same 4 x 4 at u_e 10 m/s, SRR 0.5, thermal ("full") Ree-Eyring;
  then one factor at a time about the gear-like point a/b = 30, p_h = 1.5 GPa (and a few far corners):
  speed (0.5, 2, 30 m/s), SRR (0-2), entrainment skew (10-30 deg), eta_0 (0.01, 0.1 Pa s), alpha
  (1.5, 2.2e-8 1/Pa), and the three failing contacts reported in issue 14.
Each contact: steel on steel, R_x = 20 mm, R_y/R_x from the exact Hertz ellipticity relation for the wanted
a/b (brentq), the load for the wanted p_h; Roelands viscosity, Dowson-Higginson density.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
import fnmatch
import math

import numpy as np
from scipy import optimize

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.energy_balance import energy_unbalanced
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.hertz import ellipticity, hertz_contact
from facegear_tehl.lubricant import KELVIN, Lubricant
from facegear_tehl.materials import Solid, reduced_modulus
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import Outcome, PointSolution

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
    found += [key for key in ("h_c", "h_min", "p_max") if not math.isfinite(scalar_or_nan(solution, key))]
    problems = [f"non-finite {', '.join(found)}"] if found else []
    if solution.converged and not scalar_or_nan(solution, "h_min") > 0.0:
        problems.append("converged with h_min <= 0")
    if energy_unbalanced(solution):
        imbalance = scalar_or_nan(solution, "energy_balance_error")
        problems.append(f"energy balance {100 * imbalance:.2g} % (limit {100 * ENERGY_BALANCE_LIMIT:g} %)")
    return "; ".join(problems) or "ok"


CHECK_PASSED = ("ok", "no fields")
# The film's energy balance of a converged thermal solution (heat generated + mass defect against heat conducted
# and convected, energy.energy_budget) must close as the solver's error bounds ask of it.
ENERGY_BALANCE_LIMIT = TUNING.max_energy_imbalance


def scalar_or_nan(solution: PointSolution, key: str) -> float:
    """The solution's scalar `key` (SI), NaN if it has none."""
    return solution.scalar(key) if key in solution.scalars else math.nan
