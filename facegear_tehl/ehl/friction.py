"""Friction of the film: the traction the film's shear stresses exert on each surface (SI units)."""

from __future__ import annotations

import numpy as np

from facegear_tehl.ehl.film_state import FilmState


def friction_coefficients(state: FilmState, pressure: np.ndarray, cell: float,
                          load: float) -> tuple[float, float, float]:
    """Friction coefficients from the shear stresses over the pressurised film: mu_i = |F_i|/W with the traction
    on body 1, F_1 = \\iint tau(z = 0) dA, and on body 2, F_2 = -\\iint tau(z = h) dA (Couette and Poiseuille
    parts); `cell` is the area of one grid cell (m^2), `load` W (N). Returns (mean of mu_1 and mu_2, mu_1, mu_2)."""
    wet = pressure > 0.0
    f1 = np.array([state.stress_1[0][wet].sum(), state.stress_1[1][wet].sum()]) * cell
    f2 = np.array([state.stress_2[0][wet].sum(), state.stress_2[1][wet].sum()]) * cell
    mu_1, mu_2 = float(np.hypot(*f1) / load), float(np.hypot(*f2) / load)
    return 0.5 * (mu_1 + mu_2), mu_1, mu_2
