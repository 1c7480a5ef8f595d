"""The engineer's verdict on a run, added after the solve (docs/verdict.md): the film parameter at the centre beside
the one at the film's minimum, a warning where a point runs in boundary lubrication, and one verdict per case (the
/verdict group): the lowest film parameter and where, the highest contact temperature solved and by formula, the
scuffing safety against a given scuffing temperature from both, and one recommended mesh efficiency beside the
others as comparisons."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace
import math

from facegear_tehl.cycle import composite_roughness
from facegear_tehl.ehl.closure import predicted_minimum_film
from facegear_tehl.film_regime import (
    FULL_FILM_LAMBDA,
    Regime,
    central_column,
    regime,
    regime_warning,
    with_central_film_parameter,
)
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.points import contact_analysis
from facegear_tehl.ratings import rate
from facegear_tehl.record import Action
from facegear_tehl.results import Result, RunResult
from facegear_tehl.scuffing import flash_safety
from facegear_tehl.solution import Outcome, PointSolution
from facegear_tehl.units import CELSIUS, MILLIMETRE, PERCENT

# The recommended mesh power loss: the solved film's sliding traction times the sliding speed (cycle.py's
# power_loss). Why not the others: the film's whole-domain dissipation adds the rolling (Poiseuille) traction and
# the heat of the inlet back flow, which grows with the length of inlet the domain holds; Xu et al. (2007) and
# ISO/TR 14179-2 are cylindrical-gear correlations, outside their scope on a face gear (docs/cycle.md).
RECOMMENDED = ("", "film mu (solved) x sliding speed")
COMPARISONS = (("_dissipated", "film dissipation, whole domain: adds the rolling traction and the inlet back-flow "
                                "heat, grows with the inlet length"),
               ("_xu", "Xu et al. (2007) mu [c]"), ("_iso", "ISO/TR 14179-2 mean mu [c]"))


def assess(run: RunResult) -> RunResult:
    """`run` with film_parameter_central (h_c/sigma) on every solved point and along the cycle, a warning naming the
    points whose film_parameter (h_min/sigma) is below 1 (no change there for a case without roughness), and its
    verdict (`verdict_scalars`, `verdict_labels`)."""
    materials = run.case.materials
    sigma = composite_roughness(materials.body_1.roughness, materials.body_2.roughness)
    if sigma > 0.0:
        points = tuple(with_central_film_parameter(p, sigma) for p in run.points)
        lambdas = {p.name: p.scalar("film_parameter") for p in points if p.converged and "film_parameter" in p.scalars}
        warning = regime_warning(lambdas)
        run = replace(run, points=points, cycle=central_column(run.cycle, sigma) if run.cycle else run.cycle,
                      warnings=run.warnings + ((warning,) if warning else ()))
    converged = [p for p in run.points if p.converged]  # another point's figures are its last iterate's
    scalars, labels = _film_verdict(converged)
    closed_scalars, closed_labels = _closed_film_verdict(run, sigma)
    scalars.update(closed_scalars)
    labels.update(closed_labels)
    scalars.update(_temperature_verdict(run, converged))
    scalars.update(_scuffing_verdict(run.case.lubricant, scalars))
    scalars.update(_efficiency_verdict(run.cycle_scalars))
    rated, not_rated = rate(run.case, run.contact, run.contact_scalars, run.cycle)
    scalars.update(rated)
    if not_rated:
        labels["not_rated"] = "; ".join(not_rated)
    left_out = [p.name for p in run.points if not p.converged and p.outcome is not Outcome.FILM_CLOSED]
    if left_out:
        labels["left_out"] = ", ".join(left_out)
    return replace(run, verdict=scalars, verdict_labels=labels)


def _film_verdict(points: Sequence[PointSolution]) -> tuple[dict[str, tuple[float, str]], dict[str, str]]:
    """lambda_min over the converged `points`, the point where it lies (its path coordinate for a gear), lambda_c
    there and the regime."""
    solved = [p for p in points if "film_parameter" in p.scalars]
    if not solved:
        return {}, {}
    lowest = min(solved, key=lambda p: p.scalar("film_parameter"))
    scalars = {"lambda_min": (lowest.scalar("film_parameter"), "1")}
    if "film_parameter_central" in lowest.scalars:
        scalars["lambda_central_at_min"] = (lowest.scalar("film_parameter_central"), "1")
    if "path_coordinate" in lowest.scalars:
        scalars["lambda_min_s"] = (lowest.scalar("path_coordinate"), "m")
    return scalars, {"lambda_min_point": lowest.name, "regime": regime(lowest.scalar("film_parameter")).value}


def _closed_film_verdict(run: RunResult, sigma: float) -> tuple[dict[str, tuple[float, str]], dict[str, str]]:
    """For the points whose film closed (no film solved): Hamrock & Dowson's (1977) minimum film of the thinnest of
    those no grid within the caps resolves (Action.NOT_RESOLVABLE; a film that closed in a failed iteration has no
    such evidence), as the formula's estimate (`h_min_formula_closed`, and over sigma `lambda_formula_closed` with its
    regime), never a solved figure; labels naming the points and the one estimated."""
    closed = [p.name for p in run.points if p.outcome is Outcome.FILM_CLOSED]
    if not closed:
        return {}, {}
    points = {p.name: p for p in contact_analysis(run.case).points}
    unresolvable = [p.name for p in run.points if p.outcome is Outcome.FILM_CLOSED and p.record is not None
                    and any(r.action is Action.NOT_RESOLVABLE for r in p.record.retries)]
    films = {name: predicted_minimum_film(points[name], run.case.lubricant)
             for name in unresolvable if name in points}
    films = {name: film for name, film in films.items() if math.isfinite(film) and film > 0.0}
    labels = {"film_closed_points": ", ".join(closed)}
    if not films:
        return {}, labels
    thinnest = min(films, key=films.__getitem__)
    scalars = {"h_min_formula_closed": (films[thinnest], "m")}
    labels["film_closed_formula_point"] = thinnest
    if sigma > 0.0:
        scalars["lambda_formula_closed"] = (films[thinnest] / sigma, "1")
        labels["film_closed_formula_regime"] = regime(films[thinnest] / sigma).value
    return scalars, labels


def _temperature_verdict(run: RunResult, points: Sequence[PointSolution]) -> dict[str, tuple[float, str]]:
    """The highest contact temperature over the converged `points` of `run` and their flanks: solved (bulk + solved
    surface rise, thermal models) and by Blok's formula with the film's mu; for a plain contact the inlet is the bulk
    temperature."""
    inlet = run.case.lubricant.inlet_temperature
    found: dict[str, list[float]] = {"contact_temperature_max": [], "contact_temperature_blok_max": []}
    for point in points:
        scalars = point.scalars
        for body in (1, 2):
            if f"contact_temperature_{body}" in scalars:
                found["contact_temperature_max"].append(scalars[f"contact_temperature_{body}"][0])
            elif run.case.gear is None and run.case.solver.thermal != "off" and f"dT_surface_{body}_max" in scalars:
                found["contact_temperature_max"].append(inlet + scalars[f"dT_surface_{body}_max"][0])
            if f"contact_temperature_blok_{body}" in scalars:
                found["contact_temperature_blok_max"].append(scalars[f"contact_temperature_blok_{body}"][0])
        if run.case.gear is None and "flash_temperature" in scalars:
            found["contact_temperature_blok_max"].append(inlet + scalars["flash_temperature"][0])
    return {key: (max(values), "K") for key, values in found.items() if values}


def _scuffing_verdict(lubricant: Lubricant, temperatures: Mapping[str, tuple[float, str]]
                      ) -> dict[str, tuple[float, str]]:
    """The scuffing safety S_B of the hottest flank against the given scuffing temperature, from the solved and
    from Blok's contact temperature (scuffing.flash_safety), with theta_oil the inlet temperature."""
    if lubricant.scuffing_temperature is None:
        return {}
    found = {"scuffing_temperature": (lubricant.scuffing_temperature, "K")}
    for key, name in (("contact_temperature_max", "scuffing_safety"),
                      ("contact_temperature_blok_max", "scuffing_safety_blok")):
        safety = flash_safety(lubricant.scuffing_temperature, lubricant.inlet_temperature,
                              temperatures[key][0]) if key in temperatures else None
        if safety is not None:
            found[name] = (safety, "1")
    return found


def _efficiency_verdict(cycle: Mapping[str, tuple[float, str]]) -> dict[str, tuple[float, str]]:
    """The recommended mesh efficiency and power loss (RECOMMENDED), when the cycle has them."""
    suffix = RECOMMENDED[0]
    if f"mesh_efficiency{suffix}" not in cycle:
        return {}
    return {"mesh_efficiency": cycle[f"mesh_efficiency{suffix}"], "power_loss": cycle[f"power_loss{suffix}"]}


def verdict_text(result: Result) -> str:
    """The verdict of a result file, a few lines; '' when it has none."""
    lines = [*_film_lines(result), *_closed_film_lines(result), *_temperature_lines(result),
             *_scuffing_lines(result), *_standard_lines(result), *_efficiency_lines(result)]
    labels = result.verdict_labels
    if "left_out" in labels:
        lines.append(f"  left out             {labels['left_out']} (not converged: no result to assess)")
    if not lines:
        return ""
    if "not_rated" in labels:
        lines.append(f"  not assessed         {labels['not_rated']}")
    return "\n".join(["verdict:", *lines])


def _pair(v: Mapping[str, tuple[float, str]] | Mapping[str, float], key: str) -> str:
    """'<formula> formula, <solved> solved' of a verdict value and its `_solved` partner, 2 decimals."""
    solved = f", {v[key + '_solved']:.2f} solved" if key + "_solved" in v else ""
    return f"{v[key]:.2f} formula{solved}"


def _standard_lines(result: Result) -> list[str]:
    """The ISO/TS 6336-20/-21/-22 lines of the verdict (ratings.py), where rated."""
    v, lines = result.verdict, []
    if "scuffing_safety_flash" in v:
        solved = (f", {CELSIUS(v['contact_temperature_flash_solved_max']):.1f} °C solved"
                  if "contact_temperature_flash_solved_max" in v else "")
        lines.append(f"  scuffing, flash      S_B {_pair(v, 'scuffing_safety_flash')} (ISO/TS 6336-20): theta_B,max "
                     f"{CELSIUS(v['contact_temperature_flash_max']):.1f} °C formula{solved}, theta_M "
                     f"{CELSIUS(v['bulk_temperature_flash']):.1f} °C, theta_S "
                     f"{CELSIUS(v['scuffing_temperature_fzg']):.0f} °C (FZG stage), mu_m {v['mu_flash_method']:.3f}")
    if "scuffing_safety_integral" in v:
        solved = (f", {CELSIUS(v['integral_temperature_solved']):.1f} °C solved"
                  if "integral_temperature_solved" in v else "")
        lines.append(f"  scuffing, integral   S_intS {_pair(v, 'scuffing_safety_integral')} (ISO/TS 6336-21): "
                     f"theta_int {CELSIUS(v['integral_temperature']):.1f} °C formula{solved}, theta_intS "
                     f"{CELSIUS(v['scuffing_integral_temperature']):.0f} °C (FZG stage)")
    if "micropitting_safety" in v:
        where = f" at s {MILLIMETRE(v['lambda_gf_min_s']):.2f} mm"
        solved = f", {v['lambda_gf_min_solved']:.2f} solved h_min/Ra" if "lambda_gf_min_solved" in v else ""
        lines.append(f"  micropitting         S_lambda {_pair(v, 'micropitting_safety')} (ISO/TS 6336-22 method B): "
                     f"lambda_GF,min {v['lambda_gf_min']:.2f}{where}{solved}, lambda_GFP {v['lambda_gfp']:.3f}")
    return lines


def _film_lines(result: Result) -> list[str]:
    v, labels = result.verdict, result.verdict_labels
    if "lambda_min" not in v:
        return []
    where = labels["lambda_min_point"] + (f" (s {MILLIMETRE(v['lambda_min_s']):.2f} mm)" if "lambda_min_s" in v else "")
    central = f", lambda_c {v['lambda_central_at_min']:.2f} there" if "lambda_central_at_min" in v else ""
    return [f"  film                 lambda_min {v['lambda_min']:.2f} at {where}{central}: {labels['regime']} "
            f"(full film from lambda {FULL_FILM_LAMBDA:g})"]


def _closed_film_lines(result: Result) -> list[str]:
    """The line of the points whose film closed: no solved film; Hamrock & Dowson's, labelled as the formula's."""
    v, labels = result.verdict, result.verdict_labels
    if "film_closed_points" not in labels:
        return []
    line = f"  film closed          {labels['film_closed_points']}: the film closes on the grids solved, no film solved"
    if "h_min_formula_closed" not in v:
        return [line]
    line += (f"; Hamrock & Dowson (1977) formula, not solved: h_min {1e9 * v['h_min_formula_closed']:.3g} nm at "
             f"{labels['film_closed_formula_point']}")
    if "lambda_formula_closed" in v:
        line += f", lambda {v['lambda_formula_closed']:.2g}: {labels['film_closed_formula_regime']}"
        if labels["film_closed_formula_regime"] == Regime.BOUNDARY.value:
            line += " (asperities carry the load: the smooth-film model does not apply)"
    return [line]


def _temperature_lines(result: Result) -> list[str]:
    v = result.verdict
    temperatures = [f"{CELSIUS(v[key]):.1f} °C {what}" for key, what in (
        ("contact_temperature_max", "solved TEHL (bulk + solved surface rise)"),
        ("contact_temperature_blok_max", "Blok (1937) formula with the film's mu")) if key in v]
    return ["  contact temperature  max " + "; ".join(temperatures)] if temperatures else []


def _scuffing_lines(result: Result) -> list[str]:
    v = result.verdict
    if "scuffing_temperature" not in v:
        return []
    safeties = [f"{v[key]:.2f} {what}" for key, what in (("scuffing_safety", "solved"),
                                                          ("scuffing_safety_blok", "Blok formula")) if key in v]
    given = CELSIUS(v["scuffing_temperature"])
    return [f"  scuffing             S_B {', '.join(safeties) or '-'} against theta_S {given:.0f} °C given (Blok's "
            "flash-temperature criterion)"]


def _efficiency_lines(result: Result) -> list[str]:
    v, cycle = result.verdict, result.cycle_scalars
    if "mesh_efficiency" not in v:
        return []
    upper = (", an upper bound: asperity friction at lambda < 1 is not modelled"
             if result.verdict_labels.get("regime") == Regime.BOUNDARY.value else "")
    return [f"  mesh efficiency      {PERCENT(v['mesh_efficiency']):.3f} % recommended: {RECOMMENDED[1]}, "
            f"power loss {v['power_loss']:.1f} W{upper}",
            *(f"    comparison         {PERCENT(cycle[f'mesh_efficiency{suffix}']):.3f} % {label}"
              for suffix, label in COMPARISONS if f"mesh_efficiency{suffix}" in cycle)]
