"""Wide envelope suite: elliptical EHL contacts drawn at random over the ranges of issue 47 (scripts/wide_envelope.py
solves and tabulates them).

Unlike the public envelope (envelope.py, a deliberate design), these contacts are drawn with a fixed seed and
are not chosen case by case: each draws, independently,

  a/b   log-uniform in [1, 150]             u_e   log-uniform in [0.3, 40] m/s
  p_h   uniform in [0.3, 2.5] GPa           eta_0 log-uniform in [0.005, 0.2] Pa s
  SRR   uniform in [0, 2]                   skew  uniform in [0, 45] deg (entrainment to the minor axis)

and is kept while its Moes load parameter M (Moes 1992; scaling.py) is at most MAX_MOES_M; every second contact
kept is thermal ("full" energy equation with Jaeger solids) with Ree-Eyring rheology, the others isothermal
Newtonian. Solids, oil laws (Roelands, Dowson-Higginson, the oil's thermal data and Eyring stress) and R_x are
the public envelope's (envelope.py). The draws are rounded to the digits shown in the case names.
"""

from __future__ import annotations

import math

import numpy as np

from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.suites.envelope import PRESSURE_VISCOSITY, EnvelopeCase

SEED = 47  # the number: the draw is fixed, not searched for
COUNT = 44  # contacts kept (the issue asks for at least 40)
MAX_MOES_M = 3.0e5  # the heaviest load
ELLIPTICITY = (1.0, 150.0)  # a/b, log-uniform
HERTZ_PRESSURE = (0.3e9, 2.5e9)  # Pa, uniform
SPEED = (0.3, 40.0)  # m/s, log-uniform
VISCOSITY = (0.005, 0.2)  # Pa s, log-uniform
SLIDE_ROLL = (0.0, 2.0)  # uniform
SKEW = (0.0, 45.0)  # deg, uniform


def _log_uniform(rng: np.random.Generator, bounds: tuple[float, float]) -> float:
    return math.exp(rng.uniform(math.log(bounds[0]), math.log(bounds[1])))


def _drawn(rng: np.random.Generator, index: int, thermal: bool) -> EnvelopeCase:
    """One contact's draw (rounded to three significant digits, SRR and skew to two decimals / one)."""
    k = float(f"{_log_uniform(rng, ELLIPTICITY):.3g}")
    ph = round(rng.uniform(*HERTZ_PRESSURE) * 1e-7) * 1e7
    u = float(f"{_log_uniform(rng, SPEED):.3g}")
    eta = float(f"{_log_uniform(rng, VISCOSITY):.3g}")
    srr = round(rng.uniform(*SLIDE_ROLL), 2)
    skew = round(rng.uniform(*SKEW), 1)
    name = (f"w{index:02d}_ab{k:g}_ph{ph * 1e-9:g}_u{u:g}_eta{eta:g}_srr{srr:g}_skew{skew:g}_"
            f"{'th' if thermal else 'iso'}")
    return EnvelopeCase(name, "wide thermal" if thermal else "wide iso", k, ph, u, srr, skew, eta,
                        PRESSURE_VISCOSITY, thermal)


def moes_m(case: EnvelopeCase) -> float:
    """Moes' M of a contact (scaling.scaling_for)."""
    return scaling_for(case.point(), case.lubricant()).moes_m


def wide_cases() -> list[EnvelopeCase]:
    """The suite's COUNT contacts in the order drawn (SEED): draws with M > MAX_MOES_M are dropped, the model
    alternates isothermal / thermal over the contacts kept."""
    rng = np.random.default_rng(SEED)
    cases: list[EnvelopeCase] = []
    while len(cases) < COUNT:
        case = _drawn(rng, len(cases) + 1, thermal=len(cases) % 2 == 1)
        if moes_m(case) <= MAX_MOES_M:
            cases.append(case)
    return cases


def wide_envelope_contact(prefix: str) -> EnvelopeCase:
    """The one contact whose name starts with `prefix` (w08); ValueError when not exactly one does (an argparse
    type: the scripts' bad argument, exit 2)."""
    cases = [c for c in wide_cases() if c.name.startswith(prefix)]
    if len(cases) != 1:
        raise ValueError(f"case {prefix!r}: expected one wide-envelope contact, found {len(cases)}")
    return cases[0]
