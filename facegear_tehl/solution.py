"""What moves from the EHL solver to the results file: one `PointSolution` per meshing point (SI units)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np


@dataclass(frozen=True)
class Field:
    """A field or 1-D table with its units and a one-line description."""

    values: np.ndarray
    units: str
    description: str = ""


@dataclass(frozen=True)
class PointSolution:
    """Result of one contact-point solve.

    scalars: name -> (value, units); the keys of ARCHITECTURE.md (h_c, h_min, p_max, p_hertz, a, b,
        load_error, iterations, work_units, wall_time, error_estimate_h_c, ...), SI units.
    fields: 2-D arrays on the (ny, nx) grid (pressure, film_thickness, temperature, ...).
    axes: 'x' and 'y' node coordinates, m.
    history: per-cycle arrays (residual_history, load_error_history, ...).
    converged: the solve met its tolerances; message says why not (empty when converged).
    models: which models produced it (viscosity, density, rheology, thermal, with their sources).
    """

    name: str
    converged: bool
    message: str
    scalars: Mapping[str, tuple[float, str]]
    fields: Mapping[str, Field]
    axes: Mapping[str, Field]
    history: Mapping[str, Field] = field(default_factory=dict)
    models: Mapping[str, str] = field(default_factory=dict)

    def scalar(self, key: str) -> float:
        return float(self.scalars[key][0])
