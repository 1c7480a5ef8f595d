"""`tehl study` on a local Dask cluster: the speed-up of 2 worker processes over 1, and the scheduler's overhead
per variant against the variant's solve time.

The study: 24 isothermal variants of cases/ball_on_disc.yaml (6 loads x 4 entrainment speeds) on its own
257 x 257 grid. Measured, each --repeat times (medians printed):
  serial   every variant solved by `run.run_case` in this process, one after the other (what `tehl run --jobs 1`
           of each variant costs): the solve time per variant, and their sum;
  N = 1, 2 `study.run_study` on a fresh LocalCluster of N worker processes (threads_per_worker=1) whose workers
           have loaded the Numba kernels first (cluster start and warm-up timed apart; the workers' environment as
           `tehl study` sets it, study.WORKER_ENVIRON): the study's wall time
           from the first task submitted to the last file written, and the sum of the tasks' own times.
Overhead per variant on one worker: (study wall time - sum of the standalone solves) / 24, i.e. scheduling,
moving the result to this process and writing its file, as far as they keep the worker from solving; and the
worker's idle time between tasks, (study wall time - sum of the tasks' own times) / 24. Other sessions share
the machine: the load average is printed with the numbers.

    python scripts/bench_study.py [--repeat 1] [--grid 257]
"""

from __future__ import annotations

import argparse
import logging
import os
from pathlib import Path
import statistics
import tempfile
import time

from facegear_tehl.run import run_case
from facegear_tehl.study import WORKER_ENVIRON, run_study
from facegear_tehl.study_file import load_study

BASE = Path(__file__).resolve().parents[1] / "cases" / "ball_on_disc.yaml"
LOADS = (3.0, 4.5, 6.272, 9.0, 12.0, 16.0)  # N: Moes M from about 17 to 27 at the base speed
SPEEDS = (0.3, 0.6383, 1.0, 1.5)  # m/s


def write_study(folder: Path, grid: int) -> Path:
    path = folder / "bench.yaml"
    path.write_text(f"base: {BASE}\nvary:\n  contact.load: {list(LOADS)}\n  contact.entrainment_speed: "
                    f"{list(SPEEDS)}\nset: {{solver.grid: {grid}}}\n", encoding="utf-8")
    return path


def warm_up() -> None:
    """Load (or compile) the solver's Numba kernels in this process: the ball-on-disc case on a 33 x 33 grid."""
    from facegear_tehl.case import load_case

    run_case(load_case(BASE), grid=33, jobs=1)


def serial(study) -> list[float]:
    """Each variant's standalone solve time (s)."""
    times = []
    for variant in study.variants:
        start = time.perf_counter()
        run_case(variant.case, jobs=1)
        times.append(time.perf_counter() - start)
    return times


def on_cluster(study, workers: int, folder: Path) -> tuple[float, float, float]:
    """(cluster start and warm-up, study wall time, sum of the tasks' own times), s."""
    import dask
    from distributed import Client, LocalCluster

    start = time.perf_counter()
    with dask.config.set(WORKER_ENVIRON), LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                                       dashboard_address=None, silence_logs=logging.ERROR) as cluster, \
            Client(cluster) as client:
        client.run(warm_up)
        ready = time.perf_counter() - start
        report = run_study(study, folder, scheduler=cluster.scheduler_address)
    failed = [o for o in report.outcomes if o.status == "failed"]
    assert not failed, failed[0].message
    return ready, report.seconds, sum(o.seconds for o in report.outcomes)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--grid", type=int, default=257)
    args = parser.parse_args()
    load_before = os.getloadavg()
    warm_up()
    solves, totals, runs = [], [], {1: [], 2: []}
    with tempfile.TemporaryDirectory() as scratch:
        study = load_study(write_study(Path(scratch), args.grid))
        for repeat in range(args.repeat):
            times = serial(study)
            solves += times
            totals.append(sum(times))
            for workers in (1, 2):
                runs[workers].append(on_cluster(study, workers, Path(scratch) / f"out_{workers}_{repeat}"))
    n = len(study.variants)
    serial_total = statistics.median(totals)
    solve = statistics.median(solves)
    print(f"{n} variants of {BASE.name}, grid {args.grid}, isothermal; {args.repeat} repeat(s), medians; "
          f"load average {load_before[0]:.1f} before, {os.getloadavg()[0]:.1f} after, {os.cpu_count()} cores")
    print()
    print("| run | cluster start + warm-up s | study wall time s | sum of solves s | speed-up vs 1 worker |")
    print("|---|---|---|---|---|")
    print(f"| serial, this process | - | {serial_total:.1f} | {serial_total:.1f} | - |")
    wall = {w: statistics.median(r[1] for r in runs[w]) for w in runs}
    for workers, measured in runs.items():
        ready = statistics.median(r[0] for r in measured)
        tasks = statistics.median(r[2] for r in measured)
        print(f"| {workers} worker(s) | {ready:.1f} | {wall[workers]:.1f} | {tasks:.1f} | "
              f"{wall[1] / wall[workers]:.2f} |")
    print()
    overhead = (wall[1] - serial_total) / n
    idle = (wall[1] - statistics.median(r[2] for r in runs[1])) / n
    print(f"median solve per variant {solve:.2f} s; on one worker, overhead per variant against the standalone "
          f"solves {overhead:.3f} s ({100 * overhead / solve:.1f} % of a solve), worker idle between tasks "
          f"{idle:.3f} s ({100 * idle / solve:.1f} %)")


if __name__ == "__main__":
    main()
