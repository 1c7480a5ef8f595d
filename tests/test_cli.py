"""Command line: bad input exits 2 with one line, runs write a result and a summary, exit codes, info,
interrupted runs leave no partial file. A synthetic solver stands in for the real one (`fake_solver`),
except in the end-to-end tests at the bottom."""

from __future__ import annotations

from dataclasses import replace
import json
from pathlib import Path
import signal
import subprocess
import sys

from click.testing import CliRunner
import numpy as np
import pytest

from facegear_tehl.cli import tehl
from facegear_tehl.results import read_result, write_result

import synthetic

CASE_TEXT = synthetic.BALL_ON_DISC.read_text()


class FakeSolver:
    """Stands in for `solve_point`: returns the synthetic solution, or raises `error`."""

    def __init__(self) -> None:
        self.converged = True
        self.error: Exception | None = None
        self.non_finite = False
        self.calls: list[tuple] = []

    def __call__(self, point, lubricant, settings):
        self.calls.append((point, lubricant, settings))
        if self.error is not None:
            raise self.error
        solution = synthetic.solution(point, converged=self.converged)
        if self.non_finite:
            solution.fields["pressure"].values[0, 0] = np.nan
        return solution


@pytest.fixture
def fake_solver(monkeypatch) -> FakeSolver:
    solver = FakeSolver()
    monkeypatch.setattr("facegear_tehl.run.ehl_solver", lambda: solver)
    return solver


def _case(folder: Path, text: str = CASE_TEXT, name: str = "case.yaml") -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def _invoke(*args: str):
    return CliRunner().invoke(tehl, [str(a) for a in args])


def _files(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


# ------------------------------------------------------------------------------------------ bad input

def _replace(old: str, new: str) -> str:
    assert old in CASE_TEXT
    return CASE_TEXT.replace(old, new, 1)


BAD_CASES = {
    "missing key": (_replace("  load: 6.272", "  # no load"), "contact.load", "required"),
    "unknown key": (_replace("  load: 6.272", "  laod: 6.0\n  load: 6.272"), "contact.laod", "did you mean 'load'"),
    "wrong type": (_replace("  load: 6.272", "  load: heavy"), "contact.load", "a finite number"),
    "negative load": (_replace("  load: 6.272", "  load: -6.272"), "contact.load", "positive"),
    "radius_y < radius_x": (_replace("  radius_y: 0.0127", "  radius_y: 0.001"), "contact.radius_y", "radius_x"),
    "poisson ratio 0.6": (_replace("poisson_ratio: 0.3", "poisson_ratio: 0.6"), "materials.body_1.poisson_ratio",
                          "< 0.5"),
    "grid 100": (_replace("  grid: 257", "  grid: 100"), "solver.grid", "2^n + 1"),
    "grid_y 100": (_replace("  grid: 257", "  grid: 257\n  grid_y: 100"), "solver.grid_y", "2^n + 1"),
    "grid_y 9": (_replace("  grid: 257", "  grid: 257\n  grid_y: 9"), "solver.grid_y", "at least solver.coarsest_grid"),
    "grid 9": (_replace("  grid: 257", "  grid: 9"), "solver.grid", "at least solver.coarsest_grid = 17 (its default)"),
    "no V-cycles": (_replace("  grid: 257", "  grid: 257\n  max_cycles: 0"), "solver.max_cycles", "1"),
    "domain without the contact": (_replace("x: [-4.5, 1.5]", "x: [-0.5, 1.5]"), "solver.domain.x", "containing"),
    "broken yaml": (_replace("  radius_x: 0.0127", "  radius_x: [0.0127"), "(file)", "syntax error at line 7"),
    "duplicate key": (_replace("  load: 6.272", "  load: 6.272\n  load: 7.0"), "(file)", "duplicate key 'load'"),
    "missing file": (None, "(file)", "readable case file"),
}


def _bad_case(folder: Path, kind: str) -> Path:
    text = BAD_CASES[kind][0]
    return folder / "case.yaml" if text is None else _case(folder, text)


def _assert_one_line_error(code: int, stderr: str, stdout: str, key: str, expected: str) -> None:
    assert code == 2, stderr
    lines = stderr.strip().splitlines()
    assert len(lines) == 1, stderr
    assert lines[0].startswith(f"error: {key}: "), lines[0]
    assert expected in lines[0]
    assert "Traceback" not in stderr + stdout


@pytest.mark.parametrize("command", ["run", "validate"])
@pytest.mark.parametrize("kind", BAD_CASES)
def test_bad_case_exits_2_with_one_line(tmp_path, monkeypatch, kind, command):
    monkeypatch.chdir(tmp_path)
    case = _bad_case(tmp_path, kind)
    before = _files(tmp_path)
    result = _invoke(command, case)
    _assert_one_line_error(result.exit_code, result.stderr, result.stdout, *BAD_CASES[kind][1:])
    assert _files(tmp_path) == before


@pytest.mark.parametrize("kind", BAD_CASES)
def test_bad_case_exits_2_in_a_subprocess(tmp_path, kind):
    case = _bad_case(tmp_path, kind)
    before = _files(tmp_path)
    process = subprocess.run([sys.executable, "-m", "facegear_tehl", "run", str(case)], cwd=tmp_path,
                             capture_output=True, text=True, timeout=60, check=False)
    _assert_one_line_error(process.returncode, process.stderr, process.stdout, *BAD_CASES[kind][1:])
    assert _files(tmp_path) == before


@pytest.mark.parametrize(
    "options, key, expected",
    [
        (["--grid", "100"], "--grid", "2^n + 1"),
        (["--grid", "9"], "--grid", "at least solver.coarsest_grid"),
        (["-o", "."], "--output", "not a directory"),
        (["--jobs", "0"], "--jobs", ">= 1"),
        (["--accuracy", "200%"], "--accuracy", "from 0.1% to 50%"),
        (["--accuracy", "one percent"], "--accuracy", "e.g. 0.01 or 1%"),
        (["--accuracy", "1%", "--grid", "129"], "--grid", "the target chooses the grid"),
    ],
)
def test_bad_options_exit_2(tmp_path, monkeypatch, options, key, expected):
    monkeypatch.chdir(tmp_path)
    case = _case(tmp_path)
    result = _invoke("run", case, *options)
    _assert_one_line_error(result.exit_code, result.stderr, result.stdout, key, expected)
    assert _files(tmp_path) == ["case.yaml"]


@pytest.mark.parametrize("points, expected", [("S1,contact", "among: contact"), (",", "at least one point"),
                                              ("contact,contact", "each point named once")])
def test_bad_points_exit_2(tmp_path, monkeypatch, points, expected):
    monkeypatch.chdir(tmp_path)
    result = _invoke("run", _case(tmp_path), "--points", points)
    _assert_one_line_error(result.exit_code, result.stderr, result.stdout, "--points", expected)
    assert _files(tmp_path) == ["case.yaml"]


GEAR_TEXT = (synthetic.CASES / "facegear_110.yaml").read_text()


def test_every_problem_of_a_case_is_named_at_once(tmp_path):
    """Five independent mistakes in four blocks: five lines, in file order, and no file written."""
    text = (CASE_TEXT.replace("  load: 6.272", "  load: heavy")
            .replace("  entrainment_speed: 0.6383", "  entrainment_speed: -1")
            .replace("body_2: {elastic_modulus: 2.0e11, poisson_ratio: 0.3", "body_2: {elastic_modulus: 2.0e11, "
                     "poisson_ratio: 0.7")
            .replace("  rheology: newtonian", "  rheology: newtonion")
            .replace("  grid: 257", "  grid: 100"))
    result = _invoke("run", _case(tmp_path, text), "-o", tmp_path / "r.h5")
    assert result.exit_code == 2 and "Traceback" not in result.stderr
    lines = result.stderr.splitlines()
    assert [line.split(":")[1].strip() for line in lines] == [
        "contact.load", "contact.entrainment_speed", "materials.body_2.poisson_ratio", "lubricant.rheology",
        "solver.grid"]
    assert all(line.startswith("error: ") for line in lines)
    assert "expected a finite number" in lines[0] and "expected a positive number" in lines[1]
    assert _files(tmp_path) == ["case.yaml"]


@pytest.mark.parametrize("kind, old, new, key, meant", [
    ("gear", "  pinion_torque: 500.0", "  pinion_torqe: 500.0", "gear.pinion_torqe", "pinion_torque"),
    ("contact", "  load: 6.272", "  laod: 6.272", "contact.laod", "load"),
    ("contact", "lubricant:", "lubricnt:", "lubricnt", "lubricant"),
])
def test_a_misspelt_required_key_is_named_with_did_you_mean(tmp_path, kind, old, new, key, meant):
    """Not '<meant> is missing', but the key written, with the one meant (issue 15)."""
    text = (GEAR_TEXT if kind == "gear" else CASE_TEXT).replace(old, new, 1)
    result = _invoke("validate", _case(tmp_path, text))
    _assert_one_line_error(result.exit_code, result.stderr, result.stdout, key, f"did you mean '{meant}'?")
    assert "required and missing" in result.stderr


def test_a_yaml_syntax_error_names_its_line_and_the_parser_message(tmp_path):
    text = CASE_TEXT.replace("  load: 6.272", "  load: 6.272\n\tentrainment_speed: 1.0")  # a tab indents
    line = next(i for i, row in enumerate(text.splitlines(), 1) if row.startswith("\tentrainment_speed"))
    result = _invoke("validate", _case(tmp_path, text))
    _assert_one_line_error(result.exit_code, result.stderr, result.stdout, "(file)",
                           f"syntax error at line {line}, column 1")
    assert "found character '\\t' that cannot start any token" in result.stderr
    assert "got 'entrainment_speed: 1.0'" in result.stderr  # the line, without its comment


@pytest.mark.parametrize("kind, old, new, key, hint", [
    ("contact", "inlet_temperature: 40.0", "inlet_temperature: 313", "lubricant.inlet_temperature", "write 39.85"),
    ("gear", "pinion_torque: 500.0", "pinion_torque: 500000", "gear.pinion_torque", "N mm"),
    ("gear", "pinion_speed: 3000.0", "pinion_speed: 3.0e5", "gear.pinion_speed", "rpm"),
    ("contact", "viscosity: 0.04", "viscosity: 40", "lubricant.viscosity", "mPa s"),
    ("contact", "entrainment_speed: 0.6383", "entrainment_speed: 638.3", "contact.entrainment_speed", "mm/s"),
    # 257 nodes over 2e6 semi-axes: 2.6e-4 nodes across the contact (it passed the checks and ran away on every grid)
    ("contact", "x: [-4.5, 1.5]", "x: [-1.0e6, 1.0e6]", "solver.domain.x", "no film is resolved"),
])
def test_unusual_values_are_accepted_with_a_warning(tmp_path, kind, old, new, key, hint):
    """313 degC is kelvin read as degC (313.15 K = 40 degC); a torque in N mm, a viscosity in mPa s, ..."""
    base = GEAR_TEXT if kind == "gear" else CASE_TEXT
    assert old in base
    result = _invoke("validate", _case(tmp_path, base.replace(old, new, 1)))
    assert result.exit_code == 0, result.stderr
    warnings = result.stderr.splitlines()
    assert len(warnings) == 1 and warnings[0].startswith(f"warning: {key}: ") and hint in warnings[0], warnings
    assert result.stdout.startswith("ok: ")
    assert _invoke("validate", _case(tmp_path, base)).stderr == ""  # the shipped cases: no warning


def test_validate_prints_one_ok_line():
    result = _invoke("validate", synthetic.BALL_ON_DISC)
    assert result.exit_code == 0
    lines = result.stdout.strip().splitlines()
    assert len(lines) == 1
    assert lines[0].startswith("ok: ball_on_disc: plain contact")
    assert "p_hertz 450 MPa" in lines[0] and "grid 257x257" in lines[0] and "viscosity roelands" in lines[0]


def test_the_command_line_loads_no_solver_kernels():
    """`tehl validate` starts in ~0.3 s because the command line imports none of the solver's Numba kernels (loading
    them costs ~0.5 s): a light module imported at the top of cli.py (as `tehl sweep`'s tables once imported the
    error-estimate module with the formal order) would triple it. numba, the kernel modules, h5py, SciPy (its FFT
    with the scipy.special it imports: about 0.1 s) and Dask (`tehl study` alone) stay unloaded."""
    probe = ("import sys, facegear_tehl.cli; print(sorted(m for m in sys.modules if m in ('numba', 'h5py', "
             "'matplotlib', 'scipy', 'dask', 'distributed') or m.startswith('facegear_tehl.ehl.')))")
    loaded = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True).stdout
    expected = ["closure", "domain", "relaxation", "retry", "richardson", "scaling", "stopwatch", "tuning",
                "unresolved"]  # no kernels
    assert loaded.strip() == str([f"facegear_tehl.ehl.{name}" for name in expected])


# ---------------------------------------------------------------------------- runs (synthetic solver)

def test_run_writes_the_result_and_a_summary(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    result = _invoke("run", synthetic.BALL_ON_DISC)
    assert result.exit_code == 0, result.output
    assert _files(tmp_path) == ["ball_on_disc.h5"]  # <case name>.h5 in the current directory
    assert "[1/1] contact: converged (7 cycles, 0.25 s, solved on 33x17)" in result.stderr
    title, header, _, row = result.stdout.splitlines()[:4]
    assert title.endswith(":")
    assert header.split()[:4] == ["point", "converged", "h_c", "µm"]
    assert "err h_min %" in header
    cells = row.split()
    assert cells[:4] == ["contact", "yes", "0.15", "0.09"]
    # wall time, the error estimates of a file without bounds: h_c 0.40 %, none of p_max, dT_max, dT_min, mu
    assert cells[-7:] == ["0.25", "0.40", "-", "-", "-", "-", "-"]
    assert "result: ball_on_disc.h5 (status ok)" in result.stdout
    written = read_result(tmp_path / "ball_on_disc.h5")
    assert written.status == "ok" and written.case_yaml == CASE_TEXT and written.overrides == {}


def test_run_output_paths(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    case = _case(tmp_path, CASE_TEXT + "output: {file: results/bod.h5}\n", name="cases/case.yaml")
    assert _invoke("run", case).exit_code == 0
    assert (tmp_path / "cases/results/bod.h5").is_file()  # output.file is relative to the case file
    assert _invoke("run", case, "-o", "out/x.h5").exit_code == 0
    assert (tmp_path / "out/x.h5").is_file()


def test_run_grid_and_points_reach_the_solver(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    result = _invoke("run", synthetic.BALL_ON_DISC, "--grid", "33", "--points", "contact")
    assert result.exit_code == 0, result.output
    (point, lubricant, settings), = fake_solver.calls
    assert settings.grid == 33 and point.name == "contact" and lubricant.viscosity == 0.04
    assert point.load == 6.272 and point.radius_x == 0.0127
    assert read_result(tmp_path / "ball_on_disc.h5").overrides == {"grid": 33, "points": ["contact"]}
    assert "tehl run: ball_on_disc: contact on a 33x33 grid, thermal off" in result.stderr


def _with_beta(folder: Path) -> Path:
    """The ball-on-disc case (thermal: off) with the oil's temperature-viscosity coefficient a thermal model needs."""
    text = synthetic.BALL_ON_DISC.read_text().replace("  rheology: newtonian\n",
                                                       "  rheology: newtonian\n  temperature_viscosity: 0.042\n")
    path = folder / "ball_on_disc.yaml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("thermal", ["reduced", "full", "auto"])
def test_run_thermal_overrides_the_case(tmp_path, monkeypatch, fake_solver, thermal):
    monkeypatch.chdir(tmp_path)
    result = _invoke("run", _with_beta(tmp_path), "--thermal", thermal)  # the case says thermal: off
    assert result.exit_code == 0, result.output
    (_, _, settings), = fake_solver.calls
    assert settings.thermal == thermal
    written = read_result(tmp_path / "ball_on_disc.h5")
    assert written.overrides == {"thermal": thermal} and written.models["thermal"] == thermal
    assert f"thermal {thermal}" in result.stderr.splitlines()[0]


@pytest.mark.parametrize("thermal", ["reduced", "full", "auto"])
def test_a_thermal_model_without_the_temperature_viscosity_coefficient_is_bad_input(tmp_path, monkeypatch,
                                                                                       fake_solver, thermal):
    # the oil's viscosity would not fall with the temperature the thermal model computes (beta = 0 unless given)
    monkeypatch.chdir(tmp_path)
    result = _invoke("run", synthetic.BALL_ON_DISC, "--thermal", thermal)
    _assert_one_line_error(result.exit_code, result.stderr, result.stdout, "lubricant.temperature_viscosity",
                           f"with --thermal {thermal} (or thermal off)")
    assert fake_solver.calls == [] and _files(tmp_path) == []
    case = tmp_path / "case.yaml"
    case.write_text(synthetic.BALL_ON_DISC.read_text().replace("thermal: off", f"thermal: {thermal}"))
    result = _invoke("validate", case)
    _assert_one_line_error(result.exit_code, result.stderr, result.stdout, "lubricant.temperature_viscosity",
                           f"with solver.thermal {thermal} (or thermal off)")
    explicit = tmp_path / "explicit.yaml"  # an explicit 0 is taken as meant
    explicit.write_text(case.read_text().replace("  rheology: newtonian\n",
                                                 "  rheology: newtonian\n  temperature_viscosity: 0\n"))
    assert _invoke("validate", explicit).exit_code == 0


def test_run_rejects_an_unknown_thermal_model(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    result = _invoke("run", synthetic.BALL_ON_DISC, "--thermal", "warm")
    _assert_one_line_error(result.exit_code, result.stderr, result.stdout, "--thermal", "off, reduced, full, auto")
    assert fake_solver.calls == [] and _files(tmp_path) == []


@pytest.mark.parametrize("command", ["run", "sweep", "validate", "contact", "info", "plot", "init"])
def test_every_help_shows_examples(command):
    result = _invoke(command, "--help")
    assert result.exit_code == 0
    examples = result.stdout.split("Example")[1].splitlines()[1:]
    assert examples and all(line.strip().startswith("tehl ") for line in examples if line.strip())
    assert any(f"tehl {command}" in line for line in examples)


def test_not_converged_exits_3_and_writes_a_flagged_result(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    fake_solver.converged = False
    result = _invoke("run", synthetic.BALL_ON_DISC)
    assert result.exit_code == 3
    assert "warning: not converged: contact: residual 1e-3" in result.stderr
    written = read_result(tmp_path / "ball_on_disc.h5")
    assert written.status == "not_converged" and not written.points["contact"].converged
    assert "contact  " in result.stdout and " no " in result.stdout


def test_failed_point_exits_1_and_writes_a_flagged_result(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    fake_solver.error = FloatingPointError("overflow in the elastic deflection")
    result = _invoke("run", synthetic.BALL_ON_DISC)
    assert result.exit_code == 1
    assert "Traceback" not in result.output
    assert "error: contact: failed: FloatingPointError: overflow" in result.stderr
    written = read_result(tmp_path / "ball_on_disc.h5")
    assert written.status == "failed" and written.points["contact"].fields == {}
    cells = result.stdout.splitlines()[3].split()[2:]  # every value of the failed point's row (after the title)
    assert len(cells) >= 14 and set(cells) == {"-"}


def test_unexpected_error_exits_1_without_a_file(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    fake_solver.non_finite = True
    result = _invoke("run", synthetic.BALL_ON_DISC)
    assert result.exit_code == 1
    lines = result.stderr.strip().splitlines()
    assert lines[-1].startswith("error: NonFiniteError: /points/contact/pressure: refusing to write 1 NaN")
    assert lines[-1].endswith("(an unexpected error: tehl --debug with the same arguments shows where; please report "
                              "it with that output)")
    assert "Traceback" not in result.output
    assert _files(tmp_path) == []


FACE_GEAR = synthetic.CASES / "facegear_110.yaml"


def test_validate_a_face_gear_case():
    result = _invoke("validate", FACE_GEAR)
    assert result.exit_code == 0
    assert result.stdout.startswith("ok: facegear_110: face gear pair (5 points S1..S5, p_hertz ")


def test_face_gear_run_writes_points_and_the_contact_path(tmp_path, fake_solver):
    result = _invoke("run", FACE_GEAR, "--points", "S3,S1", "-o", tmp_path / "g.h5", "--jobs", "1")
    assert result.exit_code == 0, result.output
    assert [call[0].name for call in fake_solver.calls] == ["S1", "S3"]  # in the order of the path
    assert "[2/2] S3: converged" in result.stderr
    written = read_result(tmp_path / "g.h5")
    assert list(written.points) == ["S1", "S3"]
    assert written.points["S3"].scalars["path_coordinate"] == 0.0  # S3 is the pitch point
    assert written.points["S1"].scalars["path_coordinate"] < 0.0
    assert written.contact["s"].units == "m" and written.contact["u1"].values.shape[1] == 2
    assert written.contact_scalars["contact_ratio"] > 1.0 and written.contact_units["normal_load"] == "N"


def test_debug_shows_the_traceback(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    fake_solver.non_finite = True
    result = CliRunner().invoke(tehl, ["--debug", "run", str(synthetic.BALL_ON_DISC)])
    assert result.exit_code == 1
    assert "Traceback" in result.stderr and "NonFiniteError" in result.stderr


def test_run_case_api(fake_solver):
    from facegear_tehl import load_case, run_case

    seen = []
    run = run_case(load_case(synthetic.BALL_ON_DISC), grid=65, progress=lambda *args: seen.append(args))
    assert run.status == "ok" and run.case.solver.grid == 65 and run.overrides == {"grid": 65}
    assert [p.name for p in run.points] == ["contact"]
    assert seen == [(run.points[0], 1, 1)]


# ------------------------------------------------------------------------------------------- info

@pytest.fixture
def result_file(tmp_path) -> Path:
    return write_result(synthetic.run_result(), tmp_path / "r.h5")


def test_info_json_gives_the_scalars_in_si(result_file):
    result = _invoke("info", result_file, "--json")
    assert result.exit_code == 0
    data = json.loads(result.stdout)
    assert data["case"] == "ball_on_disc" and data["status"] == "ok"
    point = data["points"]["contact"]
    assert point["h_c"] == synthetic.H_C and point["iterations"] == synthetic.CYCLES
    assert point["converged"] is True
    assert data["units"]["contact"]["p_max"] == "Pa"


def test_info_table(result_file):
    """Engineering units by default: h_c = 1.5e-7 m is 0.15 µm, p_hertz = 0.450 GPa is 450 MPa (a 81.6 µm = 0.0816
    mm), the relative load error 2.5e-6 is 2.5e-4 %; --si gives the file's values."""
    result = _invoke("info", result_file)
    assert result.exit_code == 0
    lines = result.stdout.splitlines()
    assert lines[0].split() == ["case", "ball_on_disc"]
    row = {line.split()[0]: line.split()[1:] for line in lines if line.strip()}
    assert row["h_c"] == ["µm", "0.15"] and row["h_min"] == ["µm", "0.09"]
    assert row["p_hertz"][0] == "MPa" and float(row["p_hertz"][1]) == pytest.approx(450, abs=0.5)
    assert row["a"][0] == "mm" and float(row["a"][1]) == pytest.approx(0.0816, abs=1e-4)
    assert row["load_error"] == ["%", "0.00025"] and row["error_estimate_h_c"] == ["%", "0.4"]
    assert row["converged"] == ["yes"]
    assert [line.split()[0] for line in lines if line.split()[1:2] == ["unit"]] == ["film", "pressure", "convergence"]
    si = {line.split()[0]: line.split()[1:] for line in _invoke("info", result_file, "--si").stdout.splitlines()
          if line.strip()}
    assert si["h_c"] == ["m", "1.5e-07"] and si["load_error"] == ["1", "2.5e-06"]


def test_info_shows_round_off_as_zero(tmp_path):
    """A heat power of 1e-18 W next to one of 0.05 W is round-off (S3, pure rolling, in the default case)."""
    run = synthetic.run_result()
    point = run.points[0]
    scalars = {**point.scalars, "steady_power_1": (1.1e-18, "W"), "steady_power_2": (0.05, "W"),
               "dT_min": (-3e-9, "K")}
    path = write_result(replace(run, points=(replace(point, scalars=scalars),)), tmp_path / "r.h5")
    row = {line.split()[0]: line.split()[1:] for line in _invoke("info", path).stdout.splitlines() if line.strip()}
    assert row["steady_power_1"] == ["W", "0"] and row["steady_power_2"] == ["W", "0.05"]
    assert row["dT_min"] == ["K", "-3e-09"]  # alone of its unit in its table: no scale to be round-off of
    assert _invoke("info", path, "--si").stdout.count("1.1e-18") == 1


def test_info_says_which_thermal_model_auto_chose_and_why(tmp_path):
    """A point solved with `thermal: auto` lists the model it ran and the reason the solver gave (ehl/thermal.py
    thermal_choice); a point whose model was given (`solver.thermal: full`) adds no such line."""
    run = synthetic.run_result()
    point = run.points[0]
    reason = "auto: heating number G 0.0021; predicted error of off 0.75 % < 1 %"
    auto = replace(point, models={**point.models, "thermal": "off", "thermal_reason": reason})
    text = _invoke("info", write_result(replace(run, points=(auto,)), tmp_path / "auto.h5")).stdout
    assert f"  contact: off ({reason})" in text.splitlines()
    given = replace(point, models={**point.models, "thermal": "full", "thermal_reason": "solver.thermal: full"})
    assert "thermal: auto" not in _invoke("info", write_result(replace(run, points=(given,)), tmp_path / "g.h5")).stdout


@pytest.mark.parametrize("content", [b"not hdf5", None])
def test_info_rejects_what_is_not_a_result(tmp_path, content):
    path = tmp_path / "r.h5"
    if content is not None:
        path.write_bytes(content)
    result = _invoke("info", path)
    assert result.exit_code == 2
    assert result.stderr.startswith("error: ") and len(result.stderr.strip().splitlines()) == 1
    process = subprocess.run([sys.executable, "-m", "facegear_tehl", "info", str(path)], capture_output=True,
                             text=True, timeout=60, check=False)
    assert process.returncode == 2 and "Traceback" not in process.stderr


# -------------------------------------------------------------------------------- interrupted runs

@pytest.mark.parametrize("signum, code", [(signal.SIGTERM, 128 + signal.SIGTERM), (signal.SIGINT, 128 + signal.SIGINT)])
def test_interrupted_run_keeps_the_previous_result(tmp_path, signum, code):
    target = tmp_path / "r.h5"
    write_result(synthetic.run_result(), target)
    before = target.read_bytes()
    run_with_fake_solver = """
        from facegear_tehl import cli, run
        run.ehl_solver = lambda: (lambda point, lubricant, settings: synthetic.solution(point))
        cli.main(sys.argv[1:])
    """
    args = ["run", str(synthetic.BALL_ON_DISC), "-o", str(target)]
    returncode, stderr = synthetic.interrupt_while_writing(run_with_fake_solver, args, tmp_path, signum)
    assert returncode == code
    assert "Traceback" not in stderr
    assert target.read_bytes() == before
    assert _files(tmp_path) == ["r.h5"]


# ------------------------------------------------------------------------ end to end (real solver)

def _check_ball_on_disc(path: Path) -> None:
    result = read_result(path)
    point = result.points["contact"]
    assert result.status in ("ok", "not_converged")
    assert result.overrides["grid"] == 33
    assert 0.0 < point.scalars["h_min"] < point.scalars["h_c"] < 1e-6
    assert point.fields["pressure"].values.shape == (33, 33)
    assert point.scalars["p_max"] == pytest.approx(450e6, rel=0.3)


def test_run_end_to_end(tmp_path):
    result = _invoke("run", synthetic.BALL_ON_DISC, "--grid", "33", "-o", tmp_path / "r.h5")
    assert result.exit_code in (0, 3), result.output
    assert "[1/1] contact:" in result.stderr
    _check_ball_on_disc(tmp_path / "r.h5")


def test_run_end_to_end_in_a_subprocess(tmp_path):
    process = subprocess.run(["tehl", "run", str(synthetic.BALL_ON_DISC), "--grid", "33", "-o", "r.h5"],
                             cwd=tmp_path, capture_output=True, text=True, timeout=300, check=False)
    assert process.returncode in (0, 3), process.stderr
    _check_ball_on_disc(tmp_path / "r.h5")
    info = subprocess.run([sys.executable, "-m", "facegear_tehl", "info", "r.h5", "--json"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=60, check=False)
    assert info.returncode == 0
    assert json.loads(info.stdout)["points"]["contact"]["h_c"] > 0.0


def test_face_gear_point_end_to_end(tmp_path):
    result = _invoke("run", FACE_GEAR, "--grid", "33", "--points", "S3", "-o", tmp_path / "g.h5")
    assert result.exit_code in (0, 3), result.output
    point = read_result(tmp_path / "g.h5").points["S3"]
    assert 0.0 < point.scalars["h_min"] < point.scalars["h_c"] < 1e-5
    assert point.scalars["a"] / point.scalars["b"] > 10.0  # elongated ellipse of the face gear


def test_run_case_api_end_to_end(tmp_path):
    from facegear_tehl import load_case, read_result, run_case

    run = run_case(load_case(synthetic.BALL_ON_DISC), grid=33)
    write_result(run, tmp_path / "r.h5")
    _check_ball_on_disc(tmp_path / "r.h5")
    assert read_result(tmp_path / "r.h5").points["contact"].scalars["h_c"] == run.points[0].scalar("h_c")


def test_grid_override_keeps_the_aspect_of_grid_y(tmp_path):
    """--grid and tehl sweep scale solver.grid_y with solver.grid, never below solver.coarsest_grid."""
    from facegear_tehl.case import load_case

    case = load_case(_case(tmp_path, _replace("  grid: 257", "  grid: 257\n  grid_y: 65")))
    assert case.solver.nodes_y == 65
    assert case.with_grid(129).solver.grid_y == 33 and case.with_grid(513).solver.grid_y == 129
    assert case.with_grid(33).solver.grid_y == 17 and case.with_grid(17).solver.grid_y == 17  # 9 and 5 scaled
