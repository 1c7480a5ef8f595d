"""The outlet pressure spike row by row: where the beaded crescent of a long ellipse's pressure map comes from.

For each point and grid: the spike maximum of every row inside |y| < 0.8 a (the row's largest pressure), and
- `p_max`, the largest adjacent-row difference and the odd-even amplitude |mean((-1)^j d2_j)|/4 of the rows'
  second differences d2 (an alternating pattern A (-1)^j has d2 = 4 A (-1)^j; a smooth trend has d2 ~ 0);
- `y-grid`: against the first grid of the same x spacing, the largest difference between the rows' maxima at
  the same y (a mode of the y-discretisation or of the line relaxation would change with the rows);
- `line sampled`: the independent line-contact solver (`facegear_tehl.line`, 1601 nodes over -4.5 .. 1.5 b:
  radius R_x, the point's Hertz p_h, w' = pi b p_h/2, |U_e|, its SRR, the case's thermal model and rheology)
  sampled at the grid's x spacing with 32 offsets: the range of the nodal maximum that a grid of that
  spacing shows for the true spike, depending only on where the spike falls between two nodes.

    python scripts/spike_rows.py [CASE] [--points S3] [--grids 257x65,257x129] [--thermal off] [--newtonian]

Measured on the default case in docs/accuracy.md (the beaded crescent).
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import math
from pathlib import Path

import numpy as np

from facegear_tehl.case import load_case
from facegear_tehl.line import solve_line
from facegear_tehl.points import contact_analysis
from facegear_tehl.run import run_case
from facegear_tehl.sweep import with_thermal

ROW_SPAN = 0.8  # rows inside |y| < 0.8 a: the crescent's spike, away from its ends where the spike fades out
LINE_NODES = 1601  # line spacing 0.0034 b: the thermal spike (about 0.03 b wide) is resolved by ~10 nodes
LINE_DOMAIN = (-4.5, 1.5)  # x/b, the elliptical solver's default extent along x
OFFSETS = 32  # positions of the spike between two nodes at which the line solution is sampled
CASE = Path(__file__).resolve().parents[1] / "cases" / "facegear_110.yaml"


def row_maxima(pressure: np.ndarray, y: np.ndarray, a: float) -> tuple[np.ndarray, np.ndarray]:
    """(y of the rows inside |y| < ROW_SPAN a, each row's largest pressure); pressure (ny, nx), y in m."""
    rows = np.abs(y) < ROW_SPAN * a
    return y[rows], pressure[rows].max(axis=1)


def odd_even_amplitude(maxima: np.ndarray) -> float:
    """|mean((-1)^j d2_j)|/4 of the second differences d2 of `maxima`: the amplitude A of an A (-1)^j pattern."""
    d2 = maxima[2:] - 2.0 * maxima[1:-1] + maxima[:-2]
    return abs(float(np.mean(d2 * (-1.0) ** np.arange(d2.size)))) / 4.0


def sampled_range(x: np.ndarray, p: np.ndarray, spacing: float) -> tuple[float, float]:
    """Smallest and largest nodal maximum of p(x), linearly interpolated, on grids of `spacing` shifted by
    OFFSETS fractions of a cell."""
    maxima = [np.interp(np.arange(x[0] + k * spacing / OFFSETS, x[-1], spacing), x, p).max() for k in range(OFFSETS)]
    return min(maxima), max(maxima)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", nargs="?", default=str(CASE))
    parser.add_argument("--points", default="S3")
    parser.add_argument("--grids", default="257x65,257x129", help="nx x ny grids, comma-separated")
    parser.add_argument("--thermal", help="override solver.thermal")
    parser.add_argument("--newtonian", action="store_true", help="Newtonian film instead of the case's rheology")
    args = parser.parse_args()
    case = load_case(args.case)
    if args.thermal:
        case = with_thermal(case, args.thermal)
    if args.newtonian:
        case = replace(case, lubricant=replace(case.lubricant, rheology="newtonian"))
    names = args.points.split(",")
    points = {p.name: p for p in contact_analysis(case).points}
    grids = [tuple(int(n) for n in g.split("x")) for g in args.grids.split(",")]
    print(f"{case.name}: thermal {case.solver.thermal}, rheology {case.lubricant.rheology}; MPa")
    print(f"{'point':>5} {'grid':>8} {'p_max':>6} {'adjacent':>8} {'odd-even':>8} {'y-grid':>6} "
          f"{'line sampled':>12}  row maxima")
    for name in names:
        first: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        point, line = points[name], None
        for nx, ny in grids:
            run = run_case(replace(case, solver=replace(case.solver, grid=nx, grid_y=ny)), points=[name], jobs=1)
            s = run.points[0]
            a, b, p_h = s.scalar("a"), s.scalar("b"), s.scalar("p_hertz")
            y, maxima = row_maxima(s.fields["pressure"].values / 1e6, s.axes["y"].values, a)
            y_grid = ""
            if nx in first:
                y0, m0 = first[nx]
                shared = [(m, m0[np.argmin(np.abs(y0 - v))]) for v, m in zip(y, maxima)
                          if np.abs(y0 - v).min() < 1e-6 * a]
                y_grid = f"{max(abs(m - m0) for m, m0 in shared):6.1f}"
            else:
                first[nx] = (y, maxima)
            if line is None:
                line = solve_line(point.radius_x, math.pi * b * p_h / 2.0, point.entrainment_speed,
                                  point.slide_roll_ratio, case.lubricant, point.body_1, point.body_2,
                                  nodes=LINE_NODES, domain=LINE_DOMAIN, thermal=case.solver.thermal != "off")
            spacing = float(s.axes["x"].values[1] - s.axes["x"].values[0]) / b
            low, high = sampled_range(line.x / line.b, line.p / 1e6, spacing)
            sampled = f"{low:5.0f}..{high:<5.0f}" if line.converged else f"{'not conv.':>12}"
            print(f"{name:>5} {nx:>4}x{ny:<3} {s.scalar('p_max') / 1e6:6.1f} {np.abs(np.diff(maxima)).max():8.1f} "
                  f"{odd_even_amplitude(maxima):8.2f} {y_grid:>6} {sampled}  "
                  + " ".join(f"{m:.0f}" for m in maxima), flush=True)


if __name__ == "__main__":
    main()
