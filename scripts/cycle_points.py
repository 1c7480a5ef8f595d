"""Mesh efficiency of the default face gear case against the number of points along the path (cycle.py's
quadrature): the case with gear.points: N for each N given, solved on --grid, thermal as asked; prints N, the
efficiency with the film's mu, Xu's and ISO/TR 14179-2's, their change against the largest N, and the wall time;
first the case's own five points S1..S5.

    python scripts/cycle_points.py [--grid 33] [--thermal off] [--jobs 2] [11 21 41 81]
"""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path
import time

from facegear_tehl.case import load_case
from facegear_tehl.run import run_case
from facegear_tehl.tables import format_table

CASE = Path(__file__).resolve().parents[1] / "cases" / "facegear_110.yaml"
SUFFIXES = (("", "film mu"), ("_xu", "Xu"), ("_iso", "ISO/TR"))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("counts", nargs="*", type=int, default=[11, 21, 41, 81])
    parser.add_argument("--grid", type=int, default=33)
    parser.add_argument("--thermal", default="off")
    parser.add_argument("--jobs", type=int, default=2)
    options = parser.parse_args()
    base = load_case(CASE)
    samples = {"S1..S5": ("S1", "S2", "S3", "S4", "S5"), **{str(count): count for count in options.counts}}
    efficiency, seconds = {}, {}
    for label, points in samples.items():
        case = replace(base, gear=replace(base.gear, points=points),
                       solver=replace(base.solver, thermal=options.thermal))
        start = time.perf_counter()
        run = run_case(case, grid=options.grid, jobs=options.jobs)
        seconds[label] = time.perf_counter() - start
        efficiency[label] = {suffix: run.cycle_scalars.get(f"mesh_efficiency{suffix}", (float("nan"), ""))[0]
                             for suffix, _ in SUFFIXES}
    reference = efficiency[str(max(options.counts))]
    rows = [[label, *(f"{100 * efficiency[label][suffix]:.4f}" for suffix, _ in SUFFIXES),
             *(f"{100 * (efficiency[label][suffix] - reference[suffix]):+.4f}" for suffix, _ in SUFFIXES),
             f"{seconds[label]:.1f}"] for label in samples]
    headers = ["points", *(f"eta {name} %" for _, name in SUFFIXES),
               *(f"d {name} pp" for _, name in SUFFIXES), "wall s"]
    print(f"{CASE.name}, grid {options.grid}, thermal {options.thermal}, {options.jobs} jobs")
    print(format_table(headers, rows))


if __name__ == "__main__":
    main()
