"""Cost of one FFT deflection (elastic.DeflectionOperator.apply) on the grids of the face gear hierarchy, this tree
against another version's, interleaved in one run (CPU time per call, medians of --repeat rounds).

    python scripts/bench_deflection.py [--before DIR] [--repeat 5]
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path
import statistics
import subprocess
import sys

HERE = Path(__file__).resolve().parents[1]
# (nx, ny): the face gear hierarchy (513 x 65 finest) and square grids of the hard cases
SHAPES = [(1025, 129), (513, 65), (257, 65), (129, 65), (65, 65), (257, 33), (33, 33), (513, 513), (1025, 1025)]

ROUND = r'''
import json, sys, time
import numpy as np
from threadpoolctl import threadpool_limits
from facegear_tehl.ehl.elastic import DeflectionOperator
out = {}
with threadpool_limits(limits=1):
    for nx, ny in json.loads(sys.argv[1]):
        operator = DeflectionOperator(nx, ny, 6.0 / (nx - 1), 2.0 / (ny - 1), 5.0)
        pressure = np.maximum(np.random.default_rng(1).random((ny, nx)) - 0.3, 0.0)
        calls = max(int(2e6 / (nx * ny)), 20)
        operator.apply(pressure)
        start = time.process_time()
        for _ in range(calls):
            operator.apply(pressure)
        out[f"{nx} x {ny}"] = 1e3 * (time.process_time() - start) / calls
print(json.dumps(out))
'''


def _round(tree: Path) -> dict[str, float]:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    done = subprocess.run([sys.executable, "-c", ROUND, json.dumps(SHAPES)], cwd=tree, env=env, capture_output=True,
                          text=True, check=True)
    return json.loads(done.stdout)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--before", type=Path, help="source tree of the version to compare with")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    trees = ([("before", args.before.resolve())] if args.before else []) + [("this tree", HERE)]
    rounds: dict[str, list[dict[str, float]]] = {name: [] for name, _ in trees}
    for _ in range(args.repeat):
        for name, tree in trees:
            rounds[name].append(_round(tree))
    print("| grid | " + " | ".join(f"{name}, ms" for name, _ in trees) + " |")
    print("|---|" + "---|" * len(trees))
    for key in rounds[trees[0][0]][0]:
        medians = [statistics.median(r[key] for r in rounds[name]) for name, _ in trees]
        print(f"| {key} | " + " | ".join(f"{m:.3f}" for m in medians) + " |")


if __name__ == "__main__":
    main()
