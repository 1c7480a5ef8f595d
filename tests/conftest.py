"""Session fixtures shared by the test modules: the default face gear case solved once.

`facegear_run` is cases/facegear_110.yaml as shipped (thermal full, Ree-Eyring), all five points S1..S5, on
the grid `--grid 65` gives (65 x 17: the case's grid_y keeps its aspect), solved in this process. Modules that
check the physics of the face gear points (test_heat_budget, test_thermal) and its written file
(test_robustness) read this one solve instead of each solving the case again. Tests must not change it.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from facegear_tehl.case import load_case
from facegear_tehl.results import RunResult, write_result
from facegear_tehl.run import run_case

FACE_GEAR_CASE = Path(__file__).resolve().parents[1] / "cases" / "facegear_110.yaml"
FACE_GEAR_GRID = 65  # --grid 65 as test_heat_budget always ran it; test_thermal's trends (it had 65^2) hold on it


@pytest.fixture(scope="session")
def facegear_run() -> RunResult:
    """The default face gear case, every point, on `--grid 65` (65 x 17), one job."""
    return run_case(load_case(FACE_GEAR_CASE), grid=FACE_GEAR_GRID, jobs=1)


@pytest.fixture(scope="session")
def facegear_file(facegear_run, tmp_path_factory) -> Path:
    """`facegear_run` written by results.write_result into a session temporary folder (read-only for tests)."""
    return write_result(facegear_run, tmp_path_factory.mktemp("facegear") / "facegear_110.h5")
