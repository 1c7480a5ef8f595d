"""The engineer's verdict on a run, added after the solve (docs/verdict.md): the film parameter at the centre
beside the one at the film's minimum, and a warning where a point runs in boundary lubrication."""

from __future__ import annotations

from dataclasses import replace

from facegear_tehl.cycle import composite_roughness
from facegear_tehl.film_regime import central_column, regime_warning, with_central_film_parameter
from facegear_tehl.results import RunResult


def assess(run: RunResult) -> RunResult:
    """`run` with film_parameter_central (h_c/sigma) on every solved point and along the cycle, and a warning naming
    the points whose film_parameter (h_min/sigma) is below 1; unchanged when the case gives no roughness."""
    materials = run.case.materials
    sigma = composite_roughness(materials.body_1.roughness, materials.body_2.roughness)
    if sigma <= 0.0:
        return run
    points = tuple(with_central_film_parameter(p, sigma) for p in run.points)
    warning = regime_warning({p.name: p.scalar("film_parameter") for p in points if "film_parameter" in p.scalars})
    return replace(run, points=points, cycle=central_column(run.cycle, sigma) if run.cycle else run.cycle,
                   warnings=run.warnings + ((warning,) if warning else ()))
