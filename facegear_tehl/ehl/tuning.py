"""Every numerical constant of the point solve's driver, in one frozen object (`TUNING`).

Each field says what it controls and why it has this value in one line; the experiments that chose the values
(cases, grids, iteration counts, accuracy against converged references) are in docs/tuning.md, under the field's
name. Physical constants and the models' own parameters live with their physics, not here.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Tuning:
    """The solver's numerical constants (dimensionless unless a unit is given)."""

    # --- the solution domain (domain.py)
    domain_half_width: float = 3.0  # default domain: +-3 semi-axes (Venner & Lubrecht 2000) ...
    domain_upstream_shift: float = 1.5  # ... shifted 1.5 semi-axes upstream: 4.5 upstream, 1.5 downstream
    inlet_gap_target: float = 40.0  # inlet gap ratio the lengthened inlet must reach (h_c starved by 0.55-0.8 %)
    min_lengthened_nodes: int = 129  # nodes along an axis from which the inlet is lengthened (trial grids are not)
    max_inlet_doublings: int = 2  # doublings of the inlet at most (a light load needs two)
    retry_inlet_doublings: int = 1  # ... on a retry after a solve ran away (a long inlet can be the cause)
    max_lengthened_nodes: int = 2049  # nodes of a lengthened axis at most (its length then never depends on the grid)
    # --- full-multigrid start and load continuation
    diverged_load_error: float = 0.5  # |load error| after a full cycle beyond which the iteration is running away
    start_balance_error: float = 0.05  # |load error| a coarsest start running away is cycled down to (H_0 near root)
    start_balance_cycles: int = 100  # ... in at most this many V-cycles (of the coarsest grid: cheap)
    eyring_start_cycles: int = 1  # V-cycles of an isothermal Ree-Eyring film's finest start grid: its loop follows
    continuation_moes_m: float = 1000.0  # Moes M from which the last attempt starts at a fraction of the load
    load_step: float = 1.25  # the largest load factor of a continuation step (2 ran away at once)
    cycles_per_load_step: int = 12  # V-cycles a continuation step may take to its tolerance
    continuation_tolerance: float = 1e-3  # pressure change and load error a continuation step's V-cycles must reach
    semi_coarsest_columns: int = 33  # columns of the load-continued attempt's coarsest grid (17 ran w24's cycles away)
    row_coupling: float = 0.5  # ... whose rows are coarsened only where coupled at least this much as the columns
    min_load_step: float = 1.01  # a grid whose step factor falls below this does not carry a heavier load
    # --- the pressure iteration on a frozen film state
    floor_stall: float = 0.8  # stalled: the change per cycle fell by less than 20 % over two cycles ...
    floor_band: float = 10.0  # ... below this multiple of the tolerance: the algebraic floor (h_c steady to ~1e-5)
    phase_mean_band: float = 100.0  # a stall below this multiple of the tolerance takes the mean of its two phases
    max_phase_means: int = 10  # phase means per call of the pressure iteration (the 2000:1 ellipse needs ten)
    truncation_band: float = 10.0  # a stall below this multiple of the tolerance tries the truncated correction
    truncation_trial: int = 4  # cycles the truncated correction runs before a stall counts as the floor
    pressure_anderson_depth: int = 5  # Anderson columns on the V-cycle map P, H_0 -> V(P, H_0) (0: bare cycles)
    pressure_anderson_growth: float = 2.0  # ... its history is dropped when the cycle's step grew by this factor
    # --- the coupled (pressure-film state) outer loop
    cycles_per_thermal_update: int = 2  # V-cycles on the pressure between two updates of a thermal film state
    cycles_per_eyring_update: int = 1  # ... of an isothermal Ree-Eyring film's state (an update costs 1/4 cycle)
    thermal_relaxation: float = 0.7  # under-relaxation of the temperatures (the state lags the pressure by one update)
    viscosity_relaxation: float = 0.4  # ... of ln(eta*/eta), the stiffer of the two
    eyring_relaxation: float = 0.8  # ... of ln(eta*/eta) of an isothermal Ree-Eyring film (no energy equation)
    anderson_depth: int = 3  # Anderson columns of the thermal loop (5 and 10 were no better)
    eyring_anderson_depth: int = 5  # Anderson columns of an isothermal Ree-Eyring loop
    eyring_layers: int = 9  # layers of an isothermal Ree-Eyring film (Simpson on 9 nodes, as the thermal default)
    eyring_newtonian_share: float = 0.01  # share of eyring_tolerance a column taken as Newtonian may be off by
    energy_forcing: float = 0.3  # energy sweeps of an update stop below this share of the loop's last change ...
    energy_forcing_exponent: float = 2.0  # ... times (c_k / c_k-1)^this (Eisenstat & Walker 1996, choice 2) ...
    min_energy_forcing: float = 0.1  # ... but never below this share
    min_rise: float = 1.0  # K: tolerances relative to the temperature rise use at least this rise
    grid_mode_wet: float = 0.05  # share of the peak pressure from which a node lies in the loaded film (grid_mode.py)
    grid_mode_amplitude: float = 0.015  # alternating share of the film at each node of a grid mode (found: 2.8-18 %)
    grid_mode_nodes: int = 8  # consecutive alternating nodes of a grid mode (found: 17; smooth films: no 8 at 1.5 %)
    steady_updates: int = 5  # a loop stops on its tolerance only with h_c steady over this many updates
    thermal_floor_window: int = 8  # outer iterations (or cycles) over which a stall is judged
    thermal_floor_stall: float = 0.5  # stalled: the window's later half's smallest change above this share ...
    thermal_floor_fraction: float = 0.01  # largest stalled change of the temperatures accepted, share of the rise
    thermal_floor_h_c: float = 5e-4  # largest relative spread of h_c at a floor (its grid error: 1e-3 to 6e-3)
    thermal_floor_error_share: float = 0.5  # ... or this share of h_c's own error estimate, if larger
    min_relaxation_scale: float = 0.125  # a loop stalled above its floor halves its relaxation down to this scale
    cycle_damping: float = 0.5  # a stalled loop whose pressure does not converge on a frozen state damps its V-cycles
    min_under_gs: float = 0.075  # ... by this factor, while their Gauss-Seidel under-relaxation is above this
    # --- one update of the film state (thermal.py, energy.py, anderson.py, flow.py)
    max_temperature_step: float = 50.0  # K: largest temperature change of one update (a continuation in temperature)
    inner_iterations: int = 1  # surface and film-interior passes per update (the outer loop iterates them anyway)
    surface_relaxation: float = 0.6  # under-relaxation of the surface temperatures between inner passes
    energy_min_sweeps: int = 2  # column sweeps of the energy equation per pass at least ...
    energy_sweeps: int = 8  # ... and at most, until a sweep changes the temperatures by less than the tolerance ...
    energy_sweep_tolerance: float = 1e-3  # K: ... the caller gives, or this
    deferred_updates: int = 2  # updates whose deferred wall heat fluxes are kept (the last, and the one a loop
    # that runs away goes back to)
    central_peclet: float = 2.0  # cell Peclet number across the film up to which the face value is central (monotone)
    active_reach: int = 2  # after the first sweep a column is solved again when one within this many columns ...
    active_share: float = 0.1  # ... changed by more than this share of the sweeps' tolerance
    refreeze_spread: float = 0.1  # a column whose layers' ln(eta) moved apart by this is frozen again (error ~1e-4)
    gram_cutoff: float = 1e-10  # Anderson: relative cutoff of the normal equations' singular values
    anderson_growth: float = 1.0  # Anderson: the history is dropped when the weighted step grew by this factor
    support_share: float = 0.5  # Anderson: a support above this share of the components is taken whole
    auto_tolerance: float = 0.01  # `auto`: the cheapest model predicted within 1 % of `full` in h_c, h_min and mu
    auto_sliding_weight: float = 0.01  # `auto`: G = L_th + w Theta_s, the w whose envelope of `off` is tightest
    auto_off_coefficient: float = 4.64  # `auto`: error of `off` <= C G^n, the upper envelope of the errors ...
    auto_off_exponent: float = 1.042  # ... measured on suites/thermal_auto.py's contacts (scripts/thermal_auto_fit.py)
    auto_reduced_coefficient: float = 0.855  # `auto`: the same envelope of `reduced`'s errors ...
    auto_reduced_exponent: float = 0.847  # ... its exponent
    patch_coarse_cycles: int = 3  # grid-below V-cycles per coarse-grid correction of a patch started cold
    # --- the thermal full multigrid's stages
    min_coarse_thermal_grid: int = 65  # the coupled problem is solved one grid coarser first from this grid up
    coarse_stage_tolerance: float = 5.0  # the coarse stage stops at this multiple of the thermal tolerance ...
    coarse_stage_limit: float = 5e-3  # ... and never looser than this share of the rise (it seeds the estimates)
    seed_stage_limit: float = 2e-2  # the seed stage (two grids below the finest) stops at this share of the rise
    min_seed_stage_grid: int = 129  # nodes in x of the seed stage's grid from which it runs (65: no saving)
    continuation_chunk: int = 7  # points of a path solved in order by one worker, each seeded from the one before
    # --- outlet patches (outlet.py)
    patch_start: float = -0.5  # X_a / b of the first patch: on the outlet side of the centre
    nested_patch_starts: tuple[float, ...] = (-0.4, 0.0)  # X_a / b of the nested patches (a 1/4, an 1/8 spacing)
    spike_flank_nodes: int = 2  # `auto`: the hottest node lies at most this many nodes upstream of the spike
    auto_dt_max_error: float = 0.02  # `auto` patches where the grid's dT_max estimate misses 2 % ...
    auto_mu_error: float = 0.01  # ... or its mu estimate misses 1 %
    max_entrainment_angle: float = 45.0  # deg: beyond it the spike lies across the patch's rows; no stage runs
    stage_coarse_cycles: tuple[int, ...] = (1, 3)  # grid-below V-cycles per patch correction, by attempt (3 the cold
    # start's, patch_coarse_cycles)
    stage_cycles_per_update: int = 1  # V-cycles of a stage's composite per update of its film state
    figure_window: int = 4  # a stage also stops once its hottest rise settled over this many updates ...
    figure_spread: float = 0.005  # ... spanning at most this share of its mean (a quarter of auto_dt_max_error) ...
    flicker_bound: float = 0.025  # ... its changes below this share of the rise (past the transient)
    stage_load_band: float = 10.0  # ... and the composite's load error within this multiple of the tolerance
    provisional_margin: float = 1.5  # a stage ends provisionally once its figures moved by this multiple of the bound
    provisional_window: int = 2  # ... at this many consecutive outer iterations ...
    provisional_min_iterations: int = 3  # ... from this outer iteration on (the first is the transient)
    # --- grid refinement of a point whose grid does not resolve its film (retry.py)
    max_refined_grid: int = 1025  # largest refined grid along either axis (a 1025^2 solve takes about a minute)
    max_refined_thermal_grid: int = 513  # ... of a thermal solve (1025 never resolved one that 513 did not)
    unresolved_h_min: float = 0.1  # an unconverged solve estimating its h_min error above this is refined
    coarse_estimate: float = 0.1  # a converged solve estimating its h_c or h_min error above this is refined
    side_lobe: float = 0.5  # |y| / a beyond which the lowest film lies in a side lobe: rows alone are doubled
    # a closed film is not refined where its predicted constriction spans fewer nodes on the finest grid reachable
    # (closure.py): the feature_nodes a resolved feature needs
    closure_nodes: int = 3
    damped_attempt: int = 3  # the first attempt (1-based) with the damped relaxation
    rescue_film_step: float = 2.0  # ln(eta*/eta) per update of retry.RESCUE: 2 e-folds, as 50 K at beta = 0.04 1/K
    rescue_updates: int = 2  # ... after a damped attempt run away within this many updates (the start's transient)
    venner_first_nodes: int = 64  # a finest grid with fewer X nodes across 2b tries Venner's switch before the scaled
    # --- the accuracy target (accuracy_target.py, solver.accuracy)
    accuracy_start_grid: int = 129  # x nodes it starts on: the coarsest on which the inlet is lengthened as on finer
    accuracy_max_grid: int = 1025  # x nodes it refines to at most (2049 solved over the lengthened inlet)
    accuracy_max_grid_y: int = 513  # y nodes it refines to at most
    accuracy_model_share: float = 0.5  # share of the target a cheaper model's measured effect may take (grid: the rest)
    accuracy_fewer_layers: int = 7  # the cheaper layer count across the film it tries for thermal full (default 9)
    accuracy_jump_margin: float = 0.9  # share of the target the grid it jumps to is predicted to bound (e ~ h^p)
    accuracy_min_order: float = 0.5  # measured order below which a figure's refinement stops, "not met"
    accuracy_saving_reduced: float = 0.17  # share of a thermal full solve's CPU that thermal reduced saves (median)
    accuracy_saving_layers: float = -0.1  # ... that 7 layers instead of 9 save (negative: they cost more)
    accuracy_saving_newtonian: float = -0.35  # ... that a Newtonian fluid instead of Ree-Eyring saves (ditto)
    # --- error bounds of the reported figures (error_bounds.py)
    bound_safety: float = 3.0  # Roache's GCI factor F_s for a two-grid estimate at an assumed order
    asymptotic_estimate: float = 0.1  # an x or y estimate above this is outside the asymptotic range: unresolved
    contraction_window: int = 4  # outer changes an outer loop's contraction rate is taken over (its iteration error)
    max_contraction: float = 0.9  # changes contracting slower than this are a flicker: the window's largest change
    max_iteration_error: float = 0.1  # a figure whose iteration error (a floor's amplitude) exceeds this: unresolved
    # the energy balance of a converged thermal film (energy.energy_budget) is exact where its state solves the discrete
    # equations: an imbalance above this share of the heat generated says the loop stopped short, so nothing is bounded
    max_energy_imbalance: float = 0.01
    # below this inlet gap ratio G the truncated inlet starves h_c by more than asymptotic_estimate (140-200 G^-1.5 %,
    # docs/accuracy.md, domain size): the film is not the flooded one its figures' bounds are of
    min_inlet_gap_ratio: float = 7.4
    # a film whose pressure near the domain's sides passes this share of its peak is starved by them beyond its bounds
    # (domain.starved_sides; docs/accuracy.md, domain size: the sides)
    max_side_pressure: float = 0.01
    drift_floor: float = 1e-3  # a film moving one way by less than this per cycle (relative) is wandering at its floor
    feature_nodes: int = 3  # a minimum, hot or cold spot spanning fewer nodes along x or y is unresolved ...
    feature_depth: float = 0.1  # ... counted where the figure is within this share of its extreme


TUNING = Tuning()


def convergence_bands() -> dict[str, float]:
    """The bands, beyond the case's tolerances, by which a loop is accepted on its algebraic floor, as the result file
    states them for the convergence plot: the pressure change per cycle settled below pressure_floor_band times
    `solver.tolerance`; the thermal loop's change settled below thermal_floor_fraction of the rise, taken as at least
    min_rise (K)."""
    return {"pressure_floor_band": TUNING.floor_band, "thermal_floor_fraction": TUNING.thermal_floor_fraction,
            "min_rise": TUNING.min_rise}
