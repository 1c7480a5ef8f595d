"""A film that alternates node to node along an axis: a mode of the discrete problem, not a solution.

A smooth film varies on the scale of its features (the Hertzian width, the outlet constriction, the side lobes): its
second difference along an axis, d_j = h_(j+1) - 2 h_j + h_(j-1), keeps its sign over several nodes. A film whose
rows (or columns) sit alternately high and low has d_j changing sign at every node, |d_j| = 4 A h for an alternating
component A h. On a narrow ellipse's grid the rows are long cells (y spacing tens of x spacings) that the Reynolds
equation couples weakly across y; a coupled thermal iteration that stalls can settle with its rows alternating between
two states. Its central film is then that of whichever row the centre falls on: the a/b = 100, 1.5 GPa, 2 m/s, SRR 0.5
contact on 129 x 65 "converged" at its loop's floor with h_c 0.263 um against the 0.415 um of its smooth solution
(rows alternating by 18 % over 16 rows), and the error bounds' check that found it made h_c look unresolved.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from facegear_tehl.ehl.tuning import TUNING


@dataclass(frozen=True)
class GridMode:
    """The longest alternating run of a film: along `axis` ("x" or "y"), over `nodes` consecutive second differences,
    the smallest alternating component among them `amplitude` (share of the film)."""

    axis: str
    nodes: int
    amplitude: float

    def message(self, nx: int, ny: int) -> str:
        """Why the solve is not reported converged."""
        rows = "rows" if self.axis == "y" else "columns"
        return (f"the film's {rows} alternate node to node along {self.axis} over {self.nodes} nodes by "
                f"{100.0 * self.amplitude:.2g} % or more on the {nx} x {ny} grid: a mode of the discrete problem, "
                "not a smooth solution")


def alternating_run(film: np.ndarray, wet: np.ndarray) -> tuple[int, float]:
    """Along axis 0 of `film` (any positive film, `wet` where the pressure carries load): the longest run of
    consecutive nodes whose second differences alternate in sign with an alternating component |d|/(4 h) of at least
    grid_mode_amplitude, all within `wet`, and the smallest component of the longest such run (0 without one)."""
    if film.shape[0] < 3:
        return 0, 0.0
    d = film[2:] - 2.0 * film[1:-1] + film[:-2]
    share = np.abs(d) / (4.0 * np.abs(film[1:-1]))
    inside = wet[2:] & wet[1:-1] & wet[:-2]
    strong = inside & (share >= TUNING.grid_mode_amplitude)
    run = np.zeros(film.shape[1:], dtype=int)
    smallest = np.full(film.shape[1:], np.inf)
    longest, amplitude = 0, 0.0
    for j in range(d.shape[0]):
        goes_on = strong[j] & (d[j] * d[j - 1] < 0.0) if j > 0 else np.zeros_like(strong[j])
        run = np.where(goes_on, run + 1, np.where(strong[j], 1, 0))
        smallest = np.where(goes_on, np.minimum(smallest, share[j]), np.where(strong[j], share[j], np.inf))
        best = int(run.max())
        if best > longest:
            longest = best
            amplitude = float(smallest[np.argmax(run)])
    return longest, amplitude


def grid_mode(film: np.ndarray, pressure: np.ndarray) -> GridMode | None:
    """The alternating run of the film (ny, nx) where the pressure passes grid_mode_wet of its peak, along y or x,
    if it spans grid_mode_nodes nodes or more (the longer of the two); None for a smooth film."""
    wet = pressure > TUNING.grid_mode_wet * float(pressure.max())
    found = []
    for axis, along in (("y", 0), ("x", 1)):
        nodes, amplitude = alternating_run(np.moveaxis(film, along, 0), np.moveaxis(wet, along, 0))
        if nodes >= TUNING.grid_mode_nodes:
            found.append(GridMode(axis, nodes, amplitude))
    return max(found, key=lambda mode: mode.nodes, default=None)
