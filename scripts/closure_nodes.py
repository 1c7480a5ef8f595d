"""The nodes across the outlet constriction of Hamrock & Dowson's (1977) minimum film on the finest grid along x the
refinement may reach (ehl/closure.py), for every contact of the envelope and the wide envelope from the suites' 257 x
65 (513 nodes thermal, 1025 isothermal), or for the points of the cases given: the measurements of `closure_nodes`
in docs/tuning.md. Lists the contacts with the fewest nodes first.

    python scripts/closure_nodes.py [--show 15] [CASE.yaml ...]
"""

from __future__ import annotations

import argparse

from facegear_tehl.case import load_case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.closure import constriction_nodes
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.points import contact_analysis
from facegear_tehl.settings import SolverSettings
from facegear_tehl.suites.envelope import envelope_cases
from facegear_tehl.suites.wide_envelope import wide_cases


def nodes(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> tuple[float, int, float]:
    """Hamrock & Dowson's h_min (m), the finest grid's nodes along x, and the nodes its constriction spans there, on
    the largest grid the refinement may reach (RetryPolicy.largest_grid's caps for the settings' thermal model)."""
    thermal = settings.thermal != "off"
    largest = TUNING.max_refined_thermal_grid if thermal else TUNING.max_refined_grid
    found = constriction_nodes(point, lubricant, settings, largest)
    return found.film, found.nx, found.nodes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", help="case files (default: the two envelope suites)")
    parser.add_argument("--show", type=int, default=15, help="rows to print (fewest nodes first)")
    args = parser.parse_args()
    rows = []
    if args.cases:
        for path in args.cases:
            case = load_case(path)
            for point in contact_analysis(case).points:
                rows.append((f"{case.name} {point.name}", *nodes(point, case.lubricant, case.solver)))
    else:
        for contact in wide_cases() + envelope_cases():
            rows.append((contact.name, *nodes(contact.point(), contact.lubricant(), contact.settings())))
    rows.sort(key=lambda row: row[3])
    print(f"{len(rows)} contacts; closure_nodes = {TUNING.closure_nodes}")
    for name, film, nx, count in rows[:args.show]:
        print(f"{count:6.2f} nodes  on {nx} along x  h_min (formula) {1e9 * film:8.2f} nm  {name}")


if __name__ == "__main__":
    main()
