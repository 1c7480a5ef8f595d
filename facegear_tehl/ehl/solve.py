"""Solve one elliptical EHL contact: ContactPoint + Lubricant + SolverSettings -> PointSolution (SI).

Full multigrid (Venner & Lubrecht 2000) for the isothermal Newtonian film: the coarsest grid starts from the
Hertz pressure with H_0 set so that the central film equals the Hamrock & Dowson (1977) estimate; each finer
grid starts from the bicubic interpolation of the coarser solution and gets `cycles_per_level` V-cycles;
the finest grid then cycles until the pressure change per cycle is below `tolerance` and the load error
below `load_tolerance` (or `max_cycles` is spent: reported as not converged).

Thermal and/or Ree-Eyring films (thermal.py) then iterate an outer loop (an isothermal Ree-Eyring film from the
full-multigrid start itself, without the cycles to tolerance): the across-film state (temperature
and eta*/eta per layer) is updated from the current pressure and film, frozen into the flow coefficients of
every grid (flow.py), and the pressure is cycled again; the loop stops when temperature, pressure and load
have all converged. From 129^2 up a thermal solve is a thermal full multigrid in two stages: the coupled
problem one grid coarser (`PointSolve.begin`, which returns the picklable solve itself), then the finest grid
from its interpolated state (`PointSolve.finish`); `solve_point` composes them, parallel.solve_all may run
them in different workers (through `STAGED`). The discretisation error is estimated from the solution one
grid coarser (isothermal, or the coarse thermal stage), Richardson-scaled for a second-order scheme:
e = (H_h - H_2h)/(2^2 - 1).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from enum import Enum
import itertools
import math
import time

import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import grid, rheology
from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.domain import (
    MAX_INLET_DOUBLINGS,
    RETRY_INLET_DOUBLINGS,
    predicted_central_film,
    solution_domain,
    venner_lubrecht_domain,
)
from facegear_tehl.ehl.multigrid import Iterate, Level, MultigridSolver, Problem, Relaxation, at_load_fraction
from facegear_tehl.ehl.outlet import Composite, needs_outlet_patch, outlet_stages
from facegear_tehl.ehl.report import LevelSummary, point_solution, summarise, with_film_state
from facegear_tehl.ehl.richardson import ORDER, richardson_error
from facegear_tehl.ehl.scaling import Scaling, scaling_for
from facegear_tehl.ehl.thermal import MAX_TEMPERATURE_STEP, FilmState, FilmThermalModel, relaxed_steps, thermal_choice
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import CONVERGED, Outcome, PointSolution, Status

DIVERGED_LOAD_ERROR = 0.5  # a relative load error above this after a full cycle means the iteration is running away
EYRING_LAYERS = 9  # layers for an isothermal Ree-Eyring film (as the thermal default: Simpson on 9 nodes, layers.py)
CYCLES_PER_THERMAL_UPDATE = 2  # V-cycles on the pressure between two updates of the film state
# Under-relaxation of the outer loop: the film state responds to the pressure with a lag of one update, and
# the full step overshoots where the viscosity falls steeply with temperature (a period-2 oscillation of the
# hot spot); 0.7 on the temperatures and 0.4 on ln(eta*/eta) (the stiffer of the two: eta* falls by orders of
# magnitude over a few MPa of shear stress) converged every face gear point and thermal hard case tried.
THERMAL_RELAXATION = 0.7
VISCOSITY_RELAXATION = 0.4
# An isothermal Ree-Eyring film (no energy equation: its state is eta*/eta alone, and an update costs a quarter of a
# V-cycle on 513 x 65) takes a longer step on ln(eta*/eta) and one V-cycle per update: S1 of the default case (513 x
# 65) took 20 outer iterations and 42 V-cycles with 0.4 and two cycles, 15 and 24 with 0.6 and one (0.8 and one: 18
# and 27; 0.6 and two: 18 and 38); h_c and h_min within 3e-4 of their values. With the Anderson depth below, the
# 41-point cycle of the default case (513 x 65 per point) took 612 outer iterations at 0.6 and depth 3, 576 at 0.8
# and 3, 549 at 0.8 and 5 (546 at 0.8 and 8, 557 at 1.0 and 5, 597 at 0.8 and 2), the variants' h_c and h_min within
# 0.16 and 0.6 of their error estimates of one another (docs/benchmarks.md).
EYRING_RELAXATION = 0.8
CYCLES_PER_EYRING_UPDATE = 1
EYRING_ANDERSON_DEPTH = 5
# V-cycles of the full-multigrid start on the finest grid of an isothermal Ree-Eyring film (the coarser grids keep
# cycles_per_level): its outer loop follows at once and its eta*/eta updates move the pressure more than a second
# Newtonian cycle converges it. The 41-point cycle: work units 4432 -> 4237, outer iterations 549 -> 554, 35.3 -> 33.8
# s CPU (side by side), h_c and h_min within 0.27 and 0.46 of their error estimates; the Ree-Eyring hard cases with
# thermal: off 107 -> 103 outer iterations, h_min and p_max as before.
EYRING_START_CYCLES = 1
# The accelerated temperatures move by at most the temperature continuation's step (thermal.MAX_TEMPERATURE_STEP) per
# update, as the plain update does. While a hot film's updates are all held at that limit, their steps (35 K, relaxed)
# barely change and the accelerator's secant extrapolates them: the envelope's heated a/b = 30, 1.5 GPa, 10 m/s, SRR 2
# contact jumped 200-290 K in one update (plain steps 35 K) and ran away on its 129 x 65 coarse stage at attempts 3 and
# 4; whether its last attempt's 257 x 65 loop then converged depended on round-off (with one BLAS thread it did, with
# two it did not). Limited, it converged at attempt 3 either way, 5.9 -> 2.5 s. Anderson's columns are the iterates
# taken, so the next secant sees the limited step. A loop whose accelerated steps stay below the limit (S1-S5 of the
# default case) is unchanged, bit for bit.
ACCELERATED_STEP_LIMIT = MAX_TEMPERATURE_STEP
# Anderson acceleration of the outer loop (anderson.py): the film-state map contracts by ~0.6 per update on the face
# gear points even with the pressure frozen (the shear state follows the temperature), so the relaxed loop needs
# 7-9 updates per grid at S1. Depth 3 took S1 (257 x 65) from 24 to 20 outer iterations; 5 and 10 were no better.
ANDERSON_DEPTH = 3
# The columns of an isothermal Ree-Eyring film whose Newtonian wall stresses stay below r_N tau_0 take the Newtonian
# state, eta*/eta = 1 (rheology.shear_state): ln(r/sinh r) >= -r^2/6 for every r, so their viscosity is off by at
# most r_N^2/6, set to this share of the loop's tolerance on ln(eta*/eta) (`eyring_tolerance`): r_N = sqrt(6 share
# tolerance) = 7.7e-3 at the default 1e-3. In the inlet of the lengthened domain the film is Newtonian to that bound:
# at P01, P20 and P41 of the default case's 41-point cycle (513 x 65) 81, 87 and 78 % of the columns, whose largest
# |ln(eta*/eta)| solved in full was 9.88e-6 (the bound: 9.9e-6).
EYRING_NEWTONIAN_SHARE = 0.01
# Energy-equation sweeps per update (thermal.py: at least ENERGY_MIN_SWEEPS, at most ENERGY_SWEEPS) until a sweep
# changes the temperatures by less than this share of the last outer change: an inexact inner solve whose
# tolerance follows the outer loop's. With a fixed 2 sweeps the heavy face gear S2 (cases/hard, 129^2) and S3 of
# the default case were left in a flicker of 0.15-1.4 K, neither converged nor at the thermal floor; 0.1 converged
# both (60 and 25 outer iterations; 0.03 took S2 of the default case 44 instead of 27). On the lengthened 513 x 65
# grids 0.3 took S1-S5 of the default case 261 energy sweeps (counted in sweeps of the finest grid) instead of 388
# for 99 outer iterations instead of 92 (S3, S4 40 % fewer sweeps; S1, S5 2-3 more iterations), 8 % less CPU, and
# the thermal hard cases the same outer iterations.
ENERGY_FORCING = 0.3
# ... that share while the loop's changes do not fall, less as they fall (`energy_forcing`): once the sweeps solved only
# the columns next to one that moved (energy.ACTIVE_SHARE) a tighter share cost little near the fixed point, and a
# sweep's change under-reports the error of the slow modes it leaves (the inlet's recirculation, the side rows: with
# the pressure frozen, 8 sweeps per update contract the film state by 0.83 per update, 16 by 0.68, 32 by 0.5;
# docs/benchmarks.md). A fixed share took S1-S5 of the default case 138 / 121 / 114 / 119 outer iterations at
# 0.3 / 0.1 / 0.15 / 0.2 (0.05: 117, at more CPU than 0.1), but at 0.15 and 0.12 (and 0.2) the envelope's heated
# a/b = 30, 1.5 GPa, 10 m/s, SRR 2 contact (rises of 150-390 K, every step at the temperature continuation's limit)
# ran away on its last attempt, which converges at 0.3: the tight share is for the loop's approach to its fixed
# point, not for its transient. With the ratio squared (Eisenstat & Walker's alpha = 2) between 0.1 and 0.3,
# S1-S5 took 117 outer iterations and that contact converges.
ENERGY_FORCING_EXPONENT = 2.0
MIN_ENERGY_FORCING = 0.1
# V-cycles of the `full` finest grid on the interpolated film state before its outer loop: the film state changes
# next, so converging the pressure first (6 cycles at S1) was wasted; 2 saved 4 cycles at S1 with the same outer
# iterations. (The isothermal pressure before the coarse stage's loop keeps its max_cycles: with 4 cycles the
# envelope's thermal a/b = 30, 1.5 GPa, SRR 2 point ran away in its first outer iteration.)
FINE_START_CYCLES = CYCLES_PER_THERMAL_UPDATE
MIN_COARSE_THERMAL_GRID = 65  # the coupled problem is solved one grid coarser first only from this grid up
# Coarse-stage fallback: a damped attempt (DAMPED_ATTEMPT on) whose coarse thermal stage runs away solves the coupled
# problem on the finest grid alone, from the converged isothermal solution there (PointSolve._couple_on_finest). The
# thermal a/b = 30 ellipse at 1.5 GPa, 0.5 m/s, SRR 0.5 (Moes M = 5.4e4, L = 7.9) has an isothermal film that 513^2
# resolves and 257^2 does not: on 513^2 its damped attempts ran away in the coarse stage on 257^2 (the isothermal
# cycles there, then the first film-state update not finite); on 513^2 alone the damped attempt converges the
# isothermal film and then the coupled loop in 14 outer iterations. Only from the damped attempt on: the attempts
# before it are where the points that converge today do so, unchanged.
# The coarse stage of `full` seeds the finest grid's outer loop, where the film state moves by its grid error (the
# first update on 513 x 65 changes the temperatures by 2.9 % of the rise at S1 of the default case, by 60 % of it at
# S3 in the outlet's expansion cooling), and its dT_max and mu are the coarse values of the finest grid's error
# estimates (report.py): its iteration error must stay small against their grid difference. It stops at this
# multiple of the thermal tolerance, and never looser than COARSE_STAGE_LIMIT of the rise, which a looser thermal
# tolerance does not change (5e-3 of the rise at the default 2e-3). At 1e-2 of the rise, S1's coarse mu was 0.36 % off
# its converged value, seven times the difference the estimate is formed from: the estimate read 4.9e-4 (7.7e-5 at a
# thermal tolerance of 2e-3) against 4.2e-3 for a converged reference (the same solve at 3e-5). At 5e-3 every
# estimate of h_c, h_min, dT_max and mu at S1-S5 is within 15 % of the reference's, for 121 instead of 120 outer
# iterations at a thermal tolerance of 1e-3 (at 3e-3 of the rise: 130; docs/benchmarks.md). (`reduced` keeps its
# coarse stage's tolerance: its coarse temperatures are its result.)
COARSE_STAGE_TOLERANCE = 5.0
COARSE_STAGE_LIMIT = 5e-3
# The coarse stage's own seed (`full`, from 129 nodes in x two grids below the finest): the coupled problem two grids
# below the finest, to SEED_STAGE_LIMIT of the rise, interpolated to the coarse stage's grid (_seed_stage). The coarse
# stage's first updates are the temperature continuation's transient (S1 of the default case from the inlet
# temperature: 35, 31, 18, 12, 7 K on 257 x 65, 9 updates to its 5e-3 of the rise); on 129 x 65 they cost half, as
# does the isothermal pressure cycled to tolerance before them, and from the seed (5 K off) the coarse stage took 5
# updates. S1-S5 of the default case: 16.2 -> 14.4 s CPU for 125 instead of 118 outer iterations (6 + 5 + 5 at S1),
# every figure within 0.45 of a converged reference's error estimates (S4's mu; elsewhere <= 0.26); at 1e-2 or 4e-2
# of the rise 14.2 and 14.6 s. From 65 nodes (the thermal envelope's 257 x 65 grids seeded on 65 x 65) its 33 points
# took 874 instead of 803 outer iterations, 125 instead of 121 s: on 65 x 65 the seed is too far from the coarse
# stage's film state to save it updates.
SEED_STAGE_LIMIT = 2e-2
MIN_SEED_STAGE_GRID = 129
# SEED_STOP: a coarse stage whose film state has settled within that tolerance (two updates) while its pressure cannot
# hold on its grid (max_cycles V-cycles on the settled state leave it unconverged, the change per cycle stalled: the
# smallest of the last four cycles above half the smallest of the four before, _stalled) stops there and seeds the
# finest grid: the pressure of the heavy envelope points stays on a 1e-3 limit cycle on 129 x 65 (a/b = 30, 2.5 GPa,
# 10 m/s, SRR 0.5: 0.6-3.2e-3 per cycle over all 40 cycles, load error -1e-3) and their coarse stages ran out all 40
# outer iterations, 22 of them after the state had settled, for the same seed (docs/benchmarks.md, coarse stage).

# Algebraic floor of the pressure iteration (a period-2 flicker at the spike and the free boundary):
FLOOR_STALL = 0.8  # the change per cycle fell by less than 20 % over two cycles ...
FLOOR_BAND = 10.0  # ... while below this multiple of the tolerance (h_c, h_min then steady to ~1e-5)
# A limit cycle of the V-cycle above that floor: the change per cycle stalls (FLOOR_STALL) between FLOOR_BAND and
# PHASE_MEAN_BAND times the tolerance; the pressure and H_0 are then replaced by the mean of the last two iterates
# (for a period-2 cycle the fixed point its phases straddle; in general a half step, which removes a mode whose
# iteration factor is near -1), at most MAX_PHASE_MEANS times per call of `cycle`. The fixed point, the discrete
# solution, is unchanged: convergence is still judged on an undamped cycle's change and load error. Two isothermal
# envelope contacts on their lengthened 1025 x 65 grids stalled at 1.1e-3 and 1.8e-3 per cycle, undamped and damped
# (a/b = 5, 0.3 GPa, 2 m/s: h_c alternating by 5.5e-4, more than its grid error of 4.6e-4; a/b = 100, 0.8 GPa,
# 0.5 m/s): one mean each and they converged 3-4 cycles later (h_c within 5e-5 of the solve that converges with
# three pre-sweeps). The hard case ellipse_2000 (R_y/R_x = 2000, 129^2) stalls at 8e-3: with 3 means at most it
# still did, with 10 it converged in 22 cycles. Only on a frozen film state: the three changes judged are of the
# same call (the outer loop's two cycles per update never qualify).
PHASE_MEAN_BAND = 100.0
MAX_PHASE_MEANS = 10
# The coarse-grid corrections of `cycle` skip the nodes next to cavitation (multigrid.corrected_nodes) from a stall of
# the pressure change below this multiple of the tolerance (the floor's band) on, for the rest of the solve: the floor
# above was mostly a period-2 flip of the cavitation boundary by the full correction (isothermal Newtonian S2 of the
# default case on 513 x 65: 5.5e-4 per cycle for ever; truncated, 1e-6 after 20 cycles). Not before: from the start
# the truncated correction ran away on the circle at M = 20, L = 10 on 513 x 33 (its pressurised zone 7 nodes wide
# across the spike), the hard case heavy_m5000_l20 no longer converged on 513^2 (its result fell back to 257^2, h_min
# 7.6 against 67 nm), and switched on at 1e-3 the envelope's a/b = 5, 1.5 GPa, 2 m/s contact ran away from 8.3e-4 per
# cycle, where the full correction kept falling to its tolerance. A truncation that lets the change leave the band on
# one film state is switched off for good, and within the call of `cycle` that switched it on its iterate is taken back
# to where it began (and ends there, if that was the algebraic floor, as without the trial: the circle on 513 x 33
# above, whose full correction also runs away when cycled on past its floor); a stall while it is on is taken as the
# floor only after TRUNCATION_TRIAL cycles.
TRUNCATION_BAND = 10.0
TRUNCATION_TRIAL = 4


class Truncation(Enum):
    """The truncated coarse-grid correction of a solve: not yet tried, on, or switched off after it failed."""

    OFF = "off"
    ON = "on"
    FAILED = "failed"


# Algebraic floor of the thermal outer loop (see _at_thermal_floor):
THERMAL_FLOOR_WINDOW = 8  # outer iterations over which a stalled thermal change is judged
THERMAL_FLOOR_STALL = 0.5  # stalled: the smallest change of the window's last half above this share of its first
THERMAL_FLOOR_FRACTION = 0.01  # largest stalled change accepted, as a fraction of the temperature rise
THERMAL_FLOOR_H_C = 5e-4  # largest relative spread of h_c over the window (its grid error: 1e-3 to 6e-3)
THERMAL_FLOOR_ERROR_SHARE = 0.5  # or this share of h_c's own error estimate, if larger
# The loop's tolerance stop (the last change of the film state below the tolerance, the pressure converged) also
# needs h_c steady (as the floor does) over this many updates: a change below tolerance says the film state moved
# little in the last update, not that h_c has settled. With tighter energy sweeps (energy_forcing) the square
# 513^2 S1 of the default case stopped on its 0.079 K tolerance while h_c went 1.20656 ... 1.20419 ... 1.20482 um
# over its last updates, 6.8e-4 below the value it settles at. Three updates were still too few for it: after a
# round-off-level change (rheology's thinning formed without tanh) its h_c swung 1.2067 ... 1.2042 ... 1.2051 um with
# a period of about eight updates and the loop stopped at 1.20467, 1.20497, 1.20512 (spread 3.7e-4 < 5e-4), 4.2e-4
# below the 1.20555 of Venner's switch. Over five the swing shows (7.9e-4); that attempt then ran away and the next
# converged to 1.20555. The default case's S1-S5 kept their outer iterations but S5's (15 instead of 14).
STEADY_UPDATES = 5
# An outer loop whose change stopped falling above its floor bound (a limit cycle of the hot spot, e.g. 3 K per
# iteration on a 136 K rise for an a/b = 30 ellipse at 0.8 GPa, 10 m/s, SRR 0.5 on 257 x 65), or that stalled below
# it without reaching its floor (h_c unsteady or the pressure unsettled: S3 of the default case on its lengthened
# 513 x 65 grid alternated h_c by 0.12 % between iterations, twice the floor's allowance, for 24 iterations), halves
# its under-relaxation, down to
# MIN_RELAXATION_SCALE of the values above, and is judged again on a fresh window.
MIN_RELAXATION_SCALE = 0.125
# The relaxation of each attempt at a solve that runs away (StagedSolver): the defaults; then Venner's switch as
# is, with an escalating start; then that with the Gauss-Seidel / Jacobi-distributive changes damped to half
# (0.3 -> 0.15, 0.15 -> 0.1): at Moes M ~ 1e4 the full-multigrid start runs away from every coarsest grid
# undamped and converges damped (a/b = 5, p_h = 1.5 GPa, 0.5 m/s, M = 8.5e3, L = 7.9), as does the thermal
# a/b = 30, 1.5 GPa, 10 m/s, SRR 0.5 point of the envelope suite, which runs away on its finest grid undamped.
# Damping is the last resort: it slows the convergence of the points the second attempt converges (two of the
# default face gear's points on 65 x 17 then end their thermal loops unconverged). A solve that ends short of its
# tolerances in a limit cycle is tried once more, damped (needs_retry): an a/b = 5 ellipse at 0.3 GPa, 2 m/s
# (Moes M ~ 20) stalls at a pressure change of 1.1e-3 per cycle and converges damped in a quarter of the time; an
# a/b = 30 ellipse at 0.8 GPa, 0.5 m/s stalls at 1.6e-2 with h_c 18 % low (0.173 against 0.212 µm) and converges
# damped (envelope suite).
# A retry whose film closes in a limit cycle is treated as a stall (next_attempt). A heavily loaded point (Moes M above
# CONTINUATION_MOES_M) whose damped attempt runs away or closes its film, or whose retry closes its film in a converged
# iteration, is tried a fourth time, damped, from a start at a fraction of its load (PointSolve._full_multigrid): the
# thermal a/b = 100 ellipse at 2.5 GPa, 10 m/s, SRR 0.5 (M = 8.9e4) ran away on every grid up to 513 x 129 and
# converges so there; the circle at 2.5 GPa, 0.5 m/s, eta_0 = 0.01 Pa s (M = 1.5e4) on 1025^2. It comes last: an
# a/b = 30 ellipse at 1.5 GPa, 0.5 m/s (M = 5.4e4) converges damped from a 65^2 coarsest grid on 513^2 and stalls in
# a 2e-2 limit cycle from the continued start.
DAMPED = Relaxation(scale_switch=False, under_gs=0.15, under_jd=0.1)
ATTEMPTS = (  # what the attempt is called, its relaxation, whether its start begins at a fraction of the load
    ("the ellipse-scaled switch", Relaxation(), False),
    ("Venner's switch", Relaxation(scale_switch=False), False),
    ("Venner's switch, damped", DAMPED, False),
    ("Venner's switch, damped, from a fraction of the load", DAMPED, True),
)
# numpy's floating-point warnings inside a solve: an iterate that runs away overflows (inf - inf in the FAS
# right-hand side of a long ellipse's start at 15 m/s on 129 x 33) before the solver's own finiteness checks stop the
# attempt, report it and retry (StagedSolver); the warning would only repeat that on the user's terminal.
RUN_AWAY_ARITHMETIC = {"over": "ignore", "invalid": "ignore", "divide": "ignore"}
DAMPED_ATTEMPT = 3  # the first attempt (1-based) with the damped relaxation
FILM_CLOSED_MESSAGE = "the film closes (h_min <= 0: solid contact, outside the EHL model)"
MIN_RISE = 1.0  # K: tolerances relative to the temperature rise use at least this rise (near-isothermal films)
# Load continuation of the last retry's start (PointSolve._full_multigrid): above Moes M = CONTINUATION_MOES_M the
# coarse grids cannot carry the film of the full load (on 17^2 the discrete deflection of the Hertz pressure alone
# departs from the Hertz gap by 3-9 central films for a/b = 5-30 at 2.5 GPa, 0.5 m/s), and the start ran away or
# closed the film on every grid up to 1025^2 (a/b = 5, 2.5 GPa, 0.5 m/s, M = 4.0e4). The start then solves the
# contact at CONTINUATION_MOES_M / M of its load, where the full-multigrid start from 17^2 converges with an open
# film (a/b = 5, M = 1000), and raises the load on the level below the finest by LOAD_STEP per step with
# CYCLES_PER_LOAD_STEP V-cycles each: a step of 2 ran away at once there, 1.25 with 3 cycles reached the full load.
CONTINUATION_MOES_M = 1000.0
LOAD_STEP = 1.25
CYCLES_PER_LOAD_STEP = 3
# H = h R_x/b^2 of the central film against the load at fixed radii: h_c ~ W^-0.067 (Hamrock & Dowson 1977) and
# b ~ W^(1/3) (Hertz): each load step moves H_0 by the central film's predicted change.
FILM_LOAD_EXPONENT = -0.067 - 2.0 / 3.0


@dataclass
class History:
    """Bookkeeping of the finest-grid iteration: per cycle, per outer iteration, and the floors reached."""

    cycles: int
    changes: list[float] = field(default_factory=list)  # relative L1 pressure change per cycle (NaN: start)
    residuals: list[float] = field(default_factory=list)  # mean |Reynolds residual| over pressurised nodes
    loads: list[float] = field(default_factory=list)  # relative load error per cycle
    floor: float = math.nan  # pressure change at an accepted algebraic floor
    thermal_floor: float = math.nan  # K, temperature change at an accepted thermal floor
    viscosity_floor: float = math.nan  # change of ln(eta*/eta) at an accepted floor of an isothermal Ree-Eyring film
    outer: int = 0  # outer iterations of film state and pressure (all grids)
    thermal_changes: list[float] = field(default_factory=list)  # K, largest layer-temperature change per update
    viscosity_changes: list[float] = field(default_factory=list)  # largest change of ln(eta*/eta) per update
    # (an isothermal Ree-Eyring film, whose state is eta*/eta alone)
    thermal_h_c: list[float] = field(default_factory=list)  # m, central film per outer iteration


@dataclass
class _Best:
    """The best iterate of a finest-grid iteration (smallest pressure change + |load error|)."""

    score: float
    iterate: Iterate


def problem_for(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings, scaling: Scaling) -> Problem:
    """The dimensionless problem of a point on the settings' domain (Venner & Lubrecht's when not set; a solve
    lengthens its inlet first, domain.solution_domain)."""
    domain_x, domain_y = settings.domain_x, settings.domain_y
    if domain_x is None or domain_y is None:
        domain_x, domain_y = venner_lubrecht_domain(scaling)
    return Problem(
        lam=scaling.lam,
        deflection_coefficient=scaling.deflection_coefficient,
        ellipticity=scaling.ellipticity,
        geometry_y=scaling.geometry_y,
        wedge_x=scaling.wedge_x,
        wedge_y=scaling.wedge_y,
        p_hertz=scaling.p_h,
        law=lubricant.law_parameters(),
        inlet_temperature=lubricant.inlet_temperature,
        velocity_1=np.asarray(point.velocity_1) / point.entrainment_speed,
        velocity_2=np.asarray(point.velocity_2) / point.entrainment_speed,
        domain_x=domain_x,
        domain_y=domain_y,
    )


def _finite(level: Level) -> bool:
    return bool(np.isfinite(level.pressure).all() and np.isfinite(level.film).all() and np.isfinite(level.eps).all())


def _balanced(loads: list[float], settings: SolverSettings, band: float = 1.0) -> bool:
    """The load error averaged over the last two cycles is within `band` times the tolerance."""
    return len(loads) >= 2 and abs(0.5 * (loads[-1] + loads[-2])) < band * settings.load_tolerance


def _at_algebraic_floor(changes: list[float], loads: list[float], settings: SolverSettings) -> bool:
    """The iteration has reached its algebraic floor: the pressure change per cycle stopped falling
    (by less than 20 % over two cycles) below 10x the tolerance, and the load error averaged over the last
    two cycles is within tolerance. The floor is a period-2 flicker of the nodes at the pressure spike and on
    the cavitation boundary (a few 1e-4 of the pressure); h_c and h_min are then steady to about 1e-5.
    """
    if len(changes) < 5:
        return False
    stalled = changes[-1] > FLOOR_STALL * changes[-3]
    small = changes[-1] < FLOOR_BAND * settings.tolerance
    return stalled and small and _balanced(loads, settings)


def _pressure_settled(history: History, settings: SolverSettings, load_band: float = 1.0) -> bool:
    """Between film-state updates the pressure stays within its algebraic floor (_at_algebraic_floor's bound:
    the last four changes per cycle below 10x the tolerance, the load error of the last two cycles within
    `load_band` times its tolerance), though two cycles per update are too few to see it stall."""
    changes = history.changes[-4:]
    return (len(changes) == 4 and max(changes) < FLOOR_BAND * settings.tolerance
            and _balanced(history.loads, settings, load_band))


def _at_thermal_floor(changes: list[float], h_c: list[float], bound: float, h_c_error: float = 0.0) -> bool:
    """The outer loop has reached its algebraic floor: over the last THERMAL_FLOOR_WINDOW outer iterations
    (of this grid) the change of the film state stopped falling (the smallest change of the last half is
    above half the smallest of the first half), stays below `bound` (thermal: 1 % of the temperature rise, K;
    isothermal Ree-Eyring: FLOOR_BAND times the tolerance on ln(eta*/eta)), and h_c is steady
    to 5e-4 or to half its estimated discretisation error `h_c_error` (relative), if larger (the error is
    1e-3 to 6e-3 on 129^2-257^2). What is left is a period-2 flicker of a few nodes where a layer velocity
    changes sign between iterations (the upwind direction of the energy equation switches; under-relaxing the
    temperature only scales it): e.g. the heaviest face gear point of cases/hard, 0.43 K at the inlet edge with
    a 98 K rise.
    """
    n = THERMAL_FLOOR_WINDOW
    if not _stalled(changes):
        return False
    return max(changes[-n:]) < bound and _h_c_steady(h_c[-n:], h_c_error)


def _h_c_steady(h_c: list[float], h_c_error: float = 0.0) -> bool:
    """The values of h_c `h_c` span at most THERMAL_FLOOR_H_C of the last one (relative), or
    THERMAL_FLOOR_ERROR_SHARE of its estimated discretisation error `h_c_error` (relative), if larger."""
    spread = max(THERMAL_FLOOR_H_C, THERMAL_FLOOR_ERROR_SHARE * h_c_error)
    return len(h_c) > 0 and (max(h_c) - min(h_c)) <= spread * abs(h_c[-1])


def _stalled(changes: list[float]) -> bool:
    """Over the last THERMAL_FLOOR_WINDOW outer iterations (or V-cycles, for the pressure's change per cycle) the
    change stopped falling: the smallest change of the window's last half is above THERMAL_FLOOR_STALL times the
    smallest of its first half."""
    n = THERMAL_FLOOR_WINDOW
    if len(changes) < n:
        return False
    recent = changes[-n:]
    return min(recent[n // 2:]) > THERMAL_FLOOR_STALL * min(recent[:n // 2])


def _at_load(summary: LevelSummary, fraction: float) -> LevelSummary:
    """A level summary solved at `fraction` of the load in the full load's Hertzian units: H = h R_x/b^2 and
    P = p/p_h with b^2 and p_h scaling as f^(2/3) and f^(1/3) (multigrid.at_load_fraction)."""
    if fraction == 1.0:
        return summary
    return replace(summary, h_c=summary.h_c * fraction ** (2.0 / 3.0), h_min=summary.h_min * fraction ** (2.0 / 3.0),
                   p_max=summary.p_max * fraction ** (1.0 / 3.0))


def _h_c_error(h_c: float, coarse_h_c: float) -> float:
    """|Richardson estimate| of the relative error of h_c (m) from h_c one grid coarser (m); 0 without it."""
    return abs(richardson_error(h_c, coarse_h_c, ORDER)) if math.isfinite(coarse_h_c) and h_c != 0.0 else 0.0


def _next_film_state(accelerator: Anderson, temperature: np.ndarray, factor: np.ndarray, update: FilmState,
                     scale: float, rise: float | None) -> tuple[np.ndarray, np.ndarray, float, float]:
    """The next layer temperatures (K) and eta*/eta of the outer loop from the current ones and the film state
    `update` evaluated at them, and the largest changes of the plain step (K; of ln(eta*/eta)). The plain step
    is under-relaxed (THERMAL_RELAXATION and VISCOSITY_RELAXATION times `scale`, EYRING_RELAXATION without the
    energy equation; eta*/eta in log space) and
    Anderson-accelerated (anderson.py), the temperatures weighted by 1/rise (K) against ln(eta*/eta): the outer
    loop's tolerances, a share of the rise and a change of ln(eta*/eta), weigh alike; the accelerated temperatures
    move by at most the update's own MAX_TEMPERATURE_STEP (`ACCELERATED_STEP_LIMIT`). rise None: no energy
    equation (the temperatures stay)."""
    if rise is None:  # the change judged stays VISCOSITY_RELAXATION times the residual: the tolerance keeps its meaning
        log_factor, residual = np.empty(factor.shape), np.empty(factor.shape)
        largest = rheology.log_factor_change(factor, update.viscosity_factor, log_factor, residual)
        step_f = residual * (scale * EYRING_RELAXATION)
        return (temperature, np.exp(accelerator.step(log_factor, step_f)), 0.0,
                scale * VISCOSITY_RELAXATION * largest)
    size = temperature.size
    x, f = np.empty(2 * size), np.empty(2 * size)
    np.log(factor.ravel(), out=x[size:])
    np.log(update.viscosity_factor.ravel(), out=f[size:])
    thermal_change, viscosity_change = relaxed_steps(temperature, update.temperature, scale * THERMAL_RELAXATION,
                                                     scale * VISCOSITY_RELAXATION, x, f)
    x = accelerator.step(x, f, (1.0 / rise, 1.0))
    accelerated = x[:size].reshape(temperature.shape)
    np.clip(accelerated, temperature - ACCELERATED_STEP_LIMIT, temperature + ACCELERATED_STEP_LIMIT, out=accelerated)
    return accelerated, np.exp(x[size:]).reshape(temperature.shape), thermal_change, viscosity_change


def energy_forcing(changes: list[float]) -> float:
    """The share of an outer loop's last change its next update's energy sweeps stop below (ENERGY_FORCING): the
    forcing term of Eisenstat & Walker's (1996, SIAM J. Sci. Comput. 17:16-32) choice 2, ENERGY_FORCING (c_k/c_k-1)^
    ENERGY_FORCING_EXPONENT over the loop's last two changes `changes` (K), within [MIN_ENERGY_FORCING,
    ENERGY_FORCING]: loose while the loop is far from its fixed point, tighter as it converges."""
    if len(changes) < 2 or not changes[-2] > 0.0:
        return ENERGY_FORCING
    ratio = min(changes[-1] / changes[-2], 1.0)
    return max(ENERGY_FORCING * ratio**ENERGY_FORCING_EXPONENT, MIN_ENERGY_FORCING)


class PointSolve:
    """One contact point's solve: its inputs, the multigrid solver, the thermal model chosen and why, and the
    bookkeeping every step adds to (level summaries, history). `begin` runs the solve up to the end of its
    coarse thermal stage and returns itself (picklable) when a fine stage follows, else the solution;
    `finish` runs the fine stage."""

    def __init__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
                 relaxation: Relaxation = Relaxation(), elapsed: float = 0.0, escalate_start: bool = False,
                 attempt: int = 1, max_doublings: int = MAX_INLET_DOUBLINGS, load_continuation: bool = False):
        """`elapsed`: s already spent on this point (earlier attempts that ran away), counted in its wall time;
        `escalate_start`: a start that runs away begins again from a finer coarsest grid (start());
        `attempt`: which attempt at the point this is (1: the first); `max_doublings`: of the inlet (domain.py);
        `load_continuation`: above Moes M = CONTINUATION_MOES_M the start begins at a fraction of the load."""
        self.scaling = scaling_for(point, lubricant)
        self.domain = solution_domain(self.scaling, settings, max_doublings)
        self.point, self.lubricant, self.asked = point, lubricant, settings
        self.settings = settings = self.domain.settings(settings)  # the domain and nodes solved on
        shapes = grid.hierarchy_shapes(settings.grid, settings.nodes_y, settings.coarsest_grid)
        self.solver = MultigridSolver(problem_for(point, lubricant, settings, self.scaling), shapes, relaxation)
        self.mode, self.reason = thermal_choice(settings.thermal, point, lubricant)
        self.summaries: list[LevelSummary] = []
        self.history = History(cycles=settings.cycles_per_level)
        self.coarse_state: FilmState | None = None  # the film state of the coarse thermal stage
        self.coarsest = settings.coarsest_grid  # nodes of the coarsest grid's shorter side (start())
        self.start_notes: list[str] = []  # starts that ran away, from the coarsest grid they began on
        self.escalate_start = escalate_start
        # the load fraction the full-multigrid start begins at (_full_multigrid)
        self.start_load_fraction = min(1.0, CONTINUATION_MOES_M / self.scaling.moes_m) if load_continuation else 1.0
        self.attempt = attempt
        self.coarse_stage_note = ""  # why the coupled problem was solved on the finest grid alone (_couple_on_finest)
        self.outlet: Composite | None = None  # the outlet stage's composite solution (outlet.py), when it ran
        self.outlet_note = ""  # why the outlet stage was not reported (it ran away or did not converge)
        self.before_cycle: tuple[Iterate, np.ndarray] | None = None  # the iterate and film before the last V-cycle
        self.truncation = Truncation.OFF  # the truncated coarse-grid correction (TRUNCATION_BAND)
        self.truncated_since = 0  # cycles in the history when it was switched on
        # the iterate it was switched on at, its change if that was the algebraic floor (else NaN), the call of `cycle`
        self.before_truncation: tuple[Iterate, float, int] | None = None
        self.cycle_calls = 0  # calls of `cycle` so far
        self.elapsed = elapsed  # s spent up to the last pause (a solve paused between stages has no clock)
        self._clock = time.perf_counter() - elapsed

    @property
    def coupled(self) -> bool:
        """The film state is iterated with the pressure (thermal, or an isothermal Ree-Eyring film)."""
        return self.mode != "off" or self.lubricant.rheology == "ree_eyring"

    # ------------------------------------------------------------------ stages
    def begin(self) -> PointSolution | PointSolve:
        """The solve up to the end of its coarse thermal stage (self, to be finished), or the whole solve when
        it has no separate fine stage or the coarse stage failed."""
        top = len(self.solver.levels) - 1
        if self.mode != "off" and top > 0 and self.solver.levels[top - 1].nx >= MIN_COARSE_THERMAL_GRID:
            return self._coarse_thermal_stage()
        return self._solve_finest()

    def finish(self) -> PointSolution:
        """The fine stage of a thermal full-multigrid solve: the coarse solution and film state interpolated
        and frozen on the finest grid, its pressure converged; `reduced` evaluates the film state once there,
        `full` couples again on the finest grid. A finest grid that runs away reports the converged coarse
        solution."""
        self._clock = time.perf_counter() - self.elapsed
        solver, top = self.solver, len(self.solver.levels) - 1
        coarse = solver.levels[top - 1]
        # the coarse level, now with its film state (its dT_max and mu give the fine grid's error estimates)
        self.summaries[-1] = with_film_state(summarise(coarse), coarse, self.coarse_state, self.scaling,
                                             self.point.load, self.lubricant.inlet_temperature)
        saved = solver.snapshot(top - 1)
        frozen, status = self._start_fine_grid(top)
        if status.diverged:
            solver.restore(top - 1, saved)
            solver.set_film_state(top - 1, self.coarse_state.temperature, self.coarse_state.viscosity_factor)
            message = f"finest grid: {status.message}; the result is the {coarse.nx}^2 solution"
            return self.report(top - 1, Status(Outcome.DIVERGED, message), self.coarse_state)
        if self.mode == "reduced":
            fine = solver.levels[top]
            state = self._film_model(fine).update(fine.pressure * self.scaling.p_h,
                                                  fine.film * self.scaling.film_scale, frozen.temperature)
        else:
            state, status = self.couple(top, frozen, self.summaries[-1].h_c)
        self.summaries.append(summarise(solver.levels[top]))
        if self.mode == "full" and status.converged and needs_outlet_patch(self, top, state):
            self.outlet, self.outlet_note = outlet_stages(self, top, state)
        return self.report(top, status, state)

    def _coarse_thermal_stage(self) -> PointSolution | PointSolve:
        """Thermal full multigrid, first stage: the coupled problem one grid coarser than the finest (`reduced`
        stops after the fine stage's single film-state evaluation, `full` couples again there). The isothermal
        pressure is cycled first; its tolerance is not required, the coupled loop goes on from where it got. `full`
        from a seed stage two grids below the finest (MIN_SEED_STAGE_GRID) starts from that stage's state instead."""
        levels = self.solver.levels
        seeded = self.mode == "full" and len(levels) >= 3 and levels[-3].nx >= MIN_SEED_STAGE_GRID
        seed = self._seed_stage() if seeded else None
        if seed is None:
            index, status = self.start(below_top=1)
            if status.converged:
                self.cycle(index, self.settings.max_cycles)
        else:
            index, status = len(self.solver.levels) - 2, CONVERGED
        state = None
        if status.converged:
            state, status = self.couple(index, seed, math.nan if seed is None else self.summaries[-1].h_c)
            if seed is not None:  # this level's summary, after the seed stage's (the full-multigrid start's are below)
                self.summaries.append(summarise(self.solver.levels[index]))
            if state is not None and not status.diverged:
                self.coarse_state = state
                self.elapsed = time.perf_counter() - self._clock
                return self
            if self.attempt >= DAMPED_ATTEMPT:
                return self._couple_on_finest(status)
        return self.report(index, status, state)

    def _seed_stage(self) -> FilmState | None:
        """The coupled problem two grids below the finest to SEED_STAGE_LIMIT of the rise, its solution and film
        state interpolated to the next grid and cycled FINE_START_CYCLES times there; returns the frozen state there,
        or None (the solver begun again from the coarsest grid) when the stage ran away."""
        reached, status = self.start(below_top=2)
        index = len(self.solver.levels) - 3  # (a start that began again from a finer coarsest grid has fewer levels)
        if status.converged and reached == index:
            self.cycle(index, self.settings.max_cycles)
            state, status = self.couple(index)
            if state is not None and not status.diverged:
                self.summaries[-1] = summarise(self.solver.levels[index])
                frozen, status = self._interpolated_state(index + 1, state, FINE_START_CYCLES)
                if not status.diverged:
                    return frozen
        self._new_hierarchy(grid.hierarchy_shapes(self.settings.grid, self.settings.nodes_y, self.coarsest))
        return None

    def _couple_on_finest(self, status: Status) -> PointSolution:
        """After the coarse thermal stage ran away with `status`, the coupled problem on the finest grid alone, from
        its converged isothermal solution (`_solve_finest` on a new hierarchy with the same coarsest grid): the grid
        below the finest may not hold a film the finest resolves (the coarse-stage fallback above ATTEMPTS)."""
        level = self.solver.levels[-2]
        self.coarse_stage_note = (f"the coupled problem one grid coarser ({level.nx} x {level.ny}) ran away "
                                  f"({status.message}): coupled on the finest grid from its isothermal solution")
        self._new_hierarchy(grid.hierarchy_shapes(self.settings.grid, self.settings.nodes_y, self.coarsest))
        return self._solve_finest()

    def _solve_finest(self) -> PointSolution:
        """Full multigrid to the finest grid, cycles to tolerance there, then (thermal or Ree-Eyring films) the
        outer loop there. An isothermal Newtonian solve that does not converge reports its best iterate."""
        index, status = self.start(below_top=0)
        best = None if self.coupled else _Best(math.inf, self.solver.snapshot(index))
        state = None
        if status.converged:
            # An isothermal Ree-Eyring film's loop starts from the full-multigrid start, not from the Newtonian pressure
            # cycled to tolerance: its own V-cycles converge the pressure while eta*/eta moves it. Nine points of the
            # default case's 41-point cycle: 206 -> 144 V-cycles, 127 -> 126 outer iterations, 20.5 -> 16.7 s CPU (1 or
            # 2 Newtonian cycles first: 127 and 137 outer iterations); h_c, h_min within 0.08, 0.24 of their estimates.
            if self.mode != "off" or not self.coupled:
                status = self.cycle(index, self.settings.max_cycles, best)
            if self.coupled and not status.diverged:
                state, status = self.couple(index)
        if best is not None and not status.converged:
            self.solver.restore(index, best.iterate)  # the best iterate, not the last (it may be running away)
        return self.report(index, status, state)

    # ------------------------------------------------------------------- steps
    def start(self, below_top: int) -> tuple[int, Status]:
        """Full multigrid from the Hertz start up to `below_top` levels below the finest. With `escalate_start`
        (the retry of a solve that ran away), a start that runs away is begun again from a coarsest grid twice as
        fine (a heavy load's film and pressure spike are not
        resolved by coarse grids: an a/b = 34 ellipse at p_h = 1.5 GPa, Moes M = 1.4e4, ran away from 17^2 and
        33^2 and converged from 65^2 in 9 cycles), as long as the hierarchy keeps the levels asked for. Returns
        the finest level that stayed sound (a level that runs away is undone) and the status."""
        while True:
            index, status = self._full_multigrid(len(self.solver.levels) - 1 - below_top)
            finer = 2 * self.coarsest - 1
            shapes = grid.hierarchy_shapes(self.settings.grid, self.settings.nodes_y, finer)
            if (not (status.diverged and self.escalate_start) or finer > min(self.settings.grid, self.settings.nodes_y)
                    or len(shapes) <= below_top):
                return index, status
            self._restart(shapes, status)

    def _restart(self, shapes: list[tuple[int, int]], status: Status) -> None:
        """A new hierarchy (coarsest grid first in `shapes`) after the start ran away with `status`; the work
        done so far is kept in the count."""
        self._new_hierarchy(shapes)
        self.start_notes.append(f"{self.coarsest} x {self.coarsest}: {status.message}")
        self.coarsest = shapes[0][0] if shapes[0][0] <= shapes[0][1] else shapes[0][1]

    def _new_hierarchy(self, shapes: list[tuple[int, int]]) -> None:
        """A new multigrid solver on `shapes` (coarsest first), summaries and history begun again; the work done so
        far is kept in the count."""
        work = self.solver.work_units
        self.solver = MultigridSolver(self.solver.problem, shapes, self.solver.relaxation)
        self.solver.work_units = work
        self.summaries = []
        self.history = History(cycles=self.settings.cycles_per_level)

    def _full_multigrid(self, last: int) -> tuple[int, Status]:
        """Full multigrid from the Hertz start on the coarsest grid up to level `last`; appends a summary per
        level. With a `start_load_fraction` below 1 the levels up to the one below `last` are solved at that
        fraction of the load, whose load is then raised to the full load there (_raise_load: a grid four times
        cheaper than `last`, and a level summary at the full load for the error estimates), and `last` is
        interpolated from it. Returns the finest level that stayed sound (a level that runs away is undone) and
        the status."""
        solver, settings = self.solver, self.settings
        problem, fraction = solver.problem, self.start_load_fraction
        ramp = max(last - 1, 0) if fraction < 1.0 else last  # the level whose load is raised
        solver.problem = at_load_fraction(problem, fraction)
        index = 0
        try:
            solver.start_from_hertz(self._central_film_estimate() * fraction ** FILM_LOAD_EXPONENT)
            for _ in range(settings.cycles_per_level):
                solver.cycle(0)
            self.summaries.append(_at_load(summarise(solver.levels[0]), fraction))
            index, status = self._climb(1, ramp, fraction)
            if status.converged and fraction < 1.0:
                status = self._raise_load(index, problem, fraction)
                if status.converged:
                    self.summaries[-1] = summarise(solver.levels[index])
                    index, status = self._climb(index + 1, last, 1.0)
        finally:
            solver.problem = problem
            solver.update_film(solver.levels[index])
        return index, status

    def _climb(self, first: int, last: int, fraction: float) -> tuple[int, Status]:
        """Full-multigrid steps from level `first - 1` (solved) up to level `last` at `fraction` of the load (the
        solver's problem); returns the finest sound level and the status."""
        solver, settings = self.solver, self.settings
        saved = solver.snapshot(first - 1)
        for index in range(first, last + 1):
            solver.interpolate_up(index)
            # the finest grid of an isothermal Ree-Eyring film: one cycle (EYRING_START_CYCLES)
            eyring_top = index == len(solver.levels) - 1 and self.mode == "off" and self.coupled
            for _ in range(EYRING_START_CYCLES if eyring_top else settings.cycles_per_level):
                solver.cycle(index)
            level = solver.levels[index]
            runaway = abs(solver.force_error(level)) > DIVERGED_LOAD_ERROR * solver.problem.load_integral
            if not _finite(level) or runaway:
                solver.restore(index - 1, saved)
                message = f"diverged during the full-multigrid start on the {level.nx} x {level.ny} grid"
                return index - 1, Status(Outcome.DIVERGED, message)
            saved = solver.snapshot(index)
            self.summaries.append(_at_load(summarise(level), fraction))
        return max(last, first - 1), CONVERGED

    def _raise_load(self, index: int, problem: Problem, fraction: float) -> Status:
        """Raise the load of level `index` from `fraction` to the full load of `problem` by LOAD_STEP per step,
        H_0 moved by the predicted change of the central film (FILM_LOAD_EXPONENT), CYCLES_PER_LOAD_STEP
        V-cycles per step. A step that runs away restores the last sound load's iterate and reports it."""
        solver = self.solver
        level = solver.levels[index]
        while fraction < 1.0:
            saved, previous = solver.snapshot(index), fraction
            fraction = min(LOAD_STEP * fraction, 1.0)
            h_c = solver.central_film(level)
            solver.problem = at_load_fraction(problem, fraction)
            solver.h0 += h_c * ((fraction / previous) ** FILM_LOAD_EXPONENT - 1.0)
            solver.update_film(level)
            for _ in range(CYCLES_PER_LOAD_STEP):
                solver.cycle(index)
            runaway = abs(solver.force_error(level)) > DIVERGED_LOAD_ERROR * solver.problem.load_integral
            if not _finite(level) or runaway:
                solver.problem = at_load_fraction(problem, previous)
                solver.restore(index, saved)
                return Status(Outcome.DIVERGED, f"diverged raising the load of the full-multigrid start from "
                                                f"{previous:.3g} to {fraction:.3g} on the {level.nx} x {level.ny} grid")
        return CONVERGED

    def _central_film_estimate(self) -> float:
        """The Hamrock & Dowson (1977) central film, dimensionless."""
        return predicted_central_film(self.scaling) / self.scaling.film_scale

    def cycle(self, index: int, max_cycles: int, best: _Best | None = None) -> Status:
        """V-cycles on level `index` until the tolerances are met (or the algebraic floor is reached), at most
        `max_cycles`; a period-2 limit cycle above the floor is replaced by the mean of its phases
        (PHASE_MEAN_BAND). `best` (if given) keeps the best iterate for reporting a solve that does not converge."""
        solver, settings, history = self.solver, self.settings, self.history
        level = solver.levels[index]
        load_integral = solver.problem.load_integral
        previous = level.pressure.copy()
        self.cycle_calls += 1
        means = 0  # period-2 cycles replaced by the mean of their phases (PHASE_MEAN_BAND)
        for extra in itertools.count():
            change = solver.pressure_change(level, previous)
            load_error = solver.force_error(level) / load_integral
            residual = solver.residual(level)
            positive = level.pressure > 0.0
            if extra > 0 or not history.changes:
                history.changes.append(change if extra > 0 else math.nan)
                history.residuals.append(float(np.abs(residual[positive]).mean()) if positive.any() else 0.0)
                history.loads.append(load_error)
            if abs(load_error) > DIVERGED_LOAD_ERROR:
                return Status(Outcome.DIVERGED,
                              f"diverged at cycle {history.cycles} on the finest grid (load error {load_error:.2e})")
            if best is not None:
                score = (change if extra > 0 else 1.0) + abs(load_error)
                if score < best.score:
                    best.score, best.iterate = score, solver.snapshot(index)
            if extra > 0 and change < settings.tolerance and abs(load_error) < settings.load_tolerance:
                return CONVERGED
            if extra > 0 and self._update_truncation(index, settings, extra):
                return CONVERGED  # a failed truncation taken back to the floor it began at
            if extra > 0 and _at_algebraic_floor(history.changes, history.loads, settings) and not self._on_trial():
                history.floor = change
                return CONVERGED
            if extra == max_cycles:
                return Status(Outcome.NOT_CONVERGED, (
                    f"not converged after {history.cycles} cycles on the finest grid: pressure change {change:.2e} "
                    f"(tolerance {settings.tolerance:.0e}), load error {load_error:.2e} "
                    f"(tolerance {settings.load_tolerance:.0e})"))
            if (extra >= 3 and means < MAX_PHASE_MEANS and self.before_cycle is not None
                    and FLOOR_BAND * settings.tolerance <= change < PHASE_MEAN_BAND * settings.tolerance
                    and change > FLOOR_STALL * history.changes[-3]):
                self._restore_mean(index)
                means += 1
            previous = level.pressure.copy()
            self.before_cycle = (Iterate(previous, solver.h0), level.film.copy())
            solver.truncated = self.truncation is Truncation.ON
            try:
                solver.cycle(index)
            finally:
                solver.truncated = False
            history.cycles += 1
            if not _finite(level):
                return Status(Outcome.DIVERGED,
                              f"diverged at cycle {history.cycles} on the finest grid (non-finite pressure or film)")

    def _update_truncation(self, index: int, settings: SolverSettings, extra: int) -> bool:
        """Switch the truncated coarse-grid correction (TRUNCATION_BAND) on at a stall of the pressure change below
        the band (the last change above FLOOR_STALL times the one two cycles before); switch it off for good once the
        change leaves the band on one film state (`extra`: the cycle of this call of `cycle`; its first follows a
        film-state update in the outer loops) and, within the call that switched it on, take level `index` back to
        the iterate it was switched on at. Returns True when that iterate was at the algebraic floor
        (_at_algebraic_floor), which is then where the iteration ends, as it would have without the trial."""
        history = self.history
        changes = history.changes
        band = TRUNCATION_BAND * settings.tolerance
        same_call = self.before_truncation is not None and self.before_truncation[2] == self.cycle_calls
        if self.truncation is Truncation.OFF and len(changes) >= 3 and band > changes[-1] > FLOOR_STALL * changes[-3]:
            self.truncation, self.truncated_since = Truncation.ON, len(changes)
            floor = changes[-1] if _at_algebraic_floor(changes, history.loads, settings) else math.nan
            self.before_truncation = (self.solver.snapshot(index), floor, self.cycle_calls)
        elif self.truncation is Truncation.ON and changes[-1] > band and (extra > 1 or same_call):
            self.truncation = Truncation.FAILED
            iterate, floor, _ = self.before_truncation
            self.before_truncation = None
            if same_call:
                self.solver.restore(index, iterate)
                self.before_cycle = None  # its phases are the trial's
                if math.isfinite(floor):
                    history.floor = floor
                    return True
        return False

    def _on_trial(self) -> bool:
        """The truncated correction was switched on less than TRUNCATION_TRIAL cycles ago: a stall is not yet a
        floor."""
        return self.truncation is Truncation.ON and len(self.history.changes) - self.truncated_since < TRUNCATION_TRIAL

    def couple(self, index: int, initial: FilmState | None = None,
               coarse_h_c: float = math.nan) -> tuple[FilmState | None, Status]:
        """Outer loop of the film state and the pressure on level `index`, from `initial` (default: the inlet
        temperature and a Newtonian film). If the iteration runs away, the last finite iterate (at worst the
        entry state) is restored and reported with the reason. coarse_h_c: the dimensionless h_c one grid
        coarser, for the discretisation error the thermal floor is judged against."""
        solver, settings, history, scaling = self.solver, self.settings, self.history, self.scaling
        level = solver.levels[index]
        model = self._film_model(level)
        temperature = model.initial_temperature() if initial is None else initial.temperature
        factor = np.ones_like(temperature) if initial is None else initial.viscosity_factor
        state = initial
        last_finite = (solver.snapshot(index), initial)
        first = len(history.thermal_h_c)  # this grid's outer iterations start here
        # the coarse stage of a `full` thermal multigrid only seeds the finest grid's loop (COARSE_STAGE_TOLERANCE);
        # `reduced` keeps its coarse temperatures, evaluated once on the finest grid
        seeding = self.mode == "full" and index < len(solver.levels) - 1
        window = first  # the stall of the current relaxation is judged from here
        relaxation = 1.0  # scale of THERMAL_RELAXATION and VISCOSITY_RELAXATION
        status = CONVERGED
        accelerator = Anderson(ANDERSON_DEPTH if model.solve_energy else EYRING_ANDERSON_DEPTH)
        last_change = None  # the largest change of the last plain step (K, or of ln(eta*/eta))
        own_changes: list[float] = []  # this loop's (energy_forcing)
        factors = None  # the temperature factors set_film_state evaluated for `temperature`, for its update
        cycled_out = False  # the pressure was cycled to its tolerance on a converged film state (below)
        # this loop's tolerance: on the temperatures (relative to the rise) or on ln(eta*/eta)
        loop_tolerance = settings.thermal_tolerance if model.solve_energy else settings.eyring_tolerance
        for outer in range(settings.max_thermal_iterations):
            forcing = energy_forcing(own_changes) * last_change if last_change is not None else math.inf
            pressure, film = self.settled_pressure(index)
            update = model.update(pressure * scaling.p_h, film * scaling.film_scale, temperature, forcing,
                                  wall_fluxes=False, temperature_factor=factors)
            rise = max(float(temperature.max() - self.lubricant.inlet_temperature), MIN_RISE)
            temperature, factor, thermal_change, viscosity_change = _next_film_state(
                accelerator, temperature, factor, update, relaxation, rise if model.solve_energy else None)
            last_change = thermal_change if model.solve_energy else viscosity_change
            own_changes.append(last_change)
            if not (np.isfinite(temperature).all() and np.isfinite(factor).all()):
                status = Status(Outcome.DIVERGED, f"diverged in the film temperature at outer iteration {outer + 1}")
                break
            state = replace(update, temperature=temperature, viscosity_factor=factor)
            solver.set_film_state(index, state.temperature, state.viscosity_factor)
            factors = level.temperature_factor
            status = self.cycle(index, CYCLES_PER_THERMAL_UPDATE if model.solve_energy else CYCLES_PER_EYRING_UPDATE)
            history.outer += 1
            if model.solve_energy:
                history.thermal_changes.append(thermal_change)
                changes = history.thermal_changes
            else:  # an isothermal Ree-Eyring film: its state is eta*/eta alone
                history.viscosity_changes.append(viscosity_change)
                changes = history.viscosity_changes
            if status.diverged:  # its film is not finite: no h_c is recorded
                break
            film = self.settled_pressure(index)[1]
            history.thermal_h_c.append(grid.bilinear_at(film, level.x, level.y, 0.0, 0.0) * scaling.film_scale)
            last_finite = (solver.snapshot(index), state)
            if model.solve_energy:
                tolerance, floor_bound = loop_tolerance * rise, THERMAL_FLOOR_FRACTION * rise
            else:
                tolerance, floor_bound = loop_tolerance, FLOOR_BAND * loop_tolerance
            if seeding and index == len(solver.levels) - 2:
                tolerance = min(COARSE_STAGE_TOLERANCE * tolerance, COARSE_STAGE_LIMIT * rise)
            elif seeding:  # the coarse stage's seed (_seed_stage)
                tolerance = max(SEED_STAGE_LIMIT * rise, tolerance)
            # a seeding stage (it needs no steady h_c) cycles its pressure to tolerance at its first film-state change
            # below tolerance and stops there: a few V-cycles instead of another update (its film state and two
            # V-cycles) and a pressure that two V-cycles converge only by chance (S1's seeded coarse stage: 5 updates
            # instead of 7)
            settled = changes[-1:] if seeding else changes[-2:]
            if outer > 0 and not status.converged and not cycled_out and max(settled) < tolerance:
                # the film state has converged and the pressure has not: a limit cycle of the V-cycle that two
                # cycles per update never leave (the phase mean of `cycle` needs three on one film state). On the
                # quick 65 x 17 grid a face gear point (a/b = 40, 0.2 GPa) alternated its load error between
                # -1.9e-4 and +2.2e-4 at a change of 1.43e-3 per cycle for 30 outer iterations, its temperatures
                # settled to 1e-4 K: the pressure is cycled to its tolerance on the converged state. Once per
                # grid: a pressure that max_cycles on a converged state left unconverged is not in that limit
                # cycle (the coarse stage's 129 x 65 grid of the envelope's thermal a/b = 30, 2.5 GPa, 10 m/s
                # point stays at 1e-3 per cycle and load error -1e-3; cycling it again at each of its last 23
                # outer iterations spent 920 V-cycles, 2.6x the solve's CPU, for the same seed).
                cycled_out = True
                status = self.cycle(index, settings.max_cycles)
                if status.diverged:
                    break
                if seeding and not status.converged and _stalled(history.changes):
                    # the seed is as good as this grid makes it (SEED_STOP)
                    return model.completed(state), Status(Outcome.NOT_CONVERGED, (
                        f"coarse stage stopped at outer iteration {outer + 1}: film state within {tolerance:.2e} of "
                        f"its last two updates, pressure stalled at {history.changes[-1]:.2e} per cycle"))
            coarse_error = _h_c_error(history.thermal_h_c[-1], coarse_h_c * scaling.film_scale)
            steady = seeding or (len(history.thermal_h_c) - first >= STEADY_UPDATES and _h_c_steady(
                history.thermal_h_c[-STEADY_UPDATES:], coarse_error))  # a seed needs no settled h_c
            if outer > 0 and status.converged and changes[-1] < tolerance and steady:
                self.settle(index)
                return model.completed(state), CONVERGED
            if ((status.converged or _pressure_settled(history, settings))
                    and _at_thermal_floor(changes[first:], history.thermal_h_c[first:], floor_bound, coarse_error)):
                if model.solve_energy:
                    history.thermal_floor = changes[-1]
                else:
                    history.viscosity_floor = changes[-1]
                self.settle(index)
                return model.completed(state), CONVERGED
            if _stalled(changes[window:]):  # a limit cycle above the floor (or with h_c unsteady): relax harder
                relaxation = max(0.5 * relaxation, MIN_RELAXATION_SCALE)
                window = len(changes)
                accelerator.reset()
        if status.diverged:
            return model.completed(self._last_finite(index, model, initial, *last_finite)), status
        what = ("thermal loop not converged after {} outer iterations: temperature change {:.2e} K (tolerance {:.0e} "
                "of the rise)" if model.solve_energy else
                "Ree-Eyring loop not converged after {} outer iterations: largest change of ln(eta*/eta) {:.2e} "
                "(tolerance {:.0e})")
        return model.completed(state), Status(Outcome.NOT_CONVERGED, (
            what.format(settings.max_thermal_iterations, changes[-1], loop_tolerance)
            + f", last pressure change {history.changes[-1]:.2e}"))

    def _flickering(self, index: int) -> bool:
        """The pressure of level `index` flickers: the last cycle's change fell by less than 20 % against the one
        two cycles before (_at_algebraic_floor's stall, without the load balance) and is below PHASE_MEAN_BAND times
        the tolerance (the band where `cycle` takes the mean of a limit cycle's phases). Up to 10x the tolerance
        this is the algebraic floor; above it a limit cycle that two V-cycles per film-state update never leave:
        S3 of a heavily loaded slow face gear (38/41/71 teeth, 0.82 m/s pure rolling, p_h 1.08 GPa, 257 x 129)
        flickered at 1.07e-3 per cycle and its thermal loop ended unconverged while the band stopped at 10x; with
        the mean of the phases it converged. The default case's S1-S5 moved by < 7e-4 in h_c, h_min, p_max,
        dT_max (their error estimates: 1e-3 to 1e-1) in 98 instead of 97 outer iterations."""
        changes, before = self.history.changes, self.before_cycle
        if len(changes) < 3 or before is None or before[1].shape != self.solver.levels[index].film.shape:
            return False
        return FLOOR_STALL * changes[-3] < changes[-1] < PHASE_MEAN_BAND * self.settings.tolerance

    def settled_pressure(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        """The pressure and film of level `index` (dimensionless) the film state is evaluated at: on a period-2
        flicker of the pressure (_flickering) the mean of its last two iterates, the fixed point the two phases
        straddle; else the last iterate. (On the lengthened 513 x 65 grid of S3 of the default face gear case the
        V-cycle's correction from 257 x 65 alternates the outlet pressure by 1.8e-3 p_h, isothermal too, which
        moves h_c by +-0.05 %; an outer loop fed one phase after the other never settled its temperatures.)"""
        level = self.solver.levels[index]
        if not self._flickering(index):
            return level.pressure, level.film
        iterate, film = self.before_cycle
        return 0.5 * (level.pressure + iterate.pressure), 0.5 * (level.film + film)

    def settle(self, index: int) -> None:
        """Leave level `index` on the mean of its last two iterates if its pressure flickers (settled_pressure):
        the result then does not depend on the phase the loop stops on."""
        if self._flickering(index):
            self._restore_mean(index)

    def _restore_mean(self, index: int) -> None:
        """Level `index` on the mean of its pressure and H_0 and those before the last V-cycle (`before_cycle`)."""
        iterate = self.before_cycle[0]
        self.solver.restore(index, Iterate(0.5 * (self.solver.levels[index].pressure + iterate.pressure),
                                           0.5 * (self.solver.h0 + iterate.h0)))

    def _last_finite(self, index: int, model: FilmThermalModel, initial: FilmState | None, iterate: Iterate,
                     state: FilmState | None) -> FilmState | None:
        """Restore the last finite iterate of the outer loop on level `index` with its film state; returns the
        state to report (an interpolated entry state evaluated on this grid)."""
        solver = self.solver
        solver.restore(index, iterate)
        if state is None:
            solver.set_film_state(index, None, None)
            return None
        solver.set_film_state(index, state.temperature, state.viscosity_factor)
        if state is initial:  # an interpolated state: evaluate it on this grid for the outputs
            level = solver.levels[index]
            return model.update(level.pressure * self.scaling.p_h, level.film * self.scaling.film_scale,
                                initial.temperature)
        return state

    def _start_fine_grid(self, index: int) -> tuple[FilmState, Status]:
        """Interpolate the coarse solution and film state to the finest grid, freeze the state on every grid and
        cycle the pressure against it: `full` FINE_START_CYCLES times (its outer loop goes on from there), else
        to convergence. Returns (frozen state, status)."""
        return self._interpolated_state(index, self.coarse_state,
                                        FINE_START_CYCLES if self.mode == "full" else self.settings.max_cycles)

    def _interpolated_state(self, index: int, coarse_state: FilmState, cycles: int) -> tuple[FilmState, Status]:
        """Level `index` from the solution one grid coarser, its film state `coarse_state` interpolated (ln(eta*/eta)
        bilinearly) and frozen on every grid, then `cycles` V-cycles on the pressure; returns (frozen state,
        status)."""
        solver = self.solver
        solver.interpolate_up(index)
        frozen = replace(coarse_state, temperature=solver.prolong_layers(index, coarse_state.temperature),
                         viscosity_factor=np.exp(solver.prolong_layers(index, np.log(coarse_state.viscosity_factor))))
        solver.set_film_state(index, frozen.temperature, frozen.viscosity_factor)
        return frozen, self.cycle(index, cycles)

    def _film_model(self, level: Level) -> FilmThermalModel:
        if self.mode != "off":
            return FilmThermalModel(level.x * self.scaling.b, level.y * self.scaling.a, self.settings.thermal_layers,
                                    self.lubricant, self.point, solve_energy=True)
        newtonian_below = math.sqrt(6.0 * EYRING_NEWTONIAN_SHARE * self.settings.eyring_tolerance)
        return FilmThermalModel(level.x * self.scaling.b, level.y * self.scaling.a, EYRING_LAYERS, self.lubricant,
                                self.point, solve_energy=False, newtonian_below=newtonian_below)

    # ------------------------------------------------------------------ report
    def report(self, index: int, status: Status, state: FilmState | None) -> PointSolution:
        """The PointSolution of level `index`; a film that closes (h_min <= 0) is never reported as converged."""
        level = self.solver.levels[index]
        if level.film.min() <= 0.0:
            message = FILM_CLOSED_MESSAGE
            message += "; " + status.message if status.message else ""
            status = Status(Outcome.DIVERGED if status.diverged else Outcome.FILM_CLOSED, message)
        return point_solution(self, level, status, state, time.perf_counter() - self._clock)

    def __getstate__(self) -> dict:
        """Between stages the solve travels to another process: its clock does not (see `elapsed`)."""
        return {k: v for k, v in self.__dict__.items() if k != "_clock"}


def _completed(begun: PointSolution | PointSolve) -> PointSolution:
    """A begun solve finished in this process."""
    return begun.finish() if isinstance(begun, PointSolve) else begun


@dataclass(frozen=True)
class StagedSolver:
    """The EHL solver as parallel.solve_all runs it: whole (`__call__`), or in stages that may run in
    different processes with the same result (`begin`, `finish`, `needs_retry`, `with_retry`).

    Convergence policy: a solve that runs away is repeated with the relaxation of the next of ATTEMPTS (the
    ellipse-scaled Gauss-Seidel / Jacobi switch first, then Venner's circle value, then that damped;
    multigrid.Level) and a start that begins again from a finer coarsest grid when it runs away
    (PointSolve.start); an undamped attempt that stalls short of its tolerances is repeated with the damped
    relaxation (needs_retry); a heavily loaded point whose film closed or whose damped attempt failed as well gets a
    last, damped attempt from a start at a fraction of its load (next_attempt). The retry is reported, and so is a
    retry that did not help.
    """

    def __call__(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
        first = solution = _completed(self.begin(point, lubricant, settings))
        while self.needs_retry(solution):
            solution = _completed(self.begin(point, lubricant, settings, solution))
        return first if solution is first else self.with_retry(first, solution)

    def begin(self, point: ContactPoint, lubricant: Lubricant, settings: SolverSettings,
              retry_after: PointSolution | None = None) -> PointSolution | PointSolve:
        """The first stage (PointSolve.begin). `retry_after`: the last attempt, which ran away: this one uses the
        next relaxation of ATTEMPTS and an escalating start, and its wall time counts the earlier attempts'."""
        if retry_after is None:
            solve = PointSolve(point, lubricant, settings)
        else:
            attempt = next_attempt(retry_after)
            _, relaxation, continued = ATTEMPTS[attempt - 1]
            solve = PointSolve(point, lubricant, settings, relaxation, elapsed=retry_after.scalar("wall_time"),
                               escalate_start=True, attempt=attempt, max_doublings=RETRY_INLET_DOUBLINGS,
                               load_continuation=continued)
        with np.errstate(**RUN_AWAY_ARITHMETIC):
            return solve.begin()

    def finish(self, stage: PointSolve) -> PointSolution:
        """The second stage (PointSolve.finish)."""
        with np.errstate(**RUN_AWAY_ARITHMETIC):
            return stage.finish()

    def needs_retry(self, solution: PointSolution) -> bool:
        """The attempt ran away and ATTEMPTS has another relaxation to try; or an undamped attempt stalled short of
        its tolerances (it goes straight to the damped relaxation: begin; should that run away after an earlier
        attempt ran away too, the first attempt is reported, with_retry). A thermal stall is often the pressure's:
        the thermal a/b = 100 ellipse at 0.8 GPa, 10 m/s, SRR 0.5 of the envelope suite ends its outer loop with the
        temperature change below tolerance (0.05 of 0.14 K) but the pressure on a 2e-3 period-2 flicker, and
        converges damped in a quarter of the time. A film that closed on an undamped attempt may be the relaxation's:
        an a/b = 5 ellipse at 2.5 GPa, 0.5 m/s (Moes M = 4.0e4) on 513^2 ends undamped in a 5e-3 limit cycle with its
        side lobes closed, and converges damped from a start at a fraction of its load with h_min = 65 nm."""
        return next_attempt(solution) is not None

    def with_retry(self, first: PointSolution, retry: PointSolution) -> PointSolution:
        """The last retry's solution, noted, if it did better than the first attempt (converged, or anything but
        running away after a first attempt that ran away); else the first attempt's (the wall time counts all
        attempts)."""
        better = (retry.outcome is Outcome.CONVERGED if first.outcome is Outcome.NOT_CONVERGED
                  else retry.outcome is not Outcome.DIVERGED)
        if not better:  # the first attempt's record, with the time and count of all, and what the retry did
            note = f"a retry with {ATTEMPTS[int(retry.scalar('attempts')) - 1][0]} ended {retry.outcome.value}"
            return replace(first, scalars={**first.scalars, "wall_time": retry.scalars["wall_time"],
                                           "attempts": retry.scalars["attempts"]},
                           models={**first.models, "solver": first.models.get("solver", "") + "; " + note})
        attempt = int(retry.scalar("attempts"))
        note = (f"{retry.outcome.value} at attempt {attempt} with {ATTEMPTS[attempt - 1][0]} and an escalating start "
                f"(first attempt: {first.message})")
        return replace(retry, models={**retry.models, "solver": retry.models["solver"] + "; " + note})


def next_attempt(solution: PointSolution) -> int | None:
    """The attempt (1-based, ATTEMPTS) after `solution`'s, or None: the next relaxation after one that ran away; the
    damped one after an undamped attempt's stall (a limit cycle), and after a retry's stall that closed the film (the
    a/b = 5 ellipse at 2.5 GPa, 0.5 m/s, Moes M = 4.0e4, on 513^2: its undamped retry closes the side lobes in a 6e-3
    limit cycle, the damped one converges with h_min = 66 nm); for a point above Moes M = CONTINUATION_MOES_M the
    start at a fraction of the load after a damped attempt that ran away or closed the film, or a retry whose film
    closed in a converged iteration. The first attempt's closed film is left to a finer grid (run.solve_refining):
    the thin film of cases/hard (M = 2.5e3) converges damped on 257^2 with h_min = 0.5 nm (its error estimate
    -41 %), and with 4.3 nm on the 513^2 grid the refinement gives it."""
    attempt = int(solution.scalar("attempts"))
    if solution.outcome is Outcome.DIVERGED:
        following = attempt + 1
    elif solution.outcome is Outcome.NOT_CONVERGED:  # a damped attempt's stall is reported as it is
        following = DAMPED_ATTEMPT
    elif solution.outcome is Outcome.FILM_CLOSED and attempt > 1:  # a retry's film closed: in a stall, as a stall
        stalled = solution.message != FILM_CLOSED_MESSAGE
        following = max(attempt + 1, DAMPED_ATTEMPT) if stalled else len(ATTEMPTS)
    else:
        return None
    if following <= attempt or following > len(ATTEMPTS):
        return None
    heavy = solution.scalar("moes_m") > CONTINUATION_MOES_M
    return following if heavy or not ATTEMPTS[following - 1][2] else None


STAGED = StagedSolver()


def solve_point(point: ContactPoint, lubricant: Lubricant, settings: SolverSettings) -> PointSolution:
    """Solve the EHL problem of one contact point (thermal model and rheology as the settings say), retrying a
    solve that runs away or stalls as StagedSolver says."""
    return STAGED(point, lubricant, settings)
