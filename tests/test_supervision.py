"""Worker loss (docs/guarantees.md): a worker of `tehl run --jobs 2` killed with SIGKILL (as the out-of-memory
killer does) costs no point, its solves retried in a fresh pool; a point whose worker dies whenever it is solved,
even alone, is recorded as failed with a sentence saying what to do, the others solved; a run that lost points
never replaces a result file holding more converged points; killing the parent ends its workers."""

from __future__ import annotations

from contextlib import contextmanager
import os
from pathlib import Path
import signal
import subprocess
import sys
import textwrap
import time

from click.testing import CliRunner

from facegear_tehl.case import load_case
from facegear_tehl.cli import tehl
from facegear_tehl.results import read_result
from facegear_tehl.run import run_case

import synthetic

FACE_GEAR = synthetic.CASES / "facegear_110.yaml"
MARKERS = "TEHL_TEST_MARKERS"  # the folder where the killing solvers record their first attempts


def _killed_once(point, lubricant, settings):
    """S2's worker dies (SIGKILL) at its first full-grid attempt; every other solve is the synthetic one."""
    marker = Path(os.environ[MARKERS]) / point.name
    if point.name == "S2" and settings.grid > settings.coarsest_grid and not marker.exists():
        marker.touch()
        os.kill(os.getpid(), signal.SIGKILL)
    return synthetic.solution(point)


def _synthetic(point, lubricant, settings):
    return synthetic.solution(point)


def _always_killed(point, lubricant, settings):
    """S2's worker dies at every full-grid attempt."""
    if point.name == "S2" and settings.grid > settings.coarsest_grid:
        os.kill(os.getpid(), signal.SIGKILL)
    return synthetic.solution(point)


def test_a_killed_worker_costs_no_point(tmp_path, monkeypatch):
    monkeypatch.setenv(MARKERS, str(tmp_path))
    run = run_case(load_case(FACE_GEAR), jobs=2, solver=_killed_once)
    assert (tmp_path / "S2").exists()  # the worker did die
    assert run.status == "ok" and run.failed == ()
    assert [p.name for p in run.points] == ["S1", "S2", "S3", "S4", "S5"] and all(p.fields for p in run.points)


def test_a_point_whose_worker_dies_twice_fails_and_the_others_are_solved():
    run = run_case(load_case(FACE_GEAR), jobs=2, solver=_always_killed)
    assert run.failed == ("S2",)
    s2 = next(p for p in run.points if p.name == "S2")
    assert "worker process was lost 3 times, the last time solving this point alone" in s2.message
    assert all(p.converged and p.fields for p in run.points if p.name != "S2")


def test_a_run_that_lost_points_never_replaces_a_better_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    target = tmp_path / "r.h5"
    monkeypatch.setattr("facegear_tehl.run.ehl_solver", lambda: _synthetic)
    assert CliRunner().invoke(tehl, ["run", str(FACE_GEAR), "--jobs", "1", "-o", str(target)]).exit_code == 0
    before = target.read_bytes()
    monkeypatch.setattr("facegear_tehl.run.ehl_solver", lambda: _always_killed)
    result = CliRunner().invoke(tehl, ["run", str(FACE_GEAR), "--jobs", "2", "-o", str(target)])
    assert result.exit_code == 1, result.output
    assert target.read_bytes() == before  # the 5-point file is kept
    beside = [p for p in tmp_path.iterdir() if p != target]
    assert len(beside) == 1 and beside[0].name.startswith("r.") and beside[0].suffix == ".h5"
    assert f"{target} holds 5 converged points and this run 4: kept it" in result.stderr
    assert sorted(name for name, p in read_result(beside[0]).points.items() if p.converged) == ["S1", "S3", "S4",
                                                                                               "S5"]


_STALLING_RUN = textwrap.dedent(
    """
    import os, sys, time
    sys.path.insert(0, {tests!r})
    import synthetic
    from facegear_tehl import cli, run
    def stall_once(point, lubricant, settings):
        marker = os.path.join({folder!r}, f"worker-{{os.getpid()}}-{{point.name}}")
        first = not any(name.endswith("-" + point.name) for name in os.listdir({folder!r}))
        if point.name in ("S1", "S2") and settings.grid > settings.coarsest_grid and first:
            open(marker, "w").close()
            time.sleep(60)
        return synthetic.solution(point)
    run.ehl_solver = lambda: stall_once
    cli.main(sys.argv[1:])
    """
)


def test_kill_9_of_a_worker_of_tehl_run_loses_no_point(tmp_path):
    markers = tmp_path / "markers"
    markers.mkdir()
    script = _STALLING_RUN.format(tests=str(Path(__file__).parent), folder=str(markers))
    target = tmp_path / "r.h5"
    command = [sys.executable, "-c", script, "run", str(FACE_GEAR), "--jobs", "2", "-o", str(target)]
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as process:
        deadline = time.monotonic() + 120
        while len(list(markers.iterdir())) < 2:
            assert time.monotonic() < deadline and process.poll() is None, process.stderr.read()
            time.sleep(0.05)
        os.kill(int(sorted(markers.iterdir())[0].name.split("-")[1]), signal.SIGKILL)
        code = process.wait(timeout=50)  # well before the 60 s stalls: the retries do not stall
        stderr = process.stderr.read()
    assert code == 0, stderr
    assert "Traceback" not in stderr
    result = read_result(target)
    assert result.status == "ok" and sorted(result.points) == ["S1", "S2", "S3", "S4", "S5"]


def _alive(pid: int) -> bool:
    """The process runs (a zombie waiting for its reaping counts as ended)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def test_killing_the_parent_of_tehl_run_ends_its_workers(tmp_path):
    markers = tmp_path / "markers"
    markers.mkdir()
    script = _STALLING_RUN.format(tests=str(Path(__file__).parent), folder=str(markers))
    command = [sys.executable, "-c", script, "run", str(FACE_GEAR), "--jobs", "2", "-o", str(tmp_path / "r.h5")]
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as process:
        deadline = time.monotonic() + 120
        while len(list(markers.iterdir())) < 2:
            assert time.monotonic() < deadline and process.poll() is None, process.stderr.read()
            time.sleep(0.05)
        workers = [int(marker.name.split("-")[1]) for marker in markers.iterdir()]
        process.kill()  # SIGKILL: no handler of the parent runs
        process.wait(timeout=30)
    deadline = time.monotonic() + 10  # the workers stall 60 s: only their parent's death can end them sooner
    while any(_alive(pid) for pid in workers) and time.monotonic() < deadline:
        time.sleep(0.1)
    survivors = [pid for pid in workers if _alive(pid)]
    for pid in survivors:  # before the fix they ran on for minutes: end them, then fail
        os.kill(pid, signal.SIGKILL)
    assert survivors == []


def test_study_workers_are_capped_at_the_variants_to_run(tmp_path, monkeypatch):
    """`tehl study --workers 1000` on two variants starts two worker processes (it started 254 and took 8.6 GB)."""
    started: list[int] = []

    @contextmanager
    def recording_client(workers, scheduler):
        started.append(workers)
        raise KeyboardInterrupt  # stop before any cluster starts
        yield

    monkeypatch.setattr("facegear_tehl.study._client", recording_client)
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n  contact.load: [4.0, 9.0]\n", encoding="utf-8")
    result = CliRunner().invoke(tehl, ["study", str(study), "--workers", "1000", "-o", str(tmp_path / "out")])
    assert started == [2]
    assert "on a local Dask cluster of 2 worker processes" in result.stderr
