"""A film whose rows alternate node to node is a mode of the discrete problem, not a solution (ehl/grid_mode.py).

The smooth film is the shape of an elastic point contact in Venner & Lubrecht's units: flat over the Hertzian
ellipse at H_c, the outlet constriction a Gaussian dip of 25 % near X = 0.9, the rigid gap X^2/2 + Y^2/2 outside,
and the Hertzian pressure sqrt(1 - X^2 - Y^2) over it (Hamrock & Dowson 1977 describe that shape). A grid mode adds
an alternating share A (-1)^j to its rows (or columns) inside the contact: the reported h_c then depends on which row
the centre falls on."""

from __future__ import annotations

import numpy as np
import pytest

from facegear_tehl.ehl.grid_mode import alternating_run, grid_mode
from facegear_tehl.ehl.tuning import TUNING


def smooth_contact(nx: int = 129, ny: int = 65) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(X, Y, film, pressure) on X in [-4.5, 1.5], Y in [-3, 3], arrays (ny, nx)."""
    x, y = np.linspace(-4.5, 1.5, nx), np.linspace(-3.0, 3.0, ny)
    xx, yy = np.meshgrid(x, y)
    r2 = xx**2 + yy**2
    pressure = np.sqrt(np.clip(1.0 - r2, 0.0, None))
    h_c = 0.4
    film = h_c * (1.0 - 0.25 * np.exp(-((xx - 0.9) / 0.08) ** 2) * (r2 < 1.0)) + np.where(r2 > 1.0, (r2 - 1.0) / 2, 0)
    return xx, yy, film, pressure


def test_a_smooth_film_has_no_grid_mode_on_any_grid():
    for nx, ny in ((65, 33), (129, 65), (257, 65), (513, 129)):
        _, _, film, pressure = smooth_contact(nx, ny)
        assert grid_mode(film, pressure) is None


@pytest.mark.parametrize("share", [0.03, 0.2])
def test_rows_alternating_inside_the_contact_are_a_grid_mode_along_y(share):
    _, yy, film, pressure = smooth_contact()
    rows = np.arange(film.shape[0])[:, None]
    film = film * (1.0 + share * (-1.0) ** rows * (np.abs(yy) < 0.6))
    mode = grid_mode(film, pressure)
    assert mode is not None and mode.axis == "y"
    inside = int(np.count_nonzero(np.abs(yy[:, 0]) < 0.6))
    assert TUNING.grid_mode_nodes <= mode.nodes <= inside + 2  # the rows next to them see the alternation too
    assert mode.amplitude >= TUNING.grid_mode_amplitude
    assert "alternate node to node along y" in mode.message(129, 65)


def test_columns_alternating_are_a_grid_mode_along_x():
    xx, _, film, pressure = smooth_contact()
    columns = np.arange(film.shape[1])[None, :]
    film = film * (1.0 + 0.05 * (-1.0) ** columns * (np.abs(xx) < 0.5))
    mode = grid_mode(film, pressure)
    assert mode is not None and mode.axis == "x"


def test_a_weak_or_short_or_dry_alternation_is_not_a_grid_mode():
    _, yy, film, pressure = smooth_contact()
    rows = np.arange(film.shape[0])[:, None]
    alternating = (-1.0) ** rows
    weak = film * (1.0 + 0.3 * TUNING.grid_mode_amplitude * alternating * (np.abs(yy) < 0.6))
    short = film * (1.0 + 0.2 * alternating * (np.abs(yy) < 0.1))  # 3 rows: an outlet spike's width
    dry = film * (1.0 + 0.2 * alternating * (np.abs(yy) > 1.2))  # outside the loaded film
    for case in (weak, short, dry):
        assert grid_mode(case, pressure) is None


def test_the_run_counts_consecutive_alternating_nodes_only():
    line = np.array([1.0, 1.0, 1.0, 1.1, 1.0, 1.1, 1.0, 1.1, 1.0, 1.0, 1.0])[:, None]
    wet = np.ones_like(line, dtype=bool)
    nodes, amplitude = alternating_run(line, wet)
    assert nodes == 7  # second differences at nodes 2..8 alternate: +0.1, -0.2, +0.2, -0.2, +0.2, -0.2, +0.1
    assert amplitude == pytest.approx(0.1 / 4.0)  # the smallest, |d| / 4h at the run's ends (h = 1)
