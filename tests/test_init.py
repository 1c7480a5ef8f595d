"""`tehl init`: the templates it writes validate as written, and the plain-contact one runs end to end."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner
import pytest
import yaml

from facegear_tehl.case import load_case
from facegear_tehl.cli import tehl
from facegear_tehl.results import read_result


def _invoke(*args) -> object:
    return CliRunner().invoke(tehl, [str(a) for a in args])


def test_the_contact_template_validates_and_runs(tmp_path):
    """Venner & Lubrecht's (2000) ball on disc: E = 200 GPa, nu = 0.3, R = 12.7 mm, 6.272 N give the Hertz
    contact a = 81.6 µm and p_h = 0.450 GPa (Hertz: a^3 = 3 W R/(2 E'), E' = E/(1 - nu^2))."""
    case = tmp_path / "ball.yaml"
    result = _invoke("init", "--contact", "-o", case)
    assert result.exit_code == 0 and case.exists()
    assert "tehl validate" in result.stdout
    checked = _invoke("validate", case)
    assert checked.exit_code == 0 and checked.stderr == ""
    assert "p_hertz 450 MPa, a 81.6 µm, b 81.6 µm" in checked.stdout
    solved = _invoke("run", case, "--grid", "33", "--jobs", "1")
    assert solved.exit_code == 0, solved.output
    result = read_result(tmp_path / "ball.h5")  # output.file of the template, next to the case
    point = result.points["contact"]
    assert point.converged and point.scalars["p_hertz"] == pytest.approx(0.450e9, rel=0.005)
    assert point.scalars["grid"] == 33  # a trial grid: its inlet is not lengthened (ehl/domain.py)


def test_the_gear_template_validates_and_every_default_is_stated(tmp_path):
    case = tmp_path / "gear.yaml"
    assert _invoke("init", "-o", case).exit_code == 0  # --gear is the default
    checked = _invoke("validate", case)
    assert checked.exit_code == 0
    assert all(line.startswith("derived: lubricant.") for line in checked.stderr.splitlines())  # the oil's SI values
    assert checked.stdout.startswith("ok: facegear: face gear pair (5 points S1..S5")
    loaded = load_case(case)
    assert loaded.solver.thermal == "full" and loaded.lubricant.rheology == "ree_eyring"
    assert loaded.materials.body_1.roughness == loaded.materials.body_2.roughness == 3.0e-7
    assert _invoke("contact", case).exit_code == 0
    # the commented-out optional keys, uncommented, give back the defaults: the same case
    text = case.read_text()
    uncommented = "\n".join(line.replace("# ", "", 1) if line.lstrip().startswith(("# density", "# thermal_cond",
                            "# specific_heat", "# roughness", "# tolerance", "# load_tolerance", "# max_cycles",
                            "# thermal_layers", "# load_sharing", "# transition_side", "# points")) else line
                            for line in text.splitlines())
    assert uncommented != text and yaml.safe_load(uncommented)["solver"]["tolerance"] == 1e-4
    explicit = load_case(_write(tmp_path / "explicit.yaml", uncommented))
    assert (explicit.solver, explicit.gear, explicit.materials) == (loaded.solver, loaded.gear, loaded.materials)


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


@pytest.mark.parametrize("options", [["--contact"], ["--gear"]])
def test_init_does_not_overwrite_without_force(tmp_path, monkeypatch, options):
    monkeypatch.chdir(tmp_path)
    Path("case.yaml").write_text("mine\n")
    result = _invoke("init", *options)
    assert result.exit_code == 2 and result.stderr.startswith("error: --output: got 'case.yaml'")
    assert Path("case.yaml").read_text() == "mine\n"
    assert _invoke("init", *options, "--force").exit_code == 0
    assert load_case("case.yaml").name in ("ball_on_disc", "facegear")


# The 90 deg design: 22/25/70 teeth, m 4 mm, 25 deg, 200 N m at 3000 rpm, VG 100 mineral oil at 80 degC
# (the template's oil), ground flanks R_q 0.3 um; the face width inside its undercut and pointing limits
# [0.13124, 0.15781] m that tehl validate names.
DESIGN_90 = {"pinion_teeth": "22", "shaper_teeth": "25", "face_gear_teeth": "70", "module": "0.004",
             "shaft_angle": "90.0", "pinion_addendum": "0.004", "face_gear_addendum": "0.004", "inner_radius": "0.133",
             "outer_radius": "0.155", "pinion_torque": "200.0", "pinion_speed": "3000.0"}


def test_the_gear_template_made_into_the_90_degree_design_runs_to_a_verdict(tmp_path):
    case = tmp_path / "design.yaml"
    assert _invoke("init", "-o", case).exit_code == 0
    lines = case.read_text().splitlines()
    for key, value in DESIGN_90.items():
        index = next(i for i, line in enumerate(lines) if line.startswith(f"  {key}:"))
        lines[index] = f"  {key}: {value}"
    case.write_text("\n".join(lines) + "\n")
    assert _invoke("validate", case).exit_code == 0
    solved = _invoke("run", case, "--grid", "33", "--thermal", "off", "--points", "S1,S5", "--jobs", "1")
    assert solved.exit_code in (0, 3), solved.output
    assert "warning: film parameter lambda = h_min/sigma below 1 at S1" in solved.stderr
    assert "verdict:\n  film                 lambda_min" in solved.stdout and ": boundary (full film" in solved.stdout
    assert "% recommended: film mu (solved) x sliding speed" in solved.stdout
    result = read_result(tmp_path / "design.h5", fields=False)
    assert result.verdict["lambda_min"] < 1.0 and result.verdict_labels["regime"] == "boundary"
    # the template's oil carries its FZG stages: scuffing (ISO/TS 6336-20, -21) and micropitting (-22) by formula
    # over the whole path; thermal off: no solved surface rise, so no "solved" scuffing beside them
    for line in ("  scuffing, flash      S_B ", "  scuffing, integral   S_intS ", "  micropitting         S_lambda "):
        assert line in solved.stdout
    assert result.verdict["scuffing_safety_flash"] > 1.0 and result.verdict["scuffing_safety_integral"] > 1.0
    assert "scuffing_safety_flash_solved" not in result.verdict and "micropitting_safety_solved" in result.verdict
    assert result.verdict["micropitting_safety"] == pytest.approx(
        result.verdict["lambda_gf_min"] / result.verdict["lambda_gfp"])
