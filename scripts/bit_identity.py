"""Bit-identity of two versions' results, for a change that must not move a number (a refactor).

`snapshot` solves the shipped case (all points), the hard cases and/or the operating envelope with the source tree
it runs in (set PYTHONPATH to the tree) and writes, per solved point, its outcome, every scalar by repr (wall times
aside) and a SHA-1 of every field and history array; `compare` lists every point whose snapshot differs.

    PYTHONPATH=OLD python scripts/bit_identity.py snapshot old.json [--suites shipped,hard,envelope] [--jobs 2]
    PYTHONPATH=NEW python scripts/bit_identity.py snapshot new.json [...]
    python scripts/bit_identity.py compare old.json new.json
"""

from __future__ import annotations

import argparse
import hashlib
import json
from pathlib import Path
import sys

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SUITES = ("shipped", "hard", "envelope")


def _digest(values: np.ndarray) -> str:
    return hashlib.sha1(np.ascontiguousarray(values).tobytes()).hexdigest()[:16]


def snapshot_of(solution) -> dict:
    """A point's outcome, scalars (repr, timings aside) and array digests."""
    return {"outcome": solution.outcome.value,
            "scalars": {k: repr(float(v[0])) for k, v in solution.scalars.items() if "time" not in k},
            "fields": {k: _digest(f.values) for k, f in solution.fields.items()},
            "history": {k: _digest(f.values) for k, f in solution.history.items() if "time" not in k}}


def snapshot(suites: list[str], jobs: int) -> dict[str, dict]:
    """Every point of the suites asked for, solved as `tehl run` solves them (grid refinement included)."""
    from facegear_tehl.case import load_case
    from facegear_tehl.run import run_case

    found: dict[str, dict] = {}
    paths = ([ROOT / "cases" / "facegear_110.yaml"] if "shipped" in suites else []) + (
        sorted((ROOT / "cases" / "hard").glob("*.yaml")) if "hard" in suites else [])
    for path in paths:
        for point in run_case(load_case(path), jobs=jobs).points:
            found[f"{path.stem}/{point.name}"] = snapshot_of(point)
        print(path.stem, file=sys.stderr, flush=True)
    if "envelope" in suites:
        from facegear_tehl.parallel import SolveTask
        from facegear_tehl.run import ehl_solver, solve_refining
        from facegear_tehl.suites import envelope

        cases = envelope.envelope_cases()
        tasks = [SolveTask(c.point(), c.lubricant(), c.settings(envelope.GRID, envelope.GRID_Y)) for c in cases]
        solutions, _, _ = solve_refining(tasks, ehl_solver(), jobs=jobs)
        found.update({f"envelope/{c.name}": snapshot_of(s) for c, s in zip(cases, solutions, strict=True)})
    return found


def differences(first: dict[str, dict], second: dict[str, dict]) -> list[str]:
    """One line per point whose outcome, scalars or arrays differ (and per point in one snapshot alone)."""
    lines = [f"{key}: in one snapshot only" for key in sorted(set(first) ^ set(second))]
    for key in sorted(set(first) & set(second)):
        a, b = first[key], second[key]
        diff = [f"outcome {a['outcome']} -> {b['outcome']}"] if a["outcome"] != b["outcome"] else []
        for group in ("scalars", "fields", "history"):
            diff += [f"{group}.{name}" for name in sorted(set(a[group]) | set(b[group]))
                     if a[group].get(name) != b[group].get(name)]
        if diff:
            lines.append(f"{key}: " + ", ".join(diff[:8]))
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True)
    take = commands.add_parser("snapshot", help="solve the suites and write their snapshot")
    take.add_argument("output", type=Path)
    take.add_argument("--suites", default="shipped,hard", help=f"comma-separated, of {', '.join(SUITES)}")
    take.add_argument("--jobs", type=int, default=2)
    check = commands.add_parser("compare", help="list the points whose snapshots differ")
    check.add_argument("first", type=Path)
    check.add_argument("second", type=Path)
    args = parser.parse_args(argv)
    if args.command == "snapshot":
        suites = [s for s in args.suites.split(",") if s]
        unknown = sorted(set(suites) - set(SUITES))
        if unknown:
            parser.error(f"--suites: unknown {', '.join(unknown)} (one or more of {', '.join(SUITES)})")
        args.output.write_text(json.dumps(snapshot(suites, args.jobs), indent=1, sort_keys=True))
        return 0
    first, second = (json.loads(path.read_text()) for path in (args.first, args.second))
    lines = differences(first, second)
    print("\n".join(lines) if lines else f"{len(first)} points, bit-identical")
    return 1 if lines else 0


if __name__ == "__main__":
    sys.exit(main())
