"""The across-film state of one thermal update (SI units): temperature, eta*/eta, dissipation, velocities, wall
stresses and heat fluxes per layer node, the data the energy equation (energy.py), the thermal model (thermal.py)
and the friction (friction.py) exchange."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class FilmState:
    """Across-film state after one update; layer fields shaped (nz, ny, nx)."""

    temperature: np.ndarray  # K
    viscosity_factor: np.ndarray  # eta*/eta
    dissipation: np.ndarray  # W/m^3
    velocity_x: np.ndarray | None  # m/s (None without the energy equation, the only user of the velocities)
    velocity_y: np.ndarray | None  # m/s
    stress_1: np.ndarray  # (2, ny, nx) shear stress at surface 1, Pa
    stress_2: np.ndarray  # (2, ny, nx) at surface 2, Pa
    # (ny, nx) into solid 1 and 2, W/m^2 (None: deferred by `update(..., wall_fluxes=False)`, see
    # thermal.FilmThermalModel.completed)
    heat_flux_1: np.ndarray | None
    heat_flux_2: np.ndarray | None
    compression: np.ndarray | None  # beta_T T (u . grad p), W/m^3 (None without the energy equation)
    change: float  # largest temperature change of this update, K
    heat_capacity: np.ndarray | None = None  # rho c per layer node as the energy equation used it, J/(m^3 K)
    # (None without the energy equation)
