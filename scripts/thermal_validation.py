"""Published thermal validation (facegear_tehl/suites/thermal_validation.py, where the comparison, its contact and its
tolerances are described): prints the line solver's and the long ellipse's thermal correction factor C against the
thermal inlet analysis (facegear_tehl/suites/thermal_inlet.py) and Wilson & Sheu's and Murch & Wilson's fits, what
moves the line solver's C, and the inlet analysis against the fits, as Markdown tables.

    python scripts/thermal_validation.py [--nodes 401] [--layers 12] [--check 801 24] [--grid 65] [--grid-y 17]
        [--ellipse-check 129 33] [--no-ellipse]
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import math
import time

from facegear_tehl.line import solve_line
from facegear_tehl.line.solve import DEFAULT_DOMAIN
from facegear_tehl.suites.thermal_validation import (
    COLD_STEEL,
    FIT_LOADINGS,
    INLET_TOLERANCE,
    OIL,
    RADIUS,
    ROLLING_SPEEDS,
    SENSITIVITY_SPEED,
    STEEL,
    Row,
    compare,
    load_per_length,
    murch_wilson,
    rolling_inlet,
    thermal_loading,
    wilson_sheu,
)


def sensitivity(nodes: int, layers: int) -> str:
    """What moves our C at L = 0.86: one change at a time from the working grid, then all the inlet analysis's
    assumptions together, with the inlet analysis's own C last, as a Markdown table."""
    load = load_per_length()
    u = SENSITIVITY_SPEED
    barus = replace(OIL, viscosity_model="barus")
    local = replace(OIL, specific_heat=OIL.specific_heat / 100.0)
    variants = [
        ("working grid", OIL, STEEL, nodes, layers, DEFAULT_DOMAIN),
        ("viscosity exponential in T, Barus in p", barus, STEEL, nodes, layers, DEFAULT_DOMAIN),
        (f"inlet at {2 * DEFAULT_DOMAIN[0]:g} b (same spacing)", OIL, STEEL, 2 * nodes - 1, layers,
         (2 * DEFAULT_DOMAIN[0], DEFAULT_DOMAIN[1])),
        (f"{2 * layers} layers", OIL, STEEL, nodes, 2 * layers, DEFAULT_DOMAIN),
        (f"{2 * nodes - 1} nodes", OIL, STEEL, 2 * nodes - 1, layers, DEFAULT_DOMAIN),
        ("c_f / 100 (heat hardly carried along the film)", local, STEEL, nodes, layers, DEFAULT_DOMAIN),
        ("walls held at T_0", OIL, COLD_STEEL, nodes, layers, DEFAULT_DOMAIN),
        ("the inlet analysis's assumptions: Barus-exponential, walls at T_0, c_f / 100",
         replace(barus, specific_heat=OIL.specific_heat / 100.0), COLD_STEEL, nodes, layers, DEFAULT_DOMAIN),
    ]
    lines = ["| variant | C | change |", "|---|---|---|"]
    base = math.nan
    for name, lubricant, solid, n, m, domain in variants:
        iso = solve_line(RADIUS, load, u, 0.0, lubricant, solid, solid, nodes=n, domain=domain)
        hot = solve_line(RADIUS, load, u, 0.0, lubricant, solid, solid, nodes=n, domain=domain, thermal=True,
                         layers=m)
        ratio = hot.h_c / iso.h_c
        base = ratio if math.isnan(base) else base
        flag = "" if iso.converged and hot.converged else " (not converged)"
        lines.append(f"| {name} | {ratio:.4f}{flag} | {100.0 * (ratio / base - 1.0):+.2f} % |")
    inlet = rolling_inlet(u).correction(thermal_loading(OIL, u))
    lines.append(f"| the inlet analysis (thermal_inlet.py: Grubin's rigid inlet, same assumptions) | {inlet:.4f} "
                 f"| {100.0 * (inlet / base - 1.0):+.2f} % |")
    return "\n".join(lines)


def fits_table() -> str:
    """The inlet analysis against the published fits it should reproduce (Wilson & Sheu 1983 eq. 8, Murch &
    Wilson 1975 as quoted by them), over FIT_LOADINGS, at the contact of the comparison (u_e = 10 m/s; C
    depends on L and only weakly on the other groups), as a Markdown table."""
    inlet = rolling_inlet(SENSITIVITY_SPEED)
    lines = ["| L | inlet analysis C | Wilson–Sheu C | Murch–Wilson C | fit − inlet (Wilson–Sheu) |",
             "|---|---|---|---|---|"]
    for loading in FIT_LOADINGS:
        c = inlet.correction(loading)
        ws = wilson_sheu(loading, 0.0)
        lines.append(f"| {loading:g} | {c:.4f} | {ws:.4f} | {murch_wilson(loading):.4f} "
                     f"| {100.0 * (ws / c - 1.0):+.1f} % |")
    return "\n".join(lines)


def table(rows: list[Row], grid: str, check: str) -> str:
    """The comparison as a Markdown table; `grid` and `check` name the two grids (C columns)."""
    lines = [
        f"| u_e m/s | L | h_c iso µm | h_c thermal µm | ΔT_max K | C ({grid}) "
        f"| C ({check}) | inlet analysis C | vs inlet | Wilson–Sheu C | Murch–Wilson C | vs Wilson–Sheu "
        f"| (1−C)/(1−C_WS) | tolerance (inlet / Wilson–Sheu) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        tol = ("not asserted" if r.tolerance is None
               else f"{100.0 * INLET_TOLERANCE:.0f} % / {100.0 * r.tolerance:.0f} %")
        flag = "" if r.converged else " (not converged)"
        lines.append(
            f"| {r.speed:g} | {r.loading:.3f} | {1e6 * r.h_iso:.3f} | {1e6 * r.h_thermal:.3f} "
            f"| {r.dT_max:.1f} | {r.ratio:.4f} | {r.ratio_check:.4f}{flag} | {r.inlet:.4f} "
            f"| {100.0 * r.inlet_difference:+.1f} % | {r.wilson_sheu:.4f} "
            f"| {murch_wilson(r.loading):.4f} "
            f"| {100.0 * r.difference:+.1f} % | {(1.0 - r.ratio_check) / (1.0 - r.wilson_sheu):.2f} | {tol} |"
        )
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=401, help="working grid: nodes along x")
    parser.add_argument("--layers", type=int, default=12, help="working grid: layers across the film")
    parser.add_argument("--check", type=int, nargs=2, default=(801, 24), metavar=("NODES", "LAYERS"),
                        help="check grid of the line solver")
    parser.add_argument("--grid", type=int, default=65, help="ellipse: nodes along x (2^n + 1)")
    parser.add_argument("--grid-y", type=int, default=17, help="ellipse: nodes along y (2^n + 1)")
    parser.add_argument("--ellipse-check", type=int, nargs=2, default=(129, 33), metavar=("GRID", "GRID_Y"),
                        help="check grid of the ellipse")
    parser.add_argument("--no-ellipse", action="store_true", help="the line solver only")
    args = parser.parse_args()
    check = (args.check[0], args.check[1])
    start = time.perf_counter()
    rows = [compare(u, args.nodes, args.layers, check) for u in ROLLING_SPEEDS]
    print("Line solver (facegear_tehl.line), nodes x layers\n")
    print(table(rows, f"{args.nodes} × {args.layers}", f"{check[0]} × {check[1]}"))
    print(f"\nwall time {time.perf_counter() - start:.1f} s")
    print(f"\nWhat moves the line solver's C at u_e = {SENSITIVITY_SPEED:g} m/s "
          f"(L = {thermal_loading(OIL, SENSITIVITY_SPEED):.2f})\n")
    print(sensitivity(args.nodes, args.layers))
    print("\nThe inlet analysis (thermal_inlet.py) against the published fits of inlet analyses\n")
    print(fits_table())
    if args.no_ellipse:
        return
    start = time.perf_counter()
    ellipse_check = (args.ellipse_check[0], args.ellipse_check[1])
    rows = [compare(u, args.grid, args.grid_y, ellipse_check, "ellipse") for u in ROLLING_SPEEDS]
    print("\nLong ellipse a/b = 99.9 as a contact: case (run_case, thermal full against off), grid x grid_y\n")
    print(table(rows, f"{args.grid} × {args.grid_y}", f"{ellipse_check[0]} × {ellipse_check[1]}"))
    print(f"\nwall time {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    main()
