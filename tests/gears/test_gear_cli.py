"""`tehl contact CASE.yaml`: the S1..S5 table of a face gear case, exit 2 with one line on bad input."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from facegear_tehl.cli import tehl

CASES = Path(__file__).resolve().parents[2] / "cases"


def test_contact_prints_the_meshing_point_table():
    result = CliRunner().invoke(tehl, ["contact", str(CASES / "facegear_110.yaml")])
    assert result.exit_code == 0, result.output
    lines = result.output.splitlines()
    assert lines[0].split()[:4] == ["point", "s", "R_x", "R_y"]
    assert [line.split()[0] for line in lines[2:7]] == ["S1", "S2", "S3", "S4", "S5"]


def test_contact_bad_input_is_one_line_and_exit_2(tmp_path):
    case = tmp_path / "bad.yaml"
    text = (CASES / "facegear_110.yaml").read_text()
    case.write_text(text.replace("shaper_teeth: 28 ", "shaper_teeth: 25 "))
    result = CliRunner().invoke(tehl, ["contact", str(case)])
    assert result.exit_code == 2
    assert result.output.strip().splitlines() == [
        "error: gear.shaper_teeth: got 25; expected shaper_teeth - pinion_teeth in 1..3"
    ]


def test_contact_needs_a_gear_case():
    result = CliRunner().invoke(tehl, ["contact", str(CASES / "ball_on_disc.yaml")])
    assert result.exit_code == 2 and "gear" in result.output
