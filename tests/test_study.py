"""`tehl study` on a Dask LocalCluster of two worker processes, on tiny isothermal variants of the ball-on-disc
case (grid 33): each variant's file equals `tehl run` of that variant written by hand; a worker killed mid-study;
an interrupted study completed by a rerun that recomputes nothing finished; a failing variant recorded while the
others are done; bad study files exit 2 with nothing written; the maps hold the files' values."""

from __future__ import annotations

import csv
import json
import math
import os
from pathlib import Path
import re
import signal
import subprocess
import sys
import time

from click.testing import CliRunner
import h5py
import numpy as np
import pytest

from facegear_tehl.cli import tehl
from facegear_tehl.plots.study_maps import WORST, map_grids, read_index
from facegear_tehl.results import read_result
from facegear_tehl.study import run_study
from facegear_tehl.study_file import load_study

import synthetic
from test_parallel import _DIMENSION_LINKS, _linked

BASE = synthetic.BALL_ON_DISC
LOADS = (4.0, 9.0)
ROLLING = (0.0, 0.5)  # slide-roll ratios
# The attributes that may differ between two runs of the same case: when and by which version the file was
# written, and the solve's wall time.
VOLATILE = ("created", "tehl_version", "wall_time", "cpu_time", "error_check_time", "error_check_cpu_time",
            "stage_seconds")
REPOSITORY = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def cluster():
    """A local Dask cluster of two worker processes (one thread each) the tests share by its address."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as local:
        yield local


def _invoke(*args):
    return CliRunner().invoke(tehl, [str(a) for a in args])


def _study(folder: Path, vary: str, extra: str = "set: {solver.grid: 33}\n", name: str = "study.yaml") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text(f"base: {BASE}\nvary:\n{vary}{extra}", encoding="utf-8")
    return path


def _by_hand(load: float, slide_roll_ratio: float) -> str:
    """The ball-on-disc case with its load, slide-roll ratio and grid edited in its text (not by the study code)."""
    text = BASE.read_text(encoding="utf-8")
    text, loads = re.subn(r"(?m)^(\s+load:\s*)\S+", rf"\g<1>{load}", text)
    text, ratios = re.subn(r"(?m)^(\s+slide_roll_ratio:\s*)\S+", rf"\g<1>{slide_roll_ratio}", text)
    text, grids = re.subn(r"(?m)^(\s+grid:\s*)\S+", r"\g<1>33", text)
    assert loads == ratios == grids == 1
    return text


def _contents(path: Path) -> dict[str, object]:
    """Every attribute and dataset of an HDF5 file by its path ('/group.attr', '/group/dataset')."""
    found: dict[str, object] = {}
    with h5py.File(path, "r") as h5:
        found.update({f"/.{key}": value for key, value in h5.attrs.items()})

        def visit(name, item):
            # dimension-scale links are object references (different in every file): compared by what they name
            found.update({f"/{name}.{key}": _linked(h5, key, value) if key in _DIMENSION_LINKS else value
                          for key, value in item.attrs.items()})
            if isinstance(item, h5py.Dataset):
                found[f"/{name}"] = item[()]

        h5.visititems(visit)
    return found


def _index(folder: Path) -> list[dict[str, str]]:
    with (folder / "index.csv").open(newline="") as stream:
        return list(csv.DictReader(stream))


def _stamps(folder: Path) -> dict[str, tuple[int, int]]:
    """Each result file's inode and modification time: a file written again changes both."""
    return {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in folder.glob("*.h5")}


def test_each_variant_file_equals_tehl_run_of_that_variant_and_a_rerun_recomputes_nothing(cluster, tmp_path):
    study = _study(tmp_path, f"  contact.load: {list(LOADS)}\n  contact.slide_roll_ratio: {list(ROLLING)}\n")
    out = tmp_path / "out"
    done = _invoke("study", study, "-o", out, "--scheduler", cluster.scheduler_address)
    assert done.exit_code == 0, done.output
    rows = _index(out)
    assert [(float(r["contact.load"]), float(r["contact.slide_roll_ratio"])) for r in rows] == \
        [(load, srr) for load in LOADS for srr in ROLLING]
    for row in rows:
        case = tmp_path / f"hand_{row['variant']}.yaml"
        case.write_text(_by_hand(float(row["contact.load"]), float(row["contact.slide_roll_ratio"])))
        reference = tmp_path / f"run_{row['variant']}.h5"
        ran = _invoke("run", case, "-o", reference, "--jobs", "1")
        assert ran.exit_code == 0, ran.output
        mine, theirs = _contents(out / row["file"]), _contents(reference)
        assert mine.keys() == theirs.keys()
        different = sorted(key for key in mine if not np.array_equal(mine[key], theirs[key]))
        # Beyond the volatile stamps only the case text differs: the study writes the resolved case (comments
        # dropped), which reads back to the same case.
        assert "/.case_yaml" in different
        timings = {"/.created", "/points/contact.wall_time", "/points/contact.cpu_time",
                   "/points/contact.error_check_time", "/points/contact.error_check_cpu_time",
                   "/points/contact/solve.stage_seconds"}
        assert set(different) <= {"/.case_yaml"} | timings, different
        # `tehl run` of the resolved case the file holds writes the same file but for the volatile stamps
        resolved = tmp_path / f"resolved_{row['variant']}.yaml"
        resolved.write_text(read_result(out / row["file"]).case_yaml, encoding="utf-8")
        assert _invoke("run", resolved, "-o", tmp_path / "resolved.h5", "--jobs", "1").exit_code == 0
        again = _contents(tmp_path / "resolved.h5")
        assert set(key for key in mine if not np.array_equal(mine[key], again[key])) <= timings
        # index.csv carries the values of `tehl run`'s file, in SI
        point = read_result(reference).points["contact"]
        for key in ("h_c", "h_min", "p_max"):
            assert float(row[f"{key} [{point.units[key]}]"]) == pytest.approx(point.scalars[key], rel=1e-9)
        assert row["converged"] == "yes" and row["status"] == "ok" and row["dT_max [K]"] == ""
        # the file is named by the variant's values and holds its resolved case; the index gives the grid solved on
        assert row["file"] == f"load={row['contact.load']}_slide_roll_ratio={row['contact.slide_roll_ratio']}.h5"
        assert row["grid"] == "x".join(str(len(point.axes[k].values)) for k in ("x", "y"))
        assert row["refinements"] == "0"
        # the error bound of each figure, or the word where the solve cannot bound it, as `tehl run`'s file says
        for key in ("h_c", "h_min", "p_max"):
            flagged = point.scalars[f"unresolved_{key}"] == 1.0
            cell = row[f"error_bound_{key} [1]"]
            bound = None if flagged else point.scalars[f"error_bound_{key}"]
            assert cell == "unresolved" if flagged else float(cell) == pytest.approx(bound)
        assert row["error_bound_p_max [1]"] == "unresolved"  # never bounded (ehl/error_bounds.py)
    before = _stamps(out)
    again = _invoke("study", study, "-o", out, "--scheduler", cluster.scheduler_address)
    assert again.exit_code == 0, again.output
    assert "0 variants computed, 4 already finished" in again.output
    assert _stamps(out) == before


def test_the_resolved_case_reads_back_as_the_hand_edited_case(cluster, tmp_path):
    """`tehl run` of the case text a study file holds writes the same case as the hand-edited file."""
    study = load_study(_study(tmp_path, "  contact.load: [9.0]\n  contact.slide_roll_ratio: [0.5]\n"))
    (variant,) = study.variants
    hand = tmp_path / "hand.yaml"
    hand.write_text(_by_hand(9.0, 0.5))
    from facegear_tehl.case import load_case

    mine, theirs = variant.case, load_case(hand)
    assert (mine.contact, mine.materials, mine.lubricant, mine.solver, mine.name) == \
        (theirs.contact, theirs.materials, theirs.lubricant, theirs.solver, theirs.name)


def test_a_worker_killed_mid_study_the_study_still_completes(cluster, tmp_path):
    from distributed import Client

    study = load_study(_study(tmp_path, "  contact.load: [3.0, 4.0, 5.0, 6.0, 7.0, 8.0]\n",
                              "set: {solver.grid: 65}\n"))
    killed = []
    with Client(cluster.scheduler_address) as client:
        pids = client.run(os.getpid)

        def kill_a_busy_worker(outcome, done, total, eta):
            if killed:
                return
            busy = [worker for worker, keys in client.processing().items() if keys]
            assert busy, "no worker is running a variant to kill"
            os.kill(pids[busy[0]], signal.SIGKILL)
            killed.append(busy[0])

        report = run_study(study, tmp_path / "out", scheduler=cluster.scheduler_address, progress=kill_a_busy_worker)
    assert killed
    assert [o.status for o in report.outcomes] == ["ok"] * 6
    assert len(list((tmp_path / "out").glob("*.h5"))) == 6
    rerun = run_study(study, tmp_path / "out", scheduler=cluster.scheduler_address)
    assert rerun.computed == 0


def test_an_interrupted_study_completes_on_the_next_run_without_recomputing_finished_variants(cluster, tmp_path):
    path = _study(tmp_path, "  contact.load: [3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0]\n", "set: {solver.grid: 65}\n")
    out = tmp_path / "out"
    env = {**os.environ, "PYTHONPATH": str(REPOSITORY)}
    process = subprocess.Popen([sys.executable, "-m", "facegear_tehl", "study", str(path), "-o", str(out),
                                "--workers", "1"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               preexec_fn=synthetic.sigint_as_in_a_terminal)
    deadline = time.monotonic() + 120.0
    while not list(out.glob("*.h5")) and time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.02)
    process.send_signal(signal.SIGINT)  # Ctrl-C
    _, stderr = process.communicate(timeout=120.0)
    assert process.returncode != 0, stderr
    first = _stamps(out)
    assert 1 <= len(first) < 8, stderr
    pending = [row for row in _index(out) if row["status"] == "pending"]
    assert len(pending) == 8 - len(first)  # the index of the interrupted run says what is left
    done = _invoke("study", path, "-o", out, "--scheduler", cluster.scheduler_address)
    assert done.exit_code == 0, done.output
    assert f"{8 - len(first)} variants computed, {len(first)} already finished" in done.output
    after = _stamps(out)
    assert len(after) == 8 and {name: after[name] for name in first} == first
    assert [row["status"] for row in _index(out)] == ["ok"] * 8


def test_a_failing_variant_is_recorded_and_the_others_are_done(cluster, tmp_path):
    path = _study(tmp_path, "  contact.load: [4.0, 6.0, 9.0]\n")
    out = tmp_path / "out"
    blocked = out / load_study(path).variants[1].file_name
    blocked.mkdir(parents=True)  # its result cannot be written: a directory holds its name
    failed = _invoke("study", path, "-o", out, "--scheduler", cluster.scheduler_address)
    assert failed.exit_code == 3, failed.output
    assert "failed: variant 2 (contact.load=6.0): IsADirectoryError" in failed.output
    rows = _index(out)
    assert [r["status"] for r in rows] == ["ok", "failed", "ok"]
    assert "IsADirectoryError" in rows[1]["message"] and rows[1]["file"] == ""
    assert (out / "failures.txt").read_text().startswith("variant 2 (contact.load=6.0): IsADirectoryError")
    assert len(list(out.glob("*.h5"))) == 2 + 1  # two results and the directory
    blocked.rmdir()
    fixed = _invoke("study", path, "-o", out, "--scheduler", cluster.scheduler_address)
    assert fixed.exit_code == 0, fixed.output
    assert "1 variants computed, 2 already finished, 0 failed" in fixed.output
    assert not (out / "failures.txt").exists()


@pytest.mark.parametrize(
    ("vary", "extra", "message"),
    [
        ("  contact.lod: [1.0, 2.0]\n", "", "vary.contact.lod: got 1.0; expected no such key (did you mean 'load'?)"),
        ("  contact.load: [heavy]\n", "", "vary.contact.load: got 'heavy'; expected a finite number in N"),
        ("  contact.load: [1.0, -2.0]\n", "", "vary.contact.load: got -2.0; expected a positive number in N "
                                               "(variant 2 of 2: contact.load=-2.0)"),
        ("  contact.load: 5.0\n", "", "vary.contact.load: got 5.0; expected a non-empty list of values"),
        ("  contact.load: []\n", "", "vary.contact.load: got []; expected a non-empty list of values"),
        ("  contact.load: [1.0, 1.0]\n", "", "vary.contact.load: got 1.0; expected distinct values"),
        ("  contact.load: [1, 1.0]\n", "", "vary.contact.load: got 1; expected distinct values"),  # one number
        ("  contact.load.x: [1.0]\n", "", "vary.contact.load.x: got 1.0; expected a path through blocks of the case "
                                          "(contact.load is 6.272, not a block)"),
        ("  output.file: [a.h5]\n", "", "vary.output.file: got 'output.file'; expected a case key outside output"),
        ("  contact.load: [1.0]\n", "set: {contact.load: 2.0}\n", "set.contact.load: got 'contact.load'; expected "
                                                                  "a path not given twice"),
        ("  contact.load: [1.0]\n", "set: {solver.thermal: warm}\n", "set.solver.thermal: got 'warm'; expected one "
                                                                     "of off, "),
        ("  contact.load: [1.0]\n", "sett: {}\n", "sett: got {}; expected no such key (did you mean 'set'?)"),
        ("  contact.load: [1.0]\n", "set: [solver.grid]\n", "set: got ['solver.grid']; expected a mapping"),
        ("  {}\n", "", "vary: got {}; expected at least one case key"),
    ],
)
def test_a_bad_study_file_exits_2_naming_the_key_and_writes_nothing(tmp_path, vary, extra, message):
    path = _study(tmp_path, vary, extra) if vary != "  {}\n" else _bare(tmp_path, "vary: {}\n")
    out = tmp_path / "out"
    result = _invoke("study", path, "-o", out)
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {message}"), result.output
    assert not out.exists()


def _bare(folder: Path, body: str) -> Path:
    path = folder / "study.yaml"
    path.write_text(f"base: {BASE}\n{body}", encoding="utf-8")
    return path


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("--workers", "0"), "error: --workers: got 0; expected a number of worker processes >= 1"),
        (("--workers", "2", "--scheduler", "tcp://127.0.0.1:9"), "error: --workers: got 2; expected no --workers"),
        (("--scheduler", "tcp://127.0.0.1:9"), "error: --scheduler: got 'tcp://127.0.0.1:9'; expected the address "
                                               "of a running Dask scheduler"),
    ],
)
def test_bad_options_exit_2_and_write_nothing(tmp_path, args, message):
    path = _study(tmp_path, "  contact.load: [1.0]\n")
    result = _invoke("study", path, "-o", tmp_path / "out", *args)
    assert result.exit_code == 2, result.output
    assert result.output.strip().splitlines()[-1].startswith(message), result.output
    assert not (tmp_path / "out").exists()


def test_a_missing_base_and_a_relative_base(tmp_path):
    missing = tmp_path / "a" / "study.yaml"
    missing.parent.mkdir()
    missing.write_text("base: ../nowhere.yaml\nvary: {contact.load: [1.0]}\n")
    result = _invoke("study", missing, "-o", tmp_path / "out")
    assert result.exit_code == 2 and result.output.startswith("error: base: got '"), result.output
    (tmp_path / "nowhere.yaml").write_text(BASE.read_text())  # now the base exists, relative to the study file
    assert len(load_study(missing).variants) == 1


def test_maps_hold_the_values_of_the_result_files(cluster, tmp_path):
    path = _study(tmp_path, f"  contact.slide_roll_ratio: {list(ROLLING)}\n  contact.load: {list(LOADS)}\n")
    out = tmp_path / "out"
    assert _invoke("study", path, "-o", out, "--scheduler", cluster.scheduler_address).exit_code == 0
    plotted = _invoke("plot", out, "--what", "maps", "--z", "p_max", "--x", "contact.load",
                      "--y", "contact.slide_roll_ratio")
    assert plotted.exit_code == 0, plotted.output
    assert sorted(p.name for p in (out / "maps").iterdir()) == ["map_p_max_contact.png", "map_p_max_worst.png"]
    (grid, worst) = map_grids(read_index(out), "p_max", "contact.load", "contact.slide_roll_ratio")
    assert grid.values.shape == (len(ROLLING), len(LOADS))
    for row in _index(out):
        i, j = ROLLING.index(float(row["contact.slide_roll_ratio"])), LOADS.index(float(row["contact.load"]))
        assert grid.values[i, j] == pytest.approx(read_result(out / row["file"]).points["contact"].scalars["p_max"])
    np.testing.assert_array_equal(worst.values, grid.values)  # one point: it is the worst


def test_the_worst_point_is_the_thinnest_film_and_the_highest_pressure(tmp_path):
    """A hand-written index of two variants of two points, one not converged and one variant failed."""
    (tmp_path / "index.csv").write_text(
        "variant,gear.pinion_torque,point,status,converged,h_min [m],p_max [Pa],file,message\n"
        "1,250,S1,ok,yes,2e-7,1e9,a.h5,\n"
        "1,250,S2,ok,no,1e-7,8e8,a.h5,\n"
        "2,500,S1,ok,yes,3e-7,5e8,b.h5,\n"
        "2,500,S2,ok,yes,4e-7,6e8,b.h5,\n"
        "3,750,,failed,,,,,boom\n")
    index = read_index(tmp_path)
    worst_film = map_grids(index, "h_min", points=[WORST])[0]
    np.testing.assert_array_equal(worst_film.values, [[1e-7, 3e-7, math.nan]])
    np.testing.assert_array_equal(worst_film.not_converged, [[True, False, False]])
    worst_pressure = map_grids(index, "p_max", points=[WORST])[0]
    np.testing.assert_array_equal(worst_pressure.values, [[1e9, 6e8, math.nan]])
    s2 = map_grids(index, "h_min", points=["S2"])[0]
    np.testing.assert_array_equal(s2.values, [[1e-7, 4e-7, math.nan]])
    result = _invoke("plot", tmp_path, "--what", "maps", "--z", "mu")
    assert result.exit_code == 0 and "skipped map map_mu_S1: no mu in the index" in result.output, result.output


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("--z", "h_max"), "error: --z: got 'h_max'; expected a scalar of the study index"),
        (("--x", "gear.shaft_angle"), "error: --x: got 'gear.shaft_angle'; expected a key the study varies"),
        (("--point", "S9"), "error: --point: got 'S9'; expected point names of the study"),
        (("--what", "trends"), "error: --what: got 'trends'; expected maps"),
        (("--format", "bmp"), "error: --format: got 'bmp'; expected one of png, pdf, svg"),
        (("--dpi", "0"), "error: --dpi: got 0; expected a positive number"),
        (("--y", "gear.pinion_torque"), "error: --y: got 'gear.pinion_torque'; expected another varied key"),
    ],
)
def test_bad_map_options_exit_2(tmp_path, args, message):
    (tmp_path / "index.csv").write_text("variant,gear.pinion_torque,point,status,converged,h_min [m],file,message\n"
                                        "1,250,S1,ok,yes,2e-7,a.h5,\n")
    result = _invoke("plot", tmp_path, *args)
    assert result.exit_code == 2 and result.output.startswith(message), result.output


def test_a_folder_without_an_index_is_not_a_study(tmp_path):
    result = _invoke("plot", tmp_path, "--what", "maps")
    assert result.exit_code == 2 and "not a study folder" in result.output, result.output


def test_the_index_reads_lambda_power_loss_and_efficiency_when_the_file_has_them(cluster, tmp_path):
    """A file given a point's film_parameter and /cycle power_loss and mesh_efficiency (as the mesh cycle writes
    them: attributes, their units as JSON) shows them in the index of the next run, which computes nothing."""
    path = _study(tmp_path, "  contact.load: [4.0, 9.0]\n")
    out = tmp_path / "out"
    assert _invoke("study", path, "-o", out, "--scheduler", cluster.scheduler_address).exit_code == 0
    first = _index(out)[0]
    assert first["film_parameter [1]"] == first["power_loss [W]"] == first["mesh_efficiency [1]"] == ""
    with h5py.File(out / first["file"], "r+") as h5:
        point = h5["points/contact"]
        point.attrs["film_parameter"] = 1.25
        point.attrs["units"] = json.dumps({**json.loads(point.attrs["units"]), "film_parameter": "1"})
        cycle = h5.create_group("cycle")
        cycle.attrs["power_loss"], cycle.attrs["mesh_efficiency"] = 812.5, 0.9921
        cycle.attrs["units"] = json.dumps({"power_loss": "W", "mesh_efficiency": "1"})
    again = _invoke("study", path, "-o", out, "--scheduler", cluster.scheduler_address)
    assert "0 variants computed, 2 already finished" in again.output, again.output
    first, second = _index(out)
    assert (first["film_parameter [1]"], first["power_loss [W]"], first["mesh_efficiency [1]"]) == \
        ("1.25", "812.5", "0.9921")
    assert second["film_parameter [1]"] == second["power_loss [W]"] == ""


def test_a_damaged_file_is_named_and_run_again(cluster, tmp_path):
    """A result file of the folder damaged (a soft-link loop under /points) stopped the resume with AttributeError;
    now the study names it and computes its variant again (docs/guarantees.md)."""
    study = _study(tmp_path, "  contact.load: [4.0, 9.0]\n")
    out = tmp_path / "out"
    assert _invoke("study", study, "-o", out, "--scheduler", cluster.scheduler_address).exit_code == 0
    damaged = out / _index(out)[0]["file"]
    with h5py.File(damaged, "a") as h5:
        h5["points/loop"] = h5py.SoftLink("/points/loop")
    again = _invoke("study", study, "-o", out, "--scheduler", cluster.scheduler_address)
    assert again.exit_code == 0, again.output
    assert f"warning: variant 1 (contact.load=4.0): {damaged}: damaged tehl result (/points/loop:" in again.stderr
    assert "1 variants computed, 1 already finished" in again.output
    assert "loop" not in read_result(damaged).points


def test_a_variant_that_did_not_converge_exits_3_as_tehl_run_does(cluster, tmp_path):
    """One V-cycle on the finest grid does not meet the tolerances: each variant's file is written and flagged, the
    index says so, and the exit code is 3 (a failure is reported in the exit code, as `tehl run` reports it)."""
    study = _study(tmp_path, "  contact.load: [6.272]\n", "set: {solver.grid: 33, solver.max_cycles: 1}\n")
    out = tmp_path / "out"
    done = _invoke("study", study, "-o", out, "--scheduler", cluster.scheduler_address)
    assert done.exit_code == 3, done.output
    (row,) = _index(out)
    assert row["converged"] == "no" and (out / row["file"]).is_file()
