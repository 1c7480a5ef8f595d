"""No writable Numba cache (a read-only install run from a read-only home; docs/guarantees.md): the kernels are
compiled into a temporary cache with one warning instead of `RuntimeError: cannot cache function`. The package is
copied where every `__pycache__` is a plain file and the user caches lie under a file: no place Numba could write
to, even for root (who may write into read-only folders)."""

from __future__ import annotations

import os
from pathlib import Path
import shutil
import subprocess
import sys

import pytest

from facegear_tehl import kernel_cache

import synthetic

PACKAGE = Path(kernel_cache.__file__).parent


@pytest.fixture
def no_cache(tmp_path) -> tuple[Path, dict[str, str]]:
    """A copy of the package with no writable cache, and the environment of a process that has none either."""
    root = tmp_path / "install"
    shutil.copytree(PACKAGE, root / "facegear_tehl", ignore=shutil.ignore_patterns("__pycache__"))
    for folder in [root / "facegear_tehl", *(p for p in (root / "facegear_tehl").rglob("*") if p.is_dir())]:
        (folder / "__pycache__").write_text("not a folder")
    blocker = tmp_path / "blocker"
    blocker.write_text("a file: nothing can be made under it")
    environ = {**os.environ, "PYTHONPATH": str(root), "HOME": str(blocker / "home"),
               "XDG_CACHE_HOME": str(blocker / "cache"), "PYTHONDONTWRITEBYTECODE": "1"}
    environ.pop("NUMBA_CACHE_DIR", None)
    return root, environ


def test_prepare_finds_no_place_and_chooses_a_temporary_one(tmp_path, monkeypatch):
    blocker = tmp_path / "blocker"
    blocker.write_text("")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker / "cache"))
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(blocker / "given"))  # restored after the test, as WARNING is
    monkeypatch.setattr(kernel_cache, "WARNING", None)
    assert not kernel_cache.writable(blocker / "x")
    warning = kernel_cache.prepare((blocker,))
    folder = Path(os.environ["NUMBA_CACHE_DIR"])
    assert folder.is_dir() and kernel_cache.writable(folder) and str(folder) in warning
    assert kernel_cache.prepare((blocker,)) is None  # now NUMBA_CACHE_DIR is writable: nothing more to do
    monkeypatch.delenv("NUMBA_CACHE_DIR")
    assert kernel_cache.prepare((tmp_path,)) is None  # a writable __pycache__ beside the kernels: nothing to do


def test_a_kernel_module_imports_without_a_writable_cache(no_cache):
    root, environ = no_cache
    probe = "import os, facegear_tehl.lubricant_laws; print(os.environ['NUMBA_CACHE_DIR'])"
    process = subprocess.run([sys.executable, "-c", probe], env=environ, capture_output=True, text=True,
                             timeout=300, cwd=root, check=False)
    assert process.returncode == 0, process.stderr  # was: RuntimeError: cannot cache function
    assert Path(process.stdout.strip()).name.startswith("tehl-numba-")
    assert not Path(process.stdout.strip()).exists()  # removed when the process ended


@pytest.mark.slow
def test_tehl_run_without_a_writable_cache_warns_once_and_runs(no_cache, tmp_path):
    root, environ = no_cache
    target = tmp_path / "r.h5"
    command = [sys.executable, "-c", "from facegear_tehl import cli; cli.main()", "run", str(synthetic.BALL_ON_DISC),
               "--grid", "33", "--thermal", "off", "--jobs", "1", "-o", str(target)]
    process = subprocess.run(command, env=environ, capture_output=True, text=True, timeout=900, cwd=root,
                             check=False)
    assert process.returncode in (0, 3), process.stderr
    assert process.stderr.count("warning: no writable Numba cache") == 1, process.stderr
    assert "Traceback" not in process.stderr and target.is_file()
