"""What a user waits for, side by side in one run: the whole `tehl run` process against the C reference, the thermal
cost, S1-S5 thermal and the 41-point thermal meshing cycle, each against a previous version (docs/benchmarks.md).

Per source tree (this one, and with --before DIR another version, e.g. `git worktree add /tmp/before main`), runs
interleaved (before, after, before, ...; medians of --repeat):

1. Venner & Lubrecht's circular case, M = 20, L = 10, Roelands + Dowson-Higginson (`cases/ball_on_disc.yaml`, 257^2):
   `tehl run` from the command line to the file (wall and CPU time of the process) and the solve alone in a warm
   process; H_c = h_c R/a^2 of the file against the reference's 513^2 value. The reference: the C program of
   Venner & Lubrecht (2000, appendix; full multigrid, 6 V-cycles per level) run with --reference EXE when its
   build is present (its own wall time, `EXE` as given, no arguments), else its recorded 2.0 s on this machine type
   at 257^2 (docs/benchmarks.md). The process again with Python's bytecode cached (PYTHONPYCACHEPREFIX in the
   run's temporary folder, written by one untimed run per tree), as an installed package has it: an environment
   with PYTHONDONTWRITEBYTECODE set compiles the package's ~90 modules from source in every process. Its phases
   in one more run each (PHASES: importing the command line, importing the solver, Numba's first load of a cached
   kernel, the rest of the solve, writing the file, reading it back for the tables). Beside them the floor of any
   such process: one that imports what `tehl run` needs of NumPy, Numba, SciPy's FFT, h5py, PyYAML and Click and
   calls one trivial cached Numba kernel (FLOOR).
2. S1 of cases/facegear_110.yaml: the thermal full Ree-Eyring solve's CPU time over its isothermal Newtonian solve's.
3. `tehl run cases/facegear_110.yaml --jobs 2` (S1-S5, thermal full): wall and CPU time (the workers included).
4. With --cycle: the 41-point thermal cycle (`gear.points: 41`, --jobs 2), --cycle-repeat runs each, interleaved;
   with --before, each point's h_c, h_min, dT_max and mu against the before tree's file (a cold start per point,
   the previous version), in units of that file's error estimate of the figure.

    python scripts/bench_job.py [--before DIR] [--repeat 3] [--cycle] [--cycle-repeat 1] [--reference EXE]

On a machine shared with other work the wall times inflate with the load; the CPU times and the ratios of runs
interleaved in one call much less.
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import os
from pathlib import Path
import statistics
import subprocess
import sys
import tempfile
import time

from bench_coupling import SOLVE, _cpu_of_children, _cycle_case, _run, _wall
import h5py
import numpy as np

HERE = Path(__file__).resolve().parents[1]
CIRCLE = HERE / "cases" / "ball_on_disc.yaml"
FACE_GEAR = HERE / "cases" / "facegear_110.yaml"
REFERENCE_H_C = 0.4318  # H_c of the C reference at 513^2, Roelands + Dowson-Higginson (docs/benchmarks.md)
REFERENCE_SECONDS = 2.0  # its recorded wall time at 257^2 with 6 V-cycles per level (docs/benchmarks.md)
FIGURES = ("h_c", "h_min", "dT_max", "mu")
BOUNDED = ("h_c", "h_min", "p_max", "dT_max", "mu")  # S1-S5 compared in units of the before file's error bounds

CIRCLE_SOLVE = r'''
import dataclasses, json, sys, time
from threadpoolctl import threadpool_limits
from facegear_tehl.case import load_case
from facegear_tehl.points import contact_analysis
from facegear_tehl.ehl.staged import solve_point
case = load_case(sys.argv[1])
point = contact_analysis(case).points[0]
with threadpool_limits(limits=1):
    solve_point(point, case.lubricant, dataclasses.replace(case.solver, grid=33))  # load the kernels
    start, cpu = time.perf_counter(), time.process_time()
    solution = solve_point(point, case.lubricant, case.solver)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
h_c = solution.scalar("h_c") * point.radius_x / solution.scalar("a") ** 2
print(json.dumps({"wall": wall, "cpu": cpu, "H_c": h_c}))
'''


PHASES = r'''
import atexit, json, sys, time
begun = time.perf_counter()
import facegear_tehl.cli as cli
phases = {"import the command line": time.perf_counter() - begun}
import facegear_tehl.run as run
from numba.core.base import BaseContext

def timed(owner, name, phase):
    function = getattr(owner, name)
    def wrapper(*args, **kwargs):
        start = time.perf_counter()
        try:
            return function(*args, **kwargs)
        finally:
            phases[phase] = phases.get(phase, 0.0) + time.perf_counter() - start
    setattr(owner, name, wrapper)

timed(run, "path_solver", "import the solver")
timed(run, "solve_refining", "solve")
timed(BaseContext, "refresh", "Numba's first load of a cached kernel")  # its later calls cost microseconds
timed(cli, "write_result", "write the file")
timed(cli, "read_result", "read it back for the tables")
atexit.register(lambda: print(json.dumps({**phases, "whole process": time.perf_counter() - begun})))
sys.argv = ["tehl", *sys.argv[1:]]
cli.main()
'''


FLOOR = "import numpy, numba, scipy.fft, h5py, yaml, click, floor_kernel; floor_kernel.add(1.0)"
FLOOR_KERNEL = "import numba\n\n\n@numba.njit(cache=True)\ndef add(x):\n    return x + 1.0\n"


def _cached_bytecode(tree: Path, args: list[str], cache: Path) -> tuple[float, float, str]:
    """Wall time, CPU time and stdout of `python args` in `tree` with its bytecode cached in `cache`."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env.update(PYTHONPATH=str(tree), PYTHONPYCACHEPREFIX=str(cache))
    start, cpu = time.perf_counter(), _cpu_of_children()
    done = subprocess.run([sys.executable, *args], cwd=tree, env=env, capture_output=True, text=True)
    if done.returncode not in (0, 3):
        raise RuntimeError(f"{' '.join(args[:4])} in {tree} failed ({done.returncode}): {done.stderr[-500:]}")
    return time.perf_counter() - start, _cpu_of_children() - cpu, done.stdout


def circle_h_c(path: Path) -> float:
    """H_c = h_c R_x/a^2 of the circular case's result file."""
    with h5py.File(path, "r") as f:
        scalars = f["points/contact"].attrs
        return float(scalars["h_c"] * scalars["radius_x"] / scalars["a"] ** 2)


def point_figures(path: Path) -> dict[str, dict[str, float]]:
    """Per point of a result file: each figure and its error estimate (relative)."""
    out = {}
    with h5py.File(path, "r") as f:
        for name, group in f["points"].items():
            attrs = group.attrs
            out[name] = {k: float(attrs[k]) for k in FIGURES if k in attrs}
            out[name].update({f"err_{k}": float(attrs.get(f"error_estimate_{k}", np.nan)) for k in FIGURES})
    return out


def shares(after: Path, before: Path) -> dict[str, list[float]]:
    """|after - before| / |before's error estimate| of each figure at every point (the before file: a cold start)."""
    a, b = point_figures(after), point_figures(before)
    return {k: [abs(a[p][k] - b[p][k]) / abs(b[p][f"err_{k}"] * b[p][k]) for p in b if k in b[p] and k in a[p]]
            for k in FIGURES}


def bound_shares(after: Path, before: Path) -> list[str]:
    """Per point of S1-S5: each figure's |after - before| / (before's error bound x |before|), and both bounds (%);
    "unresolved" where the before file has no bound."""
    lines = []
    with h5py.File(after, "r") as a, h5py.File(before, "r") as b:
        for name, group in b["points"].items():
            was, now = group.attrs, a["points"][name].attrs
            cells = []
            for k in BOUNDED:
                if was.get(f"unresolved_{k}", 1.0) or f"error_bound_{k}" not in was:
                    cells.append(f"{k} unresolved (change {abs(now[k] / was[k] - 1):.2e})")
                    continue
                share = abs(now[k] - was[k]) / abs(was[f"error_bound_{k}"] * was[k])
                after_bound = 100 * now[f"error_bound_{k}"] if f"error_bound_{k}" in now else math.nan
                cells.append(f"{k} {share:.3f} (bound {100 * was[f'error_bound_{k}']:.2f} -> {after_bound:.2f} %)")
            lines.append(f"  {name}: " + "; ".join(cells))
    return lines


def reference_seconds(exe: Path | None) -> tuple[float, str]:
    """The C reference's wall time: its own run when the build is given, else the recorded time."""
    if exe is None or not exe.exists():
        return REFERENCE_SECONDS, "recorded (build not present)"
    start = time.perf_counter()
    subprocess.run([str(exe)], check=True, capture_output=True)
    return time.perf_counter() - start, f"run here ({exe})"


def measure(trees: dict[str, Path], args: argparse.Namespace, folder: Path) -> dict:
    """Interleaved runs of every tree; samples by (tree, quantity)."""
    samples: dict[tuple[str, str], list[float]] = collections.defaultdict(list)
    circle = ["run", str(CIRCLE), "--jobs", "1", "-o"]
    for label, tree in trees.items():  # writes each tree's bytecode cache
        _cached_bytecode(tree, ["-m", "facegear_tehl", *circle, str(folder / "warm.h5")], folder / f"{label}_pyc")
    floor = folder / "floor"
    floor.mkdir()
    (floor / "floor_kernel.py").write_text(FLOOR_KERNEL)
    _cached_bytecode(floor, ["-c", FLOOR], folder / "floor_pyc")  # compiles the kernel into its cache
    for _ in range(args.repeat):
        for label, tree in trees.items():
            output = folder / f"{label}_circle.h5"
            wall, cpu = _wall(tree, ["-m", "facegear_tehl", *circle, str(output)])
            samples[label, "circle 257^2: tehl run process, wall"].append(wall)
            samples[label, "circle 257^2: tehl run process, CPU"].append(cpu)
            samples[label, "circle 257^2: H_c of the file"].append(circle_h_c(output))
            cache = folder / f"{label}_pyc"
            wall, cpu, _ = _cached_bytecode(tree, ["-m", "facegear_tehl", *circle, str(output)], cache)
            samples[label, "circle 257^2: tehl run process, bytecode cached, wall"].append(wall)
            samples[label, "circle 257^2: tehl run process, bytecode cached, CPU"].append(cpu)
            phases = json.loads(_cached_bytecode(tree, ["-c", PHASES, *circle, str(output)], cache)[2].splitlines()[-1])
            for phase, seconds in phases.items():
                samples[label, f"circle 257^2, bytecode cached, wall: {phase}"].append(seconds)
            wall, cpu, _ = _cached_bytecode(floor, ["-c", FLOOR], folder / "floor_pyc")
            samples[label, "floor: the libraries imported, one cached kernel called, wall"].append(wall)
            samples[label, "floor: the libraries imported, one cached kernel called, CPU"].append(cpu)
            solve = json.loads(_run(tree, ["-c", CIRCLE_SOLVE, str(CIRCLE)]).stdout.splitlines()[-1])
            samples[label, "circle 257^2: solve in a warm process, wall"].append(solve["wall"])
            samples[label, "circle 257^2: solve in a warm process, CPU"].append(solve["cpu"])
            solves = json.loads(_run(tree, ["-c", SOLVE, str(FACE_GEAR), "S1"]).stdout.splitlines()[-1])
            samples[label, "S1 thermal full / isothermal Newtonian (CPU)"].append(
                solves["thermal full"][0] / solves["isothermal Newtonian"][0])
            wall, cpu = _wall(tree, ["-m", "facegear_tehl", "run", str(FACE_GEAR), "--jobs", "2",
                                     "-o", str(folder / f"{label}_s1s5.h5")])
            samples[label, "S1-S5 thermal full, --jobs 2, wall"].append(wall)
            samples[label, "S1-S5 thermal full, --jobs 2, CPU"].append(cpu)
            print(label, {q: round(v[-1], 3) for (t, q), v in samples.items() if t == label}, flush=True)
    if args.cycle:
        cycle = _cycle_case(FACE_GEAR, folder)
        for _ in range(args.cycle_repeat):
            for label, tree in trees.items():
                wall, cpu = _wall(tree, ["-m", "facegear_tehl", "run", str(cycle), "--jobs", "2",
                                         "-o", str(folder / f"{label}_cycle.h5")])
                samples[label, "41-point thermal cycle, --jobs 2, wall"].append(wall)
                samples[label, "41-point thermal cycle, --jobs 2, CPU"].append(cpu)
                print(label, "cycle", round(wall, 1), round(cpu, 1), flush=True)
    return samples


def report(trees: dict[str, Path], samples: dict, args: argparse.Namespace, folder: Path) -> None:
    labels = list(trees)
    print(f"\nMedians of {args.repeat} interleaved runs (the cycle: {args.cycle_repeat}); CPU includes the workers:\n")
    print("| quantity | " + " | ".join(labels) + (" | before / after |" if len(labels) == 2 else " |"))
    print("|---|" + "---|" * len(labels) + ("---|" if len(labels) == 2 else ""))
    medians = {}
    for quantity in dict.fromkeys(q for _, q in samples):
        row = [statistics.median(samples[label, quantity]) for label in labels]
        medians.update({(label, quantity): value for label, value in zip(labels, row)})
        ratio = f" {row[0] / row[1]:.2f}x |" if len(row) == 2 and "H_c" not in quantity else (" |" if len(row) == 2
                                                                                              else "")
        print(f"| {quantity} | " + " | ".join(f"{v:.4g}" for v in row) + " |" + ratio)
    this = labels[-1]
    seconds, how = reference_seconds(args.reference)
    h_c = medians[this, "circle 257^2: H_c of the file"]
    print(f"\nC reference (Venner & Lubrecht 2000), 257^2 Roelands + DH: {seconds:.2f} s, {how}; H_c {h_c:.4f} is "
          f"{100 * (h_c / REFERENCE_H_C - 1):+.2f} % of its 513^2 value {REFERENCE_H_C}")
    for clock in ("wall", "CPU"):  # on a loaded machine the CPU time stands for a quiet machine's wall time
        process = medians[this, f"circle 257^2: tehl run process, {clock}"]
        solve = medians[this, f"circle 257^2: solve in a warm process, {clock}"]
        print(f"  by {clock} time: whole process {seconds / process:.2f}x faster than the reference (aimed at 2x), "
              f"solve {seconds / solve:.2f}x (aimed at 3x)")
    if len(labels) == 2:
        print("S1-S5, |after - before| / before's error bound, per point and figure (the bounds before -> after):")
        print("\n".join(bound_shares(folder / f"{this}_s1s5.h5", folder / f"{labels[0]}_s1s5.h5")))
    if args.cycle and len(labels) == 2:
        found = shares(folder / f"{this}_cycle.h5", folder / f"{labels[0]}_cycle.h5")
        print("41-point cycle, |after - before| / before's error estimate, per figure (largest, points within 1):")
        for k, values in found.items():
            print(f"  {k}: largest {max(values):.3f}, {sum(v <= 1.0 for v in values)} of {len(values)} within")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", type=Path, help="source tree of the version to compare with")
    parser.add_argument("--repeat", type=int, default=3, help="interleaved runs per timing (medians)")
    parser.add_argument("--cycle", action="store_true", help="also the 41-point thermal cycle (minutes)")
    parser.add_argument("--cycle-repeat", type=int, default=1, help="interleaved runs of the cycle")
    parser.add_argument("--reference", type=Path, help="the C reference's executable, when built here")
    args = parser.parse_args()
    trees = {"before": args.before.resolve(), "after": HERE} if args.before else {"this tree": HERE}
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        samples = measure(trees, args, folder)
        report(trees, samples, args, folder)


if __name__ == "__main__":
    sys.exit(main())
