"""Long-ellipse limit: the elliptical solver's central film at a/b = 100 against the line-contact reference.

The ellipse: steel on steel (E = 200 GPa, nu = 0.3), R_x = 20 mm, R_y = 2000 R_x (Hertz a/b = 99.9), the project's
default oil law (eta_0 = 0.04 Pa s, alpha = 22 GPa^-1, Roelands + Dowson-Higginson), isothermal Newtonian,
entrainment along x (the minor axis), pure rolling, solved by `facegear_tehl.ehl.solve.solve_point` on its
default settings (`SolverSettings()`) but on Venner & Lubrecht's domain, the line contact's (LINE_DOMAIN).

The line contact: the same R_x and the same maximum Hertz pressure p_h, i.e. w' = pi b p_h/2 with b the minor
semi-axis (on the ellipse's centre line the Hertz pressure p_h sqrt(1 - x^2/b^2) carries pi b p_h/2 per unit
length; the plane-strain line contact of that load has p_h = E' b_line/(4 R_x), and b_line/b = 1.0002 at this
R_y/R_x), solved by `facegear_tehl.line.solve_line` on 801 and 1601 nodes over the elliptical solver's default
inlet/outlet extent (-4.5 b, 1.5 b); the Richardson extrapolation of the two (order 2) is the reference.

    python scripts/line_vs_ellipse.py [--grid 257] [--grid-y 65]
"""

from __future__ import annotations

import argparse
import math
import time

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.solve import solve_point
from facegear_tehl.hertz import hertz_contact
from facegear_tehl.line import solve_line
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.materials import Solid, reduced_modulus
from facegear_tehl.settings import SolverSettings

STEEL = Solid(elastic_modulus=2.0e11, poisson_ratio=0.3)
RADIUS_X = 0.02  # m
RADIUS_RATIO = 2000.0  # R_y/R_x: Hertz ellipticity a/b = 99.9
OIL = Lubricant(viscosity=0.04, pressure_viscosity=2.2e-8)
LINE_DOMAIN = (-4.5, 1.5)  # x/b: Venner & Lubrecht's extent along x (ehl.domain), given to both solvers
ELLIPSE_DOMAIN_Y = (-3.0, 3.0)  # y/a: Venner & Lubrecht's
LINE_ORDER = 2.0  # observed order of h_c of the line solver (tests/test_line_contact.py: 1.98)


def ellipse_load(p_h: float, e_prime: float) -> float:
    """Load W giving the maximum Hertz pressure p_h (p_max grows as W^(1/3) at fixed radii)."""
    reference = hertz_contact(RADIUS_X, RADIUS_X * RADIUS_RATIO, 1000.0, e_prime)
    return 1000.0 * (p_h / reference.p_max) ** 3


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=SolverSettings().grid, help="elliptical grid along x, the minor "
                        "axis (default: SolverSettings())")
    parser.add_argument("--grid-y", type=int, default=None, help="nodes along y, the major axis (default: --grid)")
    args = parser.parse_args()
    settings = SolverSettings(grid=args.grid, grid_y=args.grid_y, domain_x=LINE_DOMAIN, domain_y=ELLIPSE_DOMAIN_Y)
    e_prime = reduced_modulus(STEEL, STEEL)
    print(f"a/b = 100 ellipse (R_x = {RADIUS_X * 1e3:g} mm, R_y/R_x = {RADIUS_RATIO:g}) vs line contact, "
          f"elliptical grid {settings.grid} x {settings.nodes_y}\n")
    print("| p_h (GPa) | u_e (m/s) | ellipse h_c (nm) | ellipse status | line h_c (nm) | line error | "
          "ellipse - line | ellipse time | line time |")
    print("|---|---|---|---|---|---|---|---|---|")
    for p_h in (0.8e9, 1.5e9):
        load = ellipse_load(p_h, e_prime)
        hertz = hertz_contact(RADIUS_X, RADIUS_X * RADIUS_RATIO, load, e_prime)
        w_line = math.pi * hertz.b * hertz.p_max / 2.0
        for u_e in (2.0, 10.0):
            point = ContactPoint.from_rolling_sliding("contact", RADIUS_X, RADIUS_X * RADIUS_RATIO, load, u_e, 0.0,
                                                      0.0, STEEL, STEEL)
            start = time.perf_counter()
            try:
                ellipse = solve_point(point, OIL, settings)
                h_ellipse = ellipse.scalar("h_c")
                status = ellipse.outcome.name.lower() + (f" ({ellipse.message})" if ellipse.message else "")
            except Exception as error:  # the elliptical solver may raise where it diverges: report it
                h_ellipse, status = math.nan, f"raised {type(error).__name__}: {error}"
            t_ellipse = time.perf_counter() - start
            start = time.perf_counter()
            lines = [solve_line(RADIUS_X, w_line, u_e, 0.0, OIL, STEEL, STEEL, nodes=n, domain=LINE_DOMAIN)
                     for n in (801, 1601)]
            t_line = time.perf_counter() - start
            coarse, fine = lines[0].h_c, lines[1].h_c
            h_line = fine + (fine - coarse) / (2.0**LINE_ORDER - 1.0)
            error = abs(h_line - fine) / h_line
            ok = "" if all(s.converged for s in lines) else " (line NOT converged)"
            diff = 100.0 * (h_ellipse / h_line - 1.0)
            print(f"| {p_h / 1e9:.1f} | {u_e:g} | {h_ellipse * 1e9:.1f} | {status} | {h_line * 1e9:.1f}{ok} | "
                  f"{100 * error:.2f} % | {diff:+.2f} % | {t_ellipse:.0f} s | {t_line:.0f} s |", flush=True)


if __name__ == "__main__":
    main()
