"""Temporary files a killed writer left beside its target are removed by the next write of that target
(atomic_files.py, docs/guarantees.md); those of a writer still running are left alone."""

from __future__ import annotations

import signal
import subprocess
import sys

from click.testing import CliRunner

from facegear_tehl.cli import tehl
from facegear_tehl.results import read_result, write_result

import synthetic


def _ended_pid() -> int:
    """The pid of a process that has ended."""
    process = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                             text=True, check=True)
    return int(process.stdout)


def test_the_next_write_removes_a_dead_writers_temporary_file_only(tmp_path):
    target = tmp_path / "r.h5"
    dead = tmp_path / f".r.h5.{_ended_pid()}-0123456789ab.tmp"
    dead.write_bytes(b"half a file")
    with subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"]) as alive_writer:
        alive = tmp_path / f".r.h5.{alive_writer.pid}-0123456789ab.tmp"
        alive.write_bytes(b"being written")
        other = tmp_path / f".s.h5.{_ended_pid()}-0123456789ab.tmp"  # another target's
        other.write_bytes(b"")
        write_result(synthetic.run_result(), target)
        alive_writer.kill()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([target.name, alive.name, other.name])


def test_a_run_killed_while_writing_leaves_a_file_the_next_run_removes(tmp_path, monkeypatch):
    target = tmp_path / "r.h5"
    write_result(synthetic.run_result(), target)
    run_with_fake_solver = """
        from facegear_tehl import cli, run
        run.ehl_solver = lambda: (lambda point, lubricant, settings: synthetic.solution(point))
        cli.main(sys.argv[1:])
    """
    args = ["run", str(synthetic.BALL_ON_DISC), "-o", str(target)]
    code, _ = synthetic.interrupt_while_writing(run_with_fake_solver, args, tmp_path, signal.SIGKILL)
    assert code == -signal.SIGKILL and len(list(tmp_path.iterdir())) == 2  # the target and the killed one's
    monkeypatch.setattr("facegear_tehl.run.ehl_solver",
                        lambda: (lambda point, lubricant, settings: synthetic.solution(point)))
    assert CliRunner().invoke(tehl, ["run", str(synthetic.BALL_ON_DISC), "-o", str(target)]).exit_code == 0
    assert [p.name for p in tmp_path.iterdir()] == ["r.h5"] and read_result(target).status == "ok"
