"""Isothermal solver against the published film formulas (Hamrock & Dowson 1977, Nijenbanning et al.
1994, Chittenden et al. 1985): prints markdown tables.

1. Elliptical contacts, Barus + incompressible, entrainment along the minor axis: central film vs
   Nijenbanning-Venner-Moes (1994) and minimum film vs Hamrock-Dowson (1977), Moes' scaling.
2. Skewed entrainment on an ellipse (D = 0.2, M = 100, L = 10): h(theta)/h(0) vs Chittenden et al. (1985)
   with the groups built on R_e (radius in the entrainment direction) and, for reference, on R_x.
3. Rotation invariance of a circular contact (M = 20, L = 10).

    python scripts/validate_isothermal.py [--grid 257]
"""

from __future__ import annotations

import argparse
import math

from facegear_tehl.case import SolverSettings
from facegear_tehl.ehl.scaling import contact_from_moes, scaling_for
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.film_formulas import (
    chittenden_central,
    chittenden_minimum,
    chittenden_radii,
    hamrock_dowson_minimum,
    nijenbanning_central,
)


def solve(m, moes_l, d, angle, grid):
    point, lub = contact_from_moes(m, moes_l, d, entrainment_angle=angle)
    sol = solve_point(point, lub, SolverSettings(grid=grid, domain_x=None, domain_y=None, thermal="off",
                                                 coarsest_grid=17, cycles_per_level=2, max_cycles=40,
                                                 tolerance=1e-4, load_tolerance=1e-4))
    sc = scaling_for(point, lub)
    to_moes = 1.0 / (point.radius_x * math.sqrt(2.0 * sc.hamrock_u))
    return sol, sc, sol.scalar("h_c") * to_moes, sol.scalar("h_min") * to_moes


def mark(sol):
    return "" if sol.converged else " *"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=257)
    args = parser.parse_args()
    n = args.grid

    print(f"Elliptical contacts ({n}^2, Barus, incompressible; Moes scaling H = h/R_x (2U)^-1/2):\n")
    print("| M | L | D = R_x/R_y | H_c solver | H_c NVM | diff | H_min solver | H_min HD | diff |")
    print("|---|---|---|---|---|---|---|---|---|")
    for m, moes_l in ((20.0, 10.0), (100.0, 10.0)):
        for d in (1.0, 0.5, 0.2, 0.05):
            sol, sc, hc, hmin = solve(m, moes_l, d, 0.0, n)
            nvm = nijenbanning_central(m, moes_l, d)
            k_hd = 1.03 * (1.0 / d) ** 0.64
            hd = hamrock_dowson_minimum(sc.hamrock_u, sc.hamrock_g, sc.hamrock_w, k_hd) / math.sqrt(2 * sc.hamrock_u)
            print(f"| {m:g} | {moes_l:g} | {d:g} | {hc:.3f}{mark(sol)} | {nvm:.3f} | {100 * (hc / nvm - 1):+.1f} % | "
                  f"{hmin:.3f} | {hd:.3f} | {100 * (hmin / hd - 1):+.1f} % |")

    print(f"\nSkewed entrainment, D = 0.2, M = 100, L = 10 ({n}^2): film relative to 0 deg\n")
    print("| angle | h_c solver | Chittenden (R_e groups) | diff | h_min solver | Chittenden (R_e) | diff "
          "| h_c Chittenden (R_x groups) |")
    print("|---|---|---|---|---|---|---|---|")
    d = 0.2
    base_sol, _, base_c, base_m = solve(100.0, 10.0, d, 0.0, n)

    def chit(theta, fn, on_re):
        r_e, r_s = chittenden_radii(1.0, 1.0 / d, theta)
        factor = r_e ** (1 - 0.68 + 2 * 0.073) if on_re else 1.0
        return factor * fn(1.0, 1.0, 1.0, r_s / r_e)

    for angle in (0.0, 15.0, 30.0, 45.0, 60.0):
        sol, _, hc, hmin = solve(100.0, 10.0, d, angle, n)
        t = math.radians(angle)
        c_re = chit(t, chittenden_central, True) / chit(0.0, chittenden_central, True)
        m_re = chit(t, chittenden_minimum, True) / chit(0.0, chittenden_minimum, True)
        c_rx = chit(t, chittenden_central, False) / chit(0.0, chittenden_central, False)
        rc, rm = hc / base_c, hmin / base_m
        print(f"| {angle:g} | {rc:.3f}{mark(sol)} | {c_re:.3f} | {100 * (rc / c_re - 1):+.1f} % | {rm:.3f} | "
              f"{m_re:.3f} | {100 * (rm / m_re - 1):+.1f} % | {c_rx:.3f} |")

    print(f"\nRotation invariance, circle M = 20, L = 10 ({n}^2; * = stopped at max_cycles, best iterate):\n")
    print("| angle | H_c | H_min | cycles |")
    print("|---|---|---|---|")
    for angle in (0.0, 30.0, 45.0, 60.0):
        sol, _, hc, hmin = solve(20.0, 10.0, 1.0, angle, n)
        print(f"| {angle:g} | {hc:.4f}{mark(sol)} | {hmin:.4f} | {sol.scalar('iterations'):.0f} |")


if __name__ == "__main__":
    main()
