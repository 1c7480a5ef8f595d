"""The resource guard (resources.py, docs/guarantees.md): the memory estimate of the ball-on-disc case on 4097^2
nodes lies in the 5-6 GB that run was seen to allocate (issue 44, measured outside this estimate); a run above the
machine's memory is refused before any solve, exit 2 naming the option, unless --force."""

from __future__ import annotations

from click.testing import CliRunner
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.cli import tehl
from facegear_tehl.points import contact_analysis
from facegear_tehl.resources import estimate

import synthetic

GB = 1e9


def _tasks(case_path, grid: int, points: int | None = None):
    case = load_case(case_path).with_grid(grid)
    selected = contact_analysis(case).points[:points]
    return [(p, case.lubricant, case.solver) for p in selected]


def test_the_estimate_of_a_4097_grid_is_what_that_run_allocated():
    assert 5 * GB <= estimate(_tasks(synthetic.BALL_ON_DISC, 4097), 1).memory <= 6 * GB


def test_the_estimate_grows_with_the_grid_and_the_workers():
    face_gear = synthetic.CASES / "facegear_110.yaml"
    memory = [estimate(_tasks(face_gear, grid), 1).memory for grid in (129, 257, 513)]
    assert memory == sorted(memory) and memory[2] > 2 * memory[1] - memory[0]  # nodes x4 per step, plus a base
    assert estimate(_tasks(face_gear, 257), 2).memory > estimate(_tasks(face_gear, 257), 1).memory


@pytest.fixture
def small_machine(monkeypatch):
    """A machine of 4 GB, and a solver that records its calls (none may happen before the guard)."""
    calls = []
    monkeypatch.setattr("facegear_tehl.resources.machine_memory", lambda: 4 * GB)
    monkeypatch.setattr("facegear_tehl.cli.machine_memory", lambda: 4 * GB)
    monkeypatch.setattr("facegear_tehl.run.ehl_solver",
                        lambda: (lambda point, lubricant, settings: calls.append(point) or synthetic.solution(point)))
    return calls


def test_a_run_above_the_machine_memory_is_refused_unless_forced(tmp_path, monkeypatch, small_machine):
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(tehl, ["run", str(synthetic.BALL_ON_DISC), "--grid", "4097", "--jobs", "1"])
    assert result.exit_code == 2, result.output
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith("error: --grid: got 4097; expected a run that fits this machine's memory (estimated peak "
                           "memory 5.5 GB"), line
    assert "this machine has 4.0 GB" in line and "--force" in line
    assert small_machine == [] and list(tmp_path.iterdir()) == []
    forced = CliRunner().invoke(tehl, ["run", str(synthetic.BALL_ON_DISC), "--grid", "4097", "--jobs", "1", "--force",
                                       "-o", "r.h5"])
    assert forced.exit_code == 0, forced.output
    assert "note: estimated peak memory 5.5 GB, roughly 7 min" in forced.stderr and len(small_machine) == 1


def test_a_sweep_above_the_machine_memory_is_refused(tmp_path, monkeypatch, small_machine):
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(tehl, ["sweep", str(synthetic.BALL_ON_DISC), "--grids", "1025,2049,4097",
                                       "--jobs", "1"])
    assert result.exit_code == 2, result.output
    assert result.stderr.strip().splitlines()[-1].startswith("error: --grids: got '1025,2049,4097'; expected a run "
                                                             "that fits this machine's memory")
    assert small_machine == []


def _study(tmp_path, values: int, keys: int = 1):
    study = tmp_path / "study.yaml"
    vary = "".join(f"  {key}: [{', '.join(str(1.0 + i) for i in range(values))}]\n"
                   for key in ("contact.load", "contact.entrainment_speed", "contact.slide_roll_ratio")[:keys])
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n{vary}", encoding="utf-8")
    return study


def test_a_huge_study_is_refused_at_once_with_its_size(tmp_path):
    """10^3 x 10^3 x 10^2 = 10^8 variants: refused before any is built (it printed nothing for 90 s)."""
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n"
                     f"  contact.load: [{', '.join(str(1.0 + i) for i in range(1000))}]\n"
                     f"  contact.entrainment_speed: [{', '.join(str(0.1 + i) for i in range(1000))}]\n"
                     f"  contact.slide_roll_ratio: [{', '.join(str(i / 100) for i in range(100))}]\n",
                     encoding="utf-8")
    result = CliRunner().invoke(tehl, ["study", str(study), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    assert result.stderr.strip() == ("error: vary: got '100000000 variants'; expected at most 10000 variants (the "
                                     "product of the lengths of the vary lists): split the study")


def test_a_large_study_says_its_size_before_validating(tmp_path, monkeypatch):
    monkeypatch.setattr("facegear_tehl.study.run_study", _stop)
    result = CliRunner().invoke(tehl, ["study", str(_study(tmp_path, 10, keys=2)), "-o", str(tmp_path / "out")])
    assert result.stderr.splitlines()[0] == "tehl study: 100 variants: validating each case (about 2 s)"


def _stop(*args, **kwargs):
    raise KeyboardInterrupt


def test_a_study_above_the_machine_memory_is_refused_unless_forced(tmp_path, monkeypatch, small_machine):
    """Two variants on 4097^2 nodes, two workers: 2 x 5.5 GB on a 4 GB machine."""
    monkeypatch.setattr("facegear_tehl.study.run_study", _stop)
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n  contact.load: [4.0, 9.0]\nset:\n  solver.grid: 4097\n",
                     encoding="utf-8")
    result = CliRunner().invoke(tehl, ["study", str(study), "--workers", "2", "-o", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith("error: --workers: got 2; expected a run that fits this machine's memory (estimated peak "
                           "memory 11."), line
    forced = CliRunner().invoke(tehl, ["study", str(study), "--workers", "2", "--force", "-o", str(tmp_path / "out")])
    assert forced.exit_code == 130 and "note: estimated peak memory 11." in forced.stderr  # then stopped (_stop)
