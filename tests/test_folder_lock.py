"""One study at a time in a folder (folder_lock.py, docs/guarantees.md): a second `tehl study` on a folder whose
lock is held is refused with exit 2 naming -o and the holder's pid, and runs once the lock is released; the lock
never outlives its holder."""

from __future__ import annotations

import os
import subprocess
import sys

from click.testing import CliRunner

from facegear_tehl.cli import tehl
from facegear_tehl.folder_lock import exclusive
from facegear_tehl.points import contact_analysis
from facegear_tehl.results import RunResult, write_result
from facegear_tehl.study_file import load_study

import synthetic


def _finished_study(tmp_path):
    """A one-variant study whose result file is already in its folder (nothing left to compute)."""
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n  contact.load: [4.0]\n", encoding="utf-8")
    variant = load_study(study).variants[0]
    folder = tmp_path / "out"
    folder.mkdir()
    point = contact_analysis(variant.case).points[0]
    write_result(RunResult(case=variant.case, points=(synthetic.solution(point),)), folder / variant.file_name)
    return study, folder


def test_a_second_study_on_a_locked_folder_is_refused(tmp_path):
    study, folder = _finished_study(tmp_path)
    with exclusive(folder, "-o"):
        result = CliRunner().invoke(tehl, ["study", str(study), "-o", str(folder)])
        assert result.exit_code == 2, result.output
        line = result.stderr.strip().splitlines()[-1]
        assert line.startswith("error: -o: got '") and line.endswith(
            f"; expected a folder no other tehl study is running in (pid {os.getpid()} is; wait for it to end, or "
            "choose another folder)"), line
        assert not (folder / "index.csv").exists()
    done = CliRunner().invoke(tehl, ["study", str(study), "-o", str(folder)])
    assert done.exit_code == 0, done.output
    assert "0 variants computed, 1 already finished" in done.output


def test_the_lock_ends_with_its_holder(tmp_path):
    holder = "import sys, os; from facegear_tehl.folder_lock import exclusive; from pathlib import Path\n" \
             "with exclusive(Path(sys.argv[1]), '-o'):\n    os.kill(os.getpid(), 9)"
    subprocess.run([sys.executable, "-c", holder, str(tmp_path)], check=False, timeout=60)
    with exclusive(tmp_path, "-o"):  # no CaseError: the killed holder's lock is gone
        pass
