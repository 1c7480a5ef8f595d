"""`tehl contact CASE.yaml`: the S1..S5 table of a face gear case, exit 2 with one line on bad input."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner
import pytest

from facegear_tehl.cli import tehl

from gear_examples import case_variant

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


def _rows(output: str) -> dict[str, dict[str, float]]:
    """The point rows of a `tehl contact` table: point name -> {header: value}."""
    lines = output.splitlines()
    headers = lines[0].split()
    return {line.split()[0]: dict(zip(headers[1:], map(float, line.split()[1:]))) for line in lines[2:7]}


def test_contact_transition_side_double(tmp_path):
    """S2 and S4 carry 2/3 F_n (iso_linear, double side: the shipped case), with p_h scaled by (2/3)^(1/3) from
    the single side; S1, S3, S5 unchanged."""
    single = CliRunner().invoke(tehl, ["contact", str(case_variant(tmp_path, transition_side="single"))])
    double = CliRunner().invoke(tehl, ["contact", str(CASES / "facegear_110.yaml")])  # the shipped case: double
    assert single.exit_code == double.exit_code == 0, double.output
    before, after = _rows(single.output), _rows(double.output)
    f_n = before["S3"]["load"]
    assert [after[name]["load"] for name in after] == pytest.approx([f_n / 3, 2 * f_n / 3, f_n, 2 * f_n / 3, f_n / 3],
                                                                   abs=0.051)
    for name in ("S2", "S4"):
        assert after[name]["p_h"] == pytest.approx(before[name]["p_h"] * (2 / 3) ** (1 / 3), abs=1.0)
    for name in ("S1", "S3", "S5"):
        assert after[name] == before[name]


@pytest.mark.parametrize(
    "keys,message",
    [
        ({"transition_side": "sideways"},
         "error: gear.transition_side: got 'sideways'; expected one of single, double"),
        ({"load_sharing": "[0.4, 1, 1, 1, 0.4]", "transition_side": "double"},
         "error: gear.transition_side: got 'double'; expected no transition_side when load_sharing is a list of "
         "coefficients (the list sets K at every point; transition_side applies to iso_linear, equal)"),
    ],
)
def test_contact_bad_transition_side_exits_2(tmp_path, keys, message):
    result = CliRunner().invoke(tehl, ["contact", str(case_variant(tmp_path, **keys))])
    assert result.exit_code == 2
    assert result.output.strip().splitlines() == [message]
