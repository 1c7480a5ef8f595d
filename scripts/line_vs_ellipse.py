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

With --thermal both solve the thermal Ree-Eyring film with sliding (`solver.thermal: full` on the ellipse,
`thermal=True` on the line; the same lubricant laws, Jaeger's high-Peclet moving-source solids and friction heat,
no thermal expansion): the oil has beta = 0.03 1/K, k_f = 0.14 W/(m K), c_f = 2000 J/(kg K), tau_0 = 10 MPa
(docs/line-contact.md, thermal table), steel solids of k = 46 W/(m K), rho c = 7850 x 470 J/(m^3 K). The line
contact is solved on 201, 401 and 801 nodes; its reference is the Richardson value of the three finest converged
grids (observed order), or of the two finest at order 2 when only two converge. The ellipse's dT_max is the
largest film temperature rise anywhere; the largest rise on its centre line is printed next to it. `--newtonian`
makes the thermal film Newtonian (no tau_0) in both.

    python scripts/line_vs_ellipse.py [--grid 257] [--grid-y 65] [--thermal [--srr 0.3] [--newtonian]]
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import math
import time
import warnings

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.hertz import hertz_contact
from facegear_tehl.line import solve_line
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.materials import Solid, reduced_modulus
from facegear_tehl.settings import SolverSettings

STEEL = Solid(elastic_modulus=2.0e11, poisson_ratio=0.3)
RADIUS_X = 0.02  # m
RADIUS_RATIO = 2000.0  # R_y/R_x: Hertz ellipticity a/b = 99.9
OIL = Lubricant(viscosity=0.04, pressure_viscosity=2.2e-8)
# the thermal Ree-Eyring oil of docs/line-contact.md's thermal table (beta, k_f, c_f, tau_0 as stated there)
THERMAL_OIL = Lubricant(viscosity=0.04, pressure_viscosity=2.2e-8, temperature_viscosity=0.03,
                        thermal_conductivity=0.14, specific_heat=2000.0, rheology="ree_eyring", eyring_stress=1.0e7)
THERMAL_LINE_NODES = (201, 401, 801)  # the line solver's thermal grids (1601 nodes take minutes per point)
LINE_DOMAIN = (-4.5, 1.5)  # x/b: Venner & Lubrecht's extent along x (ehl.domain), given to both solvers
ELLIPSE_DOMAIN_Y = (-3.0, 3.0)  # y/a: Venner & Lubrecht's
LINE_ORDER = 2.0  # observed order of h_c of the line solver (tests/test_line_contact.py: 1.98)


def ellipse_load(p_h: float, e_prime: float) -> float:
    """Load W giving the maximum Hertz pressure p_h (p_max grows as W^(1/3) at fixed radii)."""
    reference = hertz_contact(RADIUS_X, RADIUS_X * RADIUS_RATIO, 1000.0, e_prime)
    return 1000.0 * (p_h / reference.p_max) ** 3


def _limit_contacts(e_prime: float):
    """(p_h Pa, u_e m/s, ellipse load N, line load w' N/m) of the comparison: p_h 0.8 and 1.5 GPa, u_e 2 and 10 m/s,
    the line carrying the ellipse centre line's pi b p_h/2."""
    for p_h in (0.8e9, 1.5e9):
        load = ellipse_load(p_h, e_prime)
        hertz = hertz_contact(RADIUS_X, RADIUS_X * RADIUS_RATIO, load, e_prime)
        for u_e in (2.0, 10.0):
            yield p_h, u_e, load, math.pi * hertz.b * hertz.p_max / 2.0


def _ellipse_status(solution) -> str:
    return solution.outcome.name.lower() + (f" ({solution.message})" if solution.message else "")


def richardson(values: list[float]) -> tuple[float, float]:
    """Extrapolated value and observed order from successive grid values (spacing halved each time): the three
    finest with their observed order p = log2(|f_2h - f_4h|/|f_h - f_2h|), or the two finest at order 2."""
    if len(values) >= 3:
        f4, f2, f1 = values[-3:]
        if (f1 - f2) != 0.0 and (f2 - f4) / (f1 - f2) > 1.0:
            order = math.log2((f2 - f4) / (f1 - f2))
            return f1 + (f1 - f2) / (2.0**order - 1.0), order
    f2, f1 = values[-2:]
    return f1 + (f1 - f2) / (2.0**LINE_ORDER - 1.0), LINE_ORDER


def isothermal_table(settings: SolverSettings, e_prime: float) -> None:
    """Isothermal Newtonian, pure rolling: ellipse h_c against the line h_c (801 and 1601 nodes, extrapolated)."""
    print("| p_h (GPa) | u_e (m/s) | ellipse h_c (nm) | ellipse status | line h_c (nm) | line error | "
          "ellipse - line | ellipse time | line time |")
    print("|---|---|---|---|---|---|---|---|---|")
    for p_h, u_e, load, w_line in _limit_contacts(e_prime):
        point = ContactPoint.from_rolling_sliding("contact", RADIUS_X, RADIUS_X * RADIUS_RATIO, load, u_e, 0.0,
                                                  0.0, STEEL, STEEL)
        start = time.perf_counter()
        try:
            ellipse = solve_point(point, OIL, settings)
            h_ellipse = ellipse.scalar("h_c")
            status = _ellipse_status(ellipse)
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


def thermal_table(settings: SolverSettings, e_prime: float, srr: float, oil: Lubricant) -> None:
    """Thermal films with sliding: ellipse h_c and dT_max against the line's (201/401/801 nodes)."""
    settings = replace(settings, thermal="full")
    print("| p_h (GPa) | u_e (m/s) | SRR | line h_c (nm) 201 / 401 / 801 | line h_c* (nm) | line dT_max (K) "
          "201 / 401 / 801 | line dT_max* (K) | ellipse h_c (nm) | ellipse dT_max (K) (centre line) | "
          "ellipse status | h_c: ellipse - line | dT_max: ellipse - line | mu line / ellipse | ellipse time |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for p_h, u_e, load, w_line in _limit_contacts(e_prime):
        lines = []
        with warnings.catch_warnings():  # the dense Jacobian of a diverging 801-node solve warns at each step
            warnings.simplefilter("ignore")
            for n in THERMAL_LINE_NODES:
                lines.append(solve_line(RADIUS_X, w_line, u_e, srr, oil, STEEL, STEEL, nodes=n,
                                        domain=LINE_DOMAIN, thermal=True))
        good = [s for s in lines if s.converged]
        h_star, _ = richardson([s.h_c for s in good]) if len(good) >= 2 else (math.nan, math.nan)
        # dT_max converges at first order or better: the finest converged value, the extrapolation beside it
        t_star, _ = richardson([s.dT_max for s in good]) if len(good) >= 2 else (math.nan, math.nan)
        line_h = " / ".join(f"{s.h_c * 1e9:.1f}" if s.converged else "n.c." for s in lines)
        line_t = " / ".join(f"{s.dT_max:.1f}" if s.converged else "n.c." for s in lines)
        point = ContactPoint.from_rolling_sliding("contact", RADIUS_X, RADIUS_X * RADIUS_RATIO, load, u_e, srr,
                                                  0.0, STEEL, STEEL)
        start = time.perf_counter()
        ellipse = solve_point(point, oil, settings)
        t_ellipse = time.perf_counter() - start
        h_e, dt_e = ellipse.scalar("h_c"), ellipse.scalar("dT_max")
        centre = int(np.argmin(np.abs(ellipse.axes["y"].values)))
        dt_centre = max(float(ellipse.fields[k].values[centre].max()) for k in
                        ("temperature_mid", "temperature_surface_1", "temperature_surface_2"))
        dt_centre -= oil.inlet_temperature
        print(f"| {p_h / 1e9:.1f} | {u_e:g} | {srr:g} | {line_h} | {h_star * 1e9:.1f} | {line_t} | {t_star:.1f} | "
              f"{h_e * 1e9:.1f} | {dt_e:.1f} ({dt_centre:.1f}) | {_ellipse_status(ellipse)} | "
              f"{100 * (h_e / h_star - 1):+.2f} % | {100 * (dt_e / t_star - 1):+.2f} % | "
              f"{good[-1].friction:.4f} / {ellipse.scalar('mu'):.4f} | {t_ellipse:.0f} s |", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=SolverSettings().grid, help="elliptical grid along x, the minor "
                        "axis (default: SolverSettings())")
    parser.add_argument("--grid-y", type=int, default=None, help="nodes along y, the major axis (default: --grid)")
    parser.add_argument("--thermal", action="store_true", help="thermal Ree-Eyring films with sliding")
    parser.add_argument("--srr", type=float, default=0.3, help="slide-to-roll ratio of --thermal (default 0.3)")
    parser.add_argument("--newtonian", action="store_true", help="--thermal with a Newtonian film (no tau_0)")
    args = parser.parse_args()
    settings = SolverSettings(grid=args.grid, grid_y=args.grid_y, domain_x=LINE_DOMAIN, domain_y=ELLIPSE_DOMAIN_Y)
    e_prime = reduced_modulus(STEEL, STEEL)
    oil = replace(THERMAL_OIL, rheology="newtonian") if args.newtonian else THERMAL_OIL
    kind = f"thermal {oil.rheology}, SRR {args.srr:g}" if args.thermal else "isothermal Newtonian, pure rolling"
    print(f"a/b = 100 ellipse (R_x = {RADIUS_X * 1e3:g} mm, R_y/R_x = {RADIUS_RATIO:g}) vs line contact, {kind}, "
          f"elliptical grid {settings.grid} x {settings.nodes_y}\n")
    if args.thermal:
        thermal_table(settings, e_prime, args.srr, oil)
    else:
        isothermal_table(settings, e_prime)


if __name__ == "__main__":
    main()
