"""The terminal tables of `tehl run` and `tehl info` read without a clash: titled, a quantity's unit in its header,
absolute temperatures in one unit, the grid reported as solved."""

from __future__ import annotations

import re

from click.testing import CliRunner
import pytest

from facegear_tehl.cli import tehl
from facegear_tehl.results import read_result

FACE_GEAR = "cases/facegear_110.yaml"


@pytest.fixture(scope="module")
def gear_run(tmp_path_factory):
    """`tehl run` of the shipped face gear at S1 and S3 on a 33-node grid: its output and the file it wrote."""
    path = tmp_path_factory.mktemp("tables") / "gear.h5"
    result = CliRunner().invoke(tehl, ["run", FACE_GEAR, "--grid", "33", "--points", "S1,S3", "--jobs", "1",
                                       "-o", str(path)])
    assert result.exit_code == 0, result.output
    return result, read_result(path), path


def _header(output: str, first: str) -> list[str]:
    """The columns of the table whose header line starts with `first` (split on two or more spaces)."""
    line = next(line for line in output.splitlines() if line.startswith(first))
    return re.split(r"\s{2,}", line.strip())


def test_every_table_of_run_has_a_title_line(gear_run):
    """Each table's header line (point ...) follows a title line, not the previous table or the progress."""
    result, _, _ = gear_run
    lines = result.stdout.splitlines()
    headers = [i for i, line in enumerate(lines) if line.startswith("point ")]
    assert len(headers) == 3
    for i in headers:
        assert lines[i - 1].endswith(":") and not lines[i - 1].startswith(("-", "S", "point")), lines[i - 1]


def test_no_column_named_by_a_unit_and_the_contact_temperatures_say_what_they_are(gear_run):
    """The load share is not headed 'K' beside kelvin columns; θ_B is marked solved, Blok's rise named as his."""
    result, _, _ = gear_run
    cycle = _header(result.stdout, "point    s mm")
    assert "K" not in cycle and "load share" in cycle
    assert [c for c in cycle if c.startswith("theta_B")] == ["theta_B,1 solved °C", "theta_B,2 solved °C"]
    assert "Blok flash dT K" in cycle and "Blok flash dT K" in _header(result.stdout, "point      mu")


def test_info_shows_every_absolute_temperature_in_celsius(gear_run):
    """tehl info: the contact temperatures in °C (as the verdict and the cycle table), T - 273.15 of the file's K;
    no row of an absolute temperature in K."""
    _, run, path = gear_run
    info = CliRunner().invoke(tehl, ["info", str(path)])
    assert info.exit_code == 0, info.output
    rows = {line.split()[0]: line.split()[1:] for line in info.stdout.splitlines() if line.startswith("contact_temp")}
    assert set(rows) == {"contact_temperature_1", "contact_temperature_2", "contact_temperature_blok_1",
                         "contact_temperature_blok_2"}
    for key, (unit, *cells) in rows.items():
        assert unit == "°C"
        kelvin = [point.scalars[key] for point in run.points.values()]
        assert [float(c) for c in cells] == pytest.approx([k - 273.15 for k in kelvin], abs=0.05)


def test_the_progress_names_the_grid_each_point_was_solved_on(gear_run):
    """'solved on NxM' on each point's line is the node count of the fields the file holds."""
    result, run, _ = gear_run
    for name, point in run.points.items():
        nodes = f"solved on {len(point.axes['x'].values)}x{len(point.axes['y'].values)}"
        assert any(line.startswith("[") and f"] {name}:" in line and nodes in line
                   for line in result.stderr.splitlines()), result.stderr
