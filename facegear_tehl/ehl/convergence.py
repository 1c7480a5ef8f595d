"""The one convergence monitor of the point solve: its history and every test of stall, floor and divergence.

The pressure iteration (pressure.py) and the coupled outer loops (coupled.py, the uniform grid's and the outlet
patches') record into one `History` and judge it with the predicates below; their bands and windows are TUNING's.
- a *flicker stall*: the pressure change per cycle fell by less than 1 - floor_stall over two cycles (a period-2
  flicker of the nodes at the spike and on the cavitation boundary);
- the *algebraic floor*: a flicker stall below floor_band times the tolerance with the load balanced;
- a *window stall*: over thermal_floor_window iterations the change stopped falling;
- the *thermal floor*: a window stall below a bound with h_c steady.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math

import numpy as np

from facegear_tehl.ehl.multigrid import Level
from facegear_tehl.ehl.richardson import ORDER, richardson_error
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.settings import SolverSettings


@dataclass
class History:
    """Bookkeeping of the finest-grid iteration: per cycle, per outer iteration, and the floors reached."""

    cycles: int
    changes: list[float] = field(default_factory=list)  # relative L1 pressure change per cycle (NaN: start)
    residuals: list[float] = field(default_factory=list)  # mean |Reynolds residual| over pressurised nodes
    loads: list[float] = field(default_factory=list)  # relative load error per cycle
    films: list[tuple[float, float, float]] = field(default_factory=list)  # per cycle: nodes along x, H_c, H_min
    floor: float = math.nan  # pressure change at an accepted algebraic floor
    thermal_floor: float = math.nan  # K, temperature change at an accepted thermal floor
    viscosity_floor: float = math.nan  # change of ln(eta*/eta) at an accepted floor of an isothermal Ree-Eyring film
    outer: int = 0  # outer iterations of film state and pressure (all grids)
    thermal_changes: list[float] = field(default_factory=list)  # K, largest layer-temperature change per update
    viscosity_changes: list[float] = field(default_factory=list)  # largest change of ln(eta*/eta) per update
    thermal_h_c: list[float] = field(default_factory=list)  # m, central film per outer iteration


def finite(level: Level) -> bool:
    """Pressure, film and flow coefficient of `level` are all finite."""
    return bool(np.isfinite(level.pressure).all() and np.isfinite(level.film).all() and np.isfinite(level.eps).all())


def running_away(load_error: float) -> bool:
    """A relative load error beyond TUNING.diverged_load_error: the iteration is running away."""
    return abs(load_error) > TUNING.diverged_load_error


def balanced(loads: list[float], settings: SolverSettings, band: float = 1.0) -> bool:
    """The load error averaged over the last two cycles is within `band` times the tolerance."""
    return len(loads) >= 2 and abs(0.5 * (loads[-1] + loads[-2])) < band * settings.load_tolerance


def flicker_stalled(changes: list[float]) -> bool:
    """The last change per cycle fell by less than 1 - floor_stall against the one two cycles before."""
    return len(changes) >= 3 and changes[-1] > TUNING.floor_stall * changes[-3]


def runs_one_way(window: np.ndarray) -> bool:
    """Over the contraction_window + 1 changes `window` the figure moves one way (their sum is more than half their
    absolute sum, which averages drift_floor or more per change) and the changes do not contract (rate above
    max_contraction)."""
    if window.size <= TUNING.contraction_window or window[0] == 0.0:
        return False
    one_way = abs(window.sum()) > 0.5 * np.abs(window).sum() and np.abs(window).mean() > TUNING.drift_floor
    return bool(one_way and abs(window[-1] / window[0]) ** (1.0 / (window.size - 1)) > TUNING.max_contraction)


def drifting(changes: np.ndarray) -> bool:
    """The figure `runs_one_way` over its last contraction_window + 1 changes or over the contraction_window + 1
    before its last contraction_window: no rate read from them bounds where it goes (a flicker straddling the fixed
    point alternates in sign instead; below drift_floor the film wanders at the iteration's floor). A rate read just
    after a drift is no bound either: the 1025^2 film of ab1_ph2.5_u0.5_eta0.01_iso rose 3-6 % per cycle over ten
    cycles, then 2.7, 2.8, 1.5 and 0.7 % (a rate of 0.58) at 35.0 nm, 28 % below its fixed point."""
    n, last = TUNING.contraction_window, changes.size
    return any(runs_one_way(changes[max(end - n - 1, 0):end]) for end in (last, last - n) if end > n)


def call_drifting(films: list[tuple[float, float, float]], cycles: int) -> bool:
    """The central film of the last `cycles` V-cycles on one frozen film state (History.films) is `drifting`."""
    h_c = np.array([film[1] for film in films[-cycles:]]) if cycles > TUNING.contraction_window + 1 else np.empty(0)
    return h_c.size > 0 and h_c[-1] != 0.0 and drifting(np.diff(h_c) / abs(h_c[-1]))


def at_algebraic_floor(changes: list[float], loads: list[float], settings: SolverSettings) -> bool:
    """The pressure iteration has reached its algebraic floor: a flicker stall below floor_band times the tolerance
    (after at least five cycles) with the load balanced to its tolerance; h_c and h_min are then steady to ~1e-5."""
    return (len(changes) >= 5 and flicker_stalled(changes) and changes[-1] < TUNING.floor_band * settings.tolerance
            and balanced(loads, settings))


def pressure_settled(history: History, settings: SolverSettings, load_band: float = 1.0) -> bool:
    """Between film-state updates the pressure stays within its algebraic floor: the last four changes per cycle
    below floor_band times the tolerance, the load error of the last two within `load_band` times its tolerance."""
    changes = history.changes[-4:]
    return (len(changes) == 4 and max(changes) < TUNING.floor_band * settings.tolerance
            and balanced(history.loads, settings, load_band))


def stalled(changes: list[float]) -> bool:
    """Over the last thermal_floor_window iterations the change stopped falling: the smallest change of the window's
    last half is above thermal_floor_stall times the smallest of its first half."""
    n = TUNING.thermal_floor_window
    if len(changes) < n:
        return False
    recent = changes[-n:]
    return min(recent[n // 2:]) > TUNING.thermal_floor_stall * min(recent[:n // 2])


def h_c_steady(h_c: list[float], h_c_error: float = 0.0) -> bool:
    """The values `h_c` span at most thermal_floor_h_c of the last one (relative), or thermal_floor_error_share of
    h_c's estimated discretisation error `h_c_error` (relative), if larger."""
    spread = max(TUNING.thermal_floor_h_c, TUNING.thermal_floor_error_share * h_c_error)
    return len(h_c) > 0 and (max(h_c) - min(h_c)) <= spread * abs(h_c[-1])


def at_thermal_floor(changes: list[float], h_c: list[float], bound: float, h_c_error: float = 0.0) -> bool:
    """An outer loop's algebraic floor: a window stall of its changes, all below `bound` (thermal: a share of the
    rise, K; Ree-Eyring: floor_band times the tolerance on ln(eta*/eta)), with h_c steady over the window
    (h_c_steady). What is left is a period-2 flicker of a few nodes where a layer velocity changes sign between
    iterations (the upwind direction of the energy equation switches)."""
    n = TUNING.thermal_floor_window
    return stalled(changes) and max(changes[-n:]) < bound and h_c_steady(h_c[-n:], h_c_error)


def h_c_error(h_c: float, coarse_h_c: float) -> float:
    """|Richardson estimate| of the relative error of h_c (m) from h_c one grid coarser (m); 0 without it."""
    return abs(richardson_error(h_c, coarse_h_c, ORDER)) if math.isfinite(coarse_h_c) and h_c != 0.0 else 0.0
