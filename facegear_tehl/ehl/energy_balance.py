"""The film's energy balance as a check on a converged thermal solve (energy.energy_budget computes it): at a solution
of the discrete equations heat generated + mass defect = heat conducted + convected up to round-off, so an imbalance
beyond TUNING.max_energy_imbalance says the film state is not one: the solve reports it not converged
(solve.PointSolve.report), and error_bounds.py bounds none of its figures."""

from __future__ import annotations

from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.solution import Outcome, PointSolution


def energy_unbalanced(solution: PointSolution) -> bool:
    """A converged thermal solve whose film's energy balance (`energy_balance_error`: heat generated + mass defect
    against heat conducted and convected, relative) misses TUNING.max_energy_imbalance."""
    imbalance = solution.scalars.get("energy_balance_error", (0.0, "1"))[0]
    return solution.outcome is Outcome.CONVERGED and abs(imbalance) > TUNING.max_energy_imbalance


def energy_failure(solution: PointSolution) -> str:
    """The message of an `energy_unbalanced` solve reported not converged: its own, and why."""
    imbalance = 100.0 * solution.scalar("energy_balance_error")
    return "; ".join(part for part in (solution.message, (
        f"the film's energy balance is off by {imbalance:.2g} % of the heat generated (beyond "
        f"{100.0 * TUNING.max_energy_imbalance:g} %): its film state does not solve the energy equation")) if part)
