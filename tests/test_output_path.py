"""The output-path policy of every command that writes (docs/guarantees.md): never an input file, never an existing
file tehl did not write unless --force, a case's output.file only inside its own folder; each refusal exits 2 with
one line naming the option or key, and leaves every file as it was."""

from __future__ import annotations

import os
from pathlib import Path

from click.testing import CliRunner
import pytest

from facegear_tehl.cli import tehl
from facegear_tehl.results import read_result, write_result

import synthetic

CASE_TEXT = synthetic.BALL_ON_DISC.read_text()


@pytest.fixture
def fake_solver(monkeypatch):
    """The synthetic solution instead of a solve (no Numba kernels)."""
    monkeypatch.setattr("facegear_tehl.run.ehl_solver",
                        lambda: (lambda point, lubricant, settings: synthetic.solution(point)))


def _invoke(*args):
    return CliRunner().invoke(tehl, [str(a) for a in args])


def _case(folder: Path, text: str = CASE_TEXT, name: str = "c.yaml") -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def _refused(result, key: str) -> None:
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {key}: got "), result.stderr
    assert "Traceback" not in result.output


@pytest.mark.parametrize("link", ["same path", "relative path", "hard link", "symbolic link"])
def test_run_never_writes_over_its_own_case(tmp_path, monkeypatch, fake_solver, link):
    monkeypatch.chdir(tmp_path)
    case = _case(tmp_path)
    target = {"same path": case, "relative path": Path("sub/../c.yaml"), "hard link": tmp_path / "hard.h5",
              "symbolic link": tmp_path / "soft.h5"}[link]
    (tmp_path / "sub").mkdir()
    if link == "hard link":
        os.link(case, target)
    elif link == "symbolic link":
        target.symlink_to(case)
    result = _invoke("run", case, "-o", target, "--force")  # not even with --force
    _refused(result, "--output")
    assert "input" in result.stderr
    assert case.read_text(encoding="utf-8") == CASE_TEXT


def test_run_refuses_an_existing_file_it_did_not_write_unless_forced(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    case = _case(tmp_path)
    notes = tmp_path / "notes.txt"
    notes.write_text("my notes\n")
    result = _invoke("run", case, "-o", notes)
    _refused(result, "--output")
    assert "--force" in result.stderr and notes.read_text() == "my notes\n"
    assert _invoke("run", case, "-o", notes, "--force").exit_code == 0
    assert read_result(notes).status == "ok"


def test_run_never_writes_over_a_fifo(tmp_path, monkeypatch, fake_solver):
    """A FIFO (like a device node) is no file to replace, not even with --force; reading it to see whose file it
    is would wait for a writer for ever."""
    monkeypatch.chdir(tmp_path)
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    _refused(_invoke("run", _case(tmp_path), "-o", fifo, "--force"), "--output")
    assert fifo.is_fifo()


def test_run_replaces_a_result_file_of_its_own(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    target = write_result(synthetic.run_result(converged=False), tmp_path / "r.h5")
    assert read_result(target).status == "not_converged"
    assert _invoke("run", _case(tmp_path), "-o", target).exit_code == 0
    assert read_result(target).status == "ok"


@pytest.mark.parametrize("where", ["../victim.txt", "/tmp/victim.h5", "sub/../../victim.h5"])
def test_output_file_of_a_case_stays_in_its_folder(tmp_path, monkeypatch, fake_solver, where):
    monkeypatch.chdir(tmp_path)
    case = _case(tmp_path / "cases", CASE_TEXT + f"output: {{file: {where}}}\n")
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me\n")
    result = _invoke("run", case)
    _refused(result, "output.file")
    assert "inside the case's folder" in result.stderr
    assert victim.read_text() == "keep me\n" and sorted(p.name for p in tmp_path.iterdir()) == ["cases", "victim.txt"]


def test_output_file_inside_the_case_folder_is_written_there(tmp_path, monkeypatch, fake_solver):
    monkeypatch.chdir(tmp_path)
    case = _case(tmp_path / "cases", CASE_TEXT + "output: {file: results/../r.h5}\n")
    assert _invoke("run", case).exit_code == 0
    assert read_result(tmp_path / "cases" / "r.h5").status == "ok"


def test_sweep_never_writes_over_its_case_nor_a_foreign_csv(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    case = _case(tmp_path, name="c.h5")  # a case file named like the sweep's output
    _refused(_invoke("sweep", case, "-o", case, "--force"), "--output")
    data = tmp_path / "data.csv"
    data.write_text("time,temperature\n0,20\n")
    _refused(_invoke("sweep", case, "-o", tmp_path / "data.h5"), "--output")  # its CSV would replace data.csv
    assert case.read_text(encoding="utf-8") == CASE_TEXT and data.read_text() == "time,temperature\n0,20\n"


@pytest.mark.parametrize("kind", ["foreign file", "directory"])
def test_study_refuses_a_folder_whose_index_it_did_not_write(tmp_path, kind):
    out = tmp_path / "out"
    out.mkdir()
    index = out / "index.csv"
    if kind == "directory":
        index.mkdir()
    else:
        index.write_text("name,phone\n")
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n  contact.load: [4.0]\n", encoding="utf-8")
    result = _invoke("study", study, "-o", out)
    _refused(result, "-o")
    assert "index.csv" in result.stderr
    assert index.is_dir() if kind == "directory" else index.read_text() == "name,phone\n"


def test_plot_refuses_an_existing_file_as_its_folder(tmp_path):
    source = write_result(synthetic.run_result(), tmp_path / "r.h5")
    before = source.read_bytes()
    _refused(_invoke("plot", source, "-o", source), "--output")
    assert source.read_bytes() == before


@pytest.mark.parametrize("command", ["validate", "run"])
def test_a_case_file_that_is_a_fifo_is_refused_at_once(tmp_path, monkeypatch, command):
    """Reading a FIFO as the case would wait for a writer for ever: it is refused naming the file, exit 2."""
    monkeypatch.chdir(tmp_path)
    fifo = tmp_path / "case.yaml"
    os.mkfifo(fifo)
    result = _invoke(command, fifo)
    assert result.exit_code == 2 and "a regular file, not a directory, device or FIFO" in result.stderr
