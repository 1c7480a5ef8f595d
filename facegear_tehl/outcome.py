"""How a solve, or one of its steps, ended: a typed outcome with the reason in words (rendered, never parsed)."""

from __future__ import annotations

from dataclasses import dataclass
import enum


class Outcome(enum.Enum):
    """How a solve ended."""

    CONVERGED = "converged"  # every tolerance met
    NOT_CONVERGED = "not converged"  # the iteration budget was spent before the tolerances were met
    DIVERGED = "diverged"  # the iteration ran away; the last sound iterate is reported
    FILM_CLOSED = "film closed"  # the iterate's h_min <= 0: the grid does not resolve the film (ehl/solve.py)
    FAILED = "failed"  # the solve raised an error; no data


@dataclass(frozen=True)
class Status:
    """The outcome of a solve or of one of its steps, with the reason in words (empty when converged)."""

    outcome: Outcome
    message: str = ""

    @property
    def converged(self) -> bool:
        return self.outcome is Outcome.CONVERGED

    @property
    def diverged(self) -> bool:
        return self.outcome is Outcome.DIVERGED


CONVERGED = Status(Outcome.CONVERGED)
