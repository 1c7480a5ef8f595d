"""The outlet stage (ehl/outlet.py): the thermal film on a patch twice as fine along x over the outlet.

The yardstick is the uniform grid of the patch's spacing, solved by the uniform solver alone: where the patch is,
the composite must land on it (the spike, the hot spot on its flank, the traction), while 513 x 65 alone is several
per cent off. The composite surface temperature is checked against Jaeger's closed form for a uniform flux.
"""

from __future__ import annotations

from dataclasses import replace
import math
from pathlib import Path
from types import SimpleNamespace

from click.testing import CliRunner
import numpy as np
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.cli import tehl
from facegear_tehl.ehl import jaeger, outlet
from facegear_tehl.ehl.outlet import GHOST, PatchFilmModel, needs_outlet_patch
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.points import contact_analysis
from facegear_tehl.record import Action, Reason, Stage
from facegear_tehl.settings import MAX_OUTLET_PATCHES, SolverSettings
from facegear_tehl.solution import Outcome, Status

FACE_GEAR_CASE = Path(__file__).resolve().parents[1] / "cases" / "facegear_110.yaml"


def _face_gear(name: str):
    case = load_case(FACE_GEAR_CASE)
    return case, next(p for p in contact_analysis(case).points if p.name == name)


def _auto(x_hot: int, spike: int, x0: float = -1.0, coarse_rise: float | None = None, choice: str = "auto",
          angle: float = 0.0, runner_up: tuple[int, float] | None = None) -> bool:
    """needs_outlet_patch (auto) for a film whose hottest node (10 K above the inlet) is column x_hot and whose
    pressure peaks at column `spike` on the same row (X from x0 in steps of 0.1); `coarse_rise`: ΔT_max of the coarse
    thermal stage (None: no coarse stage), its μ the fine film's (zero traction: μ = 0); `runner_up`: (column, K
    below the hottest) of a second hot node on the same row (the thermal tolerance 1e-3 of the 10 K rise: 0.01 K)."""
    nx, ny, nz = 21, 5, 3
    pressure = np.zeros((ny, nx))
    pressure[2, spike] = 1.0
    temperature = np.full((nz, ny, nx), 300.0)
    temperature[1, 2, x_hot] = 310.0
    if runner_up is not None:
        temperature[1, 2, runner_up[0]] = 310.0 - runner_up[1]
    stress = np.zeros((2, ny, nx))
    level = SimpleNamespace(x=x0 + 0.1 * np.arange(nx), pressure=pressure, hx=0.1, hy=0.1)
    summaries = [] if coarse_rise is None else [SimpleNamespace(dT_max=coarse_rise, mu=0.0), None]
    fake = SimpleNamespace(settings=SimpleNamespace(outlet_refinement=choice, thermal_tolerance=1e-3),
                           solver=SimpleNamespace(levels=[level]),
                           summaries=summaries, lubricant=SimpleNamespace(inlet_temperature=300.0),
                           scaling=SimpleNamespace(a=1e-3, b=1e-4),
                           point=SimpleNamespace(load=1e3, entrainment_angle=angle))
    return needs_outlet_patch(fake, 0, SimpleNamespace(temperature=temperature, stress_1=stress, stress_2=stress))


def test_auto_refines_where_the_hot_spot_is_on_the_spike_flank():
    assert _auto(15, 16) and _auto(14, 16)  # one or two nodes upstream of the spike, downstream of the centre
    assert not _auto(16, 16)  # the hottest node is the pressure maximum (S1, S5 of the default case)
    assert not _auto(13, 16)  # three nodes: not on the flank
    assert not _auto(5, 6)  # upstream of the centre (S3's hot spot)
    assert not _auto(17, 16)  # downstream of the spike


def test_a_flank_node_within_the_thermal_tolerance_of_the_hottest_counts_as_the_hottest():
    # The outer loop knows the temperatures to thermal_tolerance times the rise: a hottest node on the spike itself
    # with a flank node 0.005 K below it (tolerance 0.01 K) is a hot flank; 0.05 K below it is not (S1's flank lies
    # 0.7 K below its hottest node, 0.7 % of its rise).
    assert _auto(16, 16, runner_up=(15, 0.005)) and _auto(16, 16, runner_up=(14, 0.005))
    assert not _auto(16, 16, runner_up=(15, 0.05))
    assert not _auto(16, 16, runner_up=(13, 0.005))  # three nodes upstream: not on the flank


def test_auto_refines_only_where_the_estimates_miss_their_targets():
    """ΔT_max 10 K against the coarse stage's 9.7 K: a first-order estimate of 3 % (> 2 %); against 9.9 K, 1 %."""
    assert _auto(15, 16, coarse_rise=9.7)
    assert not _auto(15, 16, coarse_rise=9.9)


def test_no_stage_where_the_entrainment_is_far_from_x():
    """The patch refines along x: an entrainment at 60 deg to x (its spike across the patch's rows) gets no stage,
    even with `always`; at 30 deg `always` still runs it."""
    assert not _auto(15, 16, choice="always", angle=60.0) and not _auto(15, 16, angle=-60.0)
    assert _auto(15, 16, choice="always", angle=30.0) and _auto(15, 16, angle=30.0)
    assert not _auto(15, 16, choice="never")


def test_the_composite_surface_is_jaeger_over_the_whole_axis():
    """A uniform flux q from the domain inlet on: the surface rise is 2 q sqrt(x - x_in)/(sqrt(pi) B) (Jaeger 1942,
    the integral of q (x - s)^(-1/2)), whether the flux comes from the grid below or from the patch."""
    case, point = _face_gear("S2")
    nx_fine, ny, offset, size = 201, 3, 120, 60
    dx = 2e-6
    x = (offset + np.arange(size)) * dx
    model = PatchFilmModel(x, np.linspace(-1e-4, 1e-4, ny), 9, case.lubricant, point, offset,
                           (np.full((ny, nx_fine), 2e7), np.full((ny, nx_fine), 3e7)))
    for index, q in ((0, 2e7), (1, 3e7)):
        speed = float(point.velocity_1[0] if index == 0 else point.velocity_2[0])
        surface = model._surface(np.full((ny, size), q), index, speed)
        distance = x - 0.0 if speed > 0 else (nx_fine - 1) * dx - x
        expected = model.t_inlet + 2.0 * q * np.sqrt(distance) / (math.sqrt(math.pi) * model.effusivity[index])
        assert np.allclose(surface, expected, rtol=1e-9)
    # a patch flux of its own: the rise of the whole composite axis evaluated directly, both directions of motion
    own = np.random.default_rng(1).uniform(1e7, 5e7, (ny, size))
    for index in (0, 1):
        for speed in (1.0, -1.0):
            whole = jaeger.surface_temperature_rise(model.composite_flux(own, index), dx, model.effusivity[index],
                                                    reverse=speed < 0.0)
            assert np.allclose(model._surface(own, index, speed), model.t_inlet + whole[:, offset:offset + size],
                               rtol=1e-12)


def test_the_energy_sweeps_hold_the_inflow_columns():
    """The columns before `first_column` are the patch's inflow: they keep their temperatures."""
    case, point = _face_gear("S2")
    model = PatchFilmModel(np.linspace(0.0, 1e-4, 12), np.linspace(-1e-4, 1e-4, 5), 5, case.lubricant, point, 0,
                           (np.zeros((5, 30)), np.zeros((5, 30))))
    pressure = np.full((5, 12), 4e8)
    pressure[[0, -1]] = 0.0
    temperature = model.initial_temperature()
    temperature[:, :, :GHOST] += 7.0
    state = model.update(pressure, np.full((5, 12), 1e-6), temperature.copy())
    assert np.array_equal(state.temperature[1:-1, :, :GHOST], temperature[1:-1, :, :GHOST])
    assert np.abs(state.temperature[1:-1, :, GHOST:] - model.t_inlet).max() > 0.1  # the rest was solved


def test_each_patch_the_settings_allow_has_its_start():
    assert len(outlet.TUNING.nested_patch_starts) + 1 == MAX_OUTLET_PATCHES == SolverSettings().outlet_patches
    starts = (outlet.TUNING.patch_start,) + outlet.TUNING.nested_patch_starts
    assert all(a < b for a, b in zip(starts, starts[1:], strict=False))  # each inside the one before


def test_a_bad_outlet_refinement_is_named(tmp_path):
    text = FACE_GEAR_CASE.read_text().replace("  grid_y: 65\n", "  grid_y: 65\n  outlet_refinement: sometimes\n")
    path = tmp_path / "case.yaml"
    path.write_text(text)
    result = CliRunner().invoke(tehl, ["validate", str(path)])
    assert result.exit_code == 2
    assert "solver.outlet_refinement" in result.output and "auto, always, never" in result.output


def test_a_stage_that_fails_reports_the_uniform_solution(monkeypatch):
    """S2 on its quick grid (257 x 17 over the lengthened inlet): an outlet stage whose energy equation returns NaN
    runs away; the point reports the uniform solution, the same as without the stage, and says why."""
    case, point = _face_gear("S2")
    settings = replace(case.solver, grid=129, grid_y=17)
    plain = solve_point(point, case.lubricant, replace(settings, outlet_refinement="never"))
    real_update = PatchFilmModel.update

    def poisoned(self, *args, **kwargs):
        state = real_update(self, *args, **kwargs)
        return replace(state, temperature=np.full_like(state.temperature, np.nan))

    monkeypatch.setattr(PatchFilmModel, "update", poisoned)
    failed = solve_point(point, case.lubricant, replace(settings, outlet_refinement="always"))
    assert failed.outcome == plain.outcome == Outcome.CONVERGED
    for name in ("h_c", "h_min", "p_max", "dT_max", "mu"):
        assert failed.scalars[name] == plain.scalars[name], name
    assert "outlet_patch_start" not in failed.scalars
    last = failed.record.retries[-1]  # (after the attempts the relaxation needed, as for `plain`)
    assert (last.reason, last.action) == (Reason.STAGE_FAILED, Action.DROPPED)
    # each stage_coarse_cycles value but the last was tried and failed before it: recorded, in order
    tried = [r for r in failed.record.retries if r.action is Action.MORE_COARSE_CYCLES]
    assert [r.detail.split(":")[0] for r in tried] == [f"outlet patch 1, {cycles} per correction"
                                                       for cycles in outlet.TUNING.stage_coarse_cycles[:-1]]


def test_a_stage_that_converges_is_reported_with_its_patch(monkeypatch):
    """The same point with the stage (`outlet_patches: 1`, the first patch alone): its composite figures and the note
    on the patch."""
    case, point = _face_gear("S2")
    settings = replace(case.solver, grid=129, grid_y=17, outlet_refinement="always", outlet_patches=1)
    refined = solve_point(point, case.lubricant, settings)
    assert refined.outcome == Outcome.CONVERGED and refined.scalars["outlet_patches"][0] == 1
    assert refined.scalars["outlet_patch_start"][0] == pytest.approx(-0.5 * refined.scalars["b"][0], rel=0.05)
    assert [s.stage for s in refined.record.stages][-1] is Stage.OUTLET
    assert Reason.STAGE_FAILED not in [r.reason for r in refined.record.retries]
    monkeypatch.setattr(outlet, "refine_outlet", lambda *args: (None, Status(Outcome.NOT_CONVERGED, "stub")))
    assert "outlet_patch_start" not in solve_point(point, case.lubricant, settings).scalars


def test_a_nested_stage_that_fails_reports_the_first_patch(monkeypatch):
    """The quick S2 with `always`: a nested patch whose energy equation returns NaN runs away; the point reports the
    composite of the first patch exactly as a run that stops there, and says why."""
    case, point = _face_gear("S2")
    settings = replace(case.solver, grid=129, grid_y=17, outlet_refinement="always")
    with monkeypatch.context() as stop:
        stop.setattr(outlet, "TUNING", replace(outlet.TUNING, nested_patch_starts=()))
        first = solve_point(point, case.lubricant, settings)
    two = replace(outlet.TUNING, nested_patch_starts=outlet.TUNING.nested_patch_starts[:1])
    monkeypatch.setattr(outlet, "TUNING", two)  # two patches: enough here
    both = solve_point(point, case.lubricant, settings)
    assert first.scalars["outlet_patches"][0] == 1 and both.scalars["outlet_patches"][0] == 2
    assert both.scalars["dT_max"][0] != first.scalars["dT_max"][0]
    # the estimate: the change from the uniform grid (one patch's estimate is that change, first order) over the whole
    # refinement, (f_2 - f_0)/(2^2 - 1)
    uniform_dT = first.scalars["dT_max"][0] * (1.0 - first.scalars["error_estimate_dT_max"][0])
    assert both.scalars["error_estimate_dT_max"][0] == pytest.approx(
        (both.scalars["dT_max"][0] - uniform_dT) / 3.0 / both.scalars["dT_max"][0], rel=1e-9)
    _poison_nested_patch(monkeypatch)
    failed = _solved_as_one_patch(point, case, settings, first)
    last = failed.record.retries[-1]
    assert (last.reason, last.action) == (Reason.STAGE_FAILED, Action.KEPT_COARSER)
    tried = [r.detail.split(":")[0] for r in failed.record.retries if r.action is Action.MORE_COARSE_CYCLES]
    assert tried == [f"outlet patch 2, {cycles} per correction" for cycles in two.stage_coarse_cycles[:-1]]


def _poison_nested_patch(monkeypatch) -> None:
    """The energy equation of every patch finer than the first returns NaN temperatures: a nested patch runs away."""
    real_update, spacings = PatchFilmModel.update, []

    def poisoned(self, *args, **kwargs):
        state = real_update(self, *args, **kwargs)
        spacings.append(self.dx)
        if self.dx < max(spacings):  # the nested patch
            return replace(state, temperature=np.full_like(state.temperature, np.nan))
        return state

    monkeypatch.setattr(PatchFilmModel, "update", poisoned)


def _solved_as_one_patch(point, case, settings, first):
    """The point solved again: converged with one patch, its figures exactly those of `first` (one patch alone)."""
    solved = solve_point(point, case.lubricant, settings)
    assert solved.outcome == Outcome.CONVERGED and solved.scalars["outlet_patches"][0] == 1
    for name in ("h_c", "h_min", "p_max", "dT_max", "mu", "error_estimate_dT_max"):
        assert solved.scalars[name] == first.scalars[name], name
    return solved


def test_a_stage_stops_once_its_hot_spot_has_settled():
    """figures_settled on the sequences of S4's third patch (default case): the hottest rise past the transient
    (35.84, 35.87, 35.73, 35.73 K: 0.4 % of its mean) has settled within a quarter of the 2 % asked of ΔT_max; while
    it still climbs (35.11 .. 35.52 K) or the temperatures still move by more than TUNING.flicker_bound of the rise,
    it has not; nor while h_c drifts."""
    settled_rises, climbing = [35.842, 35.871, 35.731, 35.731], [35.113, 35.379, 35.438, 35.523]
    films = [0.59802, 0.59788, 0.59801, 0.59797]
    flicker = [0.324, 0.222, 0.171, 0.213]  # K per update, past the transient
    assert outlet.figures_settled(settled_rises, films, flicker, 35.8)
    assert not outlet.figures_settled(climbing, films, flicker, 35.8)
    assert not outlet.figures_settled(settled_rises[1:], films[1:], flicker[1:], 35.8)  # a window of three
    assert not outlet.figures_settled(settled_rises, films, [0.324, 1.12, 0.171, 0.213], 35.8)  # 3 % of the rise
    assert not outlet.figures_settled(settled_rises, [0.5970, 0.5975, 0.5980, 0.5985], flicker, 35.8)
    # the window's spread is judged against the accuracy asked of ΔT_max: 0.6 % of the mean is too much
    assert not outlet.figures_settled([35.70, 35.91, 35.75, 35.80], films, flicker, 35.8)


def test_a_stage_pressure_settles_with_a_small_load_bias():
    """stage_pressure_settled: a third nested patch holds a steady composite load error of about -2e-4 (S4 of the
    default case): settled, while 1e-3 of the load moves h_c by 7e-5 (Hamrock & Dowson's W^-0.067); a load error
    beyond TUNING.stage_load_band times the tolerance, or a pressure change per cycle above the algebraic floor, is
    not."""
    settings = SolverSettings()
    changes = [3.6e-4, 2.2e-4, 2.8e-4, 4.4e-4]

    def history(changes, loads):
        return SimpleNamespace(changes=changes, loads=loads)

    assert outlet.stage_pressure_settled(history(changes, [-1.7e-4, -2.3e-4]), settings)
    assert not outlet.stage_pressure_settled(history(changes, [-1.2e-3, -1.1e-3]), settings)
    assert not outlet.stage_pressure_settled(history([3.6e-4, 2.2e-4, 1.5e-3, 4.4e-4], [-1.7e-4, -2.3e-4]), settings)
    assert not outlet.stage_pressure_settled(history(changes[1:], [-1.7e-4, -2.3e-4]), settings)
    # h_c's response to the band's largest load error: within 1e-4 (h ~ W^-0.067)
    band = outlet.TUNING.stage_load_band * settings.load_tolerance
    assert abs((1.0 + band) ** -0.067 - 1.0) < 1e-4


@pytest.mark.slow
@pytest.mark.parametrize("name", ["S2", "S4"])
def test_the_outlet_patches_land_on_the_uniform_grid_of_their_spacing(name):
    """S2 and S4 of the default case (thermal full, Ree-Eyring; hot spot on the spike's flank): 513 x 65 with two
    nested outlet patches (half, then a quarter of its x spacing at the spike; `outlet_patches: 2`, both take a third
    by default) against the uniform 2049 x 65 grid of the second's spacing. Measured: dT_max 60.00 / 35.70 K against
    60.01 / 35.70 K (513 x 65 alone: 56.27 / 31.72), mu +0.15 / +0.21 % (513 x 65: +0.83 / +1.3 %), p_max +0.06 /
    0.0 % (513 x 65: -2.6 / -2.5 %). (The default, three patches: 60.20 / 36.02 K, +0.3 / +0.9 %: finer than
    2049 x 65 at the spike.)"""
    case, point = _face_gear(name)
    default = solve_point(point, case.lubricant, replace(case.solver, outlet_patches=2))
    uniform = solve_point(point, case.lubricant, replace(case.solver, outlet_refinement="never"))
    fine = solve_point(point, case.lubricant, replace(case.solver, grid=4 * (case.solver.grid - 1) + 1,
                                                      outlet_refinement="never"))
    assert default.scalars["outlet_patches"][0] == 2 and "outlet_patch_start" not in uniform.scalars
    assert default.scalars["grid"][0] == uniform.scalars["grid"][0] == (fine.scalars["grid"][0] - 1) / 4 + 1

    def gap(solution, name):
        return solution.scalars[name][0] / fine.scalars[name][0] - 1.0

    assert abs(gap(default, "dT_max")) < 0.006 < 0.05 < abs(gap(uniform, "dT_max"))
    assert abs(gap(default, "mu")) < 0.003 < 0.005 < abs(gap(uniform, "mu"))
    assert abs(gap(default, "p_max")) < 0.003 < 0.02 < abs(gap(uniform, "p_max"))
    # h_c is set in the inlet, which the patches do not refine: it stays the uniform grid's within its estimate
    assert abs(default.scalars["h_c"][0] / uniform.scalars["h_c"][0] - 1.0) < abs(
        uniform.scalars["error_estimate_h_c"][0])
    # the error estimate of dT_max is the last patch's change, first order: it brackets the gap to 2049 x 65
    assert abs(default.scalars["error_estimate_dT_max"][0]) > abs(gap(default, "dT_max"))
    assert np.all(default.fields["film_thickness"].values > 0.0)


def test_the_next_stage_is_certain_beyond_the_margin():
    """_next_certain: under `auto` a candidate whose ΔT_max or μ moved by more than provisional_margin times the
    bounds asked of them (2 %, 1 %) makes the next stage certain, one that moved by less does not (the stage then
    runs to convergence and `auto` decides on its converged figures); under `always` it is always certain."""
    previous = {"dT_max": 40.0, "mu": 0.01}
    margin = outlet.TUNING.provisional_margin
    assert margin > 1.0  # a provisional decision needs more than the converged one

    def certain(dT_max: float, mu: float, choice: str = "auto") -> bool:
        fake = SimpleNamespace(settings=SimpleNamespace(outlet_refinement=choice))
        with pytest.MonkeyPatch.context() as patch:
            patch.setattr(outlet, "stage_figures", lambda solve, candidate: {"dT_max": dT_max, "mu": mu})
            return outlet._next_certain(fake, previous)(None)

    step_dT, step_mu = outlet.TUNING.auto_dt_max_error * 40.0, outlet.TUNING.auto_mu_error * 0.01
    assert certain(40.0 + 1.01 * margin * step_dT, 0.01) and certain(40.0 - 1.01 * margin * step_dT, 0.01)
    assert certain(40.0, 0.01 + 1.01 * margin * step_mu)
    assert not certain(40.0 + 0.99 * margin * step_dT, 0.01 - 0.99 * margin * step_mu)
    assert not certain(40.0 + 1.2 * step_dT, 0.01)  # moved beyond the bound itself, but not by the margin
    assert certain(40.0, 0.01, choice="always")


def test_a_provisional_stage_leaves_the_result_within_the_last_stage_tolerance(monkeypatch):
    """The quick S2 with `always` and two patches: the first ends provisionally after TUNING.provisional_min_iterations
    outer iterations, the second converges on top of it. Against the same refinement with the first converged, the
    figures differ by less than the last stage's own stopping tolerance (TUNING.figure_spread of ΔT_max, a fifth of the
    accuracy asked of μ, h_c within the spread the outer loops accept, thermal_floor_h_c): the stage below matters
    only through the strip upstream of the next patch."""
    case, point = _face_gear("S2")
    settings = replace(case.solver, grid=129, grid_y=17, outlet_refinement="always")
    two = replace(outlet.TUNING, nested_patch_starts=outlet.TUNING.nested_patch_starts[:1])
    monkeypatch.setattr(outlet, "TUNING", two)
    real_refine = outlet.refine_outlet
    ended = []

    def spied(solve, *args):
        outer = solve.history.outer
        stage, status = real_refine(solve, *args)
        ended.append((stage is not None and stage.provisional, solve.history.outer - outer))
        return stage, status

    monkeypatch.setattr(outlet, "refine_outlet", spied)
    early = solve_point(point, case.lubricant, settings)
    assert ended == [(True, outlet.TUNING.provisional_min_iterations), (False, ended[1][1])]
    ended.clear()
    monkeypatch.setattr(outlet, "TUNING", replace(outlet.TUNING, provisional_min_iterations=10**6))
    converged = solve_point(point, case.lubricant, settings)
    assert [provisional for provisional, _ in ended] == [False, False] and ended[0][1] > ended[1][1] / 4
    assert early.outcome == converged.outcome == Outcome.CONVERGED
    assert early.scalars["outlet_patches"][0] == converged.scalars["outlet_patches"][0] == 2
    assert early.scalars["dT_max"][0] == pytest.approx(converged.scalars["dT_max"][0], rel=outlet.TUNING.figure_spread)
    assert early.scalars["mu"][0] == pytest.approx(converged.scalars["mu"][0], rel=0.2 * outlet.TUNING.auto_mu_error)
    assert early.scalars["h_c"][0] == pytest.approx(converged.scalars["h_c"][0], rel=TUNING.thermal_floor_h_c)
    assert early.scalars["iterations"][0] < converged.scalars["iterations"][0]


def test_auto_goes_on_while_the_reported_estimate_misses_its_bound():
    """_estimate_above is the estimate the result reports (report._outlet_scalars: Richardson over the whole refinement,
    first order, (f_n - f_0)/(2^n - 1)/f_n), judged against the 2 % and 1 % asked of ΔT_max and μ. S2 of the default
    case: uniform 56.28 K; two patches 60.00 K, an estimate of 2.07 % although the second moved it by 1.6 % only, so a
    third follows; with it 60.27 K, 0.95 %. μ alone: 1.5 % over one patch (the uniform grid's 1.5 % off) goes on."""
    uniform = {"dT_max": 56.28, "mu": 0.013894}
    two = {"dT_max": 60.00, "mu": 0.013804}
    three = {"dT_max": 60.27, "mu": 0.013795}
    assert not outlet._moved(two, {"dT_max": 59.04, "mu": 0.013822}, 1.0)
    assert outlet._estimate_above(two, uniform, 2)
    assert not outlet._estimate_above(three, uniform, 3)
    assert (60.00 - 56.28) / 3 / 60.00 == pytest.approx(0.0207, abs=1e-4)  # the estimate, written out
    assert outlet._estimate_above({"dT_max": 56.28, "mu": 0.013894 * 1.015}, uniform, 1)
    assert not outlet._estimate_above({"dT_max": 56.28 * 1.019, "mu": 0.013894 * 1.009}, uniform, 1)


def test_a_stage_failing_on_a_provisional_one_has_the_stages_below_solved_again(monkeypatch):
    """The quick S2 with `always` and two patches, the first ending provisionally and the nested one running away
    (its energy equation poisoned with NaN): the solve goes back to where the stages began and solves the first
    patch to convergence, the result exactly that of a solve with the first patch alone, and the record says so."""
    case, point = _face_gear("S2")
    settings = replace(case.solver, grid=129, grid_y=17, outlet_refinement="always")
    with monkeypatch.context() as one:
        one.setattr(outlet, "TUNING", replace(outlet.TUNING, nested_patch_starts=()))
        first = solve_point(point, case.lubricant, settings)
    monkeypatch.setattr(outlet, "TUNING", replace(outlet.TUNING,
                                                  nested_patch_starts=outlet.TUNING.nested_patch_starts[:1]))
    _poison_nested_patch(monkeypatch)
    again = _solved_as_one_patch(point, case, settings, first)
    actions = [r.action for r in again.record.retries if r.reason is Reason.STAGE_FAILED]
    assert Action.STAGES_AGAIN in actions and actions[-1] is Action.KEPT_COARSER
    assert "on top of a provisional stage" in next(r.detail for r in again.record.retries
                                                   if r.action is Action.STAGES_AGAIN)
