"""What moves from the EHL solver to the results file: one `PointSolution` per meshing point (SI units)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from facegear_tehl.accuracy_record import AccuracyRecord
from facegear_tehl.outcome import CONVERGED, Outcome, Status
from facegear_tehl.record import SolveRecord

__all__ = ["CONVERGED", "Field", "Outcome", "PointSolution", "Status"]


@dataclass(frozen=True)
class Field:
    """A field or 1-D table with its units and a one-line description."""

    values: np.ndarray
    units: str
    description: str = ""


@dataclass(frozen=True)
class PointSolution:
    """Result of one contact-point solve.

    scalars: name -> (value, units); the keys of the result file (README glossary: h_c, h_min, p_max, p_hertz, a, b,
        load_error, iterations, work_units, wall_time, error_estimate_h_c, ...), SI units.
    fields: 2-D arrays on the (ny, nx) grid (pressure, film_thickness, temperature, ...).
    axes: 'x' and 'y' node coordinates, m.
    history: per-cycle arrays (residual_history, load_error_history, ...).
    outcome: how the solve ended; message says why it did not converge (empty when it did).
    models: which models produced it (viscosity, density, rheology, thermal, with their sources).
    record: the typed solve record (record.py), from which models['solver'] is rendered.
    """

    name: str
    outcome: Outcome
    message: str
    scalars: Mapping[str, tuple[float, str]]
    fields: Mapping[str, Field]
    axes: Mapping[str, Field]
    history: Mapping[str, Field] = field(default_factory=dict)
    models: Mapping[str, str] = field(default_factory=dict)
    record: SolveRecord | None = None  # how the solve ran (planned and run stages, retries); None for a stand-in
    accuracy: AccuracyRecord | None = None  # what the accuracy target chose (solver.accuracy); None without one

    @property
    def converged(self) -> bool:
        return self.outcome is Outcome.CONVERGED

    def scalar(self, key: str) -> float:
        return float(self.scalars[key][0])
