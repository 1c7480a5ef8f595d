"""Cost of the thermal coupling: where the time of a thermal solve goes, and before/after timings.

1. Profile (CPU time, one process, one BLAS thread as `tehl run` solves): the thermal full solve of one point of a
   gear case (default S1 of cases/facegear_110.yaml, its own grid), split by stage (the start: full multigrid and
   the pressure cycles outside the outer loops; the coarse grids' outer loops, the seed stage's first; the finest
   grid's) into the film state (viscosity, Ree-Eyring shear state, rheology and the glue of an update), the energy
   equation (column sweeps, wall heat fluxes, Jaeger's surfaces), the flow coefficients of the generalised Reynolds
   equation (every relaxation sweep recomputes them), the rest of the V-cycles and the rest of the outer loop
   (acceleration, freezing the state); with the outer iterations and V-cycles of each stage. --thermal off profiles
   the isothermal solve (with the case's Ree-Eyring lubricant: its outer loop of eta*/eta on the finest grid).
2. With --before DIR (a source tree of another version, e.g. `git worktree add DIR HEAD~1`): the same profile of
   DIR, then timings interleaved (before, after, before, ...; medians of --repeat): the point's thermal full and
   isothermal Newtonian solves (CPU time of the solve in a warm process, and their ratio), `tehl run CASE
   --jobs 2` and `tehl validate CASE` (wall time from the command line, and the CPU time of the process and its
   workers), and with --cycle the 41-point cycle (`gear.points: 41`, --jobs 2): isothermal (`--thermal off`, the
   case's Ree-Eyring film) interleaved like the rest, thermal full one run each. On a machine shared with other work
   the wall times inflate with the load, the CPU times much less.

    python scripts/bench_coupling.py [CASE] [--point S1] [--thermal full] [--before DIR] [--repeat 3] [--cycle]
"""

from __future__ import annotations

import argparse
import collections
import json
import os
from pathlib import Path
import resource
import statistics
import subprocess
import sys
import tempfile
import time

HERE = Path(__file__).resolve().parents[1]
CYCLE_POINTS = 41  # the meshing cycle of docs/cycle.md

PROFILE = r'''
import collections, dataclasses, json, sys, time
from threadpoolctl import threadpool_limits
from facegear_tehl.case import load_case
from facegear_tehl.ehl import energy, flow, jaeger, rheology, solve, thermal
from facegear_tehl.points import contact_analysis

case = load_case(sys.argv[1])
point = next(p for p in contact_analysis(case).points if p.name == sys.argv[2])
times, counts, stage = collections.defaultdict(float), collections.Counter(), ["start"]

def timed(owner, name, key):
    original = getattr(owner, name)
    def wrapper(*args, **kwargs):
        start = time.process_time()
        try:
            return original(*args, **kwargs)
        finally:
            times[stage[0], key] += time.process_time() - start
    setattr(owner, name, wrapper)

for name in ("fixed_parts", "sweep_columns", "wall_fluxes"):
    if hasattr(energy, name):  # fixed_parts: a kernel of its own in later versions
        timed(energy, name, "energy")
timed(jaeger, "surface_temperature_rise", "energy")
for name in ("layered_coefficients", "temperature_factors", "isothermal_layered_coefficients", "column_integrals",
             "frozen_shapes", "frozen_layered_coefficients"):
    if hasattr(flow, name):  # the isothermal film's column form: a kernel of its own since this script's --thermal
        timed(flow, name, "flow")
timed(thermal.FilmThermalModel, "update", "update")
try:  # the pressure iteration of the one-engine driver; before it, PointSolve.cycle
    from facegear_tehl.ehl.pressure import PressureIteration as cycling
    from facegear_tehl.ehl.staged import solve_point
except ImportError:
    cycling, solve_point = solve.PointSolve, solve.solve_point
cycle = cycling.cycle
def counted_cycle(self, *args, **kwargs):
    before, start = self.history.cycles, time.process_time()
    try:
        return cycle(self, *args, **kwargs)
    finally:
        times[stage[0], "cycles"] += time.process_time() - start
        counts[stage[0], "cycles"] += self.history.cycles - before
cycling.cycle = counted_cycle
couple = solve.PointSolve.couple
def staged_couple(self, index, *args, **kwargs):
    level = self.solver.levels[index]
    stage[0] = "finest" if index == len(self.solver.levels) - 1 else "coarse"
    stage[0] += f" {level.nx} x {level.ny}"
    before, start = self.history.outer, time.process_time()
    try:
        return couple(self, index, *args, **kwargs)
    finally:
        times[stage[0], "loop"] += time.process_time() - start
        counts[stage[0], "outer"] += self.history.outer - before
        stage[0] = "start"
solve.PointSolve.couple = staged_couple
settings = dataclasses.replace(case.solver, thermal=sys.argv[3])
with threadpool_limits(limits=1):
    solve_point(point, case.lubricant, dataclasses.replace(settings, grid=33, grid_y=None))  # load kernels
    times.clear(), counts.clear()
    start = time.process_time()
    solution = solve_point(point, case.lubricant, settings)
    total = time.process_time() - start
print(json.dumps({"total": total, "converged": solution.converged,
                  "times": [[k[0], k[1], v] for k, v in times.items()],
                  "counts": [[k[0], k[1], v] for k, v in counts.items()]}))
'''

SOLVE = r'''
import dataclasses, json, sys, time
from threadpoolctl import threadpool_limits
from facegear_tehl.case import load_case
from facegear_tehl.points import contact_analysis
try:
    from facegear_tehl.ehl.staged import solve_point
except ImportError:  # a version before the one-engine driver
    from facegear_tehl.ehl.solve import solve_point

case = load_case(sys.argv[1])
point = next(p for p in contact_analysis(case).points if p.name == sys.argv[2])
models = {"thermal full": (dataclasses.replace(case.solver, thermal="full"), case.lubricant),
          "isothermal Newtonian": (dataclasses.replace(case.solver, thermal="off"),
                                   dataclasses.replace(case.lubricant, rheology="newtonian"))}
out = {}
with threadpool_limits(limits=1):
    for name, (settings, lubricant) in models.items():
        solve_point(point, lubricant, dataclasses.replace(settings, grid=33, grid_y=None))  # load the kernels
        start = time.process_time()
        solution = solve_point(point, lubricant, settings)
        out[name] = (time.process_time() - start, solution.converged)
print(json.dumps(out))
'''


def _run(tree: Path, args: list[str]) -> subprocess.CompletedProcess:
    """Run python with `args` in `tree` (its package first on the path: cwd and PYTHONPATH); exit codes 0 and 3
    (`tehl run`: a point not converged, the file written) pass."""
    env = {**os.environ, "PYTHONPATH": str(tree)}
    done = subprocess.run([sys.executable, *args], cwd=tree, env=env, capture_output=True, text=True)
    if done.returncode not in (0, 3):
        raise RuntimeError(f"{' '.join(args[:4])} in {tree} failed ({done.returncode}): {done.stderr[-500:]}")
    return done


def profile(tree: Path, case: Path, point: str, thermal: str) -> dict:
    """The profile of `tree` (PROFILE's JSON) under the thermal model `thermal`."""
    return json.loads(_run(tree, ["-c", PROFILE, str(case), point, thermal]).stdout.splitlines()[-1])


def print_profile(label: str, data: dict) -> None:
    """The profile as a markdown table, one row per stage, CPU seconds."""
    times = collections.defaultdict(float, {(s, k): v for s, k, v in data["times"]})
    counts = collections.defaultdict(int, {(s, k): v for s, k, v in data["counts"]})
    stages = sorted({"start"} | {s for s, _, _ in data["times"]},
                    key=lambda s: (("start", "coarse", "finest").index(s.split()[0]),
                                   int(s.split()[1]) if s.startswith("coarse") else 0))  # the seed stage first
    print(f"\n{label}: {data['total']:.2f} s CPU{'' if data['converged'] else ' (not converged)'}\n")
    print("| stage | outer iterations | V-cycles | film state s | energy equation s | flow coefficients s "
          "| rest of V-cycles s | rest of outer loop s | total s | per outer iteration s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for stage in stages:
        film = times[stage, "update"] - times[stage, "energy"]
        cycles_rest = times[stage, "cycles"] - times[stage, "flow"]
        if stage == "start":
            total = data["total"] - sum(times[s, "loop"] for s in stages if s != "start")
            rest = total - times[stage, "cycles"]
            outer, per = "–", "–"
        else:
            total = times[stage, "loop"]
            rest = total - times[stage, "update"] - times[stage, "cycles"]
            outer = counts[stage, "outer"]
            per = f"{total / max(outer, 1):.3f}"
        print(f"| {stage} | {outer} | {counts[stage, 'cycles']} | {film:.2f} | {times[stage, 'energy']:.2f} | "
              f"{times[stage, 'flow']:.2f} | {cycles_rest:.2f} | {rest:.2f} | {total:.2f} | {per} |")


def _cpu_of_children() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _wall(tree: Path, args: list[str]) -> tuple[float, float]:
    """Wall time and CPU time (the process and the workers it waited for) of one run, s."""
    start, cpu = time.perf_counter(), _cpu_of_children()
    _run(tree, args)
    return time.perf_counter() - start, _cpu_of_children() - cpu


def _cycle_case(case: Path, folder: Path) -> Path:
    """`case` with gear.points: 41 (as docs/cycle.md times it)."""
    import yaml

    data = yaml.safe_load(case.read_text())
    data["gear"]["points"] = CYCLE_POINTS
    path = folder / f"{case.stem}_cycle.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


def _add(samples: dict, label: str, quantity: str, wall_cpu: tuple[float, float]) -> None:
    """A run's wall and CPU time as two quantities."""
    samples[label, f"{quantity}, wall"].append(wall_cpu[0])
    samples[label, f"{quantity}, CPU"].append(wall_cpu[1])


def timings(trees: dict[str, Path], case: Path, point: str, repeat: int, cycle: bool) -> None:
    """Interleaved timings of every tree, medians and the ratio before/after."""
    samples: dict[tuple[str, str], list[float]] = collections.defaultdict(list)
    with tempfile.TemporaryDirectory() as folder:
        output = Path(folder) / "run.h5"
        for _ in range(repeat):
            for label, tree in trees.items():
                solves = json.loads(_run(tree, ["-c", SOLVE, str(case), point]).stdout.splitlines()[-1])
                for name, (cpu, _) in solves.items():
                    samples[label, f"{point} {name} solve, CPU"].append(cpu)
                samples[label, f"{point} thermal full / isothermal Newtonian"].append(
                    solves["thermal full"][0] / solves["isothermal Newtonian"][0])
                _add(samples, label, f"tehl run {case.name} --jobs 2",
                     _wall(tree, ["-m", "facegear_tehl", "run", str(case), "--jobs", "2", "-o", str(output)]))
                _add(samples, label, f"tehl validate {case.name}", _wall(tree, ["-m", "facegear_tehl", "validate",
                                                                                 str(case)]))
                print(label, {q: round(v[-1], 2) for (t, q), v in samples.items() if t == label}, flush=True)
        if cycle:
            cycle_case = _cycle_case(case, Path(folder))
            run = ["-m", "facegear_tehl", "run", str(cycle_case), "--jobs", "2", "-o", str(output)]
            for _ in range(repeat):
                for label, tree in trees.items():
                    _add(samples, label, f"{CYCLE_POINTS}-point cycle, isothermal (--thermal off), --jobs 2",
                         _wall(tree, [*run, "--thermal", "off"]))
            for label, tree in trees.items():
                _add(samples, label, f"{CYCLE_POINTS}-point cycle, thermal full, --jobs 2", _wall(tree, run))
    before, after = trees
    print(f"\nMedians of {repeat} interleaved runs (the thermal cycle: one run each); solves: CPU time of one "
          "process:\n")
    print(f"| quantity | {before} | {after} | ratio |")
    print("|---|---|---|---|")
    for quantity in dict.fromkeys(q for _, q in samples):
        b, a = statistics.median(samples[before, quantity]), statistics.median(samples[after, quantity])
        unit = "" if "/" in quantity else " s"
        print(f"| {quantity} | {b:.2f}{unit} | {a:.2f}{unit} | {b / a:.2f}x |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", nargs="?", default="cases/facegear_110.yaml")
    parser.add_argument("--point", default="S1", help="the meshing point profiled and timed")
    parser.add_argument("--thermal", default="full", choices=("full", "reduced", "off"),
                        help="thermal model of the profile (the timings: thermal full)")
    parser.add_argument("--before", type=Path, help="source tree of the version to compare with")
    parser.add_argument("--repeat", type=int, default=3, help="interleaved runs per timing (medians)")
    parser.add_argument("--cycle", action="store_true",
                        help="also time the 41-point cycle, isothermal and thermal full (minutes)")
    args = parser.parse_args()
    case = Path(args.case).resolve()
    trees = {"before": args.before.resolve(), "after": HERE} if args.before else {"this tree": HERE}
    for label, tree in trees.items():
        print_profile(f"{label} ({tree}), {args.point} thermal {args.thermal}",
                      profile(tree, case, args.point, args.thermal))
    if args.before:
        timings(trees, case, args.point, args.repeat, args.cycle)


if __name__ == "__main__":
    main()
