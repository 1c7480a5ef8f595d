"""The third grid of the three-grid check (ehl/error_bounds.py, asymptotic_range.py) where it was missing: the seed
stage's film state as the third grid of dT_max, dT_min and mu (coarser_estimates), and the grid run.py's refinement
refined from as the third grid of the finer solve (with_coarser_pair through accuracy_target.three_grid_checked, the
rule one_doubling_coarser shared with the accuracy target). Manufactured sequences f = f* (1 + C h^q) on the three
grids of a thermal solve (seed 129, coarse 257, finest 513 nodes along x), through the real functions, against the
exact error f/f* - 1: the bound holds where it is given, and below the lowest order F_s covers (Roache 1998, ch. 5)
the figure is unresolved where its two-grid bound would have understated it."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from facegear_tehl.accuracy_target import three_grid_checked
from facegear_tehl.ehl.asymptotic_range import lowest_order
from facegear_tehl.ehl.error_bounds import bounds, coarser_estimates, one_doubling_coarser, with_coarser_pair
from facegear_tehl.ehl.report import ORDER_DT_MAX, ORDER_MU
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.ehl.unresolved import Why
from facegear_tehl.record import SolveRecord, Stage, StageRecord
from facegear_tehl.solution import Field, Outcome, PointSolution

SEED, COARSE, FINEST = 129, 257, 513  # nodes along x of a full thermal solve's last three levels (65 rows)
EXACT = {"dT_max": 40.0, "dT_min": 8.0, "mu": 0.05}  # K, K, 1: the grid-converged figures f*


def _sequence(exact: float, q: float, error: float) -> tuple[float, float, float]:
    """f = f* (1 + C h^q) on the seed, coarse and finest grids (h = 4, 2, 1 finest spacings), C so that the finest
    figure is `error` off."""
    return tuple(exact * (1.0 + error * k**q) for k in (4.0, 2.0, 1.0))


def _thermal(figures: dict[str, tuple[float, float, float]], patches: float = 0.0,
             changes: tuple[float, ...] = (1.0, 1e-3, 1e-6, 1e-9, 1e-12, 1e-15)) -> PointSolution:
    """A converged full thermal solve on 513 x 65 whose seed and coarse stages (with their film state, report
    _film_state_levels) and finest grid carry `figures` (seed, coarse, finest); its stages' loops ran `changes` (K),
    the seed stage's the first two, the coarse stage's the next two, the finest grid's the rest."""
    levels = [33.0, 65.0, SEED, COARSE, FINEST]
    state = {f"level_{name}": Field(np.array(values[:2]), "1", "") for name, values in figures.items()}
    history = {"level_nodes": Field(np.array(levels), "1", ""),
               "level_state_nodes": Field(np.array([SEED, COARSE], dtype=float), "1", ""),
               "thermal_change_history": Field(np.array(changes), "K", ""),
               "thermal_h_c_history": Field(np.full(len(changes), 2.0e-7), "m", ""), **state}
    stages = (StageRecord(Stage.SEED, SEED, 65, 4, 2, Outcome.CONVERGED, 1.0, first_outer=0),
              StageRecord(Stage.COARSE, COARSE, 65, 4, 2, Outcome.CONVERGED, 1.0, first_outer=2),
              StageRecord(Stage.FINEST, FINEST, 65, 4, len(changes) - 4, Outcome.CONVERGED, 1.0, first_outer=4))
    scalars = {"grid": FINEST, "grid_y": 65.0, "coarsest_grid": 17.0, "outlet_patches": patches, "h_c": 2.0e-7,
               "h_min": 1.0e-7, "a": 1.0, "b": 1.0}
    for name, (_, coarse, fine) in figures.items():
        order = ORDER_MU if name == "mu" else ORDER_DT_MAX
        scalars |= {name: fine, f"error_estimate_{name}": (fine - coarse) / (2.0**order - 1.0) / fine}
    axes = {"x": Field(np.linspace(-4.5, 1.5, FINEST), "m", ""), "y": Field(np.linspace(-3.0, 3.0, 65), "m", "")}
    return PointSolution(name="P", outcome=Outcome.CONVERGED, message="", axes=axes, history=history,
                         scalars={k: (float(v), "1") for k, v in scalars.items()}, fields={},
                         record=SolveRecord(stages=stages))


@pytest.mark.parametrize("q", [0.2, 0.3, 0.6, 1.0, 1.5, 2.5])
def test_the_seed_stage_is_the_third_grid_of_the_film_state(q):
    """dT_max, dT_min and mu converging as C h^q (first order assumed, q_min = 0.415 at F_s = 3): above q_min the
    bound holds; below it the figure is unresolved, where F_s |e_x| alone understates the exact error."""
    error = 0.01
    figures = {name: _sequence(exact, q, error) for name, exact in EXACT.items()}
    solution = _thermal(figures)
    pairs = coarser_estimates(solution)
    assert set(EXACT) <= pairs.keys()
    out = bounds(solution, dict.fromkeys(EXACT, 0.0), {}, pairs)
    for name, exact in EXACT.items():
        truth = figures[name][2] / exact - 1.0
        e_x = solution.scalar(f"error_estimate_{name}")
        assert out[f"observed_order_{name}"][0] == pytest.approx(q, abs=1e-6)
        if q < lowest_order(1) - 0.05:
            assert TUNING.bound_safety * abs(e_x) < abs(truth)  # the two-grid bound would understate it
            assert out[f"unresolved_{name}"][0] == 1.0 and f"error_bound_{name}" not in out
        else:
            assert out[f"unresolved_{name}"][0] == 0.0 and out[f"error_bound_{name}"][0] >= abs(truth)


def test_a_film_state_whose_differences_change_sign_is_unresolved_beyond_the_seed_stages_loop_error():
    """dT_max rising 50.0, 52.0, 51.0 K on seed, coarse and finest grids (the differences change sign): unresolved
    where the seed and coarse stages' loops stopped within 0.1 K of their fixed points; where their loops left up to
    2 K (the seed stage stops at seed_stage_limit of the rise), the sign is within that noise and the two-grid bound
    stands."""
    figures = {"dT_max": (50.0, 52.0, 51.0)}
    settled = _thermal(figures, changes=(1.0, 0.01, 1.0, 0.01, 1e-6, 1e-9))
    out = bounds(settled, {"dT_max": 0.0}, {}, coarser_estimates(settled))
    assert out["unresolved_dT_max"][0] == 1.0 and "observed_order_dT_max" not in out
    loose = _thermal(figures, changes=(4.0, 2.0, 2.0, 1.0, 1e-6, 1e-9))
    pair = coarser_estimates(loose)["dT_max"]
    assert pair.noise > abs(pair.estimate)
    out = bounds(loose, {"dT_max": 0.0}, {}, coarser_estimates(loose))
    assert out["unresolved_dT_max"][0] == 0.0


def test_an_outlet_refined_solve_gives_dT_max_and_mu_no_third_grid_of_its_levels():
    """An outlet-refined solve's dT_max and mu estimates compare the patches with the uniform grid (over 2^patches),
    not the coarse stage: its seed and coarse stages are no coarser pair of theirs; dT_min keeps its pair."""
    solution = _thermal({name: _sequence(exact, 1.0, 0.01) for name, exact in EXACT.items()}, patches=2.0)
    assert set(coarser_estimates(solution)) == {"dT_min"}


def test_a_solve_without_the_seed_stages_film_state_gives_no_third_grid_of_it():
    """Levels summarised without their film state (no level_state_nodes), or whose film-state levels are not the
    seed and coarse stages below the finest grid, give the film state no coarser pair."""
    solution = _thermal({"dT_max": _sequence(40.0, 1.0, 0.01)})
    bare = replace(solution, history={k: v for k, v in solution.history.items() if k != "level_state_nodes"})
    assert "dT_max" not in coarser_estimates(bare)
    shifted = replace(solution, history=solution.history | {
        "level_state_nodes": Field(np.array([65.0, SEED]), "1", "")})
    assert "dT_max" not in coarser_estimates(shifted)


def _refined(nx: int, ny: int, h_c: float, e_x: float, x=(-4.5, 1.5), **models: str) -> PointSolution:
    """A converged isothermal solve on nx x ny with h_c and h_min alike and their x-estimate, bounded (bounds, e_y
    0)."""
    axes = {"x": Field(np.linspace(*x, nx), "m", ""), "y": Field(np.linspace(-3.0, 3.0, ny), "m", "")}
    solution = PointSolution(name="P", outcome=Outcome.CONVERGED, message="", axes=axes,
                             fields={"film_thickness": Field(np.full((ny, nx), 1.0e-7), "m", "")},
                             scalars={"h_c": (h_c, "m"), "error_estimate_h_c": (e_x, "1"), "h_min": (h_c, "m"),
                                      "error_estimate_h_min": (e_x, "1"), "a": (1.0, "m"), "b": (1.0, "m")},
                             models={"thermal": "off", "rheology": "newtonian"} | models)
    e_y = {"h_c": 0.0, "h_min": 0.0}
    return replace(solution, scalars=solution.scalars | bounds(solution, e_y) | {
        f"error_estimate_y_{k}": (v, "1") for k, v in e_y.items()})


def test_the_third_grid_is_one_doubling_coarser_along_x_on_the_same_domain_and_model():
    """one_doubling_coarser, the rule run.py's refinement and the accuracy target share: 129 x 33 below 257 x 65
    (both x-only estimates) and 129^2 below 257^2 are third grids; two doublings, a square grid below a non-square
    one, another domain (a trial grid's short inlet below a lengthened one) or another model are not."""
    fine = _refined(257, 65, 1e-7, 0.01)
    assert one_doubling_coarser(_refined(129, 33, 1e-7, 0.01), fine)
    assert one_doubling_coarser(_refined(129, 129, 1e-7, 0.01), _refined(257, 257, 1e-7, 0.01))
    assert not one_doubling_coarser(_refined(65, 33, 1e-7, 0.01), fine)
    assert not one_doubling_coarser(_refined(129, 129, 1e-7, 0.01), fine)
    assert not one_doubling_coarser(_refined(129, 33, 1e-7, 0.01, x=(-2.0, 1.5)), fine)
    assert not one_doubling_coarser(_refined(129, 33, 1e-7, 0.01, thermal="full"), fine)


@pytest.mark.parametrize("q", [0.5, 0.8, 1.5, 2.0, 3.0])
def test_the_grid_refined_from_checks_the_refined_solve(q):
    """h_c = f* (1 + C h^q) on 65, 129 and 257 nodes along x (the refined 257 x 65's coarse stage on 129 x 65, the
    grid refined from 129 x 33 with its own on 65 x 33): second order assumed, q_min = 1. Above it the refined bound
    holds; below it, where F_s |e_x| understates the exact error, the check makes it unresolved."""
    exact, error = 2.0e-7, 0.01
    third, second, first = (exact * (1.0 + error * k**q) for k in (4.0, 2.0, 1.0))
    coarser = _refined(129, 33, second, (second - third) / 3.0 / second)
    fine = _refined(257, 65, first, (first - second) / 3.0 / first)
    checked = three_grid_checked(coarser, fine, 300.0)
    truth = first / exact - 1.0
    assert checked.scalar("observed_order_h_c") == pytest.approx(q, abs=1e-6)
    if q < lowest_order(2) - 0.05:
        assert fine.scalar("error_bound_h_c") < abs(truth)  # the refined solve's own two grids understate it
        assert checked.scalar("unresolved_h_c") == 1.0 and "error_bound_h_c" not in checked.scalars
    else:
        assert checked.scalar("unresolved_h_c") == 0.0 and checked.scalar("error_bound_h_c") >= abs(truth)
    elsewhere = three_grid_checked(replace(coarser, axes=_refined(129, 129, 1e-7, 0.01).axes), fine, 300.0)
    assert elsewhere is fine
    unbounded = replace(fine, scalars={k: v for k, v in fine.scalars.items() if not k.startswith(("error_bound_",
                                                                                                  "unresolved_"))})
    assert with_coarser_pair(unbounded, coarser, 300.0) is unbounded  # a solve without bounds gets none


def test_the_grid_refined_from_never_clears_what_the_solves_own_levels_flag():
    """A refined 257 x 65 whose own full-multigrid levels 65, 129, 257 (x alone on 65 rows) carry h_c growing from
    pair to pair (0.111, 0.123, 0.139 um: outside the asymptotic range) stays unresolved after the check against the
    grid it was refined from, though that pair alone (second order below it) would accept it: the stricter of the two
    third grids holds."""
    first, second = 0.139e-6, 0.123e-6
    fine = _refined(257, 65, first, (first - second) / 3.0 / first)
    fine = replace(fine, scalars=fine.scalars | {"grid": (257.0, "1"), "grid_y": (65.0, "1"),
                                                 "coarsest_grid": (17.0, "1")},
                   history={"level_nodes": Field(np.array([33.0, 65.0, 129.0, 257.0]), "1", ""),
                            "level_h_c": Field(np.array([0.07e-6, 0.111e-6, second, first]), "m", ""),
                            "level_h_min": Field(np.array([0.07e-6, 0.111e-6, second, first]), "m", "")})
    accepting = 4.0 * (first - second) / 3.0 / second  # the coarser pair of a second-order fall
    coarser = _refined(129, 33, second, accepting)
    alone = with_coarser_pair(replace(fine, history={}), coarser, 300.0)
    assert alone.scalar("unresolved_h_c") == 0.0 and alone.scalar("observed_order_h_c") == pytest.approx(2.0)
    checked = with_coarser_pair(fine, coarser, 300.0)
    assert checked.scalar("unresolved_h_c") == 1.0 and "error_bound_h_c" not in checked.scalars


def test_a_thermal_contacts_friction_outside_the_asymptotic_range_along_x_is_unresolved():
    """The envelope's ab1_ph0.3_u10_srr0.5_th asked on 129 x 33 is solved on 513 x 33 (its inlet lengthened), with a
    seed stage on 129 x 33 and its coarse stage on 257 x 33. Its mu on the three grids moves by -0.03 % and then
    +0.22 %: the finer pair's difference is larger than the coarser's, beyond the seed stage's loop error (0.05 %),
    and mu is unresolved (its two-grid bound was 4.4 %). Independent of the seed stage's early stop (2 % of the
    rise): the same contact converged to the thermal tolerance on 129 x 33 and 257 x 33 of the same domain gives mu
    differences that grow tenfold towards 513 x 33, an observed order below zero, where the first-order estimate
    needs 0.415 (Roache 1998, ch. 5): the grids are outside the asymptotic range along x."""
    from facegear_tehl.ehl.staged import STAGED, UNBOUNDED
    from facegear_tehl.suites.envelope import envelope_cases

    case = next(c for c in envelope_cases() if c.name == "ab1_ph0.3_u10_srr0.5_th")
    solution = STAGED(case.point(), case.lubricant(), case.settings(129, 33))
    assert solution.converged and (solution.scalar("grid"), solution.scalar("grid_y")) == (513, 33)
    assert list(solution.history["level_state_nodes"].values) == [SEED, COARSE]
    seed, coarse = solution.history["level_mu"].values
    mu = solution.scalar("mu")
    assert (coarse - seed) * (mu - coarse) < 0.0 and abs(mu - coarse) > 4.0 * abs(coarse - seed)
    assert solution.scalar("unresolved_mu") == 1.0 and "error_bound_mu" not in solution.scalars
    # its light film (Moes M 0.95) spreads beyond the sides of +-3 a: every figure is unresolved for that first
    assert solution.scalar("unresolved_reason_dT_max") == Why.STARVED_SIDES
    x, y = solution.axes["x"].values / solution.scalar("b"), solution.axes["y"].values / solution.scalar("a")
    converged = [UNBOUNDED(case.point(), case.lubricant(), replace(
        case.settings(nx, 33), domain_x=(x[0], x[-1]), domain_y=(y[0], y[-1]))).scalar("mu") for nx in (129, 257)]
    assert 0.0 < abs(converged[1] - converged[0]) < 0.25 * abs(mu - converged[1])
    assert solution.scalar("error_estimate_mu") == pytest.approx((mu - coarse) / mu)


@pytest.mark.slow
def test_a_thermal_point_refined_by_the_run_is_checked_against_the_grid_it_was_refined_from():
    """The envelope's ab100_ph1.5_u2_srr0.5_th asked on 129 x 33 converges with h_c and h_min estimated 12 and 15 %
    off; the run refines its rows (129 x 65: the lowest film in a side lobe) and then both axes (257 x 129). That
    thermal solve has no seed stage (257 nodes along x) and so no third grid of its own; the converged 129 x 65 it was
    refined from is one (one doubling along x, same domain, neither square): every figure it bounds gets an observed
    order, above the lowest one F_s covers (first order for dT_max and mu, whose differences fall at 1.5 and 2 here,
    as a smooth solution's do at a second-order discretisation), so no bound is withdrawn."""
    from facegear_tehl.ehl.staged import STAGED
    from facegear_tehl.parallel import SolveTask
    from facegear_tehl.run import solve_refining
    from facegear_tehl.suites.envelope import envelope_cases

    case = next(c for c in envelope_cases() if c.name == "ab100_ph1.5_u2_srr0.5_th")
    (solution,), _, refined = solve_refining([SolveTask(case.point(), case.lubricant(), case.settings(129, 33))],
                                             STAGED, jobs=1)
    assert refined[case.point().name].grid == "257 x 129" and solution.converged
    assert "level_state_nodes" in solution.history and solution.history["level_state_nodes"].values.size == 1
    for name in ("h_c", "h_min", "dT_max", "mu"):
        order = 1 if name in ("dT_max", "mu") else 2
        assert solution.scalar(f"unresolved_{name}") == 0.0
        assert solution.scalar(f"observed_order_{name}") > lowest_order(order)
