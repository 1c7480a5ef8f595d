"""The correlation `solver.thermal: auto` decides by: each contact of the design (suites/thermal_auto.py) solved
`off`, `reduced` and `full`, the errors of the cheaper two against `full`, and their upper-envelope fit.

    python scripts/thermal_auto_fit.py [--save FILE] [--load FILE] [--check]

Each contact is solved on the shipped case's 257 x 65 and on 129 x 33: the fit takes the 257 x 65 errors, or the
129 x 33 ones where 257 x 65 did not converge in all three models; the contacts converged on both grids show how much
the errors move with the grid. --save writes the solutions' figures as JSON, --load tabulates and fits saved ones
without solving. --check solves the contacts the fit did not see (suites/thermal_auto.py check_contacts) with
`auto` and with `full` and prints auto's errors (tests/test_thermal_auto.py asserts them).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

from facegear_tehl.ehl import thermal
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.suites import thermal_auto as ta

CASES = Path(__file__).resolve().parent.parent / "cases"


def _solve_all(contacts, grid) -> dict:
    results = {}
    for contact in contacts:
        models = ta.solve_models(contact, grid)
        results[contact.name] = {m: {"converged": r.converged, "cpu": r.cpu, **r.figures} for m, r in models.items()}
        print(f"solved {contact.name} on {grid[0]} x {grid[1]}: " + ", ".join(
            f"{m} {'ok' if r.converged else 'NOT converged'} {r.cpu:.1f} s" for m, r in models.items()), flush=True)
    return results


def _grid_key(grid) -> str:
    return f"{grid[0]}x{grid[1]}"


def _all_converged(saved: dict) -> bool:
    return all(r["converged"] for r in saved.values())


def chosen_results(contacts, by_grid: dict) -> tuple[dict, dict]:
    """Per contact the saved figures of the finest grid converged in all three models, and that grid's name."""
    results, grids = {}, {}
    for c in contacts:
        for grid in (ta.GRID, ta.COARSE_GRID):
            saved = by_grid[_grid_key(grid)][c.name]
            if _all_converged(saved) or grid == ta.COARSE_GRID:
                results[c.name], grids[c.name] = saved, _grid_key(grid)
                break
    return results, grids


def print_grid_check(contacts, by_grid: dict) -> None:
    """The errors of off and reduced on both grids, for the contacts converged on both."""
    fine, coarse = (by_grid[_grid_key(g)] for g in (ta.GRID, ta.COARSE_GRID))
    print(f"\nGrid check: the largest error in h_c, h_min and mu on {_grid_key(ta.COARSE_GRID)} and "
          f"{_grid_key(ta.GRID)}, and h_c(full) on both:\n")
    print("| contact | off % (coarse / fine) | reduced % (coarse / fine) | h_c full µm (coarse / fine) |")
    print("|---|---|---|---|")
    for c in contacts:
        if _all_converged(fine[c.name]) and _all_converged(coarse[c.name]):
            r = [_as_models(saved[c.name]) for saved in (coarse, fine)]
            cells = [" / ".join(_percent(ta.largest_error(x, m)) for x in r) for m in ("off", "reduced")]
            h_c = " / ".join(f"{1e6 * x['full'].figures['h_c']:.3f}" for x in r)
            print(f"| {c.name.split('_')[0]} | {' | '.join(cells)} | {h_c} |")


def _as_models(saved: dict) -> dict[str, ta.ModelFigures]:
    return {m: ta.ModelFigures(r["converged"], {k: r[k] for k in ta.FIGURES}, r["cpu"]) for m, r in saved.items()}


def _percent(value: float) -> str:
    return "–" if math.isnan(value) else f"{100 * value:.2f}"


def print_table(contacts, results, grids) -> None:
    print("| contact | L_th | SRR | p_h GPa | a/b | rheology | oil | h_c µm | μ full | ΔT_max K | off h_c % | "
          "off h_min % | off μ % | red. h_c % | red. h_min % | red. μ % | red. p_max % | red. ΔT_max % | "
          "CPU off/red./full s |")
    print("|" + "---|" * 19)
    for c in contacts:
        r = _as_models(results[c.name])
        full = r["full"].figures
        errors = [ta.relative_error(r, m, f) for m, f in (("off", "h_c"), ("off", "h_min"), ("off", "mu"),
                  ("reduced", "h_c"), ("reduced", "h_min"), ("reduced", "mu"), ("reduced", "p_max"),
                  ("reduced", "dT_max"))]
        mark = "" if grids[c.name] == _grid_key(ta.GRID) else f" ({grids[c.name]})"
        print(f"| {c.name.split('_')[0]}{mark} | {c.loading:.3g} | {c.point.slide_roll_ratio:.2f} | "
              f"{c.point.hertz.p_max * 1e-9:.2f} | {c.point.hertz.a / c.point.hertz.b:.3g} | "
              f"{'Ree–Eyring' if c.lubricant.rheology == 'ree_eyring' else 'Newtonian'} | {c.oil} | "
              f"{1e6 * full['h_c']:.3f} | {full['mu']:.4f} | {full['dT_max']:.1f} | "
              + " | ".join(_percent(e) for e in errors)
              + f" | {r['off'].cpu:.1f}/{r['reduced'].cpu:.1f}/{r['full'].cpu:.1f} |"
              + ("" if _all_converged(results[c.name]) else " not converged: " + ", ".join(
                  m for m, x in r.items() if not x.converged)))


WEIGHTS = (0.0, 0.003, 0.01, 0.03, 0.1, 0.3, 1.0)  # the sliding weights w of G = L_th + w Theta_s tried


def _fit(contacts, results, weight: float, model: str) -> ta.Envelope:
    rows = [(c.loading + weight * c.sliding, ta.largest_error(_as_models(results[c.name]), model)) for c in contacts]
    rows = [(g, e) for g, e in rows if math.isfinite(e) and e > 0.0]
    return ta.envelope_fit([g for g, _ in rows], [e for _, e in rows])


def print_fit(contacts, results) -> None:
    print("\nUpper envelopes error <= C G^n of the largest error in h_c, h_min and mu, G = L_th + w Theta_s; spread: "
          "the largest factor by which the envelope overstates a measured error:\n")
    print("| w | off: C | n | spread | reduced: C | n | spread |")
    print("|---|---|---|---|---|---|---|")
    for weight in WEIGHTS:
        off, red = (_fit(contacts, results, weight, m) for m in ("off", "reduced"))
        print(f"| {weight:g} | {off.coefficient:.4g} | {off.exponent:.3f} | {off.spread:.3g} | {red.coefficient:.4g} | "
              f"{red.exponent:.3f} | {red.spread:.3g} |")
    weight = TUNING.auto_sliding_weight
    print(f"\nThe fit at w = {weight:g} (TUNING.auto_sliding_weight), against TUNING:\n")
    for model in ("off", "reduced"):
        fit, tuned = _fit(contacts, results, weight, model), thermal.AUTO_ENVELOPES[model]
        print(f"{model}: error <= {fit.coefficient:.4g} G^{fit.exponent:.3f} over {fit.points} contacts; least-squares "
              f"residual up to {fit.scatter:.3g}x, envelope overstates by up to {fit.spread:.3g}x; TUNING "
              f"{tuned[0]:.4g} G^{tuned[1]:.3f}")
    print("\n| contact | G | off: predicted % | measured % | reduced: predicted % | measured % | auto picks |")
    print("|---|---|---|---|---|---|---|")
    for c in contacts:
        r = _as_models(results[c.name])
        number = thermal.heating_number(c.point, c.lubricant)
        cells = [f"{100 * thermal.predicted_error(m, number):.3g} | {_percent(ta.largest_error(r, m))}"
                 for m in ("off", "reduced")]
        print(f"| {c.name.split('_')[0]} | {number:.3g} | {' | '.join(cells)} | "
              f"{thermal.thermal_choice('auto', c.point, c.lubricant)[0]} |")


def print_check() -> None:
    print(f"\nContacts the fit did not see, auto against full on {_grid_key(ta.GRID)} (%):\n")
    print("| contact | G | auto picks | h_c | h_min | μ | CPU auto / full s |")
    print("|---|---|---|---|---|---|---|")
    for checked in ta.check_contacts(CASES):
        model, results = ta.auto_against_full(checked)
        number = thermal.heating_number(checked.point, checked.lubricant)
        if not results:
            print(f"| {checked.name} | {number:.3g} | full | – | – | – | – |")
            continue
        errors = " | ".join(_percent(ta.relative_error(results, "auto", f)) for f in thermal.AUTO_FIGURES)
        print(f"| {checked.name} | {number:.3g} | {model} | {errors} | "
              f"{results['auto'].cpu:.1f} / {results['full'].cpu:.1f} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--save", type=Path)
    parser.add_argument("--load", type=Path)
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--grid-check", type=int, nargs="*", default=[])
    args = parser.parse_args()
    contacts = ta.fit_contacts(CASES)
    by_grid = (json.loads(args.load.read_text()) if args.load else
               {_grid_key(g): _solve_all(contacts, g) for g in (ta.GRID, ta.COARSE_GRID)})
    if args.save:
        args.save.write_text(json.dumps(by_grid, indent=1))
    results, grids = chosen_results(contacts, by_grid)
    print(f"\n{len(contacts)} contacts, errors against full (each on {_grid_key(ta.GRID)}, or "
          f"{_grid_key(ta.COARSE_GRID)} where marked):\n")
    print_table(contacts, results, grids)
    print_grid_check(contacts, by_grid)
    print_fit(contacts, results)
    if args.check:
        print_check()


if __name__ == "__main__":
    main()
