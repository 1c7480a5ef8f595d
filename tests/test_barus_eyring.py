"""An isothermal Ree-Eyring film under Barus's exponential viscosity: the outer loop's first film-state update, made at
the Newtonian pressure of the full-multigrid start, wants eta*/eta many e-folds below its fixed point; a bounded step
per update (Relaxation.film_step) limits how far ln(eta*/eta) moves."""

from __future__ import annotations

import math

import numpy as np
import pytest

from facegear_tehl.ehl import coupled
from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.film_state import FilmState
from facegear_tehl.ehl.tuning import TUNING


def _update(factor: np.ndarray) -> FilmState:
    """An isothermal film state whose eta*/eta is `factor`."""
    ones = np.ones(factor.shape)
    return FilmState(temperature=313.15 * ones, viscosity_factor=factor, dissipation=ones, velocity_x=None,
                     velocity_y=None, stress_1=ones[:2], stress_2=ones[:2], heat_flux_1=None, heat_flux_2=None,
                     compression=None, change=0.0)


@pytest.mark.parametrize("rise", [None, 10.0])  # the isothermal Ree-Eyring loop, the thermal loop
def test_a_bounded_film_step_limits_the_change_of_ln_eta_star(rise):
    """An update 10 e-folds below a Newtonian film (S1 of the face gear case under Barus: 11.4 at the first update)
    moves ln(eta*/eta) by the relaxed step unbounded and by at most film_step bounded."""
    shape = (3, 4, 5)
    temperature, factor = np.full(shape, 313.15), np.ones(shape)
    update = _update(np.full(shape, math.exp(-10.0)))
    relaxation = TUNING.eyring_relaxation if rise is None else TUNING.viscosity_relaxation
    free = coupled.next_film_state(Anderson(3), temperature, factor, update, 1.0, rise)[1]
    assert np.log(free) == pytest.approx(np.full(shape, -10.0 * relaxation))
    bounded = coupled.next_film_state(Anderson(3), temperature, factor, update, 1.0, rise, 2.0)[1]
    assert np.log(bounded) == pytest.approx(np.full(shape, -2.0))
