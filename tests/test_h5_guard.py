"""Malformed result files and study indexes (h5_guard.py, docs/guarantees.md): `tehl info` and `tehl plot` refuse
each with exit 2 and one line naming the file, never an exception name alone; external and soft links are never
followed; a small file declaring gigabytes is refused before anything is allocated; a study resumes past a
damaged file, naming it."""

from __future__ import annotations

import os
from pathlib import Path
import shutil
import time

from click.testing import CliRunner
import h5py
import numpy as np
import pytest

from facegear_tehl.cli import tehl
from facegear_tehl.results import write_result
from facegear_tehl.study import _resumed, finished
from facegear_tehl.study_file import load_study

import synthetic


def _invoke(*args):
    return CliRunner().invoke(tehl, [str(a) for a in args])


@pytest.fixture
def good(tmp_path) -> Path:
    return write_result(synthetic.run_result(), tmp_path / "good.h5")


def _refused(result, path: Path) -> None:
    assert result.exit_code == 2, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {path}: "), result.stderr


def _points_a_dataset(h5):
    del h5["points"]
    h5["points"] = np.arange(3.0)


def _text_scalar(h5):
    h5["points/contact"].attrs["h_c"] = "thin"


def _dangling(h5):
    h5["points/contact/ghost"] = h5py.SoftLink("/nowhere")


def _loop(h5):
    h5["points/loop"] = h5py.SoftLink("/points/loop")


def _text_field(h5):
    group = h5["points/contact"]
    del group["pressure"]
    group.create_dataset("pressure", data=np.array(["a"] * 3, dtype=object), dtype=h5py.string_dtype())
    group["pressure"].attrs.update(kind="field", units="Pa", description="")


def _units_a_list(h5):
    h5["points/contact"].attrs["units"] = "[1, 2]"


def _huge_history(h5):
    """500 million float64 (4 GB) declared; no byte of it stored."""
    group = h5["points/contact"]
    group.create_dataset("residual_huge", shape=(500_000_000,), dtype="f8")
    group["residual_huge"].attrs.update(kind="history", units="1", description="")


def _huge_compressed(h5):
    group = h5["points/contact"]
    group.create_dataset("residual_huge", shape=(500_000_000,), dtype="f8", chunks=(1_000_000,), compression="gzip")
    group["residual_huge"][:1000] = 1.0
    group["residual_huge"].attrs.update(kind="history", units="1", description="")


def _record_with_data(h5):
    """The solve record holds attributes alone: a dataset in it is no record of ours."""
    h5["points/contact"].create_group("solve")["hidden"] = np.arange(3.0)


def _record_a_dataset(h5):
    h5["points/contact/solve"] = np.arange(3.0)


DAMAGE = {"points a dataset": _points_a_dataset, "data in the solve record": _record_with_data,
          "the solve record a dataset": _record_a_dataset, "text scalar": _text_scalar, "dangling link": _dangling,
          "soft-link loop": _loop, "text field": _text_field, "units a list": _units_a_list,
          "4 GB history": _huge_history, "4 GB compressed history": _huge_compressed}


@pytest.mark.parametrize("damage", DAMAGE)
@pytest.mark.parametrize("command", ["info", "plot"])
def test_a_malformed_file_is_refused_naming_it(good, damage, command):
    with h5py.File(good, "a") as h5:
        DAMAGE[damage](h5)
    assert good.stat().st_size < 1_000_000  # the 4 GB are declared, not stored
    started = time.monotonic()
    _refused(_invoke(command, good), good)
    assert time.monotonic() - started < 5.0
    assert not (good.parent / "good_plots").exists()


def test_a_fifo_is_refused_at_once(tmp_path):
    fifo = tmp_path / "r.h5"
    os.mkfifo(fifo)
    _refused(_invoke("info", fifo), fifo)  # opening it would wait for a writer for ever


def test_an_external_link_is_not_followed(tmp_path, good):
    other = write_result(synthetic.run_result(), tmp_path / "other.h5")
    with h5py.File(good, "a") as h5:
        h5["points/intruder"] = h5py.ExternalLink(str(other), "/points/contact")
    result = _invoke("info", good, "--json")
    _refused(result, good)
    assert "intruder" in result.stderr and "link" in result.stderr


@pytest.mark.parametrize("kind", ["external raw file", "virtual dataset"])
def test_data_held_in_another_file_is_not_read(tmp_path, good, kind):
    other = write_result(synthetic.run_result(), tmp_path / "other.h5")
    with h5py.File(good, "a") as h5:
        group = h5["points/contact"]
        if kind == "external raw file":
            raw = tmp_path / "raw.bin"
            raw.write_bytes(np.arange(4.0).tobytes())
            group.create_dataset("residual_external", shape=(4,), dtype="f8", external=[(str(raw), 0, 32)])
        else:
            layout = h5py.VirtualLayout(shape=(33,), dtype="f8")
            layout[:] = h5py.VirtualSource(str(other), "points/contact/x", shape=(33,))
            group.create_virtual_dataset("residual_external", layout)
        group["residual_external"].attrs.update(kind="history", units="1", description="")
    result = _invoke("info", good)
    _refused(result, good)
    assert "residual_external" in result.stderr


def test_a_damaged_chunk_is_refused_by_plot(good):
    with h5py.File(good, "r") as h5:
        offset = h5["points/contact/pressure"].id.get_chunk_info(0).byte_offset
    with open(good, "r+b") as stream:
        stream.seek(offset)
        stream.write(b"\xff" * 64)  # the deflate stream no longer inflates
    _refused(_invoke("plot", good), good)


def test_a_study_resumes_past_a_damaged_file_and_names_it(tmp_path, good):
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n  contact.load: [4.0]\n", encoding="utf-8")
    variant = load_study(study).variants[0]
    folder = tmp_path / "out"
    folder.mkdir()
    damaged = shutil.copy(good, folder / variant.file_name)
    with h5py.File(damaged, "a") as h5:
        _loop(h5)
    assert not finished(Path(damaged), variant)  # was: AttributeError out of the resume
    notices: list[str] = []
    assert _resumed(load_study(study), folder, notices.append) == {}
    assert len(notices) == 1 and notices[0].startswith("variant 1 (contact.load=4.0): ")
    assert variant.file_name in notices[0] and notices[0].endswith("running it again")


INDEX_HEADER = "variant,contact.load,point,status,converged,h_c [m],h_min [m],file,message\n"


@pytest.mark.parametrize(("body", "expected"), [
    (INDEX_HEADER.encode() + b"1,4.0,contact,ok,yes,1e-7,\xff\xfe,a.h5,\n", "not a readable study index"),
    (INDEX_HEADER.encode() + b"1,4.0,contact,ok,yes,1e-7,thin,a.h5,\n", "column h_min [m]: 'thin' is not a number"),
    (INDEX_HEADER.encode() + b"1,4.0,contact,ok,yes,1e-7,9e-8,a.h5,\n2,9.0,contact,ok,y", "truncated"),
    (INDEX_HEADER.encode() + b"1,4.0,contact,ok,yes,1e-7,9e-8,a.h5,\n2,9.0,contact,ok\n", "line 3 has 4 cells"),
])
def test_a_bad_study_index_is_refused_by_plot(tmp_path, body, expected):
    (tmp_path / "index.csv").write_bytes(body)
    result = _invoke("plot", tmp_path, "--what", "maps")
    assert result.exit_code == 2, result.output
    assert expected in result.stderr and "Traceback" not in result.output
    assert not (tmp_path / "maps").exists()


def test_an_index_cut_between_rows_is_noticed_by_the_files_it_does_not_name(tmp_path):
    listed, unlisted = "0123456789abcdef.h5", "fedcba9876543210.h5"
    (tmp_path / "index.csv").write_text(INDEX_HEADER + f"1,4.0,contact,ok,yes,1e-7,9e-8,{listed},\n")
    for name in (listed, unlisted):
        (tmp_path / name).write_bytes(b"")
    result = _invoke("plot", tmp_path, "--what", "maps", "-o", tmp_path / "maps")
    assert result.exit_code == 0, result.output
    assert f"warning: {tmp_path / 'index.csv'} does not name 1 result file(s) of the folder" in result.output
