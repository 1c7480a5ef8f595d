"""The meshing cycle (/cycle, cycle.py): the mesh power loss against hand calculations (constant and linear power
per pair, the time mean over one base pitch of every pair in mesh), zero friction, the quadrature's convergence
(41 vs 81 points), the film parameter by hand, the contact temperature, bad keys, and the CLI end to end."""

from __future__ import annotations

from dataclasses import replace
import json
import math
from pathlib import Path

from click.testing import CliRunner
import numpy as np
import pytest
import yaml

from facegear_tehl import cycle
from facegear_tehl.case import parse_case
from facegear_tehl.cli import tehl
from facegear_tehl.gears.loads import load_share
from facegear_tehl.lubricant import KELVIN
from facegear_tehl.points import contact_analysis
from facegear_tehl.results import read_result, write_result
from facegear_tehl.run import run_case
from facegear_tehl.verdict import assess, verdict_text

import synthetic

FACE_GEAR = synthetic.CASES / "facegear_110.yaml"
TORQUE, SPEED = 500.0, 3000.0 * 2.0 * math.pi / 60.0  # the case's pinion torque (N m) and speed (rad/s)


def _case(**gear_keys):
    """The shipped face gear case with keys of its gear: block replaced."""
    raw = yaml.safe_load(FACE_GEAR.read_text())
    raw["gear"].update(gear_keys)
    return parse_case(yaml.safe_dump(raw), name="facegear_110")


def _prescribed(power_of_s):
    """A stand-in solver (synthetic film, h_min = 0.6 H_C) whose friction coefficient makes the sliding power of
    the pair at s equal power_of_s(s): mu = P(s) / (F |v_s|)."""
    def solve(point, lubricant, settings):
        solution = synthetic.solution(point)
        mu = power_of_s(point.path_coordinate) / (point.load * point.sliding_speed)
        return replace(solution, scalars={**solution.scalars, "mu": (mu, "1")})
    return solve


def test_constant_power_per_pair_is_lost_contact_ratio_times():
    # Hand calculation: every pair dissipates P0 wherever it is, so the mean over one base pitch is P0 times the
    # mean number of pairs in mesh, the contact ratio eps = (s_max - s_min)/p_b.
    p0 = 250.0
    run = run_case(_case(points=41), solver=_prescribed(lambda s: p0), jobs=1)
    geometry = run.contact_scalars
    eps = (geometry["path_end"][0] - geometry["path_start"][0]) / geometry["base_pitch"][0]
    assert eps == pytest.approx(geometry["contact_ratio"][0], rel=1e-12)
    scalars = run.cycle_scalars
    assert scalars["power_loss"][0] == pytest.approx(p0 * eps, rel=1e-12)
    assert scalars["input_power"][0] == pytest.approx(TORQUE * SPEED, rel=1e-12)  # 157.08 kW
    assert scalars["mesh_efficiency"][0] == pytest.approx(1.0 - p0 * eps / (TORQUE * SPEED), rel=1e-12)


def test_linear_power_along_the_path_by_hand():
    # P(s) = P0 (1 + s/L): (1/p_b) int P ds = P0/p_b [(s_max - s_min) + (s_max^2 - s_min^2)/(2L)], which the
    # trapezoidal rule integrates exactly.
    p0, length = 300.0, 0.02
    run = run_case(_case(points=11), solver=_prescribed(lambda s: p0 * (1.0 + s / length)), jobs=1)
    g = {key: value for key, (value, _) in run.contact_scalars.items()}
    s_min, s_max, p_b = g["path_start"], g["path_end"], g["base_pitch"]
    hand = p0 / p_b * ((s_max - s_min) + (s_max**2 - s_min**2) / (2.0 * length))
    assert run.cycle_scalars["power_loss"][0] == pytest.approx(hand, rel=1e-12)
    assert run.cycle["sliding_power"].values == pytest.approx(p0 * (1.0 + run.cycle["s"].values / length), rel=1e-12)


def test_base_pitch_mean_counts_every_pair_in_mesh():
    # The time mean over one base pitch of the summed loss of the pairs in mesh (s, s + p_b, ... inside the path),
    # taken by brute force over pinion positions, equals (1/p_b) int P ds: two pairs in the double-tooth zones.
    s_min, s_max, p_b = -0.015, 0.013, 0.018

    def power(s):
        return load_share("iso_linear", s, s_min, s_max, p_b) * 7000.0 * 0.03 * 0.9 * np.abs(s) / 0.01

    positions = s_min + (np.arange(200_000) + 0.5) / 200_000 * p_b  # the pair entering at s_min, over one pitch
    in_mesh = [positions + k * p_b for k in range(3)]
    instantaneous = sum(np.where(s <= s_max, power(s), 0.0) for s in in_mesh)
    pairs = sum((s <= s_max).astype(int) for s in in_mesh)
    assert set(pairs) == {1, 2}
    s = np.linspace(s_min, s_max, 4001)
    assert cycle.mesh_power_loss(s, power(s), p_b) == pytest.approx(instantaneous.mean(), rel=2e-4)


def test_zero_friction_loses_nothing():
    run = run_case(_case(points=11), solver=_prescribed(lambda s: 0.0), jobs=1)
    scalars = run.cycle_scalars
    assert scalars["power_loss"][0] == 0.0 and scalars["mesh_efficiency"][0] == 1.0
    # ISO/TR 14179-2's coefficient does not come from the film: its efficiency stays below 1.
    assert 0.0 < scalars["mu_iso"][0] and scalars["mesh_efficiency_iso"][0] < 1.0


def test_film_parameter_by_hand_and_absent_without_roughness(tmp_path):
    # h_min = 0.6 x 0.15 um = 0.09 um; sigma = sqrt(0.3^2 + 0.3^2) um = 0.42426 um; lambda = 0.21213.
    run = run_case(_case(points=[ "S1", "S2", "S3", "S4", "S5"]), solver=_prescribed(lambda s: 100.0), jobs=1)
    result = read_result(write_result(run, tmp_path / "cycle.h5"))
    assert result.points["S3"].scalars["film_parameter"] == pytest.approx(0.09 / math.sqrt(0.18), rel=1e-12)
    assert result.cycle["film_parameter"].values == pytest.approx(np.full(5, 0.212132034), rel=1e-8)
    assert result.cycle["film_parameter"].units == "1" and "h_min" in result.cycle["film_parameter"].description
    raw = yaml.safe_load(FACE_GEAR.read_text())
    for body in ("body_1", "body_2"):
        del raw["materials"][body]["roughness"]
    smooth = run_case(parse_case(yaml.safe_dump(raw)), solver=_prescribed(lambda s: 100.0), jobs=1)
    assert "film_parameter" not in smooth.cycle and "power_loss_iso" not in smooth.cycle_scalars
    assert all("film_parameter" not in p.scalars for p in smooth.points)
    for body in ("body_1", "body_2"):  # roughness 0 written out: smooth flanks, valid, no film parameter either
        raw["materials"][body]["roughness"] = 0.0
    written = run_case(parse_case(yaml.safe_dump(raw)), solver=_prescribed(lambda s: 100.0), jobs=1)
    assert "film_parameter" not in written.cycle and all("film_parameter" not in p.scalars for p in written.points)


def test_ends_not_solved_give_no_power_loss_and_say_so():
    run = run_case(_case(), points=["S1", "S3"], solver=_prescribed(lambda s: 100.0), jobs=1)
    assert "power_loss" not in run.cycle_scalars and list(run.cycle["point"].values) == ["S1", "S3"]
    assert any("do not span the contact path" in w for w in run.warnings)


def test_a_point_that_did_not_converge_is_left_out_of_the_cycle_and_the_verdict(tmp_path):
    # A point that did not converge carries its last iterate's figures (here a lower film and a larger friction):
    # not a result, so neither the cycle's power loss nor the verdict's lambda_min may take them.
    def solve(point, lubricant, settings):
        solution = _prescribed(lambda s: 100.0)(point, lubricant, settings)
        if point.name != "S2":
            return solution
        failed = synthetic.solution(point, converged=False)
        return replace(failed, scalars={**failed.scalars, "h_min": (0.01 * synthetic.H_C, "m"), "mu": (30.0, "1")})
    roughness = {"body_1": {"roughness": 1.0e-7}, "body_2": {"roughness": 1.0e-7}}
    raw = yaml.safe_load(FACE_GEAR.read_text())
    for body, keys in roughness.items():
        raw["materials"][body].update(keys)
    run = assess(run_case(parse_case(yaml.safe_dump(raw), name="facegear_110"), solver=solve, jobs=1))
    assert list(run.cycle["point"].values) == ["S1", "S3", "S4", "S5"]
    assert any("S2 left out (not converged)" in w for w in run.warnings)
    # every other point dissipates 100 W: the trapezoid over them, as if S2 had its neighbours' power
    assert run.cycle["sliding_power"].values == pytest.approx(100.0, rel=1e-12)
    assert run.verdict_labels["lambda_min_point"] != "S2" and run.verdict_labels["left_out"] == "S2"
    assert run.verdict["lambda_min"][0] == pytest.approx(0.6 * synthetic.H_C / (math.sqrt(2.0) * 1.0e-7), rel=1e-3)
    text = verdict_text(read_result(write_result(run, tmp_path / "r.h5"), fields=False))
    assert "left out             S2 (not converged" in text


def test_a_run_where_no_point_converged_writes_its_file_and_says_why(tmp_path):
    def solve(point, lubricant, settings):
        return synthetic.solution(point, converged=False)
    target = tmp_path / "failed.h5"
    run = assess(run_case(_case(), points=["S1"], solver=solve, jobs=1))
    assert run.verdict == {} and run.verdict_labels["left_out"] == "S1"
    result = read_result(write_result(run, target), fields=False)
    assert result.status == "not_converged" and result.verdict_labels["left_out"] == "S1"
    assert "S1 (not converged: no result to assess)" in verdict_text(result)


def test_contact_temperature_is_bulk_plus_flash(facegear_run):
    # Blok (1937): theta_B = theta_bulk + theta_fl per flank; the bulk defaults to the oil inlet temperature.
    case = facegear_run.case
    analysis = contact_analysis(case)
    inlet = case.lubricant.inlet_temperature
    columns = facegear_run.cycle
    for body in (1, 2):
        assert columns[f"contact_temperature_{body}"].values == pytest.approx(
            inlet + columns[f"dT_surface_{body}_max"].values, rel=1e-12)
        assert columns[f"contact_temperature_blok_{body}"].values == pytest.approx(
            inlet + columns["flash_temperature"].values, rel=1e-12)
    hot = replace(case, gear=replace(case.gear, pinion_bulk_temperature=90.0 + KELVIN))
    again = cycle.mesh_cycle(hot, analysis.points, facegear_run.points, analysis.path, analysis.scalars)
    assert again.columns["contact_temperature_1"].values == pytest.approx(
        90.0 + KELVIN + columns["dT_surface_1_max"].values, rel=1e-12)
    assert again.columns["contact_temperature_2"].values == pytest.approx(columns["contact_temperature_2"].values)
    # The solved rises of a thermal film: the hottest flank is tens of kelvin above the inlet, as Blok's estimate.
    assert 5.0 < max(columns["dT_surface_1_max"].values) < 200.0


def test_bulk_temperature_key_in_degrees_celsius():
    assert _case(face_gear_bulk_temperature=75.0).gear.face_gear_bulk_temperature == pytest.approx(348.15)
    assert _case().gear.pinion_bulk_temperature is None


def _write(tmp_path: Path, edit) -> Path:
    raw = yaml.safe_load(FACE_GEAR.read_text())
    edit(raw)
    path = tmp_path / "case.yaml"
    path.write_text(yaml.safe_dump(raw))
    return path


@pytest.mark.parametrize("block, key, value, expected", [
    ("materials.body_1", "roughness", -3e-7, "a number >= 0"),
    ("materials.body_2", "roughness", 2e-3, "a number <= 0.0001"),
    ("materials.body_1", "roughness", "rough", "a finite number"),
    ("materials.body_2", "roughness", float("inf"), "a finite number"),
    ("gear", "pinion_bulk_temperature", 900.0, "a number <= 400"),
    ("gear", "face_gear_bulk_temperature", "hot", "a finite number"),
    ("lubricant", "oil_type", "olive", "one of mineral, pao, ester, pag"),
])
def test_bad_cycle_keys_exit_2_naming_the_key(tmp_path, block, key, value, expected):
    def edit(raw):
        entry = raw
        for part in block.split("."):
            entry = entry[part]
        entry[key] = value

    output = tmp_path / "out.h5"
    result = CliRunner().invoke(tehl, ["run", str(_write(tmp_path, edit)), "-o", str(output)])
    assert result.exit_code == 2, result.output
    line = result.output.strip()
    assert "\n" not in line and line.startswith(f"error: {block}.{key}: got ") and expected in line, line
    assert "Traceback" not in result.output and not output.exists()


def test_cli_run_info_and_plot_of_a_solved_cycle(tmp_path):
    # Real solves: five points, isothermal, on 33 x 9.
    case = _write(tmp_path, lambda raw: raw["solver"].update(thermal="off"))
    output = tmp_path / "gear.h5"
    run = CliRunner().invoke(tehl, ["run", str(case), "--grid", "33", "--jobs", "1", "-o", str(output)])
    assert run.exit_code in (0, 3), run.output
    assert "mesh cycle: 5 points" in run.output and "ISO/TR 14179-2 mean mu" in run.output
    assert "5 points are a coarse sample" in run.output and "cylindrical-gear correlations" in run.output
    info = json.loads(CliRunner().invoke(tehl, ["info", str(output), "--json"]).output)
    loss = info["cycle"]["power_loss"]
    assert info["cycle"]["units"]["power_loss"] == "W" and 0.0 < loss < 0.05 * TORQUE * SPEED
    assert info["cycle"]["mesh_efficiency"] == pytest.approx(1.0 - loss / (TORQUE * SPEED), rel=1e-12)
    assert len(info["cycle"]["columns"]["film_parameter"]) == 5
    assert all("film_parameter" in p for p in info["points"].values())
    text = CliRunner().invoke(tehl, ["info", str(output)]).output
    assert "meshing cycle:" in text and "film mu (solved)" in text
    plot = CliRunner().invoke(tehl, ["plot", str(output), "--what", "cycle", "-o", str(tmp_path / "plots")])
    assert plot.exit_code == 0 and (tmp_path / "plots" / "cycle.png").stat().st_size > 10_000, plot.output


@pytest.mark.slow
def test_41_and_81_points_agree_on_the_efficiency():
    # The statement is about the quadrature: the film solved isothermally on a coarse grid (33 x 9).
    efficiency = {}
    for count in (41, 81):
        case = _case(points=count)
        case = replace(case, solver=replace(case.solver, thermal="off"))
        run = run_case(case, grid=33, jobs=1)
        efficiency[count] = run.cycle_scalars["mesh_efficiency"][0]
    assert 0.98 < efficiency[81] < 1.0
    assert abs(efficiency[41] - efficiency[81]) < 0.05e-2, efficiency
